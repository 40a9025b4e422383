"""Capture map of oblique adhesive impacts: outcome over impact angle and speed for one particle.

:func:`capture_map_data` computes the outcome (:mod:`microimpact.oblique.adhesive`: bounce, stick,
captured rolling, captured sliding) on a grid of angle and speed; :func:`plot_capture_map` draws it,
with the tangential restitution of the bouncing particles as contours and the law's head-on capture
speed marked.
"""

from __future__ import annotations

import numpy as np

from ..oblique import adhesive as ad
from ..quantities import axis_label

__all__ = ["capture_map_data", "plot_capture_map"]

#: Fill colour of each outcome (colour-blind-safe, Okabe & Ito).
COLORS = {"bounce": "#f0f0f0", "stick": "#000000", "captured rolling": "#0072B2", "captured sliding": "#E69F00"}


def capture_map_data(pair, *, model, params, friction, kappa, tangential="lammps_mindlin", speeds=None,
                     angles=None, steps=1000):  # fmt: skip
    """``(angles [deg], speeds [m/s], outcome codes (index of OUTCOMES), e_t)`` on the grid (speed rows)."""
    speeds = np.geomspace(0.01, 1.0, 25) if speeds is None else np.asarray(speeds, dtype=float)
    angles = np.linspace(0.0, 85.0, 18) if angles is None else np.asarray(angles, dtype=float)
    A, S = np.meshgrid(angles, speeds)
    out = ad.adhesive_oblique_impact(
        pair, S, A, friction, model=model, params=params, tangential=tangential, kappa=kappa, steps=steps
    )
    code = np.vectorize(ad.OUTCOMES.index)(out.outcome)
    return angles, speeds, code, np.where(out.captured, np.nan, out.tangential_restitution)


def plot_capture_map(pair, *, model, params, friction, kappa, ax=None, sticking_velocity=None, **kw):
    """Draw the capture map; returns the axes."""
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    angles, speeds, code, et = capture_map_data(pair, model=model, params=params, friction=friction, kappa=kappa, **kw)
    if ax is None:
        _, ax = plt.subplots(figsize=(3.5, 2.9), constrained_layout=True)
    cmap = ListedColormap([COLORS[o] for o in ad.OUTCOMES])
    ax.pcolormesh(angles, speeds, code, cmap=cmap, vmin=-0.5, vmax=len(ad.OUTCOMES) - 0.5, shading="nearest")
    cs = ax.contour(angles, speeds, et, levels=[0.6, 0.7, 0.8, 0.9], colors="0.35", linewidths=0.6)
    ax.clabel(cs, fontsize=6, fmt=lambda v: f"{v:.1f}", inline_spacing=2)
    ax.text(0.98, 0.97, "contours: $e_t$ of the rebound", transform=ax.transAxes, ha="right", va="top", fontsize=6)
    if sticking_velocity is not None:
        th = np.linspace(0.0, 85.0, 200)
        ax.plot(th, sticking_velocity / np.cos(np.radians(th)), "k--", lw=0.8, label="$V\\cos\\theta = V_s$")
    ax.set_yscale("log")
    ax.set_ylim(speeds[0], speeds[-1])
    ax.set_xlabel(axis_label("angle", "impact angle from the normal"))
    ax.set_ylabel(axis_label("velocity", "impact speed"))
    handles = [
        Patch(facecolor=COLORS[o], edgecolor="0.3", lw=0.4, label=o)
        for o in ad.OUTCOMES
        if (code == ad.OUTCOMES.index(o)).any()
    ]
    if sticking_velocity is not None:
        handles.append(ax.lines[-1])
    ax.legend(handles=handles, fontsize=6, loc="lower left", framealpha=0.9)
    return ax
