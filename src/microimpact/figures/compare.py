"""Figure of a model comparison: ``e``, energy loss and contact time against impact speed.

:func:`comparison_data` gives the plotted numbers as columns (one row per model and speed);
:func:`plot_comparison` draws them as three panels side by side, one line style and colour per
model (:mod:`microimpact.figures.style`), with the seed's yield velocity marked and the speeds where
the seed's model leaves its small-strain range (``a*/R* > 0.3``) hatched. matplotlib (the ``plot``
extra) is imported only when a plot function is called.
"""

from __future__ import annotations

import math

import numpy as np

from .. import quantities
from . import style as _style

__all__ = ["comparison_data", "plot_comparison", "COMPARISON_COLUMNS", "model_label", "model_style"]

#: Columns of :func:`comparison_data`: name -> unit (from :data:`~microimpact.core.quantities.QUANTITIES`;
#: the contact time in its display unit, ns).
COMPARISON_COLUMNS = {
    name: unit
    for name, (unit, _) in {
        **quantities.columns(["model", "calibrated", "velocity", "restitution", "energy_loss"]),
        **quantities.columns(["contact_time"], display=True),
        **quantities.columns(["large_strain"]),
    }.items()
}


def model_label(name: str) -> str:
    """Legend label of model ``name``: its declared ``LABEL`` (:mod:`microimpact.core.models`)."""
    from .. import models

    return models.get(name).LABEL


def model_style(name: str, i: int) -> dict:
    """Line style of model ``name``, the ``i``-th line of a figure: its face's ``STYLE``
    (:func:`microimpact.models.face`; the seed's black and solid, Okabe-Ito colours), so that a
    model looks the same in every comparison, else :func:`~.style.series_style` ``(i)``."""
    from .. import models

    return models.face(name).STYLE or _style.series_style(i)


def __getattr__(name):
    if name in ("MODEL_LABELS", "MODEL_STYLES"):  # deprecated: each model declares them
        import warnings

        from .. import models

        new = "model_label(name)" if name == "MODEL_LABELS" else "model_style(name, i)"
        warnings.warn(
            f"microimpact.figures.compare.{name} is deprecated; use microimpact.figures.compare.{new}",
            DeprecationWarning,
            stacklevel=2,
        )
        if name == "MODEL_LABELS":
            return {n: models.get(n).LABEL for n in models.available()}
        return {n: models.face(n).STYLE for n in models.available() if models.face(n).STYLE}
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _dataset(comparison, **kwargs):
    if comparison is None or not hasattr(comparison, "data_vars"):
        from ..compare import compare_models

        return compare_models(comparison, **kwargs)
    if kwargs and any(v is not None for v in kwargs.values()):
        raise ValueError("give either a comparison Dataset or the arguments of compare_models, not both")
    return comparison


def comparison_data(comparison=None, **kwargs) -> dict:
    """The numbers of :func:`plot_comparison` as columns, one row per model and speed.

    Parameters
    ----------
    comparison : xarray.Dataset, ContactPair or str, optional
        A result of :func:`microimpact.compare.compare_models`, or the pair (or paper case name)
        to compare the models for; default the seed's silicon case.
    **kwargs
        ``velocity``, ``models``, ``params``, ``reference_velocity`` of
        :func:`~microimpact.compare.compare_models` when ``comparison`` is not a Dataset.

    Returns
    -------
    dict of ndarray
        Columns of :data:`COMPARISON_COLUMNS`: ``model``, ``calibrated`` (0/1),
        ``velocity_m_s`` [m/s], ``restitution`` [-], ``energy_loss`` [-], ``contact_time_ns``
        [ns], ``large_strain`` (0/1, ``a*/R* > 0.3``).
    """
    ds = _dataset(comparison, **kwargs)
    names = [str(n) for n in ds["model"].values]
    V = np.asarray(ds["velocity"].values, dtype=float)
    n = len(names) * V.size
    return {
        "model": np.repeat(np.array(names, dtype=object), V.size),
        "calibrated": np.repeat(np.asarray(ds["calibrated"].values, dtype=int), V.size),
        quantities.column("velocity"): np.tile(V, len(names)),
        "restitution": np.asarray(ds["restitution"].values, dtype=float).reshape(n),
        "energy_loss": np.asarray(ds["energy_loss"].values, dtype=float).reshape(n),
        quantities.column("contact_time", display=True): np.asarray(ds["contact_time"].values, dtype=float).reshape(n)
        * quantities.QUANTITIES["contact_time"].scale,
        "large_strain": np.asarray(ds["large_strain"].values, dtype=int).reshape(n),
    }


def plot_comparison(comparison=None, ax=None, *, legend=True, **kwargs):
    """Restitution, energy loss and contact time against impact speed, one line per model.

    Parameters
    ----------
    comparison : xarray.Dataset, ContactPair or str, optional
        As :func:`comparison_data`.
    ax : sequence of three matplotlib Axes, optional
        Panels for ``e``, ``1 - e^2`` and ``t_c``; default a new double-column figure.
    legend : bool
        Draw the legend (above the panels; calibrated models marked "cal.").
    **kwargs
        Passed to :func:`~microimpact.compare.compare_models` when ``comparison`` is not a Dataset.

    Returns
    -------
    ndarray of three matplotlib Axes

    Examples
    --------
    >>> from microimpact.figures.compare import plot_comparison
    >>> axes = plot_comparison("silicon")  # doctest: +SKIP
    >>> axes[0].figure.savefig("compare.png", dpi=300)  # doctest: +SKIP
    """
    ds = _dataset(comparison, **kwargs)
    V = np.asarray(ds["velocity"].values, dtype=float)
    names = [str(n) for n in ds["model"].values]
    calibrated = np.asarray(ds["calibrated"].values, dtype=bool)
    Vy = float(ds.attrs.get("yield_velocity", math.nan))
    V_ls = float(ds.attrs.get("seed_large_strain_velocity", math.nan))
    ref = float(ds.attrs.get("reference_velocity", math.nan))
    panels = [
        ("restitution", 1.0, r"Coefficient of restitution, $e$"),
        ("energy_loss", 1.0, r"Energy loss, $1 - e^2$"),
        ("contact_time", 1e9, quantities.axis_label("contact_time", "Contact time")),
    ]
    with _style.style() as plt:
        if ax is None:
            fig, axes = plt.subplots(1, 3, figsize=(7.2, 2.75), layout="constrained")
        else:
            axes = np.asarray(ax, dtype=object).ravel()
            if axes.size != 3:
                raise ValueError(f"ax must be three Axes (restitution, energy loss, contact time), got {axes.size}")
            fig = axes[0].figure
        handles = []
        for i, name in enumerate(names):
            st = model_style(name, i)
            label = model_label(name) + (" (cal.)" if calibrated[i] else "")
            if V.size <= 12:  # a few speeds: mark them
                st = {**st, "marker": _style.MARKERS[i % len(_style.MARKERS)], "markersize": 3.5}
            for a, (var, scale, _) in zip(axes, panels):
                (line,) = a.plot(V, np.asarray(ds[var].values[i], dtype=float) * scale, label=label, **st)
            handles.append(line)
        for a, (var, _, ylabel) in zip(axes, panels):
            a.set_xlabel(quantities.axis_label("velocity", "Impact velocity"))
            a.set_ylabel(ylabel)
            a.set_xlim(0.0, float(V.max()) * 1.02)
            a.minorticks_on()
            if math.isfinite(Vy) and V.min() < Vy < V.max():
                a.axvline(Vy, color="0.45", linewidth=0.6, linestyle=":", zorder=1)
            if math.isfinite(ref):
                a.axvline(ref, color="0.7", linewidth=0.5, linestyle="-", zorder=0.5)
        axes[0].set_ylim(0.0, 1.05)
        axes[1].set_ylim(0.0, 1.0)
        axes[2].set_ylim(bottom=0.0)
        for k, a in enumerate(axes):
            if math.isfinite(V_ls):
                _style.shade_large_strain(a, V_ls, label=(k == 0))
        if math.isfinite(Vy) and V.min() < Vy < V.max():
            axes[0].annotate(
                r"$V_y$",
                xy=(Vy, 0.02),
                xycoords=("data", "axes fraction"),
                xytext=(2, 0),
                textcoords="offset points",
                fontsize=6.5,
                color="0.35",
                va="bottom",
            )
        if math.isfinite(ref):
            axes[0].annotate(
                r"$V_\mathrm{cal}$",
                xy=(ref, 0.02),
                xycoords=("data", "axes fraction"),
                xytext=(2, 0),
                textcoords="offset points",
                fontsize=6.5,
                color="0.5",
                va="bottom",
            )
        if legend:
            fig.legend(
                handles=handles,
                loc="outside upper center",
                ncol=min(len(handles), 4),
                handlelength=3.0,
                columnspacing=1.4,
            )
    return np.asarray(axes, dtype=object)
