"""
Stick or bounce: the capture velocity and the stick/bounce map
==============================================================

A particle sticks when its rebound energy is not positive. Thornton & Ning
(1998) give two answers: their *additive rule* (the seed's plastic loss plus
the elastic adhesive loss of the undeformed sphere, eq. 78) and their *whole
law*, in which adhesion lowers the pressure at which the contact yields and the
flattened contact unloads along a JKR curve of larger radius with a larger
pull-off force (``thornton_ning_1998_adhesive_plastic``). Here the seed's
NH4Fl particle on silicon with a work of adhesion of 1 J/m^2.
"""

import numpy as np

import microimpact as mi
from microimpact import stick
from microimpact.figures.stick import plot_stick_map

pair = mi.ContactPair.paper_case("silicon")
G = 1.0  # work of adhesion [J/m^2]

# %%
# Capture velocities against diameter: equal while the particle sticks before
# the contact yields, apart below the diameter where it yields first.

d = np.array([0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0]) * 1e-6
additive = pair.sticking_velocity(d, model="additive", work_of_adhesion=G)
whole = pair.sticking_velocity(d, work_of_adhesion=G)
for x, a, w in zip(d, additive, whole):
    print(
        f"d = {x * 1e6:5.2f} um   V_s additive {a:8.3f} m/s   whole law {w:8.3f} m/s   ratio {w / a:5.2f}"
    )
print(
    f"the two part by more than 10 % below d = {stick.parting_diameter(pair, G) * 1e6:.3g} um"
)

# %%
# The map: restitution as colour, white where the particle sticks; black the
# capture velocity, dashed the yield velocity (reduced to 0 by adhesion for the
# small particles of the whole law), dotted the other law's capture velocity.

axes = plot_stick_map(pair, G)
