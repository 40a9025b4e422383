"""
Fig. 4: effect of the particle's Young's modulus
================================================

Particle modulus ``E1`` = 1.2 to 21.2 GPa against a surface of 150 GPa
(Poisson ratios 0.3).
"""

from microimpact.figures import plot_energy_loss

ax = plot_energy_loss("particle_modulus", [1.2e9, 6.2e9, 11.2e9, 16.2e9, 21.2e9])
