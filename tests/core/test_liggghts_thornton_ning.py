"""The ``liggghts_thornton_ning`` model: closed form against its own force law, against LIGGGHTS, against the seed.

Independent checks, each of which a wrong formula would fail:

* the closed-form ``e``, approaches and contact time against a DOP853 integration of Newton's
  equation with the model's own :func:`force` (1e-8 relative, hypothesis over speed and pair);
* the incomplete beta function and the unloading quadrature against scipy;
* the stored LIGGGHTS 3.8.0 runs of the seed's silicon case (``benchmarks/data/dem_runs.csv``,
  written by ``benchmarks/dem_runs.py``) at 10-100 m/s to 1e-3 in ``e`` and contact time;
* energy is never created, and the difference from the seed has the sign and size derived in the
  model's docstring.
"""

from __future__ import annotations

import csv
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument
from scipy import integrate, special

from microimpact.core.models import available, get
from microimpact.core.quantities import OUTCOME_FIELDS
from microimpact.core.special import incomplete_beta

try:
    settings.get_profile("ci")
except InvalidArgument:
    settings.register_profile("ci", derandomize=True, deadline=None, max_examples=40)
CI = settings(settings.get_profile("ci"), max_examples=40)

M = get("liggghts_thornton_ning")
CSV = Path(__file__).resolve().parents[2] / "benchmarks" / "data" / "dem_runs.csv"
SRC = Path(__file__).resolve().parents[2] / "src"

# The seed's silicon case (THEORY.md section 5): NH4Fl sphere, d = 4.9 um, rho = 1350, on silicon.
E_SI, R_SI, RHO, PY_SI = 1.31e9, 2.45e-6, 1350.0, 156e6
M_SI = 4.0 / 3.0 * math.pi * R_SI**3 * RHO


def out(V, E=E_SI, R=R_SI, m=M_SI, p_y=PY_SI):
    return dict(zip(OUTCOME_FIELDS, M.outcome(V, E, R, m, p_y, ())))


def impact_scalar(V, E, R, m, p_y):
    """The seed's outcome: the core's ``thornton_ning_2016`` where it exists, else the scalar path it replaces."""
    return dict(zip(OUTCOME_FIELDS, get("thornton_ning_2016").outcome(V, E, R, m, p_y, ())))


def integrate_force_law(V, E, R, m, p_y, rtol=1e-13):
    """Newton's equation with the model's own force law, in yield units; returns e, t_c, alpha*, alpha_p."""
    ac = math.pi * p_y * R / (2 * E)
    ay = ac * ac / R
    Py = 4 / 3 * E * math.sqrt(R) * ay**1.5
    Vy = math.sqrt(0.8 * Py * ay / m)
    tau = ay / Vy  # time unit
    acc = tau * tau / (m * ay)  # y'' = -acc F

    def rhs(amax):
        def f(t, y):
            a = y[0] * ay
            top = a if amax is None else amax
            return [y[1], -acc * M.force(a, y[1] * ay / tau, top, E, R, m, p_y, ())]

        return f

    def ev(fun):
        fun.terminal = True
        fun.direction = -1
        return fun

    opts = dict(method="DOP853", rtol=rtol, atol=1e-15)
    # loading, Hertz stage: stop at yield (a kink of the force) or at rest
    s1 = integrate.solve_ivp(
        rhs(None), (0, 50), [0.0, V / Vy], events=[ev(lambda t, y: 1.0 - y[0]), ev(lambda t, y: y[1])], **opts
    )
    t, y = s1.t[-1], s1.y[:, -1]
    if s1.status == 1 and s1.t_events[0].size:  # yielded: plastic stage until rest
        s2 = integrate.solve_ivp(rhs(None), (t, t + 50), y, events=[ev(lambda t, y: y[1])], **opts)
        t, y = s2.t[-1], s2.y[:, -1]
    amax = y[0] * ay
    pmax = M.force(amax, 0.0, amax, E, R, m, p_y, ())
    # unloading from rest at alpha*: stop where the force vanishes (1e-15 P* above zero, a
    # 1e-15 relative shift of the end time since the force has a finite slope there)
    s3 = integrate.solve_ivp(
        rhs(amax),
        (t, t + 50),
        [y[0], 0.0],
        events=[ev(lambda t, y: M.force(y[0] * ay, 0.0, amax, E, R, m, p_y, ()) - 1e-15 * pmax)],
        **opts,
    )
    te, ye = s3.t_events[0][0], s3.y_events[0][0]
    return {
        "restitution": -ye[1] * Vy / V,
        "contact_time": te * tau,
        "max_approach": amax,
        "plastic_approach": ye[0] * ay,
    }


def test_registered():
    assert "liggghts_thornton_ning" in available()
    assert M.NAME == "liggghts_thornton_ning" and M.PARAMETERS == () and get(M.NAME).DEFAULTS == ()
    assert len(M.outcome(50.0, E_SI, R_SI, M_SI, PY_SI, ())) == len(OUTCOME_FIELDS)


@settings(CI)
@given(
    v=st.floats(1.0005, 1e3),
    E=st.floats(1e8, 1e12),
    R=st.floats(1e-7, 1e-2),
    rho=st.floats(500.0, 2e4),
    ratio=st.floats(1e-4, 0.3),  # p_y / E*
)
def test_closed_form_equals_integration_of_own_force_law(v, E, R, rho, ratio):
    p_y = ratio * E
    m = 4 / 3 * math.pi * R**3 * rho
    Vy = out(1.0, E, R, m, p_y)["yield_velocity"]
    V = v * Vy
    closed = out(V, E, R, m, p_y)
    ode = integrate_force_law(V, E, R, m, p_y)
    for key in ("restitution", "contact_time", "max_approach", "plastic_approach"):
        assert closed[key] == pytest.approx(ode[key], rel=1e-8), key


@pytest.mark.parametrize("V", [3.0, 7.0])
def test_elastic_impact_is_hertz_both_ways(V):
    o = out(V)
    ode = integrate_force_law(V, E_SI, R_SI, M_SI, PY_SI)
    assert o["elastic"] == 1.0 and o["restitution"] == 1.0 and o["plastic_approach"] == 0.0
    assert ode["restitution"] == pytest.approx(1.0, rel=1e-9)
    assert o["contact_time"] == pytest.approx(ode["contact_time"], rel=1e-8)
    # Deresiewicz's exact constant (THEORY.md section 4): (4/5) B(2/5,1/2) (15/16)^(2/5)
    tc = 0.8 * special.beta(0.4, 0.5) * (15 / 16) ** 0.4 * (M_SI**2 / (R_SI * E_SI**2 * V)) ** 0.2
    assert o["contact_time"] == pytest.approx(tc, rel=1e-13)


@settings(CI)
# scipy loses digits for subnormal x (x^a/a is 1.190e-129 at x = 5e-324, a = 0.4; scipy gives 1.152e-129)
@given(
    x=st.floats(0.0, 1.0, allow_subnormal=False), a=st.sampled_from([0.4, 0.5, 1.3]), b=st.sampled_from([0.5, 0.4, 2.0])
)
def test_incomplete_beta_against_scipy(x, a, b):
    ref = special.betainc(a, b, x) * special.beta(a, b)
    assert incomplete_beta(x, a, b) == pytest.approx(ref, rel=1e-13, abs=1e-300)


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")  # quad's own accuracy notes
@settings(CI)
@given(v=st.floats(1.0001, 100.0))
def test_unloading_quadrature_against_scipy_quad(v):
    o = out(v * out(1.0)["yield_velocity"])
    beta = o["plastic_approach"] / o["max_approach"]

    def g(s):
        return 0.4 * (1 - s**2.5) - beta**1.5 * (1 - s)

    # the 1/sqrt end point at s = 1 handled by quad's algebraic weight
    J, err = integrate.quad(
        lambda s: 1 / math.sqrt(g(s) / (1 - s)) if s < 1 else 1 / math.sqrt(1 - beta**1.5),
        beta,
        1,
        weight="alg",
        wvar=(0, -0.5),
        epsabs=0,
        epsrel=1e-13,
        limit=200,
    )
    c = 1 - beta**1.5
    h = 1 - beta
    assert M.unloading_integral(c, h) == pytest.approx(J, rel=1e-10)


# J at v = V/V_y by mpmath (40 digits, mp.quad of the same substituted integrand in exact arithmetic).
MPMATH_J = [
    (1.0001, 2.3268605107930176),
    (1.5, 2.2157067837014246),
    (10.0, 1.933735357942933),
    (1153.0, 1.8229935179873156),
    (1e5, 1.8147674675326464),
    (1e6, 1.814105008831197),
]


@pytest.mark.parametrize("v, J", MPMATH_J)
def test_unloading_quadrature_against_mpmath(v, J):
    s = math.sqrt((24 * v * v - 4) / 5)
    A, P = (1 + s) / 3, s / 2
    c = P / A**1.5
    h = -math.expm1(2 / 3 * math.log1p(-c))
    assert M.unloading_integral(c, h) == pytest.approx(J, rel=1e-14)


def test_unloading_quadrature_elastic_limit():
    # beta = 0: J = int_0^1 ds / (0.4 (1 - s^(5/2)))^(1/2); with w = s^(5/2) this is (2/5)^(1/2) B(2/5, 1/2)
    J = math.sqrt(0.4) * special.beta(0.4, 0.5)
    assert M.unloading_integral(1.0, 1.0) == pytest.approx(J, rel=1e-14)


@settings(CI)
@given(v=st.floats(0.0, 1e8))
def test_energy_never_created(v):
    o = out(v * out(1.0)["yield_velocity"])
    assert 0.0 <= o["restitution"] <= 1.0
    assert o["energy_loss"] == pytest.approx(1 - o["restitution"] ** 2, abs=1e-15)
    if v > 1:
        assert o["plastic_approach"] > 0.0 and o["restitution"] < 1.0


@settings(CI)
@given(s_max=st.floats(1e-3, 50.0), frac=st.floats(0.0, 1.0))
def test_unloading_never_above_loading(s_max, frac):
    # the force on the way back is at most the virgin-loading force at the same approach: no energy created
    ay = (math.pi * PY_SI * R_SI / (2 * E_SI)) ** 2 / R_SI
    amax = s_max * ay
    a = frac * amax
    back = M.force(a, -1.0, amax, E_SI, R_SI, M_SI, PY_SI, ())
    virgin = M.force(a, 1.0, a, E_SI, R_SI, M_SI, PY_SI, ())
    assert 0.0 <= back <= virgin * (1 + 1e-14)


def test_loading_is_the_seeds():
    for V in (7.6, 10.0, 50.0, 100.0, 1e4):
        o, s = out(V), impact_scalar(V, E_SI, R_SI, M_SI, PY_SI)
        for key in ("yield_velocity", "max_approach", "max_force", "elastic_stage_time", "plastic_stage_time"):
            assert o[key] == pytest.approx(s[key], rel=1e-13), (V, key)


def test_difference_from_seed():
    """Lower e, deeper dent and shorter contact than the seed above V_y; the sizes quoted in the docs."""
    rows = []
    for V in (10.0, 50.0, 100.0):
        o, s = out(V), impact_scalar(V, E_SI, R_SI, M_SI, PY_SI)
        rows.append((o["restitution"] / s["restitution"], o["contact_time"] / s["contact_time"]))
        assert o["plastic_approach"] > s["plastic_approach"]
        assert o["unloading_radius"] == R_SI < s["unloading_radius"]
    e_ratio, t_ratio = np.array(rows).T
    # values of the closed forms (model docstring), rounded to the 4 digits docs/dem_codes.rst prints
    assert e_ratio.round(4).tolist() == [0.9963, 0.9526, 0.9402]
    assert t_ratio.round(4).tolist() == [0.9834, 0.9306, 0.9268]
    # high-speed limits: e v^(1/4) -> (15/8 (8/15)^(3/4))^(1/2) here, Thornton-Ning's (seed) 1.185 there
    v = 1e10
    Vy = out(1.0)["yield_velocity"]
    c_here = out(v * Vy)["restitution"] * v**0.25
    c_seed = impact_scalar(v * Vy, E_SI, R_SI, M_SI, PY_SI)["restitution"] * v**0.25
    assert c_here == pytest.approx(math.sqrt(15 / 8 * (8 / 15) ** 0.75), rel=1e-4)
    assert c_seed == pytest.approx(1.185, abs=5e-4)


def test_numba_compiles_the_same_source():
    """numba compiles outcome and force from this very source (registered as the core's arrays will).

    In a fresh interpreter, so that registering the functions here cannot clash with other tests.
    """
    pytest.importorskip("numba")
    code = f"""
import numpy as np, numba
from numba.extending import register_jitable
from microimpact.core._jit import JITABLE
from microimpact.core.models import get
M = get("liggghts_thornton_ning")
for fn in JITABLE:
    register_jitable(fn)
outcome, force = numba.njit(M.outcome), numba.njit(M.force)
args = ({E_SI!r}, {R_SI!r}, {M_SI!r}, {PY_SI!r}, ())
for V in (5.0, 10.0, 50.0, 100.0):
    np.testing.assert_allclose(outcome(V, *args), M.outcome(V, *args), rtol=1e-14)
for a in (1e-9, 1e-7, 3e-7):
    assert abs(force(a, -1.0, 3e-7, *args) - M.force(a, -1.0, 3e-7, *args)) <= 1e-14 * M.force(3e-7, 1.0, 3e-7, *args)
print("ok")
"""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=600)
    assert proc.returncode == 0 and proc.stdout.strip() == "ok", proc.stderr[-3000:]


def _liggghts_rows():
    if not CSV.exists():
        return []
    with open(CSV, newline="") as fh:
        lines = [line for line in fh if not line.startswith("#")]
    rows = [r for r in csv.DictReader(lines) if r["code"] == "LIGGGHTS" and r["model_style"] == "thornton_ning"]
    # the finest time step of each speed
    best = {}
    for r in rows:
        V = float(r["velocity_m_s"])
        if V not in best or float(r["timestep_s"]) < float(best[V]["timestep_s"]):
            best[V] = r
    return [best[V] for V in sorted(best)]


@pytest.mark.skipif(not _liggghts_rows(), reason="no stored LIGGGHTS thornton_ning runs")
def test_reproduces_stored_liggghts_runs():
    rows = _liggghts_rows()
    assert [float(r["velocity_m_s"]) for r in rows] == [10.0 * i for i in range(1, 11)]
    for r in rows:
        E = float(r["effective_modulus_Pa"])
        R = float(r["particle_radius_m"])
        m = 4 / 3 * math.pi * R**3 * float(r["density_kg_m3"])
        o = out(float(r["velocity_m_s"]), E, R, m, float(r["limiting_pressure_Pa"]))
        assert float(r["restitution"]) == pytest.approx(o["restitution"], rel=1e-3)
        assert float(r["contact_time_s"]) == pytest.approx(o["contact_time"], rel=1e-3)
        assert float(r["plastic_approach_m"]) == pytest.approx(o["plastic_approach"], rel=1e-2)


def test_rebound_work_without_cancellation():
    """e from the returned work W = 0.4 A^(5/2) - D A + 0.6 D^(5/3), D = A^(3/2) - P*/P_y, against the same
    W in 60-digit decimal arithmetic from the same A and P*/P_y: to 1e-10 from V/V_y = 1.01 to 1e15 (the
    closed form in doubles cancels as c^2 (1e-11 just above the series' switch at c = 1e-2, and e reached
    1.35 at V = 1e30 m/s before the series), and e stays in [0, 1] and never
    grows with V up to 1e300 m/s, where the power overflowed (a traceback in ``microimpact impact``)."""
    import decimal

    import microimpact as mi
    from microimpact.core.models import liggghts_thornton_ning as L
    from microimpact.core.models import thornton_ning_2016 as seed

    ctx = decimal.Context(prec=60)
    for v in np.geomspace(1.01, 1e15, 300):
        A, Phat = seed.plastic_stage(float(v), float(v) - 1.0)[:2]
        e = L.plastic_rebound(float(v))[4]
        a, p = decimal.Decimal(A), decimal.Decimal(Phat)
        a15 = ctx.multiply(a, ctx.sqrt(a))
        d = ctx.subtract(a15, p)
        w = ctx.add(
            ctx.subtract(ctx.multiply(decimal.Decimal("0.4"), ctx.multiply(a, a15)), ctx.multiply(d, a)),
            ctx.multiply(decimal.Decimal("0.6"), ctx.power(d, ctx.divide(5, 3))),
        )
        exact = float(ctx.divide(ctx.sqrt(ctx.divide(w, decimal.Decimal("0.4"))), decimal.Decimal(float(v))))
        assert e == pytest.approx(exact, rel=1e-10, abs=0.0), v
    pair = mi.ContactPair.paper_case("silicon")
    V = np.geomspace(10.0, 1e300, 121)
    e = pair.impact(V, model="liggghts_thornton_ning", warn=False).restitution
    assert np.all((e >= 0.0) & (e <= 1.0)) and np.all(np.diff(e) <= 0.0)
    assert all(
        0.0 <= float(pair.impact(float(v), model="liggghts_thornton_ning", warn=False).restitution) <= 1.0 for v in V
    )
