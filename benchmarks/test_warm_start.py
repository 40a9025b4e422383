"""11. Warm start of what needs the oblique universal table: ``microimpact oblique --alumina``, a script's
first compliant ``wall_interaction`` and ``microimpact export --tangential mindlin``, each a fresh process
with the cache on disk warm (the table stored by the warm-up run), interleaved run by run with
``python -c "import numpy"`` so that the ratios hold on a loaded machine; best of the rounds."""

import os
import subprocess
import sys
import tempfile
import time

KEY = "warm_start"

WALL = """
import numpy as np
from microimpact.wall import wall_interaction
v = np.array([[3.0, -10.0, 0.0]])
wall_interaction(v, np.array([0.0, 1.0, 0.0]), 5e-6, 1350.0, effective_modulus=1.31e9, limiting_pressure=156e6,
                 friction=0.3, tangential="mindlin", poisson_ratio=0.3)
"""

_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}  # as in test_startup


def test_warm_start(record, size):
    rounds = 5 if size["paper"] else 2
    with tempfile.TemporaryDirectory() as tmp:
        commands = {
            "python -c 'import numpy'": [sys.executable, "-c", "import numpy"],
            "microimpact oblique --alumina": [sys.executable, "-m", "microimpact", "oblique", "--alumina"],
            "first compliant wall_interaction (script)": [sys.executable, "-c", WALL],
            "microimpact export --tangential mindlin": [
                sys.executable,
                "-m",
                "microimpact",
                "export",
                "--tangential",
                "mindlin",
                "--friction",
                "0.3",
                "--poisson-ratio",
                "0.3",
                "--out",
                os.path.join(tmp, "export"),
            ],
        }
        best = dict.fromkeys(commands, float("inf"))
        for argv in commands.values():  # warm-up: bytecode, compiled loops and tables on disk
            subprocess.run(argv, check=True, capture_output=True, env=_ENV)
        for _ in range(rounds):
            for name, argv in commands.items():
                t0 = time.perf_counter()
                subprocess.run(argv, check=True, capture_output=True, env=_ENV)
                best[name] = min(best[name], time.perf_counter() - t0)
    for name, seconds in best.items():
        record.time(KEY, name, seconds)
