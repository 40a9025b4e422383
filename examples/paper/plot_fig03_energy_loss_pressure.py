"""
Fig. 3: effect of the limiting contact pressure on the energy loss
==================================================================

Fraction of the kinetic energy lost, ``1 - e^2`` (seed eq. 29), for ``p_y`` =
50 to 250 MPa.
"""

from microimpact.figures import plot_energy_loss

ax = plot_energy_loss("limiting_pressure", [50e6, 100e6, 150e6, 200e6, 250e6])
