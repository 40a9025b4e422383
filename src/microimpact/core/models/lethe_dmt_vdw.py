"""Lethe's DMT law with non-contact van der Waals attraction (Meier et al. 2019), one sphere at a wall.

Sources: the Lethe theory guide, ``chaos-polymtl/lethe:doc/source/theory/multiphase/cfd_dem/dem.rst``
(commit ``03d8e368``: "Contact Force and Torque Models", the nonlinear viscoelastic constants, and
"Cohesive force models", the DMT force of Meier, Weinhart & Luding after their 2019 paper), and the
code that runs it: ``include/dem/particle_wall_contact_force.h`` (``calculate_DMT_contact``,
``calculate_nonlinear_contact``, ``get_force_calculation_threshold_distance``; the same law as
``source/dem/particle_wall_dmt_force.cc@01b3ebcd`` with ``include/dem/particle_wall_dmt_force.h@01b3ebcd``,
``set_dmt_cut_off_distance``). The older wall path, ``include/dem/particle_wall_dmt_force.h@e529a602``
with its ``.cc``, computed no force before contact and a pull-off ``4 pi R gamma_e``, twice the
documented ``2 pi R gamma_e``; this model follows the later code, which agrees with the theory guide
(``docs/laws/lethe_dmt_vdw.rst``). Lethe is not installed here: no Lethe run checks this model.

The force on the particle, pushing it off the wall (negative: attractive), at the overlap ``alpha``
(negative: a gap) and its rate ``alpha'`` (positive towards the wall), ``R`` the particle radius,
``m`` its mass, ``E*`` Lethe's effective Young's modulus of the particle-wall pair, ``gamma_e`` its
effective surface energy and ``A`` its effective Hamaker constant (the mean of particle's and
wall's):

* contact, ``alpha > 0``: ``P = 1.3333 E* (R alpha)^(1/2) alpha + 1.8257 (-beta) (S_n m)^(1/2) alpha'
  - F_po``, ``S_n = 2 E* (R alpha)^(1/2)``, ``beta = ln e/(ln^2 e + 9.8696)^(1/2)`` (the code's
  constants: 1.3333 for 4/3, 1.8257 for ``2 (5/6)^(1/2)``, 9.8696 for ``pi^2``);
* ``delta_0 < alpha <= 0``: ``P = -F_po``, ``F_po = 2 pi R gamma_e``;
* ``delta* < alpha <= delta_0``: ``P = -A R/(6 alpha^2)`` (van der Waals, sphere-flat);
* ``alpha <= delta*``: no force; ``delta_0 = -(A R/(6 F_po))^(1/2) = -(A/(12 pi gamma_e))^(1/2)``
  (where the van der Waals force equals the pull-off force) and ``delta* = delta_0/C^(1/2)`` (the
  input ``dmt cut-off threshold`` ``C``: the van der Waals force has fallen to ``C F_po`` there).

Impact (derived here). ``V`` is the speed outside the cut-off, where a run starts. The attraction
before contact is conservative: it does the work ``W = F_po |delta_0| (2 - C^(1/2))`` from
``delta*`` to contact (``A R/(6|delta_0|) = F_po |delta_0|``), so the particle touches at
``v_c = (V^2 + 2W/m)^(1/2)``. In contact the particle moves under ``P`` (integrated with DOP853,
:mod:`microimpact.core.dop853`, as :mod:`~microimpact.core.models.lammps_mdr` does); the contact ends
where the overlap returns to zero, at ``v_out``, or the particle turns back inside it (held). It
escapes the field only if ``v_out^2 > 2W/m``: then ``e = (v_out^2 - 2W/m)^(1/2)/V``; else it falls
back, and with every contact it loses energy it cannot regain: captured, ``e = 0``. The capture
velocity ``V_s`` is the root of ``v_out(v_c(V))^2 = 2W/m`` (:func:`sticking_velocity`).

Undamped (``e`` input 1) every force is conservative and ``e = 1`` at any speed: no capture. The
restitution the code's ``e`` input gives is not ``e`` once there is cohesion: the constant
``-F_po`` in contact and the work ``W`` change it (``docs/laws/lethe_dmt_vdw.rst``).

Two equal spheres (Lethe's particle-particle path) use ``R* = R/2``, ``m* = m/2`` and ``E*`` of the
pair in the same law; the model takes ``E``, ``R``, ``m`` as the pair's ``E*``, ``R*``, ``m*``, so a
:class:`~microimpact.pair.ContactPair` of two spheres gives that case.

**Parameters of this model** (``params``, in this order):

``restitution`` ``e`` [-], ``0 < e <= 1``
    Lethe's effective restitution coefficient of the pair (the harmonic mean ``2 e_p e_w/(e_p + e_w)``
    of the particle's and wall's inputs), which sets ``beta``.
``effective_surface_energy`` ``gamma_e`` [J/m^2], ``> 0``
    Lethe's ``gamma_p + gamma_w - (gamma_p^(1/2) - gamma_w^(1/2))^2`` (``2 gamma`` for one material):
    the work of adhesion ``G`` of DMT's pull-off ``2 pi R G``.
``hamaker_constant`` ``A`` [J], ``> 0``
    Lethe's effective Hamaker constant, the mean of the particle's and the wall's.
``cut_off_threshold`` ``C`` [-], ``0 < C <= 1``
    Lethe's ``dmt cut-off threshold``.

Fields not defined (NaN): ``yield_velocity``, ``normalized_velocity``, ``unloading_radius``,
``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is 0 (the contact ends at zero
overlap), the contact time is the time in contact (overlap > 0) of the first contact,
``max_contact_radius`` is ``(R alpha_max)^(1/2)``; a captured particle has ``e = 0`` and an infinite
``unloading_time``.
"""

from __future__ import annotations

import math

from .. import dop853 as dp
from .. import hertz
from .._jit import jitable
from ..roots import illinois, secant_point
from . import Parameter, checks
from ._common import dem_outcome, in_bounds, nan_outcome

NAME = "lethe_dmt_vdw"
TITLE = "Lethe DMT with non-contact van der Waals attraction (Meier et al. 2019), sphere on a wall"
CITATION = (
    "Meier, Weinhart & Luding, Powder Technol. (2019); Lethe theory guide dem.rst, "
    "include/dem/particle_wall_contact_force.h (calculate_DMT_contact)"
)
LABEL = "Lethe DMT + vdW"
STICKS = True
COST = "slow"
ADHESION_LIMIT = "DMT"
PARAMETERS = (
    Parameter.of(
        "restitution",
        "Lethe's effective restitution coefficient e in (0, 1]",
        default=1.0,
        low=0.0,
        high=1.0,
        low_open=True,
    ),
    Parameter(
        "effective_surface_energy",
        "J/m^2",
        "gamma_e > 0, Lethe's effective surface energy (= G)",
        low=0.0,
        low_open=True,
    ),
    Parameter(
        "hamaker_constant", "J", "A > 0, Lethe's effective Hamaker constant", default=1e-19, low=0.0, low_open=True
    ),
    Parameter(
        "cut_off_threshold",
        "1",
        "C in (0, 1], Lethe's dmt cut-off threshold",
        default=0.1,
        low=0.0,
        high=1.0,
        low_open=True,
    ),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
_TOL = 1e-13
_MAX_STEPS = 200000


@jitable
def work_of_adhesion(params):
    """``G`` [J/m^2] of the parameters: Lethe's ``gamma_e`` (its pull-off is ``2 pi R gamma_e``)."""
    return params[1]


@jitable
def pull_off_force(R, params):
    """``F_po = 2 pi R gamma_e`` [N]."""
    return 2.0 * math.pi * R * params[1]


@jitable
def constant_zone_edge(R, params):
    """``delta_0 = -(A/(12 pi gamma_e))^(1/2)`` [m] (< 0): the van der Waals force equals ``F_po`` there."""
    return -math.sqrt(params[2] * R / (6.0 * pull_off_force(R, params)))


@jitable
def cut_off(R, params):
    """``delta* = delta_0/C^(1/2)`` [m] (< 0): no force beyond."""
    return constant_zone_edge(R, params) / math.sqrt(params[3])


@jitable
def approach_work(R, params):
    """``W`` [J]: the work of the attraction from ``delta*`` to contact, ``F_po |delta_0| (2 - C^(1/2))``."""
    return pull_off_force(R, params) * -constant_zone_edge(R, params) * (2.0 - math.sqrt(params[3]))


@jitable
def beta(params):
    """The code's ``beta = ln e/(ln^2 e + 9.8696)^(1/2)`` (<= 0)."""
    le = math.log(params[0])
    return le / math.sqrt(le * le + 9.8696)


@jitable
def contact_force(alpha, alpha_dot, E, R, m, params):
    """``P`` [N] in contact (``alpha > 0``): the nonlinear spring and dashpot minus ``F_po``."""
    s = math.sqrt(R * alpha)
    sn = 2.0 * E * s
    return 1.3333 * E * s * alpha - 1.8257 * beta(params) * math.sqrt(sn * m) * alpha_dot - pull_off_force(R, params)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Force [N] at any overlap ``alpha`` (negative: a gap), as the code computes it."""
    if alpha > 0.0:
        return contact_force(alpha, alpha_dot, E, R, m, params)
    d0 = constant_zone_edge(R, params)
    if alpha > d0:
        return -pull_off_force(R, params)
    if alpha > cut_off(R, params):
        return -params[2] * R / (6.0 * alpha * alpha)
    return 0.0


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """:func:`signed_force` (the contact's law, attraction included: the contact may pull)."""
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


@jitable
def separation_approach(E, R, m, p_y, params):
    """Overlap [m] at which the contact ends: 0 (the attraction beyond is the field's, see :func:`outcome`)."""
    return 0.0


@jitable
def _acc(x, v, amax, E, R, m, params, L, V, c):
    """Scaled acceleration ``-P c`` in contact, at ``x = alpha/L > 0``, ``v = alpha'/V``."""
    if x <= 0.0:
        return 2.0 * math.pi * R * params[1] * c  # F_po: the contact's constant attraction at alpha = 0
    return -contact_force(x * L, v * V, E, R, m, params) * c


@jitable
def _rates(x, v, p):
    """:func:`_acc` as :func:`~microimpact.core.dop853.step` calls it, ``p = (amax, E, R, m, params,
    L, V, c)``: no third state."""
    return _acc(x, v, p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]), 0.0


@jitable
def _step(x, v, h, amax, E, R, m, params, L, V, c):
    """One step of length ``h`` of Hairer's DOP853 (:func:`microimpact.core.dop853.step`): ``(x, v,
    error)``, the error measured as Hairer's code measures it (root mean square over ``x`` and
    ``x'``, each relative to ``_TOL (1e-3 + |new value|)``)."""
    xn, vn, _, e5x, e5v, e3x, e3v = dp.step(_rates, x, v, 0.0, h, (amax, E, R, m, params, L, V, c))
    return xn, vn, dp.hairer_error(h, e5x, e5v, e3x, e3v, _TOL * (1e-3 + abs(xn)), _TOL * (1e-3 + abs(vn)))


@jitable
def _event(which, x, v, level):
    """Event functions, each crossing zero from above: 0 top (``x' = 0``), 1 the end of the contact
    (``x = 0``) or a turn back inside it (``x' = 0`` again: the attraction holds the particle),
    whichever comes first (``min(x, -x')``)."""
    if which == 0:
        return v
    return x - level if x - level < -v else -v


@jitable
def _locate(which, level, x, v, h, xh, vh, amax, E, R, m, params, L, V, c):
    """Step length ``0 < s <= h`` from ``(x, v)`` at which event ``which`` crosses zero (Illinois
    secant with bisection), to ``1e-14 s``."""
    a = 0.0
    ga = _event(which, x, v, level)
    b = h
    gb = _event(which, xh, vh, level)
    side = 0
    for _ in range(200):
        s = secant_point(a, b, ga, gb)
        xs, vs, _ = _step(x, v, s, amax, E, R, m, params, L, V, c)
        gs = _event(which, xs, vs, level)
        if gs == 0.0:
            return s
        a, b, ga, gb, side = illinois(a, b, ga, gb, side, s, gs)
        if b - a <= 1e-14 * (b if b > 1e-300 else 1.0):
            break
    return b


@jitable
def _peak(xa, va, hh, amax, E, R, m, params, L, V, c):
    """Largest scaled force on ``[0, hh]`` of the trajectory from ``(xa, va)`` (golden section over the
    length of one step from there: the bracket spans the two steps around the best step end)."""
    g = 0.6180339887498949
    a = 0.0
    b = hh
    s1 = b - g * (b - a)
    s2 = a + g * (b - a)
    x1, v1, _ = _step(xa, va, s1, amax, E, R, m, params, L, V, c)
    x2, v2, _ = _step(xa, va, s2, amax, E, R, m, params, L, V, c)
    f1 = -_acc(x1, v1, amax, E, R, m, params, L, V, c)
    f2 = -_acc(x2, v2, amax, E, R, m, params, L, V, c)
    for _ in range(80):
        if f1 > f2:
            b = s2
            s2 = s1
            f2 = f1
            s1 = b - g * (b - a)
            x1, v1, _ = _step(xa, va, s1, amax, E, R, m, params, L, V, c)
            f1 = -_acc(x1, v1, amax, E, R, m, params, L, V, c)
        else:
            a = s1
            s1 = s2
            f1 = f2
            s2 = a + g * (b - a)
            x2, v2, _ = _step(xa, va, s2, amax, E, R, m, params, L, V, c)
            f2 = -_acc(x2, v2, amax, E, R, m, params, L, V, c)
        if b - a <= 1e-12 * hh:
            break
    return f1 if f1 > f2 else f2


@jitable
def _phase(x, v, t, h, amax, which, level, E, R, m, params, L, V, c):
    """Integrate from ``(x, v)`` at scaled time ``t`` with first step ``h`` until event ``which``
    (at ``level``); returns ``(x, v, t, h, found, fmax)`` at the event, ``fmax`` the largest scaled
    force (``-acceleration``) of the phase: the best step end, refined by :func:`_peak` over the
    two steps around it."""
    fmax = 0.0
    xa = x
    va = v
    ha = 0.0
    hb = -1.0  # the length of the step after the best step end (-1: not yet taken)
    h_old = 0.0
    err_old = 0.0
    for _ in range(_MAX_STEPS):
        xn, vn, err = _step(x, v, h, amax, E, R, m, params, L, V, c)
        if err > 1.0:
            h *= max(0.2, 0.9 * err**-0.125)
            continue
        if _event(which, xn, vn, level) <= 0.0:
            s = _locate(which, level, x, v, h, xn, vn, amax, E, R, m, params, L, V, c)
            xs, vs, _ = _step(x, v, s, amax, E, R, m, params, L, V, c)
            fs = -_acc(xs, vs, amax, E, R, m, params, L, V, c)
            if hb < 0.0:
                hb = s
            if ha > 0.0:
                fmax = max(fmax, _peak(xa, va, ha + hb, amax, E, R, m, params, L, V, c))
            return xs, vs, t + s, h, True, max(fmax, fs)
        f = -_acc(xn, vn, amax, E, R, m, params, L, V, c)
        if hb < 0.0:
            hb = h
        if f > fmax:
            fmax = f
            xa = x
            va = v
            ha = h
            hb = -1.0
        t += h
        x = xn
        v = vn
        if t > 1e4:
            break
        err = max(err, 1e-10)
        trend = 1.0
        if h_old > 0.0:
            trend = min(1.0, h / h_old * (err_old / err) ** 0.125)
        h_old = h
        err_old = err
        h *= min(5.0, 0.9 * trend * err**-0.125)
    return x, v, t, h, False, fmax


@jitable
def contact_exit(vc, E, R, m, params):
    """The first contact at the touch-down speed ``vc`` [m/s]: ``(v_out, held, alpha_max, P_max,
    t_load, t_unload)``, ``v_out`` the speed [m/s] at which the overlap returns to zero (0 where the
    particle turns back inside the contact: ``held`` 1.0)."""
    T = hertz.time_scale(vc, E, R, m)
    L = vc * T
    c = T / (m * vc)
    x, v, t, h, hit, f1 = _phase(0.0, 1.0, 0.0, 1e-3, -1.0, 0, 0.0, E, R, m, params, L, vc, c)
    if not hit:
        return 0.0, 1.0, math.nan, math.nan, math.inf, math.inf
    tL = t
    amax = x * L
    x, v, t, h, hit, f2 = _phase(x, 0.0, t, h, amax, 1, 0.0, E, R, m, params, L, vc, c)
    fmax = max(f1, f2) / c
    if not hit or -v <= 0.0:
        return 0.0, 1.0, amax, fmax, T * tL, math.inf
    return -v * vc, 0.0, amax, fmax, T * tL, T * (t - tL)


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact at the speed ``V`` outside the cut-off (module docstring; ``p_y`` unused)."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    W2 = 2.0 * approach_work(R, params) / m
    vc = math.sqrt(V * V + W2)
    v_out, held, amax, Pm, tL, tU = contact_exit(vc, E, R, m, params)
    if held == 1.0 or not v_out * v_out > W2:
        return dem_outcome(V, 0.0, amax, 0.0, Pm, R, tL, math.inf)
    e = math.sqrt((v_out - math.sqrt(W2)) * (v_out + math.sqrt(W2))) / V
    if e > 1.0:  # the dashpot only takes energy: e above 1 is the integration's rounding
        e = 1.0
    return dem_outcome(V, e, amax, 0.0, Pm, R, tL, tU)


@jitable
def escape_margin(V, E, R, m, params):
    """``v_out^2 - 2W/m`` [m^2/s^2] at the speed ``V`` outside the cut-off: positive where the
    particle escapes (``-2W/m`` where the contact holds it)."""
    W2 = 2.0 * approach_work(R, params) / m
    v_out, held, amax, Pm, tL, tU = contact_exit(math.sqrt(V * V + W2), E, R, m, params)
    return v_out * v_out - W2


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """``V_s`` [m/s]: the largest speed outside the cut-off at which the particle is captured, the root
    of :func:`escape_margin` (bisection to rounding); 0 where it escapes at every speed (undamped)."""
    if not in_bounds(params, BOUNDS):
        return math.nan
    if params[0] == 1.0:
        return 0.0
    W2 = 2.0 * approach_work(R, params) / m
    hi = math.sqrt(W2)
    for _ in range(200):
        if escape_margin(hi, E, R, m, params) > 0.0:
            break
        hi *= 2.0
    lo = 0.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if not (lo < mid < hi):
            break
        if escape_margin(mid, E, R, m, params) > 0.0:
            hi = mid
        else:
            lo = mid
    return lo
