"""Face of :mod:`microimpact.core.models.kogut_etsion_ekk`: its plot style."""

__all__ = ["STYLE"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#D55E00", "linestyle": (0, (1, 1)), "linewidth": 1.5}
