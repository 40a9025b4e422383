"""Hertz's elastic contact of a sphere (seed eqs. 1-3; Johnson, *Contact Mechanics*, 1985, §4.2).

Scalar functions over floats, shared by every model whose loading or unloading is Hertzian.
``E`` is the effective modulus ``E*`` [Pa], ``R`` the effective (or unloading) radius [m],
``m`` the effective mass [kg], ``alpha`` the approach [m], ``V`` the impact speed [m/s].
"""

from __future__ import annotations

import math

from ._jit import jitable
from .special import BETA_25_12

__all__ = ["force", "contact_radius", "central_pressure", "max_approach", "time_scale", "contact_time"]


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
def contact_time(V, E, R, m):
    """Duration of an elastic Hertz impact, ``(4/5) B(2/5, 1/2) alpha_m / V`` [s] (seed eq. 30, exact constant)."""
    return 0.8 * BETA_25_12 * time_scale(V, E, R, m)
