"""The DEM codes' tangential laws along the closed-form normal history (microimpact.core.tangential_laws).

The laws are checked against the DEM codes themselves in ``tests/test_oblique_laws.py``; here: the
generic integrator against the independent one of :mod:`microimpact.core.tangential` (another state
variable, another code) for the law they share, convergence, and the array paths bitwise.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from microimpact import engine
from microimpact.core import tangential as tg
from microimpact.core import tangential_laws as tl

KAPPA = 2 * (1 - 0.23) / (2 - 0.23)  # alumina on a rigid flat


@pytest.mark.parametrize("x", [2.0, 0.5, 0.05])
@pytest.mark.parametrize("psi", [0.3, 0.9, 1.2, 3.0, 6.0])
def test_rescale_force_law_equals_the_mindlin_integrator(x, psi):
    """LAMMPS mindlin_rescale/force in the generic form (state T/a^c, spin and centre apart) is the
    model "mindlin" (state T, then T/k_t; slip alone) to rounding, however u0 is split."""
    u0 = psi / KAPPA
    ref, regime = tg.integrate_tangential(u0, KAPPA, x, 400)
    for share in (1.0, 0.3, -0.5):
        v, w, rg = tl.integrate_law(
            tl.law_code("lammps_mindlin_rescale_force"), share * u0, (1 - share) * u0, KAPPA, x, 0.0, 400
        )
        assert v + w == pytest.approx(ref, abs=1e-12)
        assert rg == regime
        # the centre takes 2/7 of the slip change, the rim 5/7 (a solid sphere, arm R)
        assert (v - share * u0) == pytest.approx((ref - u0) / 3.5, abs=1e-12)


@pytest.mark.parametrize("law", tl.LAWS)
def test_fixed_steps_converge(law):
    code = tl.law_code(law)
    for x in (2.0, 0.1):
        for u0 in (0.4, 1.5, 4.0):
            coarse = tl.integrate_law(code, u0, 0.0, KAPPA, x, 3e-3, 400)
            fine = tl.integrate_law(code, u0, 0.0, KAPPA, x, 3e-3, 1600)
            # Mindlin-Deresiewicz: its stiffness's cube root has an infinite slope at the limit,
            # which the stuck force hugs where psi > 1 (T/(mu P) = 1 - psi^-3 at first touch):
            # the fixed steps converge at about first order there.
            tol = 5e-4 if code == tl.MD_CODE else 1e-6
            assert coarse[0] == pytest.approx(fine[0], abs=tol)
            assert coarse[1] == pytest.approx(fine[1], abs=tol)


def test_the_laws_differ_where_the_codes_do():
    """Below the sliding-throughout angle the laws give different impulses (the reason to offer them)."""
    out = {law: tl.integrate_law(tl.law_code(law), 1.5, 0.0, KAPPA, 2.0, 0.0, 400)[0] for law in tl.LAWS}
    values = sorted(out.values())
    assert min(np.diff(values)) > 1e-4 or len(set(np.round(values, 6))) >= 5
    # far beyond it every law slides throughout: the Coulomb impulse mu (1 + e) m V = 2 mu m V
    for law in tl.LAWS:
        v, w, rg = tl.integrate_law(tl.law_code(law), 40.0, 0.0, KAPPA, 2.0, 0.0, 400)
        if law == "mindlin_deresiewicz":
            # never slides at first touch: stuck at T/(mu P) = r, r = psi (1 - r)^(1/3) (psi = 34.4:
            # 1 - r = 2.4e-5) while the contact grows, then slides: micro-slip, the impulse a hair
            # below Coulomb's (that deficit, and the steps' error where the force hugs the limit:
            # 2.8e-4 at 400 steps)
            assert rg == tg.REGIME_MICROSLIP
            assert 0.0 < v - (40.0 - 2.0) < 5e-4
            continue
        assert rg == tg.REGIME_SLIDING
        assert v == pytest.approx(40.0 - 2.0, abs=1e-9)


def test_paths_bitwise_equal():
    rng = np.random.default_rng(3)
    n = 24
    code = rng.integers(0, len(tl.LAWS), n).astype(float)
    v0 = rng.uniform(-3, 3, n)
    w0 = rng.uniform(-1, 1, n)
    kap = rng.uniform(0.6, 1.2, n)
    x = 10 ** rng.uniform(-2, 0.3, n)
    eps = rng.uniform(0, 1e-2, n)
    steps = np.full(n, 60.0)
    args = (code, v0, w0, kap, x, eps, steps)
    scalar = np.array([tl.integrate_law(*(float(a[i]) for a in args)) for i in range(n)]).T
    py = engine.evaluate(tl.integrate_law, *args, nout=3, backend="python")
    serial = engine.evaluate(tl.integrate_law, *args, nout=3, backend="numba")
    old = engine.PARALLEL_MIN
    try:
        engine.PARALLEL_MIN = 1
        parallel = engine.evaluate(tl.integrate_law, *args, nout=3, backend="numba")
    finally:
        engine.PARALLEL_MIN = old
    assert np.array_equal(py, scalar)
    assert np.array_equal(parallel, serial)
    # Compiled against Python: the same bits, since the integer powers of core.tangential's stage
    # points are products (Python's ``w**5`` is libm's pow, numba's is (w^2)^2 w; they differed
    # for half the w, and the integration carried that to 1e-16 here and 1e-8 in a table).
    assert np.array_equal(serial, scalar)


# ---------------------------------------------------------------- Stronge's compliant impact


def _stronge_closed_form(u0, kappa, e):
    """Stronge's impact piece by piece in closed form (the cases of pooltool's stronge_compliant.py):
    sliding ``u = u0 - 7/2 int P``, sticking the harmonic ``u = u1 cos(w s) - w x1 sin(w s)`` with
    ``w^2 = 7/2 kappa``, switches where ``|x|/eta^2 = P`` (slip) or ``cos s = (u0 - 7/2)/(eta^2 - 7/2)``
    (stick), the last slip to the end ``u_f = u - 7/2 e (1 + cos phase)``. Roots by brentq."""
    from scipy.optimize import brentq

    eta2 = 1.0 / kappa
    w = np.sqrt(3.5 * kappa)
    end = 0.5 * np.pi * (1 + e)

    def P(s):
        return np.sin(s) if s <= 0.5 * np.pi else np.sin(s / e + 0.5 * np.pi * (1 - 1 / e))

    def impulse(s):  # int_0^s P: 1 - cos s, then 1 + e (0 - cos phase) from the top
        if s <= 0.5 * np.pi:
            return 1 - np.cos(s)
        return 1 - e * np.cos(s / e + 0.5 * np.pi * (1 - 1 / e))

    def first_root(f, a, b, n=4000):
        grid = np.linspace(a, b, n)
        vals = [f(x) for x in grid]
        for i in range(n - 1):
            if vals[i] < 0 <= vals[i + 1]:
                return brentq(f, grid[i], grid[i + 1], xtol=1e-15)
        return None

    if u0 > eta2:  # slides from first touch (u0 > 0)
        x = (u0 - 3.5) / (eta2 - 3.5)
        u_slide = lambda s: u0 - 3.5 * impulse(s)  # noqa: E731

        # sticks where the stuck force's rate falls below the limit's
        def g(s):
            dP = np.cos(s) if s <= 0.5 * np.pi else np.cos(s / e + 0.5 * np.pi * (1 - 1 / e)) / e
            return dP - u_slide(s) / eta2

        s1 = first_root(g, 1e-9, end - 1e-9)
        if s1 is None:
            return u0 - 3.5 * (1 + e), x
        u1, x1 = u_slide(s1), eta2 * P(s1)
    else:
        s1, u1, x1 = 0.0, u0, 0.0

    def xs(s):
        return x1 * np.cos(w * (s - s1)) + u1 / w * np.sin(w * (s - s1))

    def us(s):
        return u1 * np.cos(w * (s - s1)) - w * x1 * np.sin(w * (s - s1))

    s2 = first_root(lambda s: abs(xs(s)) / eta2 - P(s), s1 + 1e-9, end - 1e-12)
    sign = np.sign(xs(s2))
    return us(s2) - 3.5 * sign * (impulse(end) - impulse(s2)), None


@pytest.mark.parametrize("e", [1.0, 0.7, 0.6])
def test_stronge_gross_slip_threshold_is_the_sources(e):
    """Gross slip beyond u0/(mu V) = (1 + e) beta_t/beta_n - eta^2/e (pooltool's is_gross_slip): the
    Coulomb impulse; just below, not. (The source's criterion looks at the last instant only; for
    ``e < omega_n/omega_t`` = 0.57 here the contact sticks again earlier, just above it: the closed
    forms below, which test the stick condition all along, agree with the integration there.)"""
    eta2 = 1.0 / KAPPA
    thr = 3.5 * (1 + e) - eta2 / e
    above = tl.integrate_stronge(thr * 1.001, KAPPA, e, 400)
    below = tl.integrate_stronge(thr * 0.999, KAPPA, e, 400)
    assert above[1] == tg.REGIME_SLIDING and above[0] == pytest.approx(thr * 1.001 - 3.5 * (1 + e), abs=1e-12)
    assert below[1] == tg.REGIME_MICROSLIP


@pytest.mark.parametrize("e", [1.0, 0.8, 0.5, 0.3])
@pytest.mark.parametrize("frac", [0.05, 0.3, 0.7, 0.95, 1.2, 2.0, 3.0, 4.5])
def test_stronge_equals_its_closed_forms(e, frac):
    """Stick-slip (u0 < eta^2), slip-stick-slip, gross slip: the integration against the piecewise closed forms."""
    eta2 = 1.0 / KAPPA
    u0 = frac * eta2
    ref, gross = _stronge_closed_form(u0, KAPPA, e)
    got, regime = tl.integrate_stronge(u0, KAPPA, e, 400)
    assert got == pytest.approx(ref, abs=1e-8)
    assert regime == (tg.REGIME_SLIDING if gross is not None else tg.REGIME_MICROSLIP)


def test_stronge_paths_bitwise_equal():
    rng = np.random.default_rng(5)
    n = 20
    args = (rng.uniform(-8, 8, n), rng.uniform(0.6, 1.2, n), rng.uniform(0.2, 1.0, n), np.full(n, 50.0))
    scalar = np.array([tl.integrate_stronge(*(float(a[i]) for a in args)) for i in range(n)]).T
    py = engine.evaluate(tl.integrate_stronge, *args, nout=2, backend="python")
    serial = engine.evaluate(tl.integrate_stronge, *args, nout=2, backend="numba")
    old = engine.PARALLEL_MIN
    try:
        engine.PARALLEL_MIN = 1
        parallel = engine.evaluate(tl.integrate_stronge, *args, nout=2, backend="numba")
    finally:
        engine.PARALLEL_MIN = old
    assert np.array_equal(py, scalar)
    assert np.array_equal(parallel, serial)
    assert np.array_equal(serial, scalar)


# ---------------------------------------------------------------- Mindlin-Deresiewicz with turning points
#
# The rate law (MercuryDPM's MindlinInteraction::updateK_t), in units mu P = 1 and K_t0 = 1, for the
# spring force S = -T along the displacement delta: virgin loading dS/d(delta) = (1 - |S|)^(1/3) while
# |S| grows; from a turning point (delta_b, S_b), moving in the direction m = +-1,
# dS/d(delta) = (1 - |S - S_b|/2)^(1/3), until |S| passes the turning point S_a reached from the virgin
# curve, where the virgin curve takes over again; |S| = 1: sliding.
#
# Its integral, by separation of variables. Virgin: d(1 - S)/(1 - S)^(1/3) = -d(delta) gives
# (3/2)(1 - S)^(2/3) = 3/2 - delta, S = 1 - (1 - 2 delta/3)^(3/2) (= 1 at delta = 3/2). Branch: with
# w = m (S - S_b)/2, dw/d(m (delta - delta_b)) = (1/2)(1 - w)^(1/3), so
# (1 - w)^(2/3) = 1 - m (delta - delta_b)/3 and S = S_b + 2 m [1 - (1 - m (delta - delta_b)/3)^(3/2)]
# (Masing's rule: the virgin curve doubled about the turning point).


def _virgin(x):
    """Virgin force at the virgin displacement x >= 0 (1 past 3/2: sliding)."""
    return 1.0 - max(1.0 - 2.0 * x / 3.0, 0.0) ** 1.5


def _virgin_x(s):
    """Inverse of _virgin: the virgin displacement of the force magnitude s <= 1."""
    return 1.5 * (1.0 - (1.0 - s) ** (2.0 / 3.0))


def _md_closed_form(legs):
    """Spring force S at the end of each leg 0 -> legs[0] -> legs[1] -> ... from the integrals above."""
    delta, S = 0.0, 0.0
    mode, S_a, S_b, delta_b = "virgin", 0.0, 0.0, 0.0
    m_prev = None
    out = []
    for target in legs:
        m = 1.0 if target > delta else -1.0
        if m_prev is not None and m != m_prev:  # a turning point (from the limit too)
            S_a = S if mode != "branch" else S_a
            S_b, delta_b, mode = S, delta, "branch"
        if mode == "branch":
            # where |S| passes |S_a| on this branch (S = m |S_a|), if within the leg
            w = m * (m * abs(S_a) - S_b) / 2.0
            d_join = delta_b + 3.0 * m * (1.0 - (1.0 - w) ** (2.0 / 3.0))
            if m * (target - d_join) > 0.0:
                mode, delta, S = "virgin", d_join, m * abs(S_a)
            else:
                S = S_b + 2.0 * m * (1.0 - (1.0 - m * (target - delta_b) / 3.0) ** 1.5)
        if mode == "virgin":  # along the virgin curve in the direction m from |S|
            S = m * _virgin(_virgin_x(min(abs(S), 1.0)) + abs(target - delta))
        delta, m_prev = target, m
        out.append(S)
    return out


def test_md_closed_form_solves_the_rate_law():
    # The test's own integral, differentiated numerically, gives back the rate law on each branch.
    h = 1e-6
    for x in (0.1, 0.7, 1.3):
        dS = (_virgin(x + h) - _virgin(x - h)) / (2 * h)
        assert dS == pytest.approx((1.0 - _virgin(x)) ** (1.0 / 3.0), rel=1e-8)
    S_b, d_b, m = 0.8, 1.0, -1.0

    def branch(d):
        return S_b + 2.0 * m * (1.0 - (1.0 - m * (d - d_b) / 3.0) ** 1.5)

    for d in (0.8, 0.2, -0.5):
        dS = (branch(d + h) - branch(d - h)) / (2 * h)
        assert dS == pytest.approx((1.0 - abs(branch(d) - S_b) / 2.0) ** (1.0 / 3.0), rel=1e-8)


@pytest.mark.parametrize(
    "legs",
    [
        (0.5, -0.5, 0.5),  # load, unload through zero, reload: no rejoining
        (1.0, -0.4, 0.7),
        (0.6, 0.2, 1.2),  # partial unloading; the reload rejoins the virgin curve at delta = 0.6
        (0.5, -0.9, 0.0),  # the unloading rejoins the virgin curve on the far side (delta = -0.5)
        (2.0, -0.5, 0.5),  # slides past delta = 3/2, then unloads from the limit
        (-0.8, 0.3, -1.0),
    ],
)
def test_md_cycle_equals_the_closed_form_integral(legs):
    got = tl.mindlin_deresiewicz_cycle(*legs, 400)
    want = _md_closed_form(legs)
    # T = -S; the stepper locates every turning point and rejoining point by bisection
    np.testing.assert_allclose([-t for t in got[:3]], want, rtol=0, atol=1e-9)
    slid = abs(legs[0]) > 1.5
    assert got[3] == (tg.REGIME_MICROSLIP if slid else tg.REGIME_STICKING)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(
    d1=st.floats(-2.5, 2.5).filter(lambda d: abs(d) > 1e-3),
    d2=st.floats(-2.5, 2.5),
    d3=st.floats(-2.5, 2.5),
)
def test_md_cycle_force_never_exceeds_the_limit(d1, d2, d3):
    assume(abs(d2 - d1) > 1e-3 and abs(d3 - d2) > 1e-3)
    got = tl.mindlin_deresiewicz_cycle(d1, d2, d3, 200)
    assert all(abs(t) <= 1.0 + 1e-12 for t in got[:3])
    # 1e-4: a leg that ends just at the limit meets the cube root's infinite slope there (the
    # steps converge as h^(3/2): 3e-5 at 100 steps for d1 = 3/2); elsewhere 1e-9 (cases above)
    np.testing.assert_allclose([-t for t in got[:3]], _md_closed_form((d1, d2, d3)), rtol=0, atol=1e-4)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(
    vt=st.floats(-8.0, 8.0),
    rw=st.floats(-3.0, 3.0),
    kappa=st.floats(0.6, 1.2),
    x=st.floats(0.01, 2.0),
)
def test_md_impact_creates_no_energy_and_respects_coulomb(vt, rw, kappa, x):
    v, w, regime = tl.integrate_law(tl.MD_CODE, vt, rw, kappa, x, 0.0, 200)
    # |u_r| <= |u0|: the contact point's effective energy (2m/7) u^2/2 does not grow
    assert abs(v + w) <= abs(vt + rw) * (1.0 + 1e-9) + 1e-12
    # |J_t| <= mu J_n: the impulse in mu m V is at most 1 + e
    e = tg.history_constants(min(x, 1.0))[13]
    assert abs(v - vt) <= (1.0 + e) * (1.0 + 1e-9)
    assert w - rw == pytest.approx(2.5 * (v - vt), abs=1e-9)  # solid sphere
    assert regime in (tg.REGIME_STICKING, tg.REGIME_MICROSLIP, tg.REGIME_SLIDING)


@pytest.mark.parametrize("x", [2.0, 0.3])
def test_md_sticking_limit_is_the_mindlin_stiffness(x):
    # mu -> infinity is u0/(mu V) -> 0: the force ratio T/(mu P) vanishes, K_t = K_t0 and the law is
    # the force history rescaled by a/a_old as the contact shrinks (code 0 = the seed's "mindlin").
    for eps in (1e-4, 1e-6):
        md = tl.integrate_law(tl.MD_CODE, eps, 0.0, KAPPA, x, 0.0, 400)
        ref = tl.integrate_law(0.0, eps, 0.0, KAPPA, x, 0.0, 400)
        seed = tg.integrate_tangential(eps, KAPPA, x, 400)[0]
        assert (md[0] + md[1]) / eps == pytest.approx(seed / eps, abs=50 * eps)
        assert md[0] / eps == pytest.approx(ref[0] / eps, abs=50 * eps)


def test_md_stiffness_factor_is_updateK_t():
    # MercuryDPM's updateK_t (fb0ebf1d, MindlinInteraction.cc l. 226-277): virgin K_t0 cbrt(1 - |T|/(mu P)),
    # from a turning point K_t0 cbrt(1 - |T - T*|/(2 mu P)); the bracket clamped at 0 here.
    assert tl.md_stiffness_factor(0.3, 0.0, 1.0, 0.0) == pytest.approx(0.7 ** (1 / 3), rel=1e-15)
    assert tl.md_stiffness_factor(-0.3, 0.9, 2.0, 1.0) == pytest.approx((1 - 1.2 / 4.0) ** (1 / 3), rel=1e-15)
    assert tl.md_stiffness_factor(1.0, 0.0, 1.0, 0.0) == 0.0
    assert tl.md_stiffness_factor(-1.0, 1.5, 1.0, 1.0) == 0.0
    assert tl.md_stiffness_factor(0.0, 0.0, 0.0, 0.0) == 1.0


def test_md_paths_bitwise_equal():
    rng = np.random.default_rng(22)
    n = 16
    args = (
        np.full(n, tl.MD_CODE),
        rng.uniform(-4, 4, n),
        rng.uniform(-1, 1, n),
        rng.uniform(0.6, 1.2, n),
        10 ** rng.uniform(-2, 0.3, n),
        np.zeros(n),
        np.full(n, 60.0),
    )
    scalar = np.array([tl.integrate_law(*(float(a[i]) for a in args)) for i in range(n)]).T
    py = engine.evaluate(tl.integrate_law, *args, nout=3, backend="python")
    serial = engine.evaluate(tl.integrate_law, *args, nout=3, backend="numba")
    assert np.array_equal(py, scalar)
    # Compiled against Python: bit for bit (test_paths_bitwise_equal). A last-bit difference would
    # be carried far here: a step that ends within rounding of the limit under a growing normal
    # force takes K_t = 0 in one path and not in the other.
    assert np.array_equal(serial, scalar)
    cyc = np.array([[0.5, 1.0, 2.0], [-0.5, -0.4, -0.5], [0.5, 0.7, 0.5], [100.0, 100.0, 100.0]])
    cyc_py = engine.evaluate(tl.mindlin_deresiewicz_cycle, *cyc, nout=4, backend="python")
    cyc_nb = engine.evaluate(tl.mindlin_deresiewicz_cycle, *cyc, nout=4, backend="numba")
    assert np.array_equal(cyc_nb, cyc_py)
