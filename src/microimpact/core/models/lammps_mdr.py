"""LAMMPS ``pair_style granular`` normal model ``mdr`` (Zunker & Kamrin), one sphere on a wall, as the code computes it.

Sources: Zunker & Kamrin (2024), "A mechanically-derived contact model for adhesive elastic-perfectly
plastic particles", Part I, *J. Mech. Phys. Solids* 183:105492 (the method of dimensionality reduction:
an elliptical 1D indenter of height ``A`` and width ``B``) and Part II, 105493 (the bulk response);
the law is read from the code that runs it, ``lammps/lammps:src/GRANULAR/gran_sub_mod_normal.cpp``
(class ``GranSubModNormalMDR``, ``calculate_forces`` and ``calculate_nonadhesive_mdr_force``;
read at commit ``07b704ca``, the 22 Jul 2025 release's law, checked against its runs below),
``src/GRANULAR/gran_sub_mod_damping.cpp`` (``GranSubModDampingMDR``), ``src/GRANULAR/fix_granular_mdr.cpp``
(the apparent-radius update) and ``doc/src/pair_granular.rst``; the authors' own branch
``willzunker/lammps_mdr:src/GRANULAR/gran_sub_mod_normal.cpp@329ef053`` (lammps/lammps#4409) for
what changed on the way into LAMMPS.

What LAMMPS computes for one contact with a ``fix wall/gran granular mdr ... zplane`` wall (one
evaluation, against a rigid flat; ``E_eff = E/(1 - nu^2)`` is the code's "composite plane strain
modulus", so ``E* = E_eff`` at the wall, the wall taken rigid), with ``alpha`` the overlap and
``alpha_max`` its largest value so far:

* yield: the contact turns plastic on loading where the Hertz *mean* pressure
  ``4 E_eff alpha^(1/2)/(3 pi R^(1/2))`` passes ``p_Y = Y (1.75 exp(-4.4 alpha_max/R) + 1)`` (the
  code's "average pressure along yield surface"); the overlap there is ``alpha_Y``
  (:func:`yield_approach`), and ``c_A = pi (alpha_Y^2 - alpha_Y R)``;
* elastic contact (``alpha_max < alpha_Y``): the indenter ``A = 4R``, ``B = 2R``, ``delta_e = alpha``;
* plastic contact: ``a_max = (2 alpha_max R - alpha_max^2 + c_A/pi)^(1/2)``, ``A = 4 p_Y a_max/E_eff``,
  ``B = 2 a_max``; with ``F_max = pi E_eff A B/8``, ``z_R = R - (alpha_max - A/2)`` and the shear
  modulus ``G = E/(2(1 + nu))``, the elastic correction
  ``Delta_R = F_max [2 a_max^2 (nu - 1) - (2 nu - 1) z_R ((a_max^2 + z_R^2)^(1/2) - z_R)] /
  (2 pi G a_max^2 (a_max^2 + z_R^2)^(1/2))``, and ``delta_e = (alpha - alpha_max + A/2 + Delta_R)/(1 +
  2 Delta_R/A)``; on loading ``delta_e = A/2``, so the loading force is ``pi a_max^2 p_Y``;
* the force ``F = (E_eff A B/4) [acos(1 - 2 d) - (2 - 4 d)(d - d^2)^(1/2)]``, ``d = delta_e/A``,
  zero for ``delta_e <= 0``: the contact ends where ``delta_e`` returns to zero, at ``alpha_p =
  alpha_max - A/2 - Delta_R`` (0 for an elastic contact);
* at a wall the force is multiplied by the code's "wall force magnifier" ``1 + exp(10.7 alpha/R - 10)``
  (``1 + 4.5e-5`` at small overlaps);
* damping ``mdr 1``: ``F_d = eta (m E_eff a/2)^(1/2) dalpha/dt`` at a wall (``eta`` the sixth
  coefficient, ``a`` the contact radius ``a_na = B (A - delta_e)^(1/2) delta_e^(1/2)/A``), not
  clipped: attractive on unloading.

Adhesion (``gamma > 0``) as LAMMPS runs it. LAMMPS stores, on every step of a compressive
contact, ``a_Adh = 0.99 a_na`` (``a_fac``) and lets the tensile springs act only on a step where
``a_na`` falls below that stored value, i.e. where the contact radius shrinks by more than 1 % in
one step. The authors' branch (329ef053) stored ``a_Adh = a_na`` and so switched adhesion on as soon
as the unloading began. With LAMMPS's gate the adhesive force acts only over the last ~50 steps of
an unloading (where ``a_na ~ delta_e^(1/2)`` falls fast): it vanishes as the step shrinks (at
1 m/s, elastic, ``gamma = 0.1 J/m^2``: ``1 - e = 2.6e-4`` at t_H/2000 steps, ``8e-7`` at
t_H/20000), so the run converged in the step has no adhesion at all: the ``e(V)`` of ``gamma = 0``,
no capture (``V_s = 0``). The one trace ``gamma > 0`` leaves at a converged step is in the damping:
its contact radius is then the stored ``a_Adh = 0.99 a_na``. This model is that converged limit;
``tests/test_lammps_mdr.py`` reproduces the step dependence in LAMMPS.

Past the wall plane (``alpha >= R``), what LAMMPS does not run. ``fix wall/gran ... zplane`` passes the
signed distance ``dz`` of the centre from the plane to the contact (``src/GRANULAR/fix_wall_gran.cpp``,
``post_force``, at ``7d53f8d1``), whose overlap is ``R - |dz|`` (``GranularModel::calculate_forces``,
``delta = radsum - r`` with ``radsum = R`` at a wall): it can never exceed ``R``. A particle whose
loading reaches ``alpha = R`` (its centre on the plane) sees the overlap fall again as the centre
crosses, its normal flipped, and goes through the wall (a LAMMPS run at 300 m/s in the silicon case
leaves below the wall at 136 m/s; ``tests/test_lammps_mdr.py``). :func:`outside_validity` flags such
an impact (code 8); the outcome is what the force law gives with the overlap carried past ``R``, and
NaN where that law has no unloading (:func:`geometry_lost`, beyond ``R`` only: ``c = 1 + 2 Delta_R/A
<= 0``, where LAMMPS's ``delta_e`` would rise past ``A`` and its force turn NaN, "F_MDR is NaN").

Not modelled (the single contact only): the apparent-radius update of ``fix GRANULAR/MDR`` (the
volume displaced by the plastic cap redistributed over the free surface, which grows the radius and
so the overlap while the contact yields) and the bulk response. Both are off for one sphere on a wall
with ``psi_b = 1`` (the update runs only where ``psi_b`` is below the free-surface fraction, which
cannot exceed 1; the bulk response needs a mean surface displacement that only particle contacts
produce), which is what the printed input lines set. With ``psi_b = 0.5`` the radius update raises
``e`` by 3.5e-3 at 30 m/s in the seed's silicon case (``benchmarks/data/dem_runs.csv``).

Two equal spheres (LAMMPS's pair path): the overlap is split in halves, each side is the wall law at
``alpha/2`` with the particle's radius, and the force is their mean; with ``m* = m/2`` this is the wall
impact of one sphere of mass ``m`` at ``V/2``, except that the pair has no wall force magnifier and
its damping is 4 times the wall's for that motion (``(2 m* E_eff (a_0 + a_1))^(1/2)``).

This model's arguments: ``E`` = ``E_eff`` (the wall's ``E*``), ``R`` the particle radius, ``m`` its
mass; ``p_y`` is not used (the code's yield input is ``Y``; its relation to the seed's ``p_y`` is in
``docs/laws/lammps_mdr.rst``).

**Parameters of this model** (``params``, in this order):

``poisson_ratio`` ``nu`` [-], ``0 <= nu < 0.5``
    The code's second coefficient (with ``E = (1 - nu^2) E*`` the first); it sets ``G`` of ``Delta_R``.
``yield_strength`` ``Y`` [Pa], ``> 0``
    The code's third coefficient.
``surface_energy`` ``gamma`` [J/m^2], ``>= 0``
    The code's fourth coefficient ("effective surface energy"); at a converged step it only scales
    the damping radius (0.99), see above.
``damping`` ``eta`` [-], ``>= 0``
    The sixth coefficient, with ``damping mdr 1``.

The outcome integrates ``m d2alpha/dt2 = -F`` with DOP853 (:mod:`microimpact.core.dop853`, the tableau
and error measure of :mod:`~microimpact.core.models.hertz_viscoelastic`), the yield overlap, the
maximum overlap and the end of the contact located inside the steps. Fields not defined (NaN):
``yield_velocity``, ``normalized_velocity``, ``unloading_radius``; ``max_contact_radius`` is ``a_na``
at ``alpha_max``; the stage times are the loading to ``alpha_Y`` and from it to ``alpha_max``.
"""

from __future__ import annotations

import math

from .. import dop853 as dp
from .. import hertz
from .._jit import jitable
from ..roots import illinois, secant_point
from . import Parameter, checks
from ._common import in_bounds, nan_outcome, pack

NAME = "lammps_mdr"
TITLE = "LAMMPS mdr: Zunker & Kamrin's elastic-plastic (adhesive) law for one sphere on a rigid wall"
CITATION = (
    "Zunker & Kamrin, J. Mech. Phys. Solids 183:105492 and 105493 (2024); "
    "LAMMPS src/GRANULAR/gran_sub_mod_normal.cpp (GranSubModNormalMDR)"
)
LABEL = "LAMMPS mdr"
STICKS = False
COST = "slow"
STAGES = {1: "elastic loading", 2: "plastic loading", 3: "unloading"}
PARAMETERS = (
    Parameter.of(
        "poisson_ratio", "nu in [0, 0.5), the code's second coefficient", default=0.3, low=0.0, high=0.5, high_open=True
    ),
    Parameter.of("yield_strength", "Y > 0, the code's third coefficient", default=74e6, low=0.0, low_open=True),
    Parameter.of("surface_energy", "gamma >= 0, the code's fourth coefficient", default=0.0, low=0.0),
    Parameter("damping", "1", "eta >= 0 of damping mdr 1, the code's sixth coefficient", default=0.0, low=0.0),
)
BOUNDS, validate = checks(NAME, PARAMETERS)

#: The code's ``a_fac``: the stored adhesive radius is this fraction of the contact radius.
A_FAC = 0.99
_TOL = 1e-13
_MAX_STEPS = 200000


@jitable
def yield_approach(E, R, Y):
    """``alpha_Y`` [m]: where the Hertz mean pressure ``4 E alpha^(1/2)/(3 pi R^(1/2))`` reaches
    ``Y (1.75 exp(-4.4 alpha/R) + 1)`` (one root: the left side rises, the right falls); ``inf`` if
    not before ``alpha = R``. Bisection in ``s = (alpha/R)^(1/2)`` to rounding."""
    k = 4.0 * E / (3.0 * math.pi * Y)
    if k - (1.75 * math.exp(-4.4) + 1.0) < 0.0:
        return math.inf
    lo = 0.0
    hi = 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if not (lo < mid < hi):
            break
        s2 = mid * mid
        if k * mid - (1.75 * math.exp(-4.4 * s2) + 1.0) > 0.0:
            hi = mid
        else:
            lo = mid
    return R * hi * hi


@jitable
def unloading_geometry(alpha_max, E, R, params):
    """``(A, B, alpha_p, c)`` of the contact after ``alpha_max``: ``delta_e = (alpha - alpha_p)/c``.

    Elastic (``alpha_max < alpha_Y``): ``(4R, 2R, 0, 1)``; plastic: the code's ``A``, ``B`` and
    ``alpha_p = alpha_max - A/2 - Delta_R``, ``c = 1 + 2 Delta_R/A`` (module docstring)."""
    return _geometry(alpha_max, E, R, params, yield_approach(E, R, params[1]))


@jitable
def _geometry(alpha_max, E, R, params, aY):
    """:func:`unloading_geometry` with the yield overlap ``aY`` (:func:`yield_approach`) given: an
    integration computes that bisection once, not at each of its force evaluations."""
    nu = params[0]
    Y = params[1]
    if not alpha_max > aY:
        return 4.0 * R, 2.0 * R, 0.0, 1.0
    cA = math.pi * (aY * aY - aY * R)
    amax2 = 2.0 * alpha_max * R - alpha_max * alpha_max + cA / math.pi
    if not amax2 > 1e-30 * R * R:  # an overlap past the sphere (a trial stage of a rejected step)
        amax2 = 1e-30 * R * R
    amax = math.sqrt(amax2)
    pY = Y * (1.75 * math.exp(-4.4 * alpha_max / R) + 1.0)
    A = 4.0 * pY * amax / E
    B = 2.0 * amax
    Fmax = 0.125 * math.pi * E * A * B
    zR = R - (alpha_max - 0.5 * A)
    root = math.sqrt(amax2 + zR * zR)
    G = 0.5 * E * (1.0 - nu)  # E/(2(1 + nu)) with E = (1 - nu^2) E_eff
    dR = 2.0 * amax2 * (nu - 1.0) - (2.0 * nu - 1.0) * zR * (root - zR)
    dR *= Fmax / (2.0 * math.pi * amax2 * G * root)
    return A, B, alpha_max - 0.5 * A - dR, 1.0 + 2.0 * dR / A


@jitable
def indenter_force(d, E, A, B):
    """Force [N] of the elliptical indenter ``(A, B)`` at depth ``d`` (the code's
    ``calculate_nonadhesive_mdr_force``; 0 for ``d <= 0``)."""
    if d <= 0.0:
        return 0.0
    x = d / A
    if x >= 0.5:
        x = 0.5
    return 0.25 * E * A * B * (math.acos(1.0 - 2.0 * x) - (2.0 - 4.0 * x) * math.sqrt(x - x * x))


@jitable
def loading_force(alpha, E, R, params):
    """Force [N] on first loading to ``alpha`` (no magnifier, no damping): the elastic indenter
    below ``alpha_Y``, ``pi a_max^2 p_Y`` above."""
    if alpha <= 0.0:
        return 0.0
    aY = yield_approach(E, R, params[1])
    if not alpha > aY:
        return indenter_force(alpha, E, 4.0 * R, 2.0 * R)
    A, B, ap, c = unloading_geometry(alpha, E, R, params)
    return indenter_force(0.5 * A, E, A, B)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N] of LAMMPS's wall contact at a converged step: indenter force times the wall
    magnifier, plus the ``mdr 1`` damping (attractive while the overlap falls)."""
    return _signed_force(alpha, alpha_dot, alpha_max, E, R, m, params, yield_approach(E, R, params[1]))


@jitable
def _signed_force(alpha, alpha_dot, alpha_max, E, R, m, params, aY):
    """:func:`signed_force` with the yield overlap ``aY`` given."""
    amax = alpha_max if alpha_max > alpha else alpha
    A, B, ap, c = _geometry(amax, E, R, params, aY)
    if c > 0.0:
        d = (alpha - ap) / c
    elif alpha >= amax:
        d = 0.5 * A  # loading: the code's quotient is A/2 for any c != 0 (0/0 at c = 0)
    else:
        return math.nan  # no unloading geometry (geometry_lost): the code's force turns NaN and the run stops
    if d <= 0.0:
        return 0.0
    f = indenter_force(d, E, A, B) * (1.0 + math.exp(10.7 * alpha / R - 10.0))
    if params[3] > 0.0:
        x = d / A if d < 0.5 * A else 0.5
        a = B * math.sqrt(x * (1.0 - x))
        if params[2] > 0.0:
            a *= A_FAC
        f += params[3] * math.sqrt(0.5 * m * E * a) * alpha_dot
    return f


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """:func:`signed_force` while ``delta_e > 0``; zero outside the contact."""
    if alpha <= 0.0:
        return 0.0
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


@jitable
def separation_approach(E, R, m, p_y, params):
    """Overlap [m] at which an elastic contact ends: 0."""
    return 0.0


@jitable
def separation_approach_after(alpha_max, E, R, m, p_y, params):
    """``alpha_p`` [m]: where ``delta_e`` returns to zero after ``alpha_max`` (the dent)."""
    return unloading_geometry(alpha_max, E, R, params)[2]


@jitable
def geometry_lost(alpha_max, E, R, params):
    """True where the code's unloading after ``alpha_max`` is undefined: a plastic contact whose
    truncation radius ``a_max^2 = 2 alpha_max R - alpha_max^2 + c_A/pi`` is gone (the cap has passed
    its widest section at ``alpha_max = R``) or whose correction ``Delta_R <= -A/2`` (``c <= 0``: the
    dent would lie deeper than the largest overlap). LAMMPS's ``delta_e`` then rises above ``A/2``
    as the overlap falls and passes ``A``, where ``calculate_nonadhesive_mdr_force`` takes the square
    root of a negative number and the run stops ("F_MDR is NaN"). Both need ``alpha_max > R``."""
    aY = yield_approach(E, R, params[1])
    if not alpha_max > aY:
        return False
    cA = math.pi * (aY * aY - aY * R)
    amax2 = 2.0 * alpha_max * R - alpha_max * alpha_max + cA / math.pi
    if not amax2 > 0.0:
        return True
    return not unloading_geometry(alpha_max, E, R, params)[3] > 0.0


@jitable
def outside_validity(V, E, R, m, p_y, params):
    """The contract's validity code: 8 where the loading reaches the wall plane (``alpha_max >= R``),
    which LAMMPS's wall does not run (module docstring: its overlap is ``R - |z|``, the particle goes
    through the wall); 0 otherwise and for invalid input."""
    if not in_bounds(params, BOUNDS) or not (V > 0.0 and V < math.inf) or not m * V > 0.0:
        return 0.0
    x, v, t, h, hit, f1, t1, elastic, L, c, aY = _loading(V, E, R, m, params)
    return 8.0 if hit and x * L >= R else 0.0


@jitable
def stage_two_approach(E, R, m, p_y, params):
    """``alpha_Y`` [m] (:func:`yield_approach`): the loading force changes law there."""
    return yield_approach(E, R, params[1])


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """0: a LAMMPS run converged in the step never captures the particle (no adhesion acts; the
    damping only slows the separating particle, the indenter force stays repulsive)."""
    return 0.0


@jitable
def _acc(x, v, amax, E, R, m, params, L, V, c, aY):
    """Scaled acceleration ``-F c`` at ``x = alpha/L``, ``v = alpha'/V``; ``amax < 0``: loading."""
    if x <= 0.0:
        return 0.0
    al = x * L
    am = al if amax < 0.0 else amax
    return -_signed_force(al, v * V, am, E, R, m, params, aY) * c


@jitable
def _rates(x, v, p):
    """:func:`_acc` as :func:`~microimpact.core.dop853.step` calls it, ``p = (amax, E, R, m, params,
    L, V, c, aY)``: no third state."""
    return _acc(x, v, p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8]), 0.0


@jitable
def _step(x, v, h, amax, E, R, m, params, L, V, c, aY):
    """One step of length ``h`` of Hairer's DOP853 (:func:`microimpact.core.dop853.step`): ``(x, v,
    error)``, the error measured as Hairer's code measures it (root mean square over ``x`` and
    ``x'``, each relative to ``_TOL (1e-3 + |new value|)``)."""
    xn, vn, _, e5x, e5v, e3x, e3v = dp.step(_rates, x, v, 0.0, h, (amax, E, R, m, params, L, V, c, aY))
    return xn, vn, dp.hairer_error(h, e5x, e5v, e3x, e3v, _TOL * (1e-3 + abs(xn)), _TOL * (1e-3 + abs(vn)))


@jitable
def _event(which, x, v, level):
    """Event functions, each crossing zero from above: 0 top (``x' = 0``), 1 yield or top, whichever
    comes first (``min(x_Y - x, x')``: a speed that just reaches ``x_Y`` may turn first in a second
    integration), 2 end of the contact (``x - x_p``); ``level`` is ``x_Y`` or ``x_p``."""
    if which == 0:
        return v
    if which == 1:
        return level - x if level - x < v else v
    return x - level


@jitable
def _locate(which, level, x, v, h, xh, vh, amax, E, R, m, params, L, V, c, aY):
    """Step length ``0 < s <= h`` from ``(x, v)`` at which event ``which`` crosses zero (Illinois
    secant with bisection), to ``1e-14 s``."""
    a = 0.0
    ga = _event(which, x, v, level)
    b = h
    gb = _event(which, xh, vh, level)
    side = 0
    for _ in range(200):
        s = secant_point(a, b, ga, gb)
        xs, vs, _ = _step(x, v, s, amax, E, R, m, params, L, V, c, aY)
        gs = _event(which, xs, vs, level)
        if gs == 0.0:
            return s
        a, b, ga, gb, side = illinois(a, b, ga, gb, side, s, gs)
        if b - a <= 1e-14 * (b if b > 1e-300 else 1.0):
            break
    return b


@jitable
def _peak(xa, va, hh, amax, E, R, m, params, L, V, c, aY):
    """Largest scaled force on ``[0, hh]`` of the trajectory from ``(xa, va)`` (golden section over the
    length of one step from there: the bracket spans the two steps around the best step end)."""
    g = 0.6180339887498949
    a = 0.0
    b = hh
    s1 = b - g * (b - a)
    s2 = a + g * (b - a)
    x1, v1, _ = _step(xa, va, s1, amax, E, R, m, params, L, V, c, aY)
    x2, v2, _ = _step(xa, va, s2, amax, E, R, m, params, L, V, c, aY)
    f1 = -_acc(x1, v1, amax, E, R, m, params, L, V, c, aY)
    f2 = -_acc(x2, v2, amax, E, R, m, params, L, V, c, aY)
    for _ in range(80):
        if f1 > f2:
            b = s2
            s2 = s1
            f2 = f1
            s1 = b - g * (b - a)
            x1, v1, _ = _step(xa, va, s1, amax, E, R, m, params, L, V, c, aY)
            f1 = -_acc(x1, v1, amax, E, R, m, params, L, V, c, aY)
        else:
            a = s1
            s1 = s2
            f1 = f2
            s2 = a + g * (b - a)
            x2, v2, _ = _step(xa, va, s2, amax, E, R, m, params, L, V, c, aY)
            f2 = -_acc(x2, v2, amax, E, R, m, params, L, V, c, aY)
        if b - a <= 1e-12 * hh:
            break
    return f1 if f1 > f2 else f2


@jitable
def _phase(x, v, t, h, amax, which, level, E, R, m, params, L, V, c, aY):
    """Integrate from ``(x, v)`` at scaled time ``t`` with first step ``h`` until event ``which``
    (at ``level``); returns ``(x, v, t, h, found, fmax)`` at the event, ``fmax`` the largest scaled
    force (``-acceleration``) of the phase: the best step end, refined by :func:`_peak` over the
    two steps around it."""
    fmax = 0.0
    xa = x
    va = v
    ha = 0.0
    hb = -1.0  # the length of the step after the best step end (-1: not yet taken)
    h_old = 0.0
    err_old = 0.0
    for _ in range(_MAX_STEPS):
        xn, vn, err = _step(x, v, h, amax, E, R, m, params, L, V, c, aY)
        if err > 1.0:
            h *= max(0.2, 0.9 * err**-0.125)
            continue
        if _event(which, xn, vn, level) <= 0.0:
            s = _locate(which, level, x, v, h, xn, vn, amax, E, R, m, params, L, V, c, aY)
            xs, vs, _ = _step(x, v, s, amax, E, R, m, params, L, V, c, aY)
            fs = -_acc(xs, vs, amax, E, R, m, params, L, V, c, aY)
            if hb < 0.0:
                hb = s
            if ha > 0.0:
                fmax = max(fmax, _peak(xa, va, ha + hb, amax, E, R, m, params, L, V, c, aY))
            return xs, vs, t + s, h, True, max(fmax, fs)
        f = -_acc(xn, vn, amax, E, R, m, params, L, V, c, aY)
        if hb < 0.0:
            hb = h
        if f > fmax:
            fmax = f
            xa = x
            va = v
            ha = h
            hb = -1.0
        t += h
        x = xn
        v = vn
        if t > 1e4:
            break
        err = max(err, 1e-10)
        trend = 1.0
        if h_old > 0.0:
            trend = min(1.0, h / h_old * (err_old / err) ** 0.125)
        h_old = h
        err_old = err
        h *= min(5.0, 0.9 * trend * err**-0.125)
    return x, v, t, h, False, fmax


@jitable
def _loading(V, E, R, m, params):
    """The loading of an impact at ``V > 0`` to the largest overlap, in the scales of :func:`outcome`:
    ``(x, v, t, h, hit, f1, t1, elastic, L, c, aY)`` (``x = alpha_max/L``, the time ``t`` of the top
    and ``t1`` of the yield, ``hit`` False where the top was not found, ``f1`` the largest scaled
    force, ``aY`` the yield overlap)."""
    T = hertz.time_scale(V, E, R, m)
    L = V * T
    c = T / (m * V)
    aY = yield_approach(E, R, params[1])
    xY = aY / L
    # loading: the elastic stage to the yield overlap, then the plastic stage, to the top
    x, v, t, h, hit, f1 = _phase(0.0, 1.0, 0.0, 1e-3, -1.0, 0, 0.0, E, R, m, params, L, V, c, aY)
    t1 = t
    elastic = 1.0
    if x > xY:  # the contact yielded inside the loading: redo it in two stages
        x, v, t, h, hit, f1 = _phase(0.0, 1.0, 0.0, 1e-3, -1.0, 1, xY, E, R, m, params, L, V, c, aY)
        t1 = t
        if v > 0.0:  # yielded (else the top came first: elastic after all)
            x, v, t, h, hit, f2 = _phase(xY, v, t, h, -1.0, 0, 0.0, E, R, m, params, L, V, c, aY)
            f1 = max(f1, f2)
            elastic = 0.0
    return x, v, t, h, hit, f1, t1, elastic, L, c, aY


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact at a wall (see the module docstring; ``p_y`` unused): NaN where the
    loading ends where the code has no unloading (:func:`geometry_lost`)."""
    if not in_bounds(params, BOUNDS) or not (V > 0.0 and V < math.inf):
        return nan_outcome(V)
    if not m * V > 0.0:  # a momentum below the smallest float: the scales of the integration do not exist
        return nan_outcome(V)
    T = hertz.time_scale(V, E, R, m)
    x, v, t, h, hit, f1, t1, elastic, L, c, aY = _loading(V, E, R, m, params)
    if not hit:
        return nan_outcome(V)
    tL = t
    amax = x * L
    if geometry_lost(amax, E, R, params):
        return nan_outcome(V)
    fmax = max(f1, loading_force(amax, E, R, params) * (1.0 + math.exp(10.7 * amax / R - 10.0)) * c)
    ap = separation_approach_after(amax, E, R, m, p_y, params)
    x, v, t, h, hit, f3 = _phase(x, 0.0, t, h, amax, 2, ap / L, E, R, m, params, L, V, c, aY)
    A, B, _, _ = unloading_geometry(amax, E, R, params)
    a_max = B * 0.5 if elastic == 0.0 else B * math.sqrt(amax / A * (1.0 - amax / A))
    if not hit:
        return pack(
            V,
            math.nan,
            math.nan,
            elastic,
            0.0,
            0.0,
            amax,
            ap,
            fmax / c,
            math.nan,
            a_max,
            R,
            T * t1 if elastic == 0.0 else T * tL,
            T * (tL - t1) if elastic == 0.0 else 0.0,
            T * tL,
            math.inf,
        )
    e = -v if -v < 1.0 else 1.0  # the law only takes energy: e > 1 is the integration's rounding
    return pack(
        V,
        math.nan,
        math.nan,
        elastic,
        e,
        e * V,
        amax,
        ap,
        fmax / c,
        math.nan,
        a_max,
        R,
        T * t1 if elastic == 0.0 else T * tL,
        T * (tL - t1) if elastic == 0.0 else 0.0,
        T * tL,
        T * (t - tL),
    )
