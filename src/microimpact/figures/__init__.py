"""Figures: plot functions that take ``ax=None`` and return the Axes (matplotlib, the ``plot`` extra).

:mod:`microimpact.figures.paper` draws the seed paper's Figures 2-10; each plot
function has a ``*_data`` companion returning the plotted numbers as columns.
:func:`plot_history` (:mod:`microimpact.figures.history`) draws one impact's
time history from :meth:`ContactPair.history`.
Importing this package does not import matplotlib; the plot functions do, and
raise :class:`~microimpact._optional.MissingExtraError` naming the extra when it
is missing.
"""

from .history import plot_history
from .paper import (
    COLUMNS,
    approach_data,
    contact_time_data,
    dynamics_data,
    energy_loss_data,
    force_displacement_data,
    force_time_data,
    large_strain_velocity,
    plot_approach,
    plot_contact_times,
    plot_dynamics,
    plot_energy_loss,
    plot_force_displacement,
    plot_force_time,
    plot_restitution,
    restitution_data,
)

__all__ = [
    "COLUMNS",
    "large_strain_velocity",
    "restitution_data",
    "plot_restitution",
    "energy_loss_data",
    "plot_energy_loss",
    "force_displacement_data",
    "plot_force_displacement",
    "force_time_data",
    "plot_force_time",
    "approach_data",
    "plot_approach",
    "contact_time_data",
    "plot_contact_times",
    "dynamics_data",
    "plot_dynamics",
    "plot_history",
]
