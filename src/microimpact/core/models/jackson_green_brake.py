"""Jackson & Green's elastic-plastic loading with Brake's (2015) unloading.

**Loading** (a deformable sphere pressed by a flat, elastic-perfectly plastic; Jackson & Green
2005, J. Tribol. 127:343), as Ghaednia, Brake, Berryhill & Jackson (2019, J. Tribol., "Strain
hardening from elastic-perfectly plastic to perfectly elastic flattening single asperity
contact") print it in their eqs. 5-30, read in ``tmd-lab/microslip-rough-contact``
``ROUTINES/FRIC_MODELS/PLASTIC/GHAEDNIA_ET_AL_FLATTENING.m`` and its Python/JAX port
``tmd-lab/tmdsimpy`` ``tmdsimpy/jax/nlforces/roughcontact/_asperity_functions.py``:

* ``C = 1.295 exp(0.736 nu)`` (eq. 6), critical interference ``delta_c = (pi C S_y/(2E))^2 R``
  (eq. 5), critical force ``F_c = 4/3 (R/E)^2 (C pi S_y/2)^3`` (eq. 29, Hertz's force at
  ``delta_c``);
* Hertz's force while ``delta <= 1.9 delta_c`` (eq. 1; Sec. 3.2), beyond it, with ``x =
  delta/delta_c``,

  .. math:: \\frac{F}{F_c} = e^{-x^{5/12}/4} x^{3/2}
            + \\frac{4 H_G}{C S_y}\\left(1 - e^{-x^{5/9}/25}\\right) x \\qquad \\text{(eq. 27)}

  with the hardness ``H_G/S_y = 2.84 - 0.92 (1 - cos(pi a/R))`` (eq. 28) at the contact radius
  ``a = R (pi C S_y/(2E)) (x (x/1.9)^B)^(1/2)``, ``B = 0.14 exp(23 S_y/E)`` (eqs. 23, 24).
  Ghaednia et al.'s strain hardening (tangent modulus ``E_t``, eqs. 11, 21, 25, 26, 30) is left
  out: with ``E_t = 0`` their eq. 30 is eq. 27 and eq. 25 gives ``a = a_p``.

**Hardness term** (parameter ``hardness``). Two fits of the hardness ``H_G/S_y`` at the contact
radius are offered:

* ``hardness = 0`` (default): ``H_G/S_y = 2.84 - 0.92 (1 - cos(pi a/R))``, Ghaednia et al. 2019's
  eq. 28, the form both tmd-lab codes print (labelled "Eqn 28" in ``GHAEDNIA_ET_AL_FLATTENING.m``).
  It is Jackson & Green's later (2006, Tribol. Int. 39:906) hardness, the one Ghaednia et al.
  (Jackson a co-author) carry into the law this model states, and it is the default because the
  whole law here, eqs. 5-29, is theirs as printed and has been compared with their finite elements
  in that form (their Figs. 8-12); the computed numbers of every earlier release are this form's.
* ``hardness = 1``: the 2005 paper's own fit ``H_G/S_y = 2.84 [1 - exp(-0.82 (a/R)^(-0.7))]``,
  the form the project's source list quotes from a public ``JG.m`` for Jackson & Green 2005
  (J. Tribol. 127:343). That script could not be read here (the public files of that name found
  are unrelated), nor the paper's equation itself: the attribution rests on the source list, and
  on the paper's abstract (its hardness "varies with the deformed contact geometry", fitted for
  the hemisphere it models). Use it to see how much the choice of hardness fit matters.

Both are 2.84 at ``a/R -> 0`` and agree within 2 % up to ``a/R = 0.3`` (2.42 against 2.46 there);
beyond it the cosine form falls faster (1.00 against 1.59 at ``a/R = 1``), where ``large_strain``
flags the impact anyway.

**Unloading** (Brake 2015, Int. J. Solids Struct., as ``SPHERE_PLASTIC_PRE.m`` and tmdsimpy's
``_normal_asperity_unloading`` write it; the paper's equation numbers are not given there):
Hertzian from the maximum approach ``alpha*`` and force ``P*``, with the residual interference
``delta_bar = alpha* (1 - P*/F_e)``, ``F_e`` Hertz's force at ``alpha*``, and the unloading radius
``R_bar = P*^2/((4/3 E*)^2 (alpha* - delta_bar)^3)`` (``= R* F_e/P*``): the seed's eqs. 9-11
exactly (:func:`~microimpact.core.models.thornton_ning_2016.unloading_force_from`).

**Modulus convention.** GHAEDNIA_ET_AL_FLATTENING.m takes a sphere on an elastic flat,
``E = ((1 - nu_s^2)/E_s + (1 - nu_f^2)/E_f)^(-1)`` (eq. 3) and the effective radius: the pair's
``E*`` and ``R*`` (``identical_spheres = 0``, the default). tmdsimpy takes two identical spheres,
each pressed against the plane of symmetry with ``2 E*``, radius ``2 R*`` and half the approach
(``identical_spheres = 1``). The conversion is made once
(:func:`~microimpact.core.models._fitted_laws.frame`); Hertz's force, ``delta_c``, ``F_c`` and
the unloading are the same in both, eq. 24's ``B`` (``S_y/E``) and eq. 28's ``a/R`` are not.

**The jump at 1.9 delta_c.** Eq. 27 at ``x = 1.9`` is not Hertz's force there: for ``nu = 0.3``
it is 0.46-0.47 % above it (for ``E*/S_y`` from 220 to 370; 1.5 % at ``nu = 0.25``; below
it for ``nu > 0.32``). Just past an upward
jump ``P* > F_e``, so Brake's residual interference is negative and his unloading returns more
work than the loading stored: ``e > 1``, energy created. Neither source addresses this (Jackson &
Green fitted loading only; the public code combines the two). microimpact does not return it: where the
published unloading would return more work than the loading stored, the contact is taken as
reversible and unloads along its loading curve (``e = 1``, ``plastic_approach = 0``,
``unloading_radius`` NaN, ``elastic`` 0), in :func:`outcome` and :func:`force` alike, so that the
two agree. ``e`` is continuous there (the published unloading gives ``e = 1`` at the band's upper
end). For ``nu = 0.3`` the band ends 7 % above the speed reaching ``1.9 delta_c`` (the
maximum approach 5 % past it): about 2.23 to 2.38 ``V_y`` for ``E*/S_y`` near 300. That band lies
outside what the published law can say: :func:`outside_validity` gives it code 1 (the contract's hook;
:func:`microimpact.models.outside_validity` flags it and warns,
:class:`~microimpact.models.OutsideValidityWarning`). So does (code 2) a contact radius ``a*`` beyond
the sphere's radius: eq. 23's ``a`` grows without bound, and ``e`` rises with the speed again there
(by 0.105 from ``a* = R`` to 10^4 ``V_y`` for the seed's silicon pair at ``S_y`` = 54 MPa).

**Parameters of this model** (``params``, in this order):

``yield_strength`` ``S_y`` [Pa], ``> 0``
    Yield strength of the sphere (the softer body).
``poisson_ratio`` ``nu`` [-], ``-1 < nu <= 0.5``
    Poisson's ratio of the sphere, in ``C`` (eq. 6); default 0.3.
``identical_spheres`` [0 or 1]
    0 (default): a sphere on a flat with the pair's ``E*``, ``R*``; 1: two identical spheres.
``hardness`` [0 or 1]
    0 (default): eq. 28's cosine hardness (Jackson & Green 2006, as Ghaednia et al. print it);
    1: the 2005 paper's exponential fit (see "Hardness term").

``yield_velocity`` is Hertz's impact speed reaching ``delta_c`` (yield inception); the loading
leaves Hertz's curve only at ``1.9 delta_c``, so ``e = 1`` up to the speed reaching it.
``unloading_radius`` is ``R_bar``, ``plastic_approach`` ``max(delta_bar, 0)`` (where
``delta_bar < 0`` the contact ends at zero approach with a force still pressing), and
``max_contact_radius`` eq. 23's ``a``. ``elastic_stage_time`` is the Hertz loading up to
``1.9 delta_c``, ``plastic_stage_time`` the rest of the loading (quadrature of eq. 27); the
unloading time is Hertz's in closed form. ``p_y`` is not used.

Validity: Ghaednia et al. compare the law with their finite elements up to ``Delta/R = 0.05``
(their Figs. 8-12, regenerated by ``TESTS/verification_normal_plasticity.m``); beyond it, or beyond
``a*/R* = 0.3``, ``large_strain`` is 1 (flagged, not refused). Quasi-static, rate-independent, no
adhesion.
Where double precision cannot compute the impact (a yield strength so small beside ``E*`` that
``delta_c`` underflows, a speed whose square overflows, a rebound lost to the rounding of ``alpha*``
past about 1e35 m/s) the outcome is NaN: the law cannot say
(``_fitted_laws.computable``).
"""

from __future__ import annotations

import math

from .._jit import jitable
from . import Parameter, checks
from . import _fitted_laws as fl
from ._common import in_bounds, nan_outcome

NAME = "jackson_green_brake"
TITLE = "Jackson-Green loading (Ghaednia et al. 2019 eqs. 5-29) with Brake's (2015) unloading"
CITATION = "Jackson & Green, J. Tribol. 127:343 (2005); Ghaednia et al., J. Tribol. (2019); Brake, IJSS (2015)"
LABEL = "Jackson-Green/Brake"
PARAMETERS = (
    Parameter.of("yield_strength", "S_y > 0, yield strength of the sphere", low=0.0, low_open=True),
    Parameter.of(
        "poisson_ratio",
        "nu of the sphere, -1 < nu <= 0.5, in C = 1.295 exp(0.736 nu)",
        default=0.3,
        low=-1.0,
        high=0.5,
        low_open=True,
    ),
    Parameter(
        "identical_spheres",
        "1",
        "0: sphere on a flat with the pair's E*, R*; 1: two identical spheres",
        default=0.0,
        flag=True,
    ),
    Parameter(
        "hardness",
        "1",
        "0: H_G/S_y = 2.84 - 0.92 (1 - cos(pi a/R)) (Ghaednia et al. 2019 eq. 28, Jackson & Green 2006); "
        "1: H_G/S_y = 2.84 [1 - exp(-0.82 (a/R)^-0.7)] (Jackson & Green 2005)",
        default=0.0,
        flag=True,
    ),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
#: Cost class (the contract's ``COST``): ``e`` and the outcome take 0.14 and 0.85 ms a point in Python.
COST = "slow"

#: Largest ``Delta/R`` of Ghaednia et al.'s comparisons with finite elements (Figs. 8-12).
VALID_INTERFERENCE_RATIO = 0.05


@jitable
def _law(params):
    """The law code of the chosen hardness fit (``params[3]``)."""
    return fl.JACKSON_GREEN if params[3] == 0.0 else fl.JACKSON_GREEN_2005


@jitable
def _limit(E, R, params):
    """Largest approach [m] inside the compared range ``Delta/R <= 0.05`` (in the law's frame)."""
    El, Rl, s = fl.frame(E, R, params[2])
    return VALID_INTERFERENCE_RATIO * Rl / s


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (see the module docstring; ``p_y`` unused)."""
    if not in_bounds(params, BOUNDS):
        return nan_outcome(V)
    return fl.impact(_law(params), V, E, R, m, params[0], params[1], params[2], _limit(E, R, params))


@jitable
def restitution_only(V, E, R, m, p_y, params):
    """``e`` [-] of :func:`outcome` alone, bit for bit (the contract's hook: fitting compares ``e``),
    without the contact times' quadrature."""
    if not in_bounds(params, BOUNDS):
        return math.nan
    return fl.restitution(_law(params), V, E, R, m, params[0], params[1], params[2])


@jitable
def outside_validity(V, E, R, m, p_y, params):
    """The contract's validity code of an impact at ``V`` (:func:`~microimpact.core.models._fitted_laws.outside_validity`):
    1 where the published unloading would give ``e > 1`` (``e = 1`` returned, module docstring), plus 2
    where ``a*`` exceeds the sphere's radius; 0 inside (and for invalid ``params``)."""
    if not in_bounds(params, BOUNDS):
        return 0.0
    return fl.outside_validity(_law(params), V, E, R, m, params[0], params[1], params[2])


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """The force law [N]: loading (eqs. 1, 27) while ``alpha >= alpha_max``, else Brake's unloading
    (negative below ``delta_bar``, where the contact has ended), or the loading curve where the
    unloading would create energy (module docstring)."""
    return fl.signed_force(_law(params), alpha, alpha_max, E, R, params[0], params[1], params[2])


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N] at approach ``alpha`` with largest approach so far ``alpha_max`` (>= 0)."""
    p = signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)
    return p if p > 0.0 else 0.0


@jitable
def ends_at_zero_force(params):
    """True: the contact ends where the unloading force vanishes (at ``delta_bar > 0``) or at zero approach."""
    return True


@jitable
def critical_interference(E, R, params):
    """``delta_c`` [m] in the pair's frame (eq. 5; two identical spheres: the same value)."""
    return fl.critical_approach(_law(params), E, R, params[0], params[1], params[2])


@jitable
def residual_interference(alpha_max, E, R, params):
    """Brake's residual interference ``delta_bar`` [m] after unloading from ``alpha_max`` (negative just past the jump)."""
    return fl.unloading(_law(params), alpha_max, E, R, params[0], params[1], params[2])[1]
