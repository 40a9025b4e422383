r"""LIGGGHTS-PUBLIC 3.8 ``cohesion easo/capillary/viscous`` on ``gran model hertz``: a liquid bridge that
forms at contact and breaks at its rupture distance.

Source read: ``src/cohesion_model_easo_capillary_viscous.h`` of CFDEMproject/LIGGGHTS-PUBLIC at the
3.8.0 release commit ``84ba3d76`` (what Debian's ``liggghts 3.8.0+repack1`` runs), and the later
commits ``ce1931e3`` (the wall fix below) and ``9805a233`` (the contact-angle mixing). The code
cites Soulie et al. 2006 (Int. J. Numer. Anal. Meth. Geomech. 30:213) eqs. 13-14 for the capillary
force, Nase et al. 2001 as cited by Shi & McCarthy 2008 (Powder Technol. 184:65) eqs. 40-41 for the
viscous force and Lian et al. 1993 for the rupture distance.

What the code computes, for one pair (``r_i``, ``r_j`` the radii; at a wall the code sets
``radj = radi`` and ``radsum = radi``):

* bridge volume ``V_b = sum_k 1/2 (4/3 pi r_k^3 c) (1 - (1 - r_other^2/radsum^2)^(1/2))`` with ``c``
  the ``surfaceLiquidContentInitial`` (written as ``1333.333333 pi r^3 c`` for 1000 times the
  volume, so ``c`` enters as a fraction of the solid volume, though the documentation says %).
  Two equal spheres: ``V_b = (4/3 pi r^3 c)(1 - 3^(1/2)/2)``; at a wall (dry: no wall liquid)
  ``V_b = 1/2 (4/3 pi r^3 c)``;
* effective contact angle ``theta_eff = 0.5 * theta_i * theta_j`` in 3.8.0 (a product, in rad^2,
  where the documentation states the mean; the code takes the mean ``0.5 (theta_i + theta_j)`` from
  ``9805a233`` on): the parameter ``angle_mixing`` chooses (0: the code as released, 1: the mean);
* in contact (``surfacesIntersect``) a constant attraction ``pi gamma (r_i r_j)^(1/2) (exp(B) + C)``
  (Soulie at zero separation) and the viscous force ``6 pi eta r_eff alpha_dot / s_min``,
  ``r_eff = r_i r_j/(r_i + r_j)``, ``s_min`` = ``minSeparationDistanceRatio``;
* outside (``surfacesClose``), once a contact has set the bridge flag: ``pi gamma (r_i r_j)^(1/2)
  (exp(A d/R_2 + B) + C)`` with ``R_2`` the larger radius and the viscous force ``6 pi eta r_eff
  alpha_dot / max(s_min, d/r_eff)``, while ``d < d_max = (1 + theta_eff/2) V_b^(1/3)`` and
  ``d < (maxSeparationDistanceRatio - 1)(r_i + r_j)``; beyond either the bridge breaks for good;
* on top of LIGGGHTS' Hertz normal model with its damping (:mod:`~microimpact.core.models.hertz_tsuji`,
  ``alpha_T`` from ``coefficientRestitution``); the cohesion force is added after the Hertz force
  (and after ``limitForce`` clipped it).

At a wall (``fix wall/gran ... cohesion easo/capillary/viscous``): the constructor warns "only
supports dry walls". In 3.8.0 ``surfacesClose`` reads the velocity ``v[j]`` of atom ``j``, which at a
primitive wall is ``-(wall type)``: the run dies with a segmentation fault as soon as the particle
leaves the wall with a bridge (reproduced in ``tests/laws/test_capillary_bridges.py``). Commit
``ce1931e3`` reads the wall's velocity instead. ``two_spheres = 0`` (the default, the wall) computes
what the fixed code computes there (``r_i = r_j = R*``: ``r_eff = R*/2``), flagged by
:func:`outside_validity` as a law the released binary cannot run; ``two_spheres = 1`` two equal spheres of
radius ``2 R*`` (mass ``2 m*``), which 3.8.0 runs.

Below a bridge volume of 1e-17 m^3 the code adds no cohesive force at all ("skip if bond volume too
small", ``volBond1000 < 1e-14``, in both ``surfacesIntersect`` and ``surfacesClose``): a 6 um sphere
with 1 % liquid bounces in LIGGGHTS as if dry. The law does the same (and flags it, bit 16 of
:func:`outside_validity`); :mod:`~microimpact.core.models.willett_capillary` gives the bridge's physics.

The force law and its integration are in :mod:`~microimpact.core.models._capillary`.

**Parameters of this model** (``params``, in this order; the code's own inputs):

``surface_tension`` ``gamma`` [N/m] (``surfaceTension``), ``contact_angle`` ``theta`` [deg]
(``contactAngle``, one type, in degrees: the code reads degrees and works in radians), ``liquid_content`` ``c`` [-] (``surfaceLiquidContentInitial``),
``fluid_viscosity`` ``eta`` [Pa s] (``fluidViscosity``), ``min_separation_ratio`` ``s_min``
(``minSeparationDistanceRatio``), ``max_separation_ratio`` (``maxSeparationDistanceRatio`` >= 1),
``coefficient_restitution`` ``e_n`` (Hertz damping input), ``limit_force`` (``limitForce``),
``angle_mixing`` (0 code, 1 mean), ``two_spheres`` (0 wall, 1 two equal spheres).

Fields: ``plastic_approach`` is ``-d_r`` (the approach where the bridge breaks); ``unloading_time``
runs from the maximum approach to rupture. ``p_y`` is not used.
"""

from __future__ import annotations

import math

from .._jit import jitable
from . import LIMIT_FORCE, Parameter, checks
from . import _capillary as cap
from ._common import dem_outcome, in_bounds, nan_outcome
from .hertz_tsuji import alpha_coeff_restitution

NAME = "liggghts_easo_capillary"
TITLE = "LIGGGHTS-PUBLIC 3.8 cohesion easo/capillary/viscous (Soulie bridge + viscous force) on hertz"
CITATION = (
    "LIGGGHTS-PUBLIC 3.8, src/cohesion_model_easo_capillary_viscous.h (CFDEMproject, commit 84ba3d76); "
    "Soulie et al., Int. J. Numer. Anal. Meth. Geomech. 30:213 (2006)"
)
LABEL = "LIGGGHTS easo capillary"
STICKS = True
COST = "slow"
KIND = cap.EASO

PARAMETERS = (
    Parameter.of("surface_tension", default=0.072, low=0.0, low_open=True),
    Parameter.of("contact_angle", default=0.0, low=0.0, high=90.0),
    Parameter.of("liquid_content", low=0.0, high=1.0, low_open=True),
    Parameter.of("fluid_viscosity", default=0.0, low=0.0),
    Parameter.of("min_separation_ratio", default=1.01, low=0.0, low_open=True),
    Parameter.of("max_separation_ratio", default=1.1, low=1.0),
    Parameter.of("coefficient_restitution", default=1.0, low=0.0, high=1.0, low_open=True),
    LIMIT_FORCE._replace(default=0.0),
    Parameter.of("angle_mixing", default=0.0, flag=True),
    Parameter.of("two_spheres", default=0.0, flag=True),
)
BOUNDS, validate = checks(NAME, PARAMETERS)

#: ``4/3 * 1000`` as the code writes it (its volumes are 1000 times the liquid volume).
_VOL1000 = 1333.333333


@jitable
def mixed_angle(theta, params):
    """``theta_eff`` [rad] of one type with itself, from its ``contactAngle`` ``theta`` [deg] (the code
    turns degrees into radians when it reads them, ``global_properties.cpp``): ``0.5 theta^2`` in
    radians (3.8.0, a product) or ``theta`` (the mean)."""
    t = theta * math.pi / 180.0
    return t if params[8] == 1.0 else 0.5 * t * t


@jitable
def constants(E, R, m, params):
    """The tuple ``q`` of :mod:`~microimpact.core.models._capillary` for this pair."""
    gamma, theta, c, eta, s_min, s_max = params[0], params[1], params[2], params[3], params[4], params[5]
    th = mixed_angle(theta, params)
    if params[9] == 1.0:  # two equal spheres of radius 2 R*
        r = 2.0 * R
        vol1000 = 2.0 * 0.5 * _VOL1000 * math.pi * r * r * r * c * (1.0 - math.sqrt(1.0 - 0.25))
        cut = (s_max - 1.0) * 2.0 * r
    else:  # wall: radj = radsum = radi, no wall liquid
        r = R
        vol1000 = 0.5 * _VOL1000 * math.pi * r * r * r * c
        # the bridge breaks at (s_max - 1)(radi + radj); the wall forgets the contact beyond
        # (1.1 s_max - 1) radi, its contact distance
        cut = min((s_max - 1.0) * 2.0 * r, (1.1 * s_max - 1.0) * r)
    d_max = (1.0 + 0.5 * th) * vol1000 ** (1.0 / 3.0) * 0.1
    d_r = d_max if d_max < cut else cut
    r_eff = 0.5 * r
    a_T = alpha_coeff_restitution(params[6]) if params[6] < 1.0 else 0.0
    return cap.liggghts_floor((gamma, th, vol1000 * 0.001, r, r_eff, r_eff, s_min, d_r, a_T, params[7], eta))


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact at contact speed ``V`` (module docstring), by integration."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    q = constants(E, R, m, params)
    if V == 0.0:
        return dem_outcome(V, 0.0, 0.0, -q[7], 0.0, R, 0.0, math.inf)
    e, x_max, p_max, tL, tU = cap.integrate(KIND, V, E, R, m, q)
    return dem_outcome(V, e, x_max, -q[7], p_max, R, tL, tU)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N] (attractive < 0): :func:`microimpact.core.models._capillary.signed_force`."""
    return cap.signed_force(KIND, alpha, alpha_dot, E, R, m, constants(E, R, m, params))


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """The same as :func:`signed_force`: the bridge's pull is part of the law."""
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


@jitable
def separation_approach(E, R, m, p_y, params):
    """``-d_r`` [m]: the bridge breaks at surface distance ``d_r``."""
    return -constants(E, R, m, params)[7]


@jitable
def work(E, R, m, params):
    """The work [J] the bridge takes from a particle from contact to rupture (without the viscous part)."""
    return cap.bridge_work(KIND, constants(E, R, m, params))


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """Capture velocity [m/s]: ``(2 W/m*)^(1/2)`` where nothing dissipates (``e_n = 1``, ``eta = 0``:
    the constant pull in contact does no net work), else the bisection of
    :func:`microimpact.core.models._capillary.capture_speed`."""
    if not in_bounds(params, BOUNDS):
        return math.nan
    q = constants(E, R, m, params)
    if params[6] == 1.0 and params[3] == 0.0:
        return math.sqrt(2.0 * cap.bridge_work(KIND, q) / m)
    return cap.capture_speed(KIND, E, R, m, q)


@jitable
def outside_validity(V, E, R, m, p_y, params):
    """8 at a wall (``two_spheres = 0``): the released 3.8.0 binary crashes there once the bridge forms
    (module docstring); the law is what the fixed code computes. 16 where the bridge is below the
    code's volume floor, which leaves it without any cohesive force (:data:`~microimpact.core.models._capillary.LIGGGHTS_VOLUME_FLOOR`)."""
    code = 8.0 if params[9] == 0.0 else 0.0
    if cap.below_liggghts_floor(constants(E, R, m, params)):
        code += 16.0
    return code
