"""The seed's dynamic elastic-plastic impact model (the default model).

Source: "Dynamic impact model of plastic deformation between micro-particles and flat surfaces
without adhesion", *Aerosol Science and Technology* 50(4):321-330 (2016), eqs. 1-33 (restored
in the theory page), after Thornton & Ning (1998). Loading is Hertzian up to the yield approach
``alpha_y`` (eqs. 2, 5, 7), then linear with the limiting pressure ``p_y`` (eqs. 6, 8); unloading is
Hertzian with the enlarged radius ``R_p`` from the plastic approach ``alpha_p`` (eqs. 9-11). The
outcome is in closed form (eqs. 22, 27-29) and so are the contact times (eqs. 20, 23, 26, 32, 33;
the theory page derives them: the seed integrated them numerically).

Validity: small strain, flagged by ``large_strain`` when ``a*/R* > 0.3``
(:data:`~microimpact.core.constants.LARGE_STRAIN_RATIO`); no adhesion; no rate dependence;
``p_y`` constant during plastic loading. Defines every field of
:data:`~microimpact.core.quantities.OUTCOME_FIELDS`. No parameters beyond the pair.
"""

from __future__ import annotations

import math

from .. import hertz
from .._jit import jitable
from ..constants import LARGE_STRAIN_RATIO
from ..hertz_beta_table import U_SPLIT
from ..special import hertz_beta_scaled_s, hertz_beta_scaled_u
from . import checks, deprecated_names
from ._common import pack

NAME = "thornton_ning_2016"
TITLE = "Elastic-plastic impact without adhesion (Aerosol Sci. Tech. 50(4), 2016; Thornton & Ning 1998)"
LABEL = "seed (Thornton-Ning 2016)"
PARAMETERS = ()
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(
    __name__, NAME, signed_force="signed_force"
)  # released DEFAULTS and signed_force: one release, with a warning
#: History stages (seed eqs. 2, 8, 10).
STAGES = {1: "Hertz loading (eq. 2)", 2: "plastic loading (eq. 8)", 3: "elastic unloading (eq. 10)"}
CITATION = "Aerosol Sci. Tech. 50(4):321-330 (2016); Thornton & Ning, Powder Technol. 99:154-162 (1998)"
#: The generated C source writes this law's e_p(V/V_y) (microimpact.cexport): its fits can be exported.
C_EXPORT = True


@jitable
def yield_point(E, R, m, p_y):
    """``(alpha_y, P_y, V_y)``: yield approach [m] (eq. 5), force [N] (eq. 7) and velocity [m/s] (eq. 28).

    ``V_y`` from the energy balance ``1/2 m* V_y^2 = 2/5 P_y alpha_y`` (Davies 1949; Thornton & Ning
    1998). ``p_y = inf`` gives ``inf`` for all three (every impact elastic).
    """
    if p_y == math.inf:
        return math.inf, math.inf, math.inf
    a_y = yield_approach(p_y, E, R)
    P_y = hertz.force(a_y, E, R)
    return a_y, P_y, math.sqrt(0.8 * P_y * a_y / m)


@jitable
def yield_velocity_sphere_on_flat(p_y, E, rho):
    """``V_y = (pi^4/40)^(1/2) (p_y^5/(E*^4 rho))^(1/2)`` [m/s] (eq. 28, a sphere on a flat)."""
    p2 = p_y * p_y
    e2 = E * E
    return math.sqrt((math.pi * math.pi) * (math.pi * math.pi) / 40.0) * math.sqrt((p2 * p2) * p_y / ((e2 * e2) * rho))


@jitable
def limiting_pressure_for_yield_velocity(V_y_new, p_y, V_y):
    """The limiting pressure [Pa] that moves the yield velocity from ``V_y`` (at ``p_y`` [Pa]) to
    ``V_y_new`` [m/s], ``E*``, ``R*`` and ``m*`` kept: ``p_y (V_y_new/V_y)^(2/5)``, since ``V_y`` grows
    as ``p_y^(5/2)`` (eq. 28)."""
    return p_y * (V_y_new / V_y) ** 0.4


@jitable
def plastic_stage(v, dv):
    """Normalised outcome of a plastic impact at ``v = V/V_y > 1``, ``dv = v - 1`` (eqs. 22, 14, 11, 9, 27).

    Returns ``(A, Phat, alpha_p_hat, R_p_hat, e)``: ``alpha*/alpha_y`` (eq. 22), ``P*/P_y`` (eq. 14),
    ``alpha_p/alpha_y`` (eq. 11), ``R_p/R*`` (eq. 9) and the restitution coefficient (eq. 27, by
    :func:`restitution`). All are computed from ``q = s/v = ((24 - 4/v^2)/5)^(1/2)``, with
    ``s = 2 P*/P_y``, so that nothing overflows before ``v`` does.

    ``alpha_p_hat = A - Phat/A^(1/2)`` cancels as ``v -> 1`` (both terms tend to 1; it vanishes as
    ``(v - 1)^2``). Below ``v = 2`` it is computed from the identity
    ``A^3 - Phat^2 = (s - 2)^2 (4 s + 1)/108`` (expand ``(1 + s)^3/27 - s^2/4``), with
    ``s - 2 = 24 (v - 1)(v + 1)/(5 (s + 2))``: exact to rounding, given ``dv`` computed as
    ``(V - V_y)/V_y`` (exact subtraction) rather than as ``V/V_y - 1``.
    """
    q = math.sqrt((24.0 - 4.0 / (v * v)) / 5.0)
    A = (1.0 + v * q) / 3.0
    Phat = 0.5 * v * q
    sqA = math.sqrt(A)
    if dv < 1.0:
        s = v * q
        d = 24.0 * dv * (v + 1.0) / (5.0 * (s + 2.0))  # s - 2
        ap = d * d * (4.0 * s + 1.0) / (108.0 * (A * sqA + Phat) * sqA)
    else:
        ap = max(A - Phat / sqA, 0.0)
    return A, Phat, ap, A * sqA / Phat, restitution(v)


@jitable
def normalized_outcome(v):
    """``(alpha*/alpha_y, P*/P_y, alpha_p/alpha_y, R_p/R*, e)`` at any ``v = V/V_y >= 0`` (eqs. 13-15, 22, 27).

    Elastic for ``v <= 1`` (``v^(4/5)``, ``v^(6/5)``, 0, 1, 1); the limits ``inf, inf, inf, inf, 0`` at
    ``v = inf``.
    """
    if v <= 1.0:
        return v**0.8, v**1.2, 0.0, 1.0, 1.0
    if v == math.inf:
        return math.inf, math.inf, math.inf, math.inf, 0.0
    return plastic_stage(v, v - 1.0)


_THIRD = 1.0 / 3.0


@jitable
def restitution(v):
    """Restitution coefficient at ``v = V/V_y`` [-] (eq. 27): 1 for ``v <= 1``, 0 at ``v = inf``.

    ``e = P^/(A^(1/4) v) = (q/2) (3/(1 + v q))^(1/4)``, with ``/5`` and ``/3`` as products (two
    divisions), written without early returns (the formula on
    ``max(v, 1)``, then a select) so that the compiled loop vectorises: at ``v = 1`` it gives 1
    exactly (``q = 2``, ``A = 1``) and at ``v = inf`` it gives 0 (``A = inf``).
    """
    vp = v if v > 1.0 else 1.0
    q = math.sqrt((24.0 - 4.0 / (vp * vp)) * 0.2)
    e = 0.5 * q / math.sqrt(math.sqrt((1.0 + vp * q) * _THIRD))
    return e if v > 1.0 else 1.0


@jitable
def restitution_at(V, V_y):
    """Restitution coefficient of an impact at ``V`` [m/s] for the yield velocity ``V_y`` [m/s] (eq. 27)."""
    return restitution(normalized_velocity(V, V_y))


@jitable
def thornton_ning_restitution(V, V_y):
    """Thornton & Ning's (1998) closed form of the restitution coefficient [-], 1 for ``V <= V_y``.

    ``e = (6 3^(1/2)/5)^(1/2) (1 - w^2/6)^(1/2) [w / (w + 2 (6/5 - w^2/5)^(1/2))]^(1/4)`` with
    ``w = V_y/V``: written independently of :func:`restitution` (eq. 27), to which it is
    algebraically equal (the theory page shows it), as its check.
    """
    if V <= V_y:
        return 1.0
    w = V_y / V
    if w > 1.0:
        w = 1.0
    return (
        math.sqrt(6.0 * math.sqrt(3.0) / 5.0)
        * math.sqrt(1.0 - w * w / 6.0)
        * (w / (w + 2.0 * math.sqrt(6.0 / 5.0 - w * w / 5.0))) ** 0.25
    )


@jitable
def energy_loss(e):
    """Fraction of the kinetic energy lost, ``1 - e^2`` [-] (eq. 29); also takes arrays."""
    return 1.0 - e * e


@jitable
def normalized_velocity(V, V_y):
    """``v = V/V_y``; 0 where ``V_y = inf`` (``p_y = inf``: every impact elastic, even ``V = inf``)."""
    r = V / V_y  # computed first, then selected: no branch in the compiled loop
    return 0.0 if V_y == math.inf else r


@jitable
def restitution_group(V, E, R, m, p_y, params):
    """``v = V/V_y`` [-] at speed ``V`` [m/s], as :func:`outcome` computes it: ``e`` is one function of
    it (eq. 27), the contract's group hook (``params``: the law's empty tuple)."""
    return normalized_velocity(V, yield_point(E, R, m, p_y)[2])


@jitable
def restitution_of_group(v, params):
    """``e`` [-] at ``v = V/V_y`` (:func:`restitution`, eq. 27): the field ``restitution`` of :func:`outcome`."""
    return restitution(v)


@jitable
def elastic_stage_time(V, E, R, m, alpha_y, V_y):
    """Stage 1, Hertz loading to yield or to rest: ``t1 = (2/5)(alpha_m/V) B(u; 2/5, 1/2)`` [s] (eq. 20).

    ``u = min(1, (V_y/V)^2)``; 0 at ``V = inf``. Elastic (``u = 1``): ``(2/5) B(2/5, 1/2) alpha_m/V``.
    Plastic: with ``alpha_m = alpha_y u^(-2/5)`` (``alpha_m`` grows as ``V^(4/5)``, eq. 17, and equals
    ``alpha_y`` at ``V_y``) this is ``(2/5)(alpha_y/V) G(u)``, ``G(u) = B(u; 2/5, 1/2)/u^(2/5)``
    (:func:`~microimpact.core.special.hertz_beta_scaled`), which needs no power of ``V``.
    """
    if V == math.inf:
        return 0.0
    if V > V_y:
        w = V_y / V
        u = w * w  # w * w, not w ** 2: the same bits compiled
        if u < U_SPLIT:
            G = hertz_beta_scaled_u(u)
        else:  # next to V_y: 1 - u from (V - V_y)(V + V_y), exact to rounding, not from u
            G = hertz_beta_scaled_s(math.sqrt((V - V_y) * (V + V_y)) / V)
        return 0.4 * (alpha_y / V) * G
    return hertz.half_period(V, E, R, m)


@jitable
def plastic_stage_time(V, R, m, p_y, alpha_y, V_y):
    """Stage 2, plastic loading: ``t2 = atan2((V^2 - V_y^2)^(1/2), 2 omega alpha_y/3) / omega`` [s] (eq. 23).

    A harmonic oscillation of angular frequency ``omega = (pi p_y R*/m*)^(1/2)`` about ``alpha_y/3``;
    0 for an elastic impact, ``pi/(2 omega)`` (Ning's loading time, eq. 31) at ``V = inf``.
    """
    if not V > V_y:
        return 0.0
    omega = plastic_frequency(p_y, R, m)
    v1 = math.sqrt((V - V_y) * (V + V_y))  # (V^2 - V_y^2)^(1/2) without cancellation next to V_y
    return math.atan2(v1, 2.0 * omega * alpha_y / 3.0) / omega


@jitable
def plastic_frequency(p_y, R, m):
    """Angular frequency of the plastic stage, ``omega = (pi p_y R*/m*)^(1/2)`` [rad/s] (eqs. 18-23)."""
    return math.sqrt(math.pi * p_y * R / m)


@jitable
def ning_loading_time(p_y, R, m):
    """Ning's (1995) loading time at high speed, ``pi/(2 omega)`` [s] (eq. 31): the limit of ``t1 + t2``."""
    return 0.5 * math.pi / plastic_frequency(p_y, R, m)


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome and contact times of one impact (eqs. 5-33), in the order of ``OUTCOME_FIELDS``."""
    inf = math.inf
    a_y, P_y, Vy = yield_point(E, R, m, p_y)
    v = normalized_velocity(V, Vy)
    elastic = v <= 1.0
    if elastic:
        max_approach = hertz.max_approach(V, E, R, m)  # dimensional, so p_y = inf works
        max_force = hertz.force(max_approach, E, R)
        e = 1.0
        plastic = 0.0
        recovery = max_approach
        R_p = R
    elif v == inf:
        e = 0.0
        max_approach = max_force = plastic = R_p = recovery = inf
    else:
        A, Phat, ap_hat, Rp_hat, e = plastic_stage(v, (V - Vy) / Vy)
        # elastic recovery alpha* - alpha_p = alpha* P*/F_e (eq. 11) = alpha_y P^/A^(1/2): no cancellation
        # (not A R*/R_p: A^(3/2) in R_p overflows two hundred decades before A does)
        recovery = a_y * min(Phat / math.sqrt(A), A)
        max_approach = a_y * A
        max_force = P_y * Phat
        plastic = a_y * ap_hat
        R_p = R * Rp_hat
    rebound = inf if v == inf else e * V
    a_max = math.sqrt(R * max_approach)

    # Contact times (eqs. 20, 23, 26, 32, 33).
    t1 = elastic_stage_time(V, E, R, m, a_y, Vy)
    t2 = plastic_stage_time(V, R, m, p_y, a_y, Vy)
    if v == inf:  # V = inf, or V/V_y beyond the largest float: the limit t_U ~ v^(-1/4) -> 0
        tU = 0.0
    elif elastic:
        tU = hertz.half_period(V, E, R, m)
    else:
        # Hertz unloading with R_p from alpha* to alpha_p (eq. 26): the stage-1 integral run backwards.
        tU = hertz.rise_time(recovery, rebound)
    return pack(
        V,
        Vy,
        v,
        1.0 if elastic else 0.0,
        e,
        rebound,
        max_approach,
        plastic,
        max_force,
        R_p,
        a_max,
        R,
        t1,
        t2,
        t1 + t2,
        tU,
    )


@jitable
def yield_contact_radius(p_y, E, R):
    """Contact radius at yield, ``a_y = pi p_y R*/(2 E*)`` [m] (eq. 4 with ``p0 = p_y``)."""
    return math.pi * p_y * R / (2.0 * E)


@jitable
def yield_approach(p_y, E, R):
    """Yield approach ``alpha_y = a_y^2/R* = (pi p_y/(2 E*))^2 R*`` [m] (eq. 5)."""
    ac = yield_contact_radius(p_y, E, R)
    return ac * ac / R


@jitable
def yield_force(p_y, E, R):
    """Force at first yield, ``P_y = 4/3 E* R*^(1/2) alpha_y^(3/2)`` [N] (eq. 7): Hertz at ``alpha_y``."""
    return hertz.force(yield_approach(p_y, E, R), E, R)


@jitable
def plastic_loading_force(alpha, E, R, p_y):
    """Plastic loading force ``P_y + pi p_y R* (alpha - alpha_y)`` [N] (eqs. 6, 8), for ``alpha >= alpha_y``."""
    a_y = yield_approach(p_y, E, R)
    return hertz.force(a_y, E, R) + math.pi * p_y * R * (alpha - a_y)


@jitable
def loading_force(alpha, E, R, p_y):
    """Loading force [N]: Hertz up to ``alpha_y`` (eq. 2), then plastic (eqs. 6, 8)."""
    if p_y == math.inf or alpha <= yield_approach(p_y, E, R):
        return hertz.force(alpha, E, R)
    return plastic_loading_force(alpha, E, R, p_y)


@jitable
def unloading_radius(alpha_max, P_max, E, R):
    """``R_p = R* F_e/P*`` [m] (eq. 9), ``F_e`` the Hertz force at ``alpha*``; ``R*`` where ``P* = 0``."""
    if not P_max > 0.0:
        return R
    return R * (hertz.force(alpha_max, E, R) / P_max)


@jitable
def plastic_approach(alpha_max, P_max, E, R):
    """Plastic approach ``alpha_p = alpha* (1 - P*/F_e)`` [m] (eq. 11), >= 0; 0 where ``F_e = 0``."""
    F_e = hertz.force(alpha_max, E, R)
    if not F_e > 0.0:
        return 0.0
    return max(alpha_max * (1.0 - P_max / F_e), 0.0)


@jitable
def unloading_force(alpha, a_p, R_p, E):
    """Unloading force ``4/3 E* R_p^(1/2) (alpha - alpha_p)^(3/2)`` [N] (eq. 10); 0 below ``alpha_p``."""
    return hertz.force(max(alpha - a_p, 0.0), E, R_p)


@jitable
def unloading_force_from(alpha, alpha_max, E, R, p_y):
    """Force [N] at ``alpha`` while unloading from the maximum approach ``alpha_max`` (eqs. 9-11, 10)."""
    P_max = loading_force(alpha_max, E, R, p_y)
    return unloading_force(alpha, plastic_approach(alpha_max, P_max, E, R), unloading_radius(alpha_max, P_max, E, R), E)


@jitable
def normalized_loading_force(a):
    """``P/P_y`` against ``alpha/alpha_y`` on loading: ``a^(3/2)`` to 1, then ``(3a - 1)/2`` (eqs. 13, 14)."""
    return a * math.sqrt(a) if a <= 1.0 else (3.0 * a - 1.0) / 2.0


@jitable
def normalized_unloading_force(a, am):
    """``P/P_y`` on unloading from ``am = alpha*/alpha_y`` (eq. 15): ``(R_p/R*)^(1/2) (a - a_p)^(3/2)``."""
    Pm = normalized_loading_force(am)
    d = max(a - (am - Pm / math.sqrt(am)), 0.0)
    return math.sqrt(am * math.sqrt(am) / Pm) * (d * math.sqrt(d))


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """The model's force law [N]: loading (eqs. 2, 6, 8) while ``alpha >= alpha_max``, else unloading (eq. 10)."""
    if alpha <= 0.0:
        return 0.0
    if alpha >= alpha_max:
        return loading_force(alpha, E, R, p_y)
    return unloading_force_from(alpha, alpha_max, E, R, p_y)


@jitable
def ends_at_zero_force(params):
    """False: the contact ends at the plastic approach (:func:`separation_approach_after`), where the
    unloading force (eq. 10) vanishes; located as an approach, a simple zero in time."""
    return False


@jitable
def separation_approach_after(alpha_max, E, R, m, p_y, params):
    """Approach [m] at which unloading from ``alpha_max`` ends: the plastic approach ``alpha_p``
    (eq. 11, with ``P*`` the loading force at ``alpha_max``, eqs. 2, 8); 0 for an elastic contact."""
    return plastic_approach(alpha_max, loading_force(alpha_max, E, R, p_y), E, R)


@jitable
def stage_two_approach(E, R, m, p_y, params):
    """Approach [m] at which Hertz loading (stage 1, eq. 2) gives way to plastic loading (stage 2,
    eq. 8): the yield approach ``alpha_y`` (eq. 5); ``inf`` for ``p_y = inf``."""
    if p_y == math.inf:
        return math.inf
    return yield_approach(p_y, E, R)


@jitable
def large_strain_velocity(E, R, m, p_y):
    """Impact speed [m/s] at which ``a*/R*`` reaches :data:`~microimpact.core.constants.LARGE_STRAIN_RATIO`.

    Closed form (derived here from the seed's energy balances; the root finders it replaces agreed
    to 1e-12): the limit ``a* = r R*`` (``r = 0.3``) is the maximum approach ``alpha* = r^2 R*``
    (eq. 3). If that is at most ``alpha_y`` the impact is elastic and eq. 17 at rest,
    ``1/2 m* V^2 = 2/5 k_n alpha*^(5/2)`` (``k_n = 4/3 E* R*^(1/2)``), gives ``V``. Otherwise eq. 22,
    ``A = alpha*/alpha_y = (1 + s)/3`` with ``s = v q``, ``q^2 = (24 - 4/v^2)/5``, inverts as
    ``s = 3 A - 1``, ``v^2 = (5 s^2 + 4)/24`` and ``V = v V_y`` (eq. 28).
    """
    r = LARGE_STRAIN_RATIO
    a_star = r * r * R
    a_y, P_y, Vy = yield_point(E, R, m, p_y)
    if a_star <= a_y:
        return math.sqrt(0.8 * hertz.stiffness(E, R) * a_star * a_star * math.sqrt(a_star) / m)
    s = 3.0 * (a_star / a_y) - 1.0
    return math.sqrt((5.0 * s * s + 4.0) / 24.0) * Vy
