"""A pair shown to people: a few lines of text (:meth:`ContactPair.describe
<microimpact.pair.ContactPair.describe>`) and a table for notebooks, its effective values and yield point.

Every symbol and unit is its quantity's row of :data:`~microimpact.core.quantities.QUANTITIES` (the
SI unit: the values are printed unscaled), so the card says what the pair's attributes are.
"""

from __future__ import annotations

import html
import math

from ..core.quantities import QUANTITIES, unit_text

__all__ = ["describe", "html_table"]

#: The pair's attributes the card shows, by quantity: the effective values, then the yield point.
_EFFECTIVE = ("effective_modulus", "effective_radius", "effective_mass", "limiting_pressure")
_YIELD = ("yield_velocity", "yield_approach", "yield_force")


def _entry(pair, name) -> tuple[str, float, str]:
    """``(symbol, value, unit shown)`` of the pair's attribute ``name`` from its quantity's row."""
    q = QUANTITIES[name]
    return q.symbol, getattr(pair, name), unit_text(q.unit)


def _line(entries) -> str:
    return "   ".join(f"{sym} = {value:.6g} {unit}" for sym, value, unit in entries)


def html_table(pair) -> str:
    """The pair's effective values and yield point as an HTML table."""
    names = list(_EFFECTIVE)
    if pair.density is not None:
        names.append("density")
    if math.isfinite(pair.limiting_pressure):
        names += _YIELD[:2]
    rows = [_entry(pair, n) for n in names]
    body = "".join(f"<tr><td>{k}</td><td>{v:.6g}</td><td>{u}</td></tr>" for k, v, u in rows)
    return (
        f"<table><caption>ContactPair {html.escape(pair.label or 'unnamed')}</caption>"
        f"<tr><th>quantity</th><th>value</th><th>unit</th></tr>{body}</table>"
    )


def describe(pair) -> str:
    """:meth:`ContactPair.describe <microimpact.pair.ContactPair.describe>`."""
    lines = [f"pair: {pair.label or 'unnamed'}", "  " + _line(_entry(pair, n) for n in _EFFECTIVE)]
    if math.isfinite(pair.limiting_pressure):
        lines.append("  yield: " + _line(_entry(pair, n) for n in _YIELD))
    return "\n".join(lines)
