"""
Bounce or stick in an impinging jet
===================================

Not in the seed paper: the coupling it proposes in its conclusions. NH4Fl
particles carried by a stagnation-point flow onto a silicon plate (Stokes drag
with Cunningham slip), bouncing or sticking by the seed's restitution with
Thornton & Ning's adhesion (work of adhesion ``G = 0.3 J/m^2``) and Coulomb
friction (``mu = 0.3``) (:ref:`theory-extensions`,
:mod:`microimpact.deposition`). Particles below the critical Stokes number
follow the gas and never reach the plate (dashed: fraction that reaches it);
just above it they arrive slowly and stick; larger ones arrive faster than they
can stick and bounce off: the particle-bounce problem of impactors.
"""

import numpy as np

from microimpact.deposition import plot_deposition, simulate_deposition

result = simulate_deposition(
    np.geomspace(1e-6, 30e-6, 30),
    jet_speeds=[1.0, 2.0, 5.0],
    n_particles=40,
    work_of_adhesion=0.3,
    friction=0.3,
)
ax = plot_deposition(result)
