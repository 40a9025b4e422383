"""Elastic adhesive impact with the JKR contact law, as LAMMPS' ``pair_style granular`` ``jkr`` computes it.

The force of Johnson, Kendall & Roberts (1971, Proc. R. Soc. Lond. A 324, 301) between an elastic
sphere and a flat, written as in LAMMPS' ``doc/src/pair_granular.rst`` (normal model ``jkr``) in
terms of the contact radius ``a``:

.. math::  P = \\frac{4 E^* a^3}{3 R^*} - 2\\pi a^2 \\left(\\frac{4 \\gamma E^*}{\\pi a}\\right)^{1/2},
           \\qquad \\alpha = \\frac{a^2}{R^*} - 2 \\left(\\frac{\\pi \\gamma a}{E^*}\\right)^{1/2},

with the surface energy ``gamma`` (LAMMPS' ``cohesion``; JKR's work of adhesion is ``2 gamma``).
As in LAMMPS (``src/GRANULAR/gran_sub_mod_normal_kernel.h``: ``gran_normal_jkr_touch``,
``gran_normal_jkr_pulloff_distance``), the contact forms when the approach reaches zero (the force
jumps to ``-8/3 pi gamma R*``), follows the JKR curve in loading and unloading, and breaks at the
approach ``-delta_c``, ``delta_c = (3 pi^2/16)^(1/3) (R* gamma^2/E*^2)^(1/3)``, where the force is
the pull-off force ``-3 pi gamma R*`` (derived here: the force minimum of the curve lies at that
approach; LAMMPS doc: "a tensile force up to 3 pi gamma R, at which point they lose contact").
No damping (LAMMPS' damping coefficient 0).

The law is conservative along the curve, so the energy lost is the work of the tensile branch
between zero approach and pull-off, ``W = -int_{-delta_c}^{0} P d alpha``, in closed form (the
integrand is a polynomial in ``b = a^(1/2)``; derived here):

.. math::  W = E^* R^{*4/3} \\left(\\frac{\\pi\\gamma}{E^*}\\right)^{5/3} \\left[g(c_F) - g(c_0)\\right],
           \\quad g(c) = \\tfrac{8}{15} c^5 - \\tfrac{8}{3} c^{7/2} + 2 c^2 ,
           \\quad c_0 = 2^{2/3},\\ c_F = (3/2)^{2/3},

``g(c_F) - g(c_0) = 1.65015...``; ``e = (1 - 2 W/(m* V^2))^(1/2)``, and the particle sticks
(``e = 0``, ``contact_time = inf``) below the critical sticking speed ``V_s = (2 W/m*)^(1/2)``.
The maximum approach solves the energy balance (Newton's method on the polynomial in ``b``); the
loading and unloading times are the integrals ``int d alpha / |alpha'|``, computed by 48-point
Gauss-Legendre quadrature after the substitutions ``b = b_max - w^2`` (turning point) and
``b = b_F + w^2`` (pull-off, near the sticking speed) that remove the square-root singularities (agreement with the integration of :func:`force` to 1e-8 is tested).

**Parameters of this model** (``params``):

``surface_energy`` ``gamma`` [J/m^2], ``>= 0``
    LAMMPS' ``cohesion`` of the ``jkr`` normal model; 0 gives Hertz's elastic impact.

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is 0
(no permanent deformation; the contact breaks at the negative approach ``-delta_c``).
``max_contact_radius`` is the JKR contact radius at the maximum approach. ``p_y`` is not used.

Validity: elastic spheres with a short-range adhesion (JKR limit: large, soft, strongly adhesive
particles; Tabor parameter well above 1); no plasticity, no damping.
"""

from __future__ import annotations

import math

from .._jit import jitable
from . import Parameter, _jkr, checks, deprecated_names
from ._common import in_bounds

NAME = "jkr_elastic_adhesive"
TITLE = "JKR elastic adhesion, contact at zero approach, pull-off at -3 pi gamma R (LAMMPS granular jkr)"
CITATION = "Johnson, Kendall & Roberts, Proc. R. Soc. Lond. A 324:301 (1971); LAMMPS pair_style granular jkr"
LABEL = "JKR adhesive"
STICKS = True
PARAMETERS = (
    Parameter.of("surface_energy", "gamma >= 0, LAMMPS' cohesion (work of adhesion 2 gamma)", low=0.0, normal=True),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(__name__, NAME)  # released DEFAULTS: one release, with a warning
#: Cost class of the outcome (the contract's ``OUTCOME_COST``): its contact times' quadrature, 1.0 ms a
#: point in Python (``e`` alone: 4 us).
OUTCOME_COST = "slow"

#: ``g(c_F) - g(c_0)``: the pull-off work in units of ``E* R*^(4/3) (pi gamma/E*)^(5/3)``.
WORK_CONSTANT = (
    8.0 / 15.0 * (1.5 ** (2.0 / 3.0)) ** 5
    - 8.0 / 3.0 * (1.5 ** (2.0 / 3.0)) ** 3.5
    + 2.0 * (1.5 ** (2.0 / 3.0)) ** 2
    - (
        8.0 / 15.0 * (2.0 ** (2.0 / 3.0)) ** 5
        - 8.0 / 3.0 * (2.0 ** (2.0 / 3.0)) ** 3.5
        + 2.0 * (2.0 ** (2.0 / 3.0)) ** 2
    )
)


@jitable
def pulloff_approach(E, R, gamma):
    """``delta_c = (3 pi^2/16)^(1/3) (R* gamma^2/E*^2)^(1/3)`` [m]: the contact breaks at approach ``-delta_c``."""
    return (3.0 * math.pi * math.pi / 16.0) ** (1.0 / 3.0) * (R * gamma * gamma / (E * E)) ** (1.0 / 3.0)


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """Sticking velocity [m/s], ``V_s = (2 W/m*)^(1/2)`` with ``W`` the pull-off work
    ``WORK_CONSTANT E* R*^(4/3) (pi gamma/E*)^(5/3)``: ``e = 0`` at and below it."""
    gamma = params[0]
    W = WORK_CONSTANT * E * R ** (4.0 / 3.0) * (math.pi * gamma / E) ** (5.0 / 3.0)
    return math.sqrt(2.0 * W / m)


@jitable
def contact_radius(alpha, E, R, gamma):
    """JKR contact radius [m] at approach ``alpha`` (LAMMPS' closed form, ``gran_normal_jkr_contact_radius``)."""
    dR = alpha * R
    R2 = R * R
    dR2 = dR * dR
    t0 = gamma * gamma * R2 * R2 * E
    t1 = 27.0 * math.pi * math.pi * t0
    t2 = 8.0 * dR * dR2 * E * E * E
    t3 = 4.0 * dR2 * E
    s1 = t0 * (t1 + 2.0 * t2)
    if s1 < 0.0:
        s1 = 0.0
    t4 = (t1 + t2 + 3.0 * math.sqrt(3.0) * math.pi * math.sqrt(s1)) ** (1.0 / 3.0)
    t5 = t3 / t4 + t4 / E
    s2 = 2.0 * dR + t5
    if s2 < 0.0:
        s2 = 0.0
    t6 = math.sqrt(s2)
    s3 = 4.0 * dR - t5 + 6.0 * math.sqrt(6.0) * gamma * math.pi * R2 / (E * t6)
    if s3 < 0.0:
        s3 = 0.0
    return (t6 + math.sqrt(s3)) / math.sqrt(6.0)


@jitable
def _curve(E, R, params):
    """``(valid, gamma, s, b_0, b_F)``: ``params`` in bounds, the adhesion and the JKR curve of these
    parameters (see the module docstring); zeros where invalid or without adhesion (Hertz)."""
    if not in_bounds(params, BOUNDS):
        return False, 0.0, 0.0, 0.0, 0.0
    gamma = params[0]
    if gamma == 0.0:
        return True, 0.0, 0.0, 0.0, 0.0
    s = math.sqrt(math.pi * gamma / E)
    b0 = math.sqrt((2.0 * R * s) ** (2.0 / 3.0))
    bF = math.sqrt((1.5 * R * s) ** (2.0 / 3.0))
    return True, gamma, s, b0, bF


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (see the module docstring; ``p_y`` unused)."""
    valid, g, s, b0, bF = _curve(E, R, params)
    return _jkr.law_outcome(V, E, R, m, valid, g, s, b0, bF)


@jitable
def restitution_only(V, E, R, m, p_y, params):
    """``e`` [-] of :func:`outcome` alone, bit for bit (the contract's hook: fitting compares ``e``),
    without the maximum approach and the contact times' quadratures."""
    valid, g, s, b0, bF = _curve(E, R, params)
    return _jkr.law_restitution(V, E, R, m, valid, g, s, b0, bF)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """JKR force [N] at approach ``alpha >= -delta_c`` (contact radius from LAMMPS' closed form)."""
    gamma = params[0]
    if gamma == 0.0:
        a = math.sqrt(R * alpha) if alpha > 0.0 else 0.0
        return 4.0 * E * a * a * a / (3.0 * R)
    a = contact_radius(alpha, E, R, gamma)
    return 4.0 * E * a * a * a / (3.0 * R) - 2.0 * math.pi * a * a * math.sqrt(4.0 * gamma * E / (math.pi * a))


@jitable
def ends_at_zero_force(params):
    """False: the contact ends at the approach :func:`separation_approach`, not at zero force."""
    return False


@jitable
def separation_approach(E, R, m, p_y, params):
    """Approach [m] at which the contact breaks on unloading: ``-delta_c``."""
    return -pulloff_approach(E, R, params[0])


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N]: the JKR curve while in contact (from zero approach in loading down to
    ``-delta_c`` in unloading), zero outside."""
    if alpha_max <= 0.0 and alpha < 0.0:
        return 0.0
    if alpha < -pulloff_approach(E, R, params[0]):
        return 0.0
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


#: The adhesion limit the law is written for (``"JKR"``: Tabor parameter large; ``"DMT"``: small):
#: :meth:`microimpact.pair.ContactPair.impact` flags pairs outside it
#: (:func:`microimpact.core.adhesion.tabor_parameter`).
ADHESION_LIMIT = "JKR"


@jitable
def work_of_adhesion(params):
    """The work of adhesion ``G`` [J/m^2] of ``params`` (twice LAMMPS' ``cohesion``: ``2 gamma``), for Tabor's parameter."""
    return 2.0 * params[0]


@jitable
def tangential_contact_radius(alpha, alpha_max, E, R, m, p_y, params):
    """Contact radius [m] a tangential spring sees (:mod:`microimpact.oblique.adhesive`): the JKR radius
    of :func:`contact_radius`, positive at negative approach down to pull-off, as LAMMPS' ``jkr`` gives it
    to its ``mindlin`` tangential models (``GranSubModNormalJKR::calculate_contact_radius``)."""
    if params[0] == 0.0:
        return math.sqrt(R * alpha) if alpha > 0.0 else 0.0
    return contact_radius(alpha, E, R, params[0])
