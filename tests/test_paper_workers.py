"""Figures of ``paper`` drawn in other processes (``reproduce(workers=...)``): the same bytes as drawn
in the calling process, with its rcParams; a worker that fails or dies costs nothing but time (its
figure is drawn here); an interrupt ends the workers with the command; a bad ``workers`` writes nothing."""

from __future__ import annotations

import multiprocessing
import os
import signal
import subprocess
import sys
import threading
import time
import uuid
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")

import microimpact.paper as paper  # noqa: E402
from microimpact.paper import _draw, _driver, _worker  # noqa: E402
from microimpact.paper._setup import FIGURES  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
STEMS = [f[0] for f in FIGURES]
FORMATS = ["png", "pdf"]


def _env():
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "src") + os.pathsep + env.get("PYTHONPATH", "")
    for key in [k for k in env if k.startswith("COV_CORE_") or k == "COVERAGE_PROCESS_START"]:
        env.pop(key)
    return env


def _tables(stems):
    return [(stem, _driver._TABLES[stem]({})) for stem in stems]


def test_a_worker_draws_the_same_bytes_as_this_process_with_its_rcparams():
    import matplotlib as mpl

    tables = _tables(["fig06", "fig09"])
    here = {stem: _draw.draw_figure(stem, table, FORMATS) for stem, table in tables}
    with mpl.rc_context({"lines.linewidth": 2.5, "font.family": "serif"}):
        rc = _driver._rc_snapshot()
        here_rc = {stem: _draw.draw_figure(stem, table, FORMATS) for stem, table in tables}
    before = {p.pid for p in multiprocessing.active_children()}
    pool = _worker.Pool(1)
    try:
        futures = [pool.executor.submit(_worker.draw, stem, table, FORMATS, rc) for stem, table in tables]
        answers = [f.result(timeout=300) for f in futures]
        pids = {p.pid for p in multiprocessing.active_children()} - before
    finally:
        pool.stop()
    for (stem, _table), (images, said, seconds) in zip(tables, answers):
        assert said == [] and seconds > 0
        assert images == here_rc[stem], stem  # png and pdf, byte for byte
        assert images["png"] != here[stem]["png"]  # the rcParams did reach the worker
    assert pids and pids.isdisjoint(p.pid for p in multiprocessing.active_children())  # shut down: it has ended


def test_stop_ends_a_busy_worker_at_once():
    """A worker in the middle of a long job is ended by ``stop`` at once, not when its job is done."""
    pool = _worker.Pool(1)
    try:
        assert pool.ready[0].exception(timeout=300) is None
        busy = pool.executor.submit(time.sleep, 120)
        t0 = time.monotonic()
        while not busy.running() and time.monotonic() - t0 < 60:
            time.sleep(0.01)
        time.sleep(0.2)
    finally:
        t0 = time.monotonic()
        pool.stop()
        elapsed = time.monotonic() - t0
    assert elapsed < 30 and busy.done() and busy.exception() is not None  # ended, not finished


def _files(out):
    """Every file's bytes; the report without its one run-dependent number (the elapsed time), the
    manifest as the names it lists (it holds the report's hash)."""
    import json
    import re

    files = {}
    for p in sorted(out.iterdir()):
        data = p.read_bytes()
        if p.name in ("report.md", "report.html"):
            data = re.sub(rb"in [0-9.]+ s\.", b"in - s.", data)
        if p.name == ".microimpact-manifest.json":
            data = sorted(json.loads(data)["files"])
        files[p.name] = data
    return files


def test_two_workers_write_the_same_files_as_one(tmp_path):
    one = paper.reproduce(tmp_path / "one", workers=1, progress=False)
    lines = []
    two = paper.reproduce(tmp_path / "two", workers=2, progress=lines.append)
    a, b = _files(tmp_path / "one"), _files(tmp_path / "two")
    assert sorted(a) == sorted(b) and len(a) == 2 * len(STEMS) + len(STEMS) + 4  # png, pdf, csv, 4 more
    assert [name for name in a if a[name] != b[name]] == []
    assert one.figures.keys() == two.figures.keys() and list(two.figures) == STEMS
    # progress in the figures' order, whoever drew them
    assert [ln.split()[1] for ln in lines[: len(STEMS)]] == STEMS and lines[-1].startswith("[report]")


@pytest.fixture(scope="module")
def png_only(tmp_path_factory):
    """The files of ``paper --formats png`` drawn in one process."""
    out = tmp_path_factory.mktemp("ref") / "ref"
    paper.reproduce(out, workers=1, progress=False, formats=["png"])
    return _files(out)


# What a worker runs instead of its start-up or its figures: a module the spawned worker imports by
# name (the caller's sys.path travels with it). One process runs every job of the pool, in order.
_FAULTS = """
import os

calls = []


def dies(*args):
    os._exit(3)


def answers_then_errs(stem, table, formats, rc):
    calls.append(stem)
    if len(calls) == 1:
        return {"png": b"x"}, [], 0.0
    raise RuntimeError("no")
"""


@pytest.mark.parametrize("fault", ["dies-starting", "dies-holding-a-job", "answers-then-errs"])
def test_a_failing_worker_costs_nothing_but_time(tmp_path, monkeypatch, fault, png_only):
    """A worker that dies as it starts, dies holding a figure or answers an error: every figure is
    still written, the same bytes as with one process. (The third answers its first job: that figure
    is its answer, b'x' -- proof that the worker's answers are used; the test then checks the rest.)"""
    name = f"paper_worker_faults_{uuid.uuid4().hex}"
    (tmp_path / f"{name}.py").write_text(_FAULTS)
    monkeypatch.syspath_prepend(str(tmp_path))
    faults = __import__(name)
    if fault == "dies-starting":
        monkeypatch.setattr(_worker, "prepare", faults.dies)
    else:
        monkeypatch.setattr(_worker, "draw", faults.dies if fault == "dies-holding-a-job" else faults.answers_then_errs)
    # the worker must get its jobs: this process waits for the worker's feeder to end before drawing
    gate = threading.Event()
    orig_run, orig_draw = _worker.Feeder._run, _draw.draw_figure

    def run(self):
        try:
            orig_run(self)
        finally:
            gate.set()

    def draw(*args, **kws):
        assert gate.wait(120)
        return orig_draw(*args, **kws)

    monkeypatch.setattr(_worker.Feeder, "_run", run)
    monkeypatch.setattr(_draw, "draw_figure", draw)
    paper.reproduce(tmp_path / "out", workers=2, progress=False, formats=["png"])
    monkeypatch.undo()
    a, b = _files(tmp_path / "out"), png_only
    assert sorted(a) == sorted(b)
    differ = [name for name in a if a[name] != b[name]]
    if fault == "answers-then-errs":
        # the last figure was the worker's answer; the report embeds it too
        assert a["fig10.png"] == b"x" and sorted(differ) == ["fig10.png", "report.html"]
    else:
        assert differ == []


@pytest.mark.parametrize("workers", [0, -1, 1.5, True, "2"])
def test_bad_workers_fail_before_writing_anything(tmp_path, workers):
    with pytest.raises(ValueError, match="workers"):
        paper.reproduce(tmp_path / "out", workers=workers, progress=False)
    assert not (tmp_path / "out").exists()


def _marked(mark):
    """PIDs of live processes whose environment holds ``mark`` (the command and what it started)."""
    pids = []
    for d in Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        try:
            if mark.encode() in (d / "environ").read_bytes():
                state = (d / "stat").read_text().rsplit(")", 1)[1].split()[0]
                if state != "Z":
                    pids.append(int(d.name))
        except OSError:
            continue
    return pids


def _started_worker(mark) -> bool:
    """Whether a pool worker of the command marked ``mark`` is running and past its start-up: a spawned
    process (``spawn_main`` in its command line) that ignores SIGINT (the pool's initializer has run)."""
    for pid in _marked(mark):
        try:
            cmdline = Path(f"/proc/{pid}/cmdline").read_bytes()
            status = Path(f"/proc/{pid}/status").read_text()
        except OSError:
            continue
        ignored = int(next(ln.split()[1] for ln in status.splitlines() if ln.startswith("SigIgn:")), 16)
        if b"spawn_main" in cmdline and ignored & (1 << (signal.SIGINT - 1)):
            return True
    return False


@pytest.mark.skipif(not Path("/proc/self/environ").exists(), reason="needs /proc")
@pytest.mark.parametrize("group", [False, True], ids=["to-the-command", "to-the-group"])
@pytest.mark.parametrize(
    "sig",
    [
        pytest.param(signal.SIGINT, id="SIGINT", marks=pytest.mark.needs_sigint),
        pytest.param(signal.SIGTERM, id="SIGTERM"),
    ],
)
def test_an_interrupt_ends_the_worker_with_the_command(tmp_path, sig, group):
    """SIGINT or SIGTERM to the command (a process manager) or to its whole process group (a Ctrl-C
    at a terminal): exit 128 + signal, one line, nothing written, and no worker left running."""
    mark = f"MICROIMPACT_TEST_MARK={uuid.uuid4().hex}"
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "src") + os.pathsep + env.get("PYTHONPATH", "")
    env[mark.split("=")[0]] = mark.split("=")[1]
    for key in [k for k in env if k.startswith("COV_CORE_") or k == "COVERAGE_PROCESS_START"]:
        env.pop(key)
    proc = subprocess.Popen(
        [sys.executable, "-m", "microimpact", "paper", "--out", "out", "--quiet", "--workers", "2"],
        cwd=tmp_path,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        t0 = time.monotonic()
        while not _started_worker(mark) and proc.poll() is None and time.monotonic() - t0 < 60:
            time.sleep(0.02)
        time.sleep(0.3)  # the worker importing or drawing, the command drawing
        if proc.poll() is not None:
            pytest.skip("finished before the signal (a very fast machine)")
        if group:
            os.killpg(proc.pid, sig)
        else:
            proc.send_signal(sig)
        _, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 128 + sig, err
    assert len(err.strip().splitlines()) == 1 and "interrupted" in err and "Traceback" not in err, err
    t0 = time.monotonic()
    while _marked(mark) and time.monotonic() - t0 < 5:
        time.sleep(0.05)
    assert _marked(mark) == []
    assert list(tmp_path.iterdir()) == []  # no output folder, no staging folder


@pytest.mark.parametrize(
    ("cores", "load", "frozen", "expected"),
    [
        (1, 0.0, False, 1),
        (2, 0.5, False, 2),
        (2, 1.0, False, 2),
        (2, 1.5, False, 1),
        (8, 6.5, False, 2),
        (4, 0.0, True, 1),
    ],
)
def test_default_workers_need_an_idle_core(monkeypatch, cores, load, frozen, expected):
    """By default a second process only where a whole core of those this process may use is idle
    (on a busy machine a new interpreter's imports would only add work), and only where
    sys.executable is a Python."""
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(cores)), raising=False)
    monkeypatch.setattr(os, "getloadavg", lambda: (load, load, load), raising=False)
    if frozen:
        monkeypatch.setattr(sys, "frozen", True, raising=False)
    assert _driver._processes(None) == expected
    assert _driver._processes(3) == 3 and _driver._processes(50) == len(STEMS)


_CHECK = "print(_worker.can_start(), _driver._processes(2))"
_GUARDED = f'''"""A script that defines and imports, and works only under its guard."""
import sys

from microimpact.paper import _driver, _worker

LIMIT = 3


def main():
    {_CHECK}


if __name__ == "__main__":
    main()
'''


@pytest.mark.parametrize(
    "how, expected",
    [
        ("guarded script", "True"),
        ("unguarded script", "False"),
        ("script calling at import", "False"),
        ("-c", "True"),
        ("-m package", "True"),
    ],
)
def test_a_worker_starts_only_where_it_runs_none_of_the_callers_code(tmp_path, how, expected):
    """A spawned worker runs the caller's main script again as it starts: it is started only where that
    script's top level defines and imports (behind an ``if __name__ == "__main__":`` guard), or where
    there is no script to run again (``python -c``, ``python -m microimpact``); elsewhere the figures
    are drawn in one process (``_processes`` is 1 whatever ``workers`` asks)."""
    script = tmp_path / "script.py"
    imports = "from microimpact.paper import _driver, _worker\n"
    if how == "guarded script":
        script.write_text(_GUARDED)
    elif how == "unguarded script":
        script.write_text(imports + _CHECK + "\n")
    elif how == "script calling at import":
        script.write_text("import sys\nLIMIT = len(sys.argv)\n" + imports + "if __name__ == '__main__':\n    " + _CHECK)
    argv = [str(script)]
    if how == "-c":
        argv = ["-c", imports + _CHECK]
    elif how == "-m package":
        (tmp_path / "pkg").mkdir()
        (tmp_path / "pkg" / "__init__.py").write_text("")
        (tmp_path / "pkg" / "__main__.py").write_text(imports + _CHECK + "\n")
        argv = ["-m", "pkg"]
    proc = subprocess.run(
        [sys.executable, *argv], capture_output=True, text=True, env=_env(), cwd=tmp_path, timeout=300
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stdout.split() == [expected, "2" if expected == "True" else "1"]
