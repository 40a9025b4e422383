"""Contact times and time histories (seed eqs. 16-26, 30-33): closed forms against Newton's equation.

The closed forms (incomplete beta function, sinusoid) are checked against an
independent numerical integration of ``m* alpha'' = -P`` with the force law of
``microimpact.contact`` (``integrate_impact``), against the numbers the seed
prints for its silicon case, against Hertz's/Deresiewicz's elastic contact time
and Ning's loading time, and against energy conservation along the history.
"""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

import microimpact as mi
from microimpact import contact, dynamics

SILICON = mi.ContactPair.paper_case("silicon")
TIME_KEYS = ("elastic_stage_time", "plastic_stage_time", "loading_time", "unloading_time", "contact_time")
ODE_KEYS = TIME_KEYS + ("max_approach", "rebound_velocity", "max_force")


def rel(a, b):
    return abs(a / b - 1.0)


# ----------------------------------------------------------------------------- random pairs
pairs = st.builds(
    lambda E, R, rho, ratio: mi.ContactPair.sphere_on_flat(R, rho, E, ratio * E),
    E=st.floats(1e8, 1e12).map(float),
    R=st.floats(-7.0, -2.0).map(lambda x: 10.0**x),
    rho=st.floats(500.0, 20000.0),
    ratio=st.floats(-3.0, -0.3).map(lambda x: 10.0**x),  # p_y / E*
)


@settings(max_examples=30, deadline=None)
@given(pair=pairs, v=st.floats(1.001, 50.0))
def test_closed_form_equals_ode_plastic(pair, v):
    """Times, maximum approach, force and rebound speed: closed form = Newton's equation to 1e-8."""
    V = v * pair.yield_velocity
    closed = pair.impact(V, warn=False)
    ode = dynamics.integrate_impact(V, *pair._args)
    for key in ODE_KEYS:
        assert rel(ode[key], float(getattr(closed, key))) < 1e-8, key
    # alpha_p = alpha* - P*/alpha*^(1/2) cancels just above V_y: compare on the scale of alpha*
    assert abs(ode["plastic_approach"] - float(closed.plastic_approach)) < 1e-9 * float(closed.max_approach)


@settings(max_examples=10, deadline=None)
@given(pair=pairs, v=st.floats(0.01, 1.0))
def test_closed_form_equals_ode_elastic(pair, v):
    V = v * pair.yield_velocity
    closed = pair.impact(V, warn=False)
    ode = dynamics.integrate_impact(V, *pair._args)
    assert ode["plastic_stage_time"] == 0.0 and ode["plastic_approach"] == 0.0
    for key in (
        "elastic_stage_time",
        "loading_time",
        "unloading_time",
        "contact_time",
        "max_approach",
        "rebound_velocity",
        "max_force",
    ):
        assert rel(ode[key], float(getattr(closed, key))) < 1e-8, key


def test_ode_equivalent_elastic_pair():
    el = SILICON.elastic_equivalent()
    ode = dynamics.integrate_impact(70.0, *el._args)
    assert rel(ode["contact_time"], float(mi.dynamics.hertz_contact_time(70.0, *el._args[:3]))) < 1e-9
    assert rel(ode["rebound_velocity"], 70.0) < 1e-9


# ----------------------------------------------------------------------------- the seed's numbers
@pytest.mark.parametrize(
    "V, key, paper_us",
    [
        (50.0, "loading_time", 0.01365),  # Sec. 3.6; model 0.013644
        (50.0, "unloading_time", 0.01115),  # model 0.011117
        (7.6, "loading_time", 0.01671),  # Sec. 3.5; model 0.016736
        (7.6, "unloading_time", 0.01675),  # model 0.016736
        (7.6, "contact_time", 0.03346),  # model 0.033472
        (120.0, "loading_time", 0.01333),  # "tends to a constant of 0.01333 us"; model 0.013311
    ],
)
def test_paper_silicon_times(V, key, paper_us):
    value = float(getattr(SILICON.impact(V, warn=False), key)) * 1e6
    assert value == pytest.approx(paper_us, rel=0.01)


def test_paper_reference_formulas():
    m, R, E, p_y = (
        SILICON.effective_mass,
        SILICON.effective_radius,
        SILICON.effective_modulus,
        SILICON.limiting_pressure,
    )
    # eq. 30 at 7.6 m/s: the seed prints 0.03348 us
    assert dynamics.deresiewicz_contact_time(7.6, E, R, m) * 1e6 == pytest.approx(0.03348, rel=0.01)
    # eq. 31: 0.01307 us
    ning = float(dynamics.ning_loading_time(p_y, R, m))
    assert ning * 1e6 == pytest.approx(0.01307, rel=0.01)
    # the loading time tends to eq. 31 from above as V -> inf (Ning neglects the elastic stage)
    V = np.array([120.0, 1e3, 1e5, 1e7])
    tL = SILICON.impact(V, warn=False).loading_time
    assert np.all(np.diff(tL) < 0) and np.all(tL > ning)
    assert rel(tL[-1], ning) < 1e-4
    assert float(SILICON.impact(1e200, warn=False).loading_time) == pytest.approx(ning, rel=1e-15)


def test_hertz_time_constant():
    # (4/5) B(2/5, 1/2) (15/16)^(2/5) = 2.868, printed 2.87 in eq. 30
    assert dynamics.HERTZ_TIME_CONSTANT == pytest.approx(2.8683, abs=1e-4)
    assert dynamics.BETA_25_12 == pytest.approx(math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9), rel=1e-14)


# ----------------------------------------------------------------------------- elastic range, limits
@settings(max_examples=40, deadline=None)
@given(pair=pairs, v=st.floats(1e-4, 1.0))
def test_elastic_times_are_hertz(pair, v):
    V = v * pair.yield_velocity
    out = pair.impact(V, warn=False)
    E, R, m, _ = pair._args
    hertz = float(dynamics.hertz_contact_time(V, E, R, m))
    dere = float(dynamics.deresiewicz_contact_time(V, E, R, m, constant=dynamics.HERTZ_TIME_CONSTANT))
    assert rel(float(out.contact_time), hertz) < 1e-12
    assert rel(hertz, dere) < 1e-12
    assert float(out.plastic_stage_time) == 0.0
    assert rel(float(out.loading_time), float(out.unloading_time)) < 1e-12
    assert float(out.elastic_stage_time) == float(out.loading_time)


@settings(max_examples=25, deadline=None)
@given(pair=pairs)
def test_times_continuous_at_yield(pair):
    Vy = pair.yield_velocity
    below = pair.impact(Vy * (1 - 1e-12), warn=False)
    above = pair.impact(Vy * (1 + 1e-12), warn=False)
    for key in ("elastic_stage_time", "loading_time", "unloading_time", "contact_time"):
        assert rel(float(getattr(above, key)), float(getattr(below, key))) < 1e-5, key
    assert float(above.plastic_stage_time) < 1e-5 * float(above.loading_time)


def test_edge_speeds():
    with np.errstate(all="ignore"):  # 1e300 m/s overflows intermediate powers; the limits are right
        out = SILICON.impact([0.0, 1e300], warn=False)
    assert np.all(
        np.isinf([out.elastic_stage_time[0], out.loading_time[0], out.unloading_time[0], out.contact_time[0]])
    )
    assert out.plastic_stage_time[0] == 0.0
    assert out.elastic_stage_time[1] < 1e-60 and out.unloading_time[1] < 1e-60
    assert out.plastic_stage_time[1] == pytest.approx(SILICON.ning_loading_time(), rel=1e-12)
    with np.errstate(all="ignore"):
        el = SILICON.elastic_equivalent().impact([0.0, 50.0, 1e300], warn=False)
    assert np.isinf(el.contact_time[0]) and el.contact_time[2] < 1e-60
    with pytest.raises(ValueError, match="velocity"):
        SILICON.impact([np.inf])
    assert np.all(el.plastic_stage_time == 0.0)


def test_times_vectorized_and_checked():
    V = np.array([[5.0, 50.0], [7.6, 120.0]])
    t = dynamics.contact_times(V, *SILICON._args)
    for i, j in np.ndindex(V.shape):
        one = dynamics.contact_times(V[i, j], *SILICON._args)
        for key in TIME_KEYS:
            assert t[key][i, j] == one[key]
    with pytest.raises(ValueError, match="velocity"):
        dynamics.contact_times(-1.0, *SILICON._args)
    with pytest.raises(ValueError, match="velocity"):
        dynamics.elastic_stage_time(np.nan, *SILICON._args)
    with pytest.raises(ValueError, match="effective_mass"):
        dynamics.plastic_stage_time(50.0, 1e9, 1e-6, 0.0, 1e8)


def test_plastic_stage_time_just_above_yield():
    """t2 = atan2(v1, 2 omega alpha_y/3)/omega: to first order v1 / (2 omega^2 alpha_y/3)."""
    E, R, m, p_y = SILICON._args
    Vy = SILICON.yield_velocity
    eps = 1e-14
    V = Vy * (1 + eps)
    v1 = math.sqrt((V - Vy) * (V + Vy))  # V - Vy exact; V**2 - Vy**2 would lose 12 digits here
    omega = float(dynamics.plastic_frequency(p_y, R, m))
    expected = v1 / (omega**2 * 2 * SILICON.yield_approach / 3)
    assert rel(float(dynamics.plastic_stage_time(V, E, R, m, p_y)), expected) < 1e-12


# ----------------------------------------------------------------------------- histories
SPEEDS = [1.0, 7.0, 7.6, 30.0, 50.0, 70.0]


def _loading_work(alpha, pair):
    """Work of the loading force from 0 to alpha, by quadrature of contact.loading_force (scaled)."""
    E, R, m, p_y = pair._args
    if alpha <= 0:
        return 0.0
    scale = float(alpha)
    ay = pair.yield_approach
    f = lambda x: float(contact.loading_force(x * scale, E, R, p_y)) * scale  # noqa: E731
    pts = [ay / scale] if 0 < ay < scale else None
    return integrate.quad(f, 0.0, 1.0, points=pts, epsabs=0.0, epsrel=1e-11, limit=200)[0]


def _unloading_work(alpha, alpha_star, pair):
    E, R, m, p_y = pair._args
    f = lambda a: float(contact.contact_force(a, E, R, p_y, max_approach=alpha_star))  # noqa: E731
    P_star = float(contact.loading_force(alpha_star, E, R, p_y))
    a_p = float(contact.plastic_approach(alpha_star, P_star, E, R))
    d = alpha - a_p
    if d <= 1e-12 * alpha_star:  # at separation (the work there is below 1e-18 of the total)
        return 0.0
    return integrate.quad(lambda x: f(a_p + x * d) * d, 0.0, 1.0, epsabs=0.0, epsrel=1e-11, limit=200)[0]


@pytest.mark.parametrize("V", SPEEDS)
def test_energy_conserved_along_history(V):
    """Kinetic energy + work of the contact force is constant in loading and in unloading."""
    h = SILICON.history(V, n=21)
    m = SILICON.effective_mass
    K0 = 0.5 * m * V**2
    Kr = 0.5 * m * h.rebound_velocity**2
    for t, a, v, s in zip(h.time, h.approach, h.approach_velocity, h.stage):
        if s in (1, 2):
            assert abs(0.5 * m * v**2 + _loading_work(a, SILICON) - K0) < 1e-9 * K0
        else:
            assert abs(0.5 * m * v**2 + _unloading_work(a, h.max_approach, SILICON) - Kr) < 1e-9 * K0


@pytest.mark.parametrize("V", SPEEDS)
def test_history_force_is_the_force_law(V):
    h = SILICON.history(V, n=301)
    E, R, m, p_y = SILICON._args
    load = h.stage <= 2
    np.testing.assert_allclose(
        h.force[load], contact.loading_force(h.approach[load], E, R, p_y), rtol=1e-11, atol=1e-13 * h.max_force
    )
    un = h.stage == 3
    np.testing.assert_allclose(
        h.force[un],
        contact.contact_force(h.approach[un], E, R, p_y, max_approach=h.max_approach),
        rtol=1e-9,
        atol=1e-12 * h.max_force,
    )


@pytest.mark.parametrize("V", SPEEDS)
def test_history_continuity_and_end_states(V):
    out = SILICON.impact(V, warn=False)
    h0 = SILICON.history(V, n=11)
    t1, tL, tc = h0.elastic_stage_time, h0.loading_time, h0.contact_time
    d = 1e-12
    bounds = [tL] if out.elastic else [t1, tL]
    for b in bounds:
        h = SILICON.history(V, times=[b * (1 - d), b, b * (1 + d)])
        for arr, scale in ((h.approach, h.max_approach), (h.force, h.max_force), (h.approach_velocity, V)):
            assert np.ptp(arr) < 1e-9 * scale
    h = SILICON.history(V, times=[0.0, tL, tc])
    # first contact
    assert h.approach[0] == 0.0 and h.force[0] == 0.0 and h.approach_velocity[0] == V
    # maximum approach: the core result's alpha* and P*, at rest
    assert rel(h.approach[1], float(out.max_approach)) < 1e-13
    assert rel(h.force[1], float(out.max_force)) < 1e-13
    assert abs(h.approach_velocity[1]) < 1e-13 * V
    # separation: -V_r, at the plastic approach, no force
    assert rel(-h.approach_velocity[2], float(out.rebound_velocity)) < 1e-14
    assert abs(h.approach[2] - float(out.plastic_approach)) < 1e-13 * float(out.max_approach)
    assert abs(h.force[2]) < 1e-13 * float(out.max_force)
    # the history's scalars are the core result's
    for key in ODE_KEYS + ("plastic_approach",):
        assert getattr(h, key) == pytest.approx(float(getattr(out, key)), rel=1e-15, abs=0.0)


@pytest.mark.parametrize("V", [5.0, 7.6, 50.0])
def test_history_closed_equals_ode(V):
    closed = SILICON.history(V, n=401)
    ode = dynamics.integrate_impact(V, *SILICON._args, times=closed.time)
    # the same stages, except that at the closed form's own boundary times (t1, t_L, t_c, on its
    # grid) the integration's boundary, 1e-12 away on either side, may already have passed
    boundary = np.isin(closed.time, [closed.elastic_stage_time, closed.loading_time, closed.contact_time])
    assert np.array_equal(ode["stage"][~boundary], closed.stage[~boundary])
    after = {1: 2, 2: 3, 3: 0}
    for t, got, want in zip(closed.time[boundary], ode["stage"][boundary], closed.stage[boundary]):
        assert got in (want, after[want]), (t, got, want)
    for key in ("elastic_stage_time", "loading_time", "contact_time"):
        assert rel(ode[key], getattr(closed, key)) < 1e-10, key
    for key, scale in (("approach", closed.max_approach), ("approach_velocity", V), ("force", closed.max_force)):
        np.testing.assert_allclose(ode[key], getattr(closed, key), rtol=0, atol=1e-9 * scale, err_msg=key)
    via_pair = SILICON.history(V, n=401, method="ode")
    assert via_pair.method == "ode" and isinstance(via_pair, dynamics.ImpactHistory)
    # its grid holds the ODE's own t1, t_L: compare with the closed form at those times
    at = SILICON.history(V, times=via_pair.time)
    np.testing.assert_allclose(via_pair.force, at.force, rtol=0, atol=1e-9 * closed.max_force)


def test_history_shape_and_stages():
    h = SILICON.history(50.0, n=1001)
    assert len(h) == 1003  # n uniform points + t1 and t_L
    assert h.elastic_stage_time in h.time and h.loading_time in h.time
    assert h.time[0] == 0.0 and h.time[-1] == h.contact_time
    assert np.all(np.diff(h.stage) >= 0) and set(np.unique(h.stage)) == {1, 2, 3}
    loading = h.stage <= 2
    assert np.all(np.diff(h.approach[loading]) > 0) and np.all(np.diff(h.approach[~loading]) < 0)
    assert np.all(np.diff(h.approach_velocity) < 0)  # always decelerating (P > 0)
    assert np.all(h.force >= 0)
    # elastic impacts: stages 1 and 3 only, symmetric in time
    for hist in (SILICON.history(5.0, n=201), SILICON.elastic_equivalent().history(70.0, n=201)):
        assert set(np.unique(hist.stage)) == {1, 3}
        assert hist.plastic_stage_time == 0.0
        mirrored = (
            SILICON.elastic_equivalent().history(hist.velocity, times=hist.contact_time - hist.time)
            if math.isinf(hist.limiting_pressure)
            else SILICON.history(hist.velocity, times=hist.contact_time - hist.time)
        )
        np.testing.assert_allclose(mirrored.force, hist.force, rtol=0, atol=1e-12 * hist.max_force)
        np.testing.assert_allclose(
            mirrored.approach_velocity, -hist.approach_velocity, rtol=0, atol=1e-12 * hist.velocity
        )


def test_history_outside_contact():
    h0 = SILICON.history(50.0, n=3)
    tc, Vr, ap = h0.contact_time, h0.rebound_velocity, h0.plastic_approach
    h = SILICON.history(50.0, times=[-1e-9, 2 * tc])
    assert h.stage.tolist() == [0, 0]
    assert h.force.tolist() == [0.0, 0.0]
    assert h.approach[0] == pytest.approx(-50.0 * 1e-9, rel=1e-15)
    assert h.approach[1] == pytest.approx(ap - Vr * tc, rel=1e-13)
    assert h.approach_velocity.tolist() == [50.0, -Vr]


def test_history_matches_contact_times():
    V = 70.0
    h = dynamics.impact_history(V, *SILICON._args)
    t = dynamics.contact_times(V, *SILICON._args)
    for key in TIME_KEYS:
        assert h[key] == float(t[key])


def test_hertz_force_along():
    h = SILICON.history(70.0, n=201)
    hz = dynamics.hertz_force_along(h)
    assert np.array_equal(hz, h.hertz_force(), equal_nan=True)
    s1, s2, s3 = (h.stage == k for k in (1, 2, 3))
    np.testing.assert_allclose(hz[s1], h.force[s1], rtol=1e-12)
    assert np.all(hz[s2] > h.force[s2])  # yielding: less force than Hertz for the same approach
    assert np.all(np.isnan(hz[s3]))
    full = dynamics.hertz_force_along(h, loading_only=False)
    E, R = SILICON.effective_modulus, SILICON.effective_radius
    np.testing.assert_allclose(full, contact.hertz_force(h.approach, E, R), rtol=1e-14)
    # at the maximum approach it is the equivalent elastic force F_e = P* R_p / R* (eq. 9)
    out = SILICON.impact(70.0, warn=False)
    i = int(np.argmax(h.approach))
    assert full[i] == pytest.approx(float(out.max_force * out.unloading_radius / R), rel=1e-12)


def test_impact_history_object(tmp_path):
    h = SILICON.history(50.0, n=21)
    with pytest.raises(dataclasses.FrozenInstanceError):
        h.velocity = 1.0
    with pytest.raises(ValueError):
        h.force[0] = 1.0  # read-only arrays
    d = h.to_dict()
    assert set(dynamics.HISTORY_COLUMNS) <= set(d) and set(dynamics.HISTORY_SCALARS) <= set(d)
    again = dynamics.ImpactHistory.from_dict(d)
    assert np.array_equal(again.force, h.force) and again.method == "closed"
    path = tmp_path / "h.csv"
    h.to_csv(path)
    text = path.read_text()
    assert text.splitlines()[0] == "time [s],approach [m],approach_velocity [m/s],force [N],stage [1]"
    assert f"# max_force = {h.max_force:.17g} N" in text
    data = np.genfromtxt(path, delimiter=",", names=True)
    assert np.array_equal(data["time_s"], h.time)
    assert np.array_equal(data["force_N"], h.force)
    assert np.array_equal(data["approach_velocity_ms"], h.approach_velocity)
    assert np.array_equal(data["stage_1"].astype(int), h.stage)


def test_history_bad_input():
    args = SILICON._args
    with pytest.raises(ValueError, match="velocity"):
        dynamics.impact_history(0.0, *args)
    with pytest.raises(ValueError, match="velocity"):
        dynamics.impact_history(np.inf, *args)
    with pytest.raises(ValueError, match="velocity"):
        dynamics.impact_history(np.nan, *args)
    with pytest.raises(ValueError, match="velocity"):
        dynamics.impact_history([10.0, 20.0], *args)
    with pytest.raises(ValueError, match="n must"):
        dynamics.impact_history(10.0, *args, n=1)
    with pytest.raises(ValueError, match="n must"):
        SILICON.history(10.0, n=3.5)
    with pytest.raises(ValueError, match="times"):
        dynamics.impact_history(10.0, *args, times=[0.0, np.nan])
    with pytest.raises(ValueError, match="times"):
        dynamics.impact_history(10.0, *args, times=[])
    with pytest.raises(ValueError, match="limiting_pressure"):
        dynamics.impact_history(10.0, 1e9, 1e-6, 1e-14, -1.0)
    with pytest.raises(ValueError, match="method"):
        SILICON.history(10.0, method="euler")
    with pytest.raises(ValueError, match="n must"):
        dynamics.integrate_impact(10.0, *args, n=0)
    with pytest.raises(ValueError, match="velocity"):
        dynamics.integrate_impact(0.0, *args)
