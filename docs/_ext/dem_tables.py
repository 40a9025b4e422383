"""Build-time tables of ``dem_codes.rst`` from the stored DEM runs (no typed-in numbers).

On ``builder-inited`` this extension reads ``benchmarks/data/dem_runs.csv`` (written by
``benchmarks/dem_runs.py``, which runs LIGGGHTS and LAMMPS where they are installed) and writes
``docs/_generated/dem_thornton_ning.rst`` (the LIGGGHTS ``thornton_ning`` runs beside the closed
forms microimpact computes now) and ``docs/_generated/dem_other.rst`` (the other runs and the
time-step convergence), made by ``benchmarks/dem_runs.py::rst_tables``. The DEM codes are not needed to build the docs. A
failure is a Sphinx warning, hence an error under ``-W``.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

from sphinx.util import logging

logger = logging.getLogger(__name__)


def _script() -> Path:
    """``benchmarks/dem_runs.py`` of the checkout: beside these docs, or beside the imported sources."""
    import microimpact

    for root in (Path(__file__).resolve().parents[2], Path(microimpact.__file__).resolve().parents[2]):
        if (root / "benchmarks" / "dem_runs.py").is_file():
            return root / "benchmarks" / "dem_runs.py"
    raise FileNotFoundError("benchmarks/dem_runs.py (build the docs from a checkout)")


def load_script():
    """``benchmarks/dem_runs.py`` as a module (it is a script, not part of the package)."""
    spec = importlib.util.spec_from_file_location("dem_runs", _script())
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _write(app):
    out = Path(app.srcdir) / "_generated"
    out.mkdir(exist_ok=True)
    try:
        mod = load_script()
        tables = mod.rst_tables(mod.read_csv(mod.DEFAULT_OUT))
        texts = {"dem_thornton_ning.rst": tables[0], "dem_other.rst": "\n".join(tables[1:])}
    except Exception as exc:  # noqa: BLE001 - any failure must surface as a warning
        logger.warning(f"dem_tables: could not build the DEM tables: {exc!r}")
        texts = {"dem_thornton_ning.rst": "", "dem_other.rst": ""}
    for name, text in texts.items():
        target = out / name
        tmp = target.with_suffix(".rst.tmp")
        tmp.write_text(text)
        tmp.replace(target)


def setup(app):
    app.connect("builder-inited", _write)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
