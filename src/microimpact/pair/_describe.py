"""A pair shown to people: a few lines of text (:meth:`ContactPair.describe
<microimpact.pair.ContactPair.describe>`) and a table for notebooks, its effective values and yield point."""

from __future__ import annotations

import html
import math

__all__ = ["describe", "html_table"]


def html_table(pair) -> str:
    """The pair's effective values and yield point as an HTML table."""
    rows = [
        ("E*", pair.effective_modulus, "Pa"),
        ("R*", pair.effective_radius, "m"),
        ("m*", pair.effective_mass, "kg"),
        ("p_y", pair.limiting_pressure, "Pa"),
    ]
    if pair.density is not None:
        rows.append(("density", pair.density, "kg/m^3"))
    if math.isfinite(pair.limiting_pressure):
        rows += [("V_y", pair.yield_velocity, "m/s"), ("alpha_y", pair.yield_approach, "m")]
    body = "".join(f"<tr><td>{k}</td><td>{v:.6g}</td><td>{u}</td></tr>" for k, v, u in rows)
    return (
        f"<table><caption>ContactPair {html.escape(pair.label or 'unnamed')}</caption>"
        f"<tr><th>quantity</th><th>value</th><th>unit</th></tr>{body}</table>"
    )


def describe(pair) -> str:
    """:meth:`ContactPair.describe <microimpact.pair.ContactPair.describe>`."""
    lines = [
        f"pair: {pair.label or 'unnamed'}",
        f"  E* = {pair.effective_modulus:.6g} Pa   R* = {pair.effective_radius:.6g} m   "
        f"m* = {pair.effective_mass:.6g} kg   p_y = {pair.limiting_pressure:.6g} Pa",
    ]
    if math.isfinite(pair.limiting_pressure):
        lines.append(
            f"  yield: V_y = {pair.yield_velocity:.6g} m/s   alpha_y = {pair.yield_approach:.6g} m   "
            f"P_y = {pair.yield_force:.6g} N"
        )
    return "\n".join(lines)
