r"""What LIGGGHTS-PUBLIC 3.8's ``thornton_ning`` normal model computes for a non-adhesive impact.

Source read: ``src/normal_model_thornton_ning.h`` of CFDEMproject/LIGGGHTS-PUBLIC at commit
``84ba3d76`` (line numbers ``L...`` below are that file's), class ``NormalModel<THORNTON_NING>``,
method ``surfacesIntersect`` (L207-L407), with its helpers ``calculate_fl`` (L119),
``calculate_elastic_force_differential`` (L134), ``calculate_plastic_force_differential``
(L150), ``calculate_a`` (L166) and ``branch_2_force_calc`` (L188). The statements below are
quoted from it. The binary that runs it here, Debian's ``liggghts 3.8.0+repack1-9+b2``
("LIGGGHTS-PUBLIC 3.8.0"), reproduces the law derived below to 5e-5 in ``e`` and contact time
(``benchmarks/data/dem_runs.csv``). ``gamma_s`` (``surfaceEnergy``) is zero throughout, so the
pull-off force ``fc = gamma_s * reff * M_PI * (3./2.)`` (L240) is zero.

The force law, as the code runs it
----------------------------------
The model keeps the force in the contact history and changes it by increments, one per time
step, with ``dn = delta - delta_old`` (``delta`` is the overlap, our approach ``alpha``):

* Yield. ``a_yield = ri * yield_ratio[itype]`` (L243: the contact radius at first yield, given
  as a fraction ``coefficientYieldRatio`` of the radius of particle ``i``) and ``yield_stress =
  ((2.*Eeff*a_yield)/(M_PI*reff)) - sqrt(2.*gamma_s*Eeff/(M_PI*a_yield))`` (L244), i.e. ``p_y = 2 E* a_y /
  (pi R*)`` at ``gamma_s = 0``: the seed's yield point (seed eqs. 4-5). A user who wants the seed's
  ``p_y`` gives ``coefficientYieldRatio = pi p_y R* / (2 E* r_i)`` (``pi p_y/(2 E*)`` on a wall,
  where ``reff = ri``, L213). ``Eeff = Yeff[itype][jtype]`` (L219) is ``E*``.
* Loading (``if (delta >= delta_max)``, L296-L317): ``a = calculate_a(...) = sqrt(R * delta)``
  (L301, L172); the flag ``yielding_flag`` is set once ``a >= a_yield`` (L302). Before yield,
  ``branch_2_force_calc`` (L313) adds ``df = 2*E*a * dn`` (L198, L144:
  ``calculate_elastic_force_differential`` with ``fc == 0``); after it, ``df =
  calculate_plastic_force_differential(...) * dn = 2*E*a_yield * dn`` (L307, L160). Summed over steps
  (``dn -> 0``) these are ``dP/dalpha = 2 E* (R* alpha)^(1/2)``, i.e. Hertz ``P = 4/3 E*
  R*^(1/2) alpha^(3/2)`` (seed eq. 2), and ``dP/dalpha = 2 E* a_y = pi p_y R*`` from the yield
  point on: the seed's plastic loading, eq. 8. **Loading is the seed's.**
* Unloading after yield (``else`` branch, ``yielding_flag == 1``, L327-L340): ``fl_max =
  calculate_fl(force_max, fc, 0) = force_max`` (L331, L128) and ``reff = reff * fl_max /
  (force_max + sqrt(4*fc*fl_max))`` (L332), which is ``reff`` itself when ``fc = 0``; then
  ``branch_2_force_calc`` (L336) with that ``reff`` adds ``df = 2*E*a * dn`` with ``a = sqrt(reff * delta)``, the *total* overlap. So
  ``dP/dalpha = 2 E* (R* alpha)^(1/2)`` again, from ``(alpha*, P*)`` down:

  .. math:: P(\alpha) = P^* - \tfrac43 E^* R^{*1/2} (\alpha^{*3/2} - \alpha^{3/2}).

  Unloading before yield takes the same increment with the original ``reff`` (L319-L326):
  elastic impacts are Hertz both ways, as in the seed.
* End of contact: ``if (gamma_s == 0 && f < 0) { f = 0; detaching_flag = 1; ...}`` (L343-L349):
  the force is
  set to zero and the contact is released where ``P`` reaches zero, at the plastic approach

  .. math:: \alpha_p = \left(\alpha^{*3/2} - P^* / (\tfrac43 E^* R^{*1/2})\right)^{2/3}
            = \alpha^* (1 - P^*/F_e)^{2/3},\qquad F_e = \tfrac43 E^* R^{*1/2}\alpha^{*3/2}.

* No normal damping: ``sidata.Fn = f`` (L370) is the normal force; ``gammat`` (from
  ``coefficientRestitution``, L264) goes only to the tangential model (``sidata.gammat``, L373),
  which a normal impact does not load. ``force_max`` is the largest force so far (``force_max =
  (f > force_max) ? f : force_max``, L377), i.e. ``P*``.

Where it differs from the seed
------------------------------
The seed (Thornton & Ning 1998 as written in seed eqs. 9-11) unloads along a Hertz curve of a
*larger* radius ``R_p = R* F_e/P*`` shifted by ``alpha_p = alpha*(1 - P*/F_e)``:
``P = 4/3 E* R_p^(1/2) (alpha - alpha_p)^(3/2)``. Both curves start from ``(alpha*, P*)`` with the
same stiffness ``2 E* a*`` (``a* = (R* alpha*)^(1/2)``), but the seed's stiffness
``2 E* (R_p (alpha - alpha_p))^(1/2)`` falls to zero at separation while LIGGGHTS's
``2 E* (R* alpha)^(1/2)`` stays above ``2 E* (R* alpha_p)^(1/2)``. With ``fc = 0`` the code's
"modified R" is the original ``R*`` and its contact radius uses the total, not the elastic,
approach. Hence LIGGGHTS's plastic approach ``alpha*(1-P*/F_e)^(2/3)`` is larger than the seed's
``alpha*(1-P*/F_e)``, less elastic energy is returned and ``e`` is lower: at high speed
``e -> 1.082 (V_y/V)^(1/4)`` against the seed's ``1.185 (V_y/V)^(1/4)`` (9 % lower; see below).
Two smaller differences: the code's yield point is a fraction of the radius of particle ``i``
(L243), not a pressure, so between two particles of different radii or types it is the seed's
only when ``coefficientYieldRatio`` is set per type as above; and the code integrates its
incremental law with the time step (first order: halving the step changes ``e`` by about 2e-5 at
``t_c/dt = 20000`` in the stored runs).

Closed form of ``e`` (derived here from the law above)
------------------------------------------------------
Scale approaches by ``alpha_y`` and forces by ``P_y`` (``^``), ``v = V/V_y``. Loading is the
seed's, so ``A = alpha^* = (1 + s)/3``, ``P^* = s/2``, ``s = ((24 v^2 - 4)/5)^(1/2)`` (seed
eq. 22). The unloading law is ``P^ = x^(3/2) - x_p^(3/2)`` with ``x_p^(3/2) = D = A^(3/2) - P^*``
(``D >= 0`` since ``A^(3/2) >= (3A - 1)/2``). The work the contact returns is

.. math:: \hat W = \int_{x_p}^{A} (x^{3/2} - x_p^{3/2})\,dx
                 = \tfrac25 A^{5/2} - D A + \tfrac35 D^{5/3},

and the incident energy is ``1/2 m* V^2 = v^2 (2/5) P_y alpha_y`` (seed eq. 28), so

.. math:: e^2 = \hat W / (\tfrac25 v^2).

Checks: ``D = 0`` (no yield, ``A^(5/2) = v^2``) gives ``e = 1``; for ``v -> inf``, with
``eps = P^*/A^(3/2) -> (3/2) A^(-1/2)``, ``W^ = A^(5/2) eps^2/3 + O(A) = (3/4) A^(3/2)`` and
``A -> (24/5)^(1/2) v/3``, so ``e -> (15/8 (8/15)^(3/4))^(1/2) v^(-1/4) = 1.0818 v^(-1/4)``.

Contact time
------------
Loading is the seed's, so ``t1`` (Hertz stage, an incomplete beta function) and ``t2`` (the
harmonic plastic stage) are the seed's closed forms. Unloading obeys ``m* alpha'' = -P(alpha)``
from rest at ``alpha*`` to ``alpha_p``; with ``k = 4/3 E* R*^(1/2)``, ``s = alpha/alpha*``,
``beta = alpha_p/alpha*``, energy conservation gives

.. math:: t_U = \left(\frac{m^*}{2 k \alpha^{*1/2}}\right)^{1/2}\int_\beta^1
          \frac{ds}{\sqrt{g(s)}},\qquad g(s) = \tfrac25 (1 - s^{5/2}) - \beta^{3/2}(1 - s),

which has no elementary antiderivative. The substitution ``s = 1 - (1 - beta) u^2`` removes the
square-root end point at ``s = 1`` (``g ~ (1 - beta^(3/2))(1 - s)`` there), leaving the smooth
integrand ``2 (1-beta)^(1/2) / G(u)^(1/2)`` on ``[0, 1]``, which is integrated by tanh-sinh
quadrature to ``1e-15`` relative (the "exact quadrature" of this model). For ``beta -> 0`` it
tends to the Hertz unloading time ``(2/5) B(2/5, 1/2) alpha*/V_r`` of the seed.

Fields and validity
-------------------
Every field of :data:`~microimpact.core.quantities.OUTCOME_FIELDS` is defined. ``unloading_radius``
is ``R*`` (the code's ``reff`` is unchanged at ``fc = 0``). The contact model assumes what the
seed assumes (small strain, no adhesion, rate effects or waves); ``large_strain`` flags
``a*/R* > 0.3``. The DEM code itself integrates the incremental law with a finite step: its
``e`` and contact time converge to these values as the step goes to zero (first order in the
step; see ``benchmarks/dem_runs.py`` and the stored runs in ``benchmarks/data/dem_runs.csv``).
The functions here take plain floats and do not check them; the callers validate.
"""

from __future__ import annotations

import math
from fractions import Fraction

from .. import hertz
from .._jit import jitable
from ..special import binomial_series
from . import checks, deprecated_names
from . import thornton_ning_2016 as seed
from ._common import pack

NAME = "liggghts_thornton_ning"
TITLE = (
    "LIGGGHTS-PUBLIC 3.8 thornton_ning without adhesion: the seed's loading, incremental Hertz unloading of radius R*"
)
CITATION = "LIGGGHTS-PUBLIC 3.8, src/normal_model_thornton_ning.h (CFDEMproject, commit 84ba3d76)"
LABEL = "LIGGGHTS thornton_ning"
PARAMETERS = ()
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(__name__, NAME)  # released DEFAULTS: one release, with a warning
#: Cost class of the outcome (the contract's ``OUTCOME_COST``): its contact times' quadrature, 0.25 ms a
#: point in Python (``e`` alone: 3 us).
OUTCOME_COST = "slow"
#: Its loading is the seed's, so its history has the seed's stages.
STAGES = seed.STAGES
#: Its loading is the seed's: Hertz up to the yield approach, then plastic (the seed's stage 2).
stage_two_approach = seed.stage_two_approach


@jitable
def _hertz_remainder(x):
    """``r(x) = 1 - (2/5)(1 - (1 - x)^(5/2))/x`` for ``0 <= x <= 1``, without cancellation.

    Below ``x = 0.1`` the binomial series ``r = (2/5) sum_{k>=2} C(5/2, k) (-1)^k x^(k-1)``
    (``= 3/4 x - 1/8 x^2 - ...``); above it, ``expm1``/``log1p``.
    """
    if x >= 1.0:
        return 0.6
    if x >= 0.1:
        return 1.0 - 0.4 * (-math.expm1(2.5 * math.log1p(-x))) / x
    coef = 1.875  # C(5/2, 2)
    term = coef * x
    total = term
    k = 2
    while abs(term) > 1e-17 * abs(total) and k < 60:
        coef *= (k - 2.5) / (k + 1.0)
        k += 1
        term = coef * x ** (k - 1)
        total += term
    return 0.4 * total


@jitable
def _unloading_integrand(u, c, h):
    """``1/G(u)^(1/2)`` with ``G(u) = c - r(h u^2)`` (see the module docstring)."""
    return 1.0 / math.sqrt(c - _hertz_remainder(h * u * u))


@jitable
def unloading_integral(c, h):
    """``J = int_beta^1 ds / g(s)^(1/2)`` of the unloading time, by tanh-sinh quadrature.

    Parameters
    ----------
    c : float
        ``1 - beta^(3/2) = P^*/A^(3/2)`` [-], in ``(0, 1]``.
    h : float
        ``1 - beta`` [-], in ``(0, 1]`` (``beta = alpha_p/alpha*``).

    Returns
    -------
    float
        ``J = 2 h^(1/2) int_0^1 G(u)^(-1/2) du`` [-]: the nodes
        ``u = 1/(1 + exp(-pi sinh t))`` with ``t`` on a grid of step ``2^-level`` in
        ``[-3.5, 3.5]``, halved until two levels agree to 1e-15 relative.
    """
    tmax = 3.5
    half_pi = 0.5 * math.pi
    prev = 0.0
    total = 0.0
    step = 1.0
    for level in range(12):
        # new nodes of this level: all multiples of step at level 0, the odd ones after
        n = int(tmax / step)
        s = 0.0
        j = -n
        while j <= n:
            if level == 0 or j % 2 != 0:
                t = j * step
                e = math.exp(math.pi * math.sinh(t))
                u = e / (1.0 + e) if t < 0.0 else 1.0 / (1.0 + 1.0 / e)
                w = 2.0 * half_pi * math.cosh(t) * e / ((1.0 + e) * (1.0 + e))
                s += w * _unloading_integrand(u, c, h)
            j += 1
        total += s
        value = total * step
        if level >= 3 and abs(value - prev) <= 1e-15 * abs(value):
            break
        prev = value
        step *= 0.5
    return 2.0 * math.sqrt(h) * value


#: Below this ``c = P*/(P_y A^(3/2))`` (``V/V_y`` above about 3e4) :func:`plastic_rebound` sums the
#: series of the returned work instead of its closed form, whose terms cancel there.
SERIES_BELOW = 1e-2
#: ``0.6 binom(5/3, k) (-1)^k`` for ``k = 2 ... 11``: the series of ``0.6 (1 - c)^(5/3)`` beyond ``0.6 - c``
#: (``1/3, 1/27, 1/81, 7/1215, ...``, exact rationals rounded once).
_SERIES = binomial_series(Fraction(5, 3), 2, 12, Fraction(3, 5))


@jitable
def plastic_rebound(v):
    """The plastic impact at ``v = V/V_y > 1`` (finite): ``(A, P^*/P_y, A^(3/2), D, e)`` with
    ``A = alpha^*/alpha_y`` (seed eq. 22), ``D = x_p^(3/2) = A^(3/2) - P^*/P_y`` and the
    restitution ``e`` from the work the LIGGGHTS unloading curve returns (module docstring)."""
    A, Phat = seed.plastic_stage(v, v - 1.0)[:2]  # alpha*/alpha_y (seed eq. 22), P*/P_y
    A15 = A * math.sqrt(A)
    D = max(A15 - Phat, 0.0)  # x_p^(3/2)
    c = Phat / A15
    if c < SERIES_BELOW:
        # W = A^(5/2) g(c), g(c) = 0.4 - (1 - c) + 0.6 (1 - c)^(5/3): the three terms of the form
        # below cancel to c^2/3 (e was 1.35 at V = 1e30 m/s on the silicon pair, and the power
        # overflowed at 1e200 m/s); here g by the binomial series of 0.6 (1 - c)^(5/3) from c^2 to
        # c^11 (the next term is 1e-23 of the sum at c = 1e-2)
        g = 0.0
        for k in range(len(_SERIES) - 1, -1, -1):
            g = g * c + _SERIES[k]
        g *= c * c
        e = math.sqrt(g / 0.4) * (A / v) * math.sqrt(math.sqrt(A))
    else:
        W = 0.4 * A * A15 - D * A + 0.6 * D ** (5.0 / 3.0)  # returned work / (P_y alpha_y)
        e = math.sqrt(max(W, 0.0) / 0.4) / v
    return A, Phat, A15, D, e


@jitable
def restitution_only(V, E, R, m, p_y, params):
    """Restitution ``e`` [-] alone of :func:`outcome` (its field ``restitution``, bit for bit),
    without the contact times' quadrature: what fitting compares (the contract's hook).
    Arguments as :func:`outcome`."""
    Vy = seed.yield_point(E, R, m, p_y)[2]
    v = seed.normalized_velocity(V, Vy)
    if v <= 1.0:
        return 1.0
    if v == math.inf:
        return 0.0
    return plastic_rebound(v)[4]


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact under the LIGGGHTS ``thornton_ning`` law (see the module docstring).

    Parameters
    ----------
    V : float
        Impact speed [m/s], >= 0 (``inf`` allowed).
    E, R, m : float
        ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], positive and finite.
    p_y : float
        Limiting pressure [Pa] (``inf``: elastic); LIGGGHTS's ``coefficientYieldRatio`` is
        ``pi p_y R* / (2 E* r_i)``.
    params : tuple
        Empty: the model has no parameters of its own.

    Returns
    -------
    tuple of float
        In the order of :data:`microimpact.core.quantities.OUTCOME_FIELDS`; every field defined.
    """
    inf = math.inf
    k = 4.0 / 3.0 * E * math.sqrt(R)
    # Loading is the seed's: yield point (eqs. 4, 5, 7, 28), Hertz below it, plastic above.
    a_y, P_y, Vy = seed.yield_point(E, R, m, p_y)
    v = seed.normalized_velocity(V, Vy)
    elastic = v <= 1.0
    infinite = v == inf

    if elastic:
        max_approach = hertz.max_approach(V, E, R, m)
        max_force = hertz.force(max_approach, E, R)
        e = 1.0
        plastic = 0.0
    elif infinite:
        e = 0.0
        max_approach = max_force = plastic = inf
    else:
        A, Phat, A15, D, e = plastic_rebound(v)
        max_approach = a_y * A
        max_force = P_y * Phat
        plastic = a_y * D ** (2.0 / 3.0)
    rebound = inf if infinite else e * V
    a_max = math.sqrt(R * max_approach)

    # Loading times: the seed's (eqs. 20, 23).
    t1 = seed.elastic_stage_time(V, E, R, m, a_y, Vy)
    t2 = seed.plastic_stage_time(V, R, m, p_y, a_y, Vy)
    # Unloading time: Hertz for an elastic impact, else the quadrature above.
    if V == inf or infinite:  # (V/V_y can overflow at a finite V: e = 0, nothing to unload)
        tU = 0.0
    elif elastic:
        tU = hertz.half_period(V, E, R, m)
    else:
        c = Phat / A15  # 1 - beta^(3/2)
        if c > 0.0:
            h = -math.expm1((2.0 / 3.0) * math.log1p(-c)) if c < 1.0 else 1.0  # 1 - beta
            tU = math.sqrt(m / (2.0 * k * math.sqrt(max_approach))) * unloading_integral(c, h)
        else:  # A^(3/2) overflowed (V/V_y near 1e300): tU ~ alpha*^(-1/4), 0 to rounding
            tU = 0.0
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
        R,
        a_max,
        R,
        t1,
        t2,
        t1 + t2,
        tU,
    )


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N] of the LIGGGHTS ``thornton_ning`` law at ``fc = 0``, in the limit of small steps.

    Loading (``alpha >= alpha_max``): Hertz ``4/3 E* R*^(1/2) alpha^(3/2)`` up to ``alpha_y``, then
    ``P_y + pi p_y R* (alpha - alpha_y)``. Unloading from ``alpha_max``:
    ``P(alpha_max) - 4/3 E* R*^(1/2) (alpha_max^(3/2) - alpha^(3/2))``, never below zero (the code
    sets ``f = 0`` and detaches). ``alpha_dot`` and ``m`` are not used: the law is rate-free.

    Parameters
    ----------
    alpha, alpha_dot, alpha_max : float
        Approach [m], its rate [m/s] and the largest approach so far [m].
    E, R, m, p_y : float
        ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], ``p_y`` [Pa].
    params : tuple
        Empty.

    Returns
    -------
    float
        Force [N], >= 0.
    """
    if alpha <= 0.0:
        return 0.0
    top = alpha_max if alpha_max > alpha else alpha
    f_top = seed.loading_force(top, E, R, p_y)  # the seed's loading (eqs. 2, 6, 8)
    if top == alpha:
        return f_top
    # P* - k (alpha*^(3/2) - alpha^(3/2)), written as k alpha^(3/2) - (F_e - P*) with F_e - P* >= 0
    f = hertz.force(alpha, E, R) - (hertz.force(top, E, R) - f_top)
    return f if f > 0.0 else 0.0


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """The force law before the code's clipping at zero is irrelevant here: :func:`force` (never negative)."""
    return force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


@jitable
def ends_at_zero_force(params):
    """True: LIGGGHTS detaches the particle where the unloading force reaches zero."""
    return True
