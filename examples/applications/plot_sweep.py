"""
A parameter sweep: restitution over speed and limiting pressure
===============================================================

:func:`microimpact.sweep.sweep` evaluates the closed-form model over every
combination of the inputs given as arrays and returns an
:class:`xarray.Dataset` whose dimensions are those inputs, with units in the
attributes (extra ``sweep``). Here the seed's silicon case over 300 speeds and
120 limiting pressures: 36 000 impacts in one call.
"""

import matplotlib.pyplot as plt
import numpy as np

import microimpact as mi
from microimpact.sweep import sweep

pair = mi.ContactPair.paper_case("silicon")
ds = sweep(
    np.linspace(0.5, 120.0, 300),
    limiting_pressure=np.linspace(50e6, 250e6, 120),
    base=pair,
)
print(ds)

# %%
# The restitution coefficient as a map; the dashed line is the yield velocity
# ``V_y`` (seed eq. 28) of each limiting pressure: below it the impact is
# elastic (``e = 1``).

e = ds["restitution"].transpose("limiting_pressure", "velocity")
fig, ax = plt.subplots(figsize=(6.4, 4.2), layout="constrained")
mesh = ax.pcolormesh(
    ds["velocity"], ds["limiting_pressure"] / 1e6, e, shading="auto", cmap="viridis"
)
cs = ax.contour(
    ds["velocity"],
    ds["limiting_pressure"] / 1e6,
    e,
    levels=[0.6, 0.7, 0.8, 0.9],
    colors="white",
)
ax.clabel(cs, fmt="e = %.1f", fontsize=8)
ax.plot(
    ds["yield_velocity"],
    ds["limiting_pressure"] / 1e6,
    "k--",
    label="yield velocity $V_y$",
)
ax.set_xlabel("impact speed $V$ [m/s]")
ax.set_ylabel("limiting contact pressure $p_y$ [MPa]")
ax.set_xlim(0.5, 120.0)
ax.legend(loc="lower right")
fig.colorbar(mesh, ax=ax, label="restitution coefficient $e$ [-]")

# %%
# With ``chunks=`` the same sweep is lazy: dask evaluates it block by block
# (bounded memory, or on a ``dask.distributed`` cluster unchanged), and gives
# the same numbers.

lazy = sweep(
    np.linspace(0.5, 120.0, 300),
    limiting_pressure=np.linspace(50e6, 250e6, 120),
    base=pair,
    chunks={"velocity": 100},
)
mean_lazy = float(lazy["restitution"].mean().compute())
print(f"mean restitution: eager {float(e.mean()):.12f}, chunked {mean_lazy:.12f}")
