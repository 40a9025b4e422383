"""Face of :mod:`microimpact.core.models.jkr_elastic_adhesive`: its plot style."""

__all__ = ["STYLE"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#E69F00", "linestyle": (0, (3, 1, 1, 1))}
