"""The stick/bounce map: particle diameter against impact speed, one panel per adhesive law.

Restitution as colour (white where the particle sticks), the capture velocity (the stick/bounce
boundary) as a black line, the yield velocity dashed; both panels share the colour scale. The
numbers are :func:`microimpact.stick.stick_map`'s. matplotlib (the ``plot`` extra) is imported only
when the function is called.
"""

from __future__ import annotations

import math

import numpy as np

from ..core import models as _models
from ..quantities import axis_label
from ..stick import FULL_LAW
from . import style as _style

__all__ = ["plot_stick_map", "LAW_LABELS"]

#: Panel titles of the adhesive laws.
LAW_LABELS = {
    "additive": "additive rule (TN98 eq. 78)",
    FULL_LAW: "whole law (TN98, $R_p$ unloading)",
}


def plot_stick_map(
    pair=None, work_of_adhesion=1.0, diameter=None, velocity=None, ax=None, *, data=None, laws=None, params=None
):
    """Stick/bounce map of ``pair``, one panel per adhesive law side by side: by default the additive
    rule and Thornton & Ning's whole law (:data:`microimpact.stick.ADHESION_LAWS`).

    Parameters
    ----------
    pair : ContactPair or str, optional
        A sphere-on-flat pair, or a paper case name; default the seed's NH4Fl-on-silicon case.
    work_of_adhesion : float
        ``G`` [J/m^2].
    diameter, velocity : array_like, optional
        Grids [m], [m/s]; default 0.05-20 um and 0.1-1000 m/s, 120 points each, log-spaced.
    ax : matplotlib Axes, optional
        One per law; default a new figure (double-column for two laws, three panels a row).
    data : dict, optional
        A result of :func:`microimpact.stick.stick_map` to draw instead of computing one.
    laws : sequence of str, optional
        Laws of :func:`microimpact.stick.adhesion_laws`, one panel each.
    params : dict, optional
        ``{law: {parameter: value}}`` (:func:`microimpact.stick.stick_map`).

    Returns
    -------
    ndarray of matplotlib Axes
        One per law. For the two default laws the figure's title states the diameter below which
        their capture velocities part by more than 10 % (:func:`microimpact.stick.parting_diameter`).
    """
    from .. import stick
    from ..pair import ContactPair

    if pair is None or isinstance(pair, str):
        pair = ContactPair.paper_case(pair or "silicon")
    if data is None:
        d = np.geomspace(0.05e-6, 20e-6, 120) if diameter is None else diameter
        V = np.geomspace(0.1, 1000.0, 120) if velocity is None else velocity
        data = stick.stick_map(pair, work_of_adhesion, d, V, stick.ADHESION_LAWS if laws is None else laws, params)
    d_um = data["diameter"] * 1e6
    V = data["velocity"]
    laws = [n for n in (stick.ADHESION_LAWS if laws is None else laws) if n in data]
    both = sorted(laws) == sorted(stick.ADHESION_LAWS)  # the comparison the parting diameter is made for
    d_part = (
        stick.parting_diameter(
            pair, work_of_adhesion, 1.1, lo=float(data["diameter"].min()), hi=float(data["diameter"].max())
        )
        if both
        else math.nan
    )
    with _style.style() as plt:
        from matplotlib.colors import Normalize

        if ax is None:
            cols = min(len(laws), 3)
            rows = -(-len(laws) // cols)
            fig, grid = plt.subplots(
                rows, cols, figsize=(3.6 * cols, 3.1 * rows), sharey=True, squeeze=False, layout="constrained"
            )
            for extra in grid.ravel()[len(laws) :]:
                extra.set_visible(False)
            axes = grid.ravel()[: len(laws)]
        else:
            axes = np.asarray(ax, dtype=object).ravel()
            if axes.size != len(laws):
                raise ValueError(f"ax must be {len(laws)} Axes (one per law), got {axes.size}")
            fig = axes[0].figure
        cmap = plt.get_cmap("viridis").with_extremes(under="white")
        norm = Normalize(vmin=1e-9, vmax=1.0)
        mesh = None
        for a, law in zip(axes, laws):
            e = np.asarray(data[law]["restitution"])
            mesh = a.pcolormesh(d_um, V, e, cmap=cmap, norm=norm, shading="nearest", rasterized=True)
            cap = data[law]["capture_velocity"]
            a.plot(d_um, cap, color="black", linewidth=1.4, label="capture velocity $V_s$")
            vy = np.asarray(data[law]["yield_velocity"], dtype=float)
            vy = np.where(vy > 0.0, vy, np.nan)
            a.plot(d_um, vy, color="#D55E00", linewidth=1.2, linestyle="--", label="yield velocity $V_y$")
            other = [n for n in laws if n != law]
            if len(laws) == 2:
                a.plot(
                    d_um,
                    data[other[0]]["capture_velocity"],
                    color="0.6",
                    linewidth=0.9,
                    linestyle=":",
                    label="$V_s$ of the other law",
                )
            a.set_xscale("log")
            a.set_yscale("log")
            a.set_xlim(d_um.min(), d_um.max())
            a.set_ylim(V.min(), V.max())
            a.set_xlabel(axis_label("diameter", "Particle diameter"))
            a.set_title(LAW_LABELS.get(law) or _models.get(law).LABEL, fontsize=8)
            # the stick region always holds the lower left corner (V_s falls with d): clear of the curves
            a.text(0.03, 0.04, "stick", transform=a.transAxes, fontsize=8, color="0.2", ha="left", va="bottom")
            if np.any(np.asarray(data[law]["yield_velocity"]) == 0.0):
                k = int(np.flatnonzero(np.asarray(data[law]["yield_velocity"]) == 0.0).max())
                a.annotate(
                    "$V_y = 0$ to the left\n(yields at any speed)",
                    xy=(d_um[k], V.min()),
                    xytext=(8, 12),  # right of the curve's end, inside the axes (left of it is the y axis)
                    textcoords="offset points",
                    ha="left",
                    va="bottom",
                    fontsize=6.5,
                    color="#D55E00",
                    arrowprops={"arrowstyle": "->", "color": "#D55E00", "linewidth": 0.6, "shrinkA": 1, "shrinkB": 1},
                )
            a.text(0.96, 0.93, "bounce", transform=a.transAxes, fontsize=8, color="white", ha="right", va="top")
            if math.isfinite(d_part) and d_um.min() < d_part * 1e6 < d_um.max():
                a.axvline(d_part * 1e6, color="0.35", linewidth=0.6, linestyle="-.", zorder=3)
        for k, a in enumerate(axes):
            if k % min(len(laws), 3) == 0:  # the first panel of each row
                a.set_ylabel(axis_label("velocity", "Impact velocity"))
        axes[0].legend(loc="upper left", fontsize=6.5, framealpha=0.9)  # the lower left is the stick label's
        if mesh is not None:
            fig.colorbar(mesh, ax=list(axes), label=r"Coefficient of restitution, $e$", shrink=0.95, pad=0.01)
        part = (
            f"; capture velocities part by > 10 % below d = {d_part * 1e6:.3g} $\\mu$m"
            if math.isfinite(d_part)
            else ("; capture velocities within 10 % over the whole range" if both else "")
        )
        fig.suptitle(
            f"{pair.label or 'pair'}: $G$ = {work_of_adhesion:g} J/m$^2$, $E^*$ = {pair.effective_modulus / 1e9:.3g} GPa, "
            f"$p_y$ = {pair.limiting_pressure / 1e6:.3g} MPa{part}",
            fontsize=7.5,
        )
    return np.asarray(axes, dtype=object)
