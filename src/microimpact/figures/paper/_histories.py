"""The seed's Figs. 7 and 10, one impact in time: its force against the equivalent elastic impact's,
and its approach, velocity and force together."""

from __future__ import annotations

import numpy as np

from ... import contact, quantities
from .. import style as _style
from ._common import (
    concat_columns,
    default_pair,
    display_scale,
    groups_of,
)

__all__ = ["force_time_data", "plot_force_time", "dynamics_data", "plot_dynamics"]


# ----------------------------------------------------------------------------- Figs. 7 and 10
def _history(pair, velocity, n):
    if not hasattr(pair, "history"):
        raise NotImplementedError(
            "ContactPair.history is not available in this version of microimpact; Figs. 7 and 10 need it"
        )
    return pair.history(velocity, n=n)


def force_time_data(velocity=70.0, pair=None, n=1001) -> dict:
    """Data of Fig. 7: force against time, elastic-plastic against the equivalent elastic impact.

    ``series`` is ``'elastic-plastic'`` (``pair.history(V)``), ``'elastic'``
    (``pair.elastic_equivalent().history(V)``: no yielding) or ``'hertz'`` (the Hertz
    force ``4/3 E* R*^(1/2) alpha^(3/2)`` of the elastic-plastic approach during its
    loading, seed eq. 2).

    Parameters
    ----------
    velocity : float, optional
        Impact speed [m/s]; default 70 m/s.
    pair : ContactPair, optional
        The contact pair; default the seed's silicon case
        (:meth:`ContactPair.paper_case`).
    n : int, optional
        Points per history (default 1001).

    Returns
    -------
    dict of ndarray
        ``series``, ``time_s`` [s], ``approach_m`` [m], ``force_N`` [N].
    """
    pair = default_pair(pair)
    ep = _history(pair, float(velocity), n)
    el = _history(pair.elastic_equivalent(), float(velocity), n)
    loading = np.isin(np.asarray(ep.stage), (1, 2))
    t_load = np.asarray(ep.time, float)[loading]
    a_load = np.asarray(ep.approach, float)[loading]
    hertz = contact.hertz_force(a_load, pair.effective_modulus, pair.effective_radius)
    parts = []
    for name, t, a, P in (
        ("elastic-plastic", ep.time, ep.approach, ep.force),
        ("elastic", el.time, el.approach, el.force),
        ("hertz", t_load, a_load, hertz),
    ):
        t = np.asarray(t, float)
        parts.append(
            {
                "series": np.full(t.size, name, dtype=object),
                quantities.column("time"): t,
                quantities.column("approach"): np.asarray(a, float),
                quantities.column("force"): np.asarray(P, float),
            }
        )
    return concat_columns(parts)


def plot_force_time(velocity=70.0, ax=None, *, pair=None, table=None):
    """Fig. 7: contact force against time, elastic-plastic and equivalent elastic impacts.

    Parameters
    ----------
    velocity : float, optional
        Impact speed [m/s]; default 70 m/s.
    ax : matplotlib Axes, optional
        Axes to draw on; a new single-column figure if None.
    pair : ContactPair, optional
        The contact pair; default the seed's silicon case
        (:meth:`ContactPair.paper_case`).
    table : dict, optional
        Output of :func:`force_time_data` to draw.

    Returns
    -------
    matplotlib Axes
        The Axes drawn on.
    """
    if table is None:
        table = force_time_data(velocity, pair)
    labels = {
        "elastic-plastic": ("elastic–plastic impact", _style.COLORS[0], "-"),
        "elastic": ("equivalent elastic impact", _style.COLORS[2], "--"),
        "hertz": (r"Hertz force at the same $\alpha$ (loading)", _style.COLORS[1], "-."),
    }
    with _style.style():
        ax = _style.new_axes(ax)
        t = np.asarray(table[quantities.column("time")], float) * display_scale("time")
        P = np.asarray(table[quantities.column("force")], float) * display_scale("force")
        for name, m in groups_of(table, "series"):
            label, color, ls = labels.get(name, (name, "0.5", ":"))
            ax.plot(t[m], P[m], color=color, linestyle=ls, label=label)
        ax.set_xlim(0.0, float(t.max()) * 1.02)
        ax.set_ylim(0.0, float(P.max()) * 1.35)
        ax.set_xlabel(quantities.axis_label("time", "time"))
        ax.set_ylabel(quantities.axis_label("force", "contact force"))
        ax.legend(loc="upper right")
    return ax


def dynamics_data(velocity=50.0, pair=None, n=1001) -> dict:
    """Data of Fig. 10: approach velocity, force and approach against time for one impact.

    Parameters
    ----------
    velocity : float, optional
        Impact speed [m/s]; default 50 m/s.
    pair : ContactPair, optional
        The contact pair; default the seed's silicon case
        (:meth:`ContactPair.paper_case`).
    n : int, optional
        Points of the history (default 1001).

    Returns
    -------
    dict of ndarray
        ``time_s`` [s], ``approach_velocity_m_s`` [m/s], ``force_N`` [N],
        ``approach_m`` [m], ``stage`` (exactly ``pair.history(velocity, n=n)``).
    """
    pair = default_pair(pair)
    h = _history(pair, float(velocity), n)
    return {
        quantities.column("time"): np.asarray(h.time, float),
        quantities.column("approach_velocity"): np.asarray(h.approach_velocity, float),
        quantities.column("force"): np.asarray(h.force, float),
        quantities.column("approach"): np.asarray(h.approach, float),
        "stage": np.asarray(h.stage, dtype=int),
    }


def plot_dynamics(velocity=50.0, ax=None, *, pair=None, table=None):
    """Fig. 10: approach velocity, contact force and approach against time, in three stacked panels.

    Parameters
    ----------
    velocity : float, optional
        Impact speed [m/s]; default 50 m/s.
    ax : sequence of three matplotlib Axes, optional
        Panels for velocity, force and approach; default a new figure.
    pair : ContactPair, optional
        The contact pair; default the seed's silicon case
        (:meth:`ContactPair.paper_case`).
    table : dict, optional
        Output of :func:`dynamics_data` to draw.

    Returns
    -------
    ndarray of three matplotlib Axes
        The velocity, force and approach panels.
    """
    if table is None:
        table = dynamics_data(velocity, pair)
    with _style.style() as plt:
        if ax is None:
            fig, axes = plt.subplots(3, 1, sharex=True, figsize=(_style.FIGSIZE[0], 4.2), layout="constrained")
        else:
            axes = np.asarray(ax, dtype=object).ravel()
            if axes.size != 3:
                raise ValueError(f"ax must be three Axes (velocity, force, approach), got {axes.size}")
        t = np.asarray(table[quantities.column("time")], float) * display_scale("time")
        stage = np.asarray(table["stage"], int)
        series = [
            (
                quantities.column("approach_velocity"),
                display_scale("approach_velocity"),
                quantities.axis_label("approach_velocity", "velocity"),
            ),
            (quantities.column("force"), display_scale("force"), quantities.axis_label("force", "force")),
            (quantities.column("approach"), display_scale("approach"), quantities.axis_label("approach")),
        ]
        stage_style = {
            1: ("stage 1: Hertz loading", _style.COLORS[2], "-"),
            2: ("stage 2: plastic loading", _style.COLORS[1], "--"),
            3: ("stage 3: elastic unloading", _style.COLORS[3], "-."),
        }
        for a_, (col, scale, ylabel) in zip(axes, series):
            y = np.asarray(table[col], float) * scale
            for s, (label, color, ls) in stage_style.items():
                m = stage == s
                if not m.any():
                    continue
                # include the first point of the next stage so the curve is continuous
                idx = np.flatnonzero(m)
                idx = np.append(idx, idx[-1] + 1) if idx[-1] + 1 < t.size else idx
                a_.plot(t[idx], y[idx], color=color, linestyle=ls, label=label)
            a_.set_ylabel(ylabel)
            a_.set_xlim(0.0, float(t.max()))
        axes[0].axhline(0.0, color="0.6", linewidth=0.5, zorder=0)
        axes[1].set_ylim(bottom=0.0)
        axes[2].set_ylim(bottom=0.0)
        axes[-1].set_xlabel(quantities.axis_label("time", "time"))
        axes[0].legend(loc="lower left")
    return np.asarray(axes, dtype=object)
