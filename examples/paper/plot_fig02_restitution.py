"""
Fig. 2: restitution coefficient against impact speed
====================================================

The model for NH4Fl on silicon and on mica (seed eq. 27). The paper overlays
Wall et al.'s (1990) measurements, which are not distributed with this
library; pass your own with ``data=`` (see :doc:`/howto/fit_py`).
"""

from microimpact.figures import plot_restitution

ax = plot_restitution()
