"""Adhesive elastic-plastic impact of Thornton & Ning (1998), the whole law.

Source: Thornton, C. & Ning, Z. (1998), "A theoretical model for the stick/bounce behaviour of
adhesive, elastic-plastic spheres", *Powder Technology* 99:154-162 (TN98). The paper itself was not
available to this project; its equations are read, with their numbers, from three public sources
that agree where they overlap (the theory page, section "Adhesive elastic-plastic impact", says
what each gives and where each is wrong):

* a transcription of TN98 eqs. 1-81 (``yonghoon7153-source/Yonghoon-DEM-DFT``,
  ``docs/data/thorntonning1998_adhesive_elastoplastic_contact.csv`` at ``db230b93``);
* LIGGGHTS-PUBLIC ``src/normal_model_thornton_ning.h`` (commit ``84ba3d76``), which implements
  eqs. 60, 65, 69, 73, 76 and 77 incrementally;
* PyGran's ``ThorntonNing`` (``anabiman/pygran-sim``, ``PyGranSim/models.py`` at ``19d73146``),
  which writes the plastic loading force in closed form and solves eq. 65 for ``a_y``.

In terms of the contact radius ``a = b^2`` and ``s = (pi G/(2 E*))^(1/2)`` (``G`` the work of
adhesion, TN98's interface energy ``Gamma``), the law is:

**Loading, JKR** (eqs. 49-52, 61-62; :mod:`~microimpact.core.models.thornton_ning_1998_elastic_adhesive`):
``alpha = a^2/R* - 2 s a^(1/2)``, ``P = 4 E* a^3/(3 R*) - 4 E* s a^(3/2)``, the contact forming at
zero approach (``a_0^(3/2) = 2 s R*``, ``P = -8/9 P_c``, ``P_c = 3/2 pi G R*``, eq. 50).

**Yield** (eq. 65): where the JKR pressure at the centre of the contact reaches the limiting
pressure, ``p_y = 2 E* a_y/(pi R*) - (2 G E*/(pi a_y))^(1/2)``; with ``b = a^(1/2)`` this is the
cubic ``b^3 - a_y0 b - s R* = 0``, ``a_y0 = pi p_y R*/(2 E*)`` the yield radius without adhesion
(seed eq. 4), which has one positive root (Newton from above). Adhesion raises ``a_y`` above
``a_y0``. Where ``a_y`` is smaller than ``a_0`` the contact yields at first touch (``V_y = 0``);
where the JKR loading work from ``a_0`` to ``a_y`` is negative (``a_y`` inside the attractive part
of the curve) it yields at any speed too (``V_y = 0``).

**Plastic loading** (eq. 69): the stiffness
``dP/dalpha = (3 pi R* p_y P_1^(1/2) - 2 E* a_y P_c^(1/2))/(3 P_1^(1/2) - P_c^(1/2))``,
``P_1 = 4 E* a^3/(3 R*)`` (eq. 60), with the JKR geometry ``alpha(a)`` of loading. It integrates in
closed form (as PyGran writes it):
``P = P_Y + pi p_y (a^2 - a_Y^2) - 4 E* s a_y (a^(1/2) - a_Y^(1/2))`` from the yield point
``a_Y = max(a_y, a_0)`` with its JKR force ``P_Y`` (LIGGGHTS integrates the same stiffness from first
touch when ``a_y < a_0``; so does this file). Without adhesion this is the seed's
``P_y + pi p_y R*(alpha - alpha_y)`` (seed eqs. 6, 8).

**Unloading** (eqs. 73, 76, 77): along the JKR curve of the flattened radius ``R_p`` through the
point of maximum load ``(a*, P*)``:
``P = 4 E* a^3/(3 R_p) - 4 E* s a^(3/2)``, ``alpha = alpha_p + a^2/R_p - 2 s a^(1/2)``, with
``R_p = R* P_1*/(P* + (4 P_c P_1*)^(1/2))`` (eq. 76), ``P_1* = 4 E* a*^3/(3 R*)``, so the pull-off
force is ``P_cr = 3/2 pi G R_p`` (eq. 77), and ``alpha_p = a*^2 (1/R* - 1/R_p)``. Eq. 73's
stiffness is this curve's. The contact breaks at the least approach of the curve (``a_f^(3/2) = s
R_p/2``, force ``-5/9 P_cr``), as in the elastic case (PyGran: ``deltaf = alpha_p - 3/4 (pi^2 G^2
R_p/E*^2)^(1/3)``). Without adhesion ``R_p`` is the seed's eq. 9 and ``alpha_p`` its eq. 11; below
yield ``R_p = R*`` and the impact is the elastic adhesive one.

Where the sources disagree: LIGGGHTS evaluates ``P_1*`` in eq. 76 from the maximum *force* by
eq. 60 (``P_1* = P* + 2 P_c + 2 (P_c (P* + P_c))^(1/2)``), which is the elastic JKR load of ``P*``,
not the load of the contact radius reached: without adhesion it gives ``R_p = R*`` (no flattening,
against the seed's eq. 9). PyGran takes ``a*`` from the geometry at the maximum approach (as here)
but divides by ``P*`` alone, dropping eq. 76's ``(4 P_c P_1*)^(1/2)``. This file follows eq. 76 as
transcribed, with ``a*`` the contact radius at the maximum approach: the only reading that keeps
the unloading curve through the point of maximum load and gives the seed's eq. 9 without adhesion.

**Outcome.** The energy balance gives the maximum approach (a polynomial in ``b``: Newton from
above), ``e^2`` is the work of the unloading curve from ``a*`` to the snap-off over the impact
energy (in closed form), and the particle sticks (``e = 0``, ``contact_time = inf``) where that work
is not positive. The stage times are Gauss-Legendre quadratures after substitutions that remove
the turning-point singularities (the elastic stage as the difference of two JKR times to the
turning point of the elastic trajectory). The sticking velocity (:func:`sticking_velocity`) is TN98's
eq. 54 ``V_s = (14.18/m*)^(1/2) (G^5 R*^4/E*^2)^(1/6)`` where that is below ``V_y``, else the speed
whose rebound work is zero (bisection in ``a*``).

**Weak adhesion can raise e.** Above yield the rebound is not bounded by the same impact without
adhesion: eq. 76's ``R_p`` carries ``(4 P_c P_1*)^(1/2)``, so the recovered approach, and ``e``,
change by ``O(G^(1/2))`` while the adhesive loss ``(V_s/V)^2`` grows as ``G^(5/3)``; for the
seed's NH4Fl particle on silicon (``R = 2.45`` um) at ``V = 22.034`` m/s, three times this law's own
``V_y`` with ``G = 0.1`` (7.345 m/s; 2.93 times the seed's 7.52 m/s), weak adhesion raises ``e``
(0.8680 against 0.8669 without it). This is the law as transcribed; it is bounded by the elastic
adhesive impact (``e^2 <= 1 - (V_s/V)^2``).

**Parameters of this model** (``params``):

``work_of_adhesion`` ``G`` [J/m^2], ``>= 0``
    TN98's interface energy ``Gamma`` (LIGGGHTS' ``surfaceEnergy``, twice LAMMPS' ``cohesion``).
    0 gives the seed's model (``thornton_ning_2016``) exactly; ``p_y = inf`` gives
    ``thornton_ning_1998_elastic_adhesive``.

Fields: every field of :data:`~microimpact.core.quantities.OUTCOME_FIELDS`. ``yield_velocity`` is
the speed whose JKR loading just reaches ``a_Y`` (0 where it yields at any speed), ``elastic`` is 1
at and below it (no yield; adhesion still takes energy), ``max_contact_radius`` is the JKR contact
radius ``a*``, ``plastic_approach`` is ``alpha_p`` (the contact breaks below it, at
:func:`separation_approach_after`), ``elastic_stage_time`` / ``plastic_stage_time`` the JKR and
plastic parts of the loading time.

Validity: the JKR limit (Tabor parameter well above 1); small strain (``large_strain`` flags
``a*/R* > 0.3``); a rigid-perfectly-plastic limiting pressure; no rate effects or damping.
"""

from __future__ import annotations

import math

from .._jit import jitable
from . import Parameter, _jkr, checks
from . import thornton_ning_2016 as _seed
from ._common import in_bounds, nan_outcome, pack
from ._jkr import GW, GX
from ._jkr import b_of_alpha as _b_of_alpha
from ._jkr import force_b as _force_b
from ._jkr import work_difference as _wd

NAME = "thornton_ning_1998_adhesive_plastic"
TITLE = "Adhesive elastic-plastic spheres: JKR loading, yield, JKR unloading on R_p (Thornton & Ning 1998)"
CITATION = "Thornton & Ning, Powder Technol. 99:154 (1998)"
LABEL = "Thornton-Ning 1998 adhesive-plastic"
#: The particle can stick (``e = 0`` below the sticking velocity).
STICKS = True
STAGES = {1: "loading, JKR then plastic (eqs. 49-52, 69)", 3: "unloading, JKR on R_p (eqs. 73, 76)"}
#: The wall's adhesion law (``adhesion=NAME`` of :func:`microimpact.wall.wall_interaction`), through the
#: table of its correction :func:`microimpact.core.adhesion.whole_law_correction`.
WALL_ADHESION = True
PARAMETERS = (
    Parameter.of("work_of_adhesion", "G >= 0, interface energy (LIGGGHTS' surfaceEnergy)", low=0.0, normal=True),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
#: Cost class of the outcome (the contract's ``OUTCOME_COST``): its contact times' quadrature, 1.4 ms a
#: point in Python (``e`` alone: 30 us).
OUTCOME_COST = "slow"

_THIRD = 1.0 / 3.0


@jitable
def _pd(x, y, n):
    """``(x^n - y^n)/(x - y) = sum_k x^k y^(n-1-k)`` (no cancellation; ``n x^(n-1)`` at ``x = y``)."""
    total = 0.0
    xk = 1.0
    for k in range(n):
        yk = 1.0
        for _ in range(n - 1 - k):
            yk *= y
        total += xk * yk
        xk *= x
    return total


@jitable
def yield_root(E, R, p_y, s):
    """``b_y = a_y^(1/2)`` [m^(1/2)]: the root of ``b^3 - a_y0 b - s R* = 0`` (eq. 65); ``inf`` for ``p_y = inf``.

    Newton from ``a_y0^(1/2) + (s R*)^(1/3)``, above the root, where the cubic is convex and increasing.
    """
    if p_y == math.inf:
        return math.inf
    c = math.pi * p_y * R / (2.0 * E)
    q = s * R
    b = math.sqrt(c) + q**_THIRD
    for _ in range(200):
        step = (b * b * b - c * b - q) / (3.0 * b * b - c)
        b -= step
        if step <= 1e-16 * b:
            break
    return b


@jitable
def yield_constants(E, R, p_y, G):
    """``(s, b_0, b_y, b_Y, K, P_Y)``: ``s = (pi G/(2E*))^(1/2)``, first touch ``b_0 = (2 s R*)^(1/3)``,
    the eq. 65 root ``b_y``, the yield point ``b_Y = max(b_y, b_0)``, ``K = 4 E* s a_y`` (eq. 69's
    adhesive term) and the JKR force ``P_Y`` [N] at ``b_Y`` (all with ``b = a^(1/2)``)."""
    s = math.sqrt(0.5 * math.pi * G / E)
    b0 = (2.0 * R * s) ** _THIRD
    by = yield_root(E, R, p_y, s)
    bY = max(by, b0)
    K = 4.0 * E * s * by * by
    PY = _force_b(bY, E, R, s) if bY < math.inf else math.inf
    return s, b0, by, bY, K, PY


@jitable
def plastic_force_b(b, bY, PY, K, p_y):
    """Plastic loading force [N] at ``b = a^(1/2) >= b_Y``: eq. 69 integrated,
    ``P_Y + pi p_y (a^2 - a_Y^2) - K (a^(1/2) - a_Y^(1/2))``."""
    b2 = b * b
    bY2 = bY * bY
    return PY + math.pi * p_y * (b2 - bY2) * (b2 + bY2) - K * (b - bY)


@jitable
def loading_force_b(b, E, R, p_y, s, bY, PY, K):
    """Loading force [N] at ``b = a^(1/2)``: JKR up to the yield point, then plastic (eqs. 62, 69)."""
    if b <= bY:
        return _force_b(b, E, R, s)
    return plastic_force_b(b, bY, PY, K, p_y)


@jitable
def _plastic_work_quotient(x, y, E, R, p_y, s, bY, PY, K):
    """``(F(x) - F(y))/(x - y)`` with ``F`` the antiderivative of ``P dalpha`` on the plastic branch
    (``P = A0 + pi p_y b^4 - K b``, ``dalpha/db = 4 b^3/R - 2 s``), free of cancellation in ``x - y``."""
    A0 = PY - math.pi * p_y * bY * bY * bY * bY + K * bY
    return (
        A0 * (_pd(x, y, 4) / R - 2.0 * s)
        + math.pi * p_y * _pd(x, y, 8) / (2.0 * R)
        - (0.4 * s * math.pi * p_y + 0.8 * K / R) * _pd(x, y, 5)
        + K * s * _pd(x, y, 2)
    )


@jitable
def _plastic_turning_point(K2, E, R, p_y, s, bY, PY, K):
    """``b*`` where the plastic loading work from ``b_Y`` equals ``K2 >= 0`` (the last root: beyond the
    zero of the force the work is convex and increasing, so Newton from above converges to it)."""
    b = 1.5 * bY
    while (b - bY) * _plastic_work_quotient(b, bY, E, R, p_y, s, bY, PY, K) < K2:
        b *= 1.5
    for _ in range(200):
        f = (b - bY) * _plastic_work_quotient(b, bY, E, R, p_y, s, bY, PY, K) - K2
        d = plastic_force_b(b, bY, PY, K, p_y) * (4.0 * b * b * b / R - 2.0 * s)
        step = f / d
        b -= step
        if abs(step) <= 1e-16 * b:
            break
    return b


@jitable
def unloading_radius_b(bs, Ps, E, R, s):
    """``R_p = R* P_1*/(P* + (4 P_c P_1*)^(1/2))`` [m] (eq. 76) at ``b* = a*^(1/2)``, ``P*``:
    ``(4 E* a*^3/3) / (P* + 4 E* s a*^(3/2))``."""
    b3 = bs * bs * bs
    return (4.0 * E * b3 * b3 / 3.0) / (Ps + 4.0 * E * s * b3)


@jitable
def yield_velocity(E, R, m, p_y, G):
    """``V_y`` [m/s]: the speed whose JKR loading from first touch just reaches the yield point
    (0 where the work to get there is not positive; ``inf`` for ``p_y = inf``)."""
    s, b0, by, bY, K, PY = yield_constants(E, R, p_y, G)
    if bY == math.inf:
        return math.inf
    KY = (bY - b0) * _wd(bY, b0, E, R, s)
    return math.sqrt(2.0 * KY / m) if KY > 0.0 else 0.0


@jitable
def yield_velocity_of(E, R, m, p_y, params):
    """The contract's hook (:mod:`microimpact.core.models`): :func:`yield_velocity` [m/s] with
    ``params = (G,)``: the field ``yield_velocity`` of :func:`outcome` without its quadratures (the
    same bits for ``G > 0``; at ``G = 0``, where :func:`outcome` is the seed's, to rounding)."""
    return yield_velocity(E, R, m, p_y, params[0])


@jitable
def _rebound_work(bs, E, R, p_y, s, bY, PY, K):
    """``(W_r, R_p)``: the work [J] of the unloading curve from ``b*`` to its snap-off (the rebound
    energy; not positive where the particle sticks), and ``R_p`` [m] (eqs. 76, 77)."""
    Ps = plastic_force_b(bs, bY, PY, K, p_y)
    Rp = unloading_radius_b(bs, Ps, E, R, s)
    bf = (0.5 * Rp * s) ** _THIRD
    return (bs - bf) * _wd(bs, bf, E, Rp, s), Rp


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (module docstring), in the order of ``OUTCOME_FIELDS``."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf and p_y > 0.0):
        return nan_outcome(V)
    G = params[0]
    if G == 0.0:
        return _seed.outcome(V, E, R, m, p_y, ())
    s, b0, by, bY, K, PY = yield_constants(E, R, p_y, G)
    bF = (0.5 * R * s) ** (1.0 / 3.0)
    Kin = 0.5 * m * V * V
    if bY == math.inf:
        KY = math.inf
        Vy = math.inf
    else:
        KY = (bY - b0) * _wd(bY, b0, E, R, s)
        Vy = math.sqrt(2.0 * KY / m) if KY > 0.0 else 0.0
    if V == 0.0:
        v = 0.0
    elif Vy == 0.0:
        v = math.inf
    else:
        v = V / Vy
    if Kin <= KY:  # no yield: the elastic adhesive impact (the same code, the same bits)
        o = _jkr.impact(V, E, R, m, s, b0, bF)
        return pack(V, Vy, v, 1.0, o[4], o[5], o[6], o[7], o[8], R, o[11], R, o[15], 0.0, o[15], o[16])
    # plastic: the maximum approach on the plastic branch
    bs = _plastic_turning_point(Kin - KY, E, R, p_y, s, bY, PY, K)
    Ps = plastic_force_b(bs, bY, PY, K, p_y)
    Rp = unloading_radius_b(bs, Ps, E, R, s)
    bs2 = bs * bs
    a_max = bs2 * bs2 / R - 2.0 * s * bs
    a_p = bs2 * bs2 * (Rp - R) / (R * Rp)
    bf = (0.5 * Rp * s) ** _THIRD
    Wr = (bs - bf) * _wd(bs, bf, E, Rp, s)
    # loading times: JKR stage (difference of two times to the elastic turning point), plastic stage
    if bY > b0:
        # the elastic turning point the JKR stage would reach (as in _jkr.impact), from which both times count
        bm = _jkr.turning_point(Kin, _jkr.work_integral(b0, E, R, s), b0, E, R, s)
        t1 = _jkr.time_to_top(b0, bm, E, R, m, s) - _jkr.time_to_top(bY, bm, E, R, m, s)
    else:
        t1 = 0.0
    W = math.sqrt(bs - bY)
    total = 0.0
    for i in range(48):
        w = 0.5 * W * (GX[i] + 1.0)
        b = bs - w * w
        q = _plastic_work_quotient(bs, b, E, R, p_y, s, bY, PY, K)
        total += GW[i] * 2.0 * (4.0 * b * b * b / R - 2.0 * s) / math.sqrt(2.0 * q / m)
    t2 = 0.5 * W * total
    tL = t1 + t2
    if Wr <= 0.0:
        e = 0.0
        tU = math.inf
    else:
        e = math.sqrt(Wr / Kin)
        b0p = (2.0 * Rp * s) ** _THIRD
        tU = _jkr.time_to_top(b0p, bs, E, Rp, m, s) + _jkr.time_tensile(bf, b0p, Wr, E, Rp, m, s)
    return pack(V, Vy, v, 0.0, e, e * V, a_max, a_p, Ps, Rp, bs2, R, t1, t2, tL, tU)


@jitable
def restitution(V, E, R, m, p_y, params):
    """The restitution coefficient [-] of :func:`outcome` alone (the same operations, the same bits),
    without the contact times: for maps over many speeds and sizes."""
    G = params[0]
    if not (G >= 0.0 and G < math.inf and V >= 0.0 and V < math.inf and p_y > 0.0):
        return math.nan
    if G == 0.0:
        return _seed.restitution_at(V, _seed.yield_point(E, R, m, p_y)[2])
    s, b0, by, bY, K, PY = yield_constants(E, R, p_y, G)
    Kin = 0.5 * m * V * V
    KY = math.inf if bY == math.inf else (bY - b0) * _wd(bY, b0, E, R, s)
    if Kin <= KY:  # as _jkr.impact: e = (1 - W/K)^(1/2), W the work of the tensile branch
        bF = (0.5 * R * s) ** (1.0 / 3.0)
        W = _jkr.work_integral(bF, E, R, s) - _jkr.work_integral(b0, E, R, s)
        return 0.0 if Kin <= W else math.sqrt(1.0 - W / Kin)
    bs = _plastic_turning_point(Kin - KY, E, R, p_y, s, bY, PY, K)
    Wr = _rebound_work(bs, E, R, p_y, s, bY, PY, K)[0]
    return 0.0 if Wr <= 0.0 else math.sqrt(Wr / Kin)


#: The contract's hook (:mod:`microimpact.core.models`): fitting and ranking compare ``e`` alone.
restitution_only = restitution


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """Sticking (capture) velocity [m/s]: ``e = 0`` at and below it, ``e > 0`` above.

    TN98's ``V_s = (2 W/m*)^(1/2)`` of the elastic JKR impact (eq. 54; ``W = 7.09 (G^5 R*^4/E*^2)^(1/3)``)
    where it is at most ``V_y``; otherwise the speed whose rebound work (the unloading curve of
    ``R_p`` from ``a*`` to its snap-off) is zero: the first sign change of that work along ``a*``
    (a geometric scan by 1.02, then bisection to rounding), converted to a speed by the loading work.
    0 without adhesion.
    """
    G = params[0]
    if not G > 0.0:
        return 0.0
    s, b0, by, bY, K, PY = yield_constants(E, R, p_y, G)
    bF = (0.5 * R * s) ** (1.0 / 3.0)
    W = (b0 - bF) * _wd(b0, bF, E, R, s)  # G(b0) - G(bF) < 0: minus the work lost
    W = -W
    KY = math.inf if bY == math.inf else (bY - b0) * _wd(bY, b0, E, R, s)
    if W <= KY:
        return math.sqrt(2.0 * W / m)
    # plastic: the smallest b* (reached from rest or faster) whose rebound work is positive
    lo = _plastic_turning_point(max(-KY, 0.0), E, R, p_y, s, bY, PY, K) if KY < 0.0 else bY
    if _rebound_work(lo, E, R, p_y, s, bY, PY, K)[0] > 0.0:
        return 0.0
    hi = lo * 1.02
    while _rebound_work(hi, E, R, p_y, s, bY, PY, K)[0] <= 0.0:
        lo = hi
        hi *= 1.02
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:
            break
        if _rebound_work(mid, E, R, p_y, s, bY, PY, K)[0] > 0.0:
            hi = mid
        else:
            lo = mid
    Kin = KY + (hi - bY) * _plastic_work_quotient(hi, bY, E, R, p_y, s, bY, PY, K)
    return math.sqrt(2.0 * Kin / m)


@jitable
def _unloading_state(alpha_max, E, R, p_y, G):
    """``(yielded, R_p, alpha_p, s)`` of the unloading from ``alpha_max``."""
    s, b0, by, bY, K, PY = yield_constants(E, R, p_y, G)
    bs = _b_of_alpha(alpha_max, E, R, s)
    if bs <= bY:
        return False, R, 0.0, s
    Ps = plastic_force_b(bs, bY, PY, K, p_y)
    Rp = unloading_radius_b(bs, Ps, E, R, s)
    bs2 = bs * bs
    return True, Rp, bs2 * bs2 * (Rp - R) / (R * Rp), s


@jitable
def separation_approach_after(alpha_max, E, R, m, p_y, params):
    """Approach [m] where the contact breaks after loading to ``alpha_max``: the least approach of the
    unloading curve, ``alpha_p - 3/4 (pi^2 G^2 R_p/E*^2)^(1/3)``; 0 without adhesion (the seed ends at
    zero force)."""
    G = params[0]
    if G == 0.0:
        return 0.0
    yielded, Rp, ap, s = _unloading_state(alpha_max, E, R, p_y, G)
    return ap - 0.75 * (math.pi * math.pi * G * G * Rp / (E * E)) ** _THIRD


@jitable
def separation_approach(E, R, m, p_y, params):
    """The snap-off approach of an impact that does not yield, ``-3/4 (pi^2 G^2 R*/E*^2)^(1/3)`` [m]
    (where the contact breaks after yield depends on the impact: :func:`separation_approach_after`)."""
    G = params[0]
    return -0.75 * (math.pi * math.pi * G * G * R / (E * E)) ** _THIRD


@jitable
def ends_at_zero_force(params):
    """True only without adhesion (the seed's unloading ends at zero force)."""
    return params[0] == 0.0


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N]: JKR then plastic loading while ``alpha >= alpha_max`` (eqs. 62, 65, 69); the
    JKR curve of ``R_p`` from the maximum approach (eqs. 73, 76, 77) down to its snap-off; zero apart."""
    G = params[0]
    if G == 0.0:
        return _seed.force(alpha, alpha_dot, alpha_max, E, R, m, p_y, ())
    if alpha_max <= 0.0 and alpha < 0.0:
        return 0.0
    if alpha >= alpha_max:
        s, b0, by, bY, K, PY = yield_constants(E, R, p_y, G)
        return loading_force_b(_b_of_alpha(alpha, E, R, s), E, R, p_y, s, bY, PY, K)
    yielded, Rp, ap, s = _unloading_state(alpha_max, E, R, p_y, G)
    x = alpha - ap
    bf = (0.5 * Rp * s) ** _THIRD
    if x < bf * bf * bf * bf / Rp - 2.0 * s * bf:
        return 0.0
    return _force_b(_b_of_alpha(x, E, Rp, s), E, Rp, s)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """:func:`force` (the contact's end is the snap-off approach, not a zero of the force, with adhesion)."""
    return force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


@jitable
def rebound_energy_ratio(V, E, R, m, p_y, params):
    """``W_r/K`` [-], signed: the work of the unloading curve from the maximum approach to its snap-off
    (eqs. 73, 76, 77) over the impact energy ``K = m* V^2/2``.

    Where it is positive it is ``e^2`` (:func:`restitution` is its square root: the same operations,
    the same bits); where it is not, the particle sticks, and the value says how far it is from
    bouncing. That is what the wall interaction's table of this law interpolates
    (:func:`microimpact.core.adhesion.whole_law_correction`): a quantity smooth across the sticking
    velocity, where ``e`` itself rises like a square root. NaN for ``V <= 0`` or bad parameters.
    """
    G = params[0]
    if not (G >= 0.0 and G < math.inf and V > 0.0 and V < math.inf and p_y > 0.0):
        return math.nan
    if G == 0.0:
        e = _seed.restitution_at(V, _seed.yield_point(E, R, m, p_y)[2])
        return e * e
    s, b0, by, bY, K, PY = yield_constants(E, R, p_y, G)
    Kin = 0.5 * m * V * V
    KY = math.inf if bY == math.inf else (bY - b0) * _wd(bY, b0, E, R, s)
    if Kin <= KY:  # elastic adhesive: 1 - W/K, W the work of the tensile branch (as restitution)
        bF = (0.5 * R * s) ** (1.0 / 3.0)
        W = _jkr.work_integral(bF, E, R, s) - _jkr.work_integral(b0, E, R, s)
        return 1.0 - W / Kin
    bs = _plastic_turning_point(Kin - KY, E, R, p_y, s, bY, PY, K)
    return _rebound_work(bs, E, R, p_y, s, bY, PY, K)[0] / Kin


#: The adhesion limit the law is written for (``"JKR"``: Tabor parameter large; ``"DMT"``: small):
#: :meth:`microimpact.pair.ContactPair.impact` flags pairs outside it
#: (:func:`microimpact.core.adhesion.tabor_parameter`).
ADHESION_LIMIT = "JKR"


@jitable
def work_of_adhesion(params):
    """The work of adhesion ``G`` [J/m^2] of ``params`` (``G`` itself), for Tabor's parameter."""
    return params[0]


@jitable
def tangential_contact_radius(alpha, alpha_max, E, R, m, p_y, params):
    """Contact radius [m] at ``alpha`` for a tangential spring (:mod:`microimpact.oblique.adhesive`): the
    JKR radius of the loading curve while ``alpha >= alpha_max``, of the unloading curve of ``R_p`` from
    the plastic approach after (``a = b^2``, as :func:`force` computes it)."""
    G = params[0]
    if G == 0.0:
        return math.sqrt(R * alpha) if alpha > 0.0 else 0.0
    if alpha >= alpha_max:
        s = math.sqrt(0.5 * math.pi * G / E)
        b = _b_of_alpha(alpha, E, R, s)
        return b * b
    yielded, Rp, ap, s = _unloading_state(alpha_max, E, R, p_y, G)
    b = _b_of_alpha(alpha - ap, E, Rp, s)
    return b * b
