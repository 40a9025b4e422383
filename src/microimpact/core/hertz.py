"""Hertz's elastic contact of a sphere (seed eqs. 1-3; Johnson, *Contact Mechanics*, 1985, §4.2).

Scalar functions over floats, shared by every model whose loading or unloading is Hertzian.
``E`` is the effective modulus ``E*`` [Pa], ``R`` the effective (or unloading) radius [m],
``m`` the effective mass [kg], ``alpha`` the approach [m], ``V`` the impact speed [m/s].
"""

from __future__ import annotations

import math

from ._jit import jitable
from .special import BETA_25_12

__all__ = [
    "compliance",
    "effective_modulus",
    "equal_bodies_modulus",
    "particle_modulus",
    "stiffness",
    "force",
    "contact_radius",
    "central_pressure",
    "max_approach",
    "time_scale",
    "dem_time_scale",
    "rise_time",
    "half_period",
    "contact_time",
    "deresiewicz_contact_time",
]


@jitable
def compliance(E, nu):
    """``(1 - nu^2)/E`` [1/Pa]: one body's share of ``1/E*`` (seed, after eq. 2; see :func:`effective_modulus`)."""
    return (1.0 - nu * nu) / E


@jitable
def effective_modulus(E1, nu1, E2, nu2):
    """``E* = 1/((1 - nu1^2)/E1 + (1 - nu2^2)/E2)`` [Pa] of two elastic bodies (seed, after eq. 2).

    ``E2 = inf`` is a rigid body (its term vanishes). Plain arithmetic (squares as products): also
    takes numpy arrays.
    """
    return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2)


@jitable
def equal_bodies_modulus(E, nu):
    """Young's modulus ``E1 = 2 (1 - nu^2) E*`` [Pa] of two equal bodies whose ``E*`` is ``E`` [Pa].

    The inverse of :func:`effective_modulus` with ``E1 = E2`` and ``nu1 = nu2 = nu`` (what a DEM code
    that mixes one material with itself needs to reproduce a given ``E*``).
    """
    return 2.0 * (1.0 - nu * nu) * E


@jitable
def particle_modulus(E, nu1, E2, nu2):
    """Young's modulus ``E1 = (1 - nu1^2)/(1/E* - (1 - nu2^2)/E2)`` [Pa] of the body that, against a
    body ``(E2, nu2)``, gives the effective modulus ``E* = E`` [Pa]: :func:`effective_modulus`
    solved for ``E1``. NaN where no such body exists (``E* >= E2/(1 - nu2^2)``).
    """
    inv = 1.0 / E - (1.0 - nu2 * nu2) / E2
    return (1.0 - nu1 * nu1) / inv if inv > 0 else math.nan


@jitable
def stiffness(E, R):
    """Hertz's stiffness ``k_n = 4/3 E* R^(1/2)`` [N/m^(3/2)] of ``P = k_n alpha^(3/2)`` (seed eq. 2)."""
    return 4.0 / 3.0 * E * math.sqrt(R)


@jitable
def force(alpha, E, R):
    """Hertz force ``P = 4/3 E* R^(1/2) alpha^(3/2)`` [N] (seed eq. 2), ``alpha >= 0``.

    ``alpha^(3/2)`` as ``alpha alpha^(1/2)``: a correctly rounded square root instead of a call to
    ``pow`` (a third of the C wall function's time, and the same bits in Python, numba and C).
    """
    return 4.0 / 3.0 * E * math.sqrt(R) * (alpha * math.sqrt(alpha))


@jitable
def contact_radius(alpha, R):
    """Contact radius ``a = (R alpha)^(1/2)`` [m] (seed eq. 3)."""
    return math.sqrt(R * alpha)


@jitable
def central_pressure(alpha, E, R):
    """Pressure at the contact centre ``p0 = 2 E* a / (pi R)`` [Pa] (seed eqs. 1, 4)."""
    return 2.0 * E * math.sqrt(R * alpha) / (math.pi * R)


@jitable
def max_approach(V, E, R, m):
    """Maximum approach of an elastic impact, ``(15 m V^2 / (16 E* R^(1/2)))^(2/5)`` [m] (seed eq. 17 at rest)."""
    return (15.0 * m * (V * V) / (16.0 * E * math.sqrt(R))) ** 0.4


@jitable
def time_scale(V, E, R, m):
    """``alpha_m / V = (15 m/(16 E* R^(1/2)))^(2/5) V^(-1/5)`` [s]; ``inf`` at ``V = 0``, 0 at ``V = inf``."""
    if not V > 0.0:
        return math.inf
    return (15.0 * m / (16.0 * E * math.sqrt(R))) ** 0.4 * V ** (-0.2)


@jitable
def dem_time_scale(V, E, R, m):
    """``(m*/(k_n V^(1/2)))^(2/5)`` [s], ``k_n`` = :func:`stiffness`: the time unit of the damped Hertz laws.

    ``alpha_m / V`` without the energy balance's ``15/16`` (the scaling in which the DEM codes' damped
    Hertz equation ``x'' = -(x^(3/2) + kappa x^(1/2) x')`` has no parameter but the damping ``kappa``).
    """
    return (m / (stiffness(E, R) * math.sqrt(V))) ** 0.4


@jitable
def rise_time(alpha_m, V):
    """``(2/5) B(2/5, 1/2) alpha_m / V`` [s]: Hertz loading from first touch at ``V`` to rest at ``alpha_m``.

    Seed eq. 20 with ``u = 1`` (the elastic stage run to rest); run backwards it is the Hertz
    unloading time from ``alpha_m`` to the release at ``V`` (eq. 26, with ``alpha_m`` the elastic
    recovery ``alpha* - alpha_p`` and ``V`` the rebound speed).
    """
    return 0.4 * BETA_25_12 * alpha_m / V


@jitable
def half_period(V, E, R, m):
    """Loading (= unloading) time of an elastic Hertz impact at ``V``, ``(2/5) B(2/5, 1/2) alpha_m/V`` [s].

    :func:`rise_time` at the elastic maximum approach (seed eqs. 17, 20), from :func:`time_scale`
    (no power of ``V`` beyond ``V^(-1/5)``); ``inf`` at ``V = 0``. Half of :func:`contact_time`.
    """
    return 0.4 * BETA_25_12 * time_scale(V, E, R, m)


@jitable
def contact_time(V, E, R, m):
    """Duration of an elastic Hertz impact, ``(4/5) B(2/5, 1/2) alpha_m / V`` [s] (seed eq. 30, exact constant).

    Twice :func:`half_period` (the same bits as ``0.8 B alpha_m/V``: doubling is exact).
    """
    return 2.0 * half_period(V, E, R, m)


@jitable
def deresiewicz_contact_time(V, E, R, m, constant):
    """Deresiewicz's (1968) elastic contact time, ``constant (m*^2/(R* E*^2 V))^(1/5)`` [s] (seed eq. 30).

    With ``constant`` the seed's printed 2.87 (:data:`~microimpact.core.special.HERTZ_TIME_CONSTANT_PRINTED`);
    the exact :data:`~microimpact.core.special.HERTZ_TIME_CONSTANT` makes it :func:`contact_time`
    written the seed's way. ``constant * inf`` where the denominator is 0 (``V = 0``), as IEEE
    division gives it (NaN if ``m*^2`` is 0 too).
    """
    d = R * (E * E) * V
    mm = m * m
    if not d > 0.0:
        return constant * (math.inf if mm > 0.0 else math.nan)
    return constant * (mm / d) ** 0.2
