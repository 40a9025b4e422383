"""The JKR curve in ``b = a^(1/2)`` shared by the adhesive model files (private: not a model).

Force, the antiderivative of ``P d alpha`` and the two contact-time quadratures, moved here
unchanged from :mod:`~microimpact.core.models.jkr_elastic_adhesive` so that
:mod:`~microimpact.core.models.thornton_ning_1998_elastic_adhesive` uses the same code; ``s =
(pi gamma/E*)^(1/2)`` with ``gamma`` LAMMPS' surface energy (half the work of adhesion).
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import jitable

__all__ = ["GX", "GW", "force_b", "work_integral", "work_difference", "time_to_top", "time_tensile"]

_X, _W = np.polynomial.legendre.leggauss(48)
#: 48-point Gauss-Legendre nodes and weights on ``[-1, 1]``.
GX = tuple(float(x) for x in _X)
GW = tuple(float(w) for w in _W)


@jitable
def force_b(b, E, R, s):
    """JKR force at ``b = a^(1/2)``: ``4 E a^3/(3R) - 4 E s a^(3/2)``, ``s = (pi gamma/E)^(1/2)``."""
    b3 = b * b * b
    return 4.0 * E * b3 * b3 / (3.0 * R) - 4.0 * E * s * b3


@jitable
def work_integral(b, E, R, s):
    """Antiderivative of ``P d alpha`` in ``b``: ``8E/(15R^2) b^10 - 8Es/(3R) b^7 + 2Es^2 b^4``."""
    b2 = b * b
    b4 = b2 * b2
    return 8.0 * E / (15.0 * R * R) * b4 * b4 * b2 - 8.0 * E * s / (3.0 * R) * b4 * b2 * b + 2.0 * E * s * s * b4


@jitable
def work_difference(x, y, E, R, s):
    """``(G(x) - G(y)) / (x - y)``, free of cancellation: ``(x^n - y^n)/(x - y) = sum x^(n-1-k) y^k``."""
    p10 = 0.0
    p7 = 0.0
    p4 = 0.0
    xk = 1.0
    for k in range(10):  # xk = x^k, y^(9-k) etc. built by division-free products
        yk = 1.0
        for _ in range(9 - k):
            yk *= y
        p10 += xk * yk
        if k < 7:
            yk7 = 1.0
            for _ in range(6 - k):
                yk7 *= y
            p7 += xk * yk7
        if k < 4:
            yk4 = 1.0
            for _ in range(3 - k):
                yk4 *= y
            p4 += xk * yk4
        xk *= x
    return 8.0 * E / (15.0 * R * R) * p10 - 8.0 * E * s / (3.0 * R) * p7 + 2.0 * E * s * s * p4


@jitable
def time_to_top(b_lo, bm, E, R, m, s):
    """``int d alpha/|alpha'|`` from ``b_lo`` to the turning point ``bm`` (substitution ``b = bm - w^2``)."""
    W = math.sqrt(bm - b_lo)
    total = 0.0
    for i in range(48):
        w = 0.5 * W * (GX[i] + 1.0)
        b = bm - w * w
        q = work_difference(bm, b, E, R, s)  # (G(bm) - G(b)) / (bm - b) > 0
        total += GW[i] * 2.0 * (4.0 * b * b * b / R - 2.0 * s) / math.sqrt(2.0 * q / m)
    return 0.5 * W * total


@jitable
def time_tensile(bF, b0, excess, E, R, m, s):
    """``int d alpha/|alpha'|`` over the tensile branch ``bF <= b <= b0``, where the kinetic energy is
    ``excess + G(bF) - G(b)`` (``excess = K - W``, the rebound energy); substitution ``b = bF + w^2``
    keeps the integrand finite as ``excess -> 0`` (the sticking limit)."""
    Wd = math.sqrt(b0 - bF)
    total = 0.0
    for i in range(48):
        w = 0.5 * Wd * (GX[i] + 1.0)
        b = bF + w * w
        ke = excess - w * w * work_difference(b, bF, E, R, s)  # G(bF) - G(b) = -(b - bF) dG(b, bF) >= 0
        total += GW[i] * 2.0 * w * (4.0 * b * b * b / R - 2.0 * s) / math.sqrt(2.0 * ke / m)
    return 0.5 * Wd * total
