"""Peak memory of microimpact's writing commands, each in its own subprocess (reported, not timed).

``python benchmarks/memory.py [--points 1e7] [--json FILE]``

Runs ``microimpact sweep`` over ``--points`` points (velocity x density,
dask chunks chosen automatically) to CSV and to NetCDF, plus a baseline process
that only imports what the sweep imports, and reports each process's peak
resident memory (``ru_maxrss`` of the child, from :func:`os.wait4`), the file
size and the wall time. Memory that stays flat while the sweep grows is the
claim: the file is streamed block by block through a temporary file beside the
target (:mod:`microimpact.io`), never held whole.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def peak_rss(argv, cwd) -> tuple[float, float, int]:
    """(peak RSS [MB], wall time [s], exit status) of ``argv`` run in a subprocess."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "src") + os.pathsep + env.get("PYTHONPATH", "")
    t0 = time.perf_counter()
    proc = subprocess.Popen(argv, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    err = proc.stderr.read().decode(errors="replace") if proc.stderr else ""
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode:
        print(err, file=sys.stderr)
    return usage.ru_maxrss / 1024.0, wall, proc.returncode  # ru_maxrss is in kB on Linux


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--points", type=float, default=1e7, help="points of the sweep (default 1e7)")
    p.add_argument("--json", metavar="FILE", help="also write the results as JSON")
    args = p.parse_args(argv)
    n = int(args.points)
    nd = 1000 if n >= 1e6 else 10
    nv = max(2, math.ceil(n / nd))
    sweep = [sys.executable, "-m", "microimpact", "sweep", "--velocity", f"1:120:{nv}", "--density", f"1000:3000:{nd}"]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        base = [sys.executable, "-c", "import microimpact.sweep, xarray, dask.array, pandas, netCDF4"]
        rss, wall, rc = peak_rss(base, tmp)
        rows.append({"case": "baseline: imports only", "points": 0, "peak_rss_MB": rss, "wall_s": wall, "rc": rc})
        for suffix in ("nc", "csv"):
            rss, wall, rc = peak_rss(sweep + ["--out", f"s.{suffix}", "--quiet"], tmp)
            size = (Path(tmp) / f"s.{suffix}").stat().st_size if rc == 0 else 0
            rows.append(
                {
                    "case": f"sweep to .{suffix}, chunked (auto)",
                    "points": nv * nd,
                    "peak_rss_MB": rss,
                    "wall_s": wall,
                    "file_MB": size / 1e6,
                    "rc": rc,
                }
            )
    print(f"{'case':36s} {'points':>10s} {'peak RSS':>10s} {'wall':>8s} {'file':>10s}")
    for r in rows:
        file = f"{r['file_MB']:.0f} MB" if "file_MB" in r else ""
        print(f"{r['case']:36s} {r['points']:10d} {r['peak_rss_MB']:7.0f} MB {r['wall_s']:6.1f} s {file:>10s}")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=2) + "\n")
    return 0 if all(r["rc"] == 0 for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
