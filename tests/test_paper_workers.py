"""Figures of ``paper`` drawn in a second process (``reproduce(workers=...)``): the same bytes as drawn
in the calling process, with its rcParams; a worker that fails or dies costs nothing but time (its
figure is drawn here); an interrupt ends the worker with the command; a bad ``workers`` writes nothing."""

from __future__ import annotations

import collections
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
from microimpact.paper import _driver, _worker  # noqa: E402
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


def _feed(helper, tables, rc, formats=FORMATS):
    """Every job of ``tables`` through ``helper``; returns ``{index: answer}`` and the failed indices."""
    queue = collections.deque(range(len(tables)))
    answers = {}
    helper.feed(queue, threading.Lock(), tables, rc, formats, answers.__setitem__)
    while queue or helper.holding is not None:  # the helper takes every job (none is drawn here)
        assert helper.thread.is_alive()
        time.sleep(0.02)
    helper.finish()
    return answers, helper.failed


@pytest.fixture(params=["forked", "new-interpreter"])
def mode(request, monkeypatch):
    """Each test of a worker runs with a worker forked from this process (where it can be) and with a
    new interpreter."""
    if request.param == "forked":
        if not _worker.can_fork():
            pytest.skip("no fork here (not Linux, or another thread runs)")
    else:
        monkeypatch.setattr(_worker, "can_fork", lambda: False)
    return request.param


def test_a_worker_draws_the_same_bytes_as_this_process_with_its_rcparams(mode):
    import matplotlib as mpl

    tables = _tables(["fig06", "fig09"])
    here = {stem: _driver.draw_figure(stem, table, FORMATS) for stem, table in tables}
    with mpl.rc_context({"lines.linewidth": 2.5, "font.family": "serif"}):
        rc = _driver._rc_snapshot()
        here_rc = {stem: _driver.draw_figure(stem, table, FORMATS) for stem, table in tables}
    h = _worker.Helper()
    try:
        h.start()
        answers, failed = _feed(h, tables, rc)
    finally:
        h.close()
    assert failed == [] and sorted(answers) == [0, 1]
    for i, (stem, _table) in enumerate(tables):
        status, images, said, seconds = answers[i]
        assert status == "ok" and said == [] and seconds > 0
        assert images == here_rc[stem], stem  # png and pdf, byte for byte
        assert images["png"] != here[stem]["png"]  # the rcParams did reach the worker
    assert h.proc.poll() is not None  # closed: the process has ended
    assert isinstance(h.proc, subprocess.Popen) == (mode == "new-interpreter")


_NEVER_RETURNS = """
import collections, os, threading
from microimpact.paper import _driver, _worker

assert _worker.can_fork()
parent = os.getpid()


def serve(inp, out):
    raise SystemExit(0)


_worker._serve = serve
h = _worker.Helper()
h.start()
if os.getpid() != parent:  # the bug the test is for: the worker came back here
    os._exit(99)
queue, answers = collections.deque([0]), {}
tables = [("fig06", _driver._TABLES["fig06"]({}))]
h.feed(queue, threading.Lock(), tables, _driver._rc_snapshot(), ["png"], answers.__setitem__)
h.thread.join(30)
print(type(h.proc).__name__, h.thread.is_alive(), answers, list(queue) + h.failed, h.proc.wait(timeout=30))
h.close()
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="workers are forked on Linux")
def test_a_forked_worker_never_returns_into_the_callers_code():
    """Whatever ends a forked worker (here its loop raising SystemExit, as a ``sys.exit`` would) ends it
    with ``os._exit``: it never unwinds into the code that forked it (its ``finally`` blocks would
    remove the caller's staging folder). Were it to return, it would leave through ``os._exit(99)``.
    (In a new interpreter: one that runs no other thread, as the command.)"""
    proc = subprocess.run(
        [sys.executable, "-c", _NEVER_RETURNS], capture_output=True, text=True, env=_env(), timeout=300
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    # the worker ended with status 1, holding no answer; the caller draws the figure
    assert proc.stdout.split() == ["_Forked", "False", "{}", "[0]", "1"]


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


def test_two_workers_write_the_same_files_as_one(tmp_path, mode):
    one = paper.reproduce(tmp_path / "one", workers=1, progress=False)
    lines = []
    two = paper.reproduce(tmp_path / "two", workers=2, progress=lines.append)
    a, b = _files(tmp_path / "one"), _files(tmp_path / "two")
    assert sorted(a) == sorted(b) and len(a) == 2 * len(STEMS) + len(STEMS) + 4  # png, pdf, csv, 4 more
    assert [name for name in a if a[name] != b[name]] == []
    assert one.figures.keys() == two.figures.keys() and list(two.figures) == STEMS
    # progress in the figures' order, whoever drew them
    assert [ln.split()[1] for ln in lines[: len(STEMS)]] == STEMS and lines[-1].startswith("[report]")


_FORKED_FILES = """
import sys
from microimpact import paper
from microimpact.paper import _worker

assert _worker.can_fork()
forks = []
fork = _worker._fork
_worker._fork = lambda: forks.append(1) or fork()
paper.reproduce(sys.argv[1], workers=1, progress=False)  # this process's fonts are open when it forks
paper.reproduce(sys.argv[2], workers=2, progress=False)
print(len(forks))
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="workers are forked on Linux")
def test_a_forked_worker_writes_the_same_files_as_one_process(tmp_path):
    """In a process that runs no other thread (as the command; not this test process), the second
    process is forked, after this one has drawn figures and opened its fonts: the same files."""
    argv = [sys.executable, "-c", _FORKED_FILES, str(tmp_path / "one"), str(tmp_path / "two")]
    proc = subprocess.run(argv, capture_output=True, text=True, env=_env(), timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stdout.split() == ["1"]  # one worker, forked
    a, b = _files(tmp_path / "one"), _files(tmp_path / "two")
    assert sorted(a) == sorted(b) and len(a) == 3 * len(STEMS) + 4
    assert [name for name in a if a[name] != b[name]] == []


@pytest.fixture(scope="module")
def png_only(tmp_path_factory):
    """The files of ``paper --formats png`` drawn in one process."""
    out = tmp_path_factory.mktemp("ref") / "ref"
    paper.reproduce(out, workers=1, progress=False, formats=["png"])
    return _files(out)


_DIES = """
import pickle, sys
out = sys.stdout.buffer
pickle.dump("ready", out); out.flush()
pickle.load(sys.stdin.buffer)             # the configuration
{after}
"""


@pytest.mark.parametrize(
    "after",
    [
        "",  # ends before its first job
        "pickle.load(sys.stdin.buffer)",  # takes a job and dies with it
        "pickle.load(sys.stdin.buffer); pickle.dump(('ok', {'png': b'x'}, [], 0.0), out); out.flush(); "
        "pickle.load(sys.stdin.buffer); pickle.dump(('error', 'no', [], 0.0), out); out.flush()",
    ],
    ids=["exits", "dies-holding-a-job", "answers-then-errs"],
)
def test_a_failing_worker_costs_nothing_but_time(tmp_path, monkeypatch, after, png_only):
    """A helper process that ends, dies holding a figure or answers an error: every figure is still
    written, the same bytes as with one process. (The third answers its first job: that figure is
    its answer, b'x' -- proof that the helper's answers are used; the test then checks the rest.)"""
    script = _DIES.format(after=after)

    def start(self):
        self.proc = subprocess.Popen(
            [sys.executable, "-c", script], stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL
        )

    monkeypatch.setattr(_worker.Helper, "start", start)
    # the helper must get its jobs: this process waits for its first answer (or its end) before drawing
    orig = _driver.draw_figure
    gate = threading.Event()
    orig_run = _worker.Helper._run

    def run(self, queue, lock, tables, rc, formats, done):
        def done_and_open(i, answer):
            done(i, answer)
            gate.set()

        try:
            orig_run(self, queue, lock, tables, rc, formats, done_and_open)
        finally:
            gate.set()

    def draw(*args, **kws):
        gate.wait(60)
        return orig(*args, **kws)

    monkeypatch.setattr(_worker.Helper, "_run", run)
    monkeypatch.setattr(_driver, "draw_figure", draw)
    paper.reproduce(tmp_path / "out", workers=2, progress=False, formats=["png"])
    monkeypatch.undo()
    a, b = _files(tmp_path / "out"), png_only
    assert sorted(a) == sorted(b)
    differ = [name for name in a if a[name] != b[name]]
    if after.startswith("pickle.load(sys.stdin.buffer); pickle.dump"):
        # the last figure was the helper's answer; the report embeds it too
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


@pytest.mark.skipif(not Path("/proc/self/environ").exists(), reason="needs /proc")
@pytest.mark.parametrize("group", [False, True], ids=["to-the-command", "to-the-group"])
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_an_interrupt_ends_the_worker_with_the_command(tmp_path, sig, group):
    # (the command runs no other thread: on Linux its worker is forked from it)
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
        while len(_marked(mark)) < 2 and proc.poll() is None and time.monotonic() - t0 < 60:
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
    ("cores", "load", "frozen", "fork", "expected"),
    [
        (1, 0.0, False, False, 1),
        (2, 0.5, False, False, 2),
        (2, 1.0, False, False, 2),
        (2, 1.5, False, False, 1),
        (8, 6.5, False, False, 2),
        (4, 0.0, True, False, 1),
        (1, 0.0, False, True, 1),
        (2, 1.5, False, True, 2),
        (2, 1.99, False, True, 2),
        (2, 2.0, False, True, 1),
        (2, 3.5, False, True, 1),
        (4, 0.0, True, True, 2),
    ],
)
def test_default_workers_need_an_idle_core(monkeypatch, cores, load, frozen, fork, expected):
    """By default a second process only where one of the cores this process may use is idle: a whole
    core for a new interpreter (on a busy machine its imports would only add work; and only where
    sys.executable is a Python), part of one for a worker forked from this process (it shares the
    imports)."""
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(cores)), raising=False)
    monkeypatch.setattr(os, "getloadavg", lambda: (load, load, load), raising=False)
    monkeypatch.setattr(_worker, "can_fork", lambda: fork)
    if frozen:
        monkeypatch.setattr(sys, "frozen", True, raising=False)
    assert _driver._processes(None) == expected
    assert _driver._processes(3) == 3 and _driver._processes(50) == len(STEMS)


_SUBSET = """
import io, sys
from microimpact.paper._driver import defer_font_subsetting
deferred = defer_font_subsetting() if sys.argv[1] == "defer" else False
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.backends.backend_pdf
loaded_before = type(sys.modules["fontTools.subset"]) is type(sys)  # a lazy module's type is not yet a module's
fig = plt.figure(figsize=(2, 1))
fig.text(0.1, 0.5, "Type 42: $\\\\alpha_p$ 1.2 GPa")
out = sys.stdout.buffer
with plt.rc_context({"pdf.fonttype": 42, "ps.fonttype": 42}):
    for fmt in ("pdf", "eps"):
        buf = io.BytesIO()
        fig.savefig(buf, format=fmt, metadata={"CreationDate": None} if fmt == "pdf" else None)
        out.write(buf.getvalue() + b"\\n--8<--\\n")
out.write(repr((deferred, loaded_before, type(sys.modules["fontTools.subset"]) is type(sys))).encode())
"""


def test_font_subsetting_deferred_embeds_the_same_type42_fonts():
    """``paper`` defers ``fontTools.subset`` to its first use: a PDF and an EPS embedding a subset of a
    TrueType font (Type 42) are the same bytes as with the module imported as matplotlib imports it,
    and the module is loaded only when the first font is subset."""
    env = dict(os.environ, SOURCE_DATE_EPOCH="0")
    env["PYTHONPATH"] = str(ROOT / "src") + os.pathsep + env.get("PYTHONPATH", "")
    runs = {}
    for how in ("defer", "eager"):
        proc = subprocess.run([sys.executable, "-c", _SUBSET, how], capture_output=True, env=env, timeout=300)
        assert proc.returncode == 0, proc.stderr.decode()[-2000:]
        *files, flags = proc.stdout.split(b"\n--8<--\n")
        runs[how] = (files, flags.decode())
    assert runs["defer"][1] == "(True, False, True)" and runs["eager"][1] == "(False, True, True)"
    pdf, eps = runs["defer"][0]
    assert b"/FontFile2" in pdf and b"/CIDFontType2" in pdf  # a TrueType subset, embedded
    assert runs["defer"][0] == runs["eager"][0]


def test_no_fork_once_numbas_threading_layer_has_started():
    """numba's threads are not Python's (``threading.active_count`` does not see them) and its GNU
    OpenMP layer is not fork-safe: once a parallel loop has run, workers start as new interpreters."""
    pytest.importorskip("numba")
    code = """
import sys
import numpy as np
from microimpact import engine
from microimpact.core.models import thornton_ning_2016 as seed
from microimpact.paper import _worker
before = _worker.can_fork()
V = np.linspace(1.0, 100.0, engine.PARALLEL_MIN)  # the multi-threaded loop
engine.evaluate(seed.restitution_at, V, 0.37, backend="numba")
print(before == sys.platform.startswith("linux"), _worker.can_fork())
"""
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout.split()
    assert out == ["True", "False"]
