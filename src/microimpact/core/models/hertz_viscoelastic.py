"""Hertz contact with viscoelastic (Kelvin-Voigt) damping: Brilliantov et al. (1996).

The normal force between viscoelastic spheres (Brilliantov, Spahn, Hertzsch & Poschel 1996,
Phys. Rev. E 53, 5382; written as in Poschel & Schwager, *Computational Granular Dynamics*,
Springer 2005, eq. 2.14),

.. math::  P = \\tfrac{4}{3} E^* R^{*1/2} \\left(\\alpha^{3/2} + A\\, \\alpha^{1/2}\\, \\dot\\alpha\\right),

with the material's dissipative constant ``A`` [s]. It is what LAMMPS computes for
``pair_coeff * * hertz/material E e nu ... damping viscoelastic`` (``doc/src/pair_granular.rst``: ``hertz`` force ``k_N R^(1/2) delta^(3/2)`` with
``k_N = 4/3 E*``, damping ``eta_n0 a m_eff delta_dot`` with ``a = (R delta)^(1/2)``), so
``eta_n0 = 4 E* A / (3 m*)`` [1/(s m)] there. Near the end of the contact the damping term can make
``P`` negative: LAMMPS keeps the attractive force unless ``limit_damping`` is given; Poschel &
Schwager (2005, p. 22, as quoted in the comments of a public implementation of eq. 2.14) set it to
zero. ``limit_force`` selects the convention. (Schwager & Poschel's series for ``e`` in
``V^(1/5)`` and Muller & Poschel's (2011) compact forms were not available to this project: ``e``
is computed from the force law itself, below.)

Scaling: with ``rho = 4/3 E* R*^(1/2)``, time ``T = (m*/(rho V^(1/2)))^(2/5)`` and length
``X = V T``, Newton's equation becomes ``x'' = -(x^(3/2) + kappa x^(1/2) x')``, ``x(0) = 0``,
``x'(0) = 1``, with the single number ``kappa = A/T = A (rho/m*)^(2/5) V^(1/5)``: ``e`` is one
function of ``kappa``, decreasing from 1 as ``V`` (or ``A``) grows, with
``1 - e = C kappa + O(kappa^2)``, ``C = 4/5 (5/4)^(3/5) B(3/5, 3/2) = 1.1534`` (the damping work
along Hertz's trajectory; derived here and checked in the tests). That function has no closed form; it is computed here by integrating the
scaled equation with Hairer's eighth-order Runge-Kutta method DOP853 (Dormand & Prince's 8(5,3)
pair, :mod:`microimpact.core.dop853`) at a relative tolerance of 2e-14, its steps chosen by
Gustafsson's predictive controller (the approach falls back to the end of the contact in ever
shorter steps), starting from the series
``x = t - 4/15 kappa t^(5/2) - 4/35 t^(7/2) + 1/15 kappa^2 t^4`` at ``t = 1e-4`` (derived here),
and locating the maximum approach, the maximum force and the end of the contact by root finding
on the step length. (An earlier version integrated with Dormand & Prince's 5(4) pair at 1e-12: four
times the time a point, ``e`` the same to 4e-12 with the force clipped, 6e-11 without.) It agrees with scipy's DOP853 integration of :func:`force` to better than
1e-9 (``tests/core/test_models.py``); ``kappa = 0`` gives Hertz's elastic impact exactly.

**Parameters of this model** (``params``, in this order):

``dissipative_constant`` ``A`` [s], ``>= 0``
    ``A = 0`` is Hertz's elastic impact.
``limit_force`` [0 or 1]
    ``1`` (default): force clipped at zero, the contact ends when it vanishes (Poschel & Schwager
    2005; LAMMPS ``limit_damping``). ``0``: the force may become attractive, the contact ends when the
    approach returns to zero (LAMMPS without ``limit_damping``); at large ``kappa`` the particle
    may then never leave (``e = 0``, ``contact_time = inf``: the integration stops at its bounds,
    :data:`MAX_STEPS`, :data:`T_MAX`, and the impact is flagged in ``outside_validity`` with a warning).

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is the
approach where the contact ends (0 with ``limit_force = 0``; the still-unrecovered deformation
with ``limit_force = 1``). ``p_y`` is not used.

Validity: quasi-static viscoelastic deformation (Brilliantov et al. 1996): impact speeds well
below the speed of sound and below the yield velocity of the material; no plasticity.
"""

from __future__ import annotations

import math

from .. import dop853 as dp
from .. import hertz
from .._jit import jitable
from ..roots import illinois, secant_point
from . import LIMIT_FORCE, Parameter, checks, deprecated_names
from ._common import dem_outcome, in_bounds, nan_outcome

NAME = "hertz_viscoelastic"
TITLE = "Hertz with viscoelastic damping (Brilliantov et al. 1996; LAMMPS damping viscoelastic)"
CITATION = "Brilliantov, Spahn, Hertzsch & Poschel, Phys. Rev. E 53:5382 (1996)"
LABEL = "Hertz viscoelastic"
PARAMETERS = (
    Parameter("dissipative_constant", "s", "A >= 0, viscoelastic dissipative constant of Brilliantov et al.", low=0.0),
    LIMIT_FORCE,
)
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(__name__, NAME)  # released DEFAULTS: one release, with a warning
#: Cost class (the contract's ``COST``): ``e`` integrates the equation of motion, 0.5 ms a point in Python
#: (the whole outcome, which also locates the maximum approach and force, 0.85 ms).
COST = "slow"
#: Order of the zero of :func:`signed_force` where the contact ends: the viscous term cancels the
#: elastic one at a finite approach with the particle moving out, a simple zero.
ZERO_FORCE_ORDER = 1.0

_TOL = 2e-14
_T0 = 1e-4
#: The scaled integration's bounds: accepted or rejected steps, and scaled time. Every clipped
#: contact ends within a few thousand steps and ``t`` of a few units. Without clipping the viscous
#: force pulls the leaving particle in, and a heavily damped one (``kappa`` from about 500 at
#: ``q = 1/2``, from about 3 at Tsuji's ``q = 1/4``) comes to creep, ``x' ~ -x^(3/2-q)/kappa``,
#: which reaches ``x = 0`` only as ``t -> inf``: no integration ends it. At either bound the
#: integration stops and returns that limit, ``e = 0`` and ``t_end = inf``; :func:`reaches_bound`
#: tells such an impact, which the model's ``outside_validity`` flags (bit 4 of
#: :data:`~microimpact.core.models.VALIDITY_REASONS`) with the pair's warning.
MAX_STEPS = 200000
T_MAX = 1e4


@jitable
def _power(x, s, q):
    """``x^q``, given ``s = x^(1/2)``: ``s`` itself where ``q = 1/2`` (a square root, correctly
    rounded and about a fifth of the cost of ``pow``)."""
    return s if q == 0.5 else x**q


@jitable
def _acc(x, v, kappa, q):
    """Scaled acceleration ``-(x^(3/2) + kappa x^q v)`` (no force outside the contact)."""
    if x <= 0.0:
        return 0.0
    s = math.sqrt(x)
    return -(x * s + kappa * _power(x, s, q) * v)


@jitable
def _rates(x, v, p):
    """:func:`_acc` as :func:`~microimpact.core.dop853.step` calls it, ``p = (kappa, q)``: no third state."""
    return _acc(x, v, p[0], p[1]), 0.0


@jitable
def _step(x, v, h, kappa, q):
    """One step of length ``h`` of Hairer's DOP853 (:func:`microimpact.core.dop853.step`): ``(x, v,
    error)``, the error measured as Hairer's code measures it (root mean square over ``x`` and
    ``x'``, each relative to ``_TOL (1e-3 + |new value|)``)."""
    xn, vn, _, e5x, e5v, e3x, e3v = dp.step(_rates, x, v, 0.0, h, (kappa, q))
    return xn, vn, dp.hairer_error(h, e5x, e5v, e3x, e3v, _TOL * (1e-3 + abs(xn)), _TOL * (1e-3 + abs(vn)))


@jitable
def _event(which, x, v, kappa, q):
    """Event functions, each crossing zero from above: 0 top (``x' = 0``), 1 force maximum
    (``x^(1-q) dP/dt``), 2 zero force (``x^(3/2-q) + kappa x'``), 3 zero approach (``x``)."""
    if which == 0:
        return v
    xp = x if x > 0.0 else 0.0
    if which == 1:
        return 1.5 * xp ** (1.5 - q) * v + kappa * (q * v * v + xp * _acc(xp, v, kappa, q))
    if which == 2:
        return x if x <= 0.0 else xp ** (1.5 - q) + kappa * v
    return x


@jitable
def _locate(which, x, v, h, xh, vh, kappa, q):
    """Step length ``0 < s <= h`` from ``(x, v)`` at which event ``which`` crosses zero (Illinois),
    given the step's end ``(xh, vh)``; to ``1e-14 s`` (a few roundings: the event's value is not
    known more closely, and bisecting further only moves ``s`` by an ulp at a time)."""
    a = 0.0
    ga = _event(which, x, v, kappa, q)
    b = h
    gb = _event(which, xh, vh, kappa, q)
    side = 0
    for _ in range(200):
        s = secant_point(a, b, ga, gb)
        xs, vs, _ = _step(x, v, s, kappa, q)
        gs = _event(which, xs, vs, kappa, q)
        if gs == 0.0:  # the root itself (else the secant would return s again and only bisect)
            return s
        a, b, ga, gb, side = illinois(a, b, ga, gb, side, s, gs)
        if b - a <= 1e-14 * (b if b > 1e-300 else 1.0):
            break
    return b


@jitable
def scaled_impact(kappa, clip):
    """Scaled impact ``x'' = -(x^(3/2) + kappa x^(1/2) x')``, ``x(0)=0``, ``x'(0)=1``.

    Returns ``(e, x_max, t_max, p_max, t_end, x_end)`` (see :func:`scaled_damped_hertz`).
    """
    return scaled_damped_hertz(kappa, clip, 0.5)


@jitable
def scaled_damped_hertz(kappa, clip, q):
    """Scaled impact ``x'' = -(x^(3/2) + kappa x^q x')``, ``x(0)=0``, ``x'(0)=1`` (``0 < q < 3/2``).

    Returns ``(e, x_max, t_max, p_max, t_end, x_end)``: restitution, maximum approach and its time,
    maximum scaled force ``x^(3/2) + kappa x^q x'``, and time and approach at the end of the
    contact (``clip``: where the force vanishes; else where ``x`` returns to zero). A contact that has
    not ended within the bounds :data:`MAX_STEPS` and :data:`T_MAX` (possible without ``clip``: a
    particle creeping out, which reaches zero approach only as ``t -> inf``) gives that limit,
    ``e = 0`` and ``t_end = inf``, and :func:`reaches_bound` is True.
    """
    return _integrate(kappa, clip, q, True)


@jitable
def scaled_restitution(kappa, clip, q):
    """``e`` of :func:`scaled_damped_hertz` alone, bit for bit: the same steps, without locating
    the maximum approach and force (which do not change the steps taken)."""
    return _integrate(kappa, clip, q, False)[0]


@jitable
def _integrate(kappa, clip, q, full):
    """:func:`scaled_damped_hertz`; ``full`` False: only ``e`` (the other fields 0)."""
    # series start (derived here): x = t - kappa t^(q+2)/((q+1)(q+2)) - 4/35 t^(7/2)
    #   + 2 kappa^2 t^(2q+3)/((q+2)(2q+2)(2q+3)) + ...
    t = _T0
    t32 = t * math.sqrt(t)
    tq1 = t ** (q + 1.0)
    t2q2 = t ** (2.0 * q + 2.0)
    x = t - kappa * tq1 * t / ((q + 1.0) * (q + 2.0)) - 4.0 / 35.0 * t * t * t32
    x += 2.0 * kappa * kappa * t2q2 * t / ((q + 2.0) * (2.0 * q + 2.0) * (2.0 * q + 3.0))
    v = 1.0 - kappa * tq1 / (q + 1.0) - 0.4 * t * t32 + 2.0 * kappa * kappa * t2q2 / ((q + 2.0) * (2.0 * q + 2.0))
    h = 1e-2 * t
    end_event = 2 if clip else 3
    found_top = False
    found_pmax = False
    x_max = 0.0
    t_max = 0.0
    p_max = 0.0
    h_old = 0.0  # the last accepted step and its error (the predictive controller's memory)
    err_old = 0.0
    for _ in range(MAX_STEPS):
        xn, vn, err = _step(x, v, h, kappa, q)
        if err > 1.0:
            h *= max(0.2, 0.9 * err**-0.125)
            continue
        # events inside the accepted step, in the order they can occur
        if full and not found_pmax and _event(1, xn, vn, kappa, q) <= 0.0:
            s = _locate(1, x, v, h, xn, vn, kappa, q)
            xs, vs, _ = _step(x, v, s, kappa, q)
            rs = math.sqrt(xs)
            p_max = xs * rs + kappa * _power(xs, rs, q) * vs
            found_pmax = True
        if not found_top and vn <= 0.0:
            if full:
                s = _locate(0, x, v, h, xn, vn, kappa, q)
                xs, vs, _ = _step(x, v, s, kappa, q)
                x_max = xs
                t_max = t + s
            found_top = True
        if found_top and _event(end_event, xn, vn, kappa, q) <= 0.0:
            s = _locate(end_event, x, v, h, xn, vn, kappa, q)
            xs, vs, _ = _step(x, v, s, kappa, q)
            # The damping only takes energy (kappa >= 0): e above 1 is the integration's error
            # (1e-13 at kappa = 0), not the law's.
            e = -vs if -vs < 1.0 else 1.0
            return e, x_max, t_max, p_max, t + s, (xs if clip else 0.0)
        t += h
        x = xn
        v = vn
        if t > T_MAX:
            break
        # Gustafsson's predictive controller (Hairer & Wanner, *Solving ODEs II*, Sec. IV.8, as
        # scipy.integrate.Radau's predict_factor writes it): while the steps must shrink, as the
        # approach falls back towards the end of the contact, it shrinks them ahead of a rejection.
        err = max(err, 1e-10)
        trend = 1.0
        if h_old > 0.0:
            trend = min(1.0, h / h_old * (err_old / err) ** 0.125)
        h_old = h
        err_old = err
        h *= min(5.0, 0.9 * trend * err**-0.125)
    return 0.0, x_max, t_max, p_max, math.inf, math.nan


@jitable
def reaches_bound(kappa, clip, q):
    """True where :func:`scaled_damped_hertz` reaches its bounds before the contact ends (``t_end = inf``)."""
    if clip:
        return False
    return _integrate(kappa, clip, q, False)[4] == math.inf


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (see the module docstring; ``p_y`` unused)."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    rho = hertz.stiffness(E, R)
    if V == 0.0:
        return dem_outcome(V, 1.0, 0.0, 0.0, 0.0, R, math.inf, math.inf)
    T = hertz.dem_time_scale(V, E, R, m)
    X = V * T
    kappa = restitution_group(V, E, R, m, p_y, params)
    e, x_max, t_max, p_max, t_end, x_end = scaled_impact(kappa, params[1] == 1.0)
    return dem_outcome(V, e, X * x_max, X * x_end, rho * X * math.sqrt(X) * p_max, R, T * t_max, T * (t_end - t_max))


@jitable
def outside_validity(V, E, R, m, p_y, params):
    """The contract's validity code: 4 where the integration reached its bounds before the contact
    ended (``limit_force = 0`` only: ``e = 0`` and ``contact_time = inf`` are the limit returned); 0
    otherwise (and for invalid input)."""
    if not in_bounds(params, BOUNDS) or not (V > 0.0 and V < math.inf):
        return 0.0
    return 4.0 if reaches_bound(restitution_group(V, E, R, m, p_y, params), params[1] == 1.0, 0.5) else 0.0


@jitable
def restitution_group(V, E, R, m, p_y, params):
    """``kappa = A/T`` [-] of the scaled equation at speed ``V > 0`` [m/s], as :func:`outcome`
    computes it: ``e`` is one function of it (the contract's group hook)."""
    return params[0] / hertz.dem_time_scale(V, E, R, m)


@jitable
def restitution_of_group(kappa, params):
    """``e`` [-] at ``kappa`` (:func:`restitution_group`): the field ``restitution`` of
    :func:`outcome`, bit for bit; NaN for parameters out of bounds."""
    if not in_bounds(params, BOUNDS):
        return math.nan
    return scaled_restitution(kappa, params[1] == 1.0, 0.5)


@jitable
def restitution_only(V, E, R, m, p_y, params):
    """``e`` [-] of :func:`outcome` alone, bit for bit (the contract's hook: fitting compares
    ``e``), without locating the maximum approach and force."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return math.nan
    if V == 0.0:
        return 1.0
    return restitution_of_group(restitution_group(V, E, R, m, p_y, params), params)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """``P = 4/3 E* R*^(1/2) (alpha^(3/2) + A alpha^(1/2) alpha_dot)`` [N] before clipping."""
    if alpha <= 0.0:
        return 0.0
    s = math.sqrt(alpha)
    return 4.0 / 3.0 * E * math.sqrt(R) * (alpha * s + params[0] * s * alpha_dot)


@jitable
def ends_at_zero_force(params):
    """True when the force is clipped at zero (``limit_force`` 1): the contact ends where it vanishes."""
    return params[1] == 1.0


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N]; clipped at zero when ``limit_force`` is 1."""
    p = signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)
    if params[1] == 1.0 and p < 0.0:
        return 0.0
    return p
