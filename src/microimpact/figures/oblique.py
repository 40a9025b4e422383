"""Figures of oblique impacts: tangential restitution, rebound spin and rebound angle against angle.

* :func:`plot_oblique` draws the three curves against the impact angle for the compliant
  (Mindlin no-slip spring + Coulomb) and the rigid-body models, with the published points
  of the alumina case (Kharaz, Gorham & Salman 2001 measurements and Chung & Ooi's 2011
  DEM result, read off Chung & Ooi's figures: :func:`microimpact.oblique.measured_alumina`).
* :func:`plot_universal` draws the universal curve: the normalised contact-point rebound
  angle ``psi_2 = kappa u_r / (mu V_n)`` against the normalised impact angle ``psi_1 =
  kappa u0 / (mu V_n)`` (the form of Maw, Barber & Fawcett's plots), for several
  ``V_y / V_n``, and the rigid model.

Each has a ``*_data`` twin returning the plotted numbers as equally long columns.
"""

from __future__ import annotations

import numpy as np

from .. import oblique as ob
from ..core import tangential as tg
from . import style as _style

__all__ = [
    "LABELS",
    "LAW_MODELS",
    "oblique_data",
    "plot_oblique",
    "plot_tangential_laws",
    "tangential_comparison_data",
    "plot_tangential_comparison",
    "universal_data",
    "plot_universal",
]

_MODELS = ("mindlin", "rigid")
#: Legend labels of the tangential models.
LABELS = {
    "mindlin": "compliant (Mindlin)",
    "rigid": "rigid body",
    "lammps_mindlin": "LAMMPS mindlin",
    "lammps_mindlin_force": "LAMMPS mindlin/force",
    "lammps_mindlin_rescale": "LAMMPS mindlin_rescale",
    "lammps_mindlin_rescale_force": "LAMMPS mindlin_rescale/force",
    "lammps_linear_history": "LAMMPS linear_history",
    "liggghts_history": "LIGGGHTS history",
    "di_renzo_di_maio": "Di Renzo & Di Maio 2005",
    "mindlin_deresiewicz": "Mindlin–Deresiewicz (turning points)",
    "stronge": "Stronge (linear springs)",
}
_LABELS = LABELS


def oblique_data(
    pair=None, *, angle=None, velocity=None, friction=None, poisson_ratio=None, method="table", models=_MODELS
) -> dict:
    """Columns of :func:`plot_oblique`: the tangential models over the impact angle.

    Defaults are the alumina case (:data:`microimpact.oblique.ALUMINA_CASE`) and the models
    ``("mindlin", "rigid")``; ``models`` takes any of :data:`microimpact.oblique.TANGENTIAL_MODELS`.

    Returns
    -------
    dict
        ``model`` (str), ``angle`` [deg], ``tangential_restitution`` [-],
        ``rebound_spin`` [rad/s], ``contact_rebound_angle`` [deg], ``rebound_angle`` [deg],
        ``normalized_angle`` [-], ``impulse_ratio`` [-], ``regime`` (str).
    """
    case = ob.ALUMINA_CASE
    if pair is None:
        pair = ob.alumina_pair()  # on glass: kappa from both materials unless poisson_ratio is given
    velocity = case["velocity"] if velocity is None else velocity
    friction = case["friction"] if friction is None else friction
    angle = np.linspace(0.5, 89.5, 179) if angle is None else np.atleast_1d(np.asarray(angle, dtype=float))
    cols = {
        k: []
        for k in (
            "model",
            "angle",
            "tangential_restitution",
            "rebound_spin",
            "contact_rebound_angle",
            "rebound_angle",
            "normalized_angle",
            "impulse_ratio",
            "regime",
        )
    }
    for model in models:
        out = ob.oblique_impact(
            pair, velocity, angle, friction, poisson_ratio=poisson_ratio, tangential=model, method=method
        )
        cols["model"].append(np.full(angle.size, model))
        cols["angle"].append(angle)
        for k in list(cols)[2:]:
            cols[k].append(np.broadcast_to(getattr(out, k), angle.shape))
    return {k: np.concatenate(v) for k, v in cols.items()}


def plot_oblique(pair=None, axes=None, *, measured=True, table=None, labels=None, **kws):
    """Tangential restitution, rebound spin and contact rebound angle against the impact angle.

    Parameters
    ----------
    pair : ContactPair, optional
        Default: the alumina case; the published points are drawn only for it.
    axes : sequence of 3 Axes, optional
        Where to draw; default a new figure of three stacked panels.
    measured : bool
        Draw the published points (alumina case only).
    table : dict, optional
        The output of :func:`oblique_data` (else computed with ``**kws``).
    labels : dict, optional
        Legend labels by model, over :data:`LABELS`.

    Returns
    -------
    ndarray of Axes
    """
    data = oblique_data(pair, **kws) if table is None else table
    with _style.style() as plt:
        if axes is None:
            fig, axes = plt.subplots(3, 1, sharex=True, figsize=(3.5, 6.0), layout="constrained")
        axes = np.asarray(axes)
        keys = [
            ("tangential_restitution", r"tangential restitution $v_t'/v_t$"),
            ("rebound_spin", r"rebound spin $\omega'$ [rad/s]"),
            ("contact_rebound_angle", r"contact rebound angle [deg]"),
        ]
        big = float(np.nanmax(np.abs(data["rebound_spin"]))) if data["rebound_spin"].size else 0.0
        k3 = int(np.floor(np.log10(big) / 3.0)) * 3 if big >= 1e4 else 0
        scale = {"rebound_spin": 10.0**-k3}
        if k3:
            keys[1] = ("rebound_spin", rf"rebound spin $\omega'$ [$10^{{{k3}}}$ rad/s]")
        models = list(dict.fromkeys(data["model"].tolist()))
        for i, model in enumerate(models):
            sel = data["model"] == model
            for ax, (k, _) in zip(axes, keys):
                y = data[k][sel] * scale.get(k, 1.0)
                name = {**LABELS, **(labels or {})}.get(model, model)
                ax.plot(data["angle"][sel], y, label=name, **_style.series_style(i))
        if measured and pair is None:
            for src, mk, lab in (
                ("experiment", "o", "measured, Kharaz et al. 2001"),
                ("dem", "s", "DEM, Chung & Ooi 2011"),
            ):
                for ax, q in zip(axes, ("et", "spin", "angle")):
                    a, v = ob.measured_alumina(src, q)
                    v = v * (scale["rebound_spin"] if q == "spin" else 1.0)
                    ax.plot(
                        a, v, mk, ms=3.2, mfc="none" if src == "dem" else "k", mec="k", mew=0.7, ls="none", label=lab
                    )
        for ax, (_, lab) in zip(axes, keys):
            ax.set_ylabel(lab)
        axes[-1].set_xlabel("impact angle from the normal [deg]")
        axes[-1].set_xlim(0, 90)
        handles, labels = axes[0].get_legend_handles_labels()
        fig = axes[0].figure
        for ncol in (2, 1):  # two columns where they fit the figure's width, else one
            leg = fig.legend(
                handles, labels, loc="outside upper center", ncol=ncol, columnspacing=0.8, handlelength=2.2
            )
            if ncol == 1 or leg.get_window_extent(fig.canvas.get_renderer()).width <= 0.98 * fig.bbox.width:
                break
            leg.remove()
    return axes


#: The tangential laws of :func:`plot_tangential_laws`, in drawing order (``"lammps_mindlin_rescale_force"``
#: is ``"mindlin"``).
LAW_MODELS = (
    "mindlin",
    "lammps_mindlin",
    "lammps_mindlin_force",
    "lammps_mindlin_rescale",
    "lammps_linear_history",
    "liggghts_history",
    "di_renzo_di_maio",
    "mindlin_deresiewicz",
    "stronge",
    "rigid",
)


def plot_tangential_laws(axes=None, *, models=LAW_MODELS, **kws):
    """:func:`plot_oblique` of the alumina case for the DEM codes' tangential laws, with the published points.

    ``"mindlin"`` is drawn as LAMMPS's ``mindlin_rescale/force`` (the same law); ``**kws`` go to
    :func:`oblique_data`. Returns the three Axes.
    """
    data = oblique_data(models=models, **kws)
    if axes is None:
        with _style.style() as plt:
            _, axes = plt.subplots(3, 1, sharex=True, figsize=(6.0, 7.2), layout="constrained")
    return plot_oblique(None, axes, table=data, labels={"mindlin": "LAMMPS mindlin_rescale/force (= mindlin)"})


def tangential_comparison_data(comparison) -> dict:
    """Columns of :func:`plot_tangential_comparison`: a :func:`microimpact.compare.compare_tangential`
    Dataset as :func:`oblique_data`'s columns (one row per law and angle).

    Returns
    -------
    dict
        ``model`` (str), ``angle`` [deg], ``tangential_restitution`` [-], ``rebound_spin`` [rad/s],
        ``contact_rebound_angle`` [deg], ``rebound_angle`` [deg], ``impulse_ratio`` [-], ``regime`` (str).
    """
    names = [str(n) for n in comparison["tangential"].values]
    ang = np.asarray(comparison["angle"].values, dtype=float)
    cols = {"model": np.repeat(np.asarray(names), ang.size), "angle": np.tile(ang, len(names))}
    for k in ("tangential_restitution", "rebound_spin", "contact_rebound_angle", "rebound_angle", "impulse_ratio"):
        cols[k] = np.asarray(comparison[k].values, dtype=float).reshape(-1)
    cols["regime"] = np.asarray(comparison["regime"].values).reshape(-1)
    return cols


def plot_tangential_comparison(comparison, axes=None, *, measured=False):
    """:func:`plot_oblique` of a :func:`microimpact.compare.compare_tangential` Dataset: tangential
    restitution, rebound spin and contact rebound angle of each law against the impact angle.

    ``measured=True`` adds the published points of the alumina case (draw them only for that case).
    Returns the three Axes.
    """
    data = tangential_comparison_data(comparison)
    if axes is None:
        with _style.style() as plt:
            _, axes = plt.subplots(3, 1, sharex=True, figsize=(6.0, 7.2), layout="constrained")
    return plot_oblique(None, axes, measured=measured, table=data)


def universal_data(kappa=None, *, x=(1.0, 0.1, 0.01), psi=None) -> dict:
    """Columns of :func:`plot_universal`: ``psi_2`` against ``psi_1`` for each ``x = V_y/V_n``.

    Returns
    -------
    dict
        ``model`` (str), ``x`` [-], ``psi_1`` [-], ``psi_2`` [-] (``kappa u_r/(mu V_n)``),
        ``impulse_ratio`` [-] (``|J_t|/(mu J_n)``).
    """
    if kappa is None:
        kappa = ob.stiffness_ratio_of(ob.alumina_pair())
    psi = np.linspace(0.0, 8.0, 321) if psi is None else np.atleast_1d(np.asarray(psi, dtype=float))

    cols = {k: [] for k in ("model", "x", "psi_1", "psi_2", "impulse_ratio")}
    for xv in x:
        F, ratio, _ = ob.universal_curve(psi, kappa, xv)
        one_e = 1.0 + tg.history_constants(min(float(xv), 1.0))[13]
        psi2 = psi - tg.SLIP_FACTOR * kappa * F * one_e
        for model, f in (("mindlin", F), ("rigid", np.minimum(1.0, 2.0 * psi / (7.0 * kappa * one_e)))):
            cols["model"].append(np.full(psi.size, model))
            cols["x"].append(np.full(psi.size, float(xv)))
            cols["psi_1"].append(psi)
            cols["psi_2"].append(psi - tg.SLIP_FACTOR * kappa * f * one_e if model == "rigid" else psi2)
            cols["impulse_ratio"].append(f)
    return {k: np.concatenate(v) for k, v in cols.items()}


def plot_universal(kappa=None, ax=None, *, x=(1.0, 0.1, 0.01), table=None):
    """The universal curve ``psi_2(psi_1)`` of the compliant model (and the rigid model).

    Returns
    -------
    Axes
    """
    data = universal_data(kappa, x=x) if table is None else table
    with _style.style():
        ax = _style.new_axes(ax)
        for i, xv in enumerate(np.unique(data["x"])[::-1]):
            sel = (data["x"] == xv) & (data["model"] == "mindlin")
            lab = r"compliant, elastic ($V_n \leq V_y$)" if xv >= 1 else rf"compliant, $V_y/V_n = {xv:g}$"
            ax.plot(data["psi_1"][sel], data["psi_2"][sel], label=lab, **_style.series_style(i))
        sel = (data["x"] == np.max(data["x"])) & (data["model"] == "rigid")
        ax.plot(
            data["psi_1"][sel], data["psi_2"][sel], color="0.5", lw=0.9, ls=(0, (1, 1.2)), label="rigid body, elastic"
        )
        ax.axhline(0.0, color="0.7", lw=0.5, zorder=0)
        ax.set_xlabel(r"normalised impact angle $\psi_1 = \kappa u_0 / (\mu V_n)$")
        ax.set_ylabel(r"normalised rebound angle $\psi_2 = \kappa u_r / (\mu V_n)$")
        ax.set_xlim(0, float(np.max(data["psi_1"])))
        ax.legend(loc="upper left")
    return ax
