"""Fault corpus, part 5 (issue 24): an interrupt always ends the run -- the soak, at CI size.

The harness is ``benchmarks/interrupt_soak.py`` (its 1,000-run version is a benchmark): each of
the writing commands (NetCDF and CSV sweeps, a history CSV, a fit with its figure, an export
folder, the paper, an impact table on stdout) runs in a fresh folder holding an earlier output,
and gets SIGINT or SIGTERM at a random moment; every run must end within 5 s of the signal with
exit 130/143 and one line, leave the earlier output byte for byte and no temporary file. On the
code before, a SIGINT was once lost (the sweep ran on, exited 0 and replaced the output), a
NetCDF sweep deadlocked in xarray's file lock, and a signal in the first 0.15 s gave a traceback
or a bare -15 (``test_a_signal_at_the_first_moment``).
"""

from __future__ import annotations

import importlib.util
import os
import signal
import subprocess
import sys
import time

import pytest

from .test_faults import ROOT, SIGNALS, _env

_spec = importlib.util.spec_from_file_location("interrupt_soak", ROOT / "benchmarks" / "interrupt_soak.py")
soak = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(soak)

# 10 per command; the benchmark runs 1,000. At 15 per command the soak took 340 s of a 900 s suite split
# over two workers, and CI 1,068 s of its 1,200; the moments it found wanting (a signal during numba's
# import, at the first instant) are each held by a deterministic test since (``test_interrupt_steps``,
# ``test_a_signal_at_the_first_moment``). ``MICROIMPACT_SOAK_RUNS=210`` runs it at 30 per command.
RUNS = int(os.environ.get("MICROIMPACT_SOAK_RUNS", "70"))


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc/PID/status")
@pytest.mark.needs_sigint
def test_interrupt_soak():
    results = soak.soak(RUNS, workers=2, seed=24)
    s = soak.summary(results)
    assert s["runs"] == RUNS >= 70
    assert s["failed"] == 0, "\n".join(map(str, s["failures"]))  # whole, not cut by pytest
    # Most signals came while the commands worked. The moment is drawn over each command's duration as
    # measured before the soak; on a shared two-core host the suite's other worker makes a command faster
    # or slower than measured, and 79 % of the runs were interrupted in a clean run (the rest finished
    # first, and were checked to have written a complete new output).
    assert s["interrupted"] >= 0.7 * RUNS
    assert s["slowest_end_after_signal_s"] <= soak.LIMIT


@pytest.mark.parametrize("sig", SIGNALS)
def test_a_signal_at_the_first_moment(tmp_path, sig):
    # the moment microimpact's handlers are installed (the first lines of the package): one line, 128 + signal
    proc = subprocess.Popen(
        [sys.executable, "-m", "microimpact", "impact", "1:100:100000"],
        cwd=tmp_path,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        env=_env(),
    )
    t0 = time.monotonic()
    while not soak._handlers_installed(proc.pid) and proc.poll() is None and time.monotonic() - t0 < 30:
        time.sleep(0.0005)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 128 + sig, err
    assert len(err.strip().splitlines()) == 1 and "interrupted" in err and "Traceback" not in err, err


@pytest.mark.needs_sigint
def test_a_second_signal_ends_a_stuck_command_at_once(tmp_path):
    # a command stuck where KeyboardInterrupt cannot reach it (a C-level wait, a library's cleanup waiting on
    # its own lock): the first signal is swallowed, the second ends the process with one line and 130
    driver = (
        "import sys, threading\n"
        "from microimpact.cli import main\n"
        "import microimpact.cli.impact as ci\n"
        "lock = threading.Lock(); lock.acquire()\n"
        "def stuck(args):\n"
        "    ready = True\n"
        "    while True:\n"
        "        try:  # 'ready' inside the try: a signal right after it is swallowed too, never ends the run\n"
        "            if ready:\n"
        "                ready = False\n"
        "                print('ready', flush=True)\n"
        "            lock.acquire()\n"
        "        except KeyboardInterrupt:\n"
        "            print('swallowed', flush=True)  # as a library's cleanup waiting on its own lock would\n"
        "ci.run = stuck\n"
        "sys.exit(main(['impact', '50']))\n"
    )
    proc = subprocess.Popen(
        [sys.executable, "-c", driver],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=_env(),
    )
    assert proc.stdout.readline().strip() == "ready"
    proc.send_signal(signal.SIGINT)
    assert proc.stdout.readline().strip() == "swallowed"  # the first signal did not end it
    t = time.monotonic()
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 130, err
    assert len(err.strip().splitlines()) == 1 and "interrupted" in err, err
    assert time.monotonic() - t < soak.LIMIT


_NOTHING_CHANGED = """
import signal, sys
sys.argv = ["microimpact", "impact", "50"]  # as the command would have them
hook, excepthook = sys.unraisablehook, sys.excepthook
import microimpact, microimpact.cli, microimpact.io, microimpact.sweep
assert signal.getsignal(signal.SIGINT) is signal.default_int_handler, signal.getsignal(signal.SIGINT)
assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL, signal.getsignal(signal.SIGTERM)
assert sys.unraisablehook is hook and sys.excepthook is excepthook
print("unchanged")
"""


@pytest.mark.needs_sigint
def test_importing_the_package_changes_nothing_of_the_process():
    # the library installs no signal handler and replaces no hook, not even in the command's process:
    # the command line installs its handlers when main() starts
    proc = subprocess.run([sys.executable, "-c", _NOTHING_CHANGED], capture_output=True, text=True, env=_env())
    assert proc.returncode == 0 and proc.stdout.split() == ["unchanged"], proc.stderr


@pytest.mark.parametrize("sig", SIGNALS)
def test_a_signal_while_the_command_imports_its_modules(tmp_path, sig):
    # the signal arrives while main() imports the command's module (its own imports: scipy, xarray...):
    # one line and 128 + signal, no traceback
    driver = (
        "import os, sys\n"
        "sys.argv = ['microimpact', 'impact', '50']\n"
        "class Hook:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        f"        if name == 'microimpact.cli.impact': os.kill(os.getpid(), {int(sig)})\n"
        "        return None\n"
        "sys.meta_path.insert(0, Hook())\n"
        "from microimpact.cli import console_main\n"
        "sys.exit(console_main())\n"
    )
    proc = subprocess.run([sys.executable, "-c", driver], capture_output=True, text=True, env=_env(), cwd=tmp_path)
    assert proc.returncode == 128 + sig, proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1 and "interrupted" in proc.stderr, proc.stderr
    assert "Traceback" not in proc.stderr and proc.stdout == ""


SWALLOWING = {
    # seen once in 1,000 soak runs each: a C extension's import turned the interrupt into an ImportError
    # (a traceback and exit 1); an interrupt raised in a weakref callback printed "Exception ignored in"
    "import": (
        "def run(args):\n"
        "    try:\n"
        "        os.kill(os.getpid(), SIG)\n"
        "        time.sleep(1)\n"
        "    except KeyboardInterrupt:\n"
        "        raise ImportError('initialization failed')\n"
    ),
    "oserror": (
        "def run(args):\n"
        "    try:\n"
        "        os.kill(os.getpid(), SIG)\n"
        "        time.sleep(1)\n"
        "    except KeyboardInterrupt:\n"
        "        raise OSError(5, 'Input/output error', 'x.nc')\n"
    ),
    "callback": (
        "class T: pass\n"
        "def run(args):\n"
        "    t = T()\n"
        "    r = weakref.ref(t, lambda _: (os.kill(os.getpid(), SIG), time.sleep(0.1)))\n"
        "    del t\n"
        "    print('done', flush=True)\n"
        "    return 0\n"
    ),
}


@pytest.mark.parametrize("how", sorted(SWALLOWING))
@pytest.mark.parametrize("sig", SIGNALS)
def test_an_interrupt_a_library_swallows_or_converts_still_ends_the_run(tmp_path, how, sig):
    driver = (
        f"import os, sys, time, weakref\nSIG = {int(sig)}\n"
        + SWALLOWING[how]
        + "import microimpact.cli.impact as ci\nci.run = run\n"
        "from microimpact.cli import main\nsys.exit(main(['impact', '50']))\n"
    )
    proc = subprocess.run([sys.executable, "-c", driver], capture_output=True, text=True, env=_env(), cwd=tmp_path)
    assert proc.returncode == 128 + sig, proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1 and "interrupted" in proc.stderr, proc.stderr
    assert "Traceback" not in proc.stderr and "ignored" not in proc.stderr


def test_an_ignored_sigint_stays_ignored(tmp_path):
    # started with SIGINT ignored (a background job of a script, nohup-like launchers): the command keeps
    # ignoring it, as Python does, and runs to its end; SIGTERM still ends it
    def ignore_sigint():
        signal.signal(signal.SIGINT, signal.SIG_IGN)

    n = 20000
    runs = {}
    for sig in (signal.SIGINT, signal.SIGTERM):
        proc = subprocess.Popen(
            [sys.executable, "-m", "microimpact", "impact", f"1:100:{n}"],
            cwd=tmp_path,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env=_env(),
            preexec_fn=ignore_sigint,
        )
        first = proc.stdout.readline()  # the command is at work (and soon blocked on the full pipe)
        proc.send_signal(sig)
        out, err = proc.communicate(timeout=60)
        runs[sig] = (first + out, err, proc.returncode)
    out, err, rc = runs[signal.SIGINT]
    assert rc == 0 and "interrupted" not in err, err
    assert sum(line.strip()[:1].isdigit() for line in out.splitlines()) == n  # every impact printed
    out, err, rc = runs[signal.SIGTERM]
    assert rc == 128 + signal.SIGTERM, err
    assert len(err.strip().splitlines()) == 1 and "interrupted" in err and "Traceback" not in err, err


_CUT_SHORT = """
import gc, os, signal, sys
from microimpact import cli
from microimpact.cli import _interrupt

class HalfBuilt:  # as llvmlite's PassBuilder when the interrupt came inside numba's compiler
    def __del__(self):
        raise AttributeError("'HalfBuilt' object has no attribute '_as_parameter_'")

def command(argv):
    gc.disable()
    a = HalfBuilt()
    a.cycle = a  # garbage that only the collector frees
    del a
    os.kill(os.getpid(), signal.SIGINT)  # the handler raises Interrupted here
    return 0

restore = _interrupt.restore
def restore_then_collect(*args, **kw):
    restore(*args, **kw)
    gc.collect()  # the collector runs on the way out of the process

_interrupt.restore = restore_then_collect
cli._main = command
sys.argv = ["microimpact", "impact", "50"]
sys.exit(cli.console_main())
"""


@pytest.mark.needs_sigint
def test_what_an_interrupt_cut_short_is_not_reported(tmp_path):
    # CI's soak once printed "Exception ignored in: ObjectRef.__del__ ... AttributeError: 'PassBuilder' object has
    # no attribute '_as_parameter_'" after the interrupt line: an object the interrupt left half built, freed by
    # the collector on the way out. After an interrupt such exceptions are its consequences: one line, 130
    proc = subprocess.run(
        [sys.executable, "-c", _CUT_SHORT], cwd=tmp_path, capture_output=True, text=True, env=_env(), timeout=60
    )
    assert proc.returncode == 128 + signal.SIGINT, proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1 and "interrupted" in proc.stderr, proc.stderr


_IN_COMPILER = """
import os, signal, sys, threading
import numba
from microimpact.cli import main
import microimpact.cli.impact as ci

def run(args):
    def law(x, n):  # a fresh function: numba compiles it at its first call
        s = 0.0
        for i in range(n):
            s += (x + i) ** 1.5 / (1.0 + i * x)
        return s
    f = numba.njit(cache=False)(law)
    threading.Timer(DELAY, os.kill, (os.getpid(), SIG)).start()  # arrives while numba compiles
    try:
        f(1.0, 10)
    except KeyboardInterrupt as exc:
        tb, frames = exc.__traceback__, []
        while tb is not None:
            frames.append(tb.tb_frame.f_code.co_filename)
            tb = tb.tb_next
        print("in numba" if any("numba" in f for f in frames[1:]) else "outside numba", flush=True)
        raise
    print("compiled before the signal", flush=True)
    return 0

ci.run = run
sys.exit(main(["impact", "50"]))
"""


@pytest.mark.parametrize("delay", [0.01, 0.05, 0.1])
@pytest.mark.parametrize("sig", SIGNALS)
def test_a_signal_inside_numbas_compiler_is_one_line(tmp_path, sig, delay):
    # an interrupt raised inside numba's compiler leaves llvmlite objects half built: freeing them printed
    # "Exception ignored in: ... PassBuilder.__del__" after the interrupt line. The command says nothing of
    # what the interrupt cut short: one line, 128 + signal
    pytest.importorskip("numba")
    driver = _IN_COMPILER.replace("SIG", str(int(sig)), 1).replace("DELAY", str(delay), 1)
    proc = subprocess.run([sys.executable, "-c", driver], capture_output=True, text=True, env=_env(), cwd=tmp_path)
    if proc.stdout.split() == ["compiled", "before", "the", "signal"]:
        pytest.skip("numba compiled the function before the signal came")
    assert proc.returncode == 128 + sig, proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1 and "interrupted" in proc.stderr, proc.stderr
    assert "ignored" not in proc.stderr and "Traceback" not in proc.stderr
    assert proc.stdout.split() in (["in", "numba"], ["outside", "numba"]), proc.stdout


_AFTER_REPLACE = """
import os, sys
from microimpact.cli import main

replace = os.replace
def replace_then_a_signal(src, dst):
    replace(src, dst)
    if os.fspath(dst).endswith("out.csv"):
        os.kill(os.getpid(), SIG)  # the output is in place: the interrupt comes on the next line of Python
os.replace = replace_then_a_signal
sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.parametrize("sig", SIGNALS)
def test_a_signal_once_the_output_is_in_place(tmp_path, sig):
    # a signal just after an output was renamed into place: the run stops there (128 + signal, one line);
    # what is in place is whole (the new output; a figure written before it, whole), no temporary file is left
    (tmp_path / "out.csv").write_text("an earlier output\n")
    driver = _AFTER_REPLACE.replace("SIG", str(int(sig)), 1)
    argv = ["history", "50", "--n", "200", "--out", "out.csv", "--plot", "out.png"]
    proc = subprocess.run(
        [sys.executable, "-c", driver, *argv], capture_output=True, text=True, env=_env(), cwd=tmp_path
    )
    assert proc.returncode == 128 + sig, proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1 and "interrupted" in proc.stderr, proc.stderr
    text = (tmp_path / "out.csv").read_text()
    assert text.startswith("time [s]") and text.count("\n") > 200  # whole
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names in (["out.csv"], ["out.csv", "out.png"]), names  # no temporary
    if "out.png" in names:  # written before the table: whole too
        assert (tmp_path / "out.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
