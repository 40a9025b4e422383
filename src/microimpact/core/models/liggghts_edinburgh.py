r"""What LIGGGHTS-PUBLIC 3.8's ``edinburgh`` normal model (EEPA) computes for one normal impact.

The Edinburgh elasto-plastic adhesion model (EEPA) of Thakur, Morrissey, Sun, Chen & Ooi (2014),
*Granular Matter* 16:383-400, as LIGGGHTS-PUBLIC 3.8.0 runs it: ``src/normal_model_edinburgh.h`` of
CFDEMproject/LIGGGHTS-PUBLIC at commit ``84ba3d76`` (the release 3.8.0; unchanged at ``3d5c00f2``),
class ``NormalModel<EDINBURGH>``, method ``surfacesIntersect`` with its helpers
``calculate_deltan_p_max``, ``whichd`` and ``calculate_k_adh``; the properties are read in
``src/global_properties.cpp`` (same commit). The paper itself was not available to this project: its
law is read from the code, and the code is what is modelled (Debian's ``liggghts
3.8.0+repack1-9+b2`` lists ``edinburgh`` among its normal models and runs it;
``tests/laws/test_liggghts_edinburgh.py``).

The force, as the code computes it (``deltan`` is the approach ``alpha``)
------------------------------------------------------------------------------
* Stiffness: ``kn = 4/3 Yeff reff^(1/2)`` for ``dex != 1`` and ``kn = 2 Yeff reff`` for ``dex == 1``
  (the code's words), ``k1 = kn``, ``k2 = kn kn2k1`` with ``kn2k1`` the property
  ``UnloadingStiffness``. ``Yeff`` is ``E*``; ``reff = radi`` on a wall and ``ri rj/(ri + rj)``
  between two spheres, i.e. ``R*``; ``n = dex`` (``overlapExponent``), ``x = cex``
  (``adhesionExponent``).
* Loading (``fTmp >= k1 deltan^n``): ``k1 alpha^n`` (Thakur et al.'s eq. for ``f_hys``, first branch).
* Unloading and reloading: ``k2 (alpha^n - delta_p^n)`` with the plastic overlap
  ``delta_p = lambda alpha_max``, ``lambda = (1 - k1/k2)^(1/n)``: the unloading line leaves the loading
  curve at the largest approach ``alpha_max``, ``k2 (alpha_max^n - delta_p^n) = k1 alpha_max^n``.
* Adhesive branch: where ``k2 (alpha^n - delta_p^n) <= -k_adh alpha^x`` the force is
  ``-k_adh alpha^x``; it meets the unloading line at ``delta_s``, the root of
  ``k2 alpha^n + k_adh alpha^x = k2 delta_p^n``, and holds down to zero approach, where the contact
  ends (the code only calls the model while the surfaces overlap).
* ``k_adh``, option 1 (``fixKc off``, the default): from the surface energy ``Gamma`` (``surfaceEnergy``)
  and the contact radius ``a`` of the plastic overlap: ``f_min = 1.5 pi Gamma a`` capped at
  ``k2 delta_p^n / 2``; uncapped, ``k_adh = f_min / delta_min^x`` with ``delta_min = (delta_p^n -
  f_min/k2)^(1/n)`` (the adhesive branch meets the unloading line at the force ``-f_min``), capped,
  ``delta_min = delta_p/2``. ``a`` is the radius of the circle where two spheres of radii ``ri, rj``
  at the centre distance ``d = ri + rj - delta_p`` intersect, ``a = (4 d^2 ri^2 - (d^2 - rj^2 +
  ri^2)^2)^(1/2) / (2 d)``; for two equal spheres of radius ``r = 2 R*``,
  ``a = (r delta_p - delta_p^2/4)^(1/2)``. **On a wall the code takes ``d = ri`` and ``rj = 0`` (the
  wall sets no ``radj``; ``SurfacesIntersectData`` initialises it to 0), so ``a = 0``,
  ``f_min = 0`` and ``k_adh = 0``: the surface energy gives no adhesion against a wall.**
* ``k_adh``, option 2 (``fixKc on``): ``k_adh = kn2kc k1`` with ``kn2kc`` the property
  ``coefficientAdhesionStiffness``. On the adhesive branch the code moves its history to
  ``deltaMax = (k2 + k_adh)/(k2 - k1) alpha``, the linear law's point; for ``x = n`` this keeps every
  later step of a separating particle on the branch; for ``x != n`` the force jumps between the
  branches by amounts the step sets, so this model takes option 2 with ``x = n`` only (ValueError).
* Constant pull-off ``f_0`` (``pullOffForce``): added to the force at every step of the contact
  (``Fn = Fn_damping + Fn_contact + f_0``); negative is attractive.
* Damping: ``Fn_damping = -gamman vn`` with ``gamman = (4 meff kn / (1 + (pi/ln e)^2))^(1/2)``,
  ``e`` the property ``coefficientRestitution`` (``CoeffRestLog = ln e``; ``e = 1`` gives
  ``gamman = 0``). ``kn`` is the *coefficient* ``k1``, not a tangent stiffness, and ``gamman`` is
  constant through the contact: for ``n = 1`` it is the linear spring-dashpot's damping of the loading
  spring; for ``n != 1`` its value depends on the unit system (``kn`` is in N/m^n) and the input ``e``
  is not the ``e`` of any impact. ``meff`` is the particle's mass on a wall, ``m_i m_j/(m_i + m_j)``
  between spheres: ``m*``.
* ``limitForce`` (on by default): ``Fn`` below zero is set to zero when ``k_adh == 0`` and
  ``f_0 == 0``. With ``fixKc on`` the test reads the ``k_adh`` declared outside the branch, which
  option 2 never sets (its own ``k_adh`` is a second variable of the same name in the inner block):
  **with ``fixKc on``, ``limitForce on`` and ``f_0 = 0`` the adhesive force is always clipped away**
  (the particle bounces as without adhesion). With option 1 the outer ``k_adh`` is set once the contact
  unloads.

Geometry: the parameter ``two_spheres`` chooses the contact radius of option 1 (0: a sphere on a
wall, ``a = 0``, what ``dem.deck(geometry="wall")`` runs; 1: two equal spheres of radius ``2 R*`` and
mass ``2 m*``, ``geometry="sphere"``); ``k1``, ``k2`` and ``gamman`` are the same for both.

So the law is ``F = F_c(alpha, alpha_max) + gamma alpha' + f_0`` (clipped at zero where
``limitForce`` applies), ``F_c`` the hysteretic spring above. The speed enters only through the
damping; in its first pass (load, unload, separate or turn back) the path of ``F_c`` depends only
on ``alpha`` and ``alpha_max``, which is what :func:`force` takes.

Outcome
-------
With the constant ``gamma`` and the power laws there is no closed form; :func:`outcome` integrates
``m* alpha'' = -F`` through its phases (loading to ``alpha_max``; unloading to ``delta_s``; the
adhesive branch to zero approach) with the classical fourth-order Runge-Kutta method, each step
checked against two half steps (error below ``1e-12`` of the approach and speed scales) and
advanced by their Richardson extrapolation; the ends of the phases are located by regula falsi on
the step. A damped particle that creeps towards the equilibrium of the unloading line with ``f_0``
(where ``F_c + f_0 = 0``) never reaches it and is captured, as is a particle whose approach rate
returns to zero before the contact ends (``e = 0``, ``unloading_time = inf``). ``max_force`` is the largest force of
the contact (the damping's ``gamma V + f_0`` at first touch or the maximum of loading),
``plastic_approach`` is ``delta_p``. Where ``limitForce`` clips, the contact ends where the force
first vanishes (the particle then leaves at constant speed), as the DEM record measures it.

Capture velocity ``V_s``: the largest speed at which the particle is captured, by bisection of that
verdict (:func:`sticking_velocity`); 0 for a law without attraction.

Energy: over a separating impact ``1/2 m* V^2 - 1/2 m* (e V)^2 = W_c + W_d`` with ``W_c`` the work of
``F_c`` around its loop (loading ``k1 alpha_max^(n+1)/(n+1)`` less what the unloading line and the
adhesive branch return, both in closed form, :func:`spring_work`) and ``W_d`` the work of the damping
and of the clipping, integrated along (:func:`energy_budget`); ``f_0`` does no net work. ``F_c``
never lies above the loading curve and the damping only takes energy, so ``e <= 1``:
:func:`outside_validity` flags a budget that would create energy (bit 1), which the law cannot do.
"""

from __future__ import annotations

import math

from .._jit import jitable
from ..roots import illinois
from . import LIMIT_FORCE, Parameter, checks
from ._common import dem_outcome, in_bounds, nan_outcome

NAME = "liggghts_edinburgh"
TITLE = "LIGGGHTS-PUBLIC 3.8 edinburgh (EEPA): k1 d^n loading, k2 unloading, -k_adh d^x adhesion, f0, dashpot"
CITATION = (
    "Thakur, Morrissey, Sun, Chen & Ooi, Granular Matter 16:383 (2014); "
    "LIGGGHTS-PUBLIC 3.8, src/normal_model_edinburgh.h (CFDEMproject, commit 84ba3d76)"
)
LABEL = "LIGGGHTS EEPA"
STICKS = True
COST = "slow"
#: Where ``limitForce`` clips, the force vanishes with the slope of its damping term.
ZERO_FORCE_ORDER = 1.0
PARAMETERS = (
    Parameter(
        "unloading_ratio",
        "1",
        "k2/k1 >= 1 (LIGGGHTS' UnloadingStiffness, kn2k1; 1: elastic)",
        default=5.0,
        low=1.0,
    ),
    Parameter(
        "overlap_exponent", "1", "n >= 1 of k1 d^n, k2 d^n (overlapExponent, dex)", default=1.5, low=1.0, high=3.0
    ),
    Parameter(
        "adhesion_exponent",
        "1",
        "x >= 1 of the adhesive branch -k_adh d^x (adhesionExponent, cex)",
        default=1.5,
        low=1.0,
        high=3.0,
    ),
    Parameter.of(
        "coefficient_restitution",
        "e_n in (0.05, 1], LIGGGHTS' coefficientRestitution (1: no damping)",
        default=1.0,
        low=0.05,
        high=1.0,
        low_open=True,
    ),
    Parameter.of(
        "work_of_adhesion",
        "G >= 0: LIGGGHTS' surfaceEnergy, which its pull-off 1.5 pi G a (fixKc off) uses as the work of adhesion G",
        default=0.0,
        low=0.0,
    ),
    Parameter(
        "adhesion_stiffness_ratio",
        "1",
        "k_adh/k1 >= 0 of option fixKc on (coefficientAdhesionStiffness)",
        default=0.0,
        low=0.0,
    ),
    Parameter("pull_off_force", "N", "constant f0 added in contact (pullOffForce; negative attracts)", default=0.0),
    Parameter(
        "fix_kc", "1", "1: k_adh = kn2kc k1 (fixKc on); 0: k_adh from the surface energy", default=0.0, flag=True
    ),
    LIMIT_FORCE,  # limitForce: on (1) is the code's default
    Parameter.of(
        "two_spheres",
        "1: two equal spheres of radius 2 R*; 0: a sphere of radius R* on a wall (option 1's pull-off radius a = 0)",
        default=0.0,
        flag=True,
    ),
)
BOUNDS, _validate_bounds = checks(NAME, PARAMETERS)

# positions in params
_RATIO, _N, _X, _E, _GAMMA, _KC, _F0, _FIXKC, _LIMIT, _PAIR = range(10)


def validate(params):
    """Check ``params`` (ValueError naming the parameter and its value); return it as floats.

    Beyond the bounds: option 2 (``fix_kc = 1``) needs ``adhesion_exponent == overlap_exponent``
    (see the module docstring: for ``x != n`` the code's history update is the linear law's and the
    force it gives depends on the time step)."""
    out = _validate_bounds(params)
    if out[_FIXKC] == 1.0 and out[_X] != out[_N]:
        raise ValueError(
            f"adhesion_exponent must equal overlap_exponent ({out[_N]!r}) with fix_kc = 1, got {out[_X]!r}"
        )
    return out


@jitable
def _valid(params):
    if not in_bounds(params, BOUNDS):
        return False
    return not (params[_FIXKC] == 1.0 and params[_X] != params[_N])


@jitable
def loading_coefficient(E, R, params):
    """``k1 = kn`` [N/m^n]: ``2 E* R*`` for ``n = 1``, else ``4/3 E* R*^(1/2)`` (the code's ``kn``)."""
    if params[_N] == 1.0:
        return 2.0 * E * R
    return 4.0 / 3.0 * E * math.sqrt(R)


@jitable
def damping_coefficient(E, R, m, params):
    """``gamman = (4 m* kn / (1 + (pi/ln e)^2))^(1/2)`` [N s/m], constant through the contact; 0 at ``e = 1``."""
    e = params[_E]
    if e == 1.0:
        return 0.0
    q = math.pi / math.log(e)
    return math.sqrt(4.0 * m * loading_coefficient(E, R, params) / (1.0 + q * q))


@jitable
def _branch_root(k2, kadh, n, x, dpn, dp):
    """``delta_s`` [m] in ``(0, delta_p]``: root of ``k2 a^n + k_adh a^x = k2 delta_p^n`` (bisection to the ulp)."""
    if kadh == 0.0:
        return dp
    if x == n:
        return dp * (k2 / (k2 + kadh)) ** (1.0 / n)
    lo = 0.0
    hi = dp
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if k2 * mid**n + kadh * mid**x - k2 * dpn < 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


@jitable
def unloading_state(alpha_max, E, R, params):
    """The unloading of a contact whose largest approach is ``alpha_max`` [m]:
    ``(k2, K, delta_p, k_adh, delta_s)`` with the unloading line ``k2 alpha^n - K`` (``K = k2 delta_p^n
    = (k2 - k1) alpha_max^n``), the plastic overlap ``delta_p`` [m], the adhesive coefficient ``k_adh``
    [N/m^x] of either option and the approach ``delta_s`` [m] where the adhesive branch takes over."""
    n = params[_N]
    x = params[_X]
    k1 = loading_coefficient(E, R, params)
    k2 = k1 * params[_RATIO]
    dpn = (1.0 - 1.0 / params[_RATIO]) * alpha_max**n  # delta_p^n
    dp = dpn ** (1.0 / n)
    K = k2 * dpn
    if dp == 0.0:  # k2 = k1: elastic, the unloading line is the loading curve and never meets a branch
        return k2, 0.0, 0.0, 0.0, 0.0
    if params[_FIXKC] == 1.0:
        kadh = params[_KC] * k1
    elif params[_PAIR] == 1.0 and params[_GAMMA] > 0.0 and dp > 0.0:
        r = 2.0 * R  # two equal spheres: radius 2 R* each
        a = math.sqrt(max(r * dp - 0.25 * dp * dp, 0.0))
        fmin = 1.5 * math.pi * params[_GAMMA] * a
        flim = 0.5 * K
        if fmin > flim:
            fmin = flim
            dmin = 0.5 * dp
        else:
            dmin = ((K - fmin) / k2) ** (1.0 / n)
        kadh = fmin / dmin**x
    else:  # a wall (a = 0) or no surface energy
        kadh = 0.0
    return k2, K, dp, kadh, _branch_root(k2, kadh, n, x, dpn, dp)


@jitable
def clips(params, kadh):
    """True where ``limitForce`` sets a negative force to zero: on, ``f_0 == 0`` and the code's outer
    ``k_adh`` zero (always with ``fixKc on``; with option 1 where ``k_adh`` is)."""
    if params[_LIMIT] != 1.0 or params[_F0] != 0.0:
        return False
    return params[_FIXKC] == 1.0 or kadh == 0.0


@jitable
def _spring(alpha, top, E, R, params):
    """``F_c`` [N] at ``alpha > 0`` with largest approach ``top``: loading, unloading or adhesive branch."""
    n = params[_N]
    k1 = loading_coefficient(E, R, params)
    if alpha >= top:
        return k1 * alpha**n
    k2, K, dp, kadh, ds = unloading_state(top, E, R, params)
    unl = k2 * alpha**n - K
    adh = -kadh * alpha ** params[_X]
    return unl if unl > adh else adh


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """``F_c + gamma alpha' + f_0`` [N] before ``limitForce``'s clipping (0 outside the contact)."""
    if alpha <= 0.0:
        return 0.0
    top = alpha_max if alpha_max > alpha else alpha
    fc = _spring(alpha, top, E, R, params)
    if fc == 0.0 and alpha < top and ends_at_zero_force(params):
        # the code's force is 0 on a branch of k_adh = 0; the unloading line's continuation (negative)
        # makes the end of the contact, where that force reaches 0, a crossing of zero
        k2, K, dp, kadh, ds = unloading_state(top, E, R, params)
        if kadh == 0.0:
            fc = k2 * alpha ** params[_N] - K
    return fc + damping_coefficient(E, R, m, params) * alpha_dot + params[_F0]


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N] as the code applies it: :func:`signed_force`, set to zero where it is negative
    and ``limitForce`` applies (:func:`clips`, with the ``k_adh`` of the current branch)."""
    f = signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)
    if f < 0.0 and alpha > 0.0:
        top = alpha_max if alpha_max > alpha else alpha
        kadh = 0.0 if alpha >= top else unloading_state(top, E, R, params)[3]
        if clips(params, kadh):
            return 0.0
    return f


@jitable
def ends_at_zero_force(params):
    """True where ``limitForce`` can clip the unloading (the contact then ends where the force vanishes)."""
    if params[_LIMIT] != 1.0 or params[_F0] != 0.0:
        return False
    return params[_FIXKC] == 1.0 or params[_GAMMA] == 0.0 or params[_PAIR] == 0.0


@jitable
def separation_approach(E, R, m, p_y, params):
    """Approach [m] at which the contact ends: 0 (the code has no force at a gap)."""
    return 0.0


# ----------------------------------------------------------------------------- the integration
_TOL = 1e-12
_MAX_STEPS = 400000


@jitable
def _rhs(a, v, phase, c):
    """``(acceleration, F_c, F unclipped, F applied)`` in ``phase`` (1 loading, 2 unloading line,
    3 adhesive branch); ``c`` the coefficients of :func:`_coefficients`."""
    k1, k2, K, kadh, n, x, gam, f0, m, clip = c
    if a > 0.0:
        if phase == 1:
            fc = k1 * a**n
        elif phase == 2:
            fc = k2 * a**n - K
        else:
            fc = -kadh * a**x
        f = fc + gam * v + f0
    else:
        fc = 0.0
        f = 0.0
    fa = 0.0 if (clip and f < 0.0) else f
    return -fa / m, fc, f, fa


@jitable
def _rk4(a, v, wc, wd, h, phase, c):
    """One classical Runge-Kutta step of ``(alpha, alpha', W_c, W_d)``: ``W_c = int F_c alpha' dt``,
    ``W_d = int (F - F_c - f_0) alpha' dt`` (damping and clipping)."""
    f0 = c[7]
    q1, fc1, _, fa1 = _rhs(a, v, phase, c)
    a2 = a + 0.5 * h * v
    v2 = v + 0.5 * h * q1
    q2, fc2, _, fa2 = _rhs(a2, v2, phase, c)
    a3 = a + 0.5 * h * v2
    v3 = v + 0.5 * h * q2
    q3, fc3, _, fa3 = _rhs(a3, v3, phase, c)
    a4 = a + h * v3
    v4 = v + h * q3
    q4, fc4, _, fa4 = _rhs(a4, v4, phase, c)
    an = a + h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4)
    vn = v + h / 6.0 * (q1 + 2.0 * q2 + 2.0 * q3 + q4)
    pc1, pc2, pc3, pc4 = fc1 * v, fc2 * v2, fc3 * v3, fc4 * v4
    pd1 = (fa1 - fc1 - f0) * v if a > 0.0 else 0.0
    pd2 = (fa2 - fc2 - f0) * v2 if a2 > 0.0 else 0.0
    pd3 = (fa3 - fc3 - f0) * v3 if a3 > 0.0 else 0.0
    pd4 = (fa4 - fc4 - f0) * v4 if a4 > 0.0 else 0.0
    wcn = wc + h / 6.0 * (pc1 + 2.0 * pc2 + 2.0 * pc3 + pc4)
    wdn = wd + h / 6.0 * (pd1 + 2.0 * pd2 + 2.0 * pd3 + pd4)
    return an, vn, wcn, wdn


@jitable
def _event(which, a, v, phase, c, ds):
    """Event functions, each crossing zero from above: 0 ``-alpha'`` (the top of loading),
    1 ``alpha - delta_s``, 2 ``alpha``, 3 the unclipped force (the clipping), 4 ``alpha'`` (turned back:
    captured), 5 ``dF/dt`` (the force's maximum in loading)."""
    if which == 0:
        return v
    if which == 1:
        return a - ds
    if which == 2:
        return a
    if which == 3:
        return _rhs(a, v, phase, c)[2]
    if which == 4:
        return -v
    k1, k2, K, kadh, n, x, gam, f0, m, clip = c
    acc = _rhs(a, v, phase, c)[0]
    slope = n * k1 * a ** (n - 1.0) * v if a > 0.0 else (k1 * v if n == 1.0 else 0.0)
    return slope + gam * acc


@jitable
def _locate(which, a, v, wc, wd, h, phase, c, ds):
    """Step length ``0 < s <= h`` at which event ``which`` crosses zero within the step from ``(a, v)``
    (Illinois' regula falsi on single Runge-Kutta steps of length ``s``, to ``1e-15 h``)."""
    lo = 0.0
    g_lo = _event(which, a, v, phase, c, ds)
    hi = h
    an, vn, _, _ = _rk4(a, v, wc, wd, h, phase, c)
    g_hi = _event(which, an, vn, phase, c, ds)
    side = 0
    for _ in range(100):
        s = (lo * g_hi - hi * g_lo) / (g_hi - g_lo) if g_hi != g_lo else 0.5 * (lo + hi)
        if not (s > lo and s < hi):
            s = 0.5 * (lo + hi)
        an, vn, _, _ = _rk4(a, v, wc, wd, s, phase, c)
        g = _event(which, an, vn, phase, c, ds)
        if g == 0.0:
            return s
        lo, hi, g_lo, g_hi, side = illinois(lo, hi, g_lo, g_hi, side, s, g)
        if hi - lo <= 1e-15 * h:
            break
    return hi


@jitable
def _coefficients(E, R, m, params, K, kadh, clip):
    k1 = loading_coefficient(E, R, params)
    return (
        k1,
        k1 * params[_RATIO],
        K,
        kadh,
        params[_N],
        params[_X],
        damping_coefficient(E, R, m, params),
        params[_F0],
        m,
        clip,
    )


@jitable
def integrate(V, E, R, m, params):
    """The impact at speed ``V > 0``, integrated through its phases (module docstring).

    Returns ``(e, alpha_max, delta_p, max_force, t_L, t_U, W_c, W_d, captured, alpha_end)``: the
    restitution, largest approach [m], plastic overlap [m], largest force [N], loading and unloading
    times [s] (``inf`` when captured), the works [J] of the spring and of damping and clipping over the
    contact, 1.0 where the particle is captured, and the approach [m] where the contact ends."""
    n = params[_N]
    k1 = loading_coefficient(E, R, params)
    gam = damping_coefficient(E, R, m, params)
    f0 = params[_F0]
    clip0 = params[_LIMIT] == 1.0 and f0 == 0.0  # loading: the outer k_adh is 0
    scale_a = ((n + 1.0) * m * V * V / (2.0 * k1)) ** (1.0 / (n + 1.0))
    T0 = scale_a / V
    if gam > 0.0:
        T0 = min(T0, m / gam)
    if f0 != 0.0:
        T0 = min(T0, m * V / abs(f0))
    if not (scale_a > 0.0 and T0 > 0.0 and T0 < math.inf):  # the scales under- or overflow (V near 0 or inf)
        n_ = math.nan
        return n_, n_, n_, n_, n_, n_, n_, n_, n_, n_
    h = 1e-4 * T0
    sa = scale_a
    sv = V
    a = 0.0
    v = V
    wc = 0.0
    wd = 0.0
    t = 0.0
    phase = 1
    c = _coefficients(E, R, m, params, 0.0, 0.0, clip0)
    ds = 0.0
    a_eq = -1.0
    pmax = gam * V + f0
    amax = 0.0
    dp = 0.0
    tL = 0.0
    g5 = _event(5, a + 1e-300, v, 1, c, 0.0)
    for _ in range(_MAX_STEPS):
        a1, v1, wc1, wd1 = _rk4(a, v, wc, wd, h, phase, c)
        ah, vh, wch, wdh = _rk4(a, v, wc, wd, 0.5 * h, phase, c)
        a2, v2, wc2, wd2 = _rk4(ah, vh, wch, wdh, 0.5 * h, phase, c)
        err = max(abs(a2 - a1) / sa, abs(v2 - v1) / sv) / 15.0
        if err > _TOL:
            h *= max(0.2, 0.9 * (_TOL / err) ** 0.2)
            continue
        # the ends of the phase inside this step (the earliest one)
        first = -1
        s_first = h
        for which in range(6):
            if phase == 1 and not (which == 0 or which == 5):
                continue
            if phase == 2 and not (which == 1 or which == 3 or which == 4):
                continue
            if phase == 3 and not (which == 2 or which == 3 or which == 4):
                continue
            if which == 3 and not c[9]:
                continue
            if which == 5:
                g_new = _event(5, a1, v1, phase, c, ds)
                if g5 > 0.0 and g_new <= 0.0:
                    s = _locate(5, a, v, wc, wd, h, phase, c, ds)
                    aa, vv, _, _ = _rk4(a, v, wc, wd, s, phase, c)
                    fa = _rhs(aa, vv, phase, c)[3]
                    if fa > pmax:
                        pmax = fa
                g5 = g_new
                continue
            if _event(which, a1, v1, phase, c, ds) <= 0.0:
                s = _locate(which, a, v, wc, wd, h, phase, c, ds)
                if first < 0 or s < s_first or (which == 3 and s == s_first):
                    first = which
                    s_first = s
        if first < 0:
            t += h
            # two half steps, extrapolated (Richardson: fifth order)
            a = a2 + (a2 - a1) / 15.0
            v = v2 + (v2 - v1) / 15.0
            wc = wc2 + (wc2 - wc1) / 15.0
            wd = wd2 + (wd2 - wd1) / 15.0
            if phase == 2 and a > a_eq > 0.0 and a - a_eq <= 1e-9 * amax and -v <= 1e-6 * V:
                return 0.0, amax, dp, pmax, tL, math.inf, wc, wd, 1.0, a
            grow = 5.0 if err == 0.0 else min(5.0, 0.9 * (_TOL / err) ** 0.2)
            h *= grow
            continue
        a, v, wc, wd = _rk4(a, v, wc, wd, s_first, phase, c)
        t += s_first
        if first == 0:  # top of loading
            amax = a
            tL = t
            fa = k1 * a**n + f0
            if fa > pmax:
                pmax = fa
            k2, K, dp, kadh, ds = unloading_state(amax, E, R, params)
            c = _coefficients(E, R, m, params, K, kadh, clips(params, kadh))
            # the equilibrium of the unloading line with f0: a damped particle creeping towards it
            # never reaches it (captured after an infinite time)
            a_eq = ((K - f0) / k2) ** (1.0 / n) if K > f0 else -1.0
            if a_eq <= ds:
                a_eq = -1.0
            v = 0.0
            phase = 2
            h = 1e-4 * T0
            if ds >= amax:  # (not reached: delta_s <= delta_p < alpha_max)
                phase = 3
            continue
        if first == 1:  # onto the adhesive branch
            a = ds
            phase = 3
            if c[9] and _rhs(a, v, 3, c)[2] <= 0.0:  # a branch of k_adh = 0, clipped: the force ends here
                return -v / V, amax, dp, pmax, tL, t - tL, wc, wd, 0.0, a
            h = 1e-4 * T0
            continue
        if first == 4:  # turned back before the contact ended: captured
            return 0.0, amax, dp, pmax, tL, math.inf, wc, wd, 1.0, a
        # 2: zero approach, 3: the force clipped to zero (the particle leaves at constant speed)
        e = -v / V
        return e, amax, dp, pmax, tL, t - tL, wc, wd, 0.0, (0.0 if first == 2 else a)
    n_ = math.nan
    return n_, n_, n_, n_, n_, n_, n_, n_, n_, n_


@jitable
def _attracts(params):
    """True where the law can hold a particle: an attractive ``f_0``, or an adhesive branch left unclipped."""
    if params[_F0] < 0.0:
        return True
    if params[_F0] > 0.0:
        return False
    if params[_FIXKC] == 1.0:
        return params[_KC] > 0.0 and params[_LIMIT] == 0.0
    return params[_GAMMA] > 0.0 and params[_PAIR] == 1.0


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (module docstring; ``p_y`` unused). ``e = 0`` and ``unloading_time = inf``
    for a captured particle."""
    if not _valid(params) or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    if V == 0.0:
        if _attracts(params):
            return dem_outcome(V, 0.0, 0.0, 0.0, 0.0, R, 0.0, math.inf)
        return dem_outcome(V, 1.0, 0.0, 0.0, 0.0, R, 0.0, 0.0)
    e, amax, dp, pmax, tL, tU, wc, wd, cap, aend = integrate(V, E, R, m, params)
    if e > 1.0:  # the integration's rounding (the law cannot create energy)
        e = 1.0
    return dem_outcome(V, e, amax, dp, pmax, R, tL, tU)


@jitable
def restitution_only(V, E, R, m, p_y, params):
    """``e`` [-] of :func:`outcome` alone (its field, bit for bit)."""
    return outcome(V, E, R, m, p_y, params)[4]


@jitable
def spring_work(alpha_max, alpha_end, E, R, params):
    """Work [J] the spring ``F_c`` takes over a pass: loading to ``alpha_max`` less what the unloading
    line and the adhesive branch return down to ``alpha_end`` (closed forms of the power laws)."""
    n = params[_N]
    x = params[_X]
    k1 = loading_coefficient(E, R, params)
    k2, K, dp, kadh, ds = unloading_state(alpha_max, E, R, params)
    w_in = k1 * alpha_max ** (n + 1.0) / (n + 1.0)
    lo = ds if ds > alpha_end else alpha_end
    w_unl = k2 * (alpha_max ** (n + 1.0) - lo ** (n + 1.0)) / (n + 1.0) - K * (alpha_max - lo)
    w_adh = 0.0
    if alpha_end < ds:
        w_adh = -kadh * (ds ** (x + 1.0) - alpha_end ** (x + 1.0)) / (x + 1.0)
    return w_in - w_unl - w_adh


@jitable
def energy_budget(V, E, R, m, p_y, params):
    """``(incident, spring, damping, f0, rebound)`` energies [J] of one impact that separates:
    ``1/2 m* V^2``; the spring's loop :func:`spring_work`; the damping's and clipping's work (integrated);
    the pull-off's ``f_0 alpha_end`` (0 where the contact ends at zero approach); ``1/2 m* (e V)^2``.
    The first is the sum of the others. NaN for a captured particle."""
    e, amax, dp, pmax, tL, tU, wc, wd, cap, aend = integrate(V, E, R, m, params)
    n_ = math.nan
    if cap == 1.0 or not e == e:
        return n_, n_, n_, n_, n_
    inc = 0.5 * m * V * V
    eV = e * V
    return inc, spring_work(amax, aend, E, R, params), wd, -params[_F0] * aend, 0.5 * m * (eV * eV)


@jitable
def outside_validity(V, E, R, m, p_y, params):
    """1.0 where the integrated impact would return more energy than it brought (never, for this law:
    a check of the integration), else 0.0."""
    if not _valid(params) or not (V > 0.0 and V < math.inf):
        return 0.0
    e = integrate(V, E, R, m, params)[0]
    return 1.0 if e > 1.0 + 1e-9 else 0.0


def sticking_velocity(E, R, m, p_y, params):
    """Capture velocity ``V_s`` [m/s]: the largest speed at which the particle is captured (``e = 0``),
    by bisection of the integration's verdict to ``1e-12`` relative; 0 for a law without attraction."""
    if not _attracts(params):
        return 0.0

    def captured(V):
        return integrate(V, E, R, m, params)[8] == 1.0

    # a speed scale: the kinetic energy that the pull-off or the adhesive branch can take
    V = 1e-3
    if captured(V):
        while captured(V):
            V *= 2.0
            if V > 1e12:
                return math.inf
        lo, hi = 0.5 * V, V
    else:
        while not captured(V):
            V *= 0.5
            if V < 1e-15:
                return 0.0
        lo, hi = V, 2.0 * V
    while hi - lo > 1e-12 * hi:
        mid = 0.5 * (lo + hi)
        if captured(mid):
            lo = mid
        else:
            hi = mid
    return lo
