"""Fault corpus: peak resident memory (RSS, what the system sees) of the commands that take large inputs.

Each command runs at two sizes in a child of a small helper process, which reports
``resource.getrusage(RUSAGE_CHILDREN).ru_maxrss`` (a child forked from this large test process would
report its size: Linux keeps a process's peak across exec). The growth per item between the two
sizes is held to a bound (the sweeps' one the code before failed; at these sizes the code before
kept within the fit's and stick's, whose cost showed at 10^6-10^7 items): ``fit --json`` wrote a
Python float per residual and the whole document as one string (about 200 bytes a row; 2.0 GB at
10^7 rows), ``stick`` held a list of Python result pairs and the whole table's text (about 700
bytes a diameter; 830 MB at 10^6), a sweep held three copies of its coordinate and read the flag
back with xarray's index of it (about 40 bytes a point; 707 MB at 10^7 speeds). The full-size
figures are in ``benchmarks/README.md``.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from .test_faults import _env

resource = pytest.importorskip("resource")

HELPER = r"""
import resource, subprocess, sys
proc = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
if proc.returncode:
    sys.exit(proc.stderr.decode()[-2000:])
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024)
"""


def peak_rss(argv, cwd) -> int:
    """Peak RSS [bytes] of ``python -m microimpact ARGV``, measured by a small helper process."""
    cmd = [sys.executable, "-c", HELPER, sys.executable, "-m", "microimpact", *argv]
    out = subprocess.run(cmd, cwd=cwd, env=_env(), capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    return int(out.stdout.strip().splitlines()[-1])


def growth(argv_of, small, large, cwd, repeat=1, warm=None) -> float:
    """Bytes of peak RSS per item between ``small`` and ``large`` items, both measured with the compiled
    loops on disk: a first run warms the cache (numba's compiler held 80 MB more at its peak, which a
    cold cache charged to whichever size ran first: 70 bytes a point instead of 25 in a CSV sweep).
    Each size's peak is the least of ``repeat`` runs, taken in turn: where threads overlap the stages
    (a sweep's blocks), the peak depends on their timing, and on a loaded host it varied by 27 MB
    between runs of the same sweep, 16 bytes a point of the difference. ``warm`` items (default
    ``small``) warm the cache: enough for the threaded compiled loop the measured runs use."""
    peak_rss(argv_of(warm or small), cwd)
    peaks = {small: [], large: []}
    for _ in range(repeat):
        for n in peaks:
            peaks[n].append(peak_rss(argv_of(n), cwd))
    return (min(peaks[large]) - min(peaks[small])) / (large - small)


def test_fit_json_memory_per_row(tmp_path):
    rng = np.random.default_rng(5)
    for n in (20_000, 300_000):
        V = rng.uniform(2.0, 100.0, n)
        e = np.clip(0.9 - 0.003 * V + rng.normal(0.0, 0.02, n), 0.05, 1.0)
        with open(tmp_path / f"d{n}.csv", "w") as fh:
            fh.write("velocity,restitution\n")
            np.savetxt(fh, np.column_stack([V, e]), delimiter=",", fmt="%.6g")
    per_row = growth(lambda n: ["fit", f"d{n}.csv", "--json"], 20_000, 300_000, tmp_path)
    # the data (20 bytes a row), the residuals (8), the fit's passes: about 40; the code before about 200
    assert per_row < 100, f"{per_row:.0f} bytes a row"


def test_stick_memory_per_diameter(tmp_path):
    def argv(n):
        return ["stick", "-G", "0.1", f"1e-7:1e-5:{n}", "--json", "--out", f"s{n}.csv"]

    # both sizes above the writers' blocks (at most 65,536 rows), whose fixed cost is not per diameter;
    # 4,096 diameters run the threaded loop (above engine.SMALL, and each diameter's root search costs
    # more than engine.PARALLEL_WORK / 2,048)
    per_diameter = growth(argv, 70_000, 140_000, tmp_path, warm=4096)
    # the diameters, radii, masses and two laws' two results (64 bytes); the code before about 700
    assert per_diameter < 250, f"{per_diameter:.0f} bytes a diameter"


@pytest.mark.parametrize("suffix", ["nc", "csv"])
def test_sweep_memory_per_point(tmp_path, suffix):
    def argv(n):
        return ["sweep", "--velocity", f"1:120:{n}", "--chunks", "131072", "--out", f"s{n}.{suffix}", "-q"]

    per_point = growth(argv, 300_000, 2_000_000, tmp_path, repeat=3)
    # the sweep's one copy of the speeds (8 bytes a point) and its blocks: 24-36 measured; the code before
    # 57-76. The goal, a 1e7-point sweep within 500 MB beside the interpreter's ~100 MB, is 40 bytes a point.
    assert per_point < 40, f"{per_point:.1f} bytes a point"
