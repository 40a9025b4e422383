"""The stages of an oblique impact in normalised units: the seed's closed-form normal history, stage by
stage, and Mindlin's no-slip spring with a Coulomb limit along it.

What every tangential law steps on (:mod:`microimpact.core.tangential_laws`, whose shared stepper
also integrates the seed's own law, :func:`microimpact.core.tangential.integrate_tangential`): the
regime codes, the normal state at a point of a stage (:func:`history_constants`,
:func:`stage_point`), and the stuck and sliding rates of Mindlin's spring (:func:`tangential_rates`,
:func:`switch_function`, the conversions at a stage boundary and where sliding stops). The model,
its normalised units and the numbers ``psi``, ``kappa`` and ``x = V_y / V`` that the outcome depends
on are described in :mod:`microimpact.core.tangential`, which names these functions for users.
Plain floats, :mod:`math` only, ``@jitable``.
"""

from __future__ import annotations

import math

from ._jit import jitable

__all__ = [
    "history_constants",
    "stage_point",
    "tangential_rates",
    "switch_function",
    "REGIME_STICKING",
    "REGIME_SLIDING",
    "REGIME_MICROSLIP",
    "REGIME_ROLLING",
]

#: Regime code: the contact never slid. With any initial slip the stuck contact slides at least
#: as it opens (the stuck force falls as ``a``, the Coulomb limit as ``P ~ a^3``), so this
#: needs zero slip.
REGIME_STICKING = 0
#: Regime code: the contact slid throughout the impact (the Coulomb impulse ``mu J_n``).
REGIME_SLIDING = 1
#: Regime code: the contact stuck and slid in turn (the model's stand-in for micro-slip).
REGIME_MICROSLIP = 2
#: Regime code, rigid model only: the slip was stopped (the sphere leaves rolling).
REGIME_ROLLING = 3

#: Slip change per tangential impulse for a solid sphere, ``m (1/m + r^2/I) = 7/2``.
SLIP_FACTOR = 3.5


@jitable
def history_constants(x):
    """Constants of the normalised closed-form normal history at ``x = V_y / V``.

    Returns ``(elastic, phi1, a_y, k_pl, omega, a_c, amp, theta1, a_star, p_star, rp, a_p,
    depth, v_r)``: ``phi1 = asin(min(1, x))`` the phase at which stage 1 ends; plastic
    stage (THEORY.md section 4: harmonic about ``alpha_y/3``): ``a_y = x^(4/5)``,
    ``k_pl = 15/8 x^(2/5)`` (``pi p_y R*``), ``omega = k_pl^(1/2)``, centre ``a_c = a_y/3``,
    amplitude ``amp``, start phase ``theta1``; maximum approach ``a_star`` and force
    ``p_star`` (seed eqs. 22, 8); ``rp = R_p/R*`` (eq. 9), plastic approach ``a_p`` (eq. 11),
    ``depth = a_star - a_p`` and rebound speed ``v_r = e`` (eqs. 24–27).
    """
    if x >= 1.0:
        return (1.0, 0.5 * math.pi, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.25, 1.0, 0.0, 1.0, 1.0)
    a_y = x**0.8
    k_pl = 1.875 * x**0.4
    omega = math.sqrt(k_pl)
    a_c = a_y / 3.0
    v1 = math.sqrt(max(1.0 - x * x, 0.0))
    amp = math.hypot(a_y - a_c, v1 / omega)
    theta1 = math.asin((a_y - a_c) / amp)
    a_star = a_c + amp
    p_star = k_pl * amp
    f_e = 1.25 * a_star**1.5
    rp = f_e / p_star
    a_p = a_star * (1.0 - p_star / f_e)
    depth = a_star - a_p
    v_r = math.sqrt(0.8 * p_star * depth)
    return (0.0, math.asin(x), a_y, k_pl, omega, a_c, amp, theta1, a_star, p_star, rp, a_p, depth, v_r)


@jitable
def stage_point(stage, v, hc):
    """Normal state at the stage variable ``v`` in [0, 1] of stage 1, 2 or 3.

    Returns ``(dtau_dv, a, adot_over_a, p, pdot, kn)``: the time per unit ``v``, contact
    radius ``a/a_m``, ``(da/dtau)/a``, force ``P^``, ``dP^/dtau`` and normal stiffness
    ``dP^/dalpha^``. Stage 1 (Hertz loading) uses ``phi = phi1 v^5`` with ``alpha^ =
    sin(phi)^(4/5)``, ``dalpha^/dtau = cos(phi)`` (the Hertz energy integral); stage 2
    the phase ``theta = theta1 + (pi/2 - theta1) v`` of the harmonic plastic loading;
    stage 3 the Hertz unloading with ``R_p`` from ``alpha*`` to ``alpha_p``,
    ``phi = pi/2 (1 - v)^5``. The fifth powers make every rate smooth at the contact's
    first and last instants.
    """
    if stage == 1:
        phi1 = hc[1]
        w = v
        w4 = (w * w) * (w * w)  # products, not w**4, w**5: Python's ** is libm's pow, numba's products
        phi = phi1 * (w4 * w)
        s = math.sin(phi)
        if s <= 0.0:
            return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        c = math.cos(phi)
        a = s**0.4
        dtau = 4.0 * phi1 * w4 * s**-0.2
        p = 1.25 * s**1.2
        kn = 1.875 * a
        return (dtau, a, c / (2.0 * s**0.8), p, kn * c, kn)
    if stage == 2:
        theta1 = hc[7]
        omega = hc[4]
        theta = theta1 + (0.5 * math.pi - theta1) * v
        alpha = hc[5] + hc[6] * math.sin(theta)
        adot = hc[6] * omega * math.cos(theta)
        a = math.sqrt(alpha)
        p = hc[3] * (alpha - hc[5])
        return ((0.5 * math.pi - theta1) / omega, a, adot / (2.0 * alpha), p, hc[3] * adot, hc[3])
    w = 1.0 - v
    w4 = (w * w) * (w * w)
    phi = 0.5 * math.pi * (w4 * w)
    s = math.sin(phi)
    if s <= 0.0:
        return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    c = math.cos(phi)
    rp = hc[10]
    depth = hc[12]
    v_r = hc[13]
    q = s**0.8
    a = math.sqrt(rp * depth * q)
    adot = -v_r * c
    dtau = 2.0 * math.pi * depth / v_r * w4 * s**-0.2
    p = 1.25 * math.sqrt(rp) * (depth * q) ** 1.5
    kn = 1.875 * a
    return (dtau, a, adot / (2.0 * depth * q), p, kn * adot, kn)


@jitable
def tangential_rates(stage, v, xs, u, sliding, sign, hc, kappa):
    """``(dX/dv, du^/dv, T^)`` of the tangential state along the normal history.

    ``X`` is the stuck contact's state: the force ``T^`` while the contact grows (stages
    1, 2; ``dT^/dtau = -k^ u^``) and ``S^ = T^/k^`` while it shrinks (stage 3: the force
    scales with the stiffness, ``dS^/dtau = -u^``). Sliding (``sliding`` true),
    ``T^ = -sign P^`` and ``X`` is not used. Always ``du^/dtau = 7/2 T^``.
    """
    dtau, a, _, p, _, _ = stage_point(stage, v, hc)
    kt = 1.875 * kappa * a
    if sliding:
        t = -sign * p
        return (0.0, dtau * SLIP_FACTOR * t, t)
    if stage == 3:
        t = kt * xs
        return (-dtau * u, dtau * SLIP_FACTOR * t, t)
    return (-dtau * kt * u, dtau * SLIP_FACTOR * xs, xs)


@jitable
def switch_function(stage, v, xs, u, sliding, sign, hc, kappa):
    """Positive when the contact must change regime (stick to slip, or slip to stick).

    Stuck: ``|T^| - P^`` (Coulomb limit reached). Sliding in direction ``sign``: minus
    the slip rate times ``k^``, ``-(sign k^ u^ - dP^/dtau + c P^ (da/dtau)/a)`` with
    ``c = 1`` while the contact shrinks (stage 3): the stuck contact's force would fall
    inside the limit.
    """
    _, a, adot_a, p, pdot, _ = stage_point(stage, v, hc)
    kt = 1.875 * kappa * a
    if sliding:
        g = sign * kt * u - pdot
        if stage == 3 and a > 0.0:
            g += p * adot_a
        return -g
    t = kt * xs if stage == 3 else xs
    return abs(t) - p


@jitable
def enter_stage(stage, v, xs, sliding, hc, kappa):
    """Convert the stuck state at a stage boundary: ``T^`` to ``S^ = T^/k^`` entering stage 3."""
    if stage == 3 and not sliding:
        _, a, _, _, _, _ = stage_point(3, v, hc)
        return xs / (1.875 * kappa * a)
    return xs


@jitable
def leave_slip(stage, v, sign, hc, kappa):
    """Stuck state at the instant sliding stops: ``T^ = -sign P^`` (``S^ = T^/k^`` in stage 3)."""
    _, a, _, p, _, _ = stage_point(stage, v, hc)
    t = -sign * p
    if stage == 3:
        return t / (1.875 * kappa * a)
    return t
