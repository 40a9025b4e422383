"""Linear spring-dashpot (Hooke with viscous damping) with a constant coefficient of restitution.

The normal force of the DEM codes' ``hooke`` laws,

.. math::  P = k\\,\\alpha + \\eta\\,\\dot\\alpha ,
           \\qquad \\eta = \\left(\\frac{4 m^* k}{1 + (\\pi/\\ln e_n)^2}\\right)^{1/2} ,

with the damping coefficient ``eta`` [kg/s] that LAMMPS (``pair_style granular``, normal model
``hooke`` with ``damping coeff_restitution``; ``doc/src/pair_granular.rst``, damping section) and
LIGGGHTS-PUBLIC (``src/normal_model_hooke.h``: ``gamman = sqrt(4 meff kn / (1 + (pi/ln e)^2))``)
compute from the restitution coefficient ``e_n`` the user gives. ``pair_style gran/hooke`` of
LAMMPS writes the same force as ``k alpha + m* gamma_n alpha_dot`` (``doc/src/pair_gran.rst``), so
``gamma_n = eta / m*`` [1/s].

**Parameters of this model** (``params``, in this order):

``stiffness`` ``k`` [N/m]
    The spring constant, as DEM codes take it (``kn``). A linear spring has no contact mechanics
    of its own: ``k`` is a numerical choice (it sets the contact time, ``t_c ~ pi (m*/k)^(1/2)``),
    which is why it is a parameter and not derived from ``E*`` and ``R*``;
    :mod:`microimpact.calibrate` chooses it to match the seed's contact time.
``restitution`` ``e_n`` [-], in (0, 1]
    The coefficient of restitution the damping is computed from (what users of LAMMPS and
    LIGGGHTS enter); ``e_n`` is the input rather than ``eta`` because the law is used to impose a
    measured or calibrated ``e``.
``limit_force`` [0 or 1]
    The force-sign convention at the end of the contact. ``0`` (default; LAMMPS without
    ``limit_damping``, LIGGGHTS ``limitForce off``): the force is used as it is, turns attractive
    near the end of the contact, and the contact ends when the approach returns to zero; then
    ``e = e_n`` exactly. ``1`` (LAMMPS ``limit_damping``, LIGGGHTS ``limitForce on``): the force is clipped at zero and the particle leaves when it first
    vanishes, at ``alpha > 0``; the rebound is then faster, ``e > e_n``.

Closed form (solution of ``m* alpha'' + eta alpha' + k alpha = 0``, ``alpha(0) = 0``,
``alpha'(0) = V``; derived here and checked against the numerical integration of the same law in
``tests/core/test_models.py``): with ``omega_0 = (k/m*)^(1/2)``, ``beta = eta/(2 m*)``,
``omega = (omega_0^2 - beta^2)^(1/2)`` (note ``beta/omega = -ln(e_n)/pi``),

* ``alpha(t) = (V/omega) exp(-beta t) sin(omega t)``;
* maximum approach at ``omega t_m = atan2(omega, beta)``: ``alpha* = (V/omega_0) exp(-beta t_m)``;
* ``limit_force = 0``: the approach returns to zero at ``t_c = pi/omega``, with
  ``e = exp(-beta pi/omega) = e_n``, independent of ``V``;
* ``limit_force = 1``: the force vanishes at ``omega t_c = atan2(2 beta omega, 2 beta^2 - omega_0^2)``,
  and ``e = -alpha'(t_c)/V``, again independent of ``V``;
* maximum force: at ``t = 0`` (``eta V``) when ``omega_0^2 <= 4 beta^2``, otherwise at
  ``omega t_P = atan2((omega_0^2 - 4 beta^2) omega, beta (3 omega_0^2 - 4 beta^2))``.

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is the
approach where the contact ends: 0 with ``limit_force = 0``; with ``limit_force = 1`` the
deformation not yet recovered when the particle leaves (the spring is elastic: nothing is
permanent). ``max_contact_radius`` is the Hertz geometry ``(R* alpha*)^(1/2)``,
for comparison only. ``p_y`` is not used.

Validity: any speed (the law has no yield point and no speed dependence); it is a numerical
contact law, not contact mechanics: ``e`` does not depend on ``V``, unlike in every experiment on
elastic-plastic particles.
"""

from __future__ import annotations

import math

from .._jit import jitable
from . import LIMIT_FORCE, Parameter, checks, deprecated_names
from ._common import dem_outcome, in_bounds, nan_outcome

NAME = "linear_spring_dashpot"
TITLE = "Linear spring-dashpot, constant e (LAMMPS/LIGGGHTS hooke with coefficient of restitution)"
CITATION = "LAMMPS pair_style granular hooke, damping coeff_restitution; LIGGGHTS-PUBLIC normal_model_hooke.h"
LABEL = "linear spring-dashpot"
PARAMETERS = (
    Parameter("stiffness", "N/m", "spring constant k", low=0.0, low_open=True),
    Parameter.of(
        "restitution",
        "coefficient of restitution e_n the damping is computed from, in (0, 1]",
        low=0.0,
        high=1.0,
        low_open=True,
    ),
    LIMIT_FORCE._replace(default=0.0),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(__name__, NAME)  # released DEFAULTS: one release, with a warning
#: Order of the zero of :func:`signed_force` where the contact ends: ``k alpha + eta alpha_dot``
#: crosses zero with a slope (a simple zero).
ZERO_FORCE_ORDER = 1.0


@jitable
def damping_coefficient(k, e, m):
    """``eta = (4 m* k / (1 + (pi/ln e)^2))^(1/2)`` [kg/s] (LAMMPS ``coeff_restitution``, LIGGGHTS ``hooke``)."""
    le = math.log(e)
    if le == 0.0:
        return 0.0
    r = math.pi / le
    return math.sqrt(4.0 * m * k / (1.0 + r * r))


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (see the module docstring; ``E``, ``p_y`` unused)."""
    if not in_bounds(params, BOUNDS):
        return nan_outcome(V)
    k = params[0]
    limit = params[2] == 1.0
    eta = damping_coefficient(k, params[1], m)
    w0 = math.sqrt(k / m)
    b = 0.5 * eta / m
    w = math.sqrt(w0 * w0 - b * b)
    # maximum approach
    th_m = math.atan2(w, b)
    a_max = V / w0 * math.exp(-b * th_m / w)
    # end of contact
    if limit:
        th_c = math.atan2(2.0 * b * w, 2.0 * b * b - w0 * w0)
    else:
        th_c = math.pi
    dec = math.exp(-b * th_c / w)
    e = -dec * (math.cos(th_c) - b / w * math.sin(th_c))
    if not limit:
        e = dec  # cos(pi) = -1, sin(pi) = 0 exactly in exact arithmetic
    # maximum force
    p_max = eta * V
    if w0 * w0 > 4.0 * b * b:
        th_p = math.atan2((w0 * w0 - 4.0 * b * b) * w, b * (3.0 * w0 * w0 - 4.0 * b * b))
        s = math.sin(th_p)
        c = math.cos(th_p)
        p = m * V / w * math.exp(-b * th_p / w) * (w0 * w0 * s + 2.0 * b * (w * c - b * s))
        if p > p_max:
            p_max = p
    tL = th_m / w
    tU = (th_c - th_m) / w
    a_end = V / w * dec * math.sin(th_c) if limit else 0.0
    return dem_outcome(V, e, a_max, a_end, p_max, R, tL, tU)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """``P = k alpha + eta alpha_dot`` [N] before any clipping (negative: attractive)."""
    k = params[0]
    return k * alpha + damping_coefficient(k, params[1], m) * alpha_dot


@jitable
def ends_at_zero_force(params):
    """True when the contact ends where :func:`signed_force` vanishes (``limit_force`` 1), False when
    it ends where the approach returns to zero."""
    return params[2] == 1.0


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """``P = k alpha + eta alpha_dot`` [N]; clipped at zero when ``limit_force`` is 1."""
    p = signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)
    if params[2] == 1.0 and p < 0.0:
        return 0.0
    return p
