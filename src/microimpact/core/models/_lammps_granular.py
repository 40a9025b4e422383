"""The damped adhesive normal laws of LAMMPS' ``pair_style granular`` (``jkr``, ``dmt``) as one
equation of motion (private: not a model; :mod:`~microimpact.core.models.lammps_jkr` and
:mod:`~microimpact.core.models.lammps_dmt` are its two faces of the contract).

What LAMMPS computes (read in lammps/lammps ``src/GRANULAR/granular_model.cpp``
``GranularModel::calculate_forces``, ``gran_sub_mod_normal.cpp`` and ``gran_sub_mod_damping.cpp``,
the sources of the 22 Jul 2025 release's era): while the contact exists, the total normal force is
``F_n = F_ne + F_damp`` with ``F_damp = -eta_n v_n`` (``v_n`` the relative normal velocity, so that
``F_damp = eta_n alpha'`` with the approach rate ``alpha'``), and no clipping (``limit_damping`` is
refused with a cohesive normal model: "Cannot limit damping with a cohesive normal model"). The
damping factor ``eta_n`` of each ``damping`` keyword:

* ``viscoelastic`` (mode 0): ``eta_n = eta_n0 m* a``, ``a`` the normal model's contact radius (JKR's
  from its closed-form inversion, positive in the adhesive neck at negative approach: there the
  damping keeps acting; DMT's ``(R* alpha)^(1/2)``);
* ``tsuji`` (mode 1) and ``coeff_restitution`` (mode 2): ``eta_n = c (m* max(0, F_ne/alpha))^(1/2)``
  for ``alpha > 0``, else 0, with ``F_ne`` the normal model's whole force, cohesion included, and ``c``
  Marshall's polynomial of ``e_n`` (``tsuji``) or ``5^(1/2) (-ln e_n)/(pi^2 + ln^2 e_n)^(1/2)``
  (``coeff_restitution``, its branch for every normal model but ``hooke``). With cohesion
  ``F_ne/alpha`` is negative over the tensile part of the contact: there the guard ``max(0, .)``
  switches the damping off (the releases of 2024 without the guard took the square root of a
  negative number: NaN positions; see docs/laws/lammps_jkr_dmt.rst). LAMMPS 22 Jul 2025 refuses both keywords with
  ``jkr`` or ``dmt`` ("Cannot use tsuji model with a cohesive normal model", ``granular_model.cpp``,
  ``allow_cohesion = 0``): these modes are what its damping kernel would compute, flagged.

The impact on a flat wall (``fix wall/gran granular``: ``R* = `` the radius, ``m* = `` the mass) is
integrated here: ``m* alpha'' = -F_n`` from ``alpha = 0``, ``alpha' = V``, with Hairer's DOP853 pair
(:mod:`microimpact.core.dop853`) at a relative tolerance of 1e-12, the turning point, the end of the
contact and a second turning point (capture) located by the Illinois method on the step length. The
contact ends where the approach falls below the normal model's separation approach (``-delta_c``
for JKR, 0 for DMT); a particle whose approach rate vanishes again before that is captured
(``e = 0``): every mode dissipates (``F_damp alpha' >= 0``) and the elastic force is conservative, so
it can never leave. The energy the damping takes is integrated with the motion (a third state).

Without damping and without a neck (DMT, or JKR without cohesion) the law is conservative and
time-reversible (``m* alpha'' = -F_ne(alpha)``): the unloading retraces the loading, and the particle
leaves at zero approach after twice the loading time with exactly its impact speed (``e = 1``), which
is what LAMMPS converges to as its step falls (its velocity Verlet crosses the force's jump at zero
approach with an error in the square of the step: for the 0.3 um silicon sphere below at 1 mm/s,
``e = 0.99990`` at 20000 steps per contact and ``0.9999936`` at 80000). The integration then stops
at the turning point. Integrating the unloading instead would decide on leaving by an energy
balance the integrator cannot hold there: the DMT pull ``4 pi gamma R*`` speeds a slow particle up to
``(2 F_c alpha_eq/m*)^(1/2)`` in the well (9 m/s for a 0.3 um silicon sphere with ``gamma = 0.1``
J/m^2), and the tolerance, relative to that, leaves an energy error larger than the impact energy at
1 mm/s (a ratio of 1e8): the particle turned a hair short of zero approach and was taken as captured.
"""

from __future__ import annotations

import math

from .. import dop853 as dp
from .._jit import jitable
from ..roots import illinois, secant_point
from ._common import dem_outcome, nan_outcome
from .hertz_tsuji import alpha_coeff_restitution, alpha_tsuji
from .jkr_elastic_adhesive import WORK_CONSTANT, contact_radius, pulloff_approach
from .jkr_elastic_adhesive import signed_force as jkr_elastic_force

#: The normal models: 0 ``jkr``, 1 ``dmt``.
JKR = 0
DMT = 1
#: The damping keywords by mode.
DAMPING_NAMES = ("viscoelastic", "tsuji", "coeff_restitution")

_TOL = 1e-12
_MAX_STEPS = 400000


@jitable
def damping_factor(mode, coeff):
    """The constant of ``eta_n`` LAMMPS' ``init()`` makes of the damping input ``coeff``: ``eta_n0``
    itself (viscoelastic), Marshall's polynomial of ``e_n`` (tsuji), ``5^(1/2)(-ln e_n)/(pi^2 +
    ln^2 e_n)^(1/2)`` (coeff_restitution: at ``e_n = 0`` LAMMPS divides infinity by infinity, NaN)."""
    if mode == 0.0:
        return coeff
    if mode == 1.0:
        return alpha_tsuji(coeff)
    if coeff == 0.0:
        return math.nan
    return alpha_coeff_restitution(coeff)


@jitable
def elastic_force(kind, alpha, E, R, gamma):
    """``F_ne`` [N] of the normal model at approach ``alpha`` (in contact; JKR's curve is held at
    its end ``-delta_c`` below it, where only a step's trial stages look: the closed-form radius has
    no real value far beyond the end)."""
    if kind == JKR:
        if gamma > 0.0:
            alpha = max(alpha, -pulloff_approach(E, R, gamma))
        return jkr_elastic_force(alpha, 0.0, 0.0, E, R, 1.0, math.inf, (gamma,))
    a = math.sqrt(R * alpha) if alpha > 0.0 else 0.0
    return 4.0 / 3.0 * E * a * alpha - 4.0 * math.pi * gamma * R


@jitable
def radius(kind, alpha, E, R, gamma):
    """The normal model's contact radius ``a`` [m] (what ``damping viscoelastic`` multiplies)."""
    if kind == JKR and gamma > 0.0:
        return contact_radius(max(alpha, -pulloff_approach(E, R, gamma)), E, R, gamma)
    return math.sqrt(R * alpha) if alpha > 0.0 else 0.0


@jitable
def damping_force(kind, mode, factor, alpha, alpha_dot, E, R, m, gamma):
    """``F_damp = eta_n alpha'`` [N] (module docstring), ``factor`` from :func:`damping_factor`."""
    if factor == 0.0:
        return 0.0
    if mode == 0.0:
        return factor * m * radius(kind, alpha, E, R, gamma) * alpha_dot
    if not alpha > 0.0:
        return 0.0
    ratio = m * elastic_force(kind, alpha, E, R, gamma) / alpha
    if not ratio > 0.0:
        return 0.0
    return factor * math.sqrt(ratio) * alpha_dot


@jitable
def total_force(kind, mode, factor, alpha, alpha_dot, E, R, m, gamma):
    """``F_n = F_ne + F_damp`` [N] in contact (positive: repulsive)."""
    return elastic_force(kind, alpha, E, R, gamma) + damping_force(kind, mode, factor, alpha, alpha_dot, E, R, m, gamma)


@jitable
def separation(kind, E, R, gamma):
    """Approach [m] at which the contact breaks: ``-delta_c`` (JKR with cohesion), else 0."""
    if kind == JKR and gamma > 0.0:
        return -pulloff_approach(E, R, gamma)
    return 0.0


@jitable
def _rates(x, v, p):
    """``(alpha'', dissipation rate)`` of the state ``(x, v)``; ``p = (kind, mode, factor, E, R, m, gamma)``."""
    kind, mode, factor, E, R, m, gamma = p
    fd = damping_force(kind, mode, factor, x, v, E, R, m, gamma)
    return -(elastic_force(kind, x, E, R, gamma) + fd) / m, fd * v


@jitable
def _step(x, v, w, h, kind, mode, factor, E, R, m, gamma, sx, sv):
    """One DOP853 step of ``(alpha, alpha', dissipated work)`` (:func:`microimpact.core.dop853.step`):
    ``(x, v, w, error)`` with Hairer's error measure, ``x`` and ``v`` weighed with ``_TOL (scale + |value|)``."""
    xn, vn, wn, e5x, e5v, e3x, e3v = dp.step(_rates, x, v, w, h, (kind, mode, factor, E, R, m, gamma))
    return xn, vn, wn, dp.hairer_error(h, e5x, e5v, e3x, e3v, _TOL * (sx + abs(xn)), _TOL * (sv + abs(vn)))


@jitable
def _event(which, x, v, x_sep):
    """0: the approach rate (its zero: a turning point); 1: the approach above separation."""
    if which == 0:
        return v
    return x - x_sep


@jitable
def _locate(which, sign, x, v, w, h, xh, vh, kind, mode, factor, E, R, m, gamma, sx, sv, x_sep):
    """Step ``0 < s <= h`` at which event ``which`` (times ``sign``, falling through zero) vanishes:
    the Illinois method on the step length, re-stepping from ``(x, v)``."""
    a = 0.0
    ga = sign * _event(which, x, v, x_sep)
    b = h
    gb = sign * _event(which, xh, vh, x_sep)
    side = 0
    for _ in range(200):
        s = secant_point(a, b, ga, gb)
        xs, vs, _, _ = _step(x, v, w, s, kind, mode, factor, E, R, m, gamma, sx, sv)
        gs = sign * _event(which, xs, vs, x_sep)
        if gs == 0.0:
            return s
        a, b, ga, gb, side = illinois(a, b, ga, gb, side, s, gs)
        if b - a <= 1e-15 * b:
            break
    return b


@jitable
def impact(kind, mode, factor, V, E, R, m, gamma):
    """One impact at ``V > 0``: ``(e, alpha_max, t_max, F_max, t_end, dissipated, end)``.

    ``end`` 1: the particle left (``t_end`` the contact time, ``dissipated`` the damping's work [J];
    a conservative contact, no damping and no neck, leaves with ``e = 1`` at twice its loading time).
    Else it was captured: ``e`` 0, ``t_end`` the time of its second turning point ``alpha_2``,
    ``dissipated`` the work up to there, and ``end`` the negative measure ``-(alpha_2 -
    alpha_sep)/scale`` of how far from leaving it turned (:func:`escape_measure`)."""
    x_sep = separation(kind, E, R, gamma)
    conservative = factor == 0.0 and not (kind == JKR and gamma > 0.0)
    # length and speed scales of the error weights: Hertz's approach at V and the neck
    sx = (15.0 * m * V * V / (16.0 * E * math.sqrt(R))) ** 0.4 + abs(x_sep)
    if kind == DMT and gamma > 0.0:
        sx += (3.0 * math.pi * gamma * math.sqrt(R) / E) ** (2.0 / 3.0)
    sv = V
    t = 0.0
    x = 0.0
    v = V
    w = 0.0
    h = 1e-3 * sx / V
    phase = 0  # 0 loading (v > 0), 1 unloading (v < 0)
    x_max = 0.0
    t_max = 0.0
    f_max = total_force(kind, mode, factor, x, v, E, R, m, gamma)
    # the force's largest value: the two steps around the largest one at a step's end, searched later
    xb = x
    vb = v
    span = 0.0
    pending = False
    xp = x
    vp = v
    for _ in range(_MAX_STEPS):
        xn, vn, wn, err = _step(x, v, w, h, kind, mode, factor, E, R, m, gamma, sx, sv)
        if not (err <= 1.0):
            if err != err:
                return math.nan, math.nan, math.nan, math.nan, math.nan, math.nan, math.nan
            h *= max(0.2, 0.9 * err ** (-1.0 / 8.0))
            continue
        done = 0.0
        s = h
        if phase == 0 and vn <= 0.0:
            s = _locate(0, 1.0, x, v, w, h, xn, vn, kind, mode, factor, E, R, m, gamma, sx, sv, x_sep)
            done = 2.0
        elif phase == 1 and xn <= x_sep:
            s = _locate(1, 1.0, x, v, w, h, xn, vn, kind, mode, factor, E, R, m, gamma, sx, sv, x_sep)
            done = 1.0
        elif phase == 1 and vn >= 0.0 and x < x_max:
            s = _locate(0, -1.0, x, v, w, h, xn, vn, kind, mode, factor, E, R, m, gamma, sx, sv, x_sep)
            done = -1.0
            # a particle that barely leaves turns within the step that carries it past the separation
            # approach, where the force's continuation still pulls (DMT's constant pull, JKR's end
            # value): the step ends in contact again, but it left at the crossing before the turn
            xs, vs, _, _ = _step(x, v, w, s, kind, mode, factor, E, R, m, gamma, sx, sv)
            if xs <= x_sep:
                s = _locate(1, 1.0, x, v, w, s, xs, vs, kind, mode, factor, E, R, m, gamma, sx, sv, x_sep)
                done = 1.0
        if s != h:
            xn, vn, wn, _ = _step(x, v, w, s, kind, mode, factor, E, R, m, gamma, sx, sv)
        xp, vp = x, v
        x, v, w = xn, vn, wn
        t += s
        if pending:
            span += s
            pending = False
        f = total_force(kind, mode, factor, x, v, E, R, m, gamma)
        if f > f_max:
            f_max = f
            xb, vb, span = xp, vp, s
            pending = True
        if done == 2.0:
            x_max = x
            t_max = t
            phase = 1
            if conservative:  # the unloading retraces the loading (module docstring): leaves at 2 t_max
                f_max = _largest_force(xb, vb, w, span, f_max, kind, mode, factor, E, R, m, gamma, sx, sv)
                return 1.0, x_max, t_max, f_max, 2.0 * t_max, w, 1.0
        elif done != 0.0:
            f_max = _largest_force(xb, vb, w, span, f_max, kind, mode, factor, E, R, m, gamma, sx, sv)
            if done == 1.0:
                return -v / V, x_max, t_max, f_max, t, w, 1.0
            return 0.0, x_max, t_max, f_max, t, w, -(x - x_sep) / sx
        else:
            h *= min(4.0, 0.9 * err ** (-1.0 / 8.0)) if err > 0.0 else 4.0
    return math.nan, math.nan, math.nan, math.nan, math.nan, math.nan, math.nan


@jitable
def _largest_force(x, v, w, span, f_best, kind, mode, factor, E, R, m, gamma, sx, sv):
    """The largest total force over ``[0, span]`` of steps from ``(x, v)``: golden-section search
    (the force is unimodal over the two steps around its largest sampled value), to 1e-14 of the span."""
    if not span > 0.0:
        return f_best
    g = 0.5 * (math.sqrt(5.0) - 1.0)
    a = 0.0
    b = span
    c = b - g * (b - a)
    d = a + g * (b - a)
    xc, vc, _, _ = _step(x, v, w, c, kind, mode, factor, E, R, m, gamma, sx, sv)
    fc = total_force(kind, mode, factor, xc, vc, E, R, m, gamma)
    xd, vd, _, _ = _step(x, v, w, d, kind, mode, factor, E, R, m, gamma, sx, sv)
    fd = total_force(kind, mode, factor, xd, vd, E, R, m, gamma)
    for _ in range(120):
        if fc > fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            xc, vc, _, _ = _step(x, v, w, c, kind, mode, factor, E, R, m, gamma, sx, sv)
            fc = total_force(kind, mode, factor, xc, vc, E, R, m, gamma)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            xd, vd, _, _ = _step(x, v, w, d, kind, mode, factor, E, R, m, gamma, sx, sv)
            fd = total_force(kind, mode, factor, xd, vd, E, R, m, gamma)
        if b - a <= 1e-14 * span:
            break
    return max(f_best, fc, fd)


@jitable
def escape_measure(kind, mode, factor, V, E, R, m, gamma):
    """A continuous measure of leaving at ``V``: ``e`` where the particle leaves, minus the scaled
    distance between its second turning point and the separation approach where it is captured;
    its zero is the capture velocity."""
    r = impact(kind, mode, factor, V, E, R, m, gamma)
    if r[6] == 1.0:
        return r[0]
    return r[6]


@jitable
def capture_velocity(kind, mode, factor, E, R, m, gamma):
    """The capture velocity ``V_s`` [m/s]: the root of :func:`escape_measure` (Illinois, to 1e-12
    relative), 0 where even the slowest impact leaves (no damping and no JKR neck)."""
    if factor == 0.0 and not (kind == JKR and gamma > 0.0):
        return 0.0  # a conservative law without a neck returns every impact (DMT: e = 1)
    # a speed scale: the undamped JKR pull-off speed, or the speed the DMT pull gives over its
    # equilibrium approach
    if kind == JKR and gamma > 0.0:
        ref = math.sqrt(2.0 * 1.65 * E * R ** (4.0 / 3.0) * (math.pi * gamma / E) ** (5.0 / 3.0) / m)
    elif gamma > 0.0:
        Fc = 4.0 * math.pi * gamma * R
        a_eq = (Fc / (4.0 / 3.0 * E * math.sqrt(R))) ** (2.0 / 3.0)
        ref = math.sqrt(2.0 * Fc * a_eq / m)
    else:
        return 0.0
    hi = ref
    g_hi = escape_measure(kind, mode, factor, hi, E, R, m, gamma)
    if g_hi != g_hi:
        return math.nan
    lo = hi
    g_lo = g_hi
    if g_hi <= 0.0:
        for _ in range(200):
            lo, g_lo = hi, g_hi
            hi *= 2.0
            g_hi = escape_measure(kind, mode, factor, hi, E, R, m, gamma)
            if g_hi > 0.0 or g_hi != g_hi:
                break
    else:
        for _ in range(80):
            hi, g_hi = lo, g_lo
            lo *= 0.5
            g_lo = escape_measure(kind, mode, factor, lo, E, R, m, gamma)
            if g_lo <= 0.0 or g_lo != g_lo:
                break
        if g_lo > 0.0:
            return 0.0
    if not (g_lo <= 0.0 and g_hi > 0.0):
        return math.nan
    side = 0
    for _ in range(200):
        s = (lo * g_hi - hi * g_lo) / (g_hi - g_lo)
        if not (s > lo and s < hi):
            s = 0.5 * (lo + hi)
        g = escape_measure(kind, mode, factor, s, E, R, m, gamma)
        if g > 0.0:
            hi, g_hi = s, g
            if side == 1:
                g_lo *= 0.5
            side = 1
        else:
            lo, g_lo = s, g
            if side == -1:
                g_hi *= 0.5
            side = -1
        if hi - lo <= 1e-12 * hi:
            break
    return hi


@jitable
def outcome(kind, V, E, R, m, valid, gamma, mode, coeff):
    """The contract's outcome tuple of one impact (``valid``: the parameters passed the checks)."""
    if not valid or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    if V == 0.0:
        return dem_outcome(V, 0.0 if gamma > 0.0 else 1.0, 0.0, 0.0, 0.0, R, math.inf, math.inf)
    factor = damping_factor(mode, coeff)
    e, x_max, t_max, f_max, t_end, _, end = impact(kind, mode, factor, V, E, R, m, gamma)
    if e != e:
        return nan_outcome(V)
    if end != 1.0:
        return dem_outcome(V, 0.0, x_max, separation(kind, E, R, gamma), f_max, R, t_max, math.inf)
    if factor == 0.0 and not (kind == JKR and gamma > 0.0):
        e = 1.0  # a conservative curve left where it was entered: exactly the speed it came with
    return dem_outcome(V, e, x_max, separation(kind, E, R, gamma), f_max, R, t_max, t_end - t_max)


@jitable
def energy_budget(kind, V, E, R, m, gamma, mode, coeff):
    """``(K_in, W_adhesion, W_damping, K_out)`` [J] of one impact that leaves: the impact energy, the
    work the elastic-adhesive curve keeps (JKR's neck between zero approach and ``-delta_c``; 0 for
    DMT, whose curve is left where it was entered), the damping's work (integrated with the motion)
    and the rebound energy. ``K_in = W_adhesion + W_damping + K_out`` up to the integration's
    error; NaN for a captured particle (``K_out`` is then 0 and the rest is still moving)."""
    factor = damping_factor(mode, coeff)
    e, _, _, _, _, w, end = impact(kind, mode, factor, V, E, R, m, gamma)
    K = 0.5 * m * V * V
    if end != 1.0:
        return K, math.nan, math.nan, 0.0
    W_ad = 0.0
    if kind == JKR and gamma > 0.0:
        W_ad = WORK_CONSTANT * E * R ** (4.0 / 3.0) * (math.pi * gamma / E) ** (5.0 / 3.0)
    return K, W_ad, w, 0.5 * m * (e * V) * (e * V)


@jitable
def mode_of(x):
    """The damping keyword's number, 0, 1 or 2, of the parameter ``damping_model`` in [0, 2] (a value
    between two integers is read as the one below it, as C's cast of a float to an int)."""
    return float(math.floor(x))


@jitable
def damping_input(params):
    """``(mode, input)``: the damping keyword's number and the input it reads (``eta_n0`` for
    viscoelastic, ``e_n`` else) of ``params = (gamma, damping_model, eta_n0, e_n)``."""
    mode = mode_of(params[1])
    return mode, params[2] if mode == 0.0 else params[3]


@jitable
def refused(params):
    """The ``outside_validity`` code: 8 where LAMMPS 22 Jul 2025 refuses the damping keyword with a
    cohesive normal model (tsuji, coeff_restitution), plus 1 where the damping factor is negative
    (an ``e_n > 1``, which LAMMPS does not check): the damping then feeds energy in."""
    mode, coeff = damping_input(params)
    code = 8.0 if mode != 0.0 else 0.0
    if damping_factor(mode, coeff) < 0.0:
        code += 1.0
    return code
