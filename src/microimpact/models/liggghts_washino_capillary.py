"""Face of :mod:`microimpact.core.models.liggghts_washino_capillary`: its LIGGGHTS input lines and plot style."""

from __future__ import annotations

from ._liquid_bridge import capillary_lines

__all__ = ["STYLE", "liggghts", "params_for_work_of_adhesion"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#009E73", "linestyle": (0, (5, 1))}


def liggghts(cal, poisson, wall):
    """LIGGGHTS-PUBLIC lines: ``gran model hertz`` with ``cohesion washino/capillary/viscous`` on the pair
    and the wall; ``modifyLbVolume on`` and ``lbVolumeFraction`` where the bridge's volume fraction is
    not the code's 0.05."""
    f = cal.as_dict()["volume_fraction"]
    if f == 0.05:
        return capillary_lines(cal, poisson, wall, "washino/capillary/viscous")
    lines = capillary_lines(cal, poisson, wall, "washino/capillary/viscous", ("modifyLbVolume on",))
    return lines[:-1] + [f"fix m11 all property/global lbVolumeFraction scalar {f:.12g}", lines[-1]]


def params_for_work_of_adhesion(work_of_adhesion, pair_values, params):
    """None: the code's inputs are a surface tension and a contact angle, not a work of adhesion."""
    return None
