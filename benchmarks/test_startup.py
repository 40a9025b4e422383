"""9. Start-up: small commands against the import of what each cannot avoid, and the first array call in a
new process, each subject run in turn with its baseline (A B A B ...: the ratios hold on a loaded machine),
each ratio the subject's best of the rounds over the best of the baseline runs beside it, fresh processes
with bytecode written."""

import os
import subprocess
import sys
import tempfile
import time

KEY = "startup"

FIRST_CALL = """
import time, numpy as np, microimpact as mi
pair = mi.ContactPair.paper_case("silicon")
V = np.linspace(1.0, 120.0, {n})
t = time.perf_counter(); pair.impact(V, warn=False); print(time.perf_counter() - t)
"""

#: ``(subject, its argv after python, baseline)``: what the start-up goals compare.
_PY = [sys.executable]
BASELINES = {
    "import numpy": _PY + ["-c", "import numpy"],
    "import xarray": _PY + ["-c", "import xarray"],
    "import numba": _PY + ["-c", "import numba"],
}
#: Goals: subject -> (baseline, largest ratio).
GOALS = {
    "microimpact impact 50": ("import numpy", 2.0),
    "microimpact history 50": ("import numpy", 2.0),
    "microimpact export (one diameter, tables)": ("import numpy", 2.0),
    "microimpact sweep (50 speeds, .nc)": ("import xarray", 2.0),
    "microimpact compare (24 speeds)": ("import xarray", 2.0),
    # numba loads a cached loop only after building its target context (every implementation it has)
    "first compiled call, 1e6 speeds (whole process)": ("import numba", 2.5),
}


# An installed package has its bytecode compiled (pip does it); a source checkout gets it on the
# first import, unless PYTHONDONTWRITEBYTECODE forbids it, and then every start compiles every
# module again (20-30 ms here). The warm-up run writes the bytecode, as a first use would.
_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def _time(argv):
    t0 = time.perf_counter()
    subprocess.run(argv, check=True, capture_output=True, env=_ENV)
    return time.perf_counter() - t0


def test_small_commands(record, size):
    rounds = 5 if size["paper"] else 2
    with tempfile.TemporaryDirectory() as tmp:
        subjects = {
            "microimpact impact 50": _PY + ["-m", "microimpact", "impact", "50"],
            "microimpact history 50": _PY + ["-m", "microimpact", "history", "50"],
            "microimpact export (one diameter, tables)": _PY
            + ["-m", "microimpact", "export", "--no-c", "--out", os.path.join(tmp, "export")],
            "microimpact sweep (50 speeds, .nc)": _PY
            + ["-m", "microimpact", "sweep", "--velocity", "1:120:50", "--out", os.path.join(tmp, "s.nc")],
            "microimpact compare (24 speeds)": _PY + ["-m", "microimpact", "compare", "1:120:24"],
            "first compiled call, 1e6 speeds (whole process)": _PY + ["-c", FIRST_CALL.format(n=1_000_000)],
        }
        for argv in (*BASELINES.values(), *subjects.values()):  # warm-up: bytecode, compiled loops on disk
            subprocess.run(argv, check=True, capture_output=True, env=_ENV)
        # Each ratio is a subject's best over its rounds against the best of the baseline runs beside it:
        # as many baseline runs as subject runs (a baseline that three subjects share would otherwise
        # get three times the chances of a quiet moment, and every ratio would read high).
        best, beside = {}, {}
        for _ in range(rounds):
            for name, argv in subjects.items():
                base = GOALS[name][0]
                t_subject, t_base = _time(argv), _time(BASELINES[base])
                best[name] = min(best.get(name, float("inf")), t_subject)
                beside[name] = min(beside.get(name, float("inf")), t_base)
                best[base] = min(best.get(base, float("inf")), t_base)
    for name, seconds in best.items():
        record.time(KEY, name if name in GOALS else f"python -c '{name}'", seconds)
    for name in subjects:
        record.metric(KEY, f"ratio: {name}", best[name] / beside[name])


def test_first_array_call(record):
    for n in (1000, 1_000_000):
        code = FIRST_CALL.format(n=n)
        subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)  # warms the cache
        best = min(
            float(subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout)
            for _ in range(3)
        )
        record.time(KEY, f"first array call, {n:.0e} speeds", best)
