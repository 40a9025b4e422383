r"""Capillary (liquid) bridges as adhesive laws of an impact: the force laws and one integrator.

Shared by :mod:`~microimpact.core.models.liggghts_easo_capillary`,
:mod:`~microimpact.core.models.liggghts_washino_capillary`,
:mod:`~microimpact.core.models.willett_capillary` and :mod:`~microimpact.core.models.rabinovich_capillary`
(each of which cites its source). A bridge is a force that acts outside the contact, at a
separation ``d = -alpha > 0``, from the moment of contact until ``d`` reaches the bridge's rupture
distance ``d_r``; the particle then flies off with the speed it has left (``e = |alpha_dot|/V``), or
it is pulled back (captured, ``e = 0``).

Internally a law is a kind (:data:`EASO`, :data:`WASHINO`, :data:`WILLETT`, :data:`RABINOVICH`) and
a tuple ``q`` of derived constants (made by each model's ``constants``):

``q = (gamma, theta, V_b, r, r_eff_contact, r_eff_bridge, s_min, d_r, alpha_T, limit, viscosity)``

``gamma`` surface tension [N/m], ``theta`` the contact angle the law uses [rad], ``V_b`` the bridge
volume [m^3], ``r`` the radius in the capillary force [m], the two effective radii of the viscous
and capillary terms in and out of contact [m], ``s_min`` LIGGGHTS' ``minSeparationDistanceRatio``,
``d_r`` the rupture distance [m], ``alpha_T`` the Hertz damping (Tsuji's coefficient, 0: none),
``limit`` LIGGGHTS' ``limitForce`` (0/1), ``viscosity`` [Pa s].

The equation of motion ``m* alpha'' = -P(alpha, alpha')`` is integrated by Hairer's DOP853
(:mod:`microimpact.core.dop853`, adaptive, relative tolerance 1e-13), from first touch
(``alpha = 0``, ``alpha' = V``) through the contact, out across ``alpha = 0`` (where the force jumps
from the contact law to the bridge), to ``alpha = -d_r``; a step that would cross ``alpha = 0`` or
``-d_r`` is shortened (secant iteration on the step length) so that it ends on the boundary, where
the law changes: every step integrates a smooth law. A particle that comes back into contact is
followed as long as it takes (a captured particle oscillates in the bridge until it stays: after
:data:`MAX_RETURNS` returns it is counted as captured).
"""

from __future__ import annotations

import math

from .. import dop853 as dp
from .. import hertz
from .._jit import jitable
from ..gauss_legendre import NODES_48, WEIGHTS_48
from . import hertz_tsuji

EASO = 0
WASHINO = 1
WILLETT = 2
RABINOVICH = 3

#: Returns into contact after which a particle held by the bridge is counted as captured.
MAX_RETURNS = 40

_RTOL = 1e-13

#: LIGGGHTS' floor on 1000 times the bridge volume [m^3]: both capillary models return before adding
#: any cohesive force (capillary or viscous, in contact or outside) where ``volBond1000 < 1e-14``
#: (``src/cohesion_model_easo_capillary_viscous.h`` and ``..._washino_...``, "skip if bond volume too
#: small", 3.8.0 ``84ba3d76``): a bridge below 1e-17 m^3 does nothing in the code, which for a liquid
#: content of 1 % of the solid volume is every sphere below about 20 um in diameter.
LIGGGHTS_VOLUME_FLOOR = 1e-14


@jitable
def below_liggghts_floor(q):
    """True where the bridge (``q[2]``, its volume [m^3]) is below LIGGGHTS' floor
    (:data:`LIGGGHTS_VOLUME_FLOOR`): the code gives it no force."""
    return q[2] * 1000.0 < LIGGGHTS_VOLUME_FLOOR


@jitable
def liggghts_floor(q):
    """``q`` without its capillary and viscous forces where the bridge is below LIGGGHTS' floor
    (:func:`below_liggghts_floor`), else ``q`` unchanged."""
    if not below_liggghts_floor(q):
        return q
    return (0.0, q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8], q[9], 0.0)


@jitable
def liggghts_viscous(d, r_eff, s_min, viscosity):
    """The damping coefficient [N s/m] of LIGGGHTS' normal viscous (lubrication) force at surface
    distance ``d`` [m] (``d <= 0`` in contact): ``6 pi eta r_eff / max(s_min, d/r_eff)``
    (``FviscN = -6 pi eta r_eff v_n / max(minSeparationDistanceRatio, dist/rEff)``; in contact the code
    divides by ``minSeparationDistanceRatio`` alone). Nase et al. 2001 as cited by Shi & McCarthy
    2008 eqs. 40-41."""
    if r_eff == 0.0:
        return 0.0
    s = d / r_eff
    return 6.0 * math.pi * viscosity * r_eff / (s if s > s_min else s_min)


@jitable
def soulie(d, gamma, theta, V_b, r):
    """Soulie et al. 2006 eqs. 13-14 as LIGGGHTS' ``easo/capillary/viscous`` writes them [N, attractive > 0]:
    ``pi gamma r (exp(A d/r + B) + C)`` with ``V* = V_b/r^3``, ``A = -1.1 V*^-0.53``,
    ``B = (-0.148 ln V* - 0.96) theta^2 - 0.0082 ln V* + 0.48``, ``C = 0.0018 ln V* + 0.078``
    (``r``: the code's ``R2``, the larger radius, which for equal spheres and at a wall is also
    its ``sqrt(radi radj)``). At ``d = 0`` (and in contact, where the code sets ``d = 0``)
    ``pi gamma r (exp(B) + C)``."""
    vs = V_b / (r * r * r)
    lv = math.log(vs)
    A = -1.1 * vs**-0.53
    B = (-0.148 * lv - 0.96) * theta * theta - 0.0082 * lv + 0.48
    C = 0.0018 * lv + 0.078
    return math.pi * gamma * r * (math.exp(A * d / r + B) + C)


@jitable
def rabinovich_code(d, gamma, theta, V_b, r_eff):
    """Rabinovich et al. 2005 eqs. 19, 20, A3 as LIGGGHTS' ``washino/capillary/viscous`` writes them
    outside contact [N, attractive > 0], ``d > 0``: ``2 pi r_eff gamma (cos(theta)/(1 + d/(2 d_sp)) +
    sin(a) sin(a + theta))``, ``d_sp = d/2 (-1 + (1 + 2 V_b/(pi r_eff d^2))^(1/2))``, ``a = (d/r_eff
    (-1 + (1 + 2 V_b/(pi r_eff d^2))^(1/2)))^(1/2)``. Yade's ``Rabinovich_f`` is the same law with
    its own ``R`` for ``r_eff`` (:func:`rabinovich_yade`)."""
    pre = -1.0 + math.sqrt(1.0 + 2.0 * V_b / (math.pi * r_eff * d * d))
    dsp = 0.5 * d * pre
    a = math.sqrt(d / r_eff * pre)
    return (
        2.0 * math.pi * r_eff * gamma * (math.cos(theta) / (1.0 + d / (2.0 * dsp)) + math.sin(a) * math.sin(a + theta))
    )


@jitable
def washino_contact(alpha, gamma, theta, V_b, r_eff):
    """Rabinovich et al. 2005 eq. A11 as ``washino/capillary/viscous`` writes it in contact (approach
    ``alpha > 0``, the code's ``dist = -alpha``) [N, attractive > 0]:
    ``2 pi r_eff gamma cos(theta) (1 + alpha (pi r_eff/(2 V_b))^(1/2))``: it grows with the overlap."""
    if r_eff == 0.0:
        return 0.0
    return 2.0 * math.pi * r_eff * gamma * math.cos(theta) * (1.0 + alpha * math.sqrt(math.pi * r_eff / (2.0 * V_b)))


@jitable
def willett_analytic(d, gamma, theta, V_b, r):
    """Willett et al. 2000 eqs. 12-13 as Yade's ``Willett_analytic_f`` writes them [N, attractive > 0]:
    ``2 pi r gamma cos(theta)/(1 + 2.1 S + 10 S^2)`` with ``S = (d/2)/(V_b/r)^(1/2)`` (half the
    separation, scaled)."""
    s = 0.5 * d / math.sqrt(V_b / r)
    return 2.0 * math.pi * r * gamma * math.cos(theta) / (1.0 + 2.1 * s + 10.0 * s * s)


@jitable
def rabinovich_yade(d, gamma, theta, V_b, r):
    """Rabinovich et al. 2005 eqs. 19, 20, A3 (the first term in Lambert 2008's eq. 65 form) as Yade's
    ``Rabinovich_f`` writes them [N, attractive > 0]. At ``d = 0`` exactly Yade takes ``2 pi r gamma
    cos(theta)`` (its ``alpha = 0`` branch), though as ``d -> 0`` eq. A3 gives ``a -> (2 V_b/(pi r^3))^(1/4)``
    and the force tends to ``2 pi r gamma (cos(theta) + sin(a) sin(a + theta))``: a jump at contact,
    of no consequence for an impact (the point has no measure), kept as Yade writes it."""
    if d == 0.0:
        return 2.0 * math.pi * r * gamma * math.cos(theta)
    return rabinovich_code(d, gamma, theta, V_b, r)


@jitable
def willett_rupture(theta, V_b, r):
    """Willett et al. 2000 eq. 15 as Yade uses it [m]: ``d_r = (1 + theta/2)(V*^(1/3) + 0.1 V*^(2/3)) r``,
    ``V* = V_b/r^3``, taken by Yade as the full separation at rupture (``sCrit``)."""
    vs = V_b / (r * r * r)
    return (1.0 + 0.5 * theta) * (vs ** (1.0 / 3.0) + 0.1 * vs ** (2.0 / 3.0)) * r


@jitable
def bridge_force(kind, d, q):
    """The capillary force of the bridge at surface distance ``d > 0`` [N, attractive > 0]."""
    if kind == EASO:
        return soulie(d, q[0], q[1], q[2], q[3])
    if kind == WASHINO:
        return rabinovich_code(d, q[0], q[1], q[2], q[5])
    if kind == WILLETT:
        return willett_analytic(d, q[0], q[1], q[2], q[3])
    return rabinovich_yade(d, q[0], q[1], q[2], q[3])


@jitable
def contact_force(kind, alpha, alpha_dot, E, R, m, q):
    """The force [N] in contact (``alpha > 0``; continued to ``alpha <= 0`` by its value at 0 for the
    Hertz part, so that a step of the integrator that ends on ``alpha = 0`` sees a smooth law): Hertz,
    with LIGGGHTS' damping for its laws (:func:`microimpact.core.models.hertz_tsuji.force`, clipped
    at zero with ``limitForce``), plus the cohesion the code adds in contact (easo: the Soulie force
    at ``d = 0`` and the viscous force at ``minSeparationDistanceRatio``; washino: eq. A11 and the
    same viscous force, both zero at a wall where the code's ``radj`` is 0); Yade adds none."""
    a = alpha if alpha > 0.0 else 0.0
    if kind >= WILLETT:
        return hertz.force(a, E, R)
    p = hertz_tsuji.force(a, alpha_dot, a, E, R, m, 0.0, (q[8], q[9]))
    c = liggghts_viscous(0.0, q[4], q[6], q[10])
    if kind == EASO:
        return p - soulie(0.0, q[0], q[1], q[2], q[3]) + c * alpha_dot
    return p - washino_contact(a, q[0], q[1], q[2], q[4]) + c * alpha_dot


@jitable
def contact_potential(kind, alpha, E, R, q):
    """The potential [J] of the conservative part of :func:`contact_force` at approach ``alpha >= 0``,
    zero at first touch: Hertz's ``2/5 k alpha^(5/2)`` less the work of the cohesion in contact (easo:
    ``F_0 alpha``; washino: ``2 pi r_eff gamma cos(theta)(alpha + k alpha^2/2)``). The damping and the
    viscous force only take energy (LIGGGHTS' ``limitForce`` too: it clips a dissipative force), so a
    particle in contact whose ``m* alpha'^2/2`` plus this potential is negative never reaches
    ``alpha = 0`` again: it is captured."""
    u = 0.4 * hertz.force(alpha, E, R) * alpha
    if kind == EASO:
        u -= soulie(0.0, q[0], q[1], q[2], q[3]) * alpha
    elif kind == WASHINO and q[4] > 0.0:
        k = math.sqrt(math.pi * q[4] / (2.0 * q[2]))
        u -= 2.0 * math.pi * q[4] * q[0] * math.cos(q[1]) * (alpha + 0.5 * k * alpha * alpha)
    return u


@jitable
def separated_force(kind, d, alpha_dot, q):
    """The force [N] at surface distance ``0 < d < d_r`` (attractive < 0): the bridge and, for
    LIGGGHTS, its viscous force."""
    p = -bridge_force(kind, d, q)
    if kind <= WASHINO:
        p += liggghts_viscous(d, q[5], q[6], q[10]) * alpha_dot
    return p


@jitable
def signed_force(kind, alpha, alpha_dot, E, R, m, q):
    """Normal force [N] at approach ``alpha`` and rate ``alpha_dot`` (repulsive > 0, attractive < 0):
    :func:`contact_force` for ``alpha > 0``, :func:`separated_force` for ``0 < d = -alpha < d_r``,
    nothing at and beyond ``d_r`` (and at ``alpha = 0`` exactly, where neither code applies a bridge)."""
    if alpha > 0.0:
        return contact_force(kind, alpha, alpha_dot, E, R, m, q)
    d = -alpha
    if d >= q[7] or d == 0.0:
        return 0.0
    return separated_force(kind, d, alpha_dot, q)


@jitable
def bridge_work(kind, q):
    """The work [J] the capillary bridge does against a particle leaving from ``d = 0`` to ``d_r``:
    ``W = int_0^d_r F(d) dd`` (composite 48-point Gauss-Legendre on 16 panels: the integrands are
    smooth on ``(0, d_r]``; for Willett's law also in closed form, :func:`willett_work`)."""
    dr = q[7]
    n = 16
    h = dr / n
    total = 0.0
    for k in range(n):
        mid = (k + 0.5) * h
        s = 0.0
        for i in range(48):
            s += WEIGHTS_48[i] * bridge_force(kind, mid + 0.5 * h * NODES_48[i], q)
        total += 0.5 * h * s
    return total


@jitable
def willett_work(q):
    """``int_0^d_r`` of Willett's eq. 12-13 force in closed form [J]: with ``L = (V_b/r)^(1/2)`` and
    ``x = d/(2L)``, ``2 pi r gamma cos(theta) 2 L int_0^x_r dx/(1 + 2.1 x + 10 x^2)``, whose integral
    is ``(2/D^(1/2)) [atan((20 x + 2.1)/D^(1/2))]`` with ``D = 40 - 2.1^2`` (derived here)."""
    L = math.sqrt(q[2] / q[3])
    xr = 0.5 * q[7] / L
    sd = math.sqrt(40.0 - 2.1 * 2.1)
    integral = 2.0 / sd * (math.atan((20.0 * xr + 2.1) / sd) - math.atan(2.1 / sd))
    return 2.0 * math.pi * q[3] * q[0] * math.cos(q[1]) * 2.0 * L * integral


@jitable
def _acc(kind, inside, x, v, E, R, m, q):
    """The acceleration of the regime the step integrates (``inside``: the contact law; else the
    bridge, at a distance kept above ``1e-12 d_r``), whatever side of ``alpha = 0`` a stage lands on:
    each step integrates one smooth law."""
    if inside:
        return -contact_force(kind, x, v, E, R, m, q) / m
    d = -x
    floor = 1e-12 * q[7]
    return -separated_force(kind, d if d > floor else floor, v, q) / m


@jitable
def _rates(x, v, p):
    """:func:`_acc` as :func:`~microimpact.core.dop853.step` calls it, ``p = (kind, inside, E, R, m,
    q)``: no third state."""
    return _acc(p[0], p[1], x, v, p[2], p[3], p[4], p[5]), 0.0


@jitable
def _step(kind, inside, x, v, h, E, R, m, q, xs, vs):
    """One DOP853 step of length ``h`` from ``(x, v)`` (:func:`microimpact.core.dop853.step`):
    ``(x_new, v_new, err)`` with Hairer's error norm (each component relative to ``xs``/``vs`` plus
    ``_RTOL`` times the larger of its sizes at the step's ends)."""
    xn, vn, _, e5x, e5v, e3x, e3v = dp.step(_rates, x, v, 0.0, h, (kind, inside, E, R, m, q))
    scx = _RTOL * (xs + max(abs(x), abs(xn)))
    scv = _RTOL * (vs + max(abs(v), abs(vn)))
    e5x /= scx  # squares as products: Python's ``** 2`` is libm's pow, not always x * x as compiled
    e5v /= scv
    e3x /= scx
    e3v /= scv
    err5 = e5x * e5x + e5v * e5v
    err3 = e3x * e3x + e3v * e3v
    den = err5 + 0.01 * err3
    err = abs(h) * err5 / math.sqrt(0.5 * den) if den > 0.0 else 0.0
    return xn, vn, err


@jitable
def _land(kind, inside, x, v, h, which, target, E, R, m, q, xs, vs):
    """Shorten a step from ``(x, v)`` that crosses ``x = target`` (``which`` 0) or ``v = target``
    (``which`` 1) so that it ends on it: secant iteration on the step length, kept in its bracket
    (each trial a full step from the same start). Returns ``(h, x_new, v_new)`` of the last trial."""
    lo = 0.0
    flo = (x if which == 0 else v) - target
    hi = h
    xn, vn, _ = _step(kind, inside, x, v, hi, E, R, m, q, xs, vs)
    fhi = (xn if which == 0 else vn) - target
    hb, xb, vb = hi, xn, vn
    tol = 1e-15 * (xs if which == 0 else vs)
    for _ in range(100):
        if fhi == flo:
            break
        hn = hi - fhi * (hi - lo) / (fhi - flo)
        if not (min(lo, hi) < hn < max(lo, hi)):
            hn = 0.5 * (lo + hi)
        xn, vn, _ = _step(kind, inside, x, v, hn, E, R, m, q, xs, vs)
        f = (xn if which == 0 else vn) - target
        hb, xb, vb = hn, xn, vn
        if abs(f) <= tol or hn == hi or hn == lo:
            break
        if (f > 0.0) == (flo > 0.0):
            lo, flo = hn, f
        else:
            hi, fhi = hn, f
    return hb, xb, vb


@jitable
def _force_after(kind, x, v, s, E, R, m, q, xs, vs):
    """The contact force [N] after a step of length ``s`` from ``(x, v)`` in contact."""
    xn, vn, _ = _step(kind, True, x, v, s, E, R, m, q, xs, vs)
    return contact_force(kind, xn, vn, E, R, m, q)


@jitable
def _peak(kind, x0, v0, h0, x1, v1, h1, E, R, m, q, xs, vs):
    """The largest contact force [N] over two consecutive loading steps (from ``(x0, v0)`` of length
    ``h0``, then from ``(x1, v1)`` of length ``h1``): golden-section search on the time, each trial a
    step from the start of its own step (so as accurate as the integration)."""
    g = 0.5 * (math.sqrt(5.0) - 1.0)
    lo = 0.0
    hi = h0 + h1
    best = 0.0
    for _ in range(200):
        if hi - lo <= 1e-13 * (h0 + h1):
            break
        a = hi - g * (hi - lo)
        b = lo + g * (hi - lo)
        fa = (
            _force_after(kind, x0, v0, a, E, R, m, q, xs, vs)
            if a <= h0
            else _force_after(kind, x1, v1, a - h0, E, R, m, q, xs, vs)
        )
        fb = (
            _force_after(kind, x0, v0, b, E, R, m, q, xs, vs)
            if b <= h0
            else _force_after(kind, x1, v1, b - h0, E, R, m, q, xs, vs)
        )
        if fa > best:
            best = fa
        if fb > best:
            best = fb
        if fa > fb:
            hi = b
        else:
            lo = a
    return best


@jitable
def integrate(kind, V, E, R, m, q):
    """Integrate one impact at contact speed ``V`` [m/s]: ``(e, alpha_max, P_max, t_loading,
    t_unloading)``: the maximum approach and its time located on the step where the approach rate
    changes sign, the largest force of the loading by :func:`_peak` around the best step,
    ``t_unloading`` from the maximum approach to rupture (``inf`` and ``e = 0`` for a captured
    particle). See the module docstring."""
    dr = q[7]
    am = hertz.max_approach(V, E, R, m)
    xs = 1e-3 * (am if am > dr else dr)
    vs = 1e-3 * V
    T = hertz.time_scale(V, E, R, m)
    h = 0.01 * T
    x = 0.0
    v = V
    t = 0.0
    x_max = 0.0
    p_max = 0.0
    t_max = 0.0
    returns = 0
    inside = True
    loading = True
    # the best loading step: its start and length, and the step after it (where the peak may lie)
    p_best = -math.inf
    bx, bv, bh, nx, nv, nh = 0.0, V, 0.0, 0.0, V, 0.0
    need_next = False
    t_limit = 1e4 * T + 1e3 * (dr / V)
    W = willett_work(q) if kind == WILLETT else bridge_work(kind, q)
    while t < t_limit:
        xn, vn, err = _step(kind, inside, x, v, h, E, R, m, q, xs, vs)
        if err > 1.0 and h > 1e-9 * T:
            h *= max(0.2, 0.9 * err ** (-1.0 / 8.0))
            continue
        if loading and vn <= 0.0:  # the maximum approach lies in this step
            ht, xt, vt = _land(kind, True, x, v, h, 1, 0.0, E, R, m, q, xs, vs)
            x_max = xt
            t_max = t + ht
            if need_next:
                nx, nv, nh = x, v, ht
            elif contact_force(kind, xt, 0.0, E, R, m, q) > p_best:
                bx, bv, bh, nx, nv, nh = x, v, ht, xt, 0.0, 0.0
            p_max = _peak(kind, bx, bv, bh, nx, nv, nh, E, R, m, q, xs, vs)
            pt = contact_force(kind, xt, 0.0, E, R, m, q)
            if pt > p_max:
                p_max = pt
            loading = False
        elif loading:
            if need_next:
                nx, nv, nh = x, v, h
                need_next = False
            pn = contact_force(kind, xn, vn, E, R, m, q)
            if pn > p_best:
                p_best = pn
                bx, bv, bh = x, v, h
                need_next = True
        # a step that leaves the contact, comes back into it or reaches rupture ends on that boundary
        if inside and xn < 0.0:
            h, xn, vn = _land(kind, inside, x, v, h, 0, 0.0, E, R, m, q, xs, vs)
            t += h
            x, v = 0.0, vn
            inside = False
            if 0.5 * m * v * v < W:  # cannot climb out of the bridge's well: it comes back, poorer
                return 0.0, x_max, p_max, t_max, math.inf
            h = min(h, 0.01 * T) if h > 0.0 else 0.01 * T
            continue
        if not inside and xn > 0.0:
            h, xn, vn = _land(kind, inside, x, v, h, 0, 0.0, E, R, m, q, xs, vs)
            t += h
            x, v = 0.0, vn
            inside = True
            returns += 1
            if returns > MAX_RETURNS:
                return 0.0, x_max, p_max, t_max, math.inf
            h = 0.01 * T
            continue
        if not inside and v < 0.0 <= vn:
            # the particle turned back within the step: where it turned decides whether it reached
            # the rupture distance first (the step's end alone cannot tell)
            ht, xt, vt = _land(kind, inside, x, v, h, 1, 0.0, E, R, m, q, xs, vs)
            if xt <= -dr:
                h, xn, vn = _land(kind, inside, x, v, ht, 0, -dr, E, R, m, q, xs, vs)
                t += h
                return -vn / V, x_max, p_max, t_max, t - t_max
        if not inside and xn <= -dr:
            h, xn, vn = _land(kind, inside, x, v, h, 0, -dr, E, R, m, q, xs, vs)
            t += h
            return -vn / V, x_max, p_max, t_max, t - t_max
        t += h
        x, v = xn, vn
        if inside and 0.5 * m * v * v + contact_potential(kind, x, E, R, q) < 0.0:
            return 0.0, x_max, p_max, t_max, math.inf  # held in contact for good
        h *= min(4.0, 0.9 * err ** (-1.0 / 8.0)) if err > 0.0 else 4.0
    return 0.0, x_max, p_max, t_max, math.inf


@jitable
def capture_speed(kind, E, R, m, q):
    """The largest contact speed [m/s] at which the particle is captured (``e = 0``): bisection, to
    1e-10 relative, on the verdict of :func:`integrate` (leaves or not). Needed where the law
    dissipates (damping, viscosity); without dissipation the energy balance gives it directly."""
    W = bridge_work(kind, q) if kind != WILLETT else willett_work(q)
    if not W > 0.0:  # no bridge pulls the particle back (LIGGGHTS' floor): every impact leaves
        return 0.0
    lo = 0.0
    hi = math.sqrt(2.0 * W / m)
    while integrate(kind, hi, E, R, m, q)[0] == 0.0:
        lo = hi
        hi *= 2.0
        if hi > 1e12:
            return math.inf
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if hi - lo <= 1e-10 * hi:
            break
        if integrate(kind, mid, E, R, m, q)[0] == 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)
