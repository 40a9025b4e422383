"""Face of :mod:`microimpact.core.models.thornton_ning_1998_adhesive_plastic`: its plot style (the seed's colour, dashed: the seed's law with adhesion)."""

__all__ = ["STYLE"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#000000", "linestyle": "--", "linewidth": 1.3}
