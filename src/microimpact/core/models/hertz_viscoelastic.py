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
scaled equation with an embedded Runge-Kutta 5(4) pair (Dormand & Prince; tableau as in
:class:`scipy.integrate.RK45`) at a relative tolerance of 1e-12, starting from the series
``x = t - 4/15 kappa t^(5/2) - 4/35 t^(7/2) + 1/15 kappa^2 t^4`` at ``t = 1e-4`` (derived here),
and locating the maximum approach, the maximum force and the end of the contact by root finding
on the step length. It agrees with scipy's DOP853 integration of :func:`force` to better than
1e-9 (``tests/core/test_models.py``); ``kappa = 0`` gives Hertz's elastic impact exactly.

**Parameters of this model** (``params``, in this order):

``dissipative_constant`` ``A`` [s], ``>= 0``
    ``A = 0`` is Hertz's elastic impact.
``limit_force`` [0 or 1]
    ``1`` (default): force clipped at zero, the contact ends when it vanishes (Poschel & Schwager
    2005; LAMMPS ``limit_damping``). ``0``: the force may become attractive, the contact ends when the
    approach returns to zero (LAMMPS without ``limit_damping``); at large ``kappa`` the particle
    may then never leave (``e = 0``, ``contact_time = inf``).

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is the
approach where the contact ends (0 with ``limit_force = 0``; the still-unrecovered deformation
with ``limit_force = 1``). ``p_y`` is not used.

Validity: quasi-static viscoelastic deformation (Brilliantov et al. 1996): impact speeds well
below the speed of sound and below the yield velocity of the material; no plasticity.
"""

from __future__ import annotations

import math

from .. import hertz
from .._jit import jitable
from . import LIMIT_FORCE, Parameter, checks, deprecated_names
from ._common import dem_outcome, in_bounds, nan_outcome

NAME = "hertz_viscoelastic"
TITLE = "Hertz with viscoelastic damping (Brilliantov et al. 1996; LAMMPS damping viscoelastic)"
LABEL = "Hertz viscoelastic"
PARAMETERS = (
    Parameter("dissipative_constant", "s", "A >= 0, viscoelastic dissipative constant of Brilliantov et al.", low=0.0),
    LIMIT_FORCE,
)
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(__name__, NAME)  # released DEFAULTS: one release, with a warning
#: Cost class (the contract's ``COST``): ``e`` integrates the equation of motion, 2.3 ms a point in Python.
COST = "slow"
#: Order of the zero of :func:`signed_force` where the contact ends: the viscous term cancels the
#: elastic one at a finite approach with the particle moving out, a simple zero.
ZERO_FORCE_ORDER = 1.0

# Dormand-Prince 5(4) tableau (as in scipy.integrate.RK45).
_A21 = 1.0 / 5.0
_A31, _A32 = 3.0 / 40.0, 9.0 / 40.0
_A41, _A42, _A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
_A51, _A52, _A53, _A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
_A61, _A62, _A63, _A64, _A65 = 9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0
_B1, _B3, _B4, _B5, _B6 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
_E1, _E3, _E4, _E5, _E6, _E7 = (
    -71.0 / 57600.0,
    71.0 / 16695.0,
    -71.0 / 1920.0,
    17253.0 / 339200.0,
    -22.0 / 525.0,
    1.0 / 40.0,
)
_TOL = 1e-12
_T0 = 1e-4
_MAX_STEPS = 200000
_T_MAX = 1e4


@jitable
def _acc(x, v, kappa, q):
    """Scaled acceleration ``-(x^(3/2) + kappa x^q v)`` (no force outside the contact)."""
    if x <= 0.0:
        return 0.0
    return -(x * math.sqrt(x) + kappa * x**q * v)


@jitable
def _step(x, v, h, kappa, q):
    """One Dormand-Prince step of length ``h``: ``(x, v, error estimate)``."""
    k1x = v
    k1v = _acc(x, v, kappa, q)
    x2 = x + h * _A21 * k1x
    v2 = v + h * _A21 * k1v
    k2x = v2
    k2v = _acc(x2, v2, kappa, q)
    x3 = x + h * (_A31 * k1x + _A32 * k2x)
    v3 = v + h * (_A31 * k1v + _A32 * k2v)
    k3x = v3
    k3v = _acc(x3, v3, kappa, q)
    x4 = x + h * (_A41 * k1x + _A42 * k2x + _A43 * k3x)
    v4 = v + h * (_A41 * k1v + _A42 * k2v + _A43 * k3v)
    k4x = v4
    k4v = _acc(x4, v4, kappa, q)
    x5 = x + h * (_A51 * k1x + _A52 * k2x + _A53 * k3x + _A54 * k4x)
    v5 = v + h * (_A51 * k1v + _A52 * k2v + _A53 * k3v + _A54 * k4v)
    k5x = v5
    k5v = _acc(x5, v5, kappa, q)
    x6 = x + h * (_A61 * k1x + _A62 * k2x + _A63 * k3x + _A64 * k4x + _A65 * k5x)
    v6 = v + h * (_A61 * k1v + _A62 * k2v + _A63 * k3v + _A64 * k4v + _A65 * k5v)
    k6x = v6
    k6v = _acc(x6, v6, kappa, q)
    xn = x + h * (_B1 * k1x + _B3 * k3x + _B4 * k4x + _B5 * k5x + _B6 * k6x)
    vn = v + h * (_B1 * k1v + _B3 * k3v + _B4 * k4v + _B5 * k5v + _B6 * k6v)
    k7x = vn
    k7v = _acc(xn, vn, kappa, q)
    ex = h * (_E1 * k1x + _E3 * k3x + _E4 * k4x + _E5 * k5x + _E6 * k6x + _E7 * k7x)
    ev = h * (_E1 * k1v + _E3 * k3v + _E4 * k4v + _E5 * k5v + _E6 * k6v + _E7 * k7v)
    err = max(abs(ex) / (_TOL * (1e-3 + abs(xn))), abs(ev) / (_TOL * (1e-3 + abs(vn))))
    return xn, vn, err


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
def _locate(which, x, v, h, kappa, q):
    """Step length ``0 < s <= h`` from ``(x, v)`` at which event ``which`` crosses zero (Illinois)."""
    a = 0.0
    ga = _event(which, x, v, kappa, q)
    b = h
    xb, vb, _ = _step(x, v, b, kappa, q)
    gb = _event(which, xb, vb, kappa, q)
    side = 0
    for _ in range(200):
        s = (a * gb - b * ga) / (gb - ga)
        if not (s > a and s < b):
            s = 0.5 * (a + b)
        xs, vs, _ = _step(x, v, s, kappa, q)
        gs = _event(which, xs, vs, kappa, q)
        if gs > 0.0:
            a = s
            ga = gs
            if side == -1:
                gb *= 0.5
            side = -1
        else:
            b = s
            gb = gs
            if side == 1:
                ga *= 0.5
            side = 1
        if b - a <= 1e-15 * (b if b > 1e-300 else 1.0):
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
    contact (``clip``: where the force vanishes; else where ``x`` returns to zero). A particle that
    never leaves (possible without ``clip``) gives ``e = 0`` and ``t_end = inf``.
    """
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
    for _ in range(_MAX_STEPS):
        xn, vn, err = _step(x, v, h, kappa, q)
        if err > 1.0:
            h *= max(0.2, 0.9 * err**-0.2)
            continue
        # events inside the accepted step, in the order they can occur
        if not found_pmax and _event(1, xn, vn, kappa, q) <= 0.0:
            s = _locate(1, x, v, h, kappa, q)
            xs, vs, _ = _step(x, v, s, kappa, q)
            p_max = xs * math.sqrt(xs) + kappa * xs**q * vs
            found_pmax = True
        if not found_top and vn <= 0.0:
            s = _locate(0, x, v, h, kappa, q)
            xs, vs, _ = _step(x, v, s, kappa, q)
            x_max = xs
            t_max = t + s
            found_top = True
        if found_top and _event(end_event, xn, vn, kappa, q) <= 0.0:
            s = _locate(end_event, x, v, h, kappa, q)
            xs, vs, _ = _step(x, v, s, kappa, q)
            return -vs, x_max, t_max, p_max, t + s, (xs if clip else 0.0)
        t += h
        x = xn
        v = vn
        if t > _T_MAX:
            break
        h *= min(5.0, 0.9 * max(err, 1e-10) ** -0.2)
    return 0.0, x_max, t_max, p_max, math.inf, math.nan


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
    kappa = params[0] / T
    e, x_max, t_max, p_max, t_end, x_end = scaled_impact(kappa, params[1] == 1.0)
    return dem_outcome(V, e, X * x_max, X * x_end, rho * X * math.sqrt(X) * p_max, R, T * t_max, T * (t_end - t_max))


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
