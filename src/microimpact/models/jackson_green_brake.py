"""Face of :mod:`microimpact.core.models.jackson_green_brake`: its plot style."""

__all__ = ["STYLE"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#0072B2", "linestyle": (0, (1, 1)), "linewidth": 1.5}
