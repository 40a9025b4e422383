"""Fault corpus, part 3 (issue 24): the remaining tracebacks and lenient parses.

Each case gave a traceback or silently accepted a typo on the code before: a tiny ``p_y`` made
``V_y`` underflow to 0 (ZeroDivisionError), ``dpsi=0`` divided by zero, a closed standard output
gave an AttributeError, ``1,,2`` and ``50,`` were read as ``1,2`` and ``50``, a cell ``1_0`` was
read as 10 (Python's ``float`` takes digit separators), ``--diameters ''`` was taken as "not
given", two diameters written to one file name overwrote each other, and ``--case`` was ignored
beside ``--alumina``.
"""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

import microimpact as mi
from microimpact.impact import impact_outcome
from microimpact.io import read_table
from microimpact.oblique import universal_table

from .test_faults import _env, assert_one_line, run

DATA = "velocity,restitution\n5,1.0\n20,0.86\n50,0.72\n80,0.64\n"


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "data.csv").write_text(DATA)
    return tmp_path


# ----------------------------------------------------------------------------- a tiny p_y: V_y underflows
@pytest.mark.parametrize("p_y", ["1e-61", "1e-200", "5e-324"])
@pytest.mark.parametrize("command", ["impact", "sweep csv", "sweep nc"])
def test_tiny_limiting_pressure_is_refused_naming_it(work, capsys, command, p_y):
    argv = {
        "impact": ["impact", "50", "--limiting-pressure", p_y],
        "sweep csv": ["sweep", "--velocity", "1,2", "--limiting-pressure", f"{p_y},1e6", "--out", "s.csv"],
        "sweep nc": [
            "sweep",
            "--velocity",
            "1,2",
            "--limiting-pressure",
            f"{p_y},1e6",
            "--out",
            "s.nc",
            "--chunks",
            "1",
        ],
    }[command]
    rc, out, err = run(argv, capsys)
    assert_one_line(rc, err, "limiting_pressure", "V_y")
    assert sorted(p.name for p in work.iterdir()) == ["data.csv"]  # refused before any work


def test_tiny_limiting_pressure_in_the_api():
    with pytest.raises(ValueError, match="limiting_pressure 1e-61"):
        mi.ContactPair.sphere_on_flat(radius=2.45e-6, density=1350.0, effective_modulus=1.31e9, limiting_pressure=1e-61)
    with pytest.raises(ValueError, match="limiting_pressure"):
        impact_outcome(np.array([10.0, 50.0]), 1.31e9, 2.45e-6, 8.3e-14, np.array([156e6, 1e-70]))
    # the smallest p_y that still gives V_y > 0 is accepted, and V_y then follows eq. 28's p_y^(5/2)
    a = mi.ContactPair.sphere_on_flat(radius=2.45e-6, density=1350.0, effective_modulus=1.31e9, limiting_pressure=1e-40)
    b = a.replace(limiting_pressure=1e-39)
    assert b.yield_velocity / a.yield_velocity == pytest.approx(10**2.5, rel=1e-12)


@pytest.mark.parametrize("dpsi", [0, 0.0, -0.025, float("nan"), float("inf")])
def test_universal_table_refuses_a_zero_step(dpsi):
    with pytest.raises(ValueError, match="dpsi"):
        universal_table(4.0, dpsi=dpsi)


# ----------------------------------------------------------------------------- standard output closed
@pytest.mark.parametrize("argv", [["impact", "50"], ["impact", "50", "--json"], ["materials"]])
def test_closed_standard_output(argv):
    proc = subprocess.run(
        [sys.executable, "-m", "microimpact", *argv],
        stdin=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        env=_env(),
        preexec_fn=lambda: os.close(1),  # as the shell's  >&-
    )
    assert_one_line(proc.returncode, proc.stderr, "standard output", "closed")


# ----------------------------------------------------------------------------- lenient lists and numbers
@pytest.mark.parametrize("values", ["1,,2", "50,", ",50", " , "])
def test_empty_list_items_are_refused(work, capsys, values):
    rc, out, err = run(["impact", values], capsys)
    assert_one_line(rc, err, "velocity", "empty")
    assert out == ""


@pytest.mark.parametrize("text", ["1_0", "0x10", "1__0", "١٠"])  # digit separators, hex, Arabic-Indic digits
def test_python_only_number_forms_are_refused(work, capsys, text):
    rc, out, err = run(["impact", text], capsys)
    assert_one_line(rc, err, "velocity", text)
    rc, out, err = run(["impact", "50", "--radius", text], capsys)
    assert_one_line(rc, err, "--radius")
    (work / "u.csv").write_text(f"velocity,restitution\n5,1.0\n20,0.86\n{text},0.72\n80,0.64\n")
    rc, out, err = run(["fit", "u.csv"], capsys)
    assert_one_line(rc, err, "u.csv", "line 4", "not a number")


def test_read_table_keeps_a_separator_cell_as_text(tmp_path):
    (tmp_path / "t.csv").write_text("a [1],b [1]\n1_0,2\n3,4\n")
    t = read_table(tmp_path / "t.csv")
    assert t["b"].tolist() == [2.0, 4.0] and t["a"].tolist() == ["1_0", "3"]


@pytest.mark.parametrize("option", ["--diameters", "--velocities", "--vs-over-vy"])
def test_export_empty_option_is_not_taken_as_absent(work, capsys, option):
    rc, out, err = run(["export", "--out", "e", option, ""], capsys)
    assert_one_line(rc, err, option)
    assert not (work / "e").exists()


@pytest.mark.parametrize("fit", [False, True])
def test_export_diameters_with_one_file_name_are_refused(work, capsys, fit):
    argv = ["export", "--out", "e", "--diameters", "1e-6,1.0000001e-6"] + (["--fit", "data.csv"] if fit else [])
    rc, out, err = run(argv, capsys)
    assert_one_line(rc, err, "d1um", "1e-06", "1.0000001e-06")
    assert not (work / "e").exists()


@pytest.mark.parametrize("option", [["--case", "silicon"], ["--radius", "1e-6"], ["--particle", "silicon"]])
def test_a_pair_option_beside_alumina_is_refused(work, capsys, option):
    rc, out, err = run(["oblique", "--alumina", *option], capsys)
    assert_one_line(rc, err, "--alumina", option[0])
