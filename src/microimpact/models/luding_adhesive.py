"""Face of :mod:`microimpact.core.models.luding_adhesive`: its plot style (the Luding hysteretic colour, dash-dotted)."""

__all__ = ["STYLE"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#CC79A7", "linestyle": (0, (3, 1, 1, 1))}
