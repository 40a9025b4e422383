"""The one table of quantities, for the application modules and the command line.

The names of :mod:`microimpact.core.quantities` (name, SI unit, description, equation, symbol,
display unit and scale, format and input check of every number microimpact reports or takes),
re-exported so that code outside the physics core, the CLI above all, reads labels from here.
"""

from __future__ import annotations

from .core.quantities import (
    FLAG_FIELDS,
    HISTORY_FIELDS,
    OUTCOME_FIELDS,
    QUANTITIES,
    Quantity,
    axis_label,
    column,
    columns,
    header,
    label,
    table,
    tex_unit,
)

__all__ = [
    "Quantity",
    "QUANTITIES",
    "OUTCOME_FIELDS",
    "FLAG_FIELDS",
    "HISTORY_FIELDS",
    "table",
    "label",
    "column",
    "columns",
    "header",
    "axis_label",
    "tex_unit",
]
