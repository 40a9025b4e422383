"""The seed's Figs. 2-5: the restitution coefficient against impact speed, and the energy loss as
the limiting pressure, the particle's modulus or its density changes."""

from __future__ import annotations

import math

import numpy as np

from ... import quantities
from ...pair import ContactPair
from .. import style as _style
from ._common import (
    ENERGY_LOSS_PARAMETERS,
    V_LABEL,
    VMAX,
    concat_columns,
    default_pair,
    fmt_value,
    groups_of,
    speed_grid,
)

__all__ = ["restitution_data", "plot_restitution", "energy_loss_data", "plot_energy_loss"]


# ----------------------------------------------------------------------------- Fig. 2
def _paper_pairs(pairs):
    if pairs is None:
        return {"silicon": ContactPair.paper_case("silicon"), "mica": ContactPair.paper_case("mica")}
    if isinstance(pairs, ContactPair):
        return {pairs.label or "model": pairs}
    return dict(pairs)


def restitution_data(pairs=None, data=None, velocity=None) -> dict:
    """Data of Fig. 2: restitution against impact speed, model curves and measurements.

    Parameters
    ----------
    pairs : dict of str -> ContactPair, optional
        Model curves; default the seed's silicon and mica cases.
    data : dict of str -> (velocity, restitution), optional
        Measured points [m/s], [-] to show beside the model (e.g. from
        :func:`microimpact.paper.load_measurements`).
    velocity : array_like, optional
        Speeds of the model curves [m/s]; default 1-120 m/s, log spaced, plus each ``V_y``.

    Returns
    -------
    dict of ndarray
        ``series``, ``kind`` ('model' or 'measured'), ``velocity_m_s`` [m/s],
        ``restitution`` [-], ``yield_velocity_m_s`` [m/s] (NaN for measured points),
        ``large_strain`` (0 for measured points).
    """
    parts = []
    for name, pair in _paper_pairs(pairs).items():
        Vy = pair.yield_velocity
        if velocity is None:
            V = np.unique(np.concatenate([np.geomspace(1.0, VMAX, 400), [Vy] if 1 < Vy < VMAX else []]))
        else:
            V = np.atleast_1d(np.asarray(velocity, dtype=float))
        out = pair.impact(V, warn=False)
        n = V.size
        parts.append(
            {
                "series": np.full(n, str(name), dtype=object),
                "kind": np.full(n, "model", dtype=object),
                quantities.column("velocity"): np.asarray(out.velocity, dtype=float).ravel(),
                "restitution": np.asarray(out.restitution, dtype=float).ravel(),
                quantities.column("yield_velocity"): np.full(n, Vy),
                "large_strain": np.asarray(out.large_strain, dtype=int).ravel(),
            }
        )
    for name, (V, e) in (data or {}).items():
        V = np.atleast_1d(np.asarray(V, dtype=float))
        e = np.atleast_1d(np.asarray(e, dtype=float))
        if V.shape != e.shape:
            raise ValueError(f"data[{name!r}]: velocity and restitution differ in length ({V.size} vs {e.size})")
        n = V.size
        parts.append(
            {
                "series": np.full(n, str(name), dtype=object),
                "kind": np.full(n, "measured", dtype=object),
                quantities.column("velocity"): V,
                "restitution": e,
                quantities.column("yield_velocity"): np.full(n, np.nan),
                "large_strain": np.zeros(n, dtype=int),
            }
        )
    return concat_columns(parts)


def plot_restitution(pairs=None, data=None, ax=None, *, velocity=None, table=None, logx=True, **kws):
    """Fig. 2: coefficient of restitution against impact speed (seed eq. 27).

    Parameters
    ----------
    pairs : dict of str -> ContactPair, optional
        Model curves, as :func:`restitution_data` (default: the seed's silicon and mica cases).
    data : dict of str -> (velocity, restitution), optional
        Measured points [m/s], [-], as :func:`restitution_data`.
    ax : matplotlib Axes, optional
        Axes to draw on; a new single-column figure if None.
    velocity : array_like, optional
        Speeds of the model curves [m/s], as :func:`restitution_data`.
    table : dict, optional
        Output of :func:`restitution_data` to draw instead of computing it.
    logx : bool
        Logarithmic speed axis (default), which shows the elastic plateau and the decay.
    **kws
        Passed to ``ax.plot`` for the model curves.

    Returns
    -------
    matplotlib Axes
        The Axes drawn on.
    """
    if table is None:
        table = restitution_data(pairs, data, velocity)
    with _style.style():
        ax = _style.new_axes(ax)
        kind = np.asarray(table["kind"])
        V, e = np.asarray(table[quantities.column("velocity")], float), np.asarray(table["restitution"], float)
        i_model = i_meas = 0
        model_colors = {}
        onset = math.inf
        keys = {"series_kind": np.array([f"{s}\x00{k}" for s, k in zip(table["series"], kind)], dtype=object)}
        for key, m in groups_of(keys, "series_kind"):
            name = key.split("\x00")[0]
            if kind[m][0] == "model":
                Vy = float(np.asarray(table[quantities.column("yield_velocity")], float)[m][0])
                st = {**_style.series_style(i_model), **kws}
                model_colors[name] = st["color"]
                ax.plot(V[m], e[m], label=f"{name} (model, $V_y$ = {Vy:.2f} m/s)", **st)
                ls = np.asarray(table["large_strain"])[m].astype(bool)
                if ls.any():
                    onset = min(onset, float(V[m][ls].min()))
                i_model += 1
            else:
                # the colour of the model curve of the same name, else one no model uses
                c = model_colors.get(name, _style.COLORS[(len(model_colors) + i_meas) % len(_style.COLORS)])
                ax.plot(
                    V[m],
                    e[m],
                    linestyle="none",
                    marker=_style.MARKERS[i_meas % len(_style.MARKERS)],
                    markersize=3.5,
                    markerfacecolor="none",
                    markeredgecolor=c,
                    markeredgewidth=0.8,
                    label=f"{name} (measured)",
                )
                i_meas += 1
        if logx:
            ax.set_xscale("log")
        ax.set_xlim(1.0 if logx else 0.0, VMAX)
        top = max(1.05, float(np.nanmax(e)) + 0.05) if e.size else 1.05
        ax.set_ylim(0.0, top)
        if math.isfinite(onset):
            _style.shade_large_strain(ax, onset, label=False)
            ax.plot(
                [],
                [],
                linestyle="none",
                marker="s",
                markersize=6,
                markerfacecolor="none",
                markeredgecolor="0.75",
                label=r"$a^*/R^* > 0.3$ (outside small strain)",
            )
        ax.set_xlabel(V_LABEL)
        ax.set_ylabel(quantities.axis_label("restitution"))
        ax.legend(loc="lower left")
    return ax


# ----------------------------------------------------------------------------- Figs. 3-5
def _pair_with(pair, parameter, value, particle_poisson, surface_modulus, surface_poisson):
    """``pair`` with one input changed (:meth:`ContactPair.vary`), and the extra columns that describe it."""
    if parameter == "particle_modulus":
        p = pair.vary(
            particle_modulus=value,
            particle_poisson=particle_poisson,
            surface_modulus=surface_modulus,
            surface_poisson=surface_poisson,
        )
        return p, {quantities.column("effective_modulus"): p.effective_modulus}
    return pair.vary(**{parameter: value}), {}


def energy_loss_data(
    parameter, values, pair=None, velocity=None, *, particle_poisson=0.3, surface_modulus=150e9, surface_poisson=0.3
) -> dict:
    """Data of Figs. 3-5: fraction of energy lost (eq. 29) against impact speed, one curve per value.

    Parameters
    ----------
    parameter : {'limiting_pressure', 'particle_modulus', 'effective_modulus', 'density'}
        The swept input (``p_y`` [Pa], ``E1`` [Pa], ``E*`` [Pa], ``rho`` [kg/m^3]).
        For ``'particle_modulus'`` the effective modulus is
        ``E* = 1/((1-nu1^2)/E1 + (1-nu2^2)/E2)`` with ``particle_poisson`` ``nu1``,
        ``surface_modulus`` ``E2`` [Pa] and ``surface_poisson`` ``nu2`` (the seed's Fig. 4:
        E2 = 150 GPa; nu = 0.3 both). ``'density'`` changes the mass of a sphere on a flat.
    values : sequence of float
        Values of the parameter, one curve each.
    pair : ContactPair, optional
        The other inputs; default the seed's silicon case.
    velocity : array_like, optional
        Speeds [m/s]; default 0-120 m/s (481 points) plus each curve's ``V_y``.

    Returns
    -------
    dict of ndarray
        ``<parameter column>`` (e.g. ``limiting_pressure_Pa``), ``velocity_m_s``,
        ``energy_loss``, ``restitution``, ``yield_velocity_m_s``, ``large_strain``, and
        ``effective_modulus_Pa`` for ``'particle_modulus'``.
    """
    if parameter not in ENERGY_LOSS_PARAMETERS:
        raise ValueError(f"parameter must be one of {', '.join(ENERGY_LOSS_PARAMETERS)}, got {parameter!r}")
    col = ENERGY_LOSS_PARAMETERS[parameter][0]
    base = default_pair(pair)
    parts = []
    for value in np.atleast_1d(np.asarray(values, dtype=float)):
        p, extra = _pair_with(base, parameter, float(value), particle_poisson, surface_modulus, surface_poisson)
        Vy = p.yield_velocity
        V = speed_grid(velocity, Vy)
        out = p.impact(V, warn=False)
        n = V.size
        part = {col: np.full(n, float(value))}
        part.update({k: np.full(n, v) for k, v in extra.items()})
        part.update(
            {
                quantities.column("velocity"): np.asarray(out.velocity, float).ravel(),
                "energy_loss": np.asarray(out.energy_loss, float).ravel(),
                "restitution": np.asarray(out.restitution, float).ravel(),
                quantities.column("yield_velocity"): np.full(n, Vy),
                "large_strain": np.asarray(out.large_strain, dtype=int).ravel(),
            }
        )
        parts.append(part)
    return concat_columns(parts)


def plot_energy_loss(parameter, values, ax=None, *, pair=None, velocity=None, table=None, legend_loc="above", **kws):
    """Figs. 3-5: fraction of energy lost ``1 - e^2`` against impact speed for several values of an input (seed eq. 29).

    Parameters
    ----------
    parameter : {'limiting_pressure', 'particle_modulus', 'effective_modulus', 'density'}
        The swept input, as :func:`energy_loss_data` (e.g. ``"limiting_pressure"``
        with ``values = [50e6, ..., 250e6]`` [Pa] for the seed's Fig. 3).
    values : sequence of float
        Values of the parameter (in its SI unit), one curve each.
    ax : matplotlib Axes, optional
        Axes to draw on; a new single-column figure if None.
    pair : ContactPair, optional
        The other inputs, as :func:`energy_loss_data`.
    velocity : array_like, optional
        Speeds [m/s], as :func:`energy_loss_data`.
    table : dict, optional
        Output of :func:`energy_loss_data` to draw.
    legend_loc : str
        ``"above"`` (default: a legend in columns above the axes, clear of the curves)
        or a matplotlib ``loc`` for a legend inside the axes.
    **kws
        The keywords of :func:`energy_loss_data` (``particle_poisson``,
        ``surface_modulus`` [Pa], ``surface_poisson``) go to it; the rest to
        ``ax.plot`` for the curves.

    Returns
    -------
    matplotlib Axes
        The Axes drawn on.

    Notes
    -----
    An open circle marks where each curve leaves the small-strain range (``a*/R* = 0.3``).
    """
    data_kws = {k: kws.pop(k) for k in ("particle_poisson", "surface_modulus", "surface_poisson") if k in kws}
    if table is None:
        table = energy_loss_data(parameter, values, pair, velocity, **data_kws)
    col, symbol, unit, scale = ENERGY_LOSS_PARAMETERS[parameter]
    with _style.style():
        ax = _style.new_axes(ax)
        V = np.asarray(table[quantities.column("velocity")], float)
        y = np.asarray(table["energy_loss"], float)
        ls_flag = np.asarray(table["large_strain"]).astype(bool)
        any_onset = False
        for i, (value, m) in enumerate(groups_of(table, col)):
            st = {**_style.series_style(i), **kws}
            ax.plot(V[m], y[m], label=f"{symbol} = {fmt_value(value * scale)} {unit}", **st)
            if ls_flag[m].any():
                j = np.argmax(ls_flag[m])
                ax.plot(
                    V[m][j],
                    y[m][j],
                    marker="o",
                    markersize=3.5,
                    markerfacecolor="white",
                    markeredgecolor=st["color"],
                    markeredgewidth=0.8,
                    zorder=4,
                )
                any_onset = True
        if any_onset:
            ax.plot(
                [],
                [],
                linestyle="none",
                marker="o",
                markersize=3.5,
                markerfacecolor="white",
                markeredgecolor="0.3",
                markeredgewidth=0.8,
                label=r"$a^*/R^* = 0.3$ reached",
            )
        ax.set_xlim(0.0, max(VMAX, float(V.max())) if velocity is None else float(V.max()))
        ax.set_ylim(0.0, 1.0)
        ax.set_xlabel(V_LABEL)
        ax.set_ylabel(quantities.axis_label("energy_loss", "fraction of energy lost"))
        if legend_loc == "above":
            ax.legend(
                loc="lower center",
                bbox_to_anchor=(0.5, 1.01),
                ncol=2,
                borderaxespad=0.0,
                handlelength=2.6,
                columnspacing=1.5,
            )
        else:
            ax.legend(loc=legend_loc)
    return ax
