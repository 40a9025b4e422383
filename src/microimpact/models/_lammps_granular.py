"""What the faces of ``lammps_jkr`` and ``lammps_dmt`` share: LAMMPS lines, calibration of the damping input."""

from __future__ import annotations

import math

import numpy as np

from ..core.models import _lammps_granular as lg
from ._base import LAMMPS_TANGENTIAL, run

#: Poisson's ratio written into the lines: LAMMPS needs one; with ``E = 2 (1 - nu^2) E*`` any value
#: gives the calibration's ``E*`` at the wall and between equal spheres (``linear_nohistory`` does not use it).
POISSON = 0.3


def lammps(cal, style):
    """``(coeff, comment)``: ``STYLE E damp nu cohesion tangential ... damping KEYWORD`` (each number the
    shortest text that reads back as the same double), ``E = 2 (1 - nu^2) E*``
    (LAMMPS' ``mix_stiffnessE_wall`` and ``mix_stiffnessE`` for one material give back ``E*``)."""
    p = cal.as_dict()
    mode = int(lg.mode_of(p["damping_model"]))
    E_in = 2.0 * (1.0 - POISSON * POISSON) * cal.effective_modulus
    keyword = lg.DAMPING_NAMES[mode]
    damp = p["viscoelastic_damping"] if mode == 0 else p["normal_restitution"]
    coeff = (
        f"{style} {float(E_in)!r} {float(damp)!r} {POISSON!r} {float(p['surface_energy'])!r} {LAMMPS_TANGENTIAL} "
        f"damping {keyword}"
    )
    if mode == 0:
        note = f"# {style}: E = 2 (1 - nu^2) E*, cohesion = gamma = G/2, eta_n = eta_n0 m* a (a: the {style} contact radius)"
    else:
        note = f"# LAMMPS 22 Jul 2025 refuses damping {keyword} with {style} (a cohesive normal model)"
    return coeff, note


def calibrate(law, pair_values, velocity, target_restitution, surface_energy, damping_model):
    """The damping input that gives the mean target ``e`` at the calibration speeds (least squares
    over one variable: ``ln eta_n0`` for viscoelastic, ``e_n`` in (0, 1] for tsuji and
    coeff_restitution); the surface energy and the damping keyword are given."""
    from scipy.optimize import minimize_scalar

    gamma = float(surface_energy)
    mode = float(damping_model)
    if mode not in (0.0, 1.0, 2.0):
        raise ValueError(
            f"damping_model must be 0 (viscoelastic), 1 (tsuji) or 2 (coeff_restitution), got {damping_model!r}"
        )
    if not (gamma >= 0.0 and math.isfinite(gamma)):
        raise ValueError(f"surface_energy must be non-negative and finite, got {surface_energy!r}")
    E, R, m, _ = pair_values
    e_t = np.asarray(target_restitution, dtype=float)

    def cost(params):
        e, _ = run(law, velocity, pair_values, params)
        return float(np.sum((np.nan_to_num(e, nan=10.0) - e_t) ** 2))

    if mode == 0.0:
        # eta_n0 of the order of the Hertz stiffness over m* and a speed: 4 E* / (3 m* V) per second of A
        scale = 4.0 * E / (3.0 * m * float(np.median(velocity)))
        g = math.log(scale)
        r = minimize_scalar(
            lambda u: cost((gamma, mode, math.exp(u), 1.0)), bounds=(g - 20.0, g + 5.0), method="bounded"
        )
        best = (gamma, mode, math.exp(r.x), 1.0)
        undamped = (gamma, mode, 0.0, 1.0)  # the search's open end: an elastic target needs no damping
        return undamped if cost(undamped) <= cost(best) else best
    lo = 1e-6 if mode == 2.0 else 0.0
    r = minimize_scalar(
        lambda x: cost((gamma, mode, 0.0, x)), bounds=(lo, 1.0), method="bounded", options={"xatol": 1e-12}
    )
    best = (gamma, mode, 0.0, float(r.x))
    ends = [(gamma, mode, 0.0, x) for x in (lo, 1.0)]  # the bounds themselves, which the search does not try
    return min([best, *ends], key=cost)


def params_for_work_of_adhesion(work_of_adhesion, pair_values, params):
    """``params`` with LAMMPS' ``cohesion`` set to what its documentation makes of a work of adhesion
    ``G`` [J/m^2]: the surface energy ``gamma = G/2`` (JKR's force has ``(4 gamma E/(pi a))^(1/2)``,
    i.e. ``(8 pi G E a^3)^(1/2) = 2 pi a^2 (2 G E/(pi a))^(1/2)``; DMT's pull-off ``4 pi gamma R = 2 pi G R``)."""
    G = float(work_of_adhesion)
    if not (G >= 0.0 and math.isfinite(G)):
        raise ValueError(f"work_of_adhesion must be non-negative and finite, got {work_of_adhesion!r}")
    return (0.5 * G, *tuple(params)[1:])
