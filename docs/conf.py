"""Sphinx configuration of the microimpact documentation.

Build (warnings are errors, works offline)::

    sphinx-build -W --keep-going -b html docs docs/_build/html

No intersphinx (no network at build time). Math is typeset in the browser by
the copy of MathJax 3 that ``sphinx-mathjax-offline`` ships and copies into
``_static/mathjax``: the pages need no network to show their formulas. The
gallery is built by sphinx-gallery from the scripts in ``examples/``, each run
during the build.
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
    "sphinx-mathjax-offline",  # MathJax 3 served from _static/mathjax (no CDN)
    "numpydoc",
    "matplotlib.sphinxext.plot_directive",
    "sphinx_gallery.gen_gallery",
    "paper_comparison",  # docs/_ext: writes _generated/comparison.rst at build time
    "dem_tables",  # docs/_ext: writes _generated/dem_*.rst from benchmarks/data/dem_runs.csv
]

templates_path = ["_templates"]
exclude_patterns = ["_build", "_generated", "Thumbs.db", ".DS_Store", "gallery/**/*.ipynb", "gallery/**/*.py"]
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

# -- sphinx-gallery: examples/*.py, run at build time -> gallery/ ---------------
sphinx_gallery_conf = {
    "examples_dirs": "../examples",  # relative to this file (the test copies docs/ and examples/ side by side)
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",  # run every example (not only the default plot_ prefix in a subfolder)
    # fit_values_above_one.py is a command-line script (it writes a folder), shown in the fitting how-to
    "ignore_pattern": r"__init__\.py|fit_values_above_one\.py",
    "within_subsection_order": "FileNameSortKey",
    "subsection_order": ["../examples/paper", "../examples/applications"],
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "remove_config_comments": True,
    "download_all_examples": True,
    "show_memory": False,
    "show_signature": False,
    "min_reported_time": 1.0,
    "backreferences_dir": None,
    "write_computation_times": False,
    "first_notebook_cell": None,
    "capture_repr": (),  # show what the scripts print, not the repr of a last Axes call
}

# -- plot directive (the how-to pages) -----------------------------------------
plot_include_source = True
plot_html_show_source_link = False
plot_html_show_formats = False
plot_formats = [("png", 160)]
plot_rcparams = {"savefig.bbox": "tight"}
plot_pre_code = "import numpy as np\nimport matplotlib.pyplot as plt\nimport microimpact as mi\n"

# -- HTML ---------------------------------------------------------------------
html_theme = "furo"
html_title = f"microimpact {release}"
html_theme_options = {"navigation_with_keys": True}
html_static_path = ["_static"]
html_css_files = ["microimpact.css"]
html_show_sourcelink = False

nitpicky = False
suppress_warnings: list[str] = []


# -- the sidebar ----------------------------------------------------------------
# furo draws the whole site tree, every level expanded, in every page's sidebar: with one page per
# public name (autosummary, ~490 pages) that is ~650 entries per page, and computing and parsing
# that tree for each of the ~550 pages was ~90% of the build's time (profiled). The sidebar shows
# the top levels and the branch of the page at hand, expanded to every depth (Sphinx's ``collapse``):
# an API page still lists its module's siblings; the module pages list their names in a table.
def _sidebar_collapsed(app, pagename, templatename, context, doctree):
    toctree = context.get("toctree")
    if toctree is None:
        return

    def collapsed(**kwargs):
        kwargs["collapse"] = True
        return toctree(**kwargs)

    context["toctree"] = collapsed


def setup(app):
    # before furo's own handler (priority 500), which calls context["toctree"]
    app.connect("html-page-context", _sidebar_collapsed, priority=400)
