"""
Fitting the limiting contact pressure, with its confidence band
===============================================================

The seed notes that ``p_y`` is uncertain and "may be modified by fitting the
experimental data". :func:`microimpact.fitting.fit_restitution` fits it to
rebound measurements and returns the estimate with its standard error and
confidence interval; :func:`microimpact.figures.fit.plot_fit` draws the data, the
fitted curve with its confidence band, and the residuals.

The data here are **synthetic**: made from the model for the silicon case
(``p_y = 156 MPa``) with seeded Gaussian noise of standard deviation 0.015,
so the fit should recover 156 MPa within its interval. They are not
measurements. ``examples/synthetic_silicon.csv`` in the repository holds a
file of the same kind for ``microimpact fit``.
"""

import numpy as np

import microimpact as mi
from microimpact.figures.fit import plot_fit
from microimpact.fitting import fit_restitution

pair = mi.ContactPair.paper_case("silicon")
rng = np.random.default_rng(20160401)
V = np.sort(rng.uniform(3.0, 110.0, 40))  # impact speeds [m/s]
sigma = 0.015
e = np.minimum(
    pair.impact(V, warn=False).restitution + rng.normal(0.0, sigma, V.size), 1.0
)

# %%
# Fit ``p_y`` (the default free parameter) with the known uncertainty.

fit = fit_restitution(V, e, pair, sigma=sigma)
p, (lo, hi) = fit.params["limiting_pressure"], fit.conf_int["limiting_pressure"]
print(
    f"p_y = {p / 1e6:.1f} MPa, 95 % interval {lo / 1e6:.1f} to {hi / 1e6:.1f} MPa (true value 156 MPa)"
)
print(f"V_y = {fit.yield_velocity:.2f} m/s, chi2 / dof = {fit.chi2 / fit.dof:.2f}")

# %%
# Data with error bars, the fitted curve and its 95 % band, and the residuals.

ax = plot_fit(fit, V, e, sigma=sigma)

# %%
# Forty points pin ``p_y`` to about 1 %, so the band is thinner than the line
# above. :meth:`FitResult.confidence_band <microimpact.fitting.FitResult.confidence_band>`
# gives it as numbers: here its half-width against the speed. It vanishes at
# ``V_y`` and below (``e = 1`` there whatever ``p_y``) and is widest where
# ``e`` is most sensitive to ``V_y``.

import matplotlib.pyplot as plt

grid = np.linspace(1.0, 120.0, 400)
lo, hi = fit.confidence_band(grid)
fig, ax = plt.subplots(figsize=(6.4, 3.2), layout="constrained")
ax.plot(grid, (hi - lo) / 2, label="95 % band half-width")
ax.axvline(
    fit.yield_velocity,
    color="0.4",
    ls=":",
    label=f"$V_y$ = {fit.yield_velocity:.2f} m/s",
)
ax.set_xlabel("impact speed $V$ [m/s]")
ax.set_ylabel("half-width of the band in $e$ [-]")
ax.set_xlim(0.0, 120.0)
ax.set_ylim(bottom=0.0)
ax.legend(loc="lower right")
