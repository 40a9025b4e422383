"""Reproduce Section 3 of the seed paper with one call: figures, their data, and a report.

:func:`reproduce` (the ``microimpact paper`` command) writes the paper's Figures
2-10 (PNG and a vector format), the data behind each figure as CSV, and a report
(``report.md`` and a self-contained ``report.html``) that sets every number the
paper quotes in Section 3 beside the value the model gives now.

Only the paper's *quoted* numbers are constants here (:data:`PAPER_QUOTES`);
every computed value comes from the public API at run time
(:func:`compare_with_paper`).

One private module a subject: ``_claims`` (the quoted numbers and the
statements, checked), ``_driver`` (the figure driver and :class:`PaperReport`),
``_report`` (Markdown and HTML), ``_setup`` (the seed's cases, the figures'
inputs); the figures themselves are :mod:`microimpact.figures.paper`, the CSV
layout :func:`microimpact.io.write_table`. Every name is importable from here.

Seed: "Dynamic impact model of plastic deformation between micro-particles and
flat surfaces without adhesion", Aerosol Science and Technology 50(4):321-330 (2016).
"""

from __future__ import annotations

import warnings

from ._claims import PAPER_QUOTES, PAPER_STATEMENTS, check_statements, compare_with_paper
from ._driver import PaperReport, load_measurements, reproduce
from ._setup import (  # noqa: F401  (the figures' inputs, importable as before)
    DEFAULT_OUT_DIR,
    FIG3_PRESSURES,
    FIG4_MODULI,
    FIG4_SURFACE,
    FIG5_DENSITIES,
    FIG6_VELOCITIES,
    FIG7_VELOCITY,
    FIG9_MAX_VELOCITY,
    FIG10_VELOCITY,
    FIGURES,
    TOLERANCE,
)

__all__ = [
    "PAPER_QUOTES",
    "PAPER_STATEMENTS",
    "FIGURES",
    "DEFAULT_OUT_DIR",
    "TOLERANCE",
    "PaperReport",
    "compare_with_paper",
    "check_statements",
    "reproduce",
    "load_measurements",
]


def _write_table(path, table, title="", columns=None):
    from .. import io
    from ..figures import paper as figs
    from ._setup import SEED

    return io.write_table(path, table, title, figs.COLUMNS if columns is None else columns, f"seed: {SEED}")


def __getattr__(name):
    """``write_table`` and ``read_table`` moved to :mod:`microimpact.io`: one release of warnings."""
    if name in ("write_table", "read_table"):
        warnings.warn(
            f"microimpact.paper.{name} is deprecated; use microimpact.io.{name}"
            + (" (with columns=microimpact.figures.paper.COLUMNS)" if name == "write_table" else ""),
            DeprecationWarning,
            stacklevel=2,
        )
        if name == "write_table":
            return _write_table
        from ..io import read_table

        return read_table
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
