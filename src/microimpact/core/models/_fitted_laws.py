"""The published FE-fitted elastic-plastic laws and their impact (private: not a model).

The loading laws of Jackson & Green (as Ghaednia, Brake, Berryhill & Jackson 2019 print them) and
of Kogut & Etsion (2002), the unloading laws of Brake (2015) and of Etsion, Kligerman & Kadin
(2005) as the public codes cited beside each function write them, and the one impact computation
both model files share: the maximum approach from the energy balance, the loading time by
quadrature of the law's own force, the unloading along its Hertzian curve in closed form. The model
files :mod:`~microimpact.core.models.jackson_green_brake` and
:mod:`~microimpact.core.models.kogut_etsion_ekk` state the laws, their sources, conventions and
validity; the functions here carry the equation numbers.

Frames. Both laws were fitted for a deformable sphere pressed by a flat. The pair's ``E*``, ``R*``
(a sphere on an elastic flat, ``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2``, Ghaednia et al. eq. 3 and
Kogut & Etsion eq. 1) are used as they are (``twin = 0``). With ``twin = 1`` the pair is two
identical spheres and, as tmdsimpy does (``tmd-lab/tmdsimpy``,
``tmdsimpy/jax/nlforces/roughcontact/_asperity_functions.py``), each sphere is pressed against the
plane of symmetry: the law is evaluated at modulus ``2 E*``, radius ``2 R*`` and interference
``alpha/2`` (:func:`frame`, the one conversion). Hertz's force, the critical interference and
force, Kogut & Etsion's fits and both unloading laws are the same in the two frames; only
Jackson & Green's exponent ``B`` (``S_y/E``) and hardness (``a/R``) differ.

Quadrature: composite Gauss-Legendre (24 points a panel) in ``ln alpha``, where every force here
is smooth; the loading time near the maximum approach in ``s = (alpha* - alpha)^(1/2)``, which
removes the turning point's inverse square root. A quadrature computes what the law needs besides
the approach once (:func:`law_constants`) and evaluates the force at its nodes from it, by the same
operations as :func:`loading_force`.
"""

from __future__ import annotations

import math

from .. import hertz
from .._jit import jitable
from ..constants import TINY_NORMAL
from ..gauss_legendre import RULES
from ..special import BETA_25_12
from ._common import nan_outcome, pack, pack_beyond
from .thornton_ning_2016 import elastic_stage_time

JACKSON_GREEN = 0
KOGUT_ETSION = 1
#: Jackson & Green's law with the 2005 paper's own hardness fit (:func:`jg_hardness_ratio_2005`) in
#: place of eq. 28's cosine form; everything else as :data:`JACKSON_GREEN`.
JACKSON_GREEN_2005 = 2

#: 24-point Gauss-Legendre nodes and weights on ``[-1, 1]`` (numpy's ``leggauss``, kept as literals).
GX, GW = RULES[24]
#: 6-point Gauss-Legendre nodes and weights, for the short steps between the nodes of a panel.
GX6, GW6 = RULES[6]
#: Widest panel in ``ln alpha`` of the composite rules.
PANEL = 0.5
#: Relative Newton step of :func:`max_approach` after which the iterate is exact to rounding: the
#: next step would be about ``STEP_DONE^2``.
STEP_DONE = 1e-12

#: Jackson & Green's switch from Hertz to the elastic-plastic law, ``delta/delta_c`` (Ghaednia et al.
#: 2019 Sec. 3.2: Hertz while ``Delta <= 1.9 delta_c``).
JG_SWITCH = 1.9
#: Kogut & Etsion's regime limits ``omega/omega_c`` (eqs. 7, 8 and the fully plastic regime).
KE_LIMITS = (1.0, 6.0, 110.0)


# ----------------------------------------------------------------------------------- conventions


@jitable
def frame(E, R, twin):
    """``(E_l, R_l, s)``: the law's modulus [Pa], radius [m] and interference per approach (``delta = s alpha``).

    ``twin = 0``: a sphere on an elastic flat, the pair's own ``E*``, ``R*`` (``s = 1``); ``twin =
    1``: two identical spheres, each against the plane of symmetry, ``(2 E*, 2 R*, 1/2)``.
    """
    if twin == 1.0:
        return 2.0 * E, 2.0 * R, 0.5
    return E, R, 1.0


# ----------------------------------------------------------------------------- Jackson & Green


@jitable
def is_jackson_green(law):
    """True for either hardness form of Jackson & Green's law."""
    return law != KOGUT_ETSION


@jitable
def jg_coefficient(nu):
    """``C = 1.295 exp(0.736 nu)`` [-] (Ghaednia et al. 2019 eq. 6; Jackson & Green 2005)."""
    return 1.295 * math.exp(0.736 * nu)


@jitable
def jg_critical_interference(E, R, Y, nu):
    """Critical interference ``delta_c = (pi C S_y/(2 E))^2 R`` [m] (Ghaednia et al. 2019 eq. 5)."""
    k = math.pi * jg_coefficient(nu) * Y / (2.0 * E)
    return k * k * R


@jitable
def jg_critical_force(E, R, Y, nu):
    """Critical force ``F_c = 4/3 (R/E)^2 (C pi S_y/2)^3`` [N] (Ghaednia et al. 2019 eq. 29), Hertz's at ``delta_c``."""
    q = jg_coefficient(nu) * math.pi * Y / 2.0
    return 4.0 / 3.0 * (R / E) * (R / E) * q * q * q


@jitable
def jg_exponent(E, Y):
    """``B = 0.14 exp(23 S_y/E)`` [-] (Ghaednia et al. 2019 eq. 24; the exponent's argument capped at 700)."""
    return 0.14 * math.exp(min(23.0 * Y / E, 700.0))


@jitable
def jg_constants(E, R, Y, nu, form):
    """What Jackson & Green's law needs besides ``x``, computed once for many forces:
    ``(delta_c, C, F_c, B, a_0, R, form)`` [m, -, N, -, m, m, -], ``a_0 = R pi C S_y/(2E)`` (eqs. 5,
    6, 29, 24, 23); ``form`` the hardness: 0 eq. 28 (:func:`jg_hardness_ratio`), 1 the 2005 fit
    (:func:`jg_hardness_ratio_2005`)."""
    C = jg_coefficient(nu)
    return (
        jg_critical_interference(E, R, Y, nu),
        C,
        jg_critical_force(E, R, Y, nu),
        jg_exponent(E, Y),
        R * (math.pi * C * Y / (2.0 * E)),
        R,
        form,
    )


@jitable
def _jg_radius(x, k):
    """Eq. 23's radius [m] at ``x`` with the constants ``k`` of :func:`jg_constants` (``(x/1.9)^B`` as
    ``exp(B ln(x/1.9))``, the logarithm the overflow test needs anyway)."""
    lr = math.log(x / JG_SWITCH)
    if lr > 0.0 and k[3] * lr + math.log(x) > 700.0:
        return math.nan
    return k[4] * math.sqrt(x * math.exp(k[3] * lr))


@jitable
def jg_contact_radius(x, E, R, Y, nu):
    """Elastic-plastic contact radius ``a = R (pi C S_y/(2E)) (x (x/1.9)^B)^(1/2)`` [m] at ``x = delta/delta_c``.

    Ghaednia et al. 2019 eq. 23 (Jackson & Green's radius), ``B = 0.14 exp(23 S_y/E)`` (eq. 24);
    eq. 25 gives ``a = a_p`` without strain hardening (``E_t = 0``: ``Upsilon = 0``, eq. 26).

    Far below the law's range of ``E/S_y`` (``E*/S_y`` about 2) ``B`` is in the thousands and
    ``x (x/1.9)^B`` leaves the float range: the radius is then NaN on every path (Python's ``**``
    raised OverflowError where the compiled loop gave NaN), and so is the impact's outcome.
    """
    return _jg_radius(x, jg_constants(E, R, Y, nu, 0.0))


@jitable
def jg_hardness_ratio(a, R):
    """``H_G/S_y = 2.84 - 0.92 (1 - cos(pi a/R))`` [-] (Ghaednia et al. 2019 eq. 28; Jackson & Green 2006)."""
    return 2.84 - 0.92 * (1.0 - math.cos(math.pi * a / R))


@jitable
def jg_hardness_ratio_2005(a, R):
    """``H_G/S_y = 2.84 [1 - exp(-0.82 (a/R)^(-0.7))]`` [-] (Jackson & Green 2005's own fit, as the
    project's source list quotes it; see the model file). 2.84 at ``a = 0`` (the limit), falling
    monotonically with ``a/R``."""
    if not a > 0.0:
        return 2.84
    return 2.84 * (1.0 - math.exp(-0.82 * (a / R) ** -0.7))


@jitable
def _jg_force(x, k):
    """Eq. 27's force [N] at ``x`` with the constants ``k`` of :func:`jg_constants` (``x^p`` as
    ``exp(p ln x)``: one logarithm for both powers)."""
    if k[6] == 0.0:
        H = jg_hardness_ratio(_jg_radius(x, k), k[5])
    else:
        H = jg_hardness_ratio_2005(_jg_radius(x, k), k[5])
    lx = math.log(x)
    elastic = math.exp(-0.25 * math.exp(5.0 / 12.0 * lx)) * x * math.sqrt(x)
    plastic = 4.0 * H / k[1] * (1.0 - math.exp(-math.exp(5.0 / 9.0 * lx) / 25.0)) * x
    return k[2] * (elastic + plastic)


@jitable
def jg_plastic_force(x, E, R, Y, nu):
    """Jackson & Green's elastic-plastic force [N] at ``x = delta/delta_c`` (Ghaednia et al. 2019 eq. 27):

    ``F/F_c = exp(-x^(5/12)/4) x^(3/2) + 4 (H_G/S_y)/C (1 - exp(-x^(5/9)/25)) x``, with the hardness
    of eq. 28 at the contact radius of eq. 23 (eq. 30 with ``E_t = 0`` is this force).
    """
    return _jg_force(x, jg_constants(E, R, Y, nu, 0.0))


@jitable
def _jg_loading(delta, E, R, k):
    """:func:`jg_loading_force` with the constants ``k`` of :func:`jg_constants`."""
    if delta <= JG_SWITCH * k[0]:
        return hertz.force(delta, E, R)
    return _jg_force(delta / k[0], k)


@jitable
def jg_loading_force(delta, E, R, Y, nu):
    """Loading force [N]: Hertz up to ``1.9 delta_c`` (Ghaednia et al. 2019 eq. 1 and Sec. 3.2), eq. 27 beyond."""
    return _jg_loading(delta, E, R, jg_constants(E, R, Y, nu, 0.0))


# ------------------------------------------------------------------------------ Kogut & Etsion


@jitable
def ke_hardness_coefficient(nu):
    """``K = 0.454 + 0.41 nu`` [-] (Kogut & Etsion 2002 eq. 1, after Chang, Etsion & Bogy 1988)."""
    return 0.454 + 0.41 * nu


@jitable
def ke_critical_interference(E, R, Y, nu):
    """``omega_c = (pi K H/(2E))^2 R`` [m], ``H = 2.8 Y`` (Kogut & Etsion 2002 eq. 1)."""
    k = math.pi * ke_hardness_coefficient(nu) * 2.8 * Y / (2.0 * E)
    return k * k * R


@jitable
def ke_loading_force(w, E, R, Y, nu):
    """Loading force [N] at interference ``w`` (Kogut & Etsion 2002), ``x = w/omega_c``, ``P_c`` Hertz's at ``omega_c``:

    ``x <= 1``: ``P_c x^(3/2)`` (Hertz, eq. 2); ``1 < x <= 6``: ``1.03 P_c x^1.425`` (eq. 7);
    ``6 < x <= 110``: ``1.40 P_c x^1.263`` (eq. 8); ``x > 110``: fully plastic ``2 pi R w H``,
    ``H = 2.8 Y``.
    """
    wc = ke_critical_interference(E, R, Y, nu)
    x = w / wc
    if x <= KE_LIMITS[0]:
        return hertz.force(w, E, R)
    Pc = hertz.force(wc, E, R)
    if x <= KE_LIMITS[1]:
        return 1.03 * Pc * x**1.425
    if x <= KE_LIMITS[2]:
        return 1.40 * Pc * x**1.263
    return 2.0 * math.pi * R * w * 2.8 * Y


@jitable
def ke_contact_area(w, E, R, Y, nu):
    """Contact area [m^2] at interference ``w`` (Kogut & Etsion 2002), ``A_c = pi R omega_c``:

    ``x <= 1``: ``A_c x`` (eq. 3); ``1 < x <= 6``: ``0.93 A_c x^1.136`` (eq. 7); ``6 < x <= 110``:
    ``0.94 A_c x^1.146`` (eq. 8); ``x > 110``: ``2 pi R w``.
    """
    wc = ke_critical_interference(E, R, Y, nu)
    x = w / wc
    Ac = math.pi * R * wc
    if x <= KE_LIMITS[0]:
        return Ac * x
    if x <= KE_LIMITS[1]:
        return 0.93 * Ac * x**1.136
    if x <= KE_LIMITS[2]:
        return 0.94 * Ac * x**1.146
    return 2.0 * math.pi * R * w


@jitable
def _ke_piece_work(lo, hi, E, R, Y, nu):
    """``int_lo^hi P dw`` within one regime of :func:`ke_loading_force` (closed form of its power law)."""
    wc = ke_critical_interference(E, R, Y, nu)
    xm = 0.5 * (lo + hi) / wc
    if xm <= KE_LIMITS[0]:
        return 0.4 * (hertz.force(hi, E, R) * hi - hertz.force(lo, E, R) * lo)
    Pc = hertz.force(wc, E, R)
    if xm <= KE_LIMITS[1]:
        c = 1.03
        p = 1.425
    elif xm <= KE_LIMITS[2]:
        c = 1.40
        p = 1.263
    else:
        return math.pi * R * 2.8 * Y * (hi - lo) * (hi + lo)
    return c * Pc * wc * ((hi / wc) ** (p + 1.0) - (lo / wc) ** (p + 1.0)) / (p + 1.0)


# ---------------------------------------------------------------------------------- unloading


@jitable
def brake_unloading(alpha_max, P_max, E, R):
    """``(delta_bar, R_bar)`` of Brake's (2015) unloading from ``(alpha_max, P_max)`` [m, m]:

    ``delta_bar = alpha_max (1 - P_max/F_e)``, ``F_e = 4/3 E* R^(1/2) alpha_max^(3/2)``, and
    ``R_bar = P_max^2/((4/3 E*)^2 (alpha_max - delta_bar)^3) = R F_e/P_max``, so that the unloading
    force ``4/3 E* R_bar^(1/2) (alpha - delta_bar)^(3/2)`` passes through ``(alpha_max, P_max)`` with
    Hertz's contact radius there (as ``tmd-lab/microslip-rough-contact``
    ``ROUTINES/FRIC_MODELS/PLASTIC/SPHERE_PLASTIC_PRE.m`` and tmdsimpy's
    ``_normal_asperity_unloading`` write it; the same construction as the seed's eqs. 9-11).
    ``delta_bar < 0`` where ``P_max > F_e``.
    """
    Fe = hertz.force(alpha_max, E, R)
    return alpha_max * (1.0 - P_max / Fe), R * (Fe / P_max)


@jitable
def ekk_unloading(alpha_max, P_max, a_max, E):
    """``(delta_bar, R_bar)`` of the unloading of Etsion, Kligerman & Kadin (2005) as public code writes it [m, m]:

    a Hertzian unloading whose contact radius is continuous at the turning point:
    ``delta_bar = alpha_max (1 - 3 P_max/(4 E* a_max alpha_max))``, ``R_bar = 4 E* a_max^3/(3 P_max)``
    (``tmd-lab/microslip-rough-contact`` ``ROUTINES/FRIC_MODELS/PLASTIC/SPHERE_PLASTIC_PRE2.m`` at
    ``21706045``, "Elastic Unloading (From Etsion Paper)"); ``delta_bar < 0`` where
    ``P_max > 4/3 E* a_max alpha_max``.
    """
    return alpha_max * (1.0 - 3.0 * P_max / (4.0 * E * a_max * alpha_max)), 4.0 * E * a_max * a_max * a_max / (
        3.0 * P_max
    )


# ----------------------------------------------------------------------- the law in the pair's frame


@jitable
def law_constants(law, E, R, Y, nu, twin):
    """The law in its frame, computed once for the many forces of a quadrature:
    ``(s, E_l, R_l, Y, nu, k)`` (:func:`frame`), ``k`` :func:`jg_constants` for Jackson & Green, for
    Kogut & Etsion its critical interference first (the rest unused), so that ``k[0]`` is the law's
    critical interference in its frame."""
    El, Rl, s = frame(E, R, twin)
    if law == JACKSON_GREEN:
        return (s, El, Rl, Y, nu, jg_constants(El, Rl, Y, nu, 0.0))
    if law == JACKSON_GREEN_2005:
        return (s, El, Rl, Y, nu, jg_constants(El, Rl, Y, nu, 1.0))
    return (s, El, Rl, Y, nu, (ke_critical_interference(El, Rl, Y, nu), 0.0, 0.0, 0.0, 0.0, Rl, 0.0))


@jitable
def _critical(c):
    """:func:`critical_approach` from :func:`law_constants`."""
    return c[5][0] / c[0]


@jitable
def _switch(law, c):
    """:func:`switch_approach` from :func:`law_constants`."""
    ac = _critical(c)
    return JG_SWITCH * ac if is_jackson_green(law) else ac


@jitable
def _force(law, alpha, c):
    """:func:`loading_force` from :func:`law_constants`."""
    if alpha <= 0.0:
        return 0.0
    if is_jackson_green(law):
        return _jg_loading(c[0] * alpha, c[1], c[2], c[5])
    return ke_loading_force(c[0] * alpha, c[1], c[2], c[3], c[4])


@jitable
def critical_approach(law, E, R, Y, nu, twin):
    """The critical (yield-inception) approach ``alpha_c`` [m] in the pair's frame."""
    return _critical(law_constants(law, E, R, Y, nu, twin))


@jitable
def switch_approach(law, E, R, Y, nu, twin):
    """Approach [m] where the loading leaves Hertz's curve: ``1.9 alpha_c`` (Jackson & Green), ``alpha_c`` (Kogut & Etsion)."""
    return _switch(law, law_constants(law, E, R, Y, nu, twin))


@jitable
def loading_force(law, alpha, E, R, Y, nu, twin):
    """The law's loading force [N] at approach ``alpha`` [m] (pair's frame; 0 for ``alpha <= 0``)."""
    if alpha <= 0.0:
        return 0.0
    return _force(law, alpha, law_constants(law, E, R, Y, nu, twin))


@jitable
def contact_radius(law, alpha, E, R, Y, nu, twin):
    """The law's contact radius [m] at approach ``alpha`` on loading (Hertz's below the switch)."""
    El, Rl, s = frame(E, R, twin)
    if alpha <= switch_approach(law, E, R, Y, nu, twin):
        return math.sqrt(R * alpha)
    if is_jackson_green(law):
        return jg_contact_radius(s * alpha / jg_critical_interference(El, Rl, Y, nu), El, Rl, Y, nu)
    return math.sqrt(ke_contact_area(s * alpha, El, Rl, Y, nu) / math.pi)


@jitable
def _gl_work(law, lo, hi, E, R, Y, nu, twin):
    """``int_lo^hi P d alpha`` of a smooth piece, composite Gauss-Legendre in ``ln alpha``."""
    if not hi > lo:
        return 0.0
    u0 = math.log(lo)
    span = math.log(hi) - u0
    n = int(math.ceil(span / PANEL))
    if n < 1:
        n = 1
    h = span / n
    c = law_constants(law, E, R, Y, nu, twin)
    total = 0.0
    for k in range(n):
        mid = u0 + (k + 0.5) * h
        part = 0.0
        for i in range(24):
            a = math.exp(mid + 0.5 * h * GX[i])
            part += GW[i] * _force(law, a, c) * a
        total += 0.5 * h * part
    return total


@jitable
def _step_work(law, lo, hi, E, R, Y, nu, twin, c):
    """``int_lo^hi P d alpha`` over a short step inside one smooth piece (``ln(hi/lo)`` below a
    fiftieth of a panel): 6-point Gauss-Legendre in ``ln alpha`` for Jackson & Green, else exact
    (``c``: :func:`law_constants`)."""
    if not is_jackson_green(law) or not lo >= _switch(law, c):
        return loading_work(law, lo, hi, E, R, Y, nu, twin)
    u0 = math.log(lo)
    h = math.log(hi) - u0
    part = 0.0
    for i in range(6):
        a = math.exp(u0 + 0.5 * h * (GX6[i] + 1.0))
        part += GW6[i] * _force(law, a, c) * a
    return 0.5 * h * part


@jitable
def loading_work(law, lo, hi, E, R, Y, nu, twin):
    """``int_lo^hi P d alpha`` [J] along the loading curve, ``0 <= lo <= hi`` (split at the law's jumps)."""
    if not hi > lo:
        return 0.0
    a1 = switch_approach(law, E, R, Y, nu, twin)
    total = 0.0
    if lo < a1:  # Hertz: 2/5 (P alpha) differences
        top = hi if hi < a1 else a1
        total += 0.4 * (hertz.force(top, E, R) * top - hertz.force(lo, E, R) * lo)
        lo = top
    if not hi > lo:
        return total
    if is_jackson_green(law):
        return total + _gl_work(law, lo, hi, E, R, Y, nu, twin)
    El, Rl, s = frame(E, R, twin)
    for j in range(3):  # the regimes of Kogut & Etsion beyond omega_c: (1, 6], (6, 110], (110, inf)
        top = a1 * KE_LIMITS[j + 1] if j < 2 else math.inf
        if lo < top:
            end = hi if hi < top else top
            total += _ke_piece_work(s * lo, s * end, El, Rl, Y, nu) / s
            lo = end
            if not hi > lo:
                break
    return total


@jitable
def unloading(law, alpha_max, E, R, Y, nu, twin):
    """``(P_max, delta_bar, R_bar, a_max)`` of the published unloading from ``alpha_max`` [N, m, m, m]."""
    P = loading_force(law, alpha_max, E, R, Y, nu, twin)
    a = contact_radius(law, alpha_max, E, R, Y, nu, twin)
    if is_jackson_green(law):
        d, Rb = brake_unloading(alpha_max, P, E, R)
    else:
        d, Rb = ekk_unloading(alpha_max, P, a, E)
    return P, d, Rb, a


@jitable
def unloading_work(alpha_max, delta_bar, R_bar, E):
    """Work [J] the published unloading returns from ``alpha_max`` to where the contact ends
    (``delta_bar``, or zero approach where ``delta_bar < 0``)."""
    y = alpha_max - delta_bar
    y0 = -delta_bar if delta_bar < 0.0 else 0.0
    return 0.4 * (hertz.force(y, E, R_bar) * y - hertz.force(y0, E, R_bar) * y0)


@jitable
def retraces(law, alpha_max, E, R, Y, nu, twin):
    """True where the published unloading from ``alpha_max`` would return more work than the loading stored.

    There (just past an upward jump of the fitted loading, see the model files) the contact is
    taken as reversible: the unloading retraces the loading curve and ``e = 1``.
    """
    if not alpha_max > switch_approach(law, E, R, Y, nu, twin):
        return False
    P, d, Rb, a = unloading(law, alpha_max, E, R, Y, nu, twin)
    return unloading_work(alpha_max, d, Rb, E) > loading_work(law, 0.0, alpha_max, E, R, Y, nu, twin)


@jitable
def signed_force(law, alpha, alpha_max, E, R, Y, nu, twin):
    """The law's force [N]: loading while ``alpha >= alpha_max``, else the published unloading
    (negative below ``delta_bar``, where the contact has ended), or the loading curve where
    :func:`retraces`."""
    if alpha >= alpha_max or not alpha_max > switch_approach(law, E, R, Y, nu, twin):
        return loading_force(law, alpha, E, R, Y, nu, twin)
    if retraces(law, alpha_max, E, R, Y, nu, twin):
        return loading_force(law, alpha, E, R, Y, nu, twin)
    P, d, Rb, a = unloading(law, alpha_max, E, R, Y, nu, twin)
    y = alpha - d
    if y >= 0.0:
        return hertz.force(y, E, Rb)
    return -hertz.force(-y, E, Rb)


# ------------------------------------------------------------------------------------ the impact


@jitable
def computable(a1, V1, V, m):
    """False where an impact at ``V`` leaves what double precision can compute, so that the outcome is
    NaN (the law cannot say) instead of a division by zero or an overflow in the quadrature: the
    switch approach ``a1`` or the speed ``V1`` reaching it not a normal double (a yield strength so
    small beside ``E*`` that ``delta_c ~ (S_y/E*)^2 R`` underflows), or, beyond ``V1``, ``V^2`` or the
    kinetic energy ``m* V^2/2`` that the loading work must balance overflowing (speeds past 1e154)."""
    if not (a1 >= TINY_NORMAL and V1 >= TINY_NORMAL):
        return False
    return V <= V1 or (V * V < math.inf and 0.5 * m * V * V < math.inf)


@jitable
def max_approach(law, V, E, R, m, Y, nu, twin):
    """Maximum approach [m] of an impact at ``V`` beyond the switch: ``int_0^alpha* P = m* V^2/2``.

    Newton's method on ``ln W`` against ``ln alpha`` (``W`` the loading work; exact in one step
    where ``W`` is a power of ``alpha``, as Hertz's and the fits' far ends are), kept inside a
    bracket that every iterate narrows (bisection where a step would leave it). The work at each
    iterate from the last one's by one quadrature of the step: the 6-point rule of
    :func:`_step_work` once the step is below its stated bound (a fiftieth of a panel), else the
    composite rule. Newton's error squares at each step (with the factor ``alpha P'/(2P)`` in
    relative terms, about 1 here): the iterate after a relative step below ``STEP_DONE`` is exact
    to rounding, and is returned without a further quadrature.
    """
    c = law_constants(law, E, R, Y, nu, twin)
    a1 = _switch(law, c)
    K = 0.5 * m * V * V
    lnK = math.log(K) if K > 0.0 else -math.inf
    lo = a1
    hi = math.inf
    a = hertz.max_approach(V, E, R, m)
    if a <= a1:
        a = a1 * (1.0 + 1e-9)
    W = loading_work(law, 0.0, a, E, R, Y, nu, twin)
    for _ in range(400):
        if W > K:
            hi = a
        elif W < K:
            lo = a
        else:
            return a
        P = _force(law, a, c)
        if W > 0.0:  # Newton in logarithms: du = ln(alpha_next/alpha)
            du = min((lnK - math.log(W)) * W / (P * a), 20.0)
            nxt = a * math.exp(du)
            if abs(du) <= STEP_DONE:
                return nxt
        else:  # a quadrature far out of the law's range lost the work's sign (see the tests): linear Newton
            nxt = a - (W - K) / P
        if not (lo < nxt < hi):
            nxt = 0.5 * (lo + hi) if hi < math.inf else 2.0 * a
            if abs(nxt - a) <= 4e-16 * a:
                return nxt
        du = math.log(nxt / a)
        if abs(du) < PANEL / 50.0:
            if nxt > a:
                W += _step_work(law, a, nxt, E, R, Y, nu, twin, c)
            else:
                W -= _step_work(law, nxt, a, E, R, Y, nu, twin, c)
        elif nxt > a:
            W += loading_work(law, a, nxt, E, R, Y, nu, twin)
        else:
            W -= loading_work(law, nxt, a, E, R, Y, nu, twin)
        a = nxt
    return a


@jitable
def _time_upper(law, lo, hi, astar, E, R, m, Y, nu, twin):
    """Time [s] from ``lo`` to ``hi <= alpha*`` on loading, in ``s = (alpha* - alpha)^(1/2)``
    (integrand ``2 s/|alpha'|``, finite at the turning point), panels growing by 3 from the smaller
    end (a kink of the speed lies at ``hi`` when ``hi < alpha*``). The kinetic energy
    ``int_alpha^alpha* P`` is accumulated node to node downward from ``hi``: no cancellation."""
    s_lo = math.sqrt(astar - hi)
    s_hi = math.sqrt(astar - lo)
    c = law_constants(law, E, R, Y, nu, twin)
    total = 0.0
    prev = hi
    dW = loading_work(law, hi, astar, E, R, Y, nu, twin)
    a = s_lo
    while a < s_hi:
        b = 3.0 * a if a > 0.0 else s_hi
        if b > s_hi:
            b = s_hi
        part = 0.0
        for i in range(24):
            s = 0.5 * (a + b) + 0.5 * (b - a) * GX[i]
            x = astar - s * s
            dW += _step_work(law, x, prev, E, R, Y, nu, twin, c)
            prev = x
            if dW > 0.0:
                part += GW[i] * 2.0 * s / math.sqrt(2.0 * dW / m)
            else:  # s^2 below the rounding of alpha*: the integrand's limit, 2 (2 P(alpha*)/m*)^(-1/2)
                part += GW[i] * 2.0 / math.sqrt(2.0 * _force(law, astar, c) / m)
        total += 0.5 * (b - a) * part
        a = b
    return total


@jitable
def _time_lower(law, lo, hi, astar, Wstar, E, R, m, Y, nu, twin):
    """Time [s] from ``lo`` to ``hi <= alpha*/2`` on loading, composite Gauss-Legendre in ``ln alpha``;
    the kinetic energy ``W* - W(alpha)`` from the loading work accumulated node to node."""
    u0 = math.log(lo)
    span = math.log(hi) - u0
    n = int(math.ceil(span / PANEL))
    if n < 1:
        n = 1
    h = span / n
    c = law_constants(law, E, R, Y, nu, twin)
    total = 0.0
    prev = lo
    W = loading_work(law, 0.0, lo, E, R, Y, nu, twin)
    for k in range(n):
        mid = u0 + (k + 0.5) * h
        part = 0.0
        for i in range(24):
            a = math.exp(mid + 0.5 * h * GX[i])
            W += _step_work(law, prev, a, E, R, Y, nu, twin, c)
            prev = a
            part += GW[i] * a / math.sqrt(2.0 * (Wstar - W) / m)
        total += 0.5 * h * part
    return total


@jitable
def plastic_loading_time(law, a1, astar, E, R, m, Y, nu, twin):
    """Time [s] from the switch ``a1`` to the maximum approach ``alpha*`` along the fitted loading.

    Split at the law's jumps (a kink of the speed) and at ``alpha*/2``: below it in ``ln alpha``,
    above it in ``s = (alpha* - alpha)^(1/2)``.
    """
    Wstar = loading_work(law, 0.0, astar, E, R, Y, nu, twin)
    half = 0.5 * astar
    total = 0.0
    lo = a1
    nb = 1 if is_jackson_green(law) else 3
    for j in range(nb):
        if is_jackson_green(law):
            top = astar
        else:
            top = a1 * KE_LIMITS[j + 1] if j < 2 else astar
            if top > astar:
                top = astar
        if top > lo:
            if lo < half:
                mid = top if top < half else half
                total += _time_lower(law, lo, mid, astar, Wstar, E, R, m, Y, nu, twin)
                lo = mid
            if top > lo:
                total += _time_upper(law, lo, top, astar, E, R, m, Y, nu, twin)
                lo = top
        if not astar > lo:
            break
    return total


@jitable
def restitution(law, V, E, R, m, Y, nu, twin):
    """The restitution coefficient [-] of :func:`impact` alone (its field ``restitution``: the same
    calls in the same order), without the contact times (the plastic loading time is a quadrature)."""
    if not V < math.inf:
        return math.nan
    a1 = switch_approach(law, E, R, Y, nu, twin)
    V1 = math.sqrt(0.8 * hertz.force(a1, E, R) * a1 / m)
    if not computable(a1, V1, V, m):
        return math.nan
    if V <= V1:  # Hertz
        return 1.0
    astar = max_approach(law, V, E, R, m, Y, nu, twin)
    d, Rb = unloading(law, astar, E, R, Y, nu, twin)[1:3]
    Wu = unloading_work(astar, d, Rb, E)
    WL = 0.5 * m * V * V  # the loading work to alpha*: the energy balance max_approach solves
    if Wu > WL:  # retraces the loading: e = 1
        return 1.0
    if not rebound_resolved(astar, d, Rb, E, m):
        return math.nan
    return math.sqrt(Wu / WL)


@jitable
def rebound_resolved(astar, d, Rb, E, m):
    """False where the elastic rebound ``y = alpha* - delta_bar`` lost every digit to the rounding of
    ``alpha*`` (``delta_bar = alpha* (1 - P*/F_e)`` with ``P*/F_e`` below the rounding: speeds past
    about 1e35 m/s, the contact far wider than the sphere), so that the Hertz speed reaching it is 0:
    the outcome is NaN there, the law cannot say (its unloading time would divide by that speed)."""
    y = astar - d
    return math.sqrt(0.8 * hertz.force(y, E, Rb) * y / m) >= TINY_NORMAL


@jitable
def outside_validity(law, V, E, R, m, Y, nu, twin):
    """The ``outside_validity`` code of an impact at ``V`` (the contract's hook): 1 where the published
    unloading from ``alpha*`` returns more work than the loading stored (:func:`restitution` gives
    ``e = 1`` there, the same calls in the same order), plus 2 where the loading's contact radius ``a*``
    exceeds the sphere's radius (the law's ``R_l``: ``R*``, or ``2 R*`` for two identical spheres);
    0 inside, and on Hertz's curve below the switch."""
    if not V < math.inf:
        return 0.0
    a1 = switch_approach(law, E, R, Y, nu, twin)
    V1 = math.sqrt(0.8 * hertz.force(a1, E, R) * a1 / m)
    if V <= V1 or not computable(a1, V1, V, m):  # Hertz: reversible, inside; or no outcome to flag
        return 0.0
    astar = max_approach(law, V, E, R, m, Y, nu, twin)
    P, d, Rb, a = unloading(law, astar, E, R, Y, nu, twin)
    code = 0.0
    if unloading_work(astar, d, Rb, E) > 0.5 * m * V * V:
        code += 1.0
    El, Rl, s = frame(E, R, twin)
    if a > Rl:
        code += 2.0
    return code


@jitable
def impact(law, V, E, R, m, Y, nu, twin, a_limit):
    """The 18-tuple outcome (:data:`~microimpact.core.quantities.OUTCOME_FIELDS`) of an impact at ``V``.

    ``a_limit`` [m]: largest maximum approach inside the fit's stated range (beyond it, or beyond
    ``a*/R* = 0.3``, ``large_strain`` is 1).
    """
    n = math.nan
    if not V < math.inf:
        return nan_outcome(V)
    ac = critical_approach(law, E, R, Y, nu, twin)
    a1 = switch_approach(law, E, R, Y, nu, twin)
    Vy = math.sqrt(0.8 * hertz.force(ac, E, R) * ac / m)  # Hertz's impact speed reaching alpha_c
    V1 = math.sqrt(0.8 * hertz.force(a1, E, R) * a1 / m)
    if not (computable(a1, V1, V, m) and Vy >= TINY_NORMAL):
        return nan_outcome(V)
    if V <= V1:  # Hertz
        astar = hertz.max_approach(V, E, R, m)
        half = 0.4 * BETA_25_12 * hertz.time_scale(V, E, R, m)
        a = math.sqrt(R * astar)
        return pack(V, Vy, V / Vy, 1.0, 1.0, V, astar, 0.0, hertz.force(astar, E, R), R, a, R, half, 0.0, half, half)
    astar = max_approach(law, V, E, R, m, Y, nu, twin)
    P, d, Rb, a = unloading(law, astar, E, R, Y, nu, twin)
    t1 = elastic_stage_time(V, E, R, m, a1, V1)
    t2 = plastic_loading_time(law, a1, astar, E, R, m, Y, nu, twin)
    tL = t1 + t2
    Wu = unloading_work(astar, d, Rb, E)
    beyond = 1.0 if astar > a_limit else 0.0  # outside the fit's stated range: flagged as large_strain
    WL = 0.5 * m * V * V  # the loading work to alpha* (the energy balance max_approach solves)
    if Wu > WL:  # retraces the loading: e = 1
        return pack_beyond(V, Vy, V / Vy, 0.0, 1.0, V, astar, 0.0, P, n, a, R, beyond, t1, t2, tL, tL)
    e = math.sqrt(Wu / WL)  # <= 1 exactly where Wu <= WL (a rounded quotient is monotonic)
    y = astar - d
    y0 = -d if d < 0.0 else 0.0
    Vfull = math.sqrt(0.8 * hertz.force(y, E, Rb) * y / m)  # the speed of a Hertz impact reaching y
    if not Vfull >= TINY_NORMAL:  # y lost every digit to the rounding of alpha* (:func:`rebound_resolved`)
        return nan_outcome(V)
    V0 = math.sqrt(0.8 * hertz.force(y0, E, Rb) * y0 / m)
    tU = 0.4 * BETA_25_12 * y / Vfull - elastic_stage_time(Vfull, E, Rb, m, y0, V0)
    return pack_beyond(V, Vy, V / Vy, 0.0, e, e * V, astar, max(d, 0.0), P, Rb, a, R, beyond, t1, t2, tL, tU)
