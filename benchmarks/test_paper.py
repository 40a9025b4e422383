"""6. ``microimpact paper`` end to end, in a subprocess writing to a temporary directory, and
``python -c "import matplotlib.pyplot"`` (what it cannot avoid) timed right after it."""

import os
import subprocess
import sys

import pytest

KEY = "paper"


def test_paper_end_to_end(timed, record, size, tmp_path):
    if not size["paper"]:
        pytest.skip("not run in tiny mode")
    pytest.importorskip("matplotlib")

    def run():
        proc = subprocess.run(
            [sys.executable, "-m", "microimpact", "paper", "--out", str(tmp_path)],
            capture_output=True,
            text=True,
            timeout=600,
        )
        assert proc.returncode == 0, proc.stderr[-2000:]

    timed(KEY, "end to end", run, rounds=1, warmup_rounds=0)
    timed(
        KEY,
        "python -c 'import matplotlib.pyplot'",
        lambda: subprocess.run([sys.executable, "-c", "import matplotlib.pyplot"], check=True, capture_output=True),
        rounds=3,
        warmup_rounds=1,
    )
    files = sum(len(f) for _, _, f in os.walk(tmp_path))
    record.metric(KEY, "files", files)
    assert files >= 20
