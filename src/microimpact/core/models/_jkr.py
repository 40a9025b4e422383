"""The JKR curve in ``b = a^(1/2)`` shared by the adhesive model files (private: not a model).

Force, the antiderivative of ``P d alpha`` and the two contact-time quadratures, moved here
unchanged from :mod:`~microimpact.core.models.jkr_elastic_adhesive` so that
:mod:`~microimpact.core.models.thornton_ning_1998_elastic_adhesive` uses the same code; ``s =
(pi gamma/E*)^(1/2)`` with ``gamma`` LAMMPS' surface energy (half the work of adhesion).
"""

from __future__ import annotations

import math

from .._jit import jitable
from ..gauss_legendre import RULES
from ._common import nan_outcome, pack

__all__ = [
    "GX",
    "GW",
    "force_b",
    "work_integral",
    "work_difference",
    "time_to_top",
    "time_tensile",
    "hertz_impact",
    "turning_point",
    "impact",
    "law_outcome",
    "law_restitution",
    "b_of_alpha",
]

#: 48-point Gauss-Legendre nodes and weights on ``[-1, 1]`` (numpy's ``leggauss(48)``, kept as literals).
GX, GW = RULES[48]


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


@jitable
def hertz_impact(V, E, R, m):
    """The 18-tuple outcome of an adhesive model with zero adhesion: Hertz (contact from zero approach)."""
    n = math.nan
    if V == 0.0:
        return pack(V, n, n, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, n, 0.0, R, n, n, math.inf, math.inf)
    K = 0.5 * m * V * V
    am = (15.0 * K / (8.0 * E * math.sqrt(R))) ** 0.4
    bm = math.sqrt(math.sqrt(R * am))
    t = time_to_top(0.0, bm, E, R, m, 0.0)
    pm = 4.0 / 3.0 * E * math.sqrt(R) * am**1.5
    return pack(V, n, n, 1.0, 1.0, V, am, 0.0, pm, n, math.sqrt(R * am), R, n, n, t, t)


@jitable
def _energies(V, E, R, m, s, b0, bF):
    """``(K, G(b_0), W)``: kinetic energy, work integral at contact and the work lost to ``b_F`` [J]."""
    K = 0.5 * m * V * V
    G0 = work_integral(b0, E, R, s)
    return K, G0, work_integral(bF, E, R, s) - G0


@jitable
def restitution(V, E, R, m, s, b0, bF):
    """``e`` [-] of :func:`impact` alone (its field ``restitution``, the same operations), without the
    maximum approach's Newton iteration and the contact times' quadratures."""
    K, G0, W = _energies(V, E, R, m, s, b0, bF)
    return 0.0 if K <= W else math.sqrt(1.0 - W / K)


@jitable
def turning_point(K, G0, b0, E, R, s):
    """``b_m`` where the loading work from ``b_0`` equals ``K``: ``G(b_m) - G_0 = K``, ``G_0 = G(b_0)``
    (Newton from above, the bracket grown from ``b_0``), at least ``b_0``."""
    bm = b0
    while work_integral(bm, E, R, s) - G0 < K:
        bm *= 1.5
    for _ in range(200):
        f = work_integral(bm, E, R, s) - G0 - K
        d = force_b(bm, E, R, s) * (4.0 * bm * bm * bm / R - 2.0 * s)  # dG/db = P dalpha/db
        step = f / d
        bm -= step
        if abs(step) <= 1e-16 * bm:
            break
    if bm < b0:
        bm = b0
    return bm


@jitable
def impact(V, E, R, m, s, b0, bF):
    """The 18-tuple outcome of an impact on the JKR curve of ``s``, from contact at ``b0`` to breaking at ``bF``.

    Maximum approach from the energy balance ``G(b_m) - G(b_0) = 1/2 m* V^2`` (Newton from above),
    ``e = (1 - W/K)^(1/2)`` with ``W = G(b_F) - G(b_0)`` the work lost (0 and an infinite time when
    the particle sticks), loading and unloading times by the quadratures above.
    """
    n = math.nan
    K, G0, W = _energies(V, E, R, m, s, b0, bF)
    bm = turning_point(K, G0, b0, E, R, s)
    a_max = (bm * bm) * (bm * bm) / R - 2.0 * s * bm
    p_max = force_b(bm, E, R, s)
    t_load = time_to_top(b0, bm, E, R, m, s) if bm > b0 else 0.0
    if K <= W:
        e = 0.0
        t_un = math.inf
    else:
        e = math.sqrt(1.0 - W / K)
        t_un = t_load + time_tensile(bF, b0, K - W, E, R, m, s)
    return pack(V, n, n, 0.0, e, e * V, a_max, 0.0, p_max, n, bm * bm, R, n, n, t_load, t_un)


@jitable
def law_outcome(V, E, R, m, valid, g, s, b0, bF):
    """The outcome of an elastic adhesive law on the JKR curve ``(s, b0, bF)``, the one body of both
    laws' ``outcome``: :func:`nan_outcome` unless ``valid`` (the law's parameters in bounds) and
    ``0 <= V < inf``; Hertz's impact where the adhesion ``g`` is 0; else :func:`impact`."""
    if not valid or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    if g == 0.0:
        return hertz_impact(V, E, R, m)  # b0 = 0, no pull-off
    return impact(V, E, R, m, s, b0, bF)


@jitable
def law_restitution(V, E, R, m, valid, g, s, b0, bF):
    """``e`` [-] of :func:`law_outcome` alone, bit for bit (the laws' ``restitution_only`` hook):
    NaN, 1 (Hertz) or :func:`restitution`, without the maximum approach and the contact times."""
    if not valid or not (V >= 0.0 and V < math.inf):
        return math.nan
    if g == 0.0:
        return 1.0  # Hertz: every impact elastic
    return restitution(V, E, R, m, s, b0, bF)


@jitable
def b_of_alpha(alpha, E, R, s):
    """``b = a^(1/2)`` on the branch ``b >= b_f`` at approach ``alpha >= alpha_f`` (Newton from above:
    ``b^4/R - 2 s b - alpha`` is convex and increasing there, so the iterates decrease to the root)."""
    bf = (0.5 * s * R) ** (1.0 / 3.0)
    if alpha <= (bf * bf) * (bf * bf) / R - 2.0 * s * bf:
        return bf
    b = max((R * abs(alpha)) ** 0.25, 2.0 * bf)
    while (b * b) * (b * b) / R - 2.0 * s * b < alpha:
        b *= 2.0
    for _ in range(200):
        f = (b * b) * (b * b) / R - 2.0 * s * b - alpha
        d = 4.0 * b * b * b / R - 2.0 * s
        step = f / d
        b -= step
        if step <= 1e-15 * b:
            break
    return max(b, bf)
