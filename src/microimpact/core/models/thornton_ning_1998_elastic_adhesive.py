"""Elastic adhesive impact of Thornton & Ning (1998): JKR contact from first touch to the snap-off.

Source: Thornton, C. & Ning, Z. (1998), "A theoretical model for the stick/bounce behaviour of
adhesive, elastic-plastic spheres", *Powder Technology* 99:154-162, its elastic-adhesive part.
The paper itself was not available to this project; the law is read second-hand from two codes
that implement it and cite or name it, and every number below was reproduced from them:

* LIGGGHTS-PUBLIC ``src/normal_model_thornton_ning.h`` (CFDEMproject/LIGGGHTS-PUBLIC, commit
  ``84ba3d76``; the ``thornton_ning`` normal model): the pull-off force
  ``fc = gamma_s * reff * M_PI * (3./2.)`` (``fc = 3/2 pi G R*``, ``G = gamma_s`` the work of
  adhesion); first touch at the force ``force_old = -(8./9.)*fc`` with zero overlap; the JKR
  relation between the force ``f`` and the Hertz-equivalent load
  ``fl = f + 2 (fc + sqrt(fc (f + fc)))`` (``calculate_fl``) with the contact radius
  ``a = (3 R fl / (4 E))^(1/3)`` (``calculate_a``), i.e. ``f = P1 - 2 (fc P1)^(1/2)``,
  ``P1 = 4 E* a^3/(3 R*)``; and detachment at ``detaching_force = -(5./9.)*fc``.
* PyGran (anabiman/pygran-sim, ``pygran_sim/models.py`` at commit ``6156f9b3``, class
  ``ThorntonNing``, which cites Thornton & Ning 1998): the separation approach ``deltaf = -3/4 (pi^2 G^2 R*/E*^2)^(1/3)``.

In terms of ``b = a^(1/2)`` (as in :mod:`~microimpact.core.models.jkr_elastic_adhesive`, whose
``surface_energy`` is ``G/2``) the JKR curve is

.. math::  P = \\frac{4 E^* b^6}{3 R^*} - 4 E^* s\\, b^3, \\qquad
           \\alpha = \\frac{b^4}{R^*} - 2 s b, \\qquad s = \\left(\\frac{\\pi G}{2 E^*}\\right)^{1/2}.

The contact forms at zero approach, ``b_0^3 = 2 s R*`` (``P = -8/9 fc``), follows the curve in
loading and unloading (conservative), and snaps off where the approach is least,
``b_f^3 = s R*/2`` (``a_f = a_0 / 4^(2/3)``, ``alpha_f = -3/4 (pi^2 G^2 R*/E*^2)^(1/3)``,
``P = -5/9 fc``), past the force minimum ``-fc``. The energy lost is the work of the tensile
branch from ``b_0`` to ``b_f``,

.. math::  W = 7.0922\\, (G^5 R^{*4} / E^{*2})^{1/3},

(Thornton & Ning's 7.09, as quoted by a public LIGGGHTS input generator by A. Roy, University
of Birmingham, that cites them,
``workofadhesion = 7.09 * (surface_energy**5 * R_eq**4 / E_eq**2) ** (1 / 3)``; derived here in
closed form, the integrand being a polynomial in ``b``), so that ``e = (1 - V_s^2/V^2)^(1/2)`` with Thornton &
Ning's sticking velocity ``V_s = (2W/m*)^(1/2) = (14.18/m*)^(1/2) (G^5 R*^4/E*^2)^(1/6)``
(:func:`microimpact.core.adhesion.sticking_velocity`); the particle sticks (``e = 0``,
``contact_time = inf``) for ``V <= V_s``. The maximum approach solves the energy balance
(Newton's method); the loading time and the unloading time (back to zero approach, then along
the tensile branch to the snap-off) are Gauss-Legendre quadratures after substitutions that
remove the square-root singularities (shared with the JKR model).

It differs from :mod:`~microimpact.core.models.jkr_elastic_adhesive` (LAMMPS ``jkr``) only in
where the contact breaks: LAMMPS releases it at the force minimum ``-fc``, Thornton & Ning carry
it on to the least approach, where the contact radius jumps. The work lost is 2.025 times
LAMMPS's (7.0922 against 3.5026 in these units), and ``V_s`` 1.423 times larger.

**Parameters of this model** (``params``):

``work_of_adhesion`` ``G`` [J/m^2], ``>= 0``
    Thornton & Ning's interface energy (LIGGGHTS' ``surfaceEnergy``, twice LAMMPS' ``cohesion``
    of the ``jkr`` model); 0 gives Hertz's elastic impact.

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is 0
(no permanent deformation; the contact breaks at the negative approach ``alpha_f``).
``max_contact_radius`` is the JKR contact radius at the maximum approach; ``elastic`` is 0
(adhesion always takes energy). ``p_y`` is not used.

Validity: elastic spheres with short-range adhesion (the JKR limit: large, soft, strongly
adhesive particles); no plasticity (Thornton & Ning's plastic-adhesive unloading, on the
flattened radius with a larger pull-off force, is
:mod:`~microimpact.core.models.thornton_ning_1998_adhesive_plastic`; the additive rule of
:func:`microimpact.core.adhesion.restitution` combines the seed's plastic loss with ``V_s``);
no damping.
"""

from __future__ import annotations

import math

from .._jit import jitable
from . import Parameter, _jkr, checks, deprecated_names
from ._common import in_bounds
from ._jkr import b_of_alpha as _b_of_alpha
from ._jkr import force_b as _force_b
from ._jkr import work_integral as _G

NAME = "thornton_ning_1998_elastic_adhesive"
TITLE = "Elastic adhesive spheres, JKR from first touch to snap-off (Thornton & Ning 1998)"
CITATION = "Thornton & Ning, Powder Technol. 99:154 (1998)"
LABEL = "Thornton-Ning 1998 adhesive"
STICKS = True
PARAMETERS = (
    Parameter.of("work_of_adhesion", "G >= 0, interface energy (LIGGGHTS' surfaceEnergy)", low=0.0, normal=True),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(__name__, NAME)  # released DEFAULTS: one release, with a warning
#: Cost class of the outcome (the contract's ``OUTCOME_COST``): its contact times' quadrature, 0.8 ms a
#: point in Python (``e`` alone: 4 us).
OUTCOME_COST = "slow"

#: ``W / (G^5 R*^4 / E*^2)^(1/3)`` = 7.0922: the work of the tensile branch from ``b_0`` to ``b_f``,
#: evaluated with the antiderivative of ``P d alpha`` in ``b`` at ``G = R* = E* = 1``.
WORK_CONSTANT = _G((0.5 * math.sqrt(0.5 * math.pi)) ** (1.0 / 3.0), 1.0, 1.0, math.sqrt(0.5 * math.pi)) - _G(
    (2.0 * math.sqrt(0.5 * math.pi)) ** (1.0 / 3.0), 1.0, 1.0, math.sqrt(0.5 * math.pi)
)


@jitable
def pulloff_force(R, G):
    """``fc = 3/2 pi G R*`` [N] (LIGGGHTS ``normal_model_thornton_ning.h``)."""
    return 1.5 * math.pi * G * R


@jitable
def snapoff_approach(E, R, G):
    """``alpha_f = -3/4 (pi^2 G^2 R*/E*^2)^(1/3)`` [m]: the least approach, where the contact breaks."""
    return -0.75 * (math.pi * math.pi * G * G * R / (E * E)) ** (1.0 / 3.0)


@jitable
def sticking_work(E, R, G):
    """``W = 7.0922 (G^5 R*^4/E*^2)^(1/3)`` [J]: the work of the tensile branch, lost at each impact."""
    g2 = G * G
    return WORK_CONSTANT * ((g2 * g2) * G * ((R * R) * (R * R)) / (E * E)) ** (1.0 / 3.0)


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """Sticking velocity [m/s], ``V_s = (2 W/m*)^(1/2)`` with ``W`` the work of the tensile branch
    (:func:`sticking_work`; Thornton & Ning's eq. 54 with the exact constant 14.184): ``e = 0`` at and below it."""
    return math.sqrt(2.0 * sticking_work(E, R, params[0]) / m)


@jitable
def _curve(E, R, params):
    """``(valid, G, s, b_0, b_F)``: ``params`` in bounds, the adhesion and the JKR curve of these
    parameters (see the module docstring); zeros where invalid or without adhesion (Hertz)."""
    if not in_bounds(params, BOUNDS):
        return False, 0.0, 0.0, 0.0, 0.0
    G = params[0]
    if G == 0.0:
        return True, 0.0, 0.0, 0.0, 0.0
    s = math.sqrt(0.5 * math.pi * G / E)
    b0 = (2.0 * R * s) ** (1.0 / 3.0)
    bF = (0.5 * R * s) ** (1.0 / 3.0)
    return True, G, s, b0, bF


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
    """JKR force [N] at approach ``alpha >= alpha_f`` on the branch from first touch to snap-off."""
    G = params[0]
    if G == 0.0:
        a = math.sqrt(R * alpha) if alpha > 0.0 else 0.0
        return 4.0 * E * a * a * a / (3.0 * R)
    s = math.sqrt(0.5 * math.pi * G / E)
    return _force_b(_b_of_alpha(alpha, E, R, s), E, R, s)


@jitable
def ends_at_zero_force(params):
    """False: the contact ends at the least approach :func:`separation_approach`, not at zero force."""
    return False


@jitable
def separation_approach(E, R, m, p_y, params):
    """Approach [m] at which the contact breaks on unloading: ``alpha_f`` (:func:`snapoff_approach`)."""
    return snapoff_approach(E, R, params[0])


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N]: the JKR curve while in contact (from zero approach in loading down to
    ``alpha_f`` in unloading), zero outside."""
    if alpha_max <= 0.0 and alpha < 0.0:
        return 0.0
    if alpha < snapoff_approach(E, R, params[0]):
        return 0.0
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


#: The adhesion limit the law is written for (``"JKR"``: Tabor parameter large; ``"DMT"``: small):
#: :meth:`microimpact.pair.ContactPair.impact` flags pairs outside it
#: (:func:`microimpact.core.adhesion.tabor_parameter`).
ADHESION_LIMIT = "JKR"


@jitable
def work_of_adhesion(params):
    """The work of adhesion ``G`` [J/m^2] of ``params`` (``G`` itself), for Tabor's parameter."""
    return params[0]


@jitable
def tangential_contact_radius(alpha, alpha_max, E, R, m, p_y, params):
    """Contact radius [m] of the JKR curve at ``alpha`` (``a = b^2``, as :func:`signed_force` computes
    it), for a tangential spring (:mod:`microimpact.oblique.adhesive`)."""
    G = params[0]
    if G == 0.0:
        return math.sqrt(R * alpha) if alpha > 0.0 else 0.0
    b = _b_of_alpha(alpha, E, R, math.sqrt(0.5 * math.pi * G / E))
    return b * b
