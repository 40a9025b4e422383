"""LIGGGHTS' hertz + sjkr/sjkr2 law (``liggghts_hertz_sjkr``): against the integration of its own
force law, its energy bookkeeping, the face's lines and work-of-adhesion map, and LIGGGHTS itself.

The DEM runs (skipped without ``liggghts``) use the silicon pair with parameters used nowhere else;
8000 steps per contact time put the code's first-order error in ``e`` near 5e-5 (2e-4 at 2000).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import minimize_scalar

import microimpact as mi
from microimpact import dem
from microimpact.calibrate import Calibration
from microimpact.core.models import hertz_tsuji as ht
from microimpact.core.models import liggghts_hertz_sjkr as law
from microimpact.dynamics import integrate_model
from microimpact.models import liggghts_hertz_sjkr as face

NAME = "liggghts_hertz_sjkr"
E_SI = 1.31e9
R_SI = 2.45e-6
M_SI = 4.0 / 3.0 * math.pi * R_SI**3 * 1350.0
SILICON = mi.ContactPair.paper_case("silicon")
HAVE_LIGGGHTS = dem.find_code("liggghts") is not None


def _params(e_n, k, sjkr2=0, on_wall=1, limit=0):
    return (e_n, k, float(sjkr2), float(on_wall), float(limit))


def _leaves(V, E, R, m, params):
    """The independent integration (:func:`microimpact.dynamics.integrate_model`, scipy's DOP853 of
    :func:`force`): ``e``, or 0 where it reports a captured particle."""
    try:
        r = integrate_model(NAME, V, E, R, m, math.inf, params)
    except ValueError as exc:
        assert "does not leave the surface" in str(exc)
        return 0.0, None
    return r["rebound_velocity"] / V, r


variants = st.tuples(st.integers(0, 1), st.integers(0, 1), st.integers(0, 1))


@settings(deadline=None, max_examples=8)
@given(
    e_n=st.floats(0.06, 1.0),
    log_k=st.floats(5.0, 8.0),
    flags=variants,
    log_r=st.floats(-6.5, -4.0),
    log_e=st.floats(8.5, 11.0),
    factor=st.floats(1.3, 30.0),
)
def test_outcome_equals_the_integration_of_its_force(e_n, log_k, flags, log_r, log_e, factor):
    R = 10.0**log_r
    m = 4.0 / 3.0 * math.pi * R**3 * 2500.0
    E = 10.0**log_e
    p = _params(e_n, 10.0**log_k, *flags)
    Vs = law.sticking_velocity(E, R, m, 0.0, p)
    V = max(Vs * factor, 1e-3)
    o = law.outcome(V, E, R, m, 0.0, p)
    e, r = _leaves(V, E, R, m, p)
    assert 0.0 < o[4] <= 1.0
    assert abs(o[4] - e) < 1e-8
    assert law.restitution_only(V, E, R, m, 0.0, p) == o[4]
    assert o[-1] == pytest.approx(r["contact_time"], rel=1e-8)
    assert o[6] == pytest.approx(r["max_approach"], rel=1e-8)
    assert o[8] == pytest.approx(r["max_force"], rel=1e-8)


@settings(deadline=None, max_examples=6)
@given(e_n=st.floats(0.06, 0.95), log_k=st.floats(6.0, 8.0), flags=variants)
def test_capture_velocity_is_where_the_integration_stops_leaving(e_n, log_k, flags):
    p = _params(e_n, 10.0**log_k, *flags)
    Vs = law.sticking_velocity(E_SI, R_SI, M_SI, 0.0, p)
    assert Vs > 0.0
    assert _leaves(Vs * (1.0 - 1e-8), E_SI, R_SI, M_SI, p)[0] == 0.0
    assert _leaves(Vs * (1.0 + 1e-8), E_SI, R_SI, M_SI, p)[0] > 0.0
    assert law.outcome(Vs * (1.0 - 1e-6), E_SI, R_SI, M_SI, 0.0, p)[4] == 0.0
    assert law.outcome(Vs * (1.0 + 1e-6), E_SI, R_SI, M_SI, 0.0, p)[4] > 0.0


def test_energy_is_never_created_and_capture_needs_damping():
    """The cohesion is conservative and vanishes at zero approach: undamped, the particle leaves
    with its impact speed whatever k (to the integration's 1e-11) and is never captured; damped, e
    lies in [0, 1] and rises with the speed, from capture to hertz_tsuji's e where k = 0."""
    for k in (0.0, 1e7, 5e7):
        for flags in ((0, 1, 0), (1, 0, 1)):
            p = _params(1.0, k, *flags)
            assert law.sticking_velocity(E_SI, R_SI, M_SI, 0.0, p) == 0.0
            for V in (0.5, 5.0, 50.0):
                assert law.outcome(V, E_SI, R_SI, M_SI, 0.0, p)[4] == pytest.approx(1.0, abs=1e-10)
    p = _params(0.3, 3e7)
    es = [law.outcome(V, E_SI, R_SI, M_SI, 0.0, p)[4] for V in np.geomspace(0.1, 300.0, 25)]
    assert all(0.0 <= e <= 1.0 for e in es)
    assert es[0] == 0.0 and es[-1] > 0.0
    assert np.all(np.diff(es) >= 0.0)  # the cohesion's share of the path falls with speed
    # without cohesion it is hertz_tsuji at the damping coefficientRestitution gives
    a = ht.alpha_coeff_restitution(0.3)
    for V in (0.3, 30.0):
        ref = ht.outcome(V, E_SI, R_SI, M_SI, 0.0, (a, 0.0))[4]
        assert law.outcome(V, E_SI, R_SI, M_SI, 0.0, _params(0.3, 0.0))[4] == pytest.approx(ref, abs=1e-10)


def test_damping_sees_only_the_hertz_part():
    """The force is hertz_tsuji's (Hertz + damping) minus k A: the cohesion never enters the damping."""
    p = _params(0.4, 2e7)
    a = ht.alpha_coeff_restitution(0.4)
    for alpha, rate in ((1e-9, 3.0), (1e-8, -2.0), (3e-8, 0.5)):
        f_ht = ht.signed_force(alpha, rate, alpha, E_SI, R_SI, M_SI, 0.0, (a, 0.0))
        coh = 2e7 * math.pi * (2.0 * R_SI * alpha - alpha * alpha)
        assert law.force(alpha, rate, alpha, E_SI, R_SI, M_SI, 0.0, p) == pytest.approx(f_ht - coh, rel=1e-14)
    # limitForce clips the Hertz and damping part only: the cohesion still pulls
    alpha, rate = 1e-9, -50.0
    assert ht.signed_force(alpha, rate, alpha, E_SI, R_SI, M_SI, 0.0, (a, 0.0)) < 0.0
    clipped = law.force(alpha, rate, alpha, E_SI, R_SI, M_SI, 0.0, _params(0.4, 2e7, limit=1))
    assert clipped == pytest.approx(-2e7 * math.pi * (2.0 * R_SI * alpha - alpha * alpha), rel=1e-14)


def test_sjkr2_pulls_twice_as_hard_between_particles():
    """sjkr2's area is 2 pi R delta at a wall but 2 pi (2 R*) delta between particles: the pair with k
    is the wall with 2 k, bit for bit; sjkr's circle differs between the two only in delta^2."""
    for V in (3.0, 30.0):
        pair = law.outcome(V, E_SI, R_SI, M_SI, 0.0, _params(0.5, 1e7, 1, 0))
        wall = law.outcome(V, E_SI, R_SI, M_SI, 0.0, _params(0.5, 2e7, 1, 1))
        assert pair == wall
    ratio = law.sticking_velocity(E_SI, R_SI, M_SI, 0.0, _params(0.5, 1e7, 1, 0)) / law.sticking_velocity(
        E_SI, R_SI, M_SI, 0.0, _params(0.5, 1e7, 1, 1)
    )
    assert 4.0 < ratio < 7.0  # V_s grows about as k^(5/2): 2^(5/2) = 5.7
    s_wall = law.sticking_velocity(E_SI, R_SI, M_SI, 0.0, _params(0.5, 1e7, 0, 1))
    s_pair = law.sticking_velocity(E_SI, R_SI, M_SI, 0.0, _params(0.5, 1e7, 0, 0))
    assert s_pair > s_wall and s_pair / s_wall - 1.0 < 0.05


@pytest.mark.parametrize("flags", [(0, 1), (1, 1), (1, 0)])
def test_work_of_adhesion_gives_jkr_pulloff(flags):
    G = 0.08
    p = face.params_for_work_of_adhesion(G, (E_SI, R_SI, M_SI, math.inf), _params(0.5, 0.0, *flags))
    assert p[0] == 0.5 and p[2:] == _params(0.5, 0.0, *flags)[2:]
    assert face.pulloff_force(E_SI, R_SI, p) == pytest.approx(1.5 * math.pi * G * R_SI, rel=1e-13)
    # the resting contact's largest tension, found numerically from the force law (v = 0)
    res = minimize_scalar(
        lambda a: law.force(a, 0.0, a, E_SI, R_SI, M_SI, 0.0, p), bounds=(1e-14, 1e-7), method="bounded",
        options={"xatol": 1e-18},
    )  # fmt: skip
    small = 1e-2 if flags[0] == 0 else 1e-9  # sjkr's delta^2 term: of the order of the strain, 5e-3 here
    assert -res.fun == pytest.approx(1.5 * math.pi * G * R_SI, rel=small)
    with pytest.raises(ValueError, match="work_of_adhesion must be non-negative and finite, got -1"):
        face.params_for_work_of_adhesion(-1, (E_SI, R_SI, M_SI, math.inf), p)


def test_lines_and_calibration():
    cal = Calibration.of(SILICON, NAME, {"restitution": 0.6, "cohesion_energy_density": 1.5e7, "sjkr2": 1}, [20.0])
    text = cal.liggghts()
    assert "cohesion sjkr2 limitForce off" in text
    assert "fix m5 all property/global cohesionEnergyDensity peratomtypepair 1 15000000" in text
    assert "coefficientRestitution peratomtypepair 1 0.6" in text
    assert text.count("cohesion sjkr2") == 2  # the pair and the wall
    with pytest.raises(ValueError, match="coefficientRestitution > 0.05"):
        Calibration.of(SILICON, NAME, {"restitution": 0.05, "cohesion_energy_density": 1.0}, [20.0]).liggghts()
    pv = (E_SI, R_SI, M_SI, math.inf)
    V = np.array([10.0, 40.0])
    target = np.array([0.5, 0.6])
    got = face.calibrate(pv, V, target, None, cohesion_energy_density=2e7)
    assert got[1:] == (2e7, 0.0, 1.0, 0.0)
    mean = np.mean([law.outcome(v, E_SI, R_SI, M_SI, 0.0, got)[4] for v in V])
    assert mean == pytest.approx(0.55, abs=1e-12)
    with pytest.raises(ValueError, match="cohesion_energy_density must be non-negative"):
        face.calibrate(pv, V, target, None, cohesion_energy_density=-1.0)
    # the generic machinery takes the model
    o = SILICON.impact(20.0, model=NAME, restitution=0.6, cohesion_energy_density=1.5e7, warn=False)
    assert float(o.restitution) == law.outcome(20.0, *pv[:3], 0.0, _params(0.6, 1.5e7))[4]


# ----------------------------------------------------------------------------- LIGGGHTS itself
needs_liggghts = pytest.mark.skipif(not HAVE_LIGGGHTS, reason="LIGGGHTS (liggghts) not installed")
STEPS = 8000


@needs_liggghts
@pytest.mark.parametrize(
    "e_n, k, sjkr2",
    [(0.6, 2.5e7, 0), (0.4, 1.8e7, 1)],
    ids=["sjkr", "sjkr2"],
)
def test_liggghts_wall_bounce_and_capture(e_n, k, sjkr2):
    cal = Calibration.of(SILICON, NAME, {"restitution": e_n, "cohesion_energy_density": k, "sjkr2": sjkr2}, [20.0])
    E, R, m = cal.effective_modulus, cal.effective_radius, cal.effective_mass
    p = cal.params
    Vs = law.sticking_velocity(E, R, m, 0.0, p)
    # one bounce at twice the capture speed: e and the contact time to 1e-3
    r = dem.check(cal, "liggghts", [2.0 * Vs], steps_per_contact=STEPS)[0]
    assert r["restitution"] == pytest.approx(r["predicted_restitution"], rel=1e-3)
    assert r["contact_time"] == pytest.approx(r["predicted_contact_time"], rel=1e-3)
    assert 0.05 < r["predicted_restitution"] < 0.9 * e_n  # the cohesion matters here
    # the capture decision at V_s (1 -+ 1e-3): LIGGGHTS captures below and lets go above
    c = dem.capture(cal, "liggghts", rel=1e-3, steps_per_contact=STEPS)
    assert c["capture_velocity"] == Vs
    assert c["agrees"] and c["runs"] == 2, c


@needs_liggghts
@pytest.mark.parametrize("sjkr2", [0, 1], ids=["sjkr", "sjkr2"])
def test_liggghts_two_spheres(sjkr2):
    """Between two equal spheres the code's cohesive area is the pair's (on_wall = 0); for sjkr2 it is
    twice the wall's, which the wall's prediction misses by far."""
    given = {"restitution": 0.5, "cohesion_energy_density": 1.2e7, "sjkr2": sjkr2, "on_wall": 0}
    cal = Calibration.of(SILICON, NAME, given, [20.0])
    E, R, m = cal.effective_modulus, cal.effective_radius, cal.effective_mass
    V = 2.0 * law.sticking_velocity(E, R, m, 0.0, cal.params)
    r = dem.check(cal, "liggghts", [V], steps_per_contact=STEPS, geometry="sphere")[0]
    assert r["restitution"] == pytest.approx(r["predicted_restitution"], rel=1e-3)
    assert r["contact_time"] == pytest.approx(r["predicted_contact_time"], rel=1e-3)
    wall = law.outcome(V, E, R, m, 0.0, cal.params[:3] + (1.0,) + cal.params[4:])[4]
    if sjkr2:
        assert abs(wall / r["restitution"] - 1.0) > 0.1
