r"""Rabinovich et al. 2005's capillary bridge (eqs. 19, 20, A3) with Willett's rupture distance, as Yade
writes them, on an elastic Hertz contact.

Source read: ``pkg/dem/ViscoelasticCapillarPM.cpp`` of bchareyre/yade-mpi at commit ``122e63b3``
(``Law2_ScGeom_ViscElCapPhys_Basic::go`` and ``Rabinovich_f``; equation numbers from its comments,
Rabinovich, Esayanur & Moudgil 2005, Langmuir 21:10992, and Lambert et al. 2008 eq. 65):

* ``d_sp = H/2 (-1 + (1 + 2 V_b/(pi R H^2))^(1/2))`` (eq. 20), ``a = (H/R (-1 + (1 + 2 V_b/(pi R
  H^2))^(1/2)))^(1/2)`` (eq. A3), ``F = 2 pi R gamma cos(theta)/(1 + H/(2 d_sp)) + 2 pi R gamma
  sin(a) sin(theta + a)`` (eq. 19; the first term in Lambert's eq. 65 form) at a separation
  ``0 < H < s_c``; at ``H = 0`` exactly Yade takes ``a = 0``: ``2 pi R gamma cos(theta)``;
* the bridge, its creation at first contact, Yade's ``R`` (``2 R*`` between two spheres, ``R*`` at a
  wall) and its rupture distance are those of :mod:`~microimpact.core.models.willett_capillary`: Yade
  computes ``s_c`` by Willett's eq. 15 for every capillary type;
* no capillary force in contact; here an undamped Hertz contact carries it.

Energy balance: ``W = int_0^s_c F dH`` (Gauss-Legendre, :func:`microimpact.core.models._capillary.bridge_work`),
``e = (1 - 2 W/(m* V^2))^(1/2)``, capture velocity ``(2 W/m*)^(1/2)``.

**Parameters**: as :mod:`~microimpact.core.models.willett_capillary` (``liquid_volume``,
``surface_tension``, ``contact_angle`` [deg], ``two_spheres``).
"""

from __future__ import annotations

import math

from .. import hertz
from .._jit import jitable
from . import _capillary as cap
from . import checks
from ._common import dem_outcome, in_bounds, nan_outcome
from .willett_capillary import PARAMETERS
from .willett_capillary import constants as _willett_constants

NAME = "rabinovich_capillary"
TITLE = "Rabinovich et al. 2005 capillary bridge (eqs. 19, 20, A3; Willett's rupture) as Yade writes it, on Hertz"
CITATION = "Rabinovich, Esayanur & Moudgil, Langmuir 21:10992 (2005); Yade pkg/dem/ViscoelasticCapillarPM.cpp"
LABEL = "Rabinovich capillary"
STICKS = True
OUTCOME_COST = "slow"
KIND = cap.RABINOVICH
BOUNDS, validate = checks(NAME, PARAMETERS)


@jitable
def constants(E, R, m, params):
    """Yade's ``R`` and ``s_c``: the same as Willett's."""
    return _willett_constants(E, R, m, params)


@jitable
def work(E, R, m, params):
    """The bridge's work [J] from contact to rupture (quadrature)."""
    return cap.bridge_work(KIND, constants(E, R, m, params))


@jitable
def restitution_only(V, E, R, m, p_y, params):
    """``e = (1 - 2 W/(m* V^2))^(1/2)``, 0 at and below the capture velocity (energy balance): the
    field ``restitution`` of :func:`outcome`, bit for bit (NaN where it is NaN, at ``V = inf`` too)."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return math.nan
    mv2 = m * V * V  # 0 at a speed whose square underflows: captured, as at V = 0
    x = 1.0 - 2.0 * work(E, R, m, params) / mv2 if mv2 > 0.0 else -1.0
    return math.sqrt(x) if x > 0.0 else 0.0


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome at contact speed ``V``: ``e`` by the energy balance, the times by integration (a captured
    particle: Hertz's loading in closed form, ``unloading_time = inf``)."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    q = constants(E, R, m, params)
    e = restitution_only(V, E, R, m, p_y, params)
    if V == 0.0:
        return dem_outcome(V, 0.0, 0.0, -q[7], 0.0, R, 0.0, math.inf)
    if e == 0.0:  # captured: the bridge acts outside the contact only, so the loading is Hertz's, in closed
        # form (an integration in metres and seconds stalls at speeds near the smallest floats)
        a_m = hertz.max_approach(V, E, R, m)
        return dem_outcome(V, 0.0, a_m, -q[7], hertz.force(a_m, E, R), R, hertz.half_period(V, E, R, m), math.inf)
    run = cap.integrate(KIND, V, E, R, m, q)  # the times, and the maximum approach and force
    tU = run[4] if e > 0.0 else math.inf
    return dem_outcome(V, e, run[1], -q[7], run[2], R, run[3], tU)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Hertz in contact, Rabinovich's bridge out to ``s_c`` [N] (attractive < 0)."""
    return cap.signed_force(KIND, alpha, alpha_dot, E, R, m, constants(E, R, m, params))


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """The same as :func:`signed_force`."""
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


@jitable
def separation_approach(E, R, m, p_y, params):
    """``-s_c`` [m] (Willett's eq. 15)."""
    return -constants(E, R, m, params)[7]


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """Capture velocity ``(2 W/m*)^(1/2)`` [m/s]."""
    if not in_bounds(params, BOUNDS):
        return math.nan
    return math.sqrt(2.0 * work(E, R, m, params) / m)
