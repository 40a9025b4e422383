"""Kogut & Etsion's (2002) elastic-plastic loading with the unloading of Etsion, Kligerman & Kadin (2005).

**Loading** (Kogut & Etsion 2002, J. Appl. Mech. 69:657: finite elements of a deformable sphere
pressed by a rigid flat, fitted in three regimes), as the transcription
``yonghoon7153-source/Yonghoon-DEM-DFT`` ``docs/data/kogut_etsion2002_ep_contact_fits.csv``
(@b11f6cd4) gives the paper's equations, and ``TaoYang1999/SCHC-framework`` ``asperity_f_cal.m``,
``asperity_a_cal.m`` (@98b786e3) code them:

* critical interference ``omega_c = (pi K H/(2E))^2 R``, ``H = 2.8 Y``, ``K = 0.454 + 0.41 nu``
  (eq. 1); ``P_c``, ``A_c = pi R omega_c`` Hertz's load and area there;
* ``omega <= omega_c``: Hertz, ``P/P_c = x^(3/2)``, ``A/A_c = x`` (eqs. 2, 3), ``x = omega/omega_c``;
* ``1 < x <= 6``: ``P/P_c = 1.03 x^1.425``, ``A/A_c = 0.93 x^1.136`` (eq. 7);
* ``6 < x <= 110``: ``P/P_c = 1.40 x^1.263``, ``A/A_c = 0.94 x^1.146`` (eq. 8);
* ``x > 110``: fully plastic, ``P = 2 pi R omega H``, ``A = 2 pi R omega`` (as ``asperity_f_cal.m``
  and ``asperity_a_cal.m`` write it; the paper's equation number is not in either source).

``asperity_f_cal.m`` writes eqs. 7-8 dimensionally (``1.37 (pi K H/2E)^0.15 E R^0.575
w^1.425``: ``1.37 = 4/3 x 1.03`` rounded, and ``1.87 = 4/3 x 1.40``); this model uses the
normalised form with the printed prefactors 1.03 and 1.40.

**K.** ``SCHC-framework`` (``Surface_parameter.m``) uses ``K = 0.454 + 0.43 nu``; the
transcription of the paper's eq. 1 and a second, independent public code of the same
coefficient (``tmd-lab/microslip-rough-contact`` ``ROUTINES/FRIC_MODELS/PLASTIC/CEB_MU.m``, from
Chang, Etsion & Bogy 1988 via Eriten et al. 2010, "top of page 3") give ``0.41 nu``: this model
uses 0.41. (At ``nu = 0.3`` then ``2.8 K = 1.6156`` and Jackson & Green's ``C = 1.6150``: the two
laws' critical interferences agree to 0.08 %.)

**Unloading** (Etsion, Kligerman & Kadin 2005, Int. J. Solids Struct.) as the public code
``tmd-lab/microslip-rough-contact`` ``ROUTINES/FRIC_MODELS/PLASTIC/SPHERE_PLASTIC_PRE2.m``
(@21706045, "Elastic Unloading (From Etsion Paper)") writes it, and its ``TESTS/
test_plastic_contact_unload.m`` labels it "Etsion et al.: based on am", taken from Jackson,
Green & Marghitu's (2010) prediction of the coefficient of restitution: Hertzian from ``(omega*, P*)``
with the contact radius ``a*`` of the loading kept continuous, residual interference
``delta_bar = omega* (1 - 3 P*/(4 E* a* omega*))`` and radius ``R_bar = 4 E* a*^3/(3 P*)``. The
paper's own empirical fits of the unloading curve and of the residual interference were not in
any source read here and are not used: this is the unloading as that code computes it.

**Modulus convention.** Kogut & Etsion's ``E`` is Hertz's, ``1/E = (1 - nu1^2)/E1 + (1 -
nu2^2)/E2`` (eq. 1), a sphere on a flat: the pair's ``E*`` and ``R*``. Every term here is a power
law of ``omega/omega_c`` (or linear in ``R omega``), so the two-identical-spheres frame
(``2 E*``, ``2 R*``, half the approach) gives the same forces: there is nothing to convert.

**The jumps.** The fits do not meet Hertz's curve or each other: at ``x = 1`` the load jumps by
+3 % (1.03) and the area by -7 % (0.93), at ``x = 6`` by +1.9 % and +2.3 %, at ``x = 110`` (``nu =
0.3``) by +8 % and +7 %. Just past ``omega_c`` the unloading above has a negative residual
interference (for ``x`` below about 1.58: ``3 P*/(4 E* a* omega*) = 1.068 x^(-0.143)``) and
returns more work than the loading stored: ``e > 1``, energy created. Neither source addresses it
(Kogut & Etsion fitted loading only; the code combines the two). microimpact does not return it:
where the published unloading would return more work than the loading stored, the contact is taken
as reversible and unloads along its loading curve (``e = 1``, ``plastic_approach = 0``,
``unloading_radius`` NaN, ``elastic`` 0), in :func:`outcome` and :func:`force` alike. ``e`` is
continuous at the band's end, ``x = 1.50`` for every pair (the laws are scale-free), reached at
1.66 times the speed that reaches ``omega_c``. That band lies outside what the published law can say:
:func:`outside_validity` gives it code 1 (the contract's hook; :func:`microimpact.models.outside_validity`
flags it and warns, :class:`~microimpact.models.OutsideValidityWarning`), and code 2 where the contact
radius would exceed the sphere's. The later jumps show in ``e(V)``: for steel on steel (``nu = 0.29``)
``e`` jumps up by 0.008 where ``omega*`` crosses ``6 omega_c`` and by 0.037 at ``110 omega_c``.

**Parameters of this model** (``params``, in this order):

``yield_strength`` ``Y`` [Pa], ``> 0``
    Yield strength of the sphere (``H = 2.8 Y``).
``poisson_ratio`` ``nu`` [-], ``-1 < nu <= 0.5``
    Poisson's ratio of the sphere, in ``K`` (eq. 1); default 0.3, the value of the fits.

``yield_velocity`` is Hertz's impact speed reaching ``omega_c``; ``unloading_radius`` ``R_bar``;
``plastic_approach`` ``max(delta_bar, 0)``; ``max_contact_radius`` ``(A*/pi)^(1/2)`` of eqs. 3, 7,
8; ``elastic_stage_time`` the Hertz loading to ``omega_c``, ``plastic_stage_time`` the rest
(quadrature of the fits, split at their jumps); unloading time Hertz's in closed form. ``p_y`` is
not used.

Validity: the fits were made for ``100 < E/Y < 1000`` and ``nu = 0.3`` (the transcription's
note); an impact that leaves Hertz's curve with ``E*/Y`` outside that range, or that exceeds
``a*/R* = 0.3``, has ``large_strain`` 1 (flagged, not refused). Quasi-static, no adhesion.
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

NAME = "kogut_etsion_ekk"
TITLE = "Kogut-Etsion (2002) loading fits with Etsion-Kligerman-Kadin (2005) unloading"
CITATION = "Kogut & Etsion, J. Appl. Mech. 69:657 (2002); Etsion, Kligerman & Kadin, IJSS (2005)"
LABEL = "Kogut-Etsion/EKK"
PARAMETERS = (
    Parameter.of("yield_strength", "Y > 0, yield strength of the sphere (hardness H = 2.8 Y)", low=0.0, low_open=True),
    Parameter.of(
        "poisson_ratio",
        "nu of the sphere, -1 < nu <= 0.5, in K = 0.454 + 0.41 nu",
        default=0.3,
        low=-1.0,
        high=0.5,
        low_open=True,
    ),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
#: Cost class of the outcome (the contract's ``OUTCOME_COST``): its contact times' quadrature, 0.12 ms a
#: point in Python (``e`` alone: 18 us).
OUTCOME_COST = "slow"

#: ``E/Y`` range of Kogut & Etsion's finite elements.
VALID_MODULUS_RATIO = (100.0, 1000.0)


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (see the module docstring; ``p_y`` unused)."""
    if not in_bounds(params, BOUNDS):
        return nan_outcome(V)
    r = E / params[0]
    limit = math.inf if VALID_MODULUS_RATIO[0] <= r <= VALID_MODULUS_RATIO[1] else 0.0
    return fl.impact(fl.KOGUT_ETSION, V, E, R, m, params[0], params[1], 0.0, limit)


@jitable
def restitution_only(V, E, R, m, p_y, params):
    """``e`` [-] of :func:`outcome` alone, bit for bit (the contract's hook: fitting compares ``e``),
    without the contact times' quadrature."""
    if not in_bounds(params, BOUNDS):
        return math.nan
    return fl.restitution(fl.KOGUT_ETSION, V, E, R, m, params[0], params[1], 0.0)


@jitable
def outside_validity(V, E, R, m, p_y, params):
    """The contract's validity code of an impact at ``V`` (:func:`~microimpact.core.models._fitted_laws.outside_validity`):
    1 where the published unloading would give ``e > 1`` (``e = 1`` returned, module docstring), plus 2
    where ``a*`` exceeds the sphere's radius; 0 inside (and for invalid ``params``)."""
    if not in_bounds(params, BOUNDS):
        return 0.0
    return fl.outside_validity(fl.KOGUT_ETSION, V, E, R, m, params[0], params[1], 0.0)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """The force law [N]: loading (eqs. 2, 7, 8, fully plastic) while ``alpha >= alpha_max``, else the
    unloading (negative below ``delta_bar``), or the loading curve where the unloading would create
    energy (module docstring)."""
    return fl.signed_force(fl.KOGUT_ETSION, alpha, alpha_max, E, R, params[0], params[1], 0.0)


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
    """``omega_c`` [m] (eq. 1)."""
    return fl.critical_approach(fl.KOGUT_ETSION, E, R, params[0], params[1], 0.0)


@jitable
def residual_interference(alpha_max, E, R, params):
    """The unloading's residual interference ``delta_bar`` [m] from ``alpha_max`` (negative just past ``omega_c``)."""
    return fl.unloading(fl.KOGUT_ETSION, alpha_max, E, R, params[0], params[1], 0.0)[1]
