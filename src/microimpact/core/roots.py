"""The Illinois method's two moves, shared by the integrators that locate an event inside one of
their own steps (the zero of the event function in the step length, re-stepping from the step's
start).

The root is bracketed by ``a < b`` with ``g(a) > 0 > g(b)``: the functions that use these are
written to fall through zero. :func:`secant_point` is the regula falsi point of the bracket, or its
midpoint where rounding puts that point on or outside an end. :func:`illinois` moves the end the new
point replaces and, when the same end has moved twice in a row, halves the value kept at the other
end: plain regula falsi keeps one end fixed on a convex stretch and converges only linearly, the
halving pulls the next point across the root. Each caller keeps its own iteration limit and
tolerance, which are its numerics.
"""

from __future__ import annotations

from ._jit import jitable

__all__ = ["secant_point", "illinois"]


@jitable
def secant_point(a, b, ga, gb):
    """The regula falsi point of ``[a, b]`` with ``g(a) = ga > 0 > gb = g(b)``, or the midpoint where
    rounding puts it on or outside an end."""
    s = (a * gb - b * ga) / (gb - ga)
    if not (s > a and s < b):
        s = 0.5 * (a + b)
    return s


@jitable
def illinois(a, b, ga, gb, side, s, gs):
    """The bracket after ``g(s) = gs`` (not 0): ``(a, b, ga, gb, side)`` with ``s`` replacing the end of
    its sign, and the other end's value halved when that end was also kept the step before.
    ``side``: -1 when the last move replaced ``a``, 1 when it replaced ``b``, 0 before the first."""
    if gs > 0.0:
        a = s
        ga = gs
        if side == -1:
            gb *= 0.5
        side = -1
    else:
        b = s
        gb = gs
        if side == 1:
            ga *= 0.5
        side = 1
    return a, b, ga, gb, side
