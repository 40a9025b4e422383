"""What the seed paper's figures share: the columns of their tables, the parameters of Figs. 3-5,
labels in display units, the default pair and speed grid, and where small strain ends."""

from __future__ import annotations

import numpy as np

from ... import quantities
from ...pair import ContactPair

__all__ = [
    "COLUMNS",
    "ENERGY_LOSS_PARAMETERS",
    "V_LABEL",
    "VMAX",
    "display_scale",
    "legend_label",
    "default_pair",
    "speed_grid",
    "concat_columns",
    "groups_of",
    "large_strain_velocity",
    "fmt_value",
]


#: Every column a ``*_data`` function returns: name -> (unit, description), from
#: :data:`microimpact.core.quantities.QUANTITIES` (the CSV names carry their SI unit, ``force_N``).
COLUMNS: dict[str, tuple[str, str]] = quantities.columns(
    [
        "series",
        "kind",
        "velocity",
        "yield_velocity",
        "restitution",
        "energy_loss",
        "large_strain",
        "limiting_pressure",
        "particle_modulus",
        "effective_modulus",
        "density",
        "branch",
        "approach",
        "force",
        "max_approach",
        "plastic_approach",
        "plastic_ratio",
        "elastic_stage_time",
        "plastic_stage_time",
        "loading_time",
        "unloading_time",
        "contact_time",
        "deresiewicz_time",
        "ning_loading_time",
        "time",
        "approach_velocity",
        "stage",
    ]
)

#: Parameters of :func:`energy_loss_data` (seed Figs. 3-5): name -> (column, legend symbol, display unit,
#: scale), from :data:`~microimpact.core.quantities.QUANTITIES`.
ENERGY_LOSS_PARAMETERS: dict[str, tuple[str, str, str, float]] = {
    n: (
        quantities.column(n),
        quantities.QUANTITIES[n].tex,
        quantities.tex_unit(quantities.QUANTITIES[n].shown_unit),
        quantities.QUANTITIES[n].scale,
    )
    for n in ("limiting_pressure", "particle_modulus", "effective_modulus", "density")
}

V_LABEL = quantities.axis_label("velocity", "impact velocity")


def display_scale(name):
    """SI value times this is the value in the quantity's display unit (nm, µN, ns; QUANTITIES)."""
    return quantities.QUANTITIES[name].scale


def legend_label(words, name):
    """A legend entry for quantity ``name``: ``words``, its TeX symbol and its display unit (QUANTITIES)."""
    q = quantities.QUANTITIES[name]
    return f"{words} {q.tex} ({quantities.tex_unit(q.shown_unit)})"


VMAX = 120.0  # the seed's velocity range [m/s]


# ----------------------------------------------------------------------------- helpers
def default_pair(pair):
    return ContactPair.paper_case("silicon") if pair is None else pair


def speed_grid(velocity, *extra, start=0.0, stop=VMAX, num=481):
    """The given speeds, or ``linspace(start, stop, num)`` plus ``extra`` points (e.g. ``V_y``), sorted."""
    if velocity is not None:
        return np.atleast_1d(np.asarray(velocity, dtype=float))
    base = np.linspace(start, stop, num)
    pts = [float(x) for x in extra if start < float(x) < stop]
    return np.unique(np.concatenate([base, pts]))


def concat_columns(parts):
    """Concatenate a list of column dicts with the same keys."""
    keys = list(parts[0])
    return {k: np.concatenate([np.atleast_1d(np.asarray(p[k])) for p in parts]) for k in keys}


def groups_of(table, key):
    """``(value, mask)`` for each distinct ``table[key]`` in order of first appearance."""
    col = np.asarray(table[key])
    _, idx = np.unique(col, return_index=True)
    return [(col[i], col == col[i]) for i in sorted(idx)]


def large_strain_velocity(pair) -> float:
    """Impact speed [m/s] above which the contact radius exceeds ``0.3 R*`` (small strain ends).

    The seed's model in closed form
    (:func:`~microimpact.core.models.thornton_ning_2016.large_strain_velocity`);
    ``inf`` if above 1e6 m/s.

    Parameters
    ----------
    pair : ContactPair
        The contact pair.

    Returns
    -------
    float
        Impact speed [m/s] at which ``a*/R* = 0.3`` (``inf`` if above 1e6 m/s).

    Examples
    --------
    >>> round(large_strain_velocity(ContactPair.paper_case("silicon")), 1)
    23.3
    """
    from ...compare import seed_large_strain_velocity

    return seed_large_strain_velocity(pair)


def fmt_value(x):
    return f"{x:g}"
