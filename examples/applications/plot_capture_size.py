"""
Capture of oblique adhesive impacts against particle size
=========================================================

The seed's NH4Fl particles on silicon (E* = 1.31 GPa, p_y = 156 MPa) at 1 m/s,
Thornton & Ning's whole adhesive elastic-plastic law with G = 0.1 J/m^2 for the
normal contact, Mindlin's tangential law with Coulomb friction mu = 0.3
(:func:`microimpact.oblique.adhesive.adhesive_oblique_impact`).

Why a map. Nothing tangential acts back on the normal motion of a sphere on a
flat, so the particle is captured exactly where the normal law captures the
normal component of its speed, ``V cos(theta) <= V_s(d)``. At one angle the
captured fraction against diameter is a step from 1 to 0 at the capture
diameter; the map shows that boundary for every angle at once, together with
how the captured particles end (rolling on, sliding, or at rest head-on) and the
tangential restitution of those that bounce. The head-on capture diameter (the
orange marker) is where ``V_s(d) = V``: 1.24 um here; at 60 degrees the
boundary has moved to the d where ``V_s = 0.5 m/s``.
"""

import math
import warnings

from microimpact.figures.capture_size import capture_size_data, plot_capture_size

with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # large-strain warnings of the smallest particles
    data = capture_size_data(velocity=1.0, work_of_adhesion=0.1, friction=0.3)

print(f"head-on capture diameter d_c = {data['capture_diameter'] * 1e6:.3g} um")
for theta in (30.0, 60.0, 80.0):
    vn = data["velocity"] * math.cos(math.radians(theta))
    k = (
        data["capture_velocity"] >= vn
    ).sum()  # V_s falls with d: the first k diameters capture
    print(
        f"theta = {theta:4.0f} deg: captured up to d = {data['diameter'][k - 1] * 1e6:.3g} um "
        f"on the grid (V cos theta = {vn:.3g} m/s)"
    )

# %%
# The map: outcome as fill, the capture boundary in black.

ax = plot_capture_size(data=data)
