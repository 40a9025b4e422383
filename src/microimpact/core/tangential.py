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

The normal history stage by stage and the spring's rates along it are
:mod:`microimpact.core.tangential_stages` (named here too), which every tangential law of
:mod:`microimpact.core.tangential_laws` steps on; :func:`integrate_tangential` runs this model
through the stepper those laws share.
"""

from __future__ import annotations

import math

from . import tangential_laws
from ._jit import jitable
from .tangential_stages import (
    REGIME_MICROSLIP,
    REGIME_ROLLING,
    REGIME_SLIDING,
    REGIME_STICKING,
    SLIP_FACTOR,
    enter_stage,
    history_constants,
    stage_point,
    switch_function,
    tangential_rates,
)

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
