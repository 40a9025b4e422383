"""Face of :mod:`microimpact.core.models.thornton_ning_1998_elastic_adhesive`: its plot style (the JKR adhesive colour, dashed: the same curve from first touch)."""

__all__ = ["STYLE"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#E69F00", "linestyle": "--"}
