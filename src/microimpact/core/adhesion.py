"""Adhesion at impact: Thornton & Ning's (1998) sticking velocity and the adhesive energy loss.

Thornton, C. & Ning, Z. (1998), "A theoretical model for the stick/bounce behaviour of adhesive,
elastic-plastic spheres", *Powder Technology* 99:154-162: the elastic-adhesive sticking velocity
``V_s = (14.18/m*)^(1/2) (G^5 R*^4/E*^2)^(1/6)`` (their eq. 54, in terms of the work of adhesion
``G``), and the adhesive loss entering the restitution as ``e^2 = e_p^2 - (V_s/V)^2``, the particle
sticking when ``e_p V <= V_s``. The constant is :data:`STICKING_CONSTANT`, derived (14.1844), not
the printed 14.18.

**The whole law through two groups.** The whole adhesive elastic-plastic law of Thornton & Ning
(1998) (:mod:`~microimpact.core.models.thornton_ning_1998_adhesive_plastic`) has, for a sphere on a
flat, six inputs (``V``, ``E*``, ``R*``, ``m*``, ``p_y``, ``G``) and three units, so three groups; its
``e`` depends on two of them only. With ``a = a_y0 A`` (``a_y0 = pi p_y R*/(2 E*)``, the yield radius
without adhesion, seed eq. 4) the JKR loading (TN98 eqs. 49, 51), the yield cubic (eq. 65), the
plastic loading (eq. 69) and the unloading on ``R_p`` (eqs. 73, 76, 77) become, in units of
``P_y0 = 4 E* a_y0^3/(3 R*)`` and ``alpha_y0 = a_y0^2/R*``, functions of ``A`` and of the one number
``lambda = s R*/a_y0^(3/2)`` (``s = (pi G/(2 E*))^(1/2)``), ``lambda^2 = 4 G E*^2/(pi^2 p_y^3 R*)``
(the yield cubic is ``A^(3/2) - A^(1/2) - lambda = 0``). Energies scale with
``P_y0 alpha_y0``, that is with ``m* V_y^2`` (``V_y`` the seed's yield velocity, eq. 28). So
``e = f(V/V_y, lambda)``, and since ``(V_s/V_y)^2`` is ``lambda^(10/3)`` times a constant
(``V_s``: eq. 54 above), ``e = f(V/V_y, V_s/V_y)``: the same two groups as the additive rule's. The
tests hold both groups and change ``E*``, ``R*``, ``m*``, ``p_y`` and ``G`` (``e`` is the same to
rounding). :func:`whole_law_correction` is the whole law's ``e^2`` minus the additive rule's as a
function of the two groups; the wall interaction interpolates a table of it
(:func:`microimpact.adhesion.whole_law_table`) and :func:`corrected_restitution` adds it back.
"""

from __future__ import annotations

import math

from ._jit import jitable
from .models import thornton_ning_1998_adhesive_plastic as _whole
from .models.thornton_ning_1998_elastic_adhesive import WORK_CONSTANT
from .models.thornton_ning_2016 import restitution_at, yield_point

__all__ = [
    "STICKING_CONSTANT",
    "sticking_velocity",
    "adhesive",
    "restitution",
    "capture_velocity",
    "TABLE_LIMITING_PRESSURE",
    "whole_law_correction",
    "corrected_restitution",
    "EQUILIBRIUM_SEPARATION",
    "TABOR_JKR",
    "TABOR_DMT",
    "tabor_parameter",
]

#: ``14.18439...``: the constant of Thornton & Ning's (1998) sticking velocity, ``V_s = (2 W_s/m*)^(1/2)``
#: (their eqs. 52, 54, numbered as in the transcription SOURCES.md names). It is twice the JKR work ``W_s`` (in units of ``(G^5 R*^4 / E*^2)^(1/3)``)
#: needed to pull a contact from zero approach (contact radius ``a_0``) to separation at
#: ``a_0 / 4^(2/3)``, with ``G`` the work of adhesion (pull-off force ``1.5 pi G R*``):
#: :data:`~microimpact.core.models.thornton_ning_1998_elastic_adhesive.WORK_CONSTANT`, the integral
#: in closed form, ``(2^(2/3) + 12 2^(1/3))/5 (pi/2)^(5/3) = 7.092196``. Their eq. 52 prints it
#: rounded as ``W_s = 0.9355 P_c alpha_f = 7.09 (...)^(1/3)`` and eq. 54 the constant as ``14.18``
#: (``2 x 7.09``); the exact value is 14.18439 (``0.9355`` is 0.935503 unrounded). The printed 14.18
#: would make ``V_s`` 1.5485e-4 (relative) smaller than the elastic-adhesive model's own
#: ``(2 W_s/m*)^(1/2)``; both use the derived constant.
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


#: ``p_y/E*`` of the pair (``E* = R* = m* = 1``) for which :func:`whole_law_correction` computes the
#: whole law: any value gives the same ``e`` at the same two groups (module docstring).
TABLE_LIMITING_PRESSURE = 0.01


@jitable
def whole_law_correction(x, y):
    """``D = e^2 - (e_p^2 - (V_s/V)^2)`` [-] at ``x = V/V_y`` > 0 and ``y = V_s/V_y`` >= 0: the whole
    law's signed ``e^2`` (:func:`~microimpact.core.models.thornton_ning_1998_adhesive_plastic.rebound_energy_ratio`,
    not positive where it sticks) minus the additive rule's, unclamped (``e_p`` the seed's, eq. 27).

    Computed for the pair ``E* = R* = m* = 1``, ``p_y =`` :data:`TABLE_LIMITING_PRESSURE`, with the
    work of adhesion whose ``V_s`` (eq. 54) is ``y V_y``: ``G = (y V_y/C^(1/2))^(6/5)``. ``D = 0``
    exactly where the whole law does not yield (``e^2 = 1 - (V_s/V)^2`` in both) and at ``y = 0``
    (both are the seed's ``e_p^2``).
    """
    p_y = TABLE_LIMITING_PRESSURE
    Vy = yield_point(1.0, 1.0, 1.0, p_y)[2]
    V = x * Vy
    G = (y * Vy / math.sqrt(STICKING_CONSTANT)) ** 1.2 if y > 0.0 else 0.0
    Vs = sticking_velocity(G, 1.0, 1.0, 1.0)
    q = _whole.rebound_energy_ratio(V, 1.0, 1.0, 1.0, p_y, (G,))
    e_p = restitution_at(V, Vy)
    ratio = Vs / V
    return q - (e_p * e_p - ratio * ratio)


@jitable
def corrected_restitution(V, V_y, V_s, D):
    """``(e, stuck)`` with the whole law's correction ``D`` (:func:`whole_law_correction`, interpolated):
    ``e^2 = e_p(V/V_y)^2 - (V_s/V)^2 + D``, the particle sticking (``(0, 1)``) where that is not positive.
    """
    e_p = restitution_at(V, V_y)
    ratio = V_s / V if V > 0.0 else 0.0
    e2 = e_p * e_p - ratio * ratio + D
    if not e2 > 0.0:
        return 0.0, 1.0
    return math.sqrt(e2), 0.0


#: Default equilibrium separation ``z_0`` [m] of the surfaces in the Tabor parameter: 0.3 nm, within
#: the 0.2-0.4 nm the public transcriptions of Tabor's parameter give as typical (see
#: :func:`tabor_parameter`).
EQUILIBRIUM_SEPARATION = 0.3e-9
#: Tabor parameter above which the JKR limit applies (the laws of Thornton & Ning, LAMMPS' ``jkr``).
TABOR_JKR = 5.0
#: Tabor parameter below which the DMT limit applies (LAMMPS' ``dmt``).
TABOR_DMT = 0.1


@jitable
def tabor_parameter(E, R, G, z0):
    """Tabor's parameter ``mu = (R* G^2 / (E*^2 z_0^3))^(1/3)`` [-] (Tabor 1977, J. Colloid Interface
    Sci. 58:2): the elastic neck that adhesion pulls, ``(R* G^2/E*^2)^(1/3)``, over the range ``z_0``
    [m] of the surface forces; ``G`` [J/m^2] the work of adhesion, ``E*`` [Pa], ``R*`` [m].

    Tabor's paper was not read here; the definition is the one that public transcriptions found
    with the project's code search write alike (three independent files: two Rust contact-mechanics
    modules, "z0 the equilibrium atomic separation, typ. 0.2-0.4 nm", and a Julia tribology script),
    the JKR limit for ``mu`` large and the DMT limit for ``mu`` small. The thresholds
    :data:`TABOR_JKR` = 5 and :data:`TABOR_DMT` = 0.1 are the Julia script's (JKR above 5, DMT
    below 0.1, the transition between, which neither limit describes); a fourth transcription draws
    the lines at 2 and 0.5.
    """
    return (R * G * G / (E * E * z0 * z0 * z0)) ** (1.0 / 3.0)
