"""Adhesion at impact: Thornton & Ning's (1998) sticking velocity and the adhesive energy loss.

Thornton, C. & Ning, Z. (1998), "A theoretical model for the stick/bounce behaviour of adhesive,
elastic-plastic spheres", *Powder Technology* 99:154-162: the elastic-adhesive sticking velocity
``V_s = (14.18/m*)^(1/2) (G^5 R*^4/E*^2)^(1/6)`` (their eq. 54, in terms of the work of adhesion
``G``), and the adhesive loss entering the restitution as ``e^2 = e_p^2 - (V_s/V)^2``, the particle
sticking when ``e_p V <= V_s``. The constant is :data:`STICKING_CONSTANT`, derived (14.1844), not
the printed 14.18.
"""

from __future__ import annotations

import math

from ._jit import jitable
from .models.thornton_ning_1998_elastic_adhesive import WORK_CONSTANT
from .models.thornton_ning_2016 import restitution_at

__all__ = ["STICKING_CONSTANT", "sticking_velocity", "adhesive", "restitution", "capture_velocity"]

#: ``14.18439...``: the constant of Thornton & Ning's (1998) sticking velocity, ``V_s = (2 W_s/m*)^(1/2)``
#: (their eqs. 52, 54, numbered as in the transcription SOURCES.md names). It is twice the JKR work ``W_s`` (in units of ``(G^5 R*^4 / E*^2)^(1/3)``)
#: needed to pull a contact from zero approach (contact radius ``a_0``) to separation at
#: ``a_0 / 4^(2/3)``, with ``G`` the work of adhesion (pull-off force ``1.5 pi G R*``):
#: :data:`~microimpact.core.models.thornton_ning_1998_elastic_adhesive.WORK_CONSTANT`, the integral
#: in closed form, ``(2^(2/3) + 12 2^(1/3))/5 (pi/2)^(5/3) = 7.092196``. Their eq. 52 prints it
#: rounded as ``W_s = 0.9355 P_c alpha_f = 7.09 (...)^(1/3)`` and eq. 54 the constant as ``14.18``
#: (``2 x 7.09``); the exact value is 14.18439 (``0.9355`` is 0.935503 unrounded). Until issue 20
#: this module used the printed 14.18, which made ``V_s`` 1.5485e-4 (relative) smaller than the
#: elastic-adhesive model's own ``(2 W_s/m*)^(1/2)``; both now use the derived constant.
STICKING_CONSTANT = 2.0 * WORK_CONSTANT


@jitable
def sticking_velocity(G, E, R, m):
    """``V_s = (C/m*)^(1/2) (G^5 R*^4 / E*^2)^(1/6)`` [m/s] (Thornton & Ning 1998, eq. 54); 0 without adhesion.

    ``C`` = :data:`STICKING_CONSTANT`.

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
