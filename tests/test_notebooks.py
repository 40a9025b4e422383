"""The gallery's notebooks (written by sphinx-gallery from ``examples/``) run top to bottom.

sphinx-gallery turns every example script into a Jupyter notebook, offered for download on
its page. One of them (the fit, which prints its estimate and draws two figures) is executed
here with nbclient in a fresh kernel: every cell runs without error, the printed estimate
holds the true value in its interval, and the figures come out as PNG outputs.

Skipped, with the reason, when the docs have not been built (``docs/gallery/`` is written by
the build) or nbclient / ipykernel are missing (the ``docs`` extra has them).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
GALLERY = Path(os.environ.get("MICROIMPACT_GALLERY", ROOT / "docs" / "gallery"))
NOTEBOOK = GALLERY / "applications" / "plot_fit.ipynb"

nbformat = pytest.importorskip("nbformat", reason="nbformat is not installed (pip install 'microimpact[docs]')")
nbclient = pytest.importorskip("nbclient", reason="nbclient is not installed (pip install 'microimpact[docs]')")
pytest.importorskip("ipykernel", reason="ipykernel is not installed (pip install 'microimpact[docs]')")
pytestmark = pytest.mark.skipif(
    not NOTEBOOK.is_file(), reason=f"no generated notebook at {NOTEBOOK} (build the docs first)"
)


def test_fit_notebook_executes(tmp_path, monkeypatch):
    monkeypatch.delenv("MPLBACKEND", raising=False)  # the kernel's inline backend, as in Jupyter
    nb = nbformat.read(NOTEBOOK, as_version=4)
    assert sum(c.cell_type == "code" for c in nb.cells) >= 3
    env_dir = tmp_path  # the kernel's working directory: nothing is written beside the docs
    client = nbclient.NotebookClient(
        nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(env_dir)}}
    )
    client.execute()
    text = "".join(
        out.get("text", "") for cell in nb.cells if cell.cell_type == "code" for out in cell.get("outputs", [])
    )
    m = re.search(r"p_y = ([\d.]+) MPa, 95 % interval ([\d.]+) to ([\d.]+) MPa", text)
    assert m, text
    p, lo, hi = map(float, m.groups())
    assert lo < 156.0 < hi and lo < p < hi  # the synthetic data were made with p_y = 156 MPa
    pngs = [
        out
        for cell in nb.cells
        if cell.cell_type == "code"
        for out in cell.get("outputs", [])
        if "image/png" in out.get("data", {})
    ]
    assert len(pngs) >= 2, "the fit and the band half-width figures"
