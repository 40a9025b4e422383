"""What each DEM code gives for the same contact: ``e(V)`` of every code's adhesive law at one work of adhesion.

One pair and one work of adhesion ``G``; each adhesive law as a DEM code runs it (LAMMPS, LIGGGHTS,
Lethe, Yade), at a wall, with its inputs set as a user of the code would set them from ``G``:

* the code's adhesion input from ``G`` by the law's own reading of a work of adhesion
  (:func:`microimpact.calibrate.adhesion_inputs`, the face's ``params_for_work_of_adhesion``: a
  surface energy ``G/2``, a cohesion energy density giving JKR's pull-off, ...); a code without such
  an input (the liquid bridges, whose inputs are a liquid and its amount; LAMMPS' ``mdr``, whose
  ``gamma`` does nothing at a converged step) keeps its defaults;
* an input the code cannot run without and ``G`` does not set (LIGGGHTS' ``coefficientRestitution``
  of ``hertz`` + ``sjkr``, the liquid amount of a bridge) fitted by
  :func:`microimpact.calibrate.calibrate_adhesive` to the whole adhesive elastic-plastic law
  (Thornton & Ning 1998, :func:`microimpact.core.models.whole_law`) at ``G``, that input alone free,
  at four speeds from ``1.5 V_s`` of the whole law to the top of the speed range;
* every other input at the law's default (no damping in LAMMPS' ``jkr``/``dmt`` and Lethe's DMT
  unless given, the liquid water at zero contact angle).

The whole law is drawn in every panel as the reference, each law's capture velocity ``V_s`` (the
largest speed with ``e = 0``) as a marker on the speed axis, and a law that captures nothing at this
``G`` (``V_s = 0``: a conservative DMT force without damping, LAMMPS' ``mdr``, the EEPA law whose
pull-off LIGGGHTS sets to zero at a wall) is named in its panel, not dropped; a law that can capture
at no ``G`` (``STICKS`` false: ``mdr``) is named there without its curve, which is no adhesion's and
whose integration takes a minute to compile. The speed axis is logarithmic; ``e`` is drawn on a
linear axis, since ``e = 0`` (capture) is the point of the figure.

What it shows for the seed's pair at ``G`` = 0.1 J/m^2 (the gallery example): no two codes agree on the
capture velocity (0.224 m/s for LAMMPS' undamped ``jkr``, none for the undamped DMT laws, 0.31 m/s for
``sjkr`` with its fitted restitution, against the whole law's 0.318 m/s). Yade's liquid bridges,
fitted to that capture velocity, give ``e = (1 - V_s^2/V^2)^(1/2)``, the curve of any law that takes
a fixed energy from the particle, which is the whole law's below its yield speed. LIGGGHTS' bridges
cannot be fitted to it: the code gives no force to a bridge below 1e-17 m^3
(:data:`microimpact.core.models._capillary.LIGGGHTS_VOLUME_FLOOR`), while the fitted Yade bridge is
about 6e-23 m^3; ``washino`` stays below the floor (no capture), ``easo``'s smallest bridge above it
captures up to 3.1 m/s.

The laws are found by their declarations, not by name: a law with a capture velocity whose ``TITLE``
begins with the code running it (or says which code writes it, "as Yade writes it"); the panels are
the codes' solid contacts and the liquid bridges (the laws with a ``surface_tension`` input).
:func:`dem_adhesion_data` computes the curves, :func:`plot_dem_adhesion` draws them; matplotlib (the
``plot`` extra) is imported only when the plot function is called.
"""

from __future__ import annotations

import math
import re
import warnings

import numpy as np

from .. import calibrate as _calibrate
from .. import models as _models
from ..core import models as _core
from ..quantities import axis_label, tex_unit
from . import style as _style

__all__ = ["CODES", "code_of", "code_law_groups", "dem_adhesion_data", "plot_dem_adhesion"]

#: The DEM codes whose adhesive laws the package models, as their laws' titles name them.
CODES = ("LAMMPS", "LIGGGHTS", "Lethe", "Yade")
_CODE_AT_START = re.compile(r"^(" + "|".join(CODES) + r")\b")
_CODE_WRITES = re.compile(r"\bas (" + "|".join(CODES) + r") (?:writes|computes) it\b")


def code_of(model: str) -> str | None:
    """The DEM code that runs ``model`` as its law, from the law's declared ``TITLE`` (which begins
    with the code, or says "as CODE writes it"); None for a law that is no code's own."""
    title = _core.get(model).TITLE
    found = _CODE_AT_START.match(title) or _CODE_WRITES.search(title)
    return found.group(1) if found else None


def _is_bridge(model: str) -> bool:
    # a liquid bridge's inputs are a liquid: its surface tension is declared
    return any(p.name == "surface_tension" for p in _core.get(model).PARAMETERS)


def code_law_groups() -> tuple:
    """``((panel title, (law, ...)), ...)``: the codes' adhesive laws (:func:`code_of`, with a capture
    velocity) in three panels: LAMMPS' solid contacts, the other codes' solid contacts, the liquid
    bridges."""
    laws = [n for n in _models.available() if _core.get(n).sticking_velocity is not None and code_of(n)]
    solid = [n for n in laws if not _is_bridge(n)]
    first = [n for n in solid if code_of(n) == CODES[0]]
    rest = [n for n in solid if n not in first]
    bridges = [n for n in laws if _is_bridge(n)]
    codes = lambda names: " and ".join(dict.fromkeys(code_of(n) for n in names))  # noqa: E731
    groups = [(f"{codes(g)}: solid contact", tuple(g)) for g in (first, rest) if g]
    if bridges:
        groups.append((f"Liquid bridges ({codes(bridges)})", tuple(bridges)))
    return tuple(groups)


def _pair_values(pair):
    return (pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure)


def _start(spec, pair):
    """A start for an input without a default: a liquid volume [m^3] at 1e-6 of the particle's volume
    (a bridge's adhesion grows with the cube root of its volume, so the search needs the scale, not
    the value); None (the calibration's own start) otherwise."""
    if spec.unit == "m^3":
        return 1e-6 * 4.0 / 3.0 * math.pi * pair.effective_radius**3
    return None


def _inputs(pair, law, G, speeds, given):
    """``(params dict, fitted names, calibration or None)`` of ``law`` for ``G`` (module docstring)."""
    mod = _core.get(law)
    names = [p.name for p in mod.PARAMETERS]
    mapped = dict(zip(names, _calibrate.adhesion_inputs(law, G, _pair_values(pair), given)))
    missing = tuple(n for n in names if math.isnan(mapped[n]))
    if not missing:
        return mapped, (), None
    fixed = {n: v for n, v in mapped.items() if n not in missing}
    spec = {p.name: p for p in mod.PARAMETERS}
    for n in missing:
        s = _start(spec[n], pair)
        if s is not None:
            fixed[n] = s
    cal = _calibrate.calibrate_adhesive(pair, law, G, speeds, params=fixed, free=missing)
    return dict(zip(cal.names, cal.params)), missing, cal


def dem_adhesion_data(pair=None, work_of_adhesion=0.1, velocity=None, *, groups=None, params=None) -> dict:
    """``e(V)`` and ``V_s`` of each code's adhesive law and of the whole law, for one pair and ``G``.

    Parameters
    ----------
    pair : ContactPair, optional
        Sphere on a flat; default the seed's NH4Fl on silicon (``d`` = 4.9 um).
    work_of_adhesion : float
        ``G`` [J/m^2].
    velocity : array_like, optional
        Impact speeds [m/s]; default 0.03-100 m/s, 61 points, log-spaced.
    groups : sequence of (str, sequence of str), optional
        Panels: a title and its laws; default :func:`code_law_groups`.
    params : dict, optional
        ``{law: {parameter: value}}`` given to a law instead of the rule of the module docstring.

    Returns
    -------
    dict
        ``velocity`` [m/s], ``work_of_adhesion``, ``label`` (the pair's), ``reference`` (the whole law's
        name), ``reference_restitution``, ``reference_capture_velocity`` [m/s], ``calibration_velocity``
        [m/s], ``groups`` (as drawn), and ``laws``: ``{law: {"restitution", "capture_velocity",
        "params", "fitted" (names of the inputs fitted), "residual" (the fit's root mean square, NaN
        where nothing was fitted), "code"}}``; a law that can capture nothing whatever its inputs
        (``STICKS`` false, LAMMPS' ``mdr``) has its capture velocity and NaN for ``e``: it is listed,
        not drawn (its ``e(V)`` is no adhesion's, and its integration costs a minute to compile).
    """
    from ..pair import ContactPair

    pair = ContactPair.paper_case("silicon") if pair is None else pair
    G = float(work_of_adhesion)
    V = np.geomspace(0.03, 100.0, 61) if velocity is None else np.atleast_1d(np.asarray(velocity, dtype=float))
    groups = code_law_groups() if groups is None else tuple((str(t), tuple(g)) for t, g in groups)
    params = dict(params or {})
    whole = _core.whole_law()
    ref_names = [p.name for p in _core.get(whole).PARAMETERS]
    ref_params = dict(zip(ref_names, _calibrate.adhesion_inputs(whole, G, _pair_values(pair))))
    ref = _calibrate.code_prediction(pair, whole, V, **ref_params)
    vs_ref = ref["capture_velocity"]
    V_cal = np.geomspace(1.5 * vs_ref, float(V.max()), 4)
    laws = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # large-strain and validity warnings: the figure is the laws' own e(V)
        for _, names in groups:
            for law in names:
                p, fitted, cal = _inputs(pair, law, G, V_cal, params.get(law))
                if _core.get(law).STICKS:
                    pred = _calibrate.code_prediction(pair, law, V, **p)
                    e, vs = pred["restitution"], pred["capture_velocity"]
                else:  # a law that can capture nothing, whatever its inputs: listed with its V_s (0)
                    e = np.full(V.shape, np.nan)
                    vs = float(pair.sticking_velocity(model=law, **p))
                laws[law] = {
                    "restitution": np.asarray(e, dtype=float),
                    "capture_velocity": float(vs),
                    "params": p,
                    "fitted": fitted,
                    "residual": math.nan if cal is None else float(cal.residual),
                    "code": code_of(law),
                }
    return {
        "velocity": V,
        "work_of_adhesion": G,
        "label": pair.label or "",
        "reference": whole,
        "reference_restitution": np.asarray(ref["restitution"], dtype=float),
        "reference_capture_velocity": float(vs_ref),
        "calibration_velocity": V_cal,
        "groups": groups,
        "laws": laws,
    }


def _fitted_text(law, entry):
    spec = {p.name: p for p in _core.get(law).PARAMETERS}
    parts = []
    for n in entry["fitted"]:
        unit = spec[n].unit
        tail = f" {tex_unit(unit).replace('^3', '$^3$')}" if unit not in ("1", "-", "") else ""
        parts.append(f"{n.replace('_', ' ')} {entry['params'][n]:.3g}{tail}")
    return ", ".join(parts)


def plot_dem_adhesion(pair=None, work_of_adhesion=0.1, ax=None, *, data=None, **kw):
    """Draw :func:`dem_adhesion_data` (or ``data``): one panel per group, the whole law in black in each.

    Each law's curve is ``e(V)`` on a logarithmic speed axis, its capture velocity a marker of its
    colour on ``e = 0``; a fitted input is given in the legend (``fitted: ...``); the laws that capture
    nothing at this ``G`` are listed in the panel under "no capture". Returns the Axes (one per group).
    """
    if data is None:
        data = dem_adhesion_data(pair, work_of_adhesion, **kw)
    V = data["velocity"]
    groups = data["groups"]
    with _style.style() as plt:
        legend_axes = [None] * len(groups)
        if ax is None:
            # a second row of empty axes holds each panel's legend below it (constrained layout sizes it)
            fig, grid = plt.subplots(2, len(groups), figsize=(2.55 * len(groups) + 0.3, 4.4), squeeze=False,
                                     layout="constrained", height_ratios=(2.3, 1.0))  # fmt: skip
            axes = grid[0]
            for a in axes[1:]:
                a.sharey(axes[0])
            legend_axes = list(grid[1])
            for a in legend_axes:
                a.set_axis_off()
        else:
            axes = np.asarray(ax, dtype=object).ravel()
            if axes.size != len(groups):
                raise ValueError(f"ax must be {len(groups)} Axes (one per group), got {axes.size}")
            fig = axes[0].figure
        vs_ref = data["reference_capture_velocity"]
        for k, (a, (title, names)) in enumerate(zip(axes, groups)):
            a.plot(V, data["reference_restitution"], color="black", linewidth=2.4, zorder=2,
                   label=f"whole law (TN98), $V_s$ = {vs_ref:.3g} m/s")  # fmt: skip
            a.plot([vs_ref], [0.0], marker="o", color="black", markersize=5, clip_on=False, zorder=6,
                   linestyle="none")  # fmt: skip
            none = []
            for i, law in enumerate(names):
                entry = data["laws"][law]
                st = _style.series_style(i + 1)
                vs = entry["capture_velocity"]
                label = _core.get(law).LABEL
                if entry["fitted"]:
                    label += f"\n  (fitted: {_fitted_text(law, entry)})"
                if vs > 0.0 and math.isfinite(vs):
                    label += f", $V_s$ = {vs:.3g} m/s"
                elif np.isfinite(entry["restitution"]).any():
                    none.append(_core.get(law).LABEL)
                else:
                    none.append(_core.get(law).LABEL + " (at any $G$; not drawn)")
                if not np.isfinite(entry["restitution"]).any():
                    continue  # listed under "no capture"
                a.plot(V, entry["restitution"], linewidth=1.2, label=label, zorder=3, **st)
                if vs > 0.0 and math.isfinite(vs):
                    a.plot([vs], [0.0], marker="v", color=st["color"], markersize=6, clip_on=False, zorder=5,
                           linestyle="none")  # fmt: skip
            a.set_xscale("log")
            a.set_xlim(V.min(), V.max())
            a.set_ylim(0.0, 1.05)
            a.set_title(f"({chr(ord('a') + k)}) {title}", fontsize=7.5)
            a.set_xlabel(axis_label("velocity", "Impact speed"))
            if none:
                a.text(0.97, 0.03, "no capture ($V_s$ = 0):\n" + "\n".join(none), transform=a.transAxes,
                       ha="right", va="bottom", fontsize=5.5, color="0.25",
                       bbox={"facecolor": "white", "edgecolor": "0.7", "linewidth": 0.4, "pad": 2})  # fmt: skip
            handles, labels = a.get_legend_handles_labels()
            if legend_axes[k] is not None:
                legend_axes[k].legend(handles, labels, loc="upper center", fontsize=5.5, frameon=False)
            else:
                a.legend(fontsize=5.5, loc="center right", framealpha=0.9)
        axes[0].set_ylabel(axis_label("restitution", "Coefficient of restitution"))
        fig.suptitle(
            f"{data['label']}: $G$ = {data['work_of_adhesion']:g} J/m$^2$, sphere on a wall; markers on $e = 0$: "
            "capture velocity $V_s$\n"
            "each code's adhesion input from $G$; an input without default fitted to the whole law; "
            "the others at the law's defaults",
            fontsize=7,
        )
    return axes
