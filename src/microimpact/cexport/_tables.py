"""Restitution tables for other codes (CSV): ``e`` against ``V/V_y`` for several ``V_s/V_y``, and per size."""

from __future__ import annotations

import math

import numpy as np

from .._validation import check_nonnegative
from ..adhesion import adhesive_restitution, sticking_velocity
from ._common import check_size_names, comment_text, sized_pair

__all__ = ["restitution_table", "write_tables", "DEFAULT_V_OVER_VY", "DEFAULT_VS_OVER_VY", "DEFAULT_SPEEDS"]


def restitution_table(v_over_vy, vs_over_vy_values):
    """Normal restitution ``e`` against ``V/V_y`` for several ``V_s/V_y`` (a lookup table for other codes).

    Everything scales: ``e`` depends on ``V`` only through ``V/V_y`` (seed
    eq. 27) and on adhesion only through ``V_s/V`` (:func:`adhesive_restitution`).

    Parameters
    ----------
    v_over_vy : array_like (M,)
        Normal impact speed over the yield velocity, ``V/V_y`` >= 0.
    vs_over_vy_values : array_like (K,)
        Sticking velocity over yield velocity, ``V_s/V_y`` >= 0 (0: no adhesion).

    Returns
    -------
    ndarray (M, K)
        ``e``; 0 where the particle sticks.

    Examples
    --------
    >>> restitution_table([0.5, 2.0, 10.0], [0.0, 0.5]).round(4)
    array([[1.    , 0.    ],
           [0.9306, 0.8964],
           [0.6586, 0.6567]])
    """
    v = np.atleast_1d(check_nonnegative("v_over_vy", v_over_vy)).reshape(-1)
    s = np.atleast_1d(check_nonnegative("vs_over_vy_values", vs_over_vy_values)).reshape(-1)
    return adhesive_restitution(v[:, None], 1.0, s[None, :])


def _fmt_num(x):
    """Shortest text that reads back to the same double."""
    x = float(x)
    if not math.isfinite(x):
        return "inf" if x > 0 else ("-inf" if x < 0 else "nan")
    return str(int(x)) if x.is_integer() and abs(x) < 1e15 else repr(x)


def _slug(text):
    keep = "".join(c if c.isalnum() else "_" for c in str(text).lower())
    return "_".join(p for p in keep.split("_") if p) or "pair"


def _write_csv(path, comments, header, columns):
    """One table in the project's CSV layout (:mod:`microimpact.io`), written atomically."""
    from ..io import write_csv

    write_csv(path, [(name, unit, col) for (name, unit), col in zip(header, columns)], comments)


#: Default grid of :func:`write_tables`: ``V/V_y`` from 0 to 100.
DEFAULT_V_OVER_VY = np.concatenate([np.linspace(0.0, 2.0, 41)[:-1], np.geomspace(2.0, 100.0, 80)])
#: Default ``V_s/V_y`` columns of the dimensionless table.
DEFAULT_VS_OVER_VY = (0.0, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0)
#: Default normal speeds of the per-size tables [m/s].
DEFAULT_SPEEDS = np.geomspace(0.01, 200.0, 161)


def write_tables(
    directory,
    pairs,
    diameters=None,
    velocities=None,
    *,
    work_of_adhesion=0.0,
    v_over_vy=None,
    vs_over_vy_values=DEFAULT_VS_OVER_VY,
):
    """Write restitution tables as CSV for use in other codes.

    Files (units in the header; ``#`` lines are comments):

    * ``restitution_vs_v_over_vy.csv``: ``e`` against ``V/V_y`` with one column
      per ``V_s/V_y`` value (:func:`restitution_table`); valid for any pair.
    * ``restitution_<pair>_d<diameter>um.csv`` for each pair and diameter:
      normal impact speed [m/s], ``e`` [1] and the stick flag (0/1), with the
      pair's ``V_y`` and the size's ``V_s`` in the comments.

    Layout: the project's CSV layout (:mod:`microimpact.io`): the header
    ``name [unit]`` on the first line, then ``#`` comment lines, then the rows.
    Each file is written to a temporary name and renamed into place when
    complete; a label reaches the comments only made safe (one line, printable).

    Parameters
    ----------
    directory : path
        Created if missing.
    pairs : ContactPair or sequence of ContactPair
        Sphere-on-flat pairs with a known density (rescaled to each diameter).
    diameters : sequence of float, optional
        Particle diameters [m]; default each pair's own.
    velocities : array_like, optional
        Normal impact speeds [m/s]; default :data:`DEFAULT_SPEEDS` (0.01-200 m/s).
    work_of_adhesion : float, optional
        ``G`` [J/m^2] (work of adhesion, not surface energy; see :func:`work_of_adhesion`).
    v_over_vy, vs_over_vy_values : array_like, optional
        Grid of the dimensionless table.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    from pathlib import Path

    from ..pair import ContactPair

    out_dir = Path(directory)
    pairs = [pairs] if isinstance(pairs, ContactPair) else list(pairs)
    if not pairs:
        raise ValueError("pairs: give at least one ContactPair")
    G = float(check_nonnegative("work_of_adhesion", work_of_adhesion))
    v = DEFAULT_V_OVER_VY if v_over_vy is None else np.atleast_1d(check_nonnegative("v_over_vy", v_over_vy))
    s = np.atleast_1d(check_nonnegative("vs_over_vy_values", vs_over_vy_values)).reshape(-1)
    V = DEFAULT_SPEEDS if velocities is None else np.atleast_1d(check_nonnegative("velocities", velocities))
    multi = len(pairs) > 1
    jobs = []  # every size checked before any file is written
    for i, pair in enumerate(pairs):
        sizes = [2.0 * pair.effective_radius] if diameters is None else list(np.atleast_1d(diameters))
        check_size_names(sizes)
        tag = f"{_slug(pair.label or f'pair{i}')}_" if multi else ""
        jobs += [(pair, tag, d, sized_pair(pair, d)) for d in sizes]
    out_dir.mkdir(parents=True, exist_ok=True)
    written = [write_universal_table(out_dir, v, s)]
    for pair, tag, d, p in jobs:
        path = out_dir / f"restitution_{tag}d{float(d) * 1e6:g}um.csv"
        write_size_table(path, pair, d, p, V, G)
        written.append(path)
    return written


def write_universal_table(out_dir, v, s):
    """``restitution_vs_v_over_vy.csv`` of :func:`write_tables`; returns its path."""
    path = out_dir / "restitution_vs_v_over_vy.csv"
    table = restitution_table(v, s)
    _write_csv(
        path,
        [
            "microimpact: normal restitution e against V/V_y, one column per V_s/V_y",
            "seed eq. 27 with the adhesive loss of Thornton & Ning (1998): e^2 = e_p^2 - (V_s/V)^2, "
            "e = 0 (stick) when e_p V <= V_s",
            "V: normal impact speed, V_y: yield velocity (eq. 28), V_s: sticking velocity",
        ],
        [("V/V_y", "1")] + [(f"e at V_s/V_y={_fmt_num(x)}", "1") for x in s],
        [v, *np.asarray(table).T],
    )
    return path


def write_size_table(path, pair, d, p, V, G, extra=()):
    """One per-size table of :func:`write_tables` (``p`` is ``pair`` at diameter ``d``)."""
    Vy = p.yield_velocity
    Vs = float(sticking_velocity(G, p.effective_modulus, p.effective_radius, p.effective_mass))
    e = adhesive_restitution(V, Vy, Vs)
    stuck = (Vs > 0.0) & (e == 0.0)
    _write_csv(
        path,
        [
            f"microimpact: normal restitution of {comment_text(pair.label or 'a sphere')} on a flat, "
            f"diameter {float(d):.6g} m",
            f"E* = {p.effective_modulus:.6g} Pa, p_y = {p.limiting_pressure:.6g} Pa, "
            f"density = {pair.density:.6g} kg/m^3, work of adhesion G = {G:.6g} J/m^2",
            f"yield velocity V_y = {Vy:.10g} m/s, sticking velocity V_s = {Vs:.10g} m/s",
            *(comment_text(x) for x in extra),
        ],
        [("normal speed", "m/s"), ("restitution e", "1"), ("stuck", "1")],
        [V, e, np.broadcast_to(stuck, np.shape(V)).astype(np.int8)],
    )
