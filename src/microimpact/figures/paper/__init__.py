"""The seed paper's Figures 2-10 as plot functions, each with the data it plots.

Every figure has a pair of public functions:

* ``*_data(...)`` returns the numbers behind the figure as a dict of equally long
  1-D columns (a tidy, "long" table: one row per plotted point, a column naming the
  curve). Column names carry their SI unit as a suffix (``velocity_m_s``,
  ``force_N``, ``time_s``); names without a suffix are dimensionless.
  :data:`COLUMNS` gives the unit and a description of every column. The values are
  exactly what the public API (:meth:`ContactPair.impact`, :meth:`ContactPair.force`,
  :meth:`ContactPair.history`) returns for the same inputs: nothing is smoothed,
  rounded or rescaled.
* ``plot_*(..., ax=None, table=None)`` draws it (in display units: nm, uN, ns) on
  ``ax`` (or a new single-column figure) and returns the Axes. Pass ``table=`` the
  output of the ``*_data`` function to draw exactly those numbers.

Defaults are the seed's silicon case (NH4Fl, d = 4.9 um, rho = 1350 kg/m^3,
E* = 1.31 GPa, p_y = 156 MPa, :meth:`ContactPair.paper_case`) and its velocity
range (up to 120 m/s). Where the contact radius exceeds ``0.3 R*`` the model's
small-strain assumption no longer holds; the figures show that range lightly
hatched (or mark where each curve enters it).

Examples
--------
>>> from microimpact.figures import energy_loss_data
>>> t = energy_loss_data("limiting_pressure", [100e6, 200e6], velocity=[10.0, 50.0])
>>> sorted(t)[:3]
['energy_loss', 'large_strain', 'limiting_pressure_Pa']
"""

from __future__ import annotations

from ._common import COLUMNS, ENERGY_LOSS_PARAMETERS, large_strain_velocity
from ._contact import (
    approach_data,
    contact_time_data,
    force_displacement_data,
    plot_approach,
    plot_contact_times,
    plot_force_displacement,
)
from ._histories import dynamics_data, force_time_data, plot_dynamics, plot_force_time
from ._restitution import energy_loss_data, plot_energy_loss, plot_restitution, restitution_data

__all__ = [
    "COLUMNS",
    "ENERGY_LOSS_PARAMETERS",
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
]
