r"""LIGGGHTS-PUBLIC 3.8 ``cohesion washino/capillary/viscous`` on ``gran model hertz``: a Rabinovich liquid
bridge with a viscous force, active out to its rupture distance.

Source read: ``src/cohesion_model_washino_capillary_viscous.h`` of CFDEMproject/LIGGGHTS-PUBLIC at the
3.8.0 release commit ``84ba3d76`` (what Debian's ``liggghts 3.8.0+repack1`` runs) and commit
``dbf4eb82`` (the contact-angle mixing). The code cites Rabinovich et al. 2005 (Langmuir
21:10992) eq. A11 in contact and eqs. 19, 20, A3 outside, and Nase et al. 2001 as cited by Shi &
McCarthy 2008 eqs. 40-41 for the viscous force.

What the code computes (``r_i``, ``r_j`` the radii, ``r_eff = r_i r_j/(r_i + r_j)``):

* bridge volume ``V_b = f (4/3 pi r_i^3 c_i + 4/3 pi r_j^3 c_j)`` with ``f`` = ``lbVolumeFraction``
  (default 0.05) and ``c`` = ``surfaceLiquidContentInitial`` (entering as a fraction, as in easo);
  at a primitive wall the wall holds no liquid (``V_b = f 4/3 pi r_i^3 c``);
* ``theta_eff = 0.5 theta_i theta_j`` in 3.8.0, a product where the documentation states the mean
  (the code's from ``dbf4eb82`` on): ``angle_mixing`` chooses;
* in contact: ``2 pi r_eff gamma cos(theta_eff)(1 + alpha (pi r_eff/(2 V_b))^(1/2))`` (eq. A11 with the
  code's ``dist = -alpha``) and the viscous force ``6 pi eta r_eff alpha_dot / s_min``;
* outside, while ``d < d_max = (1 + theta_eff/2) V_b^(1/3)`` and ``d < (maxSeparationDistanceRatio -
  1)(r_i + r_j)``: Rabinovich's force (:func:`~microimpact.core.models._capillary.rabinovich_code`)
  and ``6 pi eta r_eff alpha_dot / max(s_min, d/r_eff)``. Unlike easo, ``surfacesClose`` does not ask
  whether a contact came first: the bridge also pulls an approaching particle from ``d_max`` in.

At a wall (``fix wall/gran ... cohesion washino/capillary/viscous``, no warning): in contact the code
takes ``radj`` from the wall's contact data, where it is never set (0), so ``r_eff = 0``: no capillary
and no viscous force in contact; outside, ``surfacesClose`` sets ``radj = radi`` (``r_eff = R*/2``).
``two_spheres = 0`` (the default) computes this; ``two_spheres = 1`` two equal spheres of radius ``2 R*``.

Below a bridge volume of 1e-17 m^3 the code adds no cohesive force at all (``volBond1000 < 1e-14``,
"skip if bond volume too small", as in easo): the law does the same and flags it (bit 16 of
:func:`outside_validity`).

Speed ``V`` is the speed at first touch, as for every law here: a particle that comes from beyond
``d_max`` has been pulled in by the bridge (and slowed by its viscous force) on the way; its speed far
away is ``(V^2 - 2 W/m*)^(1/2)`` without viscosity (``W`` :func:`work`).

**Parameters of this model** (``params``, in this order): as
:mod:`~microimpact.core.models.liggghts_easo_capillary` (``surface_tension``, ``contact_angle``,
``liquid_content``, ``fluid_viscosity``, ``min_separation_ratio``, ``max_separation_ratio``,
``coefficient_restitution``, ``limit_force``, ``angle_mixing``, ``two_spheres``) and ``volume_fraction``
(``lbVolumeFraction``, used with ``modifyLbVolume on``; 0.05 otherwise).
"""

from __future__ import annotations

import math

from .._jit import jitable
from . import Parameter, checks
from . import _capillary as cap
from ._common import dem_outcome, in_bounds, nan_outcome
from .hertz_tsuji import alpha_coeff_restitution
from .liggghts_easo_capillary import PARAMETERS as _EASO_PARAMETERS
from .liggghts_easo_capillary import mixed_angle

NAME = "liggghts_washino_capillary"
TITLE = "LIGGGHTS-PUBLIC 3.8 cohesion washino/capillary/viscous (Rabinovich bridge + viscous force) on hertz"
CITATION = (
    "LIGGGHTS-PUBLIC 3.8, src/cohesion_model_washino_capillary_viscous.h (CFDEMproject, commit 84ba3d76); "
    "Rabinovich et al., Langmuir 21:10992 (2005)"
)
LABEL = "LIGGGHTS washino capillary"
STICKS = True
COST = "slow"
KIND = cap.WASHINO

PARAMETERS = _EASO_PARAMETERS + (
    Parameter(
        "volume_fraction",
        "1",
        "lbVolumeFraction: bridge volume over the liquid of both",
        0.05,
        low=0.0,
        high=1.0,
        low_open=True,
    ),
)
BOUNDS, validate = checks(NAME, PARAMETERS)

_VOL1000 = 1333.333333  # 4/3 * 1000, as the code writes it


@jitable
def constants(E, R, m, params):
    """The tuple ``q`` of :mod:`~microimpact.core.models._capillary` for this pair."""
    gamma, theta, c, eta, s_min, s_max = params[0], params[1], params[2], params[3], params[4], params[5]
    th = mixed_angle(theta, params)
    f = params[10]
    if params[9] == 1.0:
        r = 2.0 * R
        vol1000 = 2.0 * _VOL1000 * math.pi * r * r * r * c * f
        cut = (s_max - 1.0) * 2.0 * r
        r_eff_contact = 0.5 * r
    else:
        r = R
        vol1000 = _VOL1000 * math.pi * r * r * r * c * f
        cut = min((s_max - 1.0) * 2.0 * r, (1.1 * s_max - 1.0) * r)
        r_eff_contact = 0.0  # the wall's radj is never set in contact
    d_max = (1.0 + 0.5 * th) * vol1000 ** (1.0 / 3.0) * 0.1
    d_r = d_max if d_max < cut else cut
    a_T = alpha_coeff_restitution(params[6]) if params[6] < 1.0 else 0.0
    return cap.liggghts_floor((gamma, th, vol1000 * 0.001, r, r_eff_contact, 0.5 * r, s_min, d_r, a_T, params[7], eta))


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
    """The work [J] the bridge does from contact to rupture (without the viscous part)."""
    return cap.bridge_work(KIND, constants(E, R, m, params))


@jitable
def outside_validity(V, E, R, m, p_y, params):
    """16 where the bridge is below the code's volume floor, which leaves it without any cohesive force
    (:data:`~microimpact.core.models._capillary.LIGGGHTS_VOLUME_FLOOR`, the same in this model's source)."""
    return 16.0 if cap.below_liggghts_floor(constants(E, R, m, params)) else 0.0


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """Capture velocity [m/s] at first touch: ``(2 W/m*)^(1/2)`` where nothing dissipates and the contact
    holds no cohesion (a wall), else the bisection of :func:`microimpact.core.models._capillary.capture_speed`."""
    if not in_bounds(params, BOUNDS):
        return math.nan
    q = constants(E, R, m, params)
    if params[6] == 1.0 and params[3] == 0.0 and params[9] == 0.0:
        return math.sqrt(2.0 * cap.bridge_work(KIND, q) / m)
    return cap.capture_speed(KIND, E, R, m, q)
