"""Capture of oblique adhesive impacts against particle size: the outcome map over diameter and angle.

Why a map and not a capture efficiency. On a sphere and a flat nothing tangential acts back on the
normal motion (:mod:`microimpact.oblique.adhesive`), so a particle of diameter ``d`` hitting at speed
``V`` and angle ``theta`` from the normal is captured exactly where the normal law captures its
normal component: ``V cos(theta) <= V_s(d)``, ``V_s`` the law's capture velocity. For one speed and
one angle the fraction captured against ``d`` is therefore a step from 1 to 0 at the capture
diameter ``d_c(theta)``, the root of ``V_s(d) = V cos(theta)`` (``V_s`` falls with ``d``): a curve of
fractions would carry one number per angle. The map carries that boundary ``theta_c(d) =
arccos(V_s(d)/V)`` for every angle at once, and what the integration adds to it: how a captured
particle ends (``"stick"`` head-on, ``"captured rolling"`` where the contact sticks and the particle
rolls on, ``"captured sliding"`` where it slides at capture), and, for the particles that bounce,
the tangential restitution ``v_t'/v_t`` as contours.

:func:`capture_size_data` computes the outcome (:func:`microimpact.oblique.adhesive.adhesive_oblique_impact`
with the law and parameters of :func:`microimpact.oblique.adhesive.adhesive_law`) on a grid of
diameter and angle, and the boundary from :func:`microimpact.stick.capture_velocities`;
:func:`plot_capture_size` draws it. matplotlib (the ``plot`` extra) is imported only when the plot
function is called.
"""

from __future__ import annotations

import math

import numpy as np

from ..oblique import adhesive as ad
from ..oblique import stiffness_ratio_of
from ..quantities import axis_label
from . import style as _style
from .oblique_adhesive import COLORS

__all__ = ["capture_size_data", "plot_capture_size", "capture_diameter", "OUTCOME_COLORS"]

#: Fill colour of each outcome of :data:`microimpact.oblique.adhesive.OUTCOMES` (Okabe & Ito).
#: The outcomes' colours, those of the speed-angle capture map (one palette for the same four outcomes).
OUTCOME_COLORS = COLORS


def _default_pair():
    from ..pair import ContactPair

    # the seed's NH4Fl particle on silicon (Sec. 3.1), its materials named so that kappa = 4 G*/E* follows
    return ContactPair.from_materials(
        "nh4fl", "silicon", radius=2.45e-6, limiting_pressure=156e6, label="NH$_4$Fl on silicon"
    )


def capture_diameter(pair, velocity, work_of_adhesion, *, adhesion=None, lo=1e-9, hi=1e-3):
    """The diameter ``d_c`` [m] below which a head-on impact at ``velocity`` [m/s] is captured: the root
    of ``V_s(d) = velocity`` (:func:`microimpact.stick.capture_velocities` of the law ``adhesion``,
    default the whole law), found by bisection in ``log d`` within ``[lo, hi]``; NaN where ``V_s - V``
    does not change sign there."""
    from scipy.optimize import brentq

    from .. import stick

    law = adhesion or stick.FULL_LAW

    def miss(log_d):
        vs = stick.capture_velocities(pair, [math.exp(log_d)], work_of_adhesion, [law])[law]["capture_velocity"][0]
        return math.log(vs / velocity) if vs > 0.0 else -math.inf

    a, b = math.log(lo), math.log(hi)
    if not (miss(a) > 0.0 > miss(b)):
        return math.nan
    return math.exp(brentq(miss, a, b, xtol=1e-10))


def capture_size_data(
    pair=None,
    velocity=1.0,
    work_of_adhesion=0.1,
    friction=0.3,
    *,
    diameter=None,
    angle=None,
    adhesion=None,
    tangential="mindlin",
    steps=1000,
):
    """Outcome of oblique adhesive impacts over diameter and angle, at one impact speed.

    Parameters
    ----------
    pair : ContactPair, optional
        The particle and wall at any size (``E*``, ``p_y``, density, and ``kappa`` from its materials
        are kept, the diameter varied); default the seed's NH4Fl on silicon (``p_y`` = 156 MPa).
    velocity : float
        Impact speed ``V`` [m/s].
    work_of_adhesion : float
        ``G`` [J/m^2] of the adhesive law.
    friction : float
        Coulomb ``mu`` [-].
    diameter, angle : array_like, optional
        Grids [m], [deg]; default 0.3-30 um (30 points, log-spaced) and 0-88 deg in 4 deg steps (each
        impact costs about 15 ms, most of it the law's pull-off force along its unloading branch).
    adhesion : str, optional
        The adhesive normal law (default the whole law, :func:`microimpact.oblique.adhesive.adhesive_law`).
    tangential : str
        Tangential law (:data:`microimpact.oblique.adhesive.ADHESIVE_LAWS`).
    steps : int
        Integration steps per contact time (the outcome's classification is converged at 1000).

    Returns
    -------
    dict
        ``diameter`` [m], ``angle`` [deg], ``outcome`` (index into
        :data:`~microimpact.oblique.adhesive.OUTCOMES`, angle rows, diameter columns),
        ``tangential_restitution`` (NaN where captured), ``capture_velocity`` ``V_s(d)`` [m/s] of the
        normal law, ``capture_angle`` ``arccos(V_s/V)`` [deg] (90 where every angle captures),
        ``capture_diameter`` the head-on ``d_c`` [m] (:func:`capture_diameter`), the boundary on a fine
        grid (``boundary_diameter`` [m] from ``d_c`` up, ``boundary_angle`` [deg]), and the inputs
        ``velocity``, ``work_of_adhesion``, ``friction``, ``model``, ``label``.
    """
    from .. import stick

    pair = _default_pair() if pair is None else pair
    d = np.geomspace(0.3e-6, 30e-6, 30) if diameter is None else np.atleast_1d(np.asarray(diameter, dtype=float))
    th = np.linspace(0.0, 88.0, 23) if angle is None else np.atleast_1d(np.asarray(angle, dtype=float))
    model, params = ad.adhesive_law(adhesion, None, work_of_adhesion)
    kappa = None if tangential == "rigid" else stiffness_ratio_of(pair)
    code = np.empty((th.size, d.size), dtype=int)
    et = np.full((th.size, d.size), np.nan)
    for j, dd in enumerate(d):
        out = ad.adhesive_oblique_impact(
            pair.resized(radius=0.5 * dd), velocity, th, friction, model=model, params=params, tangential=tangential,
            kappa=kappa, steps=steps,
        )  # fmt: skip
        code[:, j] = [ad.OUTCOMES.index(o) for o in out.outcome]
        et[:, j] = np.where(out.captured, np.nan, out.tangential_restitution)
    vs = stick.capture_velocities(pair, d, work_of_adhesion, [model])[model]["capture_velocity"]
    with np.errstate(invalid="ignore"):
        cap_angle = np.where(vs >= velocity, 90.0, np.degrees(np.arccos(np.minimum(vs / velocity, 1.0))))
    dc = capture_diameter(pair, velocity, work_of_adhesion, adhesion=model)
    # the boundary on a fine grid from d_c up: arccos(V_s/V) leaves 0 with an infinite slope there
    if math.isfinite(dc) and dc < d[-1]:
        fine = dc * np.geomspace(1.0, d[-1] / dc, 160)
        vs_fine = stick.capture_velocities(pair, fine, work_of_adhesion, [model])[model]["capture_velocity"]
        fine_angle = np.degrees(np.arccos(np.clip(vs_fine / velocity, 0.0, 1.0)))
        fine_angle[0] = 0.0  # V_s(d_c) = V to the root's tolerance
    else:
        fine, fine_angle = np.empty(0), np.empty(0)
    return {
        "diameter": d,
        "angle": th,
        "outcome": code,
        "tangential_restitution": et,
        "capture_velocity": np.asarray(vs, dtype=float),
        "capture_angle": cap_angle,
        "capture_diameter": dc,
        "boundary_diameter": fine,
        "boundary_angle": fine_angle,
        "velocity": float(velocity),
        "work_of_adhesion": float(work_of_adhesion),
        "friction": float(friction),
        "model": model,
        "label": pair.label or "",
    }


def plot_capture_size(pair=None, velocity=1.0, work_of_adhesion=0.1, friction=0.3, ax=None, *, data=None, **kw):
    """Draw the outcome map of :func:`capture_size_data` (or of ``data``); returns the Axes.

    Diameter on a log axis, angle from the normal on a linear one; the outcome as fill, the capture
    boundary ``V cos(theta) = V_s(d)`` as a black line, the head-on capture diameter ``d_c`` marked on
    the 0 deg axis, and the tangential restitution of the rebounds as grey contours.
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    if data is None:
        data = capture_size_data(pair, velocity, work_of_adhesion, friction, **kw)
    d_um = data["diameter"] * 1e6
    th = data["angle"]
    code = data["outcome"]
    with _style.style() as plt:
        if ax is None:
            _, ax = plt.subplots(figsize=(3.5, 3.4), layout="constrained")
        cmap = ListedColormap([OUTCOME_COLORS[o] for o in ad.OUTCOMES])
        ax.pcolormesh(d_um, th, code, cmap=cmap, vmin=-0.5, vmax=len(ad.OUTCOMES) - 0.5, shading="nearest",
                      rasterized=True)  # fmt: skip
        et = data["tangential_restitution"]
        if np.isfinite(et).sum() > 3:
            cs = ax.contour(d_um, th, et, levels=[0.6, 0.7, 0.8, 0.9], colors="0.45", linewidths=0.6)
            ax.clabel(cs, fontsize=5.5, fmt=lambda v: f"{v:.1f}", inline_spacing=2)
        ax.plot(data["boundary_diameter"] * 1e6, data["boundary_angle"], color="black", linewidth=1.3,
                label=r"capture boundary $V\cos\theta = V_s(d)$")  # fmt: skip
        dc = data["capture_diameter"]
        if math.isfinite(dc):
            ax.plot([dc * 1e6], [0.0], marker="v", color="#D55E00", markersize=7, clip_on=False, zorder=6,
                    linestyle="none", label=f"head-on $d_c$ = {dc * 1e6:.3g} $\\mu$m")  # fmt: skip
        ax.set_xscale("log")
        ax.set_xlim(d_um[0], d_um[-1])
        ax.set_ylim(0.0, th[-1])
        ax.set_xlabel(axis_label("diameter", "Particle diameter"))
        ax.set_ylabel(axis_label("angle", "Impact angle from the normal"))
        handles = [
            Patch(facecolor=OUTCOME_COLORS[o], edgecolor="0.3", linewidth=0.4, label=o)
            for o in ad.OUTCOMES
            if (code == ad.OUTCOMES.index(o)).any()
        ]
        handles += ax.get_lines()[-2:] if math.isfinite(dc) else ax.get_lines()[-1:]
        if np.isfinite(et).sum() > 3:  # the contours are read from their labels; the legend says of what
            handles.append(Line2D([], [], color="0.45", linewidth=0.6, label=r"rebounds: $v_t'/v_t$ (labelled)"))
        ax.figure.legend(handles=handles, fontsize=6, loc="outside lower center", ncols=2, frameon=False)
        ax.set_title(
            f"{data['label']}: $V$ = {data['velocity']:g} m/s, $G$ = {data['work_of_adhesion']:g} J/m$^2$, "
            f"$\\mu$ = {data['friction']:g}",
            fontsize=7,
        )
    return ax
