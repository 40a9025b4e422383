"""Plot of one impact's time history: velocity, force and approach against time (seed Fig. 10).

:func:`plot_history` draws an :class:`~microimpact.dynamics.ImpactHistory` (from
:meth:`ContactPair.history <microimpact.pair.ContactPair.history>`) as three stacked
panels sharing the time axis, with the three contact stages shaded and their
boundaries ``t1`` (yield) and ``t_L`` (maximum approach) marked. matplotlib (the
``plot`` extra) is imported only when the function is called.
"""

from __future__ import annotations

import math

import numpy as np

from .._optional import require

__all__ = ["plot_history", "STAGE_COLORS"]

#: Light fills of the three stages (Okabe & Ito colours: sky blue, orange, bluish green).
STAGE_COLORS = {1: "#56B4E9", 2: "#E69F00", 3: "#009E73"}

_PREFIXES = [
    (1e-15, "f"),
    (1e-12, "p"),
    (1e-9, "n"),
    (1e-6, "µ"),
    (1e-3, "m"),
    (1.0, ""),
    (1e3, "k"),
    (1e6, "M"),
    (1e9, "G"),
]

_RC = {
    "font.size": 8,
    "axes.labelsize": 8,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "legend.fontsize": 7,
    "legend.frameon": False,
    "lines.linewidth": 1.3,
    "axes.linewidth": 0.6,
    "xtick.major.width": 0.6,
    "ytick.major.width": 0.6,
    "xtick.direction": "in",
    "ytick.direction": "in",
    "xtick.top": True,
    "ytick.right": True,
    "mathtext.default": "regular",
    "pdf.fonttype": 42,
    "svg.fonttype": "none",
}


def _prefix(values, unit):
    """Scale factor and unit with an SI prefix so that the largest ``|value|`` lies in [1, 1000)."""
    big = float(np.nanmax(np.abs(values))) if np.size(values) else 0.0
    if not (big > 0 and math.isfinite(big)):
        return 1.0, unit
    chosen = _PREFIXES[0]
    for factor, prefix in _PREFIXES:
        if big >= factor:
            chosen = (factor, prefix)
    return 1.0 / chosen[0], chosen[1] + unit


def _get(history, name):
    return history[name] if isinstance(history, dict) else getattr(history, name)


def plot_history(history, ax=None, *, show_stages=True, show_hertz=False, title=True, line_kws=None):
    """Approach velocity, contact force and approach against time for one impact (seed Fig. 10).

    Parameters
    ----------
    history : ImpactHistory or dict
        From :meth:`ContactPair.history`, :func:`~microimpact.dynamics.impact_history`
        or :func:`~microimpact.dynamics.integrate_impact`.
    ax : sequence of three matplotlib Axes, optional
        Panels for velocity, force and approach (top to bottom); default a new
        figure with three stacked panels sharing the time axis.
    show_stages : bool
        Shade the three contact stages and mark their boundaries ``t1`` and ``t_L`` (the seed's
        model and LIGGGHTS' version of it); for the other models, loading and unloading.
    show_hertz : bool
        Also draw, in the force panel, the Hertz force of the same approach during
        loading (the seed's Fig. 7 comparison,
        :func:`~microimpact.dynamics.hertz_force_along`).
    title : bool or str
        A title on the top panel: True gives the impact and rebound speeds.
    line_kws : dict, optional
        Keyword arguments for the curves (``color``, ``linewidth``, ...).

    Returns
    -------
    ndarray of three matplotlib Axes
        Velocity, force and approach panels.

    Examples
    --------
    >>> import microimpact as mi
    >>> from microimpact.figures.history import plot_history
    >>> axes = plot_history(mi.ContactPair.paper_case("silicon").history(50.0))  # doctest: +SKIP
    >>> axes[0].figure.savefig("history.png", dpi=300)  # doctest: +SKIP
    """
    plt = require("matplotlib.pyplot", "plotting")
    from matplotlib.patches import Patch

    from ..dynamics import hertz_force_along, stage_names

    t = np.asarray(_get(history, "time"), dtype=float)
    order = np.argsort(t, kind="stable")
    t = t[order]
    vel = np.asarray(_get(history, "approach_velocity"), dtype=float)[order]
    force = np.asarray(_get(history, "force"), dtype=float)[order]
    alpha = np.asarray(_get(history, "approach"), dtype=float)[order]
    t1 = float(_get(history, "elastic_stage_time"))
    tL = float(_get(history, "loading_time"))
    tc = float(_get(history, "contact_time"))
    V = float(_get(history, "velocity"))
    Vr = float(_get(history, "rebound_velocity"))
    a_p = float(_get(history, "plastic_approach"))
    model = history.get("model") if isinstance(history, dict) else getattr(history, "model", None)
    stages = stage_names(model)
    seed_stages = 2 in stages  # a second loading stage: the seed's three, numbered
    labels = (
        {k: f"{k}: {v.split(' (')[0]}" for k, v in stages.items() if k} if seed_stages else stages
    )  # other laws: loading, unloading
    plastic = seed_stages and t1 < tL

    kws = {"color": "black", "linewidth": 1.3}
    kws.update(line_kws or {})
    ts, tunit = _prefix(np.r_[t, tc], "s")
    fs, funit = _prefix(force, "N")
    as_, aunit = _prefix(alpha, "m")

    with plt.rc_context(_RC):
        if ax is None:
            fig, axes = plt.subplots(3, 1, sharex=True, figsize=(3.5, 4.6), layout="constrained")
        else:
            axes = np.asarray(ax, dtype=object).ravel()
            if axes.size != 3:
                raise ValueError(f"ax must be three Axes (velocity, force, approach), got {axes.size}")
        a_v, a_f, a_a = axes

        a_v.plot(t * ts, vel, **kws)
        a_v.axhline(0.0, color="0.55", linewidth=0.5, zorder=1)
        a_v.set_ylabel(r"Velocity, $d\alpha/dt$ (m/s)")
        a_v.set_ylim(-1.12 * max(V, Vr), 1.12 * max(V, Vr))

        a_f.plot(t * ts, force * fs, label="contact force", **kws)
        if show_hertz:
            hz = hertz_force_along(
                {
                    "approach": alpha,
                    "stage": np.asarray(_get(history, "stage"))[order],
                    "effective_modulus": _get(history, "effective_modulus"),
                    "effective_radius": _get(history, "effective_radius"),
                }
            )
            a_f.plot(
                t * ts,
                hz * fs,
                color="#D55E00",
                linestyle="--",
                linewidth=1.1,
                label=r"Hertz force at the same $\alpha$",
            )
            a_f.legend(
                loc="upper right",
                fontsize=6.5,
                handlelength=2.2,
                frameon=True,
                framealpha=0.85,
                edgecolor="none",
                borderaxespad=0.3,
            )
            top = 1.3 * max(float(np.nanmax(force)), float(np.nanmax(hz, initial=0.0))) * fs
        else:
            top = 1.1 * float(np.nanmax(force)) * fs
        a_f.set_ylabel(f"Force, $P$ ({funit})")
        a_f.set_ylim(bottom=0.0, top=top if top > 0 else None)

        a_a.plot(t * ts, alpha * as_, **kws)
        a_a.set_ylabel(rf"Approach, $\alpha$ ({aunit})")
        if plastic and a_p > 0:
            a_a.axhline(a_p * as_, color="0.45", linewidth=0.7, linestyle=":")
            a_a.annotate(
                rf"$\alpha_p$ = {a_p * as_:.4g} {aunit}",
                xy=(min(t[-1], tc) * ts, a_p * as_),
                xytext=(-3, -3),
                textcoords="offset points",
                ha="right",
                va="top",
                fontsize=6.5,
                color="0.3",
            )
        a_a.set_ylim(bottom=min(0.0, float(np.nanmin(alpha * as_))), top=1.1 * float(np.nanmax(alpha * as_)))
        a_a.set_xlabel(f"Time, $t$ ({tunit})")
        a_a.set_xlim(float(t[0] * ts), float(t[-1] * ts))

        if show_stages:
            spans = [(1, 0.0, t1), (2, t1, tL), (3, tL, tc)] if plastic else [(1, 0.0, tL), (3, tL, tc)]
            for a_ in axes:
                for s, lo, hi in spans:
                    a_.axvspan(lo * ts, hi * ts, color=STAGE_COLORS[s], alpha=0.16, linewidth=0, zorder=0)
                for b in [t1, tL] if plastic else [tL]:
                    a_.axvline(b * ts, color="0.45", linewidth=0.6, linestyle="--", zorder=1)
            names = [(t1, r"$t_1$"), (tL, r"$t_L$")] if plastic else [(tL, r"$t_L$")]
            for b, name in names:
                a_v.annotate(
                    name,
                    xy=(b * ts, 1.0),
                    xycoords=("data", "axes fraction"),
                    xytext=(0, 2),
                    textcoords="offset points",
                    ha="center",
                    va="bottom",
                    fontsize=7,
                )
            handles = [Patch(facecolor=STAGE_COLORS[s], alpha=0.35, linewidth=0, label=labels[s]) for s, _, _ in spans]
            a_v.legend(
                handles=handles,
                loc="lower left",
                fontsize=6.5,
                handlelength=1.2,
                title="stage",
                title_fontsize=6.5,
                alignment="left",
                frameon=True,
                framealpha=0.85,
                edgecolor="none",
            )

        if title:
            text = (
                title
                if isinstance(title, str)
                else (f"$V$ = {V:.4g} m/s, $V_r$ = {Vr:.4g} m/s, $t_c$ = {tc * ts:.4g} {tunit}")
            )
            if title is True and not seed_stages:
                text = f"{model}\n{text}"
            a_v.set_title(text, fontsize=7.5, pad=12 if show_stages else 4)
        for a_ in axes:
            a_.minorticks_on()
    return np.asarray(axes, dtype=object)
