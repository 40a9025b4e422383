"""Face of :mod:`microimpact.core.models.dmt_elastic_adhesive`: its plot style."""

__all__ = ["STYLE"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#009E73", "linestyle": (0, (3, 1, 1, 1))}
