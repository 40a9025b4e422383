"""Sphinx configuration of the microimpact documentation.

Build (warnings are errors, works offline)::

    sphinx-build -W --keep-going -b html docs docs/_build/html

No intersphinx (no network at build time). MathJax is referenced by the
rendered pages only (the browser loads it); nothing is fetched while building.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
# Prefer the checkout's sources when building from a clone without installing.
_SRC = HERE.parent / "src"
if _SRC.is_dir():
    sys.path.insert(0, str(_SRC))

os.environ.setdefault("MPLBACKEND", "Agg")

import microimpact  # noqa: E402

project = "microimpact"
author = "the microimpact developers"
copyright = "2026, the microimpact developers"
release = microimpact.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "matplotlib.sphinxext.plot_directive",
    "paper_comparison",  # docs/_ext: writes _generated/comparison.rst at build time
    "dem_tables",  # docs/_ext: writes _generated/dem_*.rst from benchmarks/data/dem_runs.csv
]

templates_path = ["_templates"]
exclude_patterns = ["_build", "_generated", "Thumbs.db", ".DS_Store"]
root_doc = "index"
language = "en"

# -- autodoc / autosummary / numpydoc ---------------------------------------
autosummary_generate = True
autosummary_imported_members = False
autodoc_typehints = "none"  # numpydoc sections carry the types and units
autodoc_member_order = "bysource"
numpydoc_show_class_members = False  # the class templates list members explicitly
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_attributes_as_param_list = True
numpydoc_validation_checks: set[str] = set()

# -- math -------------------------------------------------------------------
math_number_all = False
math_eqref_format = "({number})"
math_numfig = False

# -- plot directive (the gallery) ---------------------------------------------
plot_include_source = True
plot_html_show_source_link = False
plot_html_show_formats = False
plot_formats = [("png", 160)]
plot_rcparams = {"savefig.bbox": "tight"}
plot_pre_code = "import numpy as np\nimport matplotlib.pyplot as plt\nimport microimpact as mi\n"

# -- HTML ---------------------------------------------------------------------
html_theme = "alabaster"
html_title = f"microimpact {release}"
html_theme_options = {
    "description": "Elastic-plastic impact of micro-particles",
    "fixed_sidebar": True,
    "page_width": "1100px",
    "sidebar_width": "230px",
}
html_sidebars = {"**": ["about.html", "navigation.html", "searchbox.html"]}
html_show_sourcelink = False

nitpicky = False
suppress_warnings: list[str] = []
