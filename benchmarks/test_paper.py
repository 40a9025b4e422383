"""6. ``microimpact paper`` end to end, in a subprocess writing to a temporary directory, run in turn
with ``python -c "import matplotlib.pyplot"`` (what it cannot avoid): A B A B, best of each, so that
the ratio holds on a loaded machine. ``paper`` as a user runs it (its figures drawn in two processes
when it may use more than one core and a whole core is idle) and in one process (``--workers 1``), reported
beside it, with the 1-minute load average over the runs (the default's choice depends on it)."""

import os
import subprocess
import sys
import time

import pytest

KEY = "paper"


def _time(argv):
    t0 = time.perf_counter()
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return time.perf_counter() - t0


def test_paper_end_to_end(record, size, tmp_path):
    if not size["paper"]:
        pytest.skip("not run in tiny mode")
    pytest.importorskip("matplotlib")
    paper = [sys.executable, "-m", "microimpact", "paper", "--out", str(tmp_path)]
    serial = paper + ["--workers", "1"]
    mpl = [sys.executable, "-c", "import matplotlib.pyplot"]
    _time(mpl)  # bytecode and matplotlib's font cache, as on a user's machine
    best = {}
    loads = [os.getloadavg()[0]] if hasattr(os, "getloadavg") else []
    for _ in range(2):
        for label, argv in (
            ("end to end", paper),
            ("end to end, one process", serial),
            ("python -c 'import matplotlib.pyplot'", mpl),
        ):
            best[label] = min(best.get(label, float("inf")), _time(argv))
        loads += [os.getloadavg()[0]] if loads else []
    for label, seconds in best.items():
        record.time(KEY, label, seconds)
    if loads:
        record.metric(KEY, "load average (1 min)", (min(loads), max(loads)))
    files = sum(len(f) for _, _, f in os.walk(tmp_path))
    record.metric(KEY, "files", files)
    assert files >= 20
