r"""Willett et al. 2000's capillary bridge (analytic form, eqs. 12-13) with its rupture distance (eq. 15),
as Yade writes them, on an elastic Hertz contact.

Source read: ``pkg/dem/ViscoelasticCapillarPM.cpp`` of bchareyre/yade-mpi at commit ``122e63b3``
(``Law2_ScGeom_ViscElCapPhys_Basic::go`` and ``Willett_analytic_f``; the equation numbers below are
its comments' references to Willett, Adams, Johnson & Seville 2000, Langmuir 16:9396):

* the bridge is created at the first contact (``liqBridgeCreated``), with Yade's radius
  ``R = 2 r_1 r_2/(r_1 + r_2)`` between two spheres (twice ``R*``) and ``R = r`` between a sphere and
  a wall; ``V* = V_b/R^3`` and the rupture distance ``s_c = (1 + theta/2)(V*^(1/3) + 0.1 V*^(2/3)) R``
  (eq. 15, taken by Yade as the full separation);
* the capillary force acts only at a separation ``0 < s < s_c`` (``penetrationDepth < 0``):
  ``F = 2 pi R gamma cos(theta)/(1 + 2.1 S + 10 S^2)``, ``S = (s/2)/(V_b/R)^(1/2)`` (eqs. 12-13);
  in contact Yade applies its contact law alone; at ``s >= s_c`` the interaction is erased;
* Yade's contact law there is its linear visco-elastic one; here, as asked of this model, an
  undamped Hertz contact (``4/3 E* R*^(1/2) alpha^(3/2)``) carries the contact: the particle leaves
  it with its impact speed.

Hence the energy balance is exact: the bridge takes ``W = int_0^s_c F ds`` (closed form,
:func:`microimpact.core.models._capillary.willett_work`), ``e = (1 - 2 W/(m* V^2))^(1/2)`` above the
capture velocity ``V_s = (2 W/m*)^(1/2)`` and 0 below. Yade's ``theta`` input is in degrees
(converted with ``pi/180``), and so is ``contact_angle`` here.

**Parameters** (``params``): ``liquid_volume`` ``V_b`` [m^3] (``Vb``), ``surface_tension`` ``gamma``
[N/m] (``gamma``), ``contact_angle`` ``theta`` [deg] (Yade's ``theta``), ``two_spheres`` (0: a
sphere on a wall, Yade's ``R = R*``; 1: two spheres, ``R = 2 R*``). ``p_y`` is not used.
"""

from __future__ import annotations

import math

from .. import hertz
from .._jit import jitable
from . import Parameter, checks
from . import _capillary as cap
from ._common import dem_outcome, in_bounds, nan_outcome

NAME = "willett_capillary"
TITLE = "Willett et al. 2000 capillary bridge (eqs. 12-13, rupture eq. 15) as Yade writes it, on elastic Hertz"
CITATION = "Willett, Adams, Johnson & Seville, Langmuir 16:9396 (2000); Yade pkg/dem/ViscoelasticCapillarPM.cpp"
LABEL = "Willett capillary"
STICKS = True
OUTCOME_COST = "slow"
KIND = cap.WILLETT

PARAMETERS = (
    Parameter.of("liquid_volume", low=0.0, low_open=True),
    Parameter.of("surface_tension", default=0.072, low=0.0, low_open=True),
    Parameter.of("contact_angle", default=0.0, low=0.0, high=90.0),
    Parameter.of("two_spheres", default=0.0, flag=True),
)
BOUNDS, validate = checks(NAME, PARAMETERS)


@jitable
def constants(E, R, m, params):
    """The tuple ``q`` of :mod:`~microimpact.core.models._capillary`: Yade's ``R`` and ``s_c`` (eq. 15)."""
    Ry = 2.0 * R if params[3] == 1.0 else R
    V_b, theta = params[0], params[2] * math.pi / 180.0  # Yade: phys->theta = mat->theta*M_PI/180
    return (params[1], theta, V_b, Ry, 0.0, Ry, 1.0, cap.willett_rupture(theta, V_b, Ry), 0.0, 0.0, 0.0)


@jitable
def work(E, R, m, params):
    """The bridge's work [J] from contact to rupture, in closed form."""
    return cap.willett_work(constants(E, R, m, params))


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
    """Hertz in contact, Willett's bridge out to ``s_c`` [N] (attractive < 0)."""
    return cap.signed_force(KIND, alpha, alpha_dot, E, R, m, constants(E, R, m, params))


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """The same as :func:`signed_force`."""
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


@jitable
def separation_approach(E, R, m, p_y, params):
    """``-s_c`` [m] (eq. 15)."""
    return -constants(E, R, m, params)[7]


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """Capture velocity ``(2 W/m*)^(1/2)`` [m/s]."""
    if not in_bounds(params, BOUNDS):
        return math.nan
    return math.sqrt(2.0 * work(E, R, m, params) / m)
