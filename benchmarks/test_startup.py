"""8. Start-up: ``microimpact impact 50`` against ``python -c "import numpy"``, and the first array
call in a new process (compiled loops cached on disk), each the best of several fresh processes."""

import os
import subprocess
import sys
import time

KEY = "startup"

FIRST_CALL = """
import time, numpy as np, microimpact as mi
pair = mi.ContactPair.paper_case("silicon")
V = np.linspace(1.0, 120.0, {n})
t = time.perf_counter(); pair.impact(V, warn=False); print(time.perf_counter() - t)
"""


# An installed package has its bytecode compiled (pip does it); a source checkout gets it on the
# first import, unless PYTHONDONTWRITEBYTECODE forbids it, and then every start compiles every
# module again (20-30 ms here). The warm-up run writes the bytecode, as a first use would.
_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def _best(argv, runs=5):
    subprocess.run(argv, check=True, capture_output=True, env=_ENV)  # warm-up: bytecode, disk cache
    best = float("inf")
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run(argv, check=True, capture_output=True, env=_ENV)
        best = min(best, time.perf_counter() - t0)
    return best


def test_cli_start(record):
    t_numpy = _best([sys.executable, "-c", "import numpy"])
    t_cli = _best([sys.executable, "-m", "microimpact", "impact", "50"])
    record.time(KEY, "python -c 'import numpy'", t_numpy)
    record.time(KEY, "microimpact impact 50", t_cli)


def test_first_array_call(record):
    for n in (1000, 1_000_000):
        code = FIRST_CALL.format(n=n)
        subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)  # warms the cache
        best = min(
            float(subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout)
            for _ in range(3)
        )
        record.time(KEY, f"first array call, {n:.0e} speeds", best)
