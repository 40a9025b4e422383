"""
What each DEM code gives for the same contact: adhesive laws at one work of adhesion
=====================================================================================

The seed's NH4Fl particle (d = 4.9 um) on silicon, a work of adhesion G = 0.1
J/m^2, at a wall. Each DEM code's adhesive law gets its adhesion input from G as
the code's documentation reads a work of adhesion
(:func:`microimpact.calibrate.adhesion_inputs`: LAMMPS' ``jkr``/``dmt`` a surface
energy G/2, LIGGGHTS' ``sjkr`` a cohesion energy density giving JKR's pull-off,
its EEPA law and Lethe's DMT the work of adhesion itself). An input the code
cannot run without and G does not set is fitted by
:func:`microimpact.calibrate.calibrate_adhesive` to Thornton & Ning's whole
adhesive elastic-plastic law at G (the black curve): LIGGGHTS'
``coefficientRestitution`` of ``hertz`` + ``sjkr``, and the liquid amount of
the four liquid bridges (water, zero contact angle: their defaults). Every other
input stays at the law's default, so LAMMPS' ``jkr`` and ``dmt`` and Lethe's
DMT run undamped, as a user who sets only the adhesion gets them.

What the figure shows (printed below with the numbers):

* LAMMPS' ``jkr`` captures below 0.224 m/s, the elastic JKR capture velocity,
  against the whole law's 0.318 m/s; above its yield speed the whole law loses
  energy to plasticity that no elastic law has (e = 0.62 at 100 m/s).
* The conservative DMT forces (LAMMPS ``dmt``, Lethe's DMT with van der Waals
  attraction) capture nothing undamped: the attraction returns on the way out
  what it gave on the way in. LAMMPS' ``mdr`` captures at no G at a converged
  step (its adhesion acts only on steps that shrink the contact by 1 %); it is
  listed, not drawn. LIGGGHTS' EEPA law sets its pull-off to zero at a wall: it
  captures nothing and rebounds with e = 0.41 from its default unloading
  stiffness ratio k2/k1 = 5 at every speed.
* ``hertz`` + ``sjkr`` with its restitution fitted (0.966) captures near the
  whole law (0.31 m/s) but rebounds with its constant damping loss at all speeds.
* Yade's two liquid bridges (Willett's, Rabinovich's), each with the liquid
  volume that captures at the whole law's V_s (about 6e-23 m^3), give one
  curve, the whole law's below its yield speed: any law that takes a fixed
  energy W from the particle rebounds with ``e = (1 - V_s^2/V^2)^(1/2)``,
  whatever force does it.
* LIGGGHTS' two bridges cannot: the code applies no cohesive force to a bridge
  below 1e-17 m^3 (its "bond volume too small"). ``washino``'s bridge, 5 % of
  the liquid on the particle, stays below it at any liquid content the law
  takes, so it captures nothing; ``easo``'s smallest bridge above it (a liquid
  content of 0.32) already captures up to 3.1 m/s, ten times the whole law.
"""

import warnings

from microimpact.figures.dem_adhesion import dem_adhesion_data, plot_dem_adhesion

with warnings.catch_warnings():
    warnings.simplefilter(
        "ignore"
    )  # validity warnings of the laws: the figure is their own e(V)
    data = dem_adhesion_data(work_of_adhesion=0.1)

print(
    f"whole law: V_s = {data['reference_capture_velocity']:.4g} m/s; "
    f"fits at {', '.join(f'{v:.3g}' for v in data['calibration_velocity'])} m/s"
)
for law, entry in data["laws"].items():
    fitted = ", ".join(f"{n} = {entry['params'][n]:.4g}" for n in entry["fitted"])
    print(
        f"{law:28s} {entry['code']:9s} V_s = {entry['capture_velocity']:.4g} m/s"
        + (f"   fitted {fitted} (rms {entry['residual']:.3f})" if fitted else "")
    )

# %%
# One panel per group of codes; the whole law in black in each, the capture
# velocities as markers on ``e = 0``, the laws that capture nothing listed.

axes = plot_dem_adhesion(data=data)
