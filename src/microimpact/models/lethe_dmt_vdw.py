"""Face of :mod:`microimpact.core.models.lethe_dmt_vdw`: Lethe's parameter-file lines, the work of
adhesion hook, plot style."""

from __future__ import annotations

__all__ = ["STYLE", "lethe", "params_for_work_of_adhesion"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#56B4E9", "linestyle": (0, (1, 1))}


def lethe(cal, poisson=0.3):
    """Lethe parameter-file lines (``subsection lagrangian physical properties`` and ``model
    parameters``) for a particle and a wall of one material that give the calibration's law.

    With one material on both sides Lethe's effective values are: ``E* = E/(2(1 - nu^2))``, so
    ``young modulus = 2 (1 - nu^2) E*``; the restitution's harmonic mean is ``e``; the effective
    surface energy ``gamma_p + gamma_w - (gamma_p^(1/2) - gamma_w^(1/2))^2 = 2 gamma``, so
    ``surface energy = gamma_e/2``; the Hamaker constants' mean is ``A``."""
    p = cal.as_dict()
    E = 2.0 * (1.0 - poisson * poisson) * cal.effective_modulus
    g = 0.5 * p["effective_surface_energy"]
    body = [
        f"young modulus {{}} = {E:.12g}",
        f"poisson ratio {{}} = {poisson:.12g}",
        f"restitution coefficient {{}} = {p['restitution']:.12g}",
        f"surface energy {{}} = {g:.12g}",
        f"Hamaker constant {{}} = {p['hamaker_constant']:.12g}",
    ]
    return [
        "subsection model parameters",
        "  set particle wall contact force method = DMT",
        "  set particle particle contact force method = DMT",
        f"  set DMT cut-off threshold = {p['cut_off_threshold']:.12g}",
        "end",
        "subsection lagrangian physical properties",
        "  subsection particle type 0",
        *["    set " + b.format("particles") for b in body],
        "  end",
        *["  set " + b.format("wall") for b in body],
        "end",
    ]


def params_for_work_of_adhesion(work_of_adhesion, pair_values, params):
    """``params`` with Lethe's effective surface energy ``gamma_e`` set to ``G``: its pull-off force
    ``2 pi R gamma_e`` is DMT's ``2 pi R G``."""
    p = list(params)
    p[1] = float(work_of_adhesion)
    return tuple(p)
