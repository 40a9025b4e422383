"""Face of :mod:`microimpact.core.models.liggghts_thornton_ning`: its plot style."""

__all__ = ["STYLE"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#009E73", "linestyle": ":", "linewidth": 1.5}
