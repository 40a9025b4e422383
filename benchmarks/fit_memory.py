"""Peak memory of fitting N measured points: ``python benchmarks/fit_memory.py [N ...]``.

Each size runs in a fresh subprocess that makes N synthetic points (the seed's e(V) for the
silicon case plus seeded noise 0.02, speeds 2-100 m/s, values above 1 included), starts
``tracemalloc`` after the data exist, calls ``fit_restitution`` (least squares) and reports
the peak of Python/numpy allocations during the fit, in MB and in bytes per point, with the
fit's time. Memory must grow linearly with N with a small constant: 1e6 points under 500 MB.
Nothing is written; the numbers are printed (``--json`` prints them as JSON).

``python benchmarks/fit_memory.py --csv N [--loader-only]``: the peak resident memory (RSS, what
the system sees, interpreter included) of the command ``microimpact fit FILE`` on a CSV file of N
rows (written to a temporary folder first, velocity and restitution as above), or of reading that
file alone (:func:`microimpact.io.load_restitution_csv`). The reader streams the file into
typed arrays (20 bytes a row: two values and a 4-byte line number); the goal is a 10^7-row fit within 500 MB.
"""

from __future__ import annotations

import json
import subprocess
import sys

CHILD = r"""
import json, sys, time, tracemalloc, warnings
import numpy as np
import microimpact as mi
from microimpact.fitting import FitWarning, fit_restitution

n = int(sys.argv[1])
loss = sys.argv[2]
pair = mi.ContactPair.paper_case("silicon")
rng = np.random.default_rng(1)
V = rng.uniform(2.0, 100.0, n)
e = pair.restitution(V) + rng.normal(0.0, 0.02, n)
fit_restitution(V[:50], e[:50], pair)  # warm caches (compilation) outside the measurement
tracemalloc.start()
t = time.perf_counter()
with warnings.catch_warnings():
    warnings.simplefilter("ignore", FitWarning)
    fit = fit_restitution(V, e, pair.replace(limiting_pressure=80e6), loss=loss)
elapsed = time.perf_counter() - t
_, peak = tracemalloc.get_traced_memory()
tracemalloc.stop()
print(json.dumps({"n": n, "loss": loss, "peak_bytes": peak, "seconds": elapsed,
                  "p_y": fit.params["limiting_pressure"], "above_one": int(np.sum(e > 1))}))
"""


def measure(n: int, loss: str = "linear") -> dict:
    """Peak traced memory [bytes] and time [s] of one fit of ``n`` points, in a subprocess."""
    out = subprocess.run([sys.executable, "-c", CHILD, str(n), loss], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


# Each child reports its own peak RSS (a forked child's RUSAGE_CHILDREN would count the parent's pages).
LOADER = r"""
import resource, sys
from microimpact.io import load_restitution_csv
print(len(load_restitution_csv(sys.argv[1])[0]))
print("peak", resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024, file=sys.stderr)
"""
FIT = r"""
import resource, sys
from microimpact.cli import main
rc = main(["fit", sys.argv[1]])
print("peak", resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024, file=sys.stderr)
sys.exit(rc)
"""


MAKE = r"""
import sys
import numpy as np
import microimpact as mi
path, n = sys.argv[1], int(sys.argv[2])
pair = mi.ContactPair.paper_case("silicon")
rng = np.random.default_rng(1)
with open(path, "w") as fh:
    fh.write("velocity,restitution" + chr(10))
    for start in range(0, n, 1_000_000):
        m = min(1_000_000, n - start)
        V = rng.uniform(2.0, 100.0, m)
        e = pair.restitution(V) + rng.normal(0.0, 0.02, m)
        np.savetxt(fh, np.column_stack([V, e]), delimiter=",", fmt="%.6g")
"""


def measure_csv(n: int, loader_only: bool = False) -> dict:
    """Peak RSS [bytes] and time [s] of ``microimpact fit`` (or of the reader alone) on an ``n``-row CSV."""
    import os
    import tempfile
    import time

    # The data are made in a child: this process stays small, because Linux keeps a process's peak
    # RSS across exec, and a child forked from a large parent would report the parent's size.
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "data.csv")
        subprocess.run([sys.executable, "-c", MAKE, path, str(n)], check=True)
        t = time.perf_counter()
        proc = subprocess.run(
            [sys.executable, "-c", LOADER if loader_only else FIT, path], capture_output=True, text=True
        )
        elapsed = time.perf_counter() - t
        peaks = [int(ln.split()[1]) for ln in proc.stderr.splitlines() if ln.startswith("peak ")]
    return {
        "n": n,
        "what": "read" if loader_only else "fit",
        "rc": proc.returncode,
        "peak_rss_bytes": peaks[-1] if peaks else -1,
        "seconds": elapsed,
        "stderr": proc.stderr[-300:] if proc.returncode else "",
    }


def main(argv=None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    if "--csv" in args:
        n = int(float(args[args.index("--csv") + 1]))
        r = measure_csv(n, "--loader-only" in args)
        print(
            json.dumps(r)
            if "--json" in args
            else f"{r['what']} of {n} CSV rows: peak RSS {r['peak_rss_bytes'] / 1e6:.0f} MB, {r['seconds']:.1f} s"
            + (f" (exit {r['rc']}: {r['stderr']})" if r["rc"] else "")
        )
        return 0
    as_json = "--json" in args
    sizes = [int(float(a)) for a in args if a != "--json"] or [10_000, 100_000, 1_000_000]
    rows = [measure(n, loss) for n in sizes for loss in ("linear", "soft_l1")]
    if as_json:
        print(json.dumps(rows, indent=2))
        return 0
    print(f"{'points':>10}  {'loss':8}  {'peak [MB]':>9}  {'bytes/point':>11}  {'time [s]':>8}  p_y [MPa]")
    for r in rows:
        print(
            f"{r['n']:>10}  {r['loss']:8}  {r['peak_bytes'] / 1e6:9.1f}  {r['peak_bytes'] / r['n']:11.0f}  "
            f"{r['seconds']:8.2f}  {r['p_y'] / 1e6:.2f}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
