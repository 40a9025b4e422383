"""Special functions the contact times need, written in numba's subset of Python.

Only the incomplete beta function ``B(u; a, b)`` is needed (the Hertz time integral of seed
eqs. 20 and 26, with ``a = 2/5``, ``b = 1/2``). It is evaluated from its continued fraction,
DLMF 8.17.22 (NIST Digital Library of Mathematical Functions, §8.17(v)), with the modified Lentz
algorithm (Lentz 1976; Press et al., *Numerical Recipes*, 3rd ed., §5.2 and §6.4), and the
symmetry ``B(u; a, b) = B(a, b) - B(1 - u; b, a)`` (DLMF 8.17.4) where the fraction converges
slowly. This keeps :mod:`scipy` out of the path of one impact: importing ``scipy.special`` costs
more than the rest of ``microimpact impact 50`` together.

:func:`binomial_series` gives the coefficients of a binomial series as a tuple of floats, computed
exactly with :class:`fractions.Fraction` and rounded once, for the series a law sums where its
closed form cancels (e.g. :mod:`microimpact.core.models.liggghts_thornton_ning`).
"""

from __future__ import annotations

import math

from ._jit import jitable
from .hertz_beta_table import DEGREE, PIECES, S_COEFFS, U_COEFFS, U_SPLIT, WIDTH

__all__ = [
    "beta",
    "binomial_series",
    "incomplete_beta",
    "incomplete_beta_with",
    "incomplete_beta_inverse",
    "hertz_beta",
    "hertz_beta_scaled",
    "hertz_beta_scaled_u",
    "hertz_beta_scaled_s",
    "BETA_25_12",
    "HERTZ_TIME_CONSTANT",
    "HERTZ_TIME_CONSTANT_PRINTED",
]


def binomial_series(p, start, stop, scale=1):
    """The coefficients ``scale binom(p, k) (-1)^k`` of ``x^k`` in ``scale (1 - x)^p``, for
    ``start <= k < stop``, each the exact rational rounded once to a float.

    ``p`` and ``scale`` are exact numbers (``int`` or :class:`fractions.Fraction`; a float is taken
    at its exact binary value). Not compiled: it runs once, at import, to build a law's table.
    """
    from fractions import Fraction

    p, c, out = Fraction(p), Fraction(1), []
    for k in range(stop):
        if k >= start:
            out.append(float(Fraction(scale) * c * (-1) ** k))
        c = c * (p - k) / (k + 1)
    return tuple(out)


_TINY = 1e-300
_EPS = 1e-16


@jitable
def beta(a, b):
    """Complete beta function ``B(a, b) = Gamma(a) Gamma(b) / Gamma(a + b)`` [-] (DLMF 5.12.1).

    With :func:`math.gamma` where it cannot overflow (``B(2/5, 1/2)`` comes out correctly rounded),
    else with :func:`math.lgamma`.
    """
    if a + b < 170.0:
        return math.gamma(a) * math.gamma(b) / math.gamma(a + b)
    return math.exp(math.lgamma(a) + math.lgamma(b) - math.lgamma(a + b))


@jitable
def _beta_fraction(x, a, b):
    """The continued fraction of DLMF 8.17.22, ``1/(1 + d1/(1 + d2/(1 + ...)))``, by modified Lentz."""
    c = 1.0
    d = 1.0 - (a + b) * x / (a + 1.0)  # 1 + d_1
    if abs(d) < _TINY:
        d = _TINY
    d = 1.0 / d
    h = d
    for m in range(1, 300):
        m2 = 2.0 * m
        # d_{2m} = m (b - m) x / ((a + 2m - 1)(a + 2m))
        aa = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2))
        d = 1.0 + aa * d
        if abs(d) < _TINY:
            d = _TINY
        c = 1.0 + aa / c
        if abs(c) < _TINY:
            c = _TINY
        d = 1.0 / d
        h *= d * c
        # d_{2m+1} = -(a + m)(a + b + m) x / ((a + 2m)(a + 2m + 1))
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0))
        d = 1.0 + aa * d
        if abs(d) < _TINY:
            d = _TINY
        c = 1.0 + aa / c
        if abs(c) < _TINY:
            c = _TINY
        d = 1.0 / d
        delta = d * c
        h *= delta
        if abs(delta - 1.0) < _EPS:
            break
    return h


@jitable
def incomplete_beta_with(u, a, b, beta_ab):
    """Non-regularised incomplete beta function ``B(u; a, b) = int_0^u t^(a-1) (1-t)^(b-1) dt`` [-].

    DLMF 8.17.22 for ``u < (a + 1)/(a + b + 2)``, else DLMF 8.17.4 with the fraction in ``1 - u``;
    ``beta_ab`` is the complete ``B(a, b)``. ``u`` in [0, 1]; ``B(0) = 0`` and ``B(1) = B(a, b)`` exactly.
    """
    if u <= 0.0:
        return 0.0
    if u < (a + 1.0) / (a + b + 2.0):
        return u**a * (1.0 - u) ** b / a * _beta_fraction(u, a, b)
    w = 1.0 - u
    if w <= 0.0:
        return beta_ab
    return beta_ab - w**b * u**a / b * _beta_fraction(w, b, a)


@jitable
def incomplete_beta(u, a, b):
    """``B(u; a, b)`` for any positive ``a``, ``b`` (:func:`incomplete_beta_with` with :func:`beta`)."""
    return incomplete_beta_with(u, a, b, beta(a, b))


@jitable
def incomplete_beta_inverse(x, a, b, beta_ab):
    """``u`` in [0, 1] with ``B(u; a, b) = x B(a, b)``: the inverse of the regularised ``I_u(a, b)`` [-].

    Newton's method on :func:`incomplete_beta_with`, whose derivative is the integrand
    ``u^(a-1) (1-u)^(b-1)`` (DLMF 8.17.1), kept inside a bracket that every evaluation narrows
    (bisection where a step would leave it), from the small-``u`` start ``(a x B(a, b))^(1/a)``
    (the leading term of DLMF 8.17.8). ``x`` in [0, 1]; within 1e-14 (relative) of
    :func:`scipy.special.betaincinv` for ``a, b`` in {2/5, 1/2} where ``u`` is below its value at
    ``x = 1/2`` (invert in ``1 - u`` with ``a``, ``b`` swapped above it, as
    :func:`microimpact.dynamics.impact_history` does).
    """
    if not (x > 0.0):
        return 0.0
    if x >= 1.0:
        return 1.0
    target = x * beta_ab
    lo = 0.0
    hi = 1.0
    u = (a * target) ** (1.0 / a)
    if u < 1e-20:  # the leading term is exact to double precision (the next is O(u) smaller)
        return u
    if not (u < 1.0):
        u = 0.5
    for _ in range(200):
        f = incomplete_beta_with(u, a, b, beta_ab) - target
        if f == 0.0:
            return u
        if f > 0.0:
            hi = u
        else:
            lo = u
        step = f / (u ** (a - 1.0) * (1.0 - u) ** (b - 1.0))
        nxt = u - step
        if not (lo < nxt < hi):
            nxt = 0.5 * (lo + hi)
        if abs(nxt - u) <= 2.0 * _EPS * u or nxt == lo or nxt == hi:
            return nxt
        u = nxt
    return u


#: Complete beta function ``B(2/5, 1/2) = 3.67909...``, the Hertz time integral.
BETA_25_12 = beta(0.4, 0.5)
#: Exact constant of Hertz's contact time, ``(4/5) B(2/5,1/2) (15/16)^(2/5) = 2.868``
#: (the seed's eq. 30 prints it as 2.87).
HERTZ_TIME_CONSTANT = 0.8 * BETA_25_12 * (15.0 / 16.0) ** 0.4
#: Deresiewicz's (1968) prefactor as the seed's eq. 30 prints it, 2.87: :data:`HERTZ_TIME_CONSTANT`
#: rounded (kept for reproducing the seed's printed numbers).
HERTZ_TIME_CONSTANT_PRINTED = 2.87


@jitable
def _piece(coeffs, t):
    """A :mod:`~microimpact.core.hertz_beta_table` table at ``t`` (``u`` or ``s``): Horner's rule on
    the piece holding ``t``, in its local variable ``x = 2 t/WIDTH - (2k + 1)`` in ``[-1, 1]`` (formed
    with powers of two only: exact)."""
    y = t * (2.0 / WIDTH)
    k = min(int(y * 0.5), PIECES - 1)
    x = y - (2.0 * k + 1.0)
    base = k * (DEGREE + 1)
    r = coeffs[base + DEGREE]
    for j in range(DEGREE - 1, -1, -1):
        r = r * x + coeffs[base + j]
    return r


@jitable
def hertz_beta_scaled(u):
    """The scaled Hertz time integral ``G(u) = B(u; 2/5, 1/2) / u^(2/5)`` [-], ``u`` in ``[0, 1]``.

    ``G(0) = 5/2`` and ``G(1) = B(2/5, 1/2)``; the stage-1 time of a plastic impact is
    ``(2/5) (alpha_y/V) G((V_y/V)^2)`` (seed eq. 20 with ``alpha_m = alpha_y u^(-2/5)``). Piecewise
    polynomials (:mod:`~microimpact.core.hertz_beta_table`): :func:`hertz_beta_scaled_u` below
    ``U_SPLIT``, :func:`hertz_beta_scaled_s` of ``s = (1 - u)^(1/2)`` above; within a few units in
    the last place; no power, no loop to convergence. Where ``1 - u`` is known more accurately than
    ``u`` (next to ``V_y``), call :func:`hertz_beta_scaled_s` with it directly.
    """
    if u < U_SPLIT:
        return hertz_beta_scaled_u(u)
    return hertz_beta_scaled_s(math.sqrt(max(1.0 - u, 0.0)))


@jitable
def hertz_beta_scaled_u(u):
    """``G(u)`` (:func:`hertz_beta_scaled`) for ``0 <= u < U_SPLIT``, from the pieces in ``u``."""
    return _piece(U_COEFFS, u)


@jitable
def hertz_beta_scaled_s(s):
    """``G(1 - s^2)`` (:func:`hertz_beta_scaled`) for ``0 <= s <= (1 - U_SPLIT)^(1/2)``, from the pieces in ``s``."""
    return _piece(S_COEFFS, s)


@jitable
def hertz_beta(u):
    """The Hertz time integral ``B(u; 2/5, 1/2)`` [-] (seed eqs. 20, 26), ``u`` in ``[0, 1]``.

    ``u^(2/5) G(u)`` with :func:`hertz_beta_scaled`; ``B(0) = 0`` and ``B(1) = B(2/5, 1/2)``
    (:data:`BETA_25_12`) exactly. Agrees with :func:`incomplete_beta` ``(u, 2/5, 1/2)`` (the continued
    fraction) to about 1e-15.
    """
    if u <= 0.0:
        return 0.0
    if u >= 1.0:
        return BETA_25_12
    return u**0.4 * hertz_beta_scaled(u)
