"""
Fig. 5: effect of the particle's density
========================================

Particle density 1350 to 5350 kg/m^3, other inputs of the silicon case.
"""

from microimpact.figures import plot_energy_loss

ax = plot_energy_loss("density", [1350.0, 2350.0, 3350.0, 4350.0, 5350.0])
