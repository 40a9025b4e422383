"""One-way hand-off from OpenFOAM: read the wall hits its particle tracking recorded, decide each.

An OpenFOAM lagrangian solver (``icoUncoupledKinematicParcelFoam``, ``MPPICFoam``, ...) tracks the
particles through the flow; its ``patchPostProcessing`` cloud function writes every hit on the
chosen patches (``postProcessing/lagrangian/<cloud>/<function>/<time>/<patch>.post``: time,
position, velocity, diameter, density, ... of the parcel as it reaches the wall). This module

* reads those records (:func:`read_patch_hits`; the column layout of OpenFOAM ESI v1912, named in
  the file's ``#`` header, so other versions that name their columns the same way read too);
* decides bounce or stick for each hit (:func:`decide`) with the seed's model and Thornton & Ning's
  adhesion (:func:`microimpact.wall.wall_interaction`, the default) or any impact model of
  :func:`microimpact.models.available` with its own parameters (an adhesive one sticks where its
  ``e`` is 0);
* reports, per particle size, the fraction of the injected particles that stick, and the
  distributions of the impact speeds and angles (:func:`deposition_report`: an xarray Dataset, to
  NetCDF with :func:`microimpact.sweep.sweep_to_netcdf`; :func:`plot_report`).

Where the hand-off is exact and where not. The first impact of each particle is exact: the
particle reached the wall through the flow OpenFOAM computed, and what happens at the wall is
decided by microimpact at the recorded velocity. Everything after a bounce is not: the rebound,
re-entrainment by the flow, second impacts and a deposit's feedback on the flow are not in a
one-way hand-off (the case lets particles leave at the wall: ``escape``). For those, run
microimpact inside the CFD code: ``microimpact export`` writes a C99 function (the seed's model
with adhesion and friction, the same numbers as :func:`~microimpact.wall.wall_interaction`) to call
from a patch interaction model, which then applies the rebound velocity and tracks the particle on
(two-way in the particle sense).

xarray is needed for :func:`deposition_report` (``pip install 'microimpact[sweep]'``).
"""

from __future__ import annotations

import math
import os
import stat
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._optional import require
from .quantities import DIMENSIONLESS, QUANTITIES
from .wall import wall_interaction

__all__ = ["PatchHits", "read_patch_hits", "decide", "deposition_report", "plot_report"]


@dataclass(frozen=True)
class PatchHits:
    """Wall hits recorded by OpenFOAM's ``patchPostProcessing`` (one entry per hit).

    Attributes
    ----------
    time : ndarray (N,)
        Simulation time of the hit [s].
    position : ndarray (N, 3)
        Where the parcel hit [m].
    velocity : ndarray (N, 3)
        Its velocity as it hit [m/s].
    diameter : ndarray (N,)
        Its diameter [m].
    density : ndarray (N,)
        Its density [kg/m^3].
    n_particle : ndarray (N,)
        Particles the parcel stands for [-].
    orig_id, orig_proc : ndarray of int64 (N,)
        The parcel's identity: its number on the processor that injected it, and that processor.
    age : ndarray (N,)
        Time since its injection [s] (NaN where not recorded).
    patch : ndarray of str (N,)
        The patch hit.
    """

    time: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    diameter: np.ndarray
    density: np.ndarray
    n_particle: np.ndarray
    orig_id: np.ndarray
    orig_proc: np.ndarray
    age: np.ndarray
    patch: np.ndarray

    def __len__(self):
        return int(self.time.size)


def _columns(header: str) -> list[str]:
    return header.lstrip("#").replace("(", " ").replace(")", " ").split()


#: The largest record read [bytes]. A hit is a line of about 300 characters, so this is some
#: 3.5 million hits per file; its floats take a few times the text in memory, which is why the
#: text is not read without a bound (a device such as ``/dev/zero`` never ends).
MAX_RECORD_BYTES = 1 << 30

#: Columns holding labels (OpenFOAM's integers): read as integers, never through a float that
#: could round them or overflow the int64 they are stored in.
_LABELS = ("origId", "origProc")
_INT64 = np.iinfo(np.int64)


def _read_text(path: Path) -> str:
    """The text of a regular file, read with the bound :data:`MAX_RECORD_BYTES`.

    A FIFO would block the read until a writer comes and a device or a growing file need not end,
    so the file's kind and size are checked with ``os.stat`` before opening and again on the open
    descriptor (opened non-blocking, so a FIFO put in its place between the two cannot hang), and
    the read itself stops one byte past the bound.
    """
    try:
        st = os.stat(path)
    except OSError as exc:
        raise ValueError(f"{path}: cannot be read ({exc.strerror})") from None
    if not stat.S_ISREG(st.st_mode):
        raise ValueError(f"{path}: not a regular file (a directory, FIFO or device named like a record?)")
    if st.st_size > MAX_RECORD_BYTES:
        raise ValueError(f"{path}: {st.st_size} bytes, more than the {MAX_RECORD_BYTES} a record is read up to")
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as exc:
        raise ValueError(f"{path}: cannot be read ({exc.strerror})") from None
    with os.fdopen(fd, "rb") as fh:
        if not stat.S_ISREG(os.fstat(fh.fileno()).st_mode):
            raise ValueError(f"{path}: not a regular file (it changed while being opened)")
        data = fh.read(MAX_RECORD_BYTES + 1)
    if len(data) > MAX_RECORD_BYTES:
        raise ValueError(f"{path}: more than the {MAX_RECORD_BYTES} bytes a record is read up to")
    try:
        return data.decode()
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not text (byte {exc.start} is not UTF-8)") from None


def _label(token: str, path: Path, line: int, name: str) -> int:
    """An integer column's value: an integer literal, or a float that is one exactly, within int64."""
    try:
        value = int(token)
    except ValueError:
        try:
            x = float(token)
        except ValueError:
            raise ValueError(f"{path}, line {line}: {name} {token!r} is not a number") from None
        # beyond 2**53 a float no longer tells neighbouring integers apart: not an exact label
        if not (math.isfinite(x) and x == math.floor(x) and abs(x) <= 2.0**53):
            raise ValueError(f"{path}, line {line}: {name} {token!r} is not an integer label") from None
        value = int(x)
    if not _INT64.min <= value <= _INT64.max:
        raise ValueError(f"{path}, line {line}: {name} {token!r} is outside the int64 range of labels")
    return value


def _read_one(path: Path):
    text = _read_text(path)
    lines = text.splitlines()
    at = next((k for k, ln in enumerate(lines) if ln.startswith("#")), None)
    if at is None:
        raise ValueError(f"{path}: no '#' header naming the columns (not a patchPostProcessing file?)")
    names = _columns(lines[at])
    seen = set()
    for n in names:
        if n in seen:  # the later column would silently take the earlier one's place in the table
            raise ValueError(f"{path}, line {at + 1}: column {n!r} named twice in the header")
        seen.add(n)
    need = ["Time", "position0", "position1", "position2", "U0", "U1", "U2", "d", "rho", "nParticle", "origId"]
    missing = [n for n in need if n not in names]
    if missing:
        raise ValueError(f"{path}: column {missing[0]!r} missing from the header (found: {' '.join(names[:12])} ...)")
    labels = [(i, n) for i, n in enumerate(names) if n in _LABELS]
    i_np = names.index("nParticle")
    rows, ids = [], []
    for k, ln in enumerate(lines):
        if not ln.strip() or ln.startswith("#"):
            continue
        parts = ln.replace("(", " ").replace(")", " ").split()
        if len(parts) != len(names):
            raise ValueError(f"{path}, line {k + 1}: {len(parts)} values for {len(names)} columns")
        try:
            row = [float(x) for x in parts]
        except ValueError:
            raise ValueError(f"{path}, line {k + 1}: not a number in {ln[:80]!r}") from None
        # a parcel stands for nParticle particles, the weight of its hit in every count: fractional
        # where OpenFOAM sizes parcels by mass, but never negative, infinite or NaN
        if not (math.isfinite(row[i_np]) and row[i_np] >= 0.0):
            raise ValueError(f"{path}, line {k + 1}: nParticle {parts[i_np]!r} is not a finite count >= 0")
        rows.append(row)
        ids.append([_label(parts[i], path, k + 1, n) for i, n in labels])
    arr = np.array(rows, dtype=float).reshape(-1, len(names))
    col = {n: arr[:, i] for i, n in enumerate(names)}
    lab = np.array(ids, dtype=np.int64).reshape(-1, len(labels))
    col.update({n: lab[:, j] for j, (_, n) in enumerate(labels)})
    return col, path.stem


def read_patch_hits(path) -> PatchHits:
    """Read the wall hits OpenFOAM's ``patchPostProcessing`` cloud function wrote.

    Parameters
    ----------
    path : str or os.PathLike
        One ``<patch>.post`` file, or a directory (a case, its ``postProcessing``, or a cloud
        function's directory): every ``*.post`` file below it is read (all times, all patches).

    Returns
    -------
    PatchHits
        Sorted by time, then parcel.

    Raises
    ------
    ValueError
        An empty path (it would mean the working directory), no such file or no ``.post`` file
        below the directory, a ``.post`` that is not a regular file (a FIFO would block, a device
        need not end) or is larger than :data:`MAX_RECORD_BYTES`, or a file that is not a
        ``patchPostProcessing`` record: no header, a column named twice, a row of the wrong
        length or with a non-number, an ``origId``/``origProc`` that is not an integer within
        int64, an ``nParticle`` that is not a finite count >= 0 (the message names the file and
        line).
    """
    if os.fspath(path) == "":  # Path("") is the working directory: never read it by accident
        raise ValueError("path must name a .post file or a directory holding them, got ''")
    p = Path(path)
    if p.is_dir():
        files = sorted(p.rglob("*.post"))
        if not files:
            raise ValueError(f"path {str(path)!r} holds no patchPostProcessing '*.post' file")
    elif p.exists():
        files = [p]  # _read_text refuses what is not a regular file
    else:
        raise ValueError(f"path {str(path)!r} does not exist")
    cols, patches = [], []
    for f in files:
        c, name = _read_one(f)
        cols.append(c)
        patches.append(np.full(c["Time"].size, name, dtype=object))

    def cat(key, default=math.nan):
        return np.concatenate([c[key] if key in c else np.full(c["Time"].size, default) for c in cols])

    t = cat("Time")
    order = np.lexsort((cat("origId"), cat("origProc", 0), t))
    pos = np.column_stack([cat("position0"), cat("position1"), cat("position2")])
    vel = np.column_stack([cat("U0"), cat("U1"), cat("U2")])
    return PatchHits(
        time=t[order],
        position=pos[order],
        velocity=vel[order],
        diameter=cat("d")[order],
        density=cat("rho")[order],
        n_particle=cat("nParticle")[order],
        orig_id=cat("origId")[order],
        orig_proc=cat("origProc", 0)[order],
        age=cat("age")[order],
        patch=np.concatenate(patches)[order],
    )


def decide(
    hits: PatchHits,
    normal=(0.0, 0.0, 1.0),
    *,
    model: str | None = None,
    pair=None,
    material="nh4fl",
    wall="silicon",
    work_of_adhesion=0.0,
    friction=0.0,
    **params,
) -> dict:
    """Bounce or stick for every hit, and its impact speed and angle.

    Parameters
    ----------
    hits : PatchHits
        From :func:`read_patch_hits`.
    normal : array_like (3,) or (N, 3)
        Wall normal pointing into the fluid (default ``+z``); normalised here.
    model : str, optional
        None (default): :func:`microimpact.wall.wall_interaction` (the seed's model, Thornton &
        Ning's adhesion with ``work_of_adhesion``, Coulomb ``friction``) for the particle
        ``material`` on the ``wall`` material, with each hit's diameter and density. Otherwise an
        impact model (:func:`microimpact.models.available`) with its ``**params``, on ``pair``
        resized to each hit's diameter and density; the particle sticks where the model's ``e`` is 0
        (the adhesive models below their sticking speed).
    pair : ContactPair, optional
        With ``model``: the pair whose ``E*`` and ``p_y`` are used (default: ``material`` on
        ``wall``).
    material, wall : str
        Particle and wall materials (:func:`microimpact.materials.list_materials`).
    work_of_adhesion, friction : float
        ``G`` [J/m^2] and ``mu`` [-] of the default decision.

    Returns
    -------
    dict
        Arrays (N,): ``normal_speed`` [m/s] (``-v.n``), ``tangential_speed`` [m/s], ``angle``
        [deg] from the normal, ``restitution`` [-] (0 for a stuck particle), ``stuck`` (bool).

    Raises
    ------
    ValueError
        Bad normal or model options (named), or a hit moving away from the wall.
    """
    n = np.asarray(normal, dtype=float)
    norm = np.linalg.norm(n, axis=-1, keepdims=True)
    if n.shape[-1] != 3 or not np.all(norm > 0.0) or not np.all(np.isfinite(n)):
        raise ValueError(f"normal must be a non-zero 3-vector (or one per hit), got {normal!r}")
    n = np.broadcast_to(n / norm, hits.velocity.shape)
    v = hits.velocity
    vn = -np.einsum("ij,ij->i", v, n)
    vt = np.linalg.norm(v + vn[:, None] * n, axis=1)
    if np.any(vn <= 0.0):
        i = int(np.flatnonzero(vn <= 0.0)[0])
        raise ValueError(f"hit {i} moves away from the wall (normal speed {vn[i]!r} m/s): check the normal")
    angle = np.degrees(np.arctan2(vt, vn))
    if model is None:
        if params or pair is not None:
            raise ValueError("pair and model parameters apply with model=...; the default decision takes materials")
        out = wall_interaction(
            v,
            n,
            hits.diameter,
            hits.density,
            material=material,
            wall=wall,
            work_of_adhesion=work_of_adhesion,
            friction=friction,
        )
        stuck = np.asarray(out.stuck, dtype=bool)
        e = np.where(stuck, 0.0, np.asarray(out.restitution, dtype=float))
    else:
        if work_of_adhesion != 0.0 or friction != 0.0:
            raise ValueError(
                "work_of_adhesion and friction belong to the default decision (model=None); "
                f"model {model!r} takes its own parameters"
            )
        from .pair import ContactPair

        base = pair if pair is not None else ContactPair.from_materials(material, wall, radius=1e-6)
        e = np.empty(vn.size)
        keys = np.column_stack([hits.diameter, hits.density])
        for d, rho in np.unique(keys, axis=0):
            sel = (hits.diameter == d) & (hits.density == rho)
            res = base.resized(radius=0.5 * d, density=rho).impact(vn[sel], model=model, warn=False, **params)
            e[sel] = np.asarray(res.restitution, dtype=float)
        stuck = ~(e > 0.0)
        e = np.where(stuck, 0.0, e)
    return {"normal_speed": vn, "tangential_speed": vt, "angle": angle, "restitution": e, "stuck": stuck}


def _attrs(unit):
    """The NetCDF attributes of a variable in ``unit`` (a unit of the quantities table), by its long name."""
    return lambda long_name: {"units": unit, "long_name": long_name}


def deposition_report(hits: PatchHits, decision: dict, injected, *, speed_bins=20, angle_bins=18):
    """Deposition against particle size and the distributions of impact speed and angle.

    Parameters
    ----------
    hits : PatchHits
        The hits (first impacts: one per parcel in a one-way hand-off).
    decision : dict
        :func:`decide`'s result for ``hits``.
    injected : dict
        ``{diameter [m]: number of particles injected}`` (particles, i.e. parcels times
        ``nParticle``), the denominators of the fractions.
    speed_bins, angle_bins : int
        Bins of the histograms (speeds from 0 to the largest, angles 0-90 degrees).

    Returns
    -------
    xarray.Dataset
        Along ``diameter`` [m]: ``injected``, ``impacted`` and ``deposited`` (particles),
        ``impact_fraction`` and ``deposition_fraction`` (of the injected), ``mean_impact_speed``
        [m/s]; ``speed_count`` (``diameter`` x ``speed``, bin centres [m/s]) and ``angle_count``
        (``diameter`` x ``angle``, bin centres [deg]): impacts per bin, and ``speed_stuck`` /
        ``angle_stuck``, the stuck ones.

    Raises
    ------
    ValueError
        No diameter, an injected count that is not positive and finite, a hit diameter not among
        the injected ones, or more particles hitting than were injected for a diameter (impact
        fraction above 1: short counts, or repeated hits of rebounding parcels in the record).
    """
    xr = require("xarray", "deposition reports")
    d_all = np.asarray(sorted(float(d) for d in injected))
    if d_all.size == 0:
        raise ValueError("injected must name at least one diameter")
    counts = np.array([float(injected[d]) for d in sorted(injected)])
    if not np.all((counts > 0) & np.isfinite(counts)):
        raise ValueError(f"injected counts must be positive and finite, got {injected!r}")
    w = hits.n_particle
    vn, ang, stuck = decision["normal_speed"], decision["angle"], decision["stuck"]
    which = np.array([int(np.argmin(np.abs(d_all - d))) for d in hits.diameter], dtype=int)
    unmatched = ~np.isclose(d_all[which], hits.diameter, rtol=1e-6, atol=0.0) if hits.diameter.size else np.array([])
    if np.any(unmatched):
        raise ValueError(f"hit diameter {hits.diameter[unmatched][0]!r} m is not among the injected diameters")
    D = d_all.size
    imp = np.bincount(which, weights=w, minlength=D)
    # A one-way hand-off counts first impacts, one per parcel: no more particles can hit than were
    # injected. More means the injected counts are short or the record holds repeated hits of
    # parcels the case let rebound, and either way the fractions would be wrong, so refuse. The
    # tolerance covers the rounding of summing fractional nParticle.
    over = imp > counts * (1.0 + 1e-9)
    if np.any(over):
        k = int(np.flatnonzero(over)[0])
        raise ValueError(
            f"injected: {float(imp[k])!r} particles of diameter {float(d_all[k])!r} m hit the wall but "
            f"{float(counts[k])!r} were injected (impact fraction {float(imp[k] / counts[k])!r} > 1): injected counts too small, "
            "or the record holds repeated hits of rebounding parcels (a one-way hand-off needs the patch to let them escape)"
        )
    dep = np.bincount(which, weights=w * stuck, minlength=D)
    with np.errstate(invalid="ignore"):
        mean_v = np.bincount(which, weights=w * vn, minlength=D) / imp
    v_edges = np.linspace(0.0, float(vn.max()) * 1.0001 if vn.size else 1.0, int(speed_bins) + 1)
    a_edges = np.linspace(0.0, 90.0, int(angle_bins) + 1)

    def hist(values, edges, mask):
        out = np.zeros((D, edges.size - 1))
        for k in range(D):
            sel = (which == k) & mask
            out[k] = np.histogram(values[sel], bins=edges, weights=w[sel])[0]
        return out

    every = np.ones(vn.size, bool)
    count = _attrs(DIMENSIONLESS)  # numbers of particles and their ratios
    speed = _attrs(QUANTITIES["velocity"].unit)
    return xr.Dataset(
        {
            "injected": ("diameter", counts, count("particles injected")),
            "impacted": ("diameter", imp, count("particles that hit the wall")),
            "deposited": ("diameter", dep, count("particles that stuck")),
            "impact_fraction": ("diameter", imp / counts, count("impacted / injected")),
            "deposition_fraction": ("diameter", dep / counts, count("deposited / injected")),
            "mean_impact_speed": ("diameter", mean_v, speed("mean normal impact speed")),
            "speed_count": (("diameter", "speed"), hist(vn, v_edges, every), count("impacts")),
            "speed_stuck": (("diameter", "speed"), hist(vn, v_edges, stuck), count("stuck")),
            "angle_count": (("diameter", "angle"), hist(ang, a_edges, every), count("impacts")),
            "angle_stuck": (("diameter", "angle"), hist(ang, a_edges, stuck), count("stuck")),
        },
        coords={
            "diameter": ("diameter", d_all, _attrs(QUANTITIES["diameter"].unit)("particle diameter")),
            "speed": ("speed", 0.5 * (v_edges[1:] + v_edges[:-1]), speed("normal impact speed")),
            "angle": (
                "angle",
                0.5 * (a_edges[1:] + a_edges[:-1]),
                _attrs(QUANTITIES["angle"].unit)("impact angle from the normal"),
            ),
        },
        attrs={"title": "microimpact: deposition from OpenFOAM wall hits (one-way, first impacts)"},
    )


def plot_report(ds, axes=None, *, reference=None):
    """Three panels: deposition (and impact) fraction against diameter, impact speeds, impact angles.

    ``reference``: optional ``(diameters [m], fractions, label)`` drawn on the first panel (e.g. the
    stagnation-flow estimate of :func:`microimpact.deposition.simulate_deposition`). Returns the axes.
    """
    import matplotlib.pyplot as plt

    if axes is None:
        _, axes = plt.subplots(1, 3, figsize=(12.0, 3.6), constrained_layout=True)
    d_um = ds["diameter"].values * 1e6
    ax = axes[0]
    ax.plot(d_um, ds["impact_fraction"].values, "s--", color="0.5", mfc="none", label="impacted (OpenFOAM)")
    ax.plot(d_um, ds["deposition_fraction"].values, "o-", color="C0", label="deposited (OpenFOAM + microimpact)")
    if reference is not None:
        rd, rf, label = reference
        ax.plot(np.asarray(rd) * 1e6, rf, "k:", lw=1.5, label=label)
    ax.set_xlabel("particle diameter d [um]")
    ax.set_ylabel("fraction of injected particles [-]")
    ax.set_ylim(-0.02, 1.02)
    ax.legend(fontsize=8, loc="center right")
    ax.grid(alpha=0.3)
    for ax, key, unit in (
        (axes[1], "speed", "normal impact speed [m/s]"),
        (axes[2], "angle", "impact angle from the normal [deg]"),
    ):
        centres = ds[key].values
        width = centres[1] - centres[0] if centres.size > 1 else 1.0
        total = ds[f"{key}_count"].sum("diameter").values
        stuck = ds[f"{key}_stuck"].sum("diameter").values
        ax.bar(centres, total - stuck, width=width * 0.9, bottom=stuck, color="C1", label="bounced")
        ax.bar(centres, stuck, width=width * 0.9, color="C0", label="stuck")
        ax.set_xlabel(unit)
        ax.set_ylabel("impacts (all sizes)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    return axes
