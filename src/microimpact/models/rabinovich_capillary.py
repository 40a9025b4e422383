"""Face of :mod:`microimpact.core.models.rabinovich_capillary`: its plot style (no LAMMPS or LIGGGHTS style runs it)."""

__all__ = ["STYLE", "params_for_work_of_adhesion"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#E69F00", "linestyle": (0, (1, 1))}


def params_for_work_of_adhesion(work_of_adhesion, pair_values, params):
    """None: the law's inputs are a bridge volume, a surface tension and a contact angle."""
    return None
