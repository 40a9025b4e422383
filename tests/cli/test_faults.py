"""Fault corpus of the command line and the writers (issue: nothing half-written, no tracebacks).

Every case asserts the exit status, a single-line message on stderr naming the
option or the file, no traceback, and that the target path holds its old content
or nothing. Most cases run ``main`` in-process (fast); the interrupt cases run
the command in a subprocess and send SIGINT or SIGTERM while it writes.

Permissions: tests may run as root, which ignores file modes, so read-only
directories are exercised through a file where a directory is expected and
through ``/dev/full``; the chmod-based cases are skipped when running as root.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import microimpact as mi
from microimpact import io as mio
from microimpact._validation import check_nonnegative, check_positive, check_velocity
from microimpact.cexport import generate_c_source
from microimpact.cli import main

#: The two signals a run is ended by; SIGINT's case needs it delivered (tests/conftest.py skips it where it is ignored).
SIGNALS = [
    pytest.param(signal.SIGINT, id="SIGINT", marks=pytest.mark.needs_sigint),
    pytest.param(signal.SIGTERM, id="SIGTERM"),
]

ROOT = Path(__file__).resolve().parents[2]
IS_ROOT = hasattr(os, "geteuid") and os.geteuid() == 0
OLD = "old content\n"


# ----------------------------------------------------------------------------- helpers
def run(argv, capsys):
    rc = main([str(a) for a in argv])
    cap = capsys.readouterr()
    return rc, cap.out, cap.err


def assert_one_line(rc, err, *words, code=2):
    assert rc == code, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    assert lines[0].startswith("microimpact"), err
    for w in words:
        assert w.lower() in lines[0].lower(), (w, lines[0])


def no_temp_files(directory: Path):
    return [p.name for p in directory.iterdir() if p.name.startswith(".") and (".tmp" in p.name or ".old" in p.name)]


@pytest.fixture
def work(tmp_path, monkeypatch):
    """A working directory with a file where a directory is expected and an old output."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "afile").write_text("not a directory\n")
    (tmp_path / "adir").mkdir()
    (tmp_path / "old.csv").write_text(OLD)
    (tmp_path / "data.csv").write_text("velocity,restitution\n5,1.0\n20,0.86\n50,0.72\n80,0.64\n")
    return tmp_path


# ----------------------------------------------------------------------------- 1. bad values of the pair options
PAIR_OPTIONS = ["--radius", "--diameter", "--density", "--effective-modulus", "--yield-strength", "--k"]
BAD_NUMBERS = ["-1", "0", "nan", "inf", "-inf", "1e400", "abc", ""]
COMMANDS = {
    "impact": ["impact", "50"],
    "history": ["history", "50", "--out", "h.csv"],
    "export": ["export", "--out", "exp"],
}


@pytest.mark.parametrize("bad", BAD_NUMBERS)
@pytest.mark.parametrize("option", PAIR_OPTIONS + ["--limiting-pressure"])
@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_bad_pair_option_values(work, capsys, command, option, bad):
    if option == "--limiting-pressure" and bad in ("inf", "1e400"):
        pytest.skip("p_y = inf is a valid input: an elastic pair")
    rc, out, err = run(COMMANDS[command] + [option, bad], capsys)
    assert_one_line(rc, err, option.lstrip("-"))
    assert not (work / "h.csv").exists() and not (work / "exp").exists()
    assert no_temp_files(work) == []


# ----------------------------------------------------------------------------- 2. bad values of the swept inputs
SWEPT = [
    "--velocity",
    "--limiting-pressure",
    "--particle-modulus",
    "--surface-modulus",
    "--density",
    "--radius",
    "--particle-poisson",
    "--surface-poisson",
    "--effective-modulus",
]
BAD_SWEEP = ["-1", "nan", "inf", "abc", "1:2", "1:2:0", "1:2:x", "5,5"]


@pytest.mark.parametrize("bad", BAD_SWEEP)
@pytest.mark.parametrize("option", SWEPT)
def test_bad_sweep_values(work, capsys, option, bad):
    if option.endswith("poisson") and bad == "1:2":
        bad = "0.1:0.2"  # still malformed (no count)
    if option in ("--limiting-pressure", "--surface-modulus") and bad == "inf":
        bad = "0"  # p_y = inf (elastic) and E2 = inf (a rigid surface) are valid
    argv = ["sweep", "--out", "s.nc"]
    argv += ["--velocity", "10,20"] if option != "--velocity" else []
    argv += [option, bad]
    rc, out, err = run(argv, capsys)
    name = option.lstrip("-")
    assert_one_line(rc, err)
    assert name in err or name.replace("-", "_") in err, err
    assert not (work / "s.nc").exists() and no_temp_files(work) == []


# ----------------------------------------------------------------------------- 3. bad values of other options
OTHER = [
    (["impact", "-1"], "velocity"),
    (["impact", "nan"], "velocity"),
    (["impact", "inf"], "velocity"),
    (["impact", "1e400"], "velocity"),
    (["impact", "abc"], "velocity"),
    (["impact", "1:2"], "velocity"),
    (["impact", "1:2:0"], "velocity"),
    (["impact", "1:2:-3"], "velocity"),
    (["impact", "1:inf:3"], "velocity"),
    (["impact", "1:2:x"], "velocity"),
    (["impact", ","], "velocity"),
    (["impact", "10,-5"], "velocity"),
    (["impact", "10", "--case", "glass"], "--case"),
    (["impact", "10", "--particle", "kryptonite", "--surface", "silicon", "--radius", "1e-6"], "kryptonite"),
    (["impact", "10", "--particle", "nh4fl"], "--surface"),
    (["impact", "10", "--particle", "nh4fl", "--surface", "silicon"], "radius"),
    (["impact", "10", "--effective-modulus", "1e9"], "--effective-modulus"),
    (["impact", "10", "--radius", "1e-300"], "--radius"),
    (["impact", "10", "--diameter", "1e-300"], "--diameter"),
    (["impact", "10", "--radius", "1e200"], "--radius"),
    (["impact", "10", "--density", "1e-320"], "--density"),
    (["history", "-1"], "velocity"),
    (["history", "0"], "velocity"),
    (["history", "nan"], "velocity"),
    (["history", "inf"], "velocity"),
    (["history", "abc"], "velocity"),
    (["history", "1e-300"], "velocity"),
    (["history", "1e308"], "velocity"),
    (["history", "50", "--n", "1"], "--n"),
    (["history", "50", "--n", "0"], "--n"),
    (["history", "50", "--n", "-5"], "--n"),
    (["history", "50", "--n", "abc"], "--n"),
    (["history", "50", "--n", "1.5"], "--n"),
    (["history", "50", "--n", "1e3"], "--n"),
    (["history", "50", "--n", "100000000000"], "--n"),
    (["history", "50", "--method", "euler"], "--method"),
    (["history", "50", "--plot", "p.bmpx"], "p.bmpx"),
    (["history", "50", "--plot", "noext"], "noext"),
    (["sweep", "--velocity", "1,2", "--out", "s.txt"], "--out"),
    (["sweep", "--velocity", "1,2", "--out", "s.nc", "--chunks", "0"], "--chunks"),
    (["sweep", "--velocity", "1,2", "--out", "s.nc", "--chunks", "-1"], "--chunks"),
    (["sweep", "--velocity", "1,2", "--out", "s.nc", "--chunks", "abc"], "--chunks"),
    (["sweep", "--velocity", "1,2", "--out", "s.nc", "--k", "-1"], "--k"),
    (["sweep", "--velocity", "1,2", "--out", "s.nc", "--k", "nan"], "--k"),
    (["sweep", "--velocity", "1,2", "--out", "s.nc", "--yield-strength", "0"], "--yield-strength"),
    (["sweep", "--velocity", "1,2", "--out", "s.nc", "--case", "glass"], "--case"),
    (["sweep", "--velocity", "1,2", "--out", "s.nc", "--particle", "nh4fl", "--surface", "silicon"], "--radius"),
    (["sweep", "--out", "s.nc"], "--velocity"),
    (["sweep", "--velocity", "1,2"], "--out"),
    (["export", "--out", "exp", "--friction", "-1"], "--friction"),
    (["export", "--out", "exp", "--friction", "nan"], "--friction"),
    (["export", "--out", "exp", "--friction", "inf"], "--friction"),
    (["export", "--out", "exp", "--friction", "abc"], "--friction"),
    (["export", "--out", "exp", "--no-c", "--friction", "-1"], "--friction"),
    (["export", "--out", "exp", "--work-of-adhesion", "-1"], "--work-of-adhesion"),
    (["export", "--out", "exp", "--work-of-adhesion", "inf"], "--work-of-adhesion"),
    (["export", "--out", "exp", "--work-of-adhesion", "x"], "--work-of-adhesion"),
    (["export", "--out", "exp", "--surface-energy", "-0.1"], "--surface-energy"),
    (["export", "--out", "exp", "--surface-energy", "0.1,0.2,0.3"], "--surface-energy"),
    (["export", "--out", "exp", "--diameters", "1e-300"], "--diameters"),
    (["export", "--out", "exp", "--diameters", "-1e-6"], "--diameters"),
    (["export", "--out", "exp", "--diameters", "0"], "--diameters"),
    (["export", "--out", "exp", "--velocities", "-1:5:3"], "--velocities"),
    (["export", "--out", "exp", "--velocities", "nan"], "--velocities"),
    (["export", "--out", "exp", "--vs-over-vy", "-0.5"], "--vs-over-vy"),
    (["paper", "--out", "pap", "--formats", "bmp"], "formats"),
    (["paper", "--out", "pap", "--formats", ""], "formats"),
    (["paper", "--out", "pap", "--data", "silicon"], "NAME=FILE.csv"),
    (["paper", "--out", "pap", "--data", "=x.csv"], "NAME=FILE.csv"),
    (["paper", "--out", "pap", "--data", "silicon=missing.csv"], "missing.csv"),
    (["paper", "--out", "pap", "--data", "silicon=adir"], "adir"),
    (["materials", "kryptonite"], "kryptonite"),
    (["fit", "missing.csv"], "missing.csv"),
    (["fit", "adir"], "adir"),
    (["fit", "data.csv", "--confidence", "2"], "confidence"),
    (["fit", "data.csv", "--confidence", "abc"], "confidence"),
    (["fit", "data.csv", "--plot", "nodir/f.png"], "nodir"),
    (["fit", "data.csv", "--plot", "afile/f.png"], "afile"),
    (["fit", "data.csv", "--fig2", "adir"], "adir"),
    (["fit", "data.csv", "--loss", "l3"], "--loss"),
    (["nosuchcommand"], "nosuchcommand"),
]


@pytest.mark.parametrize("argv, word", OTHER, ids=[" ".join(a[:4]) + f"|{w}" for a, w in OTHER])
def test_bad_option_values(work, capsys, argv, word):
    rc, out, err = run(argv, capsys)
    assert_one_line(rc, err, word)
    for name in ("s.nc", "exp", "pap", "p.bmpx", "noext", "h.csv", "f.png"):
        assert not (work / name).exists(), name
    assert no_temp_files(work) == []


# ----------------------------------------------------------------------------- 4. conflicting or ignored options
CONFLICTS = [
    (["impact", "50", "--case", "mica", "--particle", "nh4fl", "--surface", "silicon", "--radius", "1e-6"], "--case"),
    (["impact", "50", "--case", "mica", "--effective-modulus", "1e9"], "--effective-modulus"),
    (["impact", "50", "--radius", "1e-6", "--diameter", "2e-6"], "--diameter"),
    (["impact", "50", "--limiting-pressure", "1e8", "--yield-strength", "5e7"], "--yield-strength"),
    (["impact", "50", "--limiting-pressure", "1e8", "--k", "2"], "--k"),
    (
        ["impact", "50", "--particle", "nh4fl", "--surface", "silicon", "--radius", "1e-6", "--density", "3000"],
        "--density",
    ),
    (
        [
            "impact",
            "50",
            "--particle",
            "nh4fl",
            "--surface",
            "silicon",
            "--radius",
            "1e-6",
            "--effective-modulus",
            "1e9",
        ],
        "--effective-modulus",
    ),
    (
        ["impact", "50", "--effective-modulus", "1e9", "--radius", "1e-6", "--density", "1e3", "--k", "2"],
        "--yield-strength",
    ),
    (["history", "50", "--hertz"], "--plot"),
    (["history", "50", "--plot", "same.png", "--out", "same.png"], "same"),
    (["history", "50", "--case", "mica", "--particle", "nh4fl", "--surface", "silicon"], "--case"),
    (["sweep", "--velocity", "1,2", "--velocity", "3,4", "--out", "s.nc"], "--velocity"),
    (["sweep", "--velocity", "1,2", "--density", "1", "--density", "2", "--out", "s.nc"], "--density"),
    (["sweep", "--velocity", "5,1,5", "--out", "s.nc"], "more than once"),
    (["sweep", "--velocity", "1:2:3,2", "--out", "s.csv"], "more than once"),
    (
        ["sweep", "--velocity", "1,2", "--out", "s.nc", "--case", "mica", "--particle", "nh4fl", "--surface", "x"],
        "--case",
    ),
    (["sweep", "--velocity", "1,2", "--out", "s.nc", "--limiting-pressure", "1e8", "--k", "2"], "--k"),
    (
        ["sweep", "--velocity", "1,2", "--out", "s.nc", "--effective-modulus", "1e9", "--particle-modulus", "1e9"],
        "effective_modulus",
    ),
    (["export", "--out", "exp", "--work-of-adhesion", "0.1", "--surface-energy", "0.05"], "--surface-energy"),
    (["export", "--out", "exp", "--case", "mica", "--particle", "nh4fl", "--surface", "silicon"], "--case"),
]


@pytest.mark.parametrize("argv, word", CONFLICTS, ids=[" ".join(a) for a, _ in CONFLICTS])
def test_conflicting_options_refused(work, capsys, argv, word):
    rc, out, err = run(argv, capsys)
    assert_one_line(rc, err, word)
    assert not any((work / n).exists() for n in ("s.nc", "s.csv", "exp", "same.png"))


def test_k_with_a_paper_case_is_used_not_ignored(capsys):
    rc, out, _ = run(["impact", "50", "--case", "silicon", "--k", "5", "--json"], capsys)
    doc = json.loads(out)
    Y = mi.materials.PAPER_CASES["silicon"]["yield_strength"]
    assert rc == 0 and doc["pair"]["limiting_pressure"] == pytest.approx(5 * Y, rel=1e-15)
    assert "5 x" in doc["pair"]["label"]


def test_label_names_an_override(capsys):
    rc, out, _ = run(["impact", "50", "--density", "5000"], capsys)
    assert rc == 0 and out.splitlines()[0].endswith("with density 5000 kg/m^3")


# ----------------------------------------------------------------------------- 5. output paths that cannot be written
def _outputs(path):
    """Every writing command with one output at ``path``."""
    return {
        "history --out": ["history", "50", "--n", "5", "--out", path],
        "history --plot": ["history", "50", "--n", "5", "--out", "h.csv", "--plot", path],
        "sweep .nc": ["sweep", "--velocity", "1,2", "--out", path],
        "sweep .csv": ["sweep", "--velocity", "1,2", "--out", path],
        "export --out": ["export", "--out", path, "--velocities", "1,2"],
        "paper --out": ["paper", "--out", path, "--quiet"],
        "fit --plot": ["fit", "data.csv", "--plot", path],
    }


SUFFIX = {
    "history --out": ".csv",
    "history --plot": ".png",
    "sweep .nc": ".nc",
    "sweep .csv": ".csv",
    "export --out": "",
    "paper --out": "",
    "fit --plot": ".png",
}
BAD_PLACES = {
    "missing parent": ("nodir/x{sfx}", "nodir"),
    "file as parent": ("afile/x{sfx}", "afile"),
    "deep missing parent": ("nodir/sub/x{sfx}", "nodir"),
}


@pytest.mark.parametrize("place", sorted(BAD_PLACES))
@pytest.mark.parametrize("what", sorted(SUFFIX))
def test_unwritable_output_paths(work, capsys, what, place):
    pattern, word = BAD_PLACES[place]
    path = pattern.format(sfx=SUFFIX[what])
    rc, out, err = run(_outputs(path)[what], capsys)
    assert_one_line(rc, err, word)
    assert not (work / "h.csv").exists()  # nothing written before the failing check
    assert sorted(p.name for p in work.iterdir()) == ["adir", "afile", "data.csv", "old.csv"]


@pytest.mark.parametrize("what", ["history --out", "history --plot", "sweep .nc", "sweep .csv", "fit --plot"])
def test_directory_where_a_file_is_expected(work, capsys, what):
    (work / f"d{SUFFIX[what]}").mkdir()
    rc, out, err = run(_outputs(f"d{SUFFIX[what]}")[what], capsys)
    assert_one_line(rc, err, f"d{SUFFIX[what]}", "directory")
    assert (work / f"d{SUFFIX[what]}").is_dir() and not any((work / f"d{SUFFIX[what]}").iterdir())


@pytest.mark.parametrize("what", ["export --out", "paper --out"])
def test_file_where_a_directory_is_expected(work, capsys, what):
    rc, out, err = run(_outputs("old.csv")[what], capsys)
    assert_one_line(rc, err, "old.csv")
    assert (work / "old.csv").read_text() == OLD


@pytest.mark.parametrize("what", ["export --out", "paper --out"])
def test_directory_with_foreign_files_is_not_replaced(work, capsys, what):
    (work / "mine").mkdir()
    (work / "mine" / "notes.txt").write_text("precious\n")
    rc, out, err = run(_outputs("mine")[what], capsys)
    assert_one_line(rc, err, "notes.txt")
    assert (work / "mine" / "notes.txt").read_text() == "precious\n"


@pytest.mark.parametrize(
    "argv",
    [
        ["history", "50", "--n", "5", "--out", "/dev/full"],
        ["export", "--out", "/dev/full"],
        ["paper", "--out", "/dev/full", "--quiet"],
    ],
)
def test_dev_full(work, capsys, argv):
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full")
    rc, out, err = run(argv, capsys)
    assert_one_line(rc, err, "/dev/full")


@pytest.mark.parametrize(
    "argv",
    [["history", "50", "--n", "5"], ["impact", "1:100:50"], ["impact", "50", "--json"], ["materials"]],
)
def test_stdout_on_a_full_disk(argv):
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full")
    with open("/dev/full", "w") as full:
        proc = subprocess.run(
            [sys.executable, "-m", "microimpact", *argv], stdout=full, stderr=subprocess.PIPE, text=True, env=_env()
        )
    err = "\n".join(ln for ln in proc.stderr.splitlines() if not ln.startswith("warning:"))
    assert_one_line(proc.returncode, err, "standard output")


@pytest.mark.skipif(IS_ROOT, reason="root ignores file permissions: covered by /dev/full and file-as-directory cases")
@pytest.mark.parametrize("what", sorted(SUFFIX))
def test_read_only_directory(work, capsys, what):
    ro = work / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        rc, out, err = run(_outputs(f"ro/x{SUFFIX[what]}")[what], capsys)
        assert_one_line(rc, err, "ro")
        assert list(ro.iterdir()) == []
    finally:
        ro.chmod(0o700)


# ----------------------------------------------------------------------------- 6. bad input files
BAD_DATA = {
    "binary": b"\x00\xff\xfe\x01velocity",
    "latin-1": "velocity,restitution\n5,1.0\n20,0.86 \xe9\n".encode("latin-1"),
    "empty": b"",
    "header only": b"velocity,restitution\n",
    "no restitution column": b"velocity,foo\n1,2\n3,4\n",
    "text cell": b"velocity,restitution\n5,abc\n20,0.8\n30,0.7\n",
    "negative speed": b"velocity,restitution\n-5,1\n20,0.8\n30,0.7\n",
    "nan": b"velocity,restitution\nnan,1\n20,0.8\n30,0.7\n",
    "negative restitution": b"velocity,restitution\n5,-0.2\n20,0.8\n30,0.7\n",
    "ragged": b"velocity,restitution\n5\n20,0.8,9\n",
}


@pytest.mark.parametrize("kind", sorted(BAD_DATA))
@pytest.mark.parametrize("command", ["fit", "paper"])
def test_bad_data_files(work, capsys, command, kind):
    (work / "bad.csv").write_bytes(BAD_DATA[kind])
    argv = ["fit", "bad.csv"] if command == "fit" else ["paper", "--out", "pap", "--quiet", "--data", "silicon=bad.csv"]
    rc, out, err = run(argv, capsys)
    assert_one_line(rc, err)
    assert "bad.csv" in err or "line" in err, err
    assert not (work / "pap").exists()


# ----------------------------------------------------------------------------- 7. interrupted writes keep the old output
def _env(**extra):
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "src") + os.pathsep + env.get("PYTHONPATH", "")
    env.update(extra)
    return env


def _interrupt(argv, cwd, watch, sig, timeout=60.0):
    """Start the command, wait until a temporary output exists beside the target, send ``sig``."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "microimpact", *argv],
        cwd=cwd,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        env=_env(),
    )
    t0 = time.monotonic()
    try:
        while time.monotonic() - t0 < timeout:
            inside = Path(cwd) / watch  # an existing output folder is staged inside it
            staged = inside.is_dir() and any(p.name.startswith(".microimpact-staging.") for p in inside.iterdir())
            if staged or any(p.name.startswith(f".{watch}.") for p in Path(cwd).iterdir()):
                time.sleep(0.2)  # let it write a little
                break
            if proc.poll() is not None:
                break
            time.sleep(0.01)
        else:
            pytest.fail("the command never started writing")
        if proc.poll() is not None:
            pytest.fail(f"finished before the signal: {proc.stderr.read()}")
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    return proc.returncode, err


SLOW = {
    "history": (["history", "50", "--n", "1000000", "--out", "target.csv"], "target.csv", "file"),
    "sweep csv": (
        ["sweep", "--velocity", "1:120:4000", "--density", "1000:3000:500", "--out", "target.csv"],
        "target.csv",
        "file",
    ),
    "sweep nc": (
        ["sweep", "--velocity", "1:120:4000", "--density", "1000:3000:1000", "--out", "target.nc", "--chunks", "200"],
        "target.nc",
        "file",
    ),
    "paper": (["paper", "--out", "target", "--formats", "png,pdf,svg"], "target", "dir"),
}


@pytest.mark.parametrize("sig", SIGNALS)
@pytest.mark.parametrize("what", sorted(SLOW))
def test_signal_mid_write_keeps_old_output(tmp_path, what, sig):
    argv, target, kind = SLOW[what]
    path = tmp_path / target
    if kind == "file":
        path.write_text(OLD)
    else:  # an earlier run's output (with the manifest that proves it)
        with mio.owned_directory(path, "paper") as tmp:
            (tmp / "fig02.png").write_text(OLD)
    rc, err = _interrupt(argv, tmp_path, target, sig)
    assert rc == 128 + sig, err
    lines = [ln for ln in err.strip().splitlines() if not ln.startswith("sweep:")]
    assert len(lines) == 1 and "interrupted" in lines[0] and "Traceback" not in err, err
    if kind == "file":
        assert path.read_text() == OLD
    else:
        assert sorted(p.name for p in path.iterdir()) == [mio.MANIFEST, "fig02.png"]
        assert (path / "fig02.png").read_text() == OLD
    assert no_temp_files(tmp_path) == []


# ----------------------------------------------------------------------------- 8. the writers themselves
def test_atomic_write_keeps_old_content_on_any_exception(tmp_path):
    target = tmp_path / "t.txt"
    target.write_text(OLD)
    for exc in (ValueError("x"), KeyboardInterrupt(), SystemExit(3), OSError(28, "No space left on device")):
        with pytest.raises(type(exc)):
            with mio.atomic_write(target) as fh:
                fh.write("half")
                raise exc
        assert target.read_text() == OLD and no_temp_files(tmp_path) == []
    with mio.atomic_write(target) as fh:
        fh.write("new")
    assert target.read_text() == "new" and no_temp_files(tmp_path) == []


def test_atomic_write_keeps_permissions(tmp_path):
    target = tmp_path / "t.txt"
    target.write_text(OLD)
    target.chmod(0o640)
    with mio.atomic_write(target) as fh:
        fh.write("new")
    assert (target.stat().st_mode & 0o777) == 0o640


def test_owned_directory_commits_whole_or_not_at_all(tmp_path):
    out = tmp_path / "out"
    with mio.owned_directory(out, "test") as tmp:
        (tmp / "a.txt").write_text("1")
    assert sorted(p.name for p in out.iterdir()) == [mio.MANIFEST, "a.txt"]
    with pytest.raises(KeyboardInterrupt):
        with mio.owned_directory(out, "test") as tmp:
            (tmp / "b.txt").write_text("2")
            raise KeyboardInterrupt
    assert sorted(p.name for p in out.iterdir()) == [mio.MANIFEST, "a.txt"] and no_temp_files(tmp_path) == []
    with mio.owned_directory(out, "test") as tmp:
        (tmp / "b.txt").write_text("2")
    assert sorted(p.name for p in out.iterdir()) == [mio.MANIFEST, "b.txt"] and no_temp_files(tmp_path) == []


def test_json_is_always_valid(capsys):
    rc, out, _ = run(["impact", "0,50", "--json"], capsys)  # V = 0: infinite contact time

    def refuse(token):
        raise AssertionError(f"invalid JSON token {token}")

    doc = json.loads(out, parse_constant=refuse)
    assert rc == 0 and doc["results"]["contact_time"][0] is None and doc["results"]["restitution"][0] == 1.0
    assert mio.json_safe({"a": [np.nan, np.inf, -np.inf, 1.5]}) == {"a": [None, None, None, 1.5]}


@pytest.mark.parametrize("text", ["a\nb", "a\rb", "x\x00", "tab\x0bv"])
def test_csv_comment_and_header_refuse_line_breaks(tmp_path, text):
    with pytest.raises(ValueError):
        mio.write_csv(tmp_path / "t.csv", [("v", "m/s", [1.0])], comments=[text])
    with pytest.raises(ValueError):
        mio.write_csv(tmp_path / "t.csv", [(text, "m/s", [1.0])])
    assert not (tmp_path / "t.csv").exists()


@pytest.mark.parametrize("name", ["a,b", 'a"b', "a[b]", "a]"])
def test_csv_header_refuses_delimiters(tmp_path, name):
    with pytest.raises(ValueError, match="column name"):
        mio.write_csv(tmp_path / "t.csv", [(name, "1", [1.0])])


@pytest.mark.parametrize(
    "label",
    ["x */ int injected = 1; /*", "a\n#include <stdio.h>\nint injected;", "*/*/*/ int injected; /*", "\u2028*/"],
)
def test_label_cannot_inject_c(tmp_path, label):
    pair = mi.ContactPair.paper_case().replace(label=label)
    src = generate_c_source(pair)
    clean = generate_c_source(mi.ContactPair.paper_case().replace(label="x"))
    assert src.count("*/") == clean.count("*/") and src.count("/*") == clean.count("/*")
    assert len(src.splitlines()) == len(clean.splitlines())
    c = tmp_path / "w.c"
    c.write_text(src)
    if subprocess.run(["which", "cc"], capture_output=True).returncode == 0:
        subprocess.run(["cc", "-std=c99", "-c", str(c), "-o", str(tmp_path / "w.o")], check=True)
        syms = subprocess.run(["nm", str(tmp_path / "w.o")], capture_output=True, text=True).stdout
        assert "injected" not in syms


def test_label_in_csv_comment_is_one_line(tmp_path):
    from microimpact.cexport import write_tables

    pair = mi.ContactPair.paper_case().replace(label="evil\n1,2,3\n# x")
    (path,) = [p for p in write_tables(tmp_path, pair, velocities=[1.0, 2.0]) if "_d" in p.name]
    rows = [ln for ln in path.read_text().splitlines() if not ln.startswith("#")]
    assert len(rows) == 3  # header and the two speeds only


# ----------------------------------------------------------------------------- 9. Python API inputs
API_BAD = [
    (None, "got None"),
    (True, "boolean"),
    (np.bool_(False), "boolean"),
    (1e-6 + 0j, "complex"),
    (np.array([1e-6 + 1e-9j]), "complex"),
    (np.ma.masked_array([1e-6, 2e-6], mask=[False, True]), "masked"),
    ("1e-6", "text"),
    (b"1e-6", "text"),
    ([1e-6, None], "None"),
    ([[1e-6], [1e-6, 2e-6]], "radius"),
    ([True, False], "boolean"),
    (np.datetime64("2020-01-01"), "date"),
    ({"r": 1}, "radius"),
]


@pytest.mark.parametrize("value, word", API_BAD, ids=[repr(v)[:30] for v, _ in API_BAD])
def test_api_refuses_non_numbers(value, word):
    for check in (check_positive, check_nonnegative, check_velocity):
        with pytest.raises(ValueError, match="radius") as info:
            check("radius", value)
        assert word.lower() in str(info.value).lower()


@pytest.mark.parametrize("value, word", API_BAD[:8], ids=[repr(v)[:30] for v, _ in API_BAD[:8]])
def test_sphere_on_flat_refuses_non_numbers(value, word):
    with pytest.raises(ValueError, match="radius"):
        mi.ContactPair.sphere_on_flat(value, 1350.0, 1.2e9, 1.6e8)


@pytest.mark.parametrize("value", [[1e-6, 2e-6], np.ones((2, 2)), np.array([])])
def test_scalar_checks_refuse_arrays(value):
    with pytest.raises(ValueError, match="radius must be a single number"):
        check_positive("radius", value, scalar=True)


def test_scalar_check_returns_float():
    assert check_positive("radius", np.array([2e-6]), scalar=True) == 2e-6
    assert type(check_velocity("velocity", 3, scalar=True)) is float
    assert check_positive("radius", np.ma.masked_array([1.0, 2.0])).tolist() == [1.0, 2.0]  # nothing masked


@pytest.mark.parametrize("V", [np.inf, [1.0, np.inf], np.nan, -1.0])
def test_velocity_refuses_inf_and_nan(V):
    with pytest.raises(ValueError, match=r"velocity must be .*got (inf|nan|-1\.0)"):
        check_velocity("velocity", V)


# ----------------------------------------------------------------------------- 10. memory
@pytest.mark.parametrize(
    "argv, word",
    [
        (["impact", "1:120:1000000", "--json"], "velocity"),
        (["history", "50", "--n", "100000000"], "--n"),
        (["sweep", "--velocity", "1:2:1000", "--density", "1:2:1000", "--out", "s.nc", "--chunks", "1000"], "block"),
    ],
)
def test_memory_budget_refuses_up_front(work, capsys, monkeypatch, argv, word):
    monkeypatch.setenv(mio.MEMORY_ENV, "50MB")
    rc, out, err = run(argv, capsys)
    assert_one_line(rc, err, word, "memory", "50 MB")
    assert out == "" and not (work / "s.nc").exists()


def test_eager_sweep_over_budget_refused(monkeypatch):
    from microimpact.sweep import sweep

    monkeypatch.setenv(mio.MEMORY_ENV, "1MB")
    with pytest.raises(ValueError, match="without chunks"):
        sweep(np.linspace(1, 100, 3000), density=np.linspace(1000, 2000, 30))


@pytest.mark.parametrize("bad", ["abc", "-1", "0", "nan"])
def test_memory_budget_env_checked(capsys, monkeypatch, bad):
    monkeypatch.setenv(mio.MEMORY_ENV, bad)
    rc, out, err = run(["impact", "1:2:5"], capsys)
    assert_one_line(rc, err, mio.MEMORY_ENV)


# ----------------------------------------------------------------------------- 11. random argument lists
WORDS = [
    "impact", "history", "sweep", "export", "fit", "materials", "50", "-1", "nan", "inf", "1:10:3", "1,2", "abc",
    "--case", "silicon", "mica", "--k", "--radius", "--diameter", "--density", "--effective-modulus",
    "--limiting-pressure", "--yield-strength", "--particle", "--surface", "nh4fl", "--json", "--n", "5", "--out",
    "o.csv", "o.nc", "nodir/x.csv", "afile", "--plot", "p.png", "--hertz", "--method", "ode", "--velocity",
    "--chunks", "--friction", "--no-c", "--diameters", "1e-6", "--free", "k", "data.csv", "--quiet", "",
    "--help", "-x", "1e-300", "1e308", "0",
]  # fmt: skip


@settings(
    max_examples=150,
    derandomize=True,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture],
)
@given(st.lists(st.sampled_from(WORDS), min_size=0, max_size=8))
def test_random_arguments_never_traceback(work, argv):
    import contextlib
    import io

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(argv)
    text = err.getvalue()
    assert "Traceback" not in text
    assert rc in (0, 2), (argv, text)
    if rc == 2:
        lines = [ln for ln in text.strip().splitlines() if not ln.startswith("warning:")]
        assert lines or not argv, argv
        if not any(a in ("--help",) for a in argv) and argv:
            assert lines[-1].startswith(("microimpact", "usage:")), (argv, text)


def test_project_readers_read_the_one_layout(tmp_path):
    from microimpact.io import load_restitution_csv, read_table

    path = mio.write_csv(
        tmp_path / "m.csv",
        [("velocity", "m/s", [5.0, 20.0, 50.0]), ("restitution", "1", [1.0, 0.86, 0.72])],
        comments=["measured, with a comment line after the header"],
    )
    lines = path.read_text().splitlines()
    assert lines[0] == "velocity [m/s],restitution [1]" and lines[1].startswith("# ")
    V, e, sigma = load_restitution_csv(path)
    assert V.tolist() == [5.0, 20.0, 50.0] and e.tolist() == [1.0, 0.86, 0.72] and sigma is None
    assert read_table(path)["restitution"].tolist() == [1.0, 0.86, 0.72]
    data = np.genfromtxt(path, delimiter=",", names=True)
    assert data[data.dtype.names[0]].tolist() == [5.0, 20.0, 50.0]  # numpy names it velocity_ms


def test_atomic_directory_is_deprecated_and_owns_by_manifest(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "a.txt").write_text("a file the old name pattern '*.txt' would have claimed")
    with pytest.warns(DeprecationWarning, match="owned_directory"):
        with pytest.raises(FileExistsError, match="a.txt"):
            with mio.atomic_directory(out, owned=("*.txt",)):
                pass
    assert (out / "a.txt").read_text().startswith("a file")
