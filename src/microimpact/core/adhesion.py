"""Adhesion at impact: Thornton & Ning's (1998) sticking velocity and the adhesive energy loss.

Thornton, C. & Ning, Z. (1998), "A theoretical model for the stick/bounce behaviour of adhesive,
elastic-plastic spheres", *Powder Technology* 99:154-162: the elastic-adhesive sticking velocity
``V_s = (14.18/m*)^(1/2) (G^5 R*^4/E*^2)^(1/6)`` (in terms of the work of adhesion ``G``), and the adhesive loss entering the restitution as ``e^2 = e_p^2 - (V_s/V)^2``, the particle
sticking when ``e_p V <= V_s``.
"""

from __future__ import annotations

import math

from ._jit import jitable
from .models.thornton_ning_2016 import restitution_at

__all__ = ["STICKING_CONSTANT", "sticking_velocity", "adhesive", "restitution", "capture_velocity"]

#: ``14.18``: the constant of Thornton & Ning's (1998) sticking velocity. It is
#: ``2 x 7.092``, the JKR work (in units of ``(G^5 R*^4 / E*^2)^(1/3)``) needed to pull
#: a contact from zero approach (contact radius ``a_0``) to separation at
#: ``a_0 / 4^(2/3)``, with ``G`` the work of adhesion (pull-off force ``1.5 pi G R*``).
STICKING_CONSTANT = 14.18


@jitable
def sticking_velocity(G, E, R, m):
    """``V_s = (14.18/m*)^(1/2) (G^5 R*^4 / E*^2)^(1/6)`` [m/s] (Thornton & Ning 1998); 0 without adhesion.

    The integer powers as products (one ``pow`` left, the sixth root, skipped without adhesion): the
    same bits in Python, numba (which expands ``x**5`` into products itself) and C.
    """
    if not G > 0.0:
        return 0.0
    g2 = G * G
    return math.sqrt(STICKING_CONSTANT / m) * (g2 * g2 * G * ((R * R) * (R * R)) / (E * E)) ** (1.0 / 6.0)


@jitable
def adhesive(V, e_p, V_s):
    """``(e, stuck)``: ``e = (e_p^2 - (V_s/V)^2)^(1/2)``, or ``(0, 1)`` when ``e_p V <= V_s`` (sticks)."""
    if V_s > 0.0 and e_p * V <= V_s:
        return 0.0, 1.0
    ratio = V_s / V if V > 0.0 else 0.0
    return math.sqrt(max(e_p * e_p - ratio * ratio, 0.0)), 0.0


@jitable
def restitution(V, V_y, V_s):
    """``(e, stuck)`` of an adhesive elastic-plastic impact: the seed's ``e_p(V/V_y)`` (eq. 27) with the loss."""
    return adhesive(V, restitution_at(V, V_y), V_s)


@jitable
def capture_velocity(V_y, V_s):
    """Largest impact speed [m/s] at which the additive rule (:func:`restitution`) sticks: ``V_s`` up to
    ``V_y``, else the root of ``e_p(V/V_y) V = V_s`` (eq. 27; ``e_p V`` grows with ``V``), by bisection
    to rounding. 0 without adhesion."""
    if not V_s > 0.0:
        return 0.0
    if V_s <= V_y:
        return V_s
    lo = V_y
    hi = 2.0 * V_s
    while restitution_at(hi, V_y) * hi <= V_s:
        lo = hi
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:
            break
        if restitution_at(mid, V_y) * mid <= V_s:
            lo = mid
        else:
            hi = mid
    return lo
