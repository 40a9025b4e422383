"""Face of the seed's model, :mod:`microimpact.core.models.thornton_ning_2016`: style, and its
``e(V)`` through ``V_y`` alone (seed eq. 27) for fitting's grid search."""

from __future__ import annotations

from ..impact import restitution_coefficient as restitution_of_yield_velocity

__all__ = ["STYLE", "restitution_of_yield_velocity"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#000000", "linestyle": "-", "linewidth": 1.6}
