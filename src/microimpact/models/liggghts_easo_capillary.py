"""Face of :mod:`microimpact.core.models.liggghts_easo_capillary`: its LIGGGHTS input lines and plot style."""

from __future__ import annotations

from ._liquid_bridge import capillary_lines

__all__ = ["STYLE", "liggghts", "params_for_work_of_adhesion"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#56B4E9", "linestyle": (0, (5, 1))}

STYLE_NAME = "easo/capillary/viscous"


def liggghts(cal, poisson, wall):
    """LIGGGHTS-PUBLIC lines: ``gran model hertz`` (``Y* = E*``, ``coefficientRestitution`` the
    damping input) with ``cohesion easo/capillary/viscous`` on the pair and on the wall.

    LIGGGHTS 3.8.0 stops with a segmentation fault at the wall once a bridge forms there (the law's
    ``two_spheres = 0``); between two particles (``two_spheres = 1``, the deck's ``geometry="sphere"``) it runs.
    ``angle_mixing`` is the law's reading of the code, not an input: 3.8.0 mixes as a product."""
    return capillary_lines(cal, poisson, wall, STYLE_NAME)


def params_for_work_of_adhesion(work_of_adhesion, pair_values, params):
    """None: the code's inputs are a surface tension and a contact angle, not a work of adhesion."""
    return None
