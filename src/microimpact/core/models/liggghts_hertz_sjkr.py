r"""What LIGGGHTS-PUBLIC 3.8 computes for ``model hertz`` with ``cohesion sjkr`` or ``cohesion sjkr2``.

Sources read (CFDEMproject/LIGGGHTS-PUBLIC at commit ``84ba3d76``, release 3.8.0, unchanged at
``3d5c00f2``; line numbers ``L...`` are each file's): ``src/normal_model_hertz.h``
(``surfacesIntersect``, L202-L405), ``src/cohesion_model_sjkr.h`` (L87-L123),
``src/cohesion_model_sjkr2.h`` (L87-L124), ``src/global_properties.cpp`` (``createBetaEff``
L525-L544, ``createCohesionEnergyDensity`` L291), ``src/fix_wall_gran_base.h`` (L181-L196: the
wall's ``r``, ``area_ratio``, ``meff``) and ``src/pair_gran_base.h`` (L384-L394: two particles'
``meff``, ``r``), with the pages ``doc/gran_model_hertz.txt``, ``doc/gran_cohesion_sjkr.txt`` and
``doc/gran_cohesion_sjkr2.txt``.

The force law, as the code runs it
----------------------------------
``delta`` is the overlap (our approach ``alpha``), ``r`` the distance of the centres (at a wall:
of the centre from the wall, ``r = R - delta``), ``R*`` the code's ``reff`` (``radi`` at a wall,
``ri rj/(ri + rj)`` between particles), ``m*`` its ``meff`` (the particle's mass at a wall).

* Hertz and damping (``normal_model_hertz.h``): ``kn = 4/3 Y* (R* delta)^(1/2)`` (L234),
  ``Sn = 2 Y* (R* delta)^(1/2)`` (L231), ``gamman = -2 (5/6)^(1/2) beta (Sn m*)^(1/2)`` (L237) with
  ``beta = ln e_n/(ln^2 e_n + pi^2)^(1/2)`` (``createBetaEff``), and ``Fn = kn delta - gamman vn``
  (L253-L255). This is :mod:`~microimpact.core.models.hertz_tsuji`'s force with
  ``alpha_T = 5^(1/2) (-ln e_n)/(pi^2 + ln^2 e_n)^(1/2)``
  (:func:`~microimpact.core.models.hertz_tsuji.alpha_coeff_restitution`), and it is evaluated here
  by that model's :func:`~microimpact.core.models.hertz_tsuji.signed_force`. ``limitForce on``
  sets ``Fn`` to zero where it is negative (L258-L261). The damping sees only the Hertz stiffness:
  the cohesion below never enters ``gamman`` (so no NaN at small overlap, unlike LAMMPS'
  ``coeff_restitution`` with a cohesive normal model, lammps/lammps#4180).
* Cohesion, added after the normal model to the same contact (``i_forces.delta_F``), never clipped:
  ``Fn_coh = -cohEnergyDens * Acont`` (sjkr L99, sjkr2 L100), with the area ``Acont``:

  - sjkr at a wall (``sidata.is_wall``, L96): ``(ri^2 - r^2) pi = pi (2 R delta - delta^2)``;
  - sjkr between particles (L98): ``pi/4 ((r-ri-rj)(r+ri-rj)(r-ri+rj)(r+ri+rj))/r^2``;
  - sjkr2 at a wall (L96): ``2 pi ri (ri - r) = 2 pi R delta``;
  - sjkr2 between particles (L98): ``2 pi (2 ri rj/(ri+rj)) delta = 4 pi R* delta``.

  At a wall the force is multiplied by ``area_ratio`` twice (in ``Acont`` and again when applied,
  L106); ``area_ratio`` is 1 for a primitive wall (``fix_wall_gran_base.h`` L185). ``sjkr``'s
  area is the circle in which the two undeformed spheres intersect, ``pi a_g^2``; for two equal
  spheres of radius ``2 R*`` (the deck's ``geometry="sphere"``) ``a_g^2 = 2 R* delta -
  delta^2/4``. ``sjkr2``'s area is ``2 pi R delta`` at a wall but **twice that**, ``4 pi R*
  delta``, between two particles: the same ``cohesionEnergyDensity`` pulls twice as hard between
  particles as at a wall of the same ``R*``. Both act only while the spheres overlap (the
  cohesion models' ``surfacesClose`` only clears a flag): **no force beyond contact**, and both
  vanish at zero overlap, so the contact ends at zero approach.

With ``A(alpha) = pi (c_1 R* alpha - c_2 alpha^2)`` (``c_1, c_2`` = ``2, 1`` for sjkr at a wall;
``2, 1/4`` sjkr between equal spheres; ``2, 0`` sjkr2 at a wall; ``4, 0`` sjkr2 between
particles) and ``k`` the ``cohesionEnergyDensity`` [J/m^3], the normal force is

.. math:: P = \max\!\left(\tfrac43 E^* R^{*1/2}\alpha^{3/2}
              + \alpha_T \left(m^* \tfrac43 E^* (R^*\alpha)^{1/2}\right)^{1/2}\dot\alpha,\ 0^{\dagger}\right)
              - k A(\alpha),\qquad \alpha > 0,

(``dagger``: the clip only with ``limitForce on``).

Energy, restitution and capture (derived here)
----------------------------------------------
The cohesion depends on the approach alone, so it is conservative: with ``U(alpha) =
8/15 E* R*^(1/2) alpha^(5/2) - k pi (c_1 R* alpha^2/2 - c_2 alpha^3/3)`` the energy
``H = m* alpha_dot^2/2 + U`` only falls (at the rate of the damping's power, or of the Hertz
force's where ``limitForce`` clips), and ``U(0) = 0``. So the cohesion takes back on the way out
exactly the work it gave on the way in: ``(e V)^2 = V^2 - 2 W_d/m*`` with ``W_d`` the damping's
work, and the cohesion acts on ``e`` only by lengthening the path the damping works along
(deeper, slower, longer contact). Consequences: without damping (``e_n = 1``) the particle
always leaves with ``e = 1`` whatever ``k``; the particle is captured (``e = 0``) exactly when ``H``
falls below zero while it overlaps (it can no longer reach ``alpha = 0``, and oscillates in the
well of ``U`` until it rests at ``4/3 E* R*^(1/2) alpha^(3/2) = k A(alpha)``); and ``V_s``, the largest
speed at which it is captured, is where the energy left at the end of the contact is zero.

Scaling (as :mod:`~microimpact.core.models.hertz_tsuji`): ``rho = 4/3 E* R*^(1/2)``,
``T = (m*/(rho V^(1/2)))^(2/5)``, ``X = V T``; Newton's equation becomes

.. math:: x'' = -\max(x^{3/2} + \kappa x^{1/4} x', 0^\dagger) + c\,x - d\,x^2,\quad
          x(0) = 0,\ x'(0) = 1,

with ``kappa = alpha_T`` (to rounding), ``c = k pi c_1 R*/(rho X^(1/2))`` and
``d = k pi c_2 X^(1/2)/rho`` (``d/c = c_2 X/(c_1 R*)``: the ``alpha^2`` term of sjkr is of the order of the strain). ``e`` is no longer constant in ``V``: ``c`` grows as ``V^(-2/5)`` at low
speed. There is no closed form; ``e``, the times, the maximum approach and force are integrated
with Hairer's DOP853 tableau (:mod:`microimpact.core.dop853`) at a relative tolerance of 2e-14,
from the series ``x = t - kappa t^(9/4)/(45/16) - 4/35 t^(7/2) + c t^3/6`` at ``t = 1e-4``, with
its events (maximum approach, force maximum, zero approach) located by root finding on the step
length, as :mod:`~microimpact.core.models.hertz_viscoelastic` does. Capture is decided on the
scaled energy ``h = x'^2/2 + 2/5 x^(5/2) - c x^2/2 + d x^3/3``: ``h <= 0`` after the maximum
approach. :func:`sticking_velocity` solves ``s(V) = 0`` for the signed energy ``s`` (``e^2/2``
where the particle leaves; ``h`` at its first inner turning point where it is captured),
continuous through ``V_s``, by bracketing and the Illinois method to 1e-13 relative.

**Parameters of this model** (``params``, in this order):

``restitution`` ``e_n`` [-], in ``(0, 1]``
    LIGGGHTS' ``coefficientRestitution``: sets the damping only (the impact's ``e`` is lower
    where the cohesion acts). LIGGGHTS itself refuses ``e_n <= 0.05``.
``cohesion_energy_density`` ``k`` [J/m^3], ``>= 0``
    LIGGGHTS' ``cohesionEnergyDensity``.
``sjkr2`` [0 or 1]
    ``0`` (default): ``cohesion sjkr``; ``1``: ``cohesion sjkr2``.
``on_wall`` [0 or 1]
    ``1`` (default): the sphere on a flat wall of ``fix wall/gran`` (radius ``R*``, mass ``m*``);
    ``0``: two equal spheres (radius ``2 R*``, mass ``2 m*`` each), where the cohesive area differs
    (table above). Hertz and damping are the same in both.
``limit_force`` [0 or 1]
    ``0`` (default, as in LIGGGHTS): not clipped; ``1``: ``limitForce on``.

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is 0 (the
contact ends at zero approach); ``max_contact_radius`` is Hertz's ``(R* alpha*)^(1/2)``; ``max_force``
is the largest total force (Hertz, damping and cohesion) in loading. A captured particle has
``e = 0`` and an infinite ``unloading_time``. ``p_y`` is not used.

Validity: a DEM law. The cohesion is a force proportional to the geometric overlap area, not
JKR's: no neck, no pull-off force, no loss by the contact's breaking; capture comes from the
damping alone (none at ``e_n = 1``). ``cohesionEnergyDensity`` is no material property; the
face's :func:`~microimpact.models.liggghts_hertz_sjkr.params_for_work_of_adhesion` maps a work of
adhesion ``G`` to it approximately (by matching JKR's pull-off force).
"""

from __future__ import annotations

import math

from .. import dop853 as dp
from .. import hertz
from .._jit import jitable
from ..roots import illinois, secant_point
from . import LIMIT_FORCE, Parameter, checks, deprecated_names
from . import hertz_tsuji as tsuji
from ._common import dem_outcome, in_bounds, nan_outcome

NAME = "liggghts_hertz_sjkr"
TITLE = "LIGGGHTS-PUBLIC 3.8 hertz with coefficientRestitution damping and cohesion sjkr / sjkr2"
CITATION = (
    "LIGGGHTS-PUBLIC 3.8, src/normal_model_hertz.h, src/cohesion_model_sjkr.h, src/cohesion_model_sjkr2.h "
    "(CFDEMproject, commit 84ba3d76)"
)
LABEL = "LIGGGHTS hertz + sjkr"
STICKS = True
PARAMETERS = (
    Parameter.of(
        "restitution",
        "e_n in (0, 1], LIGGGHTS' coefficientRestitution: the coefficient of restitution that sets the damping only",
        low=0.0,
        high=1.0,
        low_open=True,
    ),
    Parameter("cohesion_energy_density", "J/m^3", "k >= 0, LIGGGHTS' cohesionEnergyDensity", low=0.0),
    Parameter("sjkr2", "1", "0: cohesion sjkr (intersection circle); 1: cohesion sjkr2", default=0.0, flag=True),
    Parameter("on_wall", "1", "1: sphere on a flat wall; 0: two equal spheres", default=1.0, flag=True),
    LIMIT_FORCE._replace(
        description="1: force clipped at zero (the Hertz and damping part, limitForce on; the contact ends "
        "at zero approach); 0: not clipped",
        default=0.0,
    ),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(__name__, NAME)
#: Cost class (the contract's ``COST``): ``e`` integrates the equation of motion, about 1 ms a point in Python.
COST = "slow"
#: The contact ends at zero approach, where every term of the force vanishes.
ZERO_FORCE_ORDER = 1.0

_TOL = 2e-14
_T0 = 1e-4
_MAX_STEPS = 400000
_T_MAX = 1e4


@jitable
def area_coefficients(params):
    """``(c_1, c_2)`` of the cohesive area ``A = pi (c_1 R* alpha - c_2 alpha^2)`` of the variant
    (``params[2]``: sjkr2) and geometry (``params[3]``: wall) of ``params`` (module docstring's table)."""
    if params[2] == 1.0:
        return (2.0, 0.0) if params[3] == 1.0 else (4.0, 0.0)
    return (2.0, 1.0) if params[3] == 1.0 else (2.0, 0.25)


@jitable
def cohesive_force(alpha, R, params):
    """``k A(alpha)`` [N] (attractive), ``alpha > 0``: ``Fn_coh`` of the cohesion model."""
    c1, c2 = area_coefficients(params)
    return params[1] * math.pi * (c1 * R * alpha - c2 * alpha * alpha)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N] on the particle while it overlaps (attractive negative): Hertz and
    Tsuji's damping (:func:`hertz_tsuji.signed_force <microimpact.core.models.hertz_tsuji.signed_force>`),
    clipped at zero with ``limit_force``, minus the cohesion ``k A(alpha)``."""
    if alpha <= 0.0:
        return 0.0
    p = tsuji.signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, (damping_ratio(params), 0.0))
    if params[4] == 1.0 and p < 0.0:
        p = 0.0
    return p - cohesive_force(alpha, R, params)


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N]: :func:`signed_force` while the spheres overlap, zero outside."""
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


@jitable
def ends_at_zero_force(params):
    """False: the contact ends at zero approach, whatever ``limit_force``."""
    return False


@jitable
def separation_approach(E, R, m, p_y, params):
    """Approach [m] at which the contact ends: 0 (no force beyond contact)."""
    return 0.0


@jitable
def damping_ratio(params):
    """Tsuji's ``alpha_T`` LIGGGHTS derives from ``coefficientRestitution`` ``e_n`` (``params[0]``)."""
    return tsuji.alpha_coeff_restitution(params[0])


@jitable
def scaled_groups(V, E, R, m, params):
    """``(kappa, c, d, X, T)`` of the scaled equation at speed ``V > 0`` (module docstring)."""
    rho = hertz.stiffness(E, R)
    T = hertz.dem_time_scale(V, E, R, m)
    X = V * T
    kappa = tsuji.restitution_group(V, E, R, m, 0.0, (damping_ratio(params), 0.0))
    c1, c2 = area_coefficients(params)
    sx = math.sqrt(X)
    c = params[1] * math.pi * c1 * R / (rho * sx)
    d = params[1] * math.pi * c2 * sx / rho
    return kappa, c, d, X, T


# ------------------------------------------------------------------------------ scaled integration
@jitable
def _acc(x, v, g):
    """Scaled acceleration; ``g = (kappa, c, d, clip)``; no force outside the contact."""
    if x <= 0.0:
        return 0.0
    s = math.sqrt(x)
    p = x * s + g[0] * math.sqrt(s) * v
    if g[3] == 1.0 and p < 0.0:
        p = 0.0
    return -p + g[1] * x - g[2] * x * x


@jitable
def _energy(x, v, g):
    """Scaled energy ``v^2/2 + 2/5 x^(5/2) - c x^2/2 + d x^3/3`` (``x > 0``), non-increasing."""
    xp = x if x > 0.0 else 0.0
    return 0.5 * v * v + 0.4 * xp * xp * math.sqrt(xp) - 0.5 * g[1] * xp * xp + g[2] * xp * xp * xp / 3.0


@jitable
def _force_rate(x, v, g):
    """``x^(3/4) dP/dt`` of the total scaled force ``P`` in loading (a maximum of ``P`` where it
    crosses zero from above; finite at ``x -> 0``)."""
    xp = x if x > 0.0 else 0.0
    q = math.sqrt(math.sqrt(xp))  # x^(1/4)
    a = _acc(xp, v, g)
    return 1.5 * xp * q * v + g[0] * (0.25 * v * v + xp * a) + (2.0 * g[2] * xp - g[1]) * q * q * q * v


@jitable
def _total_force(x, v, g):
    """Total scaled force ``-x''`` (repulsive positive)."""
    return -_acc(x, v, g)


@jitable
def _rates(x, v, g):
    """:func:`_acc` as :func:`~microimpact.core.dop853.step` calls it: no third state."""
    return _acc(x, v, g), 0.0


@jitable
def _step(x, v, h, g):
    """One DOP853 step of length ``h`` (:func:`microimpact.core.dop853.step`): ``(x, v, error)``
    (Hairer's error norm, tolerance ``_TOL``)."""
    xn, vn, _, e5x, e5v, e3x, e3v = dp.step(_rates, x, v, 0.0, h, g)
    return xn, vn, dp.hairer_error(h, e5x, e5v, e3x, e3v, _TOL * (1e-3 + abs(xn)), _TOL * (1e-3 + abs(vn)))


@jitable
def _event(which, x, v, g):
    """Event functions, each crossing zero from above: 0 the maximum approach (``x'``), 1 the force
    maximum (:func:`_force_rate`), 2 zero approach (``x``), 3 the inner turning point of a captured
    particle (``-x'``)."""
    if which == 0:
        return v
    if which == 1:
        return _force_rate(x, v, g)
    if which == 2:
        return x
    return -v


@jitable
def _locate(which, x, v, h, xh, vh, g):
    """Step length ``0 < s <= h`` from ``(x, v)`` at which event ``which`` crosses zero (Illinois)."""
    a = 0.0
    ga = _event(which, x, v, g)
    b = h
    gb = _event(which, xh, vh, g)
    side = 0
    for _ in range(200):
        s = secant_point(a, b, ga, gb)
        xs, vs, _ = _step(x, v, s, g)
        gs = _event(which, xs, vs, g)
        if gs == 0.0:
            return s
        a, b, ga, gb, side = illinois(a, b, ga, gb, side, s, gs)
        if b - a <= 1e-14 * (b if b > 1e-300 else 1.0):
            break
    return b


@jitable
def scaled_impact(kappa, c, d, clip, full):
    """The scaled impact (module docstring) with ``clip`` 1.0 or 0.0.

    Returns ``(e, x_max, t_max, p_max, t_end, s)``: restitution, maximum approach and its time,
    largest total scaled force in loading, the time the approach returns to zero, and the signed
    end energy ``s`` (``e^2/2``; for a captured particle, ``e = 0``, ``t_end = inf`` and ``s`` the
    energy ``h < 0`` at its first inner turning point). ``full`` False: the force maximum is not
    located (``p_max`` 0; the steps and ``e`` are the same).
    """
    g = (kappa, c, d, clip)
    t = _T0
    t14 = math.sqrt(math.sqrt(t))
    t32 = t * math.sqrt(t)
    # series (derived here): x'' = -t^(3/2) - kappa t^(1/4) + c t + ... from x = 0, x' = 1
    x = t - kappa * t * t * t14 / 2.8125 - 4.0 / 35.0 * t * t * t32 + c * t * t * t / 6.0
    v = 1.0 - kappa * t * t14 / 1.25 - 0.4 * t * t32 + 0.5 * c * t * t
    h = 1e-2 * t
    found_top = False
    captured = False
    x_max = 0.0
    t_max = 0.0
    p_max = 0.0
    h_old = 0.0
    err_old = 0.0
    for _ in range(_MAX_STEPS):
        xn, vn, err = _step(x, v, h, g)
        if err > 1.0:
            h *= max(0.2, 0.9 * err**-0.125)
            continue
        if full and not found_top and _force_rate(x, v, g) > 0.0 and _force_rate(xn, vn, g) <= 0.0:
            s = _locate(1, x, v, h, xn, vn, g)
            xs, vs, _ = _step(x, v, s, g)
            p = _total_force(xs, vs, g)
            if p > p_max:
                p_max = p
        if not found_top and vn <= 0.0:
            s = _locate(0, x, v, h, xn, vn, g)
            xs, vs, _ = _step(x, v, s, g)
            x_max = xs
            t_max = t + s
            found_top = True
            if full and x_max**1.5 - c * x_max + d * x_max * x_max > p_max:
                p_max = x_max**1.5 - c * x_max + d * x_max * x_max
        if found_top and not captured and xn <= 0.0:
            s = _locate(2, x, v, h, xn, vn, g)
            xs, vs, _ = _step(x, v, s, g)
            e = -vs if -vs < 1.0 else 1.0
            return e, x_max, t_max, p_max, t + s, 0.5 * e * e
        if found_top and not captured and _energy(xn, vn, g) <= 0.0:
            captured = True  # the particle can no longer reach zero approach
        if captured and v < 0.0 and vn >= 0.0:
            s = _locate(3, x, v, h, xn, vn, g)
            xs, vs, _ = _step(x, v, s, g)
            en = _energy(xs, vs, g)
            return 0.0, x_max, t_max, p_max, math.inf, en if en < 0.0 else 0.0
        t += h
        x = xn
        v = vn
        if t > _T_MAX:
            break
        err = max(err, 1e-10)
        trend = 1.0
        if h_old > 0.0:
            trend = min(1.0, h / h_old * (err_old / err) ** 0.125)
        h_old = h
        err_old = err
        h *= min(5.0, 0.9 * trend * err**-0.125)
    return 0.0, x_max, t_max, p_max, math.inf, math.nan


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (see the module docstring; ``p_y`` unused)."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    if V == 0.0:  # resting in touch: no force at zero approach, nothing moves
        return dem_outcome(V, 0.0, 0.0, 0.0, 0.0, R, 0.0, math.inf)
    kappa, c, d, X, T = scaled_groups(V, E, R, m, params)
    e, x_max, t_max, p_max, t_end, _ = scaled_impact(kappa, c, d, params[4], True)
    rho = hertz.stiffness(E, R)
    return dem_outcome(V, e, X * x_max, 0.0, rho * X * math.sqrt(X) * p_max, R, T * t_max, T * (t_end - t_max))


@jitable
def restitution_only(V, E, R, m, p_y, params):
    """``e`` [-] of :func:`outcome` alone, bit for bit, without locating the force maximum."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return math.nan
    if V == 0.0:
        return 0.0
    kappa, c, d, X, T = scaled_groups(V, E, R, m, params)
    return scaled_impact(kappa, c, d, params[4], False)[0]


@jitable
def end_energy(V, E, R, m, params):
    """The signed end energy [-] of :func:`scaled_impact` at ``V > 0``: ``e^2/2`` where the particle
    leaves, the scaled energy (``< 0``) at its first inner turning point where it is captured.
    Continuous in ``V``; its zero is :func:`sticking_velocity`."""
    kappa, c, d, X, T = scaled_groups(V, E, R, m, params)
    return scaled_impact(kappa, c, d, params[4], False)[5]


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """Capture velocity ``V_s`` [m/s]: the particle is captured at ``V < V_s`` and leaves above.

    0 without cohesion or without damping (``k = 0`` or ``e_n = 1``: nothing is lost that the
    cohesion's well could hold). Found by bracketing from the speed at which ``c = 1`` and the
    Illinois method on :func:`end_energy` to 1e-13 relative in ``V``.
    """
    if not in_bounds(params, BOUNDS):
        return math.nan
    if params[1] == 0.0 or params[0] == 1.0:
        return 0.0
    # speed at which the scaled cohesion c is 1: c = k pi c1 R*/(rho X^(1/2)), X = V^(4/5) (m/rho)^(2/5)
    rho = hertz.stiffness(E, R)
    c1 = area_coefficients(params)[0]
    s1 = params[1] * math.pi * c1 * R / rho
    X1 = s1 * s1
    V1 = (X1 * (rho / m) ** 0.4) ** 1.25
    lo = V1
    flo = end_energy(lo, E, R, m, params)
    hi = V1
    fhi = flo
    for _ in range(200):
        if flo < 0.0:
            break
        hi, fhi = lo, flo
        lo *= 0.25
        flo = end_energy(lo, E, R, m, params)
    for _ in range(200):
        if fhi > 0.0:
            break
        lo, flo = hi, fhi
        hi *= 4.0
        fhi = end_energy(hi, E, R, m, params)
    if not (flo < 0.0 and fhi > 0.0):
        return math.nan
    side = 0
    for _ in range(300):
        s = (lo * fhi - hi * flo) / (fhi - flo)
        if not (s > lo and s < hi):
            s = 0.5 * (lo + hi)
        fs = end_energy(s, E, R, m, params)
        if fs == 0.0:
            return s
        if fs < 0.0:
            lo, flo = s, fs
            if side == -1:
                fhi *= 0.5
            side = -1
        else:
            hi, fhi = s, fs
            if side == 1:
                flo *= 0.5
            side = 1
        if hi - lo <= 1e-13 * hi:
            break
    return hi
