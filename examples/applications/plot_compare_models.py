"""
Impact models side by side: the seed, LIGGGHTS and the DEM laws
================================================================

:func:`microimpact.compare_models` evaluates several impact models for one pair
and returns an :class:`xarray.Dataset` with dimensions ``model`` x ``velocity``
(units in the attributes). Here the seed's NH4Fl-on-silicon case from 1 to
120 m/s. The DEM laws whose parameters have no default (linear spring-dashpot,
Hertz with viscoelastic or Tsuji damping, Luding's hysteretic spring) are
calibrated to the seed's model at 50 m/s (:mod:`microimpact.calibrate`): they
all give the seed's ``e`` there, and differ everywhere else.
"""

import microimpact as mi
from microimpact.figures.compare import plot_comparison

ds = mi.compare_models("silicon")
print(ds.attrs["calibration"])
for name, params in zip(ds["model"].values, ds["parameters"].values):
    print(f"{name:24s} {params}")

# %%
# ``e`` at a few speeds: only the seed's elastic-plastic law and LIGGGHTS'
# ``thornton_ning`` (the seed's loading, a different unloading) are elastic
# below the yield velocity; Luding's spring with a plasticity depth follows the
# seed best among the DEM laws.

print(
    ds["restitution"]
    .sel(velocity=[10.0, 30.0, 100.0], method="nearest")
    .round(3)
    .to_pandas()
)

# %%
# The figure: restitution, energy loss and contact time against impact speed.
# The dotted line is the seed's yield velocity ``V_y``, the grey one the
# calibration speed; hatched, the speeds where the seed's model leaves its
# small-strain range (contact radius above 0.3 R*).

axes = plot_comparison(ds)
