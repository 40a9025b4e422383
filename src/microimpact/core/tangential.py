"""Tangential compliance in an oblique impact: Mindlin's no-slip spring with a Coulomb limit.

Model (one scalar source for every path; plain floats, :mod:`math` only, ``@jitable``):

* Tangential stiffness of the contact, Mindlin's no-slip value ``k_t = 8 G* a`` with the
  contact radius ``a`` of the seed's normal history and
  ``1/G* = (2 - nu1)/G1 + (2 - nu2)/G2``, ``G = E / (2 (1 + nu))``. This is the LAMMPS
  ``pair_style granular`` documentation's *tangential mindlin* (force ``k_t a xi`` with
  ``k_t = 4 G/(2 - nu)`` per body, i.e. ``8 G* a``, and its mixing rule
  ``1/G = 2(2 - nu_i)(1 + nu_i)/E_i + 2(2 - nu_j)(1 + nu_j)/E_j``), and the stiffness of
  Chung & Ooi's (2011) Test 4 as YADE scripts it (``Kso = 8 sqrt(r) G``).
* Incremental loading (LAMMPS's *mindlin_rescale/force* form): while the contact grows,
  ``dT = -k_t u dt`` (the force is a history variable, incremented by the stiffness of the
  moment); while it shrinks, the force is first rescaled with the contact radius,
  ``T <- T a / a_old``, then incremented. The LAMMPS documentation gives the rescaling
  ``xi = xi_(n-1) a / a_(n-1)`` "if a < a_(n-1)", states that without it spurious energy is
  created (Walton), and refers to Thornton et al. (2013) eq. 18(b); that paper itself could
  not be read here, nor Thornton & Yin (1991), Maw, Barber & Fawcett (1976) or Di Renzo &
  Di Maio (2004, 2005). ``|T| <= mu P`` (Coulomb); at the limit the contact slides. The
  micro-slip annulus of the full Mindlin–Deresiewicz solution is not resolved (the
  "no-slip" simplification DEM codes use); stick–slip alternation stands in for it.
  Chosen because it is a closed set of rules in ``a(t)`` and ``P(t)`` only, so the seed's
  closed-form history drives it exactly and the outcome collapses onto a universal curve,
  and because it never creates energy: with ``U = T^2 / (2 k_t)``, ``dU <= T du`` in every
  regime (while ``a`` grows the stored energy loses ``T^2 dk/(2 k^2)``, the rescaling
  ``T^2 |dk|/(2 k^2)``, sliding ``mu P |slip rate|``).
* The normal direction is the seed's closed-form history (THEORY.md sections 2–4):
  Hertz loading ``a^2 = R* alpha``, plastic loading ``P = P_y + pi p_y R* (alpha -
  alpha_y)`` with ``a^2 = R* alpha`` (Thornton & Ning), elastic unloading with ``R_p``
  and ``a^2 = R_p (alpha - alpha_p)``. The tangential force does not feed back on it.
* A solid sphere (``I = 2/5 m r^2``): the slip ``u = v_t + r omega`` of the contact
  point changes at ``du/dt = T (1/m + r^2/I) = 7 T / (2 m)``.

Normalised form (derived here; every quantity of one impact follows from three numbers).
Lengths in ``alpha_m`` (maximum approach of the elastic impact at the normal speed
``V``), time in ``alpha_m / V``, normal force in ``m V^2 / alpha_m``, the tangential force
in ``mu m V^2 / alpha_m`` and the slip in ``mu V``. Then Hertz gives ``P^ = 5/4
(a/a_m)^3`` with ``a_m = (R* alpha_m)^(1/2)``, the tangential stiffness is ``k^ = 15/8
kappa (a / a_m)`` with

    kappa = 4 G* / E*      (= 2 (1 - nu) / (2 - nu) for one material on a rigid flat)

and the outcome depends only on

* ``psi = kappa u0 / (mu V)``: the normalised impact angle (for a non-spinning sphere
  ``psi = kappa tan(theta) / mu``, theta from the normal). ``psi`` is also the ratio
  ``|T| / mu P`` the stuck contact would need at first touch, so ``psi > 1`` slides from
  the start. Maw, Barber & Fawcett (1976) and Thornton & Yin (1991) use an angle of this
  form; the factor here is that of this model;
* ``kappa`` (Poisson's ratios and moduli, through ``G*/E*``);
* ``x = V_y / V`` (1 or more: elastic), the seed's normalised speed.

Spin enters through ``u0`` only. Results are the tangential impulse ``J^ = J_t / (mu m
V)`` (signed, along the initial slip) and the final slip ``u^_r = u^_0 + 7/2 J^``.
"""

from __future__ import annotations

import math

from ._jit import jitable

__all__ = [
    "shear_modulus",
    "effective_shear_modulus",
    "mindlin_stiffness",
    "stiffness_ratio",
    "stiffness_ratio_same_poisson",
    "normalized_angle",
    "rigid_impulse",
    "history_constants",
    "stage_point",
    "tangential_rates",
    "switch_function",
    "integrate_tangential",
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
def shear_modulus(youngs_modulus, poisson_ratio):
    """Shear modulus ``G = E / (2 (1 + nu))`` [Pa] of an isotropic material."""
    return youngs_modulus / (2.0 * (1.0 + poisson_ratio))


@jitable
def effective_shear_modulus(E1, nu1, E2, nu2):
    """Effective shear modulus ``G* = 1/((2 - nu1)/G1 + (2 - nu2)/G2)`` [Pa] of Mindlin's contact.

    A rigid body has ``E = inf`` (its term vanishes).
    """
    s = 0.0
    if E1 != math.inf:
        s += (2.0 - nu1) / shear_modulus(E1, nu1)
    if E2 != math.inf:
        s += (2.0 - nu2) / shear_modulus(E2, nu2)
    return 1.0 / s


@jitable
def mindlin_stiffness(contact_radius, effective_shear):
    """Mindlin's no-slip tangential stiffness ``k_t = 8 G* a`` [N/m]."""
    return 8.0 * effective_shear * contact_radius


@jitable
def stiffness_ratio(effective_shear, effective_modulus):
    """``kappa = 4 G*/E*`` [-]: tangential over normal (Hertz) contact stiffness, ``8 G* a / (2 E* a)``."""
    return 4.0 * effective_shear / effective_modulus


@jitable
def stiffness_ratio_same_poisson(nu):
    """``kappa = 2 (1 - nu)/(2 - nu)`` [-]: :func:`stiffness_ratio` of two bodies with one Poisson's ratio.

    Exact for two equal materials and for one material on a rigid flat: with
    ``G = E/(2 (1 + nu))`` each body adds ``(2 - nu)/G`` to ``1/G*`` and ``(1 - nu^2)/E`` to
    ``1/E*``, so ``4 G*/E* = 4 (1 - nu^2)/(2 (1 + nu)(2 - nu)) = 2 (1 - nu)/(2 - nu)`` whatever the
    moduli, as long as both ``nu`` are equal.
    """
    return 2.0 * (1.0 - nu) / (2.0 - nu)


@jitable
def normalized_angle(slip, normal_speed, friction, kappa):
    """Normalised impact angle ``psi = kappa u0 / (mu V)`` [-] (``u0`` the contact-point slip)."""
    return kappa * slip / (friction * normal_speed)


@jitable
def rigid_impulse(u0_hat, one_plus_e):
    """Rigid-body Coulomb impulse in the normalised units: returns ``(J^, regime)``.

    The impulse that stops the slip, ``-2/7 u^_0`` (``J_stop = -2/7 m u0``), is applied if
    it is within the Coulomb limit ``(1 + e)`` (``mu J_n``; rolling), otherwise
    ``-(1 + e) sign(u^_0)`` (sliding). Walton (1993), Brach (1988): the model of
    :func:`microimpact.wall.wall_interaction`.
    """
    stop = u0_hat / SLIP_FACTOR
    if abs(stop) <= one_plus_e:
        return -stop, REGIME_ROLLING
    return -math.copysign(one_plus_e, u0_hat), REGIME_SLIDING


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


@jitable
def integrate_tangential(u0_hat, kappa, x, steps):
    """Tangential outcome of one impact along the closed-form normal history (fixed-step RK4).

    Parameters
    ----------
    u0_hat : float
        Initial slip ``u0 / (mu V)`` [-] (``psi / kappa``).
    kappa : float
        ``4 G*/E*`` [-].
    x : float
        ``V_y / V`` [-] (1 or more: elastic).
    steps : int
        RK4 steps per stage; regime changes are located by bisection within a step.

    Returns
    -------
    tuple
        ``(u_r_hat, regime)``: final slip ``u_r / (mu V)`` and the regime code
        (:data:`REGIME_STICKING`, :data:`REGIME_SLIDING` or :data:`REGIME_MICROSLIP`).
    """
    hc = history_constants(x)
    elastic = hc[0] == 1.0
    u = u0_hat
    xs = 0.0
    z = 0.0
    psi = kappa * abs(u0_hat)
    sliding = psi > 1.0
    sign = 1.0 if u0_hat >= 0.0 else -1.0
    slid = sliding
    stuck = not sliding
    steps = int(steps)  # arrays pass it as a float
    h = 1.0 / steps
    q = (kappa, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    for stage in range(1, 4):
        if stage == 2 and elastic:
            continue
        xs = enter_stage(stage, 0.0, xs, sliding, hc, kappa)
        xs, u, z, sliding, sign, slid, stuck, _ = tangential_laws.integrate_stage(
            tangential_laws.KIND_SEED,
            stage,
            0.0,
            h,
            steps,
            xs,
            u,
            z,
            sliding,
            sign,
            slid,
            stuck,
            hc,
            q,
            tangential_laws.NO_MEMORY,
        )
    return u, tangential_laws.regime_code(slid, stuck)


# The stepping routine is the one every tangential law shares (core.tangential_laws, which builds on
# this module's normal history): imported last, once every name above exists.
from . import tangential_laws  # noqa: E402
