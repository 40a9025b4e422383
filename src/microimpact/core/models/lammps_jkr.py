"""The JKR normal model of LAMMPS' ``pair_style granular`` with its damping, as LAMMPS computes it.

Source: lammps/lammps ``src/GRANULAR/gran_sub_mod_normal.cpp`` (``GranSubModNormalJKR``: ``touch``,
``pulloff_distance``, ``calculate_contact_radius``, ``calculate_forces``; commit ``58ee3925``, the
corrected JKR algebra), ``gran_sub_mod_damping.cpp`` (commit of the ``get_damp()``
era, the one with ``coeff_restitution`` and ``allow_cohesion = 0``), ``granular_model.cpp``
(``calculate_forces``: ``F_n = F_ne + F_damp``, no clipping with cohesion) and
``doc/src/pair_granular.rst``. The elastic-adhesive curve is the one of
:mod:`~microimpact.core.models.jkr_elastic_adhesive` (Johnson, Kendall & Roberts 1971, in
LAMMPS' form: ``F_ne = 4 E* a^3/(3 R*) - 2 pi a^2 (4 gamma E*/(pi a))^(1/2)``, ``delta = a^2/R* -
2 (pi gamma a/E*)^(1/2)``), used here unchanged: the contact forms at zero approach and breaks at
``-delta_c``, ``delta_c = (3 pi^2/16)^(1/3) (R* gamma^2/E*^2)^(1/3)``, where the force is the
pull-off force ``-3 pi gamma R*``. The damping and the equation of motion are
:mod:`~microimpact.core.models._lammps_granular`'s:

* ``damping_model`` 0 (``damping viscoelastic``, LAMMPS' default): ``F_damp = eta_n0 m* a alpha'``
  with JKR's contact radius ``a``, which stays positive in the adhesive neck (negative approach):
  the damping acts until the contact breaks;
* 1 (``tsuji``) and 2 (``coeff_restitution``): ``F_damp = c (m* max(0, F_ne/alpha))^(1/2) alpha'``
  at positive approach, 0 elsewhere, ``F_ne`` the whole JKR force (cohesion included), ``c`` from
  ``e_n``. LAMMPS 22 Jul 2025 refuses both with ``jkr`` ("Cannot use tsuji model with a cohesive
  normal model"): :func:`outside_validity` flags them (code 4); the 2024 releases that accepted
  ``coeff_restitution`` with ``jkr`` took ``sqrt(m* F_ne/delta)`` unguarded, NaN as soon as
  ``F_ne < 0`` at positive approach, i.e. on the first step of every contact (docs/laws/lammps_jkr_dmt.rst).
  LIGGGHTS damps only the Hertz part (``S_n = 2 Y* (R* delta)^(1/2)``), a different law.

Geometry: the wall (``fix wall/gran granular jkr``: ``R*`` the radius, ``m*`` the mass,
``E* = E/(2(1 - nu^2))`` by ``mix_stiffnessE_wall``, the wall taken as the particle's material).
Two equal spheres of one type (``pair_coeff * *``) have ``E* = E/(2(1 - nu^2))`` too, ``R* = R/2``,
``m* = m/2``; between types LAMMPS mixes ``E`` and the wall does not.

Outputs: ``e`` and the contact time by integration, ``e = 0`` (captured, infinite contact time)
where the approach rate vanishes again before ``-delta_c``; :func:`sticking_velocity` the capture
velocity ``V_s`` by a root search on the integration; :func:`energy_budget` the impact energy split
into the neck's work, the damping's work and the rebound energy.

**Parameters of this model** (``params``, in this order):

``surface_energy`` ``gamma`` [J/m^2], ``>= 0``
    LAMMPS' ``cohesion`` (the work of adhesion is ``2 gamma``); 0 gives Hertz with the damping.
``damping_model`` [-], in [0, 2]
    LAMMPS' ``damping`` keyword: 0 ``viscoelastic`` (its default), 1 ``tsuji``, 2
    ``coeff_restitution`` (a value between two integers is read as the one below it).
``viscoelastic_damping`` ``eta_n0`` [1/(m s)], ``>= 0`` (default 0)
    The normal model's damping input under ``damping viscoelastic``.
``normal_restitution`` ``e_n`` [-], ``>= 0`` (default 1)
    The normal model's damping input under ``tsuji`` and ``coeff_restitution``. LAMMPS does not
    check it: ``e_n > 1`` gives a negative factor (the damping feeds energy in; flagged, code 1)
    and ``e_n = 0`` with ``coeff_restitution`` NaN (infinity over infinity, as in LAMMPS).

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is the
approach where the contact breaks (``-delta_c``). ``p_y`` is not used.
"""

from __future__ import annotations

import math

from .._jit import jitable
from . import Parameter, checks
from . import _lammps_granular as lg
from ._common import in_bounds

NAME = "lammps_jkr"
TITLE = "LAMMPS pair granular jkr with damping viscoelastic, tsuji or coeff_restitution (as LAMMPS computes it)"
CITATION = "Johnson, Kendall & Roberts, Proc. R. Soc. Lond. A 324:301 (1971); LAMMPS pair_style granular jkr"
LABEL = "LAMMPS jkr"
STICKS = True
COST = "slow"
KIND = lg.JKR
PARAMETERS = (
    Parameter.of("surface_energy", "gamma >= 0, LAMMPS' cohesion (work of adhesion 2 gamma)", low=0.0, normal=True),
    Parameter.of(
        "damping_model",
        default=0.0,
        low=0.0,
        high=2.0,
    ),
    Parameter.of("viscoelastic_damping", "eta_n0 >= 0, used by damping_model 0", default=0.0, low=0.0),
    Parameter.of(
        "normal_restitution", "e_n >= 0 (unchecked, as LAMMPS), used by damping_model 1 and 2", default=1.0, low=0.0
    ),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
#: The adhesion limit of the law (Tabor's parameter large).
ADHESION_LIMIT = "JKR"


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (module docstring; ``p_y`` unused)."""
    ok = in_bounds(params, BOUNDS)
    if not ok:
        return lg.outcome(KIND, V, E, R, m, False, 0.0, 0.0, 0.0)
    mode, coeff = lg.damping_input(params)
    return lg.outcome(KIND, V, E, R, m, True, params[0], mode, coeff)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """``F_n = F_ne + F_damp`` [N] on the JKR curve (positive: repulsive)."""
    mode, coeff = lg.damping_input(params)
    factor = lg.damping_factor(mode, coeff)
    return lg.total_force(KIND, mode, factor, alpha, alpha_dot, E, R, m, params[0])


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N]: :func:`signed_force` from zero approach in loading down to ``-delta_c``, 0 apart."""
    if alpha_max <= 0.0 and alpha < 0.0:
        return 0.0
    if alpha < lg.separation(KIND, E, R, params[0]):
        return 0.0
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


@jitable
def ends_at_zero_force(params):
    """False: the contact ends at :func:`separation_approach`, not where the force vanishes."""
    return False


#: The force does not vanish where the contact ends (it jumps from the pull-off force to 0).
ZERO_FORCE_ORDER = 1.0


@jitable
def separation_approach(E, R, m, p_y, params):
    """Approach [m] at which the contact breaks: ``-delta_c`` (0 without cohesion)."""
    return lg.separation(KIND, E, R, params[0])


@jitable
def sticking_velocity(E, R, m, p_y, params):
    """The capture velocity ``V_s`` [m/s] (``e = 0`` at and below it; NaN for invalid ``params``)."""
    if not in_bounds(params, BOUNDS):
        return math.nan
    mode, coeff = lg.damping_input(params)
    return lg.capture_velocity(KIND, mode, lg.damping_factor(mode, coeff), E, R, m, params[0])


@jitable
def outside_validity(V, E, R, m, p_y, params):
    """8 where LAMMPS 22 Jul 2025 refuses the input (damping tsuji or coeff_restitution with jkr), plus 1
    where a negative damping factor (``e_n > 1``) feeds energy in; else 0."""
    return lg.refused(params)


def energy_budget(V, E, R, m, params):
    """``(K_in, W_neck, W_damping, K_out)`` [J] of one impact (:func:`~._lammps_granular.energy_budget`)."""
    mode, coeff = lg.damping_input(params)
    return lg.energy_budget(KIND, float(V), E, R, m, params[0], mode, coeff)


@jitable
def work_of_adhesion(params):
    """The work of adhesion ``G = 2 gamma`` [J/m^2] (LAMMPS' cohesion is ``gamma``)."""
    return 2.0 * params[0]
