"""The seed paper's Figures 2-10 as plot functions, each with the data it plots.

Every figure has a pair of public functions:

* ``*_data(...)`` returns the numbers behind the figure as a dict of equally long
  1-D columns (a tidy, "long" table: one row per plotted point, a column naming the
  curve). Column names carry their SI unit as a suffix (``velocity_m_s``,
  ``force_N``, ``time_s``); names without a suffix are dimensionless.
  :data:`COLUMNS` gives the unit and a description of every column. The values are
  exactly what the public API (:meth:`ContactPair.impact`, :meth:`ContactPair.force`,
  :meth:`ContactPair.history`) returns for the same inputs: nothing is smoothed,
  rounded or rescaled.
* ``plot_*(..., ax=None, table=None)`` draws it (in display units: nm, uN, ns) on
  ``ax`` (or a new single-column figure) and returns the Axes. Pass ``table=`` the
  output of the ``*_data`` function to draw exactly those numbers.

Defaults are the seed's silicon case (NH4Fl, d = 4.9 um, rho = 1350 kg/m^3,
E* = 1.31 GPa, p_y = 156 MPa, :meth:`ContactPair.paper_case`) and its velocity
range (up to 120 m/s). Where the contact radius exceeds ``0.3 R*`` the model's
small-strain assumption no longer holds; the figures show that range lightly
hatched (or mark where each curve enters it).

Examples
--------
>>> from microimpact.figures import energy_loss_data
>>> t = energy_loss_data("limiting_pressure", [100e6, 200e6], velocity=[10.0, 50.0])
>>> sorted(t)[:3]
['energy_loss', 'large_strain', 'limiting_pressure_Pa']
"""

from __future__ import annotations

import math

import numpy as np

from .. import contact, quantities
from ..core.constants import LARGE_STRAIN_RATIO
from ..pair import ContactPair
from . import style as _style

__all__ = [
    "COLUMNS",
    "ENERGY_LOSS_PARAMETERS",
    "large_strain_velocity",
    "restitution_data",
    "plot_restitution",
    "energy_loss_data",
    "plot_energy_loss",
    "force_displacement_data",
    "plot_force_displacement",
    "force_time_data",
    "plot_force_time",
    "approach_data",
    "plot_approach",
    "contact_time_data",
    "plot_contact_times",
    "dynamics_data",
    "plot_dynamics",
]

#: Every column a ``*_data`` function returns: name -> (unit, description), from
#: :data:`microimpact.core.quantities.QUANTITIES` (the CSV names carry their SI unit, ``force_N``).
COLUMNS: dict[str, tuple[str, str]] = quantities.columns(
    [
        "series",
        "kind",
        "velocity",
        "yield_velocity",
        "restitution",
        "energy_loss",
        "large_strain",
        "limiting_pressure",
        "particle_modulus",
        "effective_modulus",
        "density",
        "branch",
        "approach",
        "force",
        "max_approach",
        "plastic_approach",
        "plastic_ratio",
        "elastic_stage_time",
        "plastic_stage_time",
        "loading_time",
        "unloading_time",
        "contact_time",
        "deresiewicz_time",
        "ning_loading_time",
        "time",
        "approach_velocity",
        "stage",
    ]
)

#: Parameters of :func:`energy_loss_data` (seed Figs. 3-5): name -> (column, legend symbol, display unit,
#: scale), from :data:`~microimpact.core.quantities.QUANTITIES`.
ENERGY_LOSS_PARAMETERS: dict[str, tuple[str, str, str, float]] = {
    n: (
        quantities.column(n),
        quantities.QUANTITIES[n].tex,
        quantities.tex_unit(quantities.QUANTITIES[n].shown_unit),
        quantities.QUANTITIES[n].scale,
    )
    for n in ("limiting_pressure", "particle_modulus", "effective_modulus", "density")
}

_V_LABEL = quantities.axis_label("velocity", "impact velocity")


def _scale(name):
    """SI value times this is the value in the quantity's display unit (nm, µN, ns; QUANTITIES)."""
    return quantities.QUANTITIES[name].scale


def _legend_label(words, name):
    """A legend entry for quantity ``name``: ``words``, its TeX symbol and its display unit (QUANTITIES)."""
    q = quantities.QUANTITIES[name]
    return f"{words} {q.tex} ({quantities.tex_unit(q.shown_unit)})"


_VMAX = 120.0  # the seed's velocity range [m/s]


# ----------------------------------------------------------------------------- helpers
def _default_pair(pair):
    return ContactPair.paper_case("silicon") if pair is None else pair


def _grid(velocity, *extra, start=0.0, stop=_VMAX, num=481):
    """The given speeds, or ``linspace(start, stop, num)`` plus ``extra`` points (e.g. ``V_y``), sorted."""
    if velocity is not None:
        return np.atleast_1d(np.asarray(velocity, dtype=float))
    base = np.linspace(start, stop, num)
    pts = [float(x) for x in extra if start < float(x) < stop]
    return np.unique(np.concatenate([base, pts]))


def _concat(parts):
    """Concatenate a list of column dicts with the same keys."""
    keys = list(parts[0])
    return {k: np.concatenate([np.atleast_1d(np.asarray(p[k])) for p in parts]) for k in keys}


def _groups(table, key):
    """``(value, mask)`` for each distinct ``table[key]`` in order of first appearance."""
    col = np.asarray(table[key])
    _, idx = np.unique(col, return_index=True)
    return [(col[i], col == col[i]) for i in sorted(idx)]


def large_strain_velocity(pair) -> float:
    """Impact speed [m/s] above which the contact radius exceeds ``0.3 R*`` (small strain ends).

    The seed's model in closed form
    (:func:`~microimpact.core.models.thornton_ning_2016.large_strain_velocity`);
    ``inf`` if above 1e6 m/s.

    Parameters
    ----------
    pair : ContactPair
        The contact pair.

    Returns
    -------
    float
        Impact speed [m/s] at which ``a*/R* = 0.3`` (``inf`` if above 1e6 m/s).

    Examples
    --------
    >>> round(large_strain_velocity(ContactPair.paper_case("silicon")), 1)
    23.3
    """
    from ..compare import seed_large_strain_velocity

    return seed_large_strain_velocity(pair)


def _fmt_value(x):
    return f"{x:g}"


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
            V = np.unique(np.concatenate([np.geomspace(1.0, _VMAX, 400), [Vy] if 1 < Vy < _VMAX else []]))
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
    return _concat(parts)


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
        for key, m in _groups(keys, "series_kind"):
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
        ax.set_xlim(1.0 if logx else 0.0, _VMAX)
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
        ax.set_xlabel(_V_LABEL)
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
    base = _default_pair(pair)
    parts = []
    for value in np.atleast_1d(np.asarray(values, dtype=float)):
        p, extra = _pair_with(base, parameter, float(value), particle_poisson, surface_modulus, surface_poisson)
        Vy = p.yield_velocity
        V = _grid(velocity, Vy)
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
    return _concat(parts)


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
        for i, (value, m) in enumerate(_groups(table, col)):
            st = {**_style.series_style(i), **kws}
            ax.plot(V[m], y[m], label=f"{symbol} = {_fmt_value(value * scale)} {unit}", **st)
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
        ax.set_xlim(0.0, max(_VMAX, float(V.max())) if velocity is None else float(V.max()))
        ax.set_ylim(0.0, 1.0)
        ax.set_xlabel(_V_LABEL)
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
    pair = _default_pair(pair)
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
    return _concat(parts)


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
    pair = _default_pair(pair)
    with _style.style():
        ax = _style.new_axes(ax)
        branch = np.asarray(table["branch"])
        a = np.asarray(table[quantities.column("approach")], float) * _scale("approach")
        P = np.asarray(table[quantities.column("force")], float) * _scale("force")
        for i, (V, m) in enumerate(_groups(table, quantities.column("velocity"))):
            c = _style.COLORS[i % len(_style.COLORS)]
            lo, un = m & (branch == "loading"), m & (branch == "unloading")
            ax.plot(a[lo], P[lo], color=c, linestyle="-", label=f"V = {V:g} m/s", **kws)
            ax.plot(a[un], P[un], color=c, linestyle="--", **kws)
            a_p = float(np.asarray(table[quantities.column("plastic_approach")], float)[m][0]) * _scale(
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
            label=_legend_label("plastic approach", "plastic_approach"),
        )
        ax.set_xlim(0.0, float(a.max()) * 1.05)
        ax.set_ylim(0.0, float(P.max()) * 1.08)
        # a*/R* > 0.3 <=> alpha > 0.09 R*
        _style.shade_large_strain(
            ax, LARGE_STRAIN_RATIO**2 * pair.effective_radius * _scale("approach"), label=True, text_xy=(0.985, 0.06)
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
    pair = _default_pair(pair)
    V = _grid(velocity, pair.yield_velocity, start=0.25, num=479)
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
            np.asarray(table[quantities.column("max_approach")], float) * _scale("max_approach"),
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
        ax.set_xlabel(_V_LABEL)
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
    pair = _default_pair(pair)
    V = _grid(velocity, pair.yield_velocity, start=2.0, num=473)
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
                np.asarray(table[col], float) * _scale("contact_time"),
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
        ymax = float(np.nanmax(np.asarray(table[quantities.column("contact_time")], float))) * _scale("contact_time")
        ax.set_ylim(0.0, ymax * 1.4)
        ls = np.asarray(table["large_strain"]).astype(bool)
        if ls.any():
            _style.shade_large_strain(ax, float(V[ls].min()), label=True, text_xy=(0.985, 0.66))
        ax.set_xlabel(_V_LABEL)
        ax.set_ylabel(r"Time (ns)")
        ax.legend(loc="upper right", ncol=2, columnspacing=1.0, handlelength=2.8)
    return ax


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
    pair = _default_pair(pair)
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
    return _concat(parts)


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
        t = np.asarray(table[quantities.column("time")], float) * _scale("time")
        P = np.asarray(table[quantities.column("force")], float) * _scale("force")
        for name, m in _groups(table, "series"):
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
    pair = _default_pair(pair)
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
        t = np.asarray(table[quantities.column("time")], float) * _scale("time")
        stage = np.asarray(table["stage"], int)
        series = [
            (
                quantities.column("approach_velocity"),
                _scale("approach_velocity"),
                quantities.axis_label("approach_velocity", "velocity"),
            ),
            (quantities.column("force"), _scale("force"), quantities.axis_label("force", "force")),
            (quantities.column("approach"), _scale("approach"), quantities.axis_label("approach")),
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
