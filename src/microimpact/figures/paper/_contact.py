"""The seed's Figs. 6, 8 and 9, each against impact speed or approach: force against displacement,
the maximum and plastic approaches, and the contact times."""

from __future__ import annotations

import math

import numpy as np

from ... import quantities
from ...core.constants import LARGE_STRAIN_RATIO
from .. import style as _style
from ._common import (
    V_LABEL,
    concat_columns,
    default_pair,
    display_scale,
    groups_of,
    legend_label,
    speed_grid,
)

__all__ = [
    "force_displacement_data",
    "plot_force_displacement",
    "approach_data",
    "plot_approach",
    "contact_time_data",
    "plot_contact_times",
]


# ----------------------------------------------------------------------------- Fig. 6
def force_displacement_data(velocities=(30.0, 50.0, 70.0), pair=None, n=201) -> dict:
    """Data of Fig. 6: force against approach, loading and unloading branches.

    Loading from 0 to ``alpha*`` (``pair.force(alpha)``: Hertz then plastic, seed eqs. 2, 8;
    ``alpha_y`` is one of the points), unloading from ``alpha*`` down to ``alpha_p``
    (``pair.force(alpha, max_approach=alpha*)``, eq. 10), ``n`` points each.

    Parameters
    ----------
    velocities : sequence of float, optional
        Impact speeds [m/s], one pair of branches each; default 30, 50, 70 m/s (the seed's Fig. 6).
    pair : ContactPair, optional
        The contact pair; default the seed's silicon case
        (:meth:`ContactPair.paper_case`).
    n : int, optional
        Points per branch (default 201).

    Returns
    -------
    dict of ndarray
        ``velocity_m_s`` [m/s], ``branch``, ``approach_m`` [m], ``force_N`` [N],
        ``max_approach_m``, ``plastic_approach_m`` [m] (the last two repeat
        ``pair.impact(V)`` on every row).
    """
    pair = default_pair(pair)
    a_y = pair.yield_approach if math.isfinite(pair.limiting_pressure) else math.inf
    parts = []
    for V in np.atleast_1d(np.asarray(velocities, dtype=float)):
        out = pair.impact(float(V), warn=False)
        a_star, a_p = float(out.max_approach), float(out.plastic_approach)
        load = np.linspace(0.0, a_star, n)
        if 0.0 < a_y < a_star:
            load = np.unique(np.concatenate([load, [a_y]]))
        unload = np.linspace(a_star, a_p, n)
        for branch, alpha, force in (
            ("loading", load, pair.force(load)),
            ("unloading", unload, pair.force(unload, max_approach=a_star)),
        ):
            k = alpha.size
            parts.append(
                {
                    quantities.column("velocity"): np.full(k, float(V)),
                    "branch": np.full(k, branch, dtype=object),
                    quantities.column("approach"): alpha,
                    quantities.column("force"): np.asarray(force, float),
                    quantities.column("max_approach"): np.full(k, a_star),
                    quantities.column("plastic_approach"): np.full(k, a_p),
                }
            )
    return concat_columns(parts)


def plot_force_displacement(velocities=(30.0, 50.0, 70.0), ax=None, *, pair=None, table=None, **kws):
    """Fig. 6: contact force against approach at several impact speeds.

    Solid: loading (Hertz, then plastic, seed eqs. 2, 8); dashed: elastic unloading with
    the flattened radius ``R_p`` (eq. 10). A marker on the axis labels each plastic
    approach ``alpha_p`` (eq. 11).

    Parameters
    ----------
    velocities : sequence of float, optional
        Impact speeds [m/s]; default 30, 50, 70 m/s.
    ax : matplotlib Axes, optional
        Axes to draw on; a new single-column figure if None.
    pair : ContactPair, optional
        The contact pair; default the seed's silicon case
        (:meth:`ContactPair.paper_case`).
    table : dict, optional
        Output of :func:`force_displacement_data` to draw.
    **kws
        Passed to ``ax.plot`` for the curves.

    Returns
    -------
    matplotlib Axes
        The Axes drawn on.
    """
    if table is None:
        table = force_displacement_data(velocities, pair)
    pair = default_pair(pair)
    with _style.style():
        ax = _style.new_axes(ax)
        branch = np.asarray(table["branch"])
        a = np.asarray(table[quantities.column("approach")], float) * display_scale("approach")
        P = np.asarray(table[quantities.column("force")], float) * display_scale("force")
        for i, (V, m) in enumerate(groups_of(table, quantities.column("velocity"))):
            c = _style.COLORS[i % len(_style.COLORS)]
            lo, un = m & (branch == "loading"), m & (branch == "unloading")
            ax.plot(a[lo], P[lo], color=c, linestyle="-", label=f"V = {V:g} m/s", **kws)
            ax.plot(a[un], P[un], color=c, linestyle="--", **kws)
            a_p = float(np.asarray(table[quantities.column("plastic_approach")], float)[m][0]) * display_scale(
                "plastic_approach"
            )
            ax.plot([a_p], [0.0], marker="v", markersize=4, color=c, clip_on=False, zorder=5)
            ax.annotate(
                f"{a_p:.1f}",
                (a_p, 0.0),
                xytext=(0, 5),
                textcoords="offset points",
                ha="center",
                va="bottom",
                fontsize=6,
                color=c,
            )
        ax.plot([], [], color="0.3", linestyle="-", label="loading")
        ax.plot([], [], color="0.3", linestyle="--", label="unloading")
        ax.plot(
            [],
            [],
            color="0.3",
            linestyle="none",
            marker="v",
            markersize=4,
            label=legend_label("plastic approach", "plastic_approach"),
        )
        ax.set_xlim(0.0, float(a.max()) * 1.05)
        ax.set_ylim(0.0, float(P.max()) * 1.08)
        # a*/R* > 0.3 <=> alpha > 0.09 R*
        _style.shade_large_strain(
            ax,
            LARGE_STRAIN_RATIO**2 * pair.effective_radius * display_scale("approach"),
            label=True,
            text_xy=(0.985, 0.06),
        )
        ax.set_xlabel(quantities.axis_label("approach"))
        ax.set_ylabel(quantities.axis_label("force", "contact force"))
        ax.legend(loc="upper left")
    return ax


# ----------------------------------------------------------------------------- Fig. 8
def approach_data(pair=None, velocity=None) -> dict:
    """Data of Fig. 8: maximum approach ``alpha*`` and ``alpha_p/alpha*`` against impact speed.

    Parameters
    ----------
    pair : ContactPair, optional
        The contact pair; default the seed's silicon case
        (:meth:`ContactPair.paper_case`).
    velocity : array_like, optional
        Impact speeds [m/s]; default 0.25-120 m/s plus ``V_y``.

    Returns
    -------
    dict of ndarray
        ``velocity_m_s`` [m/s], ``max_approach_m`` [m], ``plastic_approach_m`` [m],
        ``plastic_ratio`` ``alpha_p/alpha*`` [-], ``large_strain``.
    """
    pair = default_pair(pair)
    V = speed_grid(velocity, pair.yield_velocity, start=0.25, num=479)
    out = pair.impact(V, warn=False)
    a_star = np.asarray(out.max_approach, float).ravel()
    a_p = np.asarray(out.plastic_approach, float).ravel()
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(a_star > 0, a_p / np.where(a_star > 0, a_star, 1.0), 0.0)
    return {
        quantities.column("velocity"): np.asarray(out.velocity, float).ravel(),
        quantities.column("max_approach"): a_star,
        quantities.column("plastic_approach"): a_p,
        "plastic_ratio": ratio,
        "large_strain": np.asarray(out.large_strain, dtype=int).ravel(),
    }


def plot_approach(pair=None, ax=None, *, velocity=None, table=None):
    """Fig. 8: maximum approach (left axis) and the plastic share ``alpha_p/alpha*`` (right axis).

    Parameters
    ----------
    pair : ContactPair, optional
        The contact pair; default the seed's silicon case
        (:meth:`ContactPair.paper_case`).
    ax : matplotlib Axes, optional
        Axes to draw on; a new single-column figure if None.
    velocity : array_like, optional
        Impact speeds [m/s], as :func:`approach_data`.
    table : dict, optional
        Output of :func:`approach_data` to draw.

    Returns
    -------
    matplotlib Axes
        The left Axes; the right one is ``ax.right_ax``.
    """
    if table is None:
        table = approach_data(pair, velocity)
    with _style.style():
        ax = _style.new_axes(ax)
        V = np.asarray(table[quantities.column("velocity")], float)
        c0, c1 = _style.COLORS[0], _style.COLORS[2]
        (l0,) = ax.plot(
            V,
            np.asarray(table[quantities.column("max_approach")], float) * display_scale("max_approach"),
            color=c0,
            linestyle="-",
            label=r"maximum approach $\alpha^*$",
        )
        ax.tick_params(axis="y", right=False)
        right = ax.twinx()
        (l1,) = right.plot(
            V,
            np.asarray(table["plastic_ratio"], float),
            color=c1,
            linestyle="--",
            label=r"plastic share $\alpha_p/\alpha^*$",
        )
        right.tick_params(axis="y", colors=c1, direction="in")
        right.spines["right"].set_color(c1)
        right.set_ylim(0.0, 1.0)
        ax.set_ylim(bottom=0.0)
        ax.set_xlim(0.0, float(V.max()))
        ls = np.asarray(table["large_strain"]).astype(bool)
        if ls.any():
            _style.shade_large_strain(ax, float(V[ls].min()), text_xy=(0.985, 0.06))
        ax.set_xlabel(V_LABEL)
        ax.set_ylabel(quantities.axis_label("max_approach"))
        right.set_ylabel(quantities.axis_label("plastic_ratio"), color=c1)
        ax.legend(handles=[l0, l1], loc="upper left")
        ax.right_ax = right
    return ax


# ----------------------------------------------------------------------------- Fig. 9
def contact_time_data(pair=None, velocity=None) -> dict:
    """Data of Fig. 9: stage, loading, unloading and contact times against impact speed.

    Parameters
    ----------
    pair : ContactPair, optional
        The contact pair; default the seed's silicon case
        (:meth:`ContactPair.paper_case`).
    velocity : array_like, optional
        Impact speeds [m/s]; default 2-120 m/s plus ``V_y``.

    Returns
    -------
    dict of ndarray
        ``velocity_m_s`` [m/s]; ``elastic_stage_time_s`` ``t1``, ``plastic_stage_time_s`` ``t2``,
        ``loading_time_s`` ``t_L``, ``unloading_time_s`` ``t_U``, ``contact_time_s`` ``t_c``
        [s] (``pair.impact``, seed eqs. 20, 23, 26, 32, 33); ``deresiewicz_time_s`` [s]
        (eq. 30, ``pair.deresiewicz_contact_time``), ``ning_loading_time_s`` [s]
        (eq. 31, ``pair.ning_loading_time()``), ``yield_velocity_m_s`` [m/s],
        ``large_strain``.
    """
    pair = default_pair(pair)
    V = speed_grid(velocity, pair.yield_velocity, start=2.0, num=473)
    out = pair.impact(V, warn=False)
    n = V.size
    cols = {quantities.column("velocity"): np.asarray(out.velocity, float).ravel()}
    for name in ("elastic_stage_time", "plastic_stage_time", "loading_time", "unloading_time", "contact_time"):
        cols[quantities.column(name)] = np.asarray(getattr(out, name), float).ravel()
    cols[quantities.column("deresiewicz_time")] = np.asarray(pair.deresiewicz_contact_time(V), float).ravel()
    cols[quantities.column("ning_loading_time")] = np.full(n, pair.ning_loading_time())
    cols[quantities.column("yield_velocity")] = np.full(n, pair.yield_velocity)
    cols["large_strain"] = np.asarray(out.large_strain, dtype=int).ravel()
    return cols


def _yield_velocity_of(table):
    """``V_y`` of the table if it lies inside its speed range, else ``None``."""
    if quantities.column("yield_velocity") not in table:
        return None
    Vy = float(np.asarray(table[quantities.column("yield_velocity")], float)[0])
    V = np.asarray(table[quantities.column("velocity")], float)
    return Vy if V.min() < Vy < V.max() else None


_TIME_SERIES = [
    (quantities.column("contact_time"), r"$t_c$ (eq. 33)", "#000000", "-"),
    (quantities.column("loading_time"), r"$t_L$ (eq. 32)", "#0072B2", "-"),
    (quantities.column("unloading_time"), r"$t_U$ (eq. 26)", "#D55E00", "--"),
    (quantities.column("elastic_stage_time"), r"$t_1$ (eq. 20)", "#009E73", "-."),
    (quantities.column("plastic_stage_time"), r"$t_2$ (eq. 23)", "#CC79A7", (0, (5, 1.5, 1, 1.5, 1, 1.5))),
    (quantities.column("deresiewicz_time"), "Deresiewicz, eq. 30", "#E69F00", ":"),
    (quantities.column("ning_loading_time"), "Ning, eq. 31", "#56B4E9", (0, (1, 1))),
]


def plot_contact_times(pair=None, ax=None, *, velocity=None, table=None):
    """Fig. 9: contact times ``t1, t2, t_L, t_U, t_c`` against impact speed, with seed eqs. 30 and 31.

    Parameters
    ----------
    pair : ContactPair, optional
        The contact pair; default the seed's silicon case
        (:meth:`ContactPair.paper_case`).
    ax : matplotlib Axes, optional
        Axes to draw on; a new single-column figure if None.
    velocity : array_like, optional
        Impact speeds [m/s], as :func:`contact_time_data`.
    table : dict, optional
        Output of :func:`contact_time_data` to draw.

    Returns
    -------
    matplotlib Axes
        The Axes drawn on.
    """
    if table is None:
        table = contact_time_data(pair, velocity)
    with _style.style():
        ax = _style.new_axes(ax)
        V = np.asarray(table[quantities.column("velocity")], float)
        for col, label, color, ls in _TIME_SERIES:
            lw = 1.6 if col == quantities.column("ning_loading_time") else None
            ax.plot(
                V,
                np.asarray(table[col], float) * display_scale("contact_time"),
                color=color,
                linestyle=ls,
                label=label,
                **({"linewidth": lw} if lw else {}),
            )
        ax.set_xlim(0.0, float(V.max()))
        Vy = _yield_velocity_of(table)
        if Vy is not None:
            ax.axvline(Vy, color="0.55", linewidth=0.6, linestyle=(0, (2, 2)), zorder=0)
            ax.annotate(
                r"$V_y$",
                (Vy, 0.0),
                xytext=(2, 2),
                textcoords="offset points",
                xycoords=("data", "axes fraction"),
                fontsize=6.5,
                color="0.35",
            )
        ymax = float(np.nanmax(np.asarray(table[quantities.column("contact_time")], float))) * display_scale(
            "contact_time"
        )
        ax.set_ylim(0.0, ymax * 1.4)
        ls = np.asarray(table["large_strain"]).astype(bool)
        if ls.any():
            _style.shade_large_strain(ax, float(V[ls].min()), label=True, text_xy=(0.985, 0.66))
        ax.set_xlabel(V_LABEL)
        ax.set_ylabel(r"Time (ns)")
        ax.legend(loc="upper right", ncol=2, columnspacing=1.0, handlelength=2.8)
    return ax
