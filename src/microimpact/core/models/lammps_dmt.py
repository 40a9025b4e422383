"""The DMT normal model of LAMMPS' ``pair_style granular`` with its damping, as LAMMPS computes it.

Source: lammps/lammps ``src/GRANULAR/gran_sub_mod_normal.cpp`` (``GranSubModNormalDMT``:
``calculate_forces``, ``F_ne = k a delta - 4 pi gamma R*``, ``k = 4/3 E*``, ``a = (R* delta)^(1/2)``;
default ``touch``: the contact exists while ``delta >= 0``; commit ``58ee3925``),
``gran_sub_mod_damping.cpp`` (the ``get_damp()`` era, with ``coeff_restitution`` and
``allow_cohesion = 0``), ``granular_model.cpp`` (``F_n = F_ne + F_damp``, no clipping with cohesion)
and ``doc/src/pair_granular.rst``. The elastic curve is the one of
:mod:`~microimpact.core.models.dmt_elastic_adhesive` (Derjaguin, Muller & Toporov 1975 in LAMMPS'
form), which alone returns every joule (``e = 1``); the damping and the equation of motion are
:mod:`~microimpact.core.models._lammps_granular`'s:

* ``damping_model`` 0 (``damping viscoelastic``, LAMMPS' default): ``F_damp = eta_n0 m* a alpha'``,
  ``a = (R* alpha)^(1/2)``: the pull ``4 pi gamma R*`` draws a slow particle in, the damping takes
  energy on the way in and out, and below the capture velocity the particle cannot climb back to
  zero approach against the pull (``e = 0``): with DMT, adhesion captures only through damping;
* 1 (``tsuji``) and 2 (``coeff_restitution``): ``F_damp = c (m* max(0, F_ne/alpha))^(1/2) alpha'``
  at positive approach, ``F_ne`` the whole DMT force (cohesion included): the damping is off while
  ``F_ne < 0`` (approach below ``(3 pi gamma R*^(1/2)/E*)^(2/3)``). LAMMPS 22 Jul 2025 refuses both
  with ``dmt`` ("Cannot use tsuji model with a cohesive normal model"): :func:`outside_validity` flags
  them (code 4). The 2024 releases that accepted ``coeff_restitution`` with ``dmt`` took
  ``sqrt(m* F_ne/delta)`` unguarded: NaN on the first step of every contact with cohesion
  (the known bugs: docs/laws/lammps_jkr_dmt.rst). LIGGGHTS damps only the Hertz part, a different law.

Geometry: the wall (``fix wall/gran granular dmt``: ``R*`` the radius, ``m*`` the mass,
``E* = E/(2(1 - nu^2))`` by ``mix_stiffnessE_wall``). Two equal spheres of one type have the same
``E*``, ``R* = R/2``, ``m* = m/2``; between types LAMMPS mixes ``E`` and the wall does not.

Outputs: ``e`` and the contact time by integration (``e = 0``, infinite contact time, where the
approach rate vanishes again at positive approach), :func:`sticking_velocity` the capture velocity
by a root search, :func:`energy_budget` the damping's work beside the impact and rebound energies.

**Parameters of this model** (``params``, in this order):

``surface_energy`` ``gamma`` [J/m^2], ``>= 0``
    LAMMPS' ``cohesion`` (work of adhesion ``2 gamma``, pull-off ``4 pi gamma R* = 2 pi G R*``).
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
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is 0 (where
the contact ends). ``p_y`` is not used.
"""

from __future__ import annotations

import math

from .._jit import jitable
from . import Parameter, checks
from . import _lammps_granular as lg
from ._common import in_bounds

NAME = "lammps_dmt"
TITLE = "LAMMPS pair granular dmt with damping viscoelastic, tsuji or coeff_restitution (as LAMMPS computes it)"
CITATION = "Derjaguin, Muller & Toporov, J. Colloid Interface Sci. 53:314 (1975); LAMMPS pair_style granular dmt"
LABEL = "LAMMPS dmt"
STICKS = True
COST = "slow"
KIND = lg.DMT
PARAMETERS = (
    Parameter.of("surface_energy", "gamma >= 0, LAMMPS' cohesion (work of adhesion 2 gamma)", low=0.0),
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
#: The adhesion limit of the law (Tabor's parameter small).
ADHESION_LIMIT = "DMT"


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
    """``F_n = F_ne + F_damp`` [N] on the DMT curve (positive: repulsive)."""
    mode, coeff = lg.damping_input(params)
    factor = lg.damping_factor(mode, coeff)
    return lg.total_force(KIND, mode, factor, alpha, alpha_dot, E, R, m, params[0])


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N]: :func:`signed_force` while the approach is positive, 0 apart."""
    if alpha < 0.0:
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
    """Approach [m] at which the contact ends: 0 (LAMMPS' ``dmt`` has no force beyond contact)."""
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
    """8 where LAMMPS 22 Jul 2025 refuses the input (damping tsuji or coeff_restitution with dmt), plus 1
    where a negative damping factor (``e_n > 1``) feeds energy in; else 0."""
    return lg.refused(params)


def energy_budget(V, E, R, m, params):
    """``(K_in, 0, W_damping, K_out)`` [J] of one impact (:func:`~._lammps_granular.energy_budget`)."""
    mode, coeff = lg.damping_input(params)
    return lg.energy_budget(KIND, float(V), E, R, m, params[0], mode, coeff)


@jitable
def work_of_adhesion(params):
    """The work of adhesion ``G = 2 gamma`` [J/m^2] (LAMMPS' cohesion is ``gamma``)."""
    return 2.0 * params[0]
