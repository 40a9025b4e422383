"""Face of :mod:`microimpact.core.models.lammps_mdr`: LAMMPS input lines, plot style."""

from __future__ import annotations

from ._base import LAMMPS_TANGENTIAL

__all__ = ["STYLE", "lammps", "params_for_work_of_adhesion"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#009E73", "linestyle": (0, (5, 1))}


def lammps(cal):
    """LAMMPS ``pair_coeff`` arguments: ``mdr E nu Y gamma psi_b eta damping mdr 1``.

    ``E = (1 - nu^2) E*``: the code's plane-strain modulus ``E/(1 - nu^2)`` is the ``E*`` of a sphere
    on its rigid wall. ``psi_b = 1`` keeps the apparent-radius update of ``fix GRANULAR/MDR`` off, which
    the single-contact law does not hold (module docstring of the law). LAMMPS needs ``newton off``."""
    p = cal.as_dict()
    nu = p["poisson_ratio"]
    E = (1.0 - nu * nu) * cal.effective_modulus
    coeff = (
        f"mdr {E:.12g} {nu:.12g} {p['yield_strength']:.12g} {p['surface_energy']:.12g} 1.0 {p['damping']:.12g} "
        f"damping mdr 1 {LAMMPS_TANGENTIAL}"
    )
    return coeff, "# mdr at a rigid wall: E = (1 - nu^2) E*; psi_b = 1 (no radius update); newton off"


def params_for_work_of_adhesion(work_of_adhesion, pair_values, params):
    """None: LAMMPS's ``gamma`` has no effect on a run converged in the step (its adhesive springs
    act only on steps that shrink the contact radius by 1 %), so no value of it gives a work of
    adhesion."""
    return None
