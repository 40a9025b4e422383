"""Interrupt soak: ``python benchmarks/interrupt_soak.py [--runs 1000] [--workers 2] [--json]``.

Runs the writing commands (NetCDF and CSV sweeps, a CSV history, a fit with its figure, an
export folder, the paper, an impact table on standard output) over and over, each in a fresh
folder holding an earlier output, and sends SIGINT or SIGTERM (chosen at random) at a random
moment of the run. Every run must end within 5 s of the signal with exit status 130/143 and one
line on stderr naming the interrupt (or, when the signal came after the command finished, exit
0 with a complete new output), leave the earlier output byte for byte as it was or, where the
signal came just after the new output was renamed into place, the complete new output (never a
part of either), and leave no temporary file. The moment is drawn uniformly over most (``SPAN``) of the command's duration on this
machine, measured first as the faster of two uninterrupted runs of each command (a fixed number of seconds
would let a faster machine finish most runs before their signal; a first run may meet a cold cache),
counted from
when microimpact's handlers are installed (read from ``/proc/PID/status``: the few tens of ms the
interpreter itself takes to start, before any of microimpact's code runs, are not the command's
to handle; ``--from-exec`` counts from the process start instead and reports those runs apart).

The test suite runs the same harness at a size that fits CI (tests/cli/test_faults_soak.py).
Prints a summary per command (``--json``: the counts as JSON); exit status 1 if any run failed.
"""

from __future__ import annotations

import argparse
import collections
import concurrent.futures
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OLD = "an earlier output, to be kept byte for byte\n"
DATA = "velocity,restitution\n" + "".join(f"{v},{e}\n" for v, e in ((5, 1.0), (20, 0.86), (50, 0.72), (80, 0.64)))
#: name -> (argv, output, kind, seconds after the handlers are installed on the machine it was written on;
#: only a fallback: ``measure`` times each command where the soak runs)
CASES = {
    "sweep-nc": (
        ["sweep", "--velocity", "1:120:2000", "--density", "1000:3000:400", "--out", "out.nc", "--chunks", "200"],
        "out.nc",
        "file",
        3.0,
    ),
    "sweep-csv": (
        ["sweep", "--velocity", "1:120:2000", "--density", "1000:3000:200", "--out", "out.csv"],
        "out.csv",
        "file",
        2.5,
    ),
    "history-csv": (["history", "50", "--n", "1000000", "--out", "out.csv"], "out.csv", "file", 2.0),
    "fit": (["fit", "data.csv", "--plot", "out.png"], "out.png", "file", 2.5),
    "export": (
        ["export", "--out", "out", "--velocities", "0.01:200:100000", "--diameters", "1e-6,2e-6"],
        "out",
        "dir",
        1.5,
    ),
    "paper": (["paper", "--out", "out", "--formats", "png", "--quiet"], "out", "dir", 6.0),
    "impact-stdout": (["impact", "1:100:1000000"], None, "stdout", 1.5),
}
LIMIT = 5.0  # seconds from the signal to the end of the process
SPAN = 0.8  # the signal comes within the first SPAN of the command's measured duration


def _env():
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "src") + os.pathsep + env.get("PYTHONPATH", "")
    env.pop("MICROIMPACT_BACKEND", None)
    # the runs measure the command, not a coverage tracer: pytest-cov (CI's --cov) starts one in every
    # child through these variables, which slows it and can add lines to its stderr
    for key in [k for k in env if k.startswith("COV_CORE_") or k == "COVERAGE_PROCESS_START"]:
        env.pop(key)
    env["PYTHONFAULTHANDLER"] = "1"  # a run that does not end is sent SIGABRT: every thread's stack on stderr
    return env


def _handlers_installed(pid) -> bool:
    """True once the process catches SIGTERM (microimpact installs its handler at the start)."""
    try:
        with open(f"/proc/{pid}/status") as fh:
            for line in fh:
                if line.startswith("SigCgt:"):
                    return bool(int(line.split()[1], 16) >> (signal.SIGTERM - 1) & 1)
    except OSError:
        pass
    return False


def _prepare(folder: Path, name: str):
    argv, out, kind, _ = CASES[name]
    (folder / "data.csv").write_text(DATA)
    if kind == "file":
        (folder / out).write_text(OLD)
    elif kind == "dir":
        sys.path.insert(0, str(ROOT / "src"))
        from microimpact.io import owned_directory

        with owned_directory(folder / out, argv[0]) as tmp:  # an earlier run's output, with its manifest
            (tmp / "old.txt").write_text(OLD)
    return sorted(p.name for p in folder.iterdir())


def _old_intact(folder: Path, name: str) -> bool:
    argv, out, kind, _ = CASES[name]
    if kind == "file":  # bytes: a finished run may have left a binary file (a figure, NetCDF) there
        return (folder / out).read_bytes() == OLD.encode()
    if kind == "dir":
        d = folder / out
        names = sorted(p.name for p in d.iterdir())
        return names == [".microimpact-manifest.json", "old.txt"] and (d / "old.txt").read_bytes() == OLD.encode()
    return True


def _new_whole(folder: Path, name: str) -> bool:
    """The run's complete new output is in place (a signal that came after it was renamed into place:
    the command is interrupted, but what it replaced was replaced whole, never cut)."""
    import hashlib
    import json

    argv, out, kind, _ = CASES[name]
    if kind == "file":
        data = (folder / out).read_bytes()
        return bool(data) and data != OLD.encode() and (not out.endswith(".csv") or data.endswith(b"\n"))
    if kind == "dir":
        d = folder / out
        try:
            files = json.loads((d / ".microimpact-manifest.json").read_text())["files"]
        except (OSError, ValueError, KeyError):
            return False
        if "old.txt" in files or sorted(p.name for p in d.iterdir()) != sorted([*files, ".microimpact-manifest.json"]):
            return False
        return all(hashlib.sha256((d / n).read_bytes()).hexdigest() == f["sha256"] for n, f in files.items())
    return True


def _temporaries(folder: Path):
    found = []
    for p in folder.rglob("*"):
        n = p.name
        if n.startswith(".") and (n.endswith(".tmp") or ".tmp." in n or n.startswith(".microimpact-staging")):
            found.append(str(p.relative_to(folder)))
    return found


def measure(name: str) -> float:
    """Seconds ``name`` takes here, uninterrupted, from the moment its handlers are installed.

    The faster of two runs: the first may meet a cold cache (kernels and tables are stored under a
    hash of the sources, so the first run after a change builds them), and a duration measured on
    it would let most of the soak's warm runs finish before their signal.
    """
    return min(_time_once(name), _time_once(name))


def _time_once(name: str) -> float:
    argv, out, kind, typical = CASES[name]
    folder = Path(tempfile.mkdtemp(prefix="soak-"))
    try:
        _prepare(folder, name)
        proc = subprocess.Popen(
            [sys.executable, "-m", "microimpact", *argv],
            cwd=folder,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            env=_env(),
        )
        t0 = time.monotonic()
        while not _handlers_installed(proc.pid) and proc.poll() is None and time.monotonic() - t0 < 30:
            time.sleep(0.002)
        t1 = time.monotonic()
        rc = proc.wait(timeout=300)
        if rc != 0:
            return typical  # the run itself will say what is wrong
        return time.monotonic() - t1
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def one_run(name: str, seed: int, from_exec: bool = False, typical: float | None = None) -> dict:
    """One interrupted run of ``name``; a dict saying what happened (``ok`` True when all held).

    The signal comes at a moment drawn uniformly over ``SPAN * typical`` seconds (``typical``: the
    command's measured duration; the fixed figure of ``CASES`` when not given).
    """
    rng = random.Random(seed)
    sig = rng.choice([signal.SIGINT, signal.SIGTERM])
    argv, out, kind, fallback = CASES[name]
    typical = SPAN * (fallback if typical is None else typical)
    folder = Path(tempfile.mkdtemp(prefix="soak-"))
    try:
        before = _prepare(folder, name)
        proc = subprocess.Popen(
            [sys.executable, "-m", "microimpact", *argv],
            cwd=folder,
            stdout=subprocess.PIPE if kind == "stdout" else subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            env=_env(),
        )
        t0 = time.monotonic()
        if not from_exec:
            while not _handlers_installed(proc.pid) and proc.poll() is None and time.monotonic() - t0 < 30:
                time.sleep(0.002)
        delay = rng.uniform(0.0, typical)
        time.sleep(delay)
        installed = _handlers_installed(proc.pid)
        finished_before = proc.poll() is not None
        sent = time.monotonic()
        if not finished_before:
            proc.send_signal(sig)
        try:
            stdout, err = proc.communicate(timeout=LIMIT + 25.0)
        except subprocess.TimeoutExpired:
            proc.send_signal(signal.SIGABRT)  # the stacks of a run that did not end (faulthandler)
            try:
                stdout, err = proc.communicate(timeout=5.0)
            except subprocess.TimeoutExpired:
                proc.kill()
                stdout, err = proc.communicate()
        took = time.monotonic() - sent
        err = err.decode("utf-8", "replace")
        lines = [ln for ln in err.strip().splitlines() if not ln.startswith(("sweep:", "warning:"))]
        rc = proc.returncode
        res = {"case": name, "signal": int(sig), "delay": round(delay, 3), "span": round(typical, 3), "rc": rc}
        res["seconds"] = round(took, 3)
        res["handlers"] = installed
        if rc == 0:  # the command ended before the signal reached it: a complete new output
            res["outcome"] = "completed"
            new_ok = kind == "stdout" or (folder / out).exists() and not _old_intact(folder, name)
            res["ok"] = new_ok and not _temporaries(folder) and "Traceback" not in err
        else:
            res["outcome"] = "interrupted"
            checks = {
                "status": rc == 128 + sig,
                "one line": len(lines) == 1 and "interrupted" in lines[0] and "Traceback" not in err,
                "in time": took <= LIMIT,
                "old output, or the whole new one": _old_intact(folder, name) or _new_whole(folder, name),
                "no temporary": not _temporaries(folder),
                "nothing else": sorted(p.name for p in folder.iterdir()) == before,
            }
            res["ok"] = all(checks.values())
            if not res["ok"]:
                res["failed"] = [k for k, v in checks.items() if not v]
                # all of it, or its beginning and end: a traceback's first frames say who printed it,
                # and faulthandler's stacks come before the list of extension modules
                res["stderr"] = err if len(err) <= 6000 else err[:3000] + "\n[...]\n" + err[-3000:]
                res["temporaries"] = _temporaries(folder)
        return res
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def soak(runs: int, workers: int = 2, seed: int = 0, cases=None, from_exec: bool = False) -> list:
    """``runs`` interrupted runs spread over ``cases`` (default all), ``workers`` at a time."""
    names = list(cases or CASES)
    jobs = [(names[i % len(names)], seed * 1_000_003 + i) for i in range(runs)]
    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        typical = dict(zip(names, pool.map(measure, names)))  # under the same load as the soak
        return list(pool.map(lambda job: one_run(*job, from_exec=from_exec, typical=typical[job[0]]), jobs))


def summary(results) -> dict:
    table = collections.defaultdict(collections.Counter)
    for r in results:
        table[r["case"]][r["outcome"] + ("" if r["ok"] else " FAILED")] += 1
    slowest = max((r["seconds"] for r in results if r["outcome"] == "interrupted"), default=0.0)
    return {
        "runs": len(results),
        "failed": sum(not r["ok"] for r in results),
        "interrupted": sum(r["outcome"] == "interrupted" for r in results),
        "completed_before_signal": sum(r["outcome"] == "completed" for r in results),
        "slowest_end_after_signal_s": slowest,
        "before_handlers": sum(not r["handlers"] for r in results),
        "failed_before_handlers": sum(not r["ok"] and not r["handlers"] for r in results),
        "per_case": {k: dict(v) for k, v in table.items()},
        "failures": [r for r in results if not r["ok"]][:10],
    }


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--runs", type=int, default=1000)
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--cases", default=None, help="comma-separated among " + ", ".join(CASES))
    p.add_argument("--from-exec", action="store_true", help="draw the moment from the process start")
    p.add_argument("--json", action="store_true")
    a = p.parse_args(argv)
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        # started as a background job of a script (SIGINT ignored, and so in every child, which then
        # rightly keeps ignoring it): the commands get SIGINT as a user's terminal gives it
        signal.signal(signal.SIGINT, signal.default_int_handler)
    t = time.monotonic()
    res = soak(a.runs, a.workers, a.seed, a.cases.split(",") if a.cases else None, a.from_exec)
    s = summary(res)
    s["wall_s"] = round(time.monotonic() - t, 1)
    if a.json:
        print(json.dumps(s, indent=1))
    else:
        print(
            f"{s['runs']} runs in {s['wall_s']} s: {s['interrupted']} interrupted, "
            f"{s['completed_before_signal']} completed before the signal, {s['failed']} failed; "
            f"slowest end after a signal {s['slowest_end_after_signal_s']:.2f} s"
        )
        for case, counts in s["per_case"].items():
            print(f"  {case:14s} {dict(counts)}")
        for r in s["failures"]:
            print("  FAILED", json.dumps(r))
    return 1 if s["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
