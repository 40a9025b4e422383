"""
Wall interaction: oblique impacts with friction and adhesion
============================================================

:func:`microimpact.coupling.wall_interaction` gives the outgoing velocity (and
spin) of particles hitting a wall, for a flow code's boundary condition: the
seed's restitution of the normal speed (eqs. 22, 27, 28), the adhesive loss of
Thornton & Ning (1998) and a Coulomb impulse for the tangential part
(:ref:`theory-extensions`). Here 4.9 um NH4Fl particles hit silicon at 20 m/s
and at angles from grazing to normal, with friction ``mu = 0.3`` and a work of
adhesion ``G = 0.3 J/m^2``.
"""

import matplotlib.pyplot as plt
import numpy as np

from microimpact.coupling import wall_interaction

speed = 20.0  # [m/s]
angle = np.radians(
    np.linspace(0.5, 90.0, 359)
)  # angle between the velocity and the wall
velocity = np.column_stack(
    [speed * np.cos(angle), np.zeros_like(angle), -speed * np.sin(angle)]
)
out = wall_interaction(
    velocity,
    normal=[0.0, 0.0, 1.0],
    diameter=4.9e-6,
    material="nh4fl",
    wall="silicon",
    limiting_pressure=156e6,
    work_of_adhesion=0.3,
    friction=0.3,
)
print(
    f"V_y = {out.yield_velocity[0]:.2f} m/s, sticking velocity V_s = {out.sticking_velocity[0]:.3f} m/s"
)

# %%
# Normal restitution (it depends on the normal speed only) and the tangential
# ratio ``v_t' / v_t``. At the shallowest angles the normal speed is below the
# sticking velocity: the particle sticks (both ratios 0). Up to about 26 deg
# the friction impulse ``mu J_n`` cannot stop the slip (sliding: the
# tangential loss grows with the normal impulse); beyond, the slip is stopped
# and a non-spinning sphere keeps 5/7 of its tangential velocity (rolling).

tangential = out.velocity[:, 0] / velocity[:, 0]
deg = np.degrees(angle)
fig, ax = plt.subplots(figsize=(6.4, 4.0), layout="constrained")
ax.plot(deg, out.restitution, label="normal restitution $e = -v'_n / v_n$")
ax.plot(deg, tangential, label="tangential ratio $v'_t / v_t$")
ax.fill_between(
    deg,
    0,
    1.05,
    where=out.regime == "rolling",
    color="0.9",
    label="rolling (slip stopped)",
)
ax.fill_between(
    deg, 0, 1.05, where=out.stuck, color="tab:red", alpha=0.25, label="stuck (adhesion)"
)
ax.set_xlabel("impact angle to the wall [deg]")
ax.set_ylabel("ratio [-]")
ax.set_ylim(0.0, 1.05)
ax.set_xlim(0.0, 90.0)
ax.set_title(f"NH4Fl on silicon, {speed:g} m/s, $\\mu$ = 0.3, G = 0.3 J/m$^2$")
ax.legend(loc="lower right")
