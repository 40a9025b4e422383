"""``pair.history(V, model=NAME, method="ode")``: every model's own force law integrated in time
(:func:`microimpact.dynamics.integrate_model`) ends where the model's closed form (or built-in
quadrature) says: rebound speed, contact time, maximum approach and force to 1e-8; energy is never
created."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import microimpact as mi
from microimpact import dynamics
from microimpact.core import models

# Parameters for the models whose parameters have no default, two conventions each where they differ.
PARAMS = {
    "thornton_ning_2016": [{}],
    "liggghts_thornton_ning": [{}],
    "liggghts_hertz_sjkr": [
        {"restitution": 0.7, "cohesion_energy_density": 2e7},
        {"restitution": 0.4, "cohesion_energy_density": 1e7, "sjkr2": 1, "on_wall": 0, "limit_force": 1},
    ],
    "linear_spring_dashpot": [
        {"stiffness": 1e3, "restitution": 0.6, "limit_force": 0},
        {"stiffness": 1e3, "restitution": 0.6, "limit_force": 1},
    ],
    "hertz_viscoelastic": [
        {"dissipative_constant": 1e-9, "limit_force": 1},
        {"dissipative_constant": 1e-9, "limit_force": 0},
    ],
    "hertz_tsuji": [{"damping_ratio": 0.3, "limit_force": 1}, {"damping_ratio": 0.3, "limit_force": 0}],
    "luding_hysteretic": [
        {"loading_stiffness": 1e3, "unloading_stiffness": 4e3, "plasticity_depth": 0.0},
        {"loading_stiffness": 1e3, "unloading_stiffness": 4e3, "plasticity_depth": 0.2},
    ],
    "jkr_elastic_adhesive": [{"surface_energy": 0.05}],
    "dmt_elastic_adhesive": [{"surface_energy": 0.05}],
    "jackson_green_brake": [
        {"yield_strength": 40e6, "poisson_ratio": 0.3},
        {"yield_strength": 40e6, "poisson_ratio": 0.25, "identical_spheres": 1},
    ],
    "kogut_etsion_ekk": [{"yield_strength": 40e6, "poisson_ratio": 0.3}],
    "thornton_ning_1998_elastic_adhesive": [{"work_of_adhesion": 0.1}],
    "thornton_ning_1998_adhesive_plastic": [{"work_of_adhesion": 0.1}],
    "luding_adhesive": [
        {"loading_stiffness": 1e3, "unloading_stiffness": 4e3, "adhesion_stiffness": 50.0, "plasticity_depth": 0.2}
    ],
    "lammps_mdr": [
        {"poisson_ratio": 0.3, "yield_strength": 74e6, "surface_energy": 0.0, "damping": 0.0},
        {"poisson_ratio": 0.3, "yield_strength": 74e6, "surface_energy": 0.1, "damping": 0.5},
    ],
    "lethe_dmt_vdw": [{"restitution": 0.6, "effective_surface_energy": 0.05, "hamaker_constant": 1e-19}],
    "liggghts_edinburgh": [{}, {"fix_kc": 1, "adhesion_stiffness_ratio": 0.2, "limit_force": 0}],
    "lammps_jkr": [
        {"surface_energy": 0.05, "viscoelastic_damping": 2e13},
        {"surface_energy": 0.05, "damping_model": 2, "normal_restitution": 0.6},
    ],
    "lammps_dmt": [
        {"surface_energy": 0.05, "viscoelastic_damping": 2e13},
        {"surface_energy": 0.05, "damping_model": 2, "normal_restitution": 0.6},
    ],
    "liggghts_easo_capillary": [
        {"liquid_content": 1e-3, "fluid_viscosity": 1e-3, "coefficient_restitution": 0.8, "contact_angle": 20.0},
        {"liquid_content": 1e-3, "two_spheres": 1, "limit_force": 1, "coefficient_restitution": 0.8},
    ],
    "liggghts_washino_capillary": [
        {"liquid_content": 1e-3, "fluid_viscosity": 1e-3, "coefficient_restitution": 0.8, "contact_angle": 20.0},
        {"liquid_content": 1e-3, "two_spheres": 1, "angle_mixing": 1, "contact_angle": 20.0},
    ],
    "willett_capillary": [{"liquid_volume": 1e-19, "contact_angle": 20.0}, {"liquid_volume": 1e-19, "two_spheres": 1}],
    "rabinovich_capillary": [{"liquid_volume": 1e-19, "contact_angle": 20.0}],
}
#: Models whose speed V is not the speed at first contact, which the generic integration starts from:
#: Lethe's DMT attracts the particle before contact (V is the speed outside its cut-off); its outcome
#: is held to its own integration from the cut-off in tests/test_lethe_dmt_vdw.py.
NOT_FROM_CONTACT = {"lethe_dmt_vdw"}
CASES = [(name, i) for name in PARAMS for i in range(len(PARAMS[name]))]
SILICON = mi.ContactPair.paper_case("silicon")
TOL = 1e-8  # the issue asks 1e-8 of closed form against the integration of the force law


def test_every_model_is_covered():
    assert set(PARAMS) == set(models.available())


def _check(pair, V, name, params, o=None):
    if name in NOT_FROM_CONTACT:
        pytest.skip(f"{name}: V is the speed outside the cut-off, not at first contact")
    if o is None:
        o = pair.impact(V, model=name, warn=False, **params)
    if math.isnan(float(o.restitution)):
        # the law has no impact here (LAMMPS mdr past the wall plane: its unloading geometry is gone and
        # the code's force turns NaN): flagged, never silent, and no history is made up for it
        assert bool(o.outside_validity), f"{name} at V = {V}: a NaN outcome must be flagged"
        with pytest.raises(ValueError, match="gives no outcome"):
            pair.history(V, model=name, method="ode", n=201, **params)
        return None
    h = pair.history(V, model=name, method="ode", n=201, **params)
    assert h.method == "ode" and h.model == name
    assert abs(h.rebound_velocity / V - float(o.restitution)) < TOL
    assert abs(h.contact_time / float(o.contact_time) - 1.0) < TOL
    assert abs(h.loading_time / float(o.loading_time) - 1.0) < TOL
    assert abs(h.max_approach / float(o.max_approach) - 1.0) < TOL
    assert abs(h.max_force / float(o.max_force) - 1.0) < TOL
    # energy is never created: the rebound is never faster than the impact (to the solver's
    # accuracy: at rtol 1e-12 its error accumulates over the steps of the contact; an elastic
    # impact has come back 1e-12 fast, and DMT's (e = 1 exactly) 1.1e-11 fast in one order of
    # the suite, where compiled kernels were already loaded) ...
    assert h.rebound_velocity <= V * (1.0 + 1e-10)
    # ... and, without adhesion, the speed never exceeds the impact speed during the contact
    if (
        "adhesive" not in name and not models.get(name).STICKS
    ):  # an attractive force speeds the particle up at first contact
        assert np.all(np.abs(h.approach_velocity) <= V * (1.0 + 1e-9))
    # the history runs from first contact to separation, loading then unloading
    assert h.time[0] == 0.0 and h.time[-1] == pytest.approx(h.contact_time, rel=1e-14)
    assert h.approach_velocity[0] == V
    assert h.approach_velocity[-1] == pytest.approx(-h.rebound_velocity, rel=1e-9, abs=1e-12 * V)
    return h


@pytest.mark.parametrize("V", [3.0, 30.0, 300.0])
@pytest.mark.parametrize("name, i", CASES)
def test_ode_history_ends_at_the_closed_form(name, i, V):
    _check(SILICON, V, name, PARAMS[name][i])


@settings(derandomize=True, deadline=None, max_examples=6)
@given(
    log_v=st.floats(-0.5, 2.5),
    log_r=st.floats(-7.0, -4.0),
    rho=st.floats(500.0, 20000.0),
    log_e=st.floats(8.0, 11.5),
    log_py=st.floats(7.0, 9.5),
)
@pytest.mark.parametrize("name, i", CASES)
def test_ode_history_ends_at_the_closed_form_wide(name, i, log_v, log_r, rho, log_e, log_py):
    if name == "jackson_green_brake":
        # Its force law runs in Python inside the ODE (about 25 ms an impact): over the wide box one
        # case (V = 316 m/s, R = 100 um, E* = 1e8 Pa) ran for minutes in CI. Its outcome is held to the
        # ODE at fixed speeds above and in tests/core/test_fitted_laws.py, across every jump.
        pytest.skip("jackson_green_brake: ODE too slow over the wide box; checked at fixed speeds")
    R = 10.0**log_r
    pair = mi.ContactPair.sphere_on_flat(R, rho, 10.0**log_e, 10.0**log_py)
    params = dict(PARAMS[name][i])
    if name in ("linear_spring_dashpot", "luding_hysteretic", "luding_adhesive"):  # stiffnesses ~ the pair
        scale = 10.0**log_e * R / 1e3
        for k in ("stiffness", "loading_stiffness", "unloading_stiffness", "adhesion_stiffness"):
            if k in params:
                params[k] = params[k] * scale
    o = None
    if "adhesive" in name or models.get(name).STICKS:  # keep the particle above its sticking speed
        o = pair.impact(10.0**log_v, model=name, warn=False, **params)
        if not o.restitution > 0.0:
            return
    _check(pair, 10.0**log_v, name, params, o)


def test_the_generic_integration_reproduces_the_seed_ode():
    """The generic route and the seed's three-stage route (which also locates the yield) agree."""
    p = SILICON
    a = dynamics.integrate_model("thornton_ning_2016", 50.0, *p._args)
    b = dynamics.integrate_impact(50.0, *p._args)
    for k in ("rebound_velocity", "contact_time", "loading_time", "max_approach", "max_force", "plastic_approach"):
        assert a[k] == pytest.approx(b[k], rel=1e-9), k


def test_closed_history_only_for_the_seed():
    with pytest.raises(
        ValueError, match=r"model 'liggghts_thornton_ning' has no closed-form history \(method 'closed'\)"
    ):
        SILICON.history(50.0, model="liggghts_thornton_ning", method="closed")
    with pytest.raises(ValueError, match="method must be 'closed' or 'ode', got 'rk4'"):
        SILICON.history(50.0, model="liggghts_thornton_ning", method="rk4")
    # without a method: closed form where it exists, the integration otherwise
    assert SILICON.history(50.0).method == "closed"
    assert SILICON.history(50.0, model="liggghts_thornton_ning").method == "ode"


def test_parameters_are_checked():
    with pytest.raises(ValueError, match="needs the parameter 'stiffness'"):
        SILICON.history(10.0, model="linear_spring_dashpot")
    with pytest.raises(ValueError, match="has no parameter 'stiffnes'"):
        SILICON.history(10.0, model="linear_spring_dashpot", stiffnes=1.0, restitution=0.5)
    with pytest.raises(ValueError, match="has no parameter 'k'"):
        SILICON.history(10.0, k=2.0)


def test_a_sticking_particle_has_no_finite_history():
    # JKR below its sticking speed: e = 0 and contact_time = inf in closed form
    o = SILICON.impact(0.01, model="jkr_elastic_adhesive", surface_energy=0.5)
    assert float(o.restitution) == 0.0 and math.isinf(float(o.contact_time))
    with pytest.raises(ValueError, match="does not leave the surface at velocity 0.01 m/s"):
        SILICON.history(0.01, model="jkr_elastic_adhesive", surface_energy=0.5)


def test_stages_and_csv_of_a_model_history(tmp_path):
    h = SILICON.history(30.0, model="luding_hysteretic", n=101, loading_stiffness=1e3, unloading_stiffness=4e3)
    assert set(np.unique(h.stage)) == {1, 3}
    assert np.all(h.stage[h.time <= h.loading_time] == 1)
    assert math.isnan(h.elastic_stage_time) and math.isnan(h.yield_velocity)
    path = tmp_path / "h.csv"
    h.to_csv(path)
    text = path.read_text()
    assert "model luding_hysteretic" in text.splitlines()[1]
    back = np.loadtxt(path, delimiter=",", comments="#", skiprows=1)
    np.testing.assert_array_equal(back[:, 0], h.time)
    np.testing.assert_array_equal(back[:, 0], h.time)


@pytest.mark.parametrize("name", ["thornton_ning_2016", "liggghts_thornton_ning"])
def test_a_second_loading_stage_is_located_and_timed(name):
    """A model that declares ``stage_two_approach`` (the seed's loading: Hertz to the yield approach,
    then plastic) has its integrated history split there: stage 2 begins at the yield approach, and
    the two stage times are the integration's own, equal to the closed form's."""
    from microimpact import contact

    closed = SILICON.impact(50.0, model=name, warn=False)
    h = SILICON.history(50.0, model=name, method="ode", n=201)
    assert set(np.unique(h.stage)) == {1, 2, 3}
    for key in ("elastic_stage_time", "plastic_stage_time", "loading_time"):
        assert getattr(h, key) == pytest.approx(float(getattr(closed, key)), rel=1e-9), key
    (at,) = np.flatnonzero(h.time == h.elastic_stage_time)  # the boundary is on the grid
    assert h.stage[at] == 1 and h.stage[at + 1] == 2
    a_y = float(contact.yield_approach(*SILICON._args[3:], *SILICON._args[:2]))
    assert h.approach[at] == pytest.approx(a_y, rel=1e-9)
    # below the yield velocity there is no second stage
    low = SILICON.history(0.5 * SILICON.yield_velocity, model=name, method="ode", n=51)
    assert set(np.unique(low.stage)) == {1, 3} and low.plastic_stage_time == 0.0


def test_a_phase_that_does_not_end_is_bounded_and_says_so():
    """An oscillator whose event never comes: the phase stops at its bound of right-hand-side evaluations
    with a ValueError naming it (the solver would otherwise run until its 60 doublings of the span)."""
    from microimpact import dynamics

    never = dynamics._event(lambda t, y: 2.0 - y[0], -1)  # |y| <= 1: never crosses

    calls = []

    def rhs(t, y):
        calls.append(t)
        return [y[1], -y[0]]

    with pytest.raises(ValueError, match="bound of 3000 right-hand-side evaluations"):
        dynamics._integrate_phase(rhs, 0.0, [0.0, 1.0], 2.0, [never], "DOP853", 1e-10, 1e-12, limit=3000)
    assert len(calls) == 3000
