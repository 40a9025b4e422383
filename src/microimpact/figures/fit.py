"""Plots of a fit and of a ranking (matplotlib, the ``plot`` extra): the data with the fitted curve,
its confidence band and the residuals (:func:`plot_fit`, :func:`plot_residuals`), and the models of
a ranking side by side (:func:`plot_models`).

They take what :mod:`microimpact.fitting` returns (:class:`~microimpact.fitting.FitResult`,
:class:`~microimpact.fitting.ModelRanking`); for one release they are importable from
:mod:`microimpact.fitting` too, with a :class:`DeprecationWarning` naming this module.
"""

from __future__ import annotations

import numpy as np

from .._optional import require
from ..fitting import FREE_PARAMETERS

__all__ = ["plot_fit", "plot_residuals", "plot_models"]


# ---------------------------------------------------------------------- plots
def _fit_curve_grid(fit, V):
    vmax = max(float(np.max(V)), fit.yield_velocity) * 1.08
    grid = np.union1d(np.linspace(0.0, vmax, 600)[1:], [fit.yield_velocity])
    return grid


def plot_fit(
    fit_result,
    data_velocity,
    data_restitution,
    ax=None,
    *,
    sigma=None,
    residual_ax=None,
    residuals=True,
    show_yield=True,
    data_kws=None,
    fit_kws=None,
    band_kws=None,
):
    """Measured restitution, the fitted ``e(V)`` with its confidence band, and residuals.

    Parameters
    ----------
    fit_result : FitResult
        From :func:`~microimpact.fitting.fit_restitution`.
    data_velocity, data_restitution : array_like
        The measured points [m/s], [-].
    ax : matplotlib Axes, optional
        Axes for data and curve. When None, a new figure with two panels (curve
        above, residuals below, shared speed axis) is made.
    sigma : array_like, optional
        Error bars; default the fit's ``sigma`` when the data are the fitted ones.
    residual_ax : matplotlib Axes, optional
        Where to draw the residuals when ``ax`` is given (skipped if None).
    residuals : bool
        Draw the residual panel in a new figure.
    show_yield : bool
        Mark the fitted ``V_y``.
    data_kws, fit_kws, band_kws : dict, optional
        Passed to ``errorbar``, ``plot`` and ``fill_between``.

    Returns
    -------
    (Axes, Axes or None)
        The curve axes and the residual axes.
    """
    plt = require("matplotlib.pyplot", "plotting")
    V = np.asarray(data_velocity, dtype=float).ravel()
    e = np.asarray(data_restitution, dtype=float).ravel()
    if sigma is None and fit_result.sigma is not None and fit_result.sigma.size == V.size:
        sigma = fit_result.sigma
    if ax is None:
        if residuals:
            fig, (ax, residual_ax) = plt.subplots(
                2,
                1,
                sharex=True,
                figsize=(6.4, 5.6),
                gridspec_kw={"height_ratios": [3, 1.2], "hspace": 0.08},
                layout="constrained",
            )
        else:
            fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
    grid = _fit_curve_grid(fit_result, V)
    lo, hi = fit_result.confidence_band(grid)
    pct = f"{100 * fit_result.confidence:g} %"
    band = {"color": "tab:blue", "alpha": 0.25, "linewidth": 0, "label": f"{pct} confidence band"}
    band.update(band_kws or {})
    ax.fill_between(grid, lo, hi, **band)
    lab = "model fit" + (f", {_param_label(fit_result)}" if fit_result.params else "")
    line = {"color": "tab:blue", "linewidth": 1.8, "label": lab}
    line.update(fit_kws or {})
    ax.plot(grid, fit_result.predict(grid), **line)
    dk = {
        "fmt": "o",
        "color": "0.15",
        "markersize": 4.5,
        "capsize": 2,
        "elinewidth": 0.8,
        "markerfacecolor": "white",
        "label": "measured",
    }
    dk.update(data_kws or {})
    ax.errorbar(V, e, yerr=sigma, **dk)
    if show_yield:
        ax.axvline(
            fit_result.yield_velocity,
            color="0.4",
            linestyle=":",
            linewidth=1.0,
            label=f"$V_y$ = {fit_result.yield_velocity:.3g} m/s",
        )
    ax.set_xlim(0.0, grid[-1])
    ax.set_ylim(0.0, max(1.05, float(np.max(e)) + 0.03) if e.size else 1.05)
    ax.set_ylabel("coefficient of restitution $e$ [-]")
    ax.legend(loc="lower left", frameon=False, fontsize="small")
    ax.grid(True, alpha=0.3)
    if residual_ax is not None:
        plot_residuals(fit_result, V, e, ax=residual_ax, sigma=sigma)
        ax.tick_params(labelbottom=False)
    else:
        ax.set_xlabel("impact velocity $V$ [m/s]")
    return ax, residual_ax


def plot_residuals(fit_result, data_velocity, data_restitution, ax=None, *, sigma=None, data_kws=None):
    """Residuals ``e - e_fit`` of a restitution fit against the impact speed.

    Parameters
    ----------
    fit_result : FitResult
        From :func:`~microimpact.fitting.fit_restitution`; ``e_fit`` is ``fit_result.predict(V)``.
    data_velocity : array_like
        Measured impact speeds ``V`` [m/s].
    data_restitution : array_like
        Measured coefficients of restitution ``e`` [-].
    ax : matplotlib Axes, optional
        Axes to draw on; a new figure if None.
    sigma : array_like, optional
        Error bars [-]; default the fit's ``sigma`` when the data are the fitted ones.
    data_kws : dict, optional
        Passed to ``ax.errorbar`` for the points.

    Returns
    -------
    matplotlib Axes
        The Axes drawn on (speed [m/s] against ``e - e_fit`` [-]).
    """
    plt = require("matplotlib.pyplot", "plotting")
    V = np.asarray(data_velocity, dtype=float).ravel()
    e = np.asarray(data_restitution, dtype=float).ravel()
    if sigma is None and fit_result.sigma is not None and fit_result.sigma.size == V.size:
        sigma = fit_result.sigma
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 2.4), layout="constrained")
    r = e - fit_result.predict(V)
    ax.axhline(0.0, color="tab:blue", linewidth=1.2)
    dk = {"fmt": "o", "color": "0.15", "markersize": 4, "capsize": 2, "elinewidth": 0.8, "markerfacecolor": "white"}
    dk.update(data_kws or {})
    ax.errorbar(V, r, yerr=sigma, **dk)
    span = float(np.max(np.abs(r) + (0 if sigma is None else np.asarray(sigma)))) if r.size else 0.0
    span = max(span * 1.15, 1e-3)
    ax.set_ylim(-span, span)
    ax.set_xlabel("impact velocity $V$ [m/s]")
    ax.set_ylabel(r"$e - e_\mathrm{fit}$ [-]")
    ax.grid(True, alpha=0.3)
    return ax


def _param_label(fit, tex=True):
    """``p_y = 156 MPa`` style text of a fit's free parameters."""
    parts = []
    for name, value in fit.params.items():
        if name in FREE_PARAMETERS:
            info = FREE_PARAMETERS[name]
            sym, scale, unit = (info["tex"] if tex else info["symbol"]), info["scale"], info["unit"]
        else:
            sym, scale, unit = name, 1.0, fit.units.get(name, "")
        parts.append(f"{sym} = {value * scale:.4g}" + (f" {unit}" if unit else ""))
    return ", ".join(parts)


def plot_models(ranking, ax=None, *, residual_ax=None, data_kws=None):
    """Data, each ranked model's fitted ``e(V)`` and their residuals.

    Parameters
    ----------
    ranking : ModelRanking
        From :func:`~microimpact.fitting.rank_models`.
    ax : matplotlib Axes, optional
        Axes for data and curves; when None a new figure with two panels (curves
        above, residuals below, shared speed axis).
    residual_ax : matplotlib Axes, optional
        Where to draw residuals when ``ax`` is given (skipped if None).
    data_kws : dict, optional
        Passed to ``errorbar`` for the measured points.

    Returns
    -------
    (Axes, Axes or None)
        Curve axes (speed [m/s] against ``e`` [-]) and residual axes (``e - e_fit`` [-]).
    """
    plt = require("matplotlib.pyplot", "plotting")
    V, e, sigma = ranking.velocity, ranking.restitution, ranking.sigma
    if ax is None:
        _, (ax, residual_ax) = plt.subplots(
            2,
            1,
            sharex=True,
            figsize=(7.0, 6.2),
            gridspec_kw={"height_ratios": [3, 1.4]},
            layout="constrained",
        )
    many = V.size > 2000
    dk = {
        "fmt": "o",
        "color": "0.15",
        "markersize": 1.5 if many else 4.5,
        "capsize": 0 if many else 2,
        "elinewidth": 0.8,
        "markerfacecolor": "white",
        "label": f"measured ({V.size} points)",
        "zorder": 1,
    }
    if many:
        dk.update(alpha=0.3, rasterized=True)
    dk.update(data_kws or {})
    ax.errorbar(V, e, yerr=None if many else sigma, **dk)
    vmax = float(np.max(V)) * 1.08
    vys = [f.yield_velocity for f in ranking.fits.values()]
    grid = np.union1d(np.geomspace(max(1e-3 * vmax, 1e-9), vmax, 500), [v for v in vys if v < vmax])
    styles = ["-", "--", "-.", ":", (0, (5, 1, 1, 1)), (0, (3, 1, 1, 1, 1, 1))]
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    span = 0.0
    for i, row in enumerate(ranking.rows):
        fit = ranking.fits[row["label"]]
        style = {"color": colors[i % len(colors)], "linestyle": styles[i % len(styles)], "linewidth": 1.8}
        detail = _param_label(fit)
        lab = f"{row['label']}: " + (detail + ", " if detail else "")
        lab += rf"$\Delta$AICc = {row['delta_aicc']:.1f}, w = {row['weight']:.2f}"
        ax.plot(grid, fit.predict(grid), label=lab, zorder=3, **style)
        if residual_ax is not None:
            r = e - fit.predict(V)
            span = max(span, float(np.max(np.abs(r))) if r.size else 0.0)
            off = (i - (len(ranking.rows) - 1) / 2) * 0.006 * vmax
            residual_ax.plot(
                V + (0 if many else off),
                r,
                marker="os^dvx"[i % 6],
                linestyle="none",
                markersize=1.5 if many else 4,
                color=style["color"],
                alpha=0.4 if many else 0.9,
                rasterized=many,
            )
    ax.set_xlim(0.0, vmax)
    ax.set_ylim(0.0, max(1.08, float(np.max(e)) + 0.04))
    ax.axhline(1.0, color="0.6", linewidth=0.8, linestyle=":")
    ax.set_ylabel("coefficient of restitution $e$ [-]")
    title = f"ranked by AICc; best: {ranking.best}"
    if ranking.caveat:
        title += "\n(the data cannot tell the leading models apart: AICc within 2)"
    ax.set_title(title, fontsize="medium")
    ax.legend(loc="lower left", frameon=False, fontsize="small")
    ax.grid(True, alpha=0.3)
    if residual_ax is not None:
        residual_ax.axhline(0.0, color="0.3", linewidth=1.0)
        span = max(span * 1.15, 1e-3)
        residual_ax.set_ylim(-span, span)
        residual_ax.set_xlabel("impact velocity $V$ [m/s]")
        residual_ax.set_ylabel(r"$e - e_\mathrm{fit}$ [-]")
        residual_ax.grid(True, alpha=0.3)
        ax.tick_params(labelbottom=False)
    else:
        ax.set_xlabel("impact velocity $V$ [m/s]")
    return ax, residual_ax
