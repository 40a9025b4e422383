"""Capture in the DEM codes: :func:`microimpact.dem.capture` and the captured runs of :func:`~microimpact.dem.run`.

Each adhesive law with DEM lines is run in the code it is written for, on cases used nowhere else
in the tests: the code keeps the particle at ``V_s (1 - 1e-3)`` and lets it go at ``V_s (1 + 1e-3)``
(its capture velocity is the law's to 1e-3), and above it gives the law's ``e`` and contact time to
1e-3. Inputs calibrated to Thornton & Ning's whole law (:func:`~microimpact.calibrate.calibrate_adhesive`)
reproduce that law's capture velocity to 1e-3 in the code itself. The peer runs skip where the code
is not installed (CI installs both).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import microimpact as mi
from microimpact import dem
from microimpact.calibrate import Calibration, calibrate_adhesive
from microimpact.core.models import get

LMP, LIGGGHTS = dem.find_code("lammps"), dem.find_code("liggghts")
# a 6 um silica-like sphere (E* = 30 GPa) and a 4 mm soft granule (E* = 0.2 GPa), both elastic here
MICRO = mi.ContactPair.sphere_on_flat(3e-6, 2200.0, 30e9, 1e12)
GRANULE = mi.ContactPair.sphere_on_flat(2e-3, 2000.0, 2e8, 1e12)
# an 18 um one: LIGGGHTS' capillary bridges between two of them lie above the code's volume floor
DROPLET = mi.ContactPair.sphere_on_flat(9e-6, 2200.0, 30e9, 1e12)
STEPS = 3000

CASES = {
    "lammps jkr viscoelastic, two spheres": (
        MICRO,
        "lammps_jkr",
        {"surface_energy": 0.03, "viscoelastic_damping": 1e13},
        "lammps",
        "sphere",
    ),
    "lammps dmt viscoelastic, wall": (
        MICRO,
        "lammps_dmt",
        {"surface_energy": 0.02, "viscoelastic_damping": 5e13},
        "lammps",
        "wall",
    ),
    "liggghts sjkr, wall": (
        MICRO,
        "liggghts_hertz_sjkr",
        {"restitution": 0.7, "cohesion_energy_density": 5e7},
        "liggghts",
        "wall",
    ),
    "liggghts edinburgh pull-off force, wall": (
        GRANULE,
        "liggghts_edinburgh",
        {"pull_off_force": -2e-3, "coefficient_restitution": 0.98},
        "liggghts",
        "wall",
    ),
    "liggghts edinburgh surface energy, two spheres": (
        GRANULE,
        "liggghts_edinburgh",
        {"work_of_adhesion": 8.0, "two_spheres": 1.0},
        "liggghts",
        "sphere",
    ),
    "liggghts easo capillary, two spheres": (
        DROPLET,
        "liggghts_easo_capillary",
        {"liquid_content": 0.01, "fluid_viscosity": 1e-3, "two_spheres": 1.0},
        "liggghts",
        "sphere",
    ),
    "liggghts washino capillary, two spheres": (
        DROPLET,
        "liggghts_washino_capillary",
        {"liquid_content": 0.02, "fluid_viscosity": 2e-3, "two_spheres": 1.0, "coefficient_restitution": 0.9},
        "liggghts",
        "sphere",
        # the bridge reaches the deck's starting gap (1.5 steps of flight) and slows the particle
        # before it touches: first order in the step, -1.7e-3 in V_s at 3000 steps, -3.7e-4 at 12000
        12000,
    ),
}


def _needs(code):
    if (LMP if code == "lammps" else LIGGGHTS) is None:
        pytest.skip(f"{code} is not installed")


@pytest.mark.parametrize("case", sorted(CASES))
def test_the_code_captures_where_the_law_does(case):
    pair, model, params, code, geometry, *steps = CASES[case]
    steps = steps[0] if steps else STEPS
    _needs(code)
    cal = Calibration.of(pair, model, params, 1.0)
    Vs = dem.capture_velocity(cal)
    assert 0.0 < Vs < math.inf
    c = dem.capture(cal, code, geometry=geometry, steps_per_contact=steps)
    assert c["capture_velocity"] == Vs
    assert c["agrees"] and c["runs"] == 2, c
    lo, hi = c["bracket"]
    assert lo == pytest.approx(Vs * (1.0 - 1e-3), rel=1e-12) and hi == pytest.approx(Vs * (1.0 + 1e-3), rel=1e-12)
    # above the capture velocity, and below it at a speed the law keeps by far
    rows = dem.check(cal, code, [0.5 * Vs, 2.0 * Vs], geometry=geometry, steps_per_contact=steps)
    kept, left = rows
    assert kept["predicted_restitution"] == 0.0 and kept["captured"] and kept["restitution"] == 0.0
    assert not left["captured"] and 0.0 < left["predicted_restitution"] < 1.0
    assert abs(left["restitution"] - left["predicted_restitution"]) < 1e-3
    assert left["contact_time"] == pytest.approx(left["predicted_contact_time"], rel=1e-3)


@pytest.mark.parametrize(
    "model, code, params",
    [
        ("lammps_jkr", "lammps", {"damping_model": 0.0, "viscoelastic_damping": 1e13}),
        ("liggghts_hertz_sjkr", "liggghts", {"restitution": 0.8}),
    ],
)
def test_inputs_calibrated_to_the_whole_law_give_its_capture_velocity_in_the_code(model, code, params):
    """The code's adhesion input searched so that the law's capture velocity is the whole law's
    (weighted 100 against the e residuals, which an elastic law cannot match), then run in the code:
    it keeps the particle at the whole law's ``V_s (1 - 1e-3)`` and lets it go at ``V_s (1 + 1e-3)``."""
    _needs(code)
    cal = calibrate_adhesive(MICRO, model, 0.06, [1.0], params=params, capture_weight=100.0)
    target = cal.target_capture_velocity
    assert cal.capture_velocity == pytest.approx(target, rel=1e-5)
    above = target * (1.0 + 1e-3)
    kept, left = (
        dem.run(dem.deck(cal, code, v, steps_per_contact=STEPS, sizing_velocity=above))
        for v in (target * (1.0 - 1e-3), above)
    )
    assert kept["captured"] and not left["captured"]
    assert abs(left["restitution"] - dem.predict(cal, above)[0]) < 1e-2  # e rises as (V - V_s)^(1/2) here


@pytest.mark.parametrize("model", ["liggghts_easo_capillary", "liggghts_washino_capillary"])
def test_below_the_codes_bridge_volume_floor_liggghts_applies_no_bridge(model):
    """Between two 6 um spheres with 1 % liquid the bridge (about 1e-18 m^3) is below the 1e-17 m^3
    under which LIGGGHTS skips every cohesive force: the code returns the dry Hertz bounce, and so
    does the law, flagged (bit 16), where the same bridge 3 times larger captures the particle."""
    _needs("liggghts")
    given = {"liquid_content": 0.01, "fluid_viscosity": 1e-3, "two_spheres": 1.0, "coefficient_restitution": 0.9}
    cal = Calibration.of(MICRO, model, given, 1.0)
    assert dem.capture_velocity(cal) == 0.0
    assert dem.capture_velocity(Calibration.of(DROPLET, model, given, 1.0)) > 1.0
    pv = (cal.effective_modulus, cal.effective_radius, cal.effective_mass, math.inf)
    assert int(get(model).outside_validity(1.0, *pv, cal.params)) & 16
    (row,) = dem.check(cal, "liggghts", [1.0], geometry="sphere", steps_per_contact=STEPS)
    dry = Calibration.of(
        MICRO, "liggghts_hertz_sjkr", {"restitution": 0.9, "cohesion_energy_density": 0.0, "on_wall": 0.0}, 1.0
    )
    assert row["predicted_restitution"] == pytest.approx(dem.predict(dry, 1.0)[0], abs=1e-9)
    assert abs(row["restitution"] - row["predicted_restitution"]) < 1e-3


# ----------------------------------------------------------------------------- without a code


def _deck(rows, velocity, time_step, contact_time):
    return dem.Deck(
        text="",
        code="lammps",
        geometry="wall",
        model="lammps_jkr",
        velocity=velocity,
        time_step=time_step,
        steps=len(rows),
        gap=1.5 * velocity * time_step,
        radius=1.0,
        mass=1.0,
        predicted_restitution=0.0,
        predicted_contact_time=contact_time,
    )


def test_a_record_that_ends_in_contact_is_a_capture_and_one_that_leaves_is_not():
    """A particle bound in a linear well (force -k (z - z_eq), never zero at the end) is captured;
    the same spring with a particle leaving at half its speed is a bounce with that e."""
    V, dt, w = 1.0, 1e-3, 2.0 * math.pi
    t = dt * np.arange(4000)
    start = 1.5 * dt
    inside = t > start
    z = np.where(inside, 1.0 - (V / w) * np.sin(w * (t - start)), 1.0 + V * (start - t))
    vz = np.where(inside, -V * np.cos(w * (t - start)), -V)
    fz = np.where(inside, (1.0 - z) * w * w, 0.0)
    kept = dem._analyse(_deck(np.column_stack([t, z, vz, fz]), V, dt, math.inf), np.column_stack([t, z, vz, fz]))
    assert kept["captured"] and kept["restitution"] == 0.0 and kept["contact_time"] == math.inf
    half = t > start + 0.5  # half a period in contact, then away at e = 1/2
    z2 = np.where(half, 1.0 + 0.5 * V * (t - start - 0.5), z)
    vz2 = np.where(half, 0.5 * V, vz)
    fz2 = np.where(half, 0.0, fz)
    rows = np.column_stack([t, z2, vz2, fz2])
    left = dem._analyse(_deck(rows, V, dt, 0.5), rows)
    assert not left["captured"] and left["restitution"] == pytest.approx(0.5, rel=1e-12)
    assert left["contact_time"] == pytest.approx(0.5, abs=2 * dt)


def test_a_captured_speed_gets_a_deck_sized_at_the_capture_velocity():
    cal = Calibration.of(MICRO, "lammps_jkr", {"surface_energy": 0.03, "viscoelastic_damping": 1e13}, 1.0)
    Vs = dem.capture_velocity(cal)
    d = dem.deck(cal, "lammps", 0.5 * Vs, steps_per_contact=1000)
    t_size = dem.predict(cal, Vs * (1.0 + dem.CAPTURE_REL))[1]
    assert d.predicted_restitution == 0.0 and d.predicted_contact_time == math.inf
    assert d.sizing_contact_time == t_size and d.time_step == pytest.approx(t_size / 1000, rel=1e-12)
    assert d.steps * d.time_step > 4.0 * t_size  # long enough for a particle the code lets go to leave
    assert "predicted: captured" in d.text
    with pytest.raises(ValueError, match="sizing_velocity must be a positive finite number, got -1"):
        dem.deck(cal, "lammps", 0.5 * Vs, sizing_velocity=-1)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"rel": 0.0}, "rel must be a number in"),
        ({"rel": 0.5}, "rel must be a number in"),
        ({"max_runs": 1}, "max_runs must be an integer >= 2"),
        ({"code": "yade"}, "code must be one of"),
    ],
)
def test_capture_refuses_bad_inputs_by_name(kwargs, match):
    cal = Calibration.of(MICRO, "lammps_jkr", {"surface_energy": 0.03, "viscoelastic_damping": 1e13}, 1.0)
    code = kwargs.pop("code", "lammps")
    with pytest.raises(ValueError, match=match):
        dem.capture(cal, code, **kwargs)


def test_capture_refuses_a_law_that_captures_nothing():
    cal = Calibration.of(MICRO, "lammps_dmt", {"surface_energy": 0.03}, 1.0)  # undamped DMT returns all
    assert dem.capture_velocity(cal) == 0.0
    with pytest.raises(ValueError, match="captures no particle"):
        dem.capture(cal, "lammps")
