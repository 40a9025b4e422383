"""Face of :mod:`microimpact.core.models.lammps_jkr`: calibration, LAMMPS lines, style."""

from __future__ import annotations

from ..core.models import lammps_jkr as law
from . import _lammps_granular as shared

__all__ = ["STYLE", "calibrate", "lammps", "params_for_work_of_adhesion"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#E69F00", "linestyle": "-"}


def calibrate(pair_values, velocity, target_restitution, target_contact_time, *, surface_energy=0.0, damping_model=0):
    """(surface_energy, damping_model, damping): the given surface energy gamma [J/m^2] and
    damping keyword (0 viscoelastic, 1 tsuji, 2 coeff_restitution) with the damping input that gives
    the mean target ``e`` (least squares); the contact time is set by ``E*`` and is not matched."""
    return shared.calibrate(law, pair_values, velocity, target_restitution, surface_energy, damping_model)


def lammps(cal):
    """LAMMPS ``pair_coeff`` arguments of ``jkr`` with the calibration's damping keyword, and a comment."""
    return shared.lammps(cal, "jkr")


params_for_work_of_adhesion = shared.params_for_work_of_adhesion
