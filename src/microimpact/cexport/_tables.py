"""Restitution tables for other codes (CSV): ``e`` against ``V/V_y`` for several ``V_s/V_y``, and per size."""

from __future__ import annotations

import math

import numpy as np

from .._validation import check_nonnegative
from ..adhesion import (
    adhesive_restitution,
    check_adhesion_rule,
    sticking_velocity,
    whole_law_restitution,
    whole_law_table,
)
from ..core import models as _models
from ..quantities import QUANTITIES
from ._common import check_size_names, comment_text, sized_pair

__all__ = ["restitution_table", "write_tables", "DEFAULT_V_OVER_VY", "DEFAULT_VS_OVER_VY", "DEFAULT_SPEEDS"]


def restitution_table(v_over_vy, vs_over_vy_values, adhesion="additive"):
    """Normal restitution ``e`` against ``V/V_y`` for several ``V_s/V_y`` (a lookup table for other codes).

    Everything scales: ``e`` depends on ``V`` only through ``V/V_y`` (seed
    eq. 27) and on adhesion only through ``V_s/V`` (:func:`adhesive_restitution`);
    Thornton & Ning's whole law, too, depends on these two groups only
    (:mod:`microimpact.core.adhesion`).

    Parameters
    ----------
    v_over_vy : array_like (M,)
        Normal impact speed over the yield velocity, ``V/V_y`` >= 0.
    vs_over_vy_values : array_like (K,)
        Sticking velocity over yield velocity, ``V_s/V_y`` >= 0 (0: no adhesion).
    adhesion : str, optional
        As ``adhesion=`` of :func:`~microimpact.wall.wall_interaction`: ``"additive"`` (default) or
        ``"thornton_ning_1998_adhesive_plastic"``, the whole law through its table
        (:func:`~microimpact.adhesion.whole_law_restitution`; beyond the table, ``V/V_y > 1000`` or
        ``V_s/V_y > 10``, its edge is used).

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
    check_adhesion_rule(adhesion)
    v = np.atleast_1d(check_nonnegative("v_over_vy", v_over_vy)).reshape(-1)
    if np.isinf(v).any():  # the restitution's own check would name the speed, which the caller did not give
        raise ValueError("v_over_vy must be finite, got inf")
    s = np.atleast_1d(check_nonnegative("vs_over_vy_values", vs_over_vy_values)).reshape(-1)
    if adhesion == "additive":
        return adhesive_restitution(v[:, None], 1.0, s[None, :])
    return whole_law_restitution(v[:, None], 1.0, s[None, :])[0]


def _fmt_num(x):
    """Shortest text that reads back to the same double."""
    x = float(x)
    if not math.isfinite(x):
        return "inf" if x > 0 else ("-inf" if x < 0 else "nan")
    return str(int(x)) if x.is_integer() and abs(x) < 1e15 else repr(x)


def _slug(text):
    keep = "".join(c if c.isalnum() else "_" for c in str(text).lower())
    return "_".join(p for p in keep.split("_") if p) or "pair"


def _head(text, quantity):
    """One header cell ``(name, unit)``: the column's name as users read it (kept as released) and the
    unit of its quantity's row of :data:`~microimpact.quantities.QUANTITIES`."""
    return text, QUANTITIES[quantity].unit


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
    adhesion="additive",
):
    """Write restitution tables as CSV for use in other codes.

    Files (units in the header; ``#`` lines are comments):

    * ``restitution_vs_v_over_vy.csv``: ``e`` against ``V/V_y`` with one column
      per ``V_s/V_y`` value (:func:`restitution_table`); valid for any pair.
    * ``restitution_<pair>_d<diameter>um.csv`` for each pair and diameter:
      normal impact speed [m/s], ``e`` [-] and the stick flag (0/1), with the
      pair's ``V_y`` and the size's ``V_s`` in the comments; with the whole law a fourth
      column, ``outside table`` (0/1), and the law's own capture speed in the comments.

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
    adhesion : str, optional
        ``"additive"`` (default; the files are those of the releases before the option, byte for
        byte) or ``"thornton_ning_1998_adhesive_plastic"``, as :func:`restitution_table`: the
        restitution :func:`~microimpact.wall.wall_interaction` and the C file of the same
        ``adhesion`` give (:func:`~microimpact.adhesion.whole_law_restitution`).

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
    check_adhesion_rule(adhesion)
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
    written = [write_universal_table(out_dir, v, s, adhesion)]
    for pair, tag, d, p in jobs:
        path = out_dir / f"restitution_{tag}d{float(d) * 1e6:g}um.csv"
        write_size_table(path, pair, d, p, V, G, adhesion=adhesion)
        written.append(path)
    return written


def _universal_text(adhesion):
    """Comment lines of the universal table for adhesion rule ``adhesion`` (checked: the additive rule
    or the whole law, by its model name)."""
    if adhesion == "additive":
        return [
            "seed eq. 27 with the adhesive loss of Thornton & Ning (1998): e^2 = e_p^2 - (V_s/V)^2, "
            "e = 0 (stick) when e_p V <= V_s",
        ]
    return [
        f"the whole adhesive elastic-plastic law of Thornton & Ning (1998) (microimpact's {adhesion}), through",
        "the table of its universal curve: e^2 = e_p^2 - (V_s/V)^2 + D(V/V_y, V_s/V_y), e = 0 (stick) where e^2 <= 0,",
        "e_p the seed's eq. 27 (microimpact.adhesion.whole_law_restitution; as wall_interaction and the C file)",
    ]


def write_universal_table(out_dir, v, s, adhesion="additive"):
    """``restitution_vs_v_over_vy.csv`` of :func:`write_tables`; returns its path."""
    path = out_dir / "restitution_vs_v_over_vy.csv"
    table = restitution_table(v, s, adhesion)
    extra = []
    if adhesion != "additive":
        tab = whole_law_table()
        rows = np.asarray(v) > tab.x_max
        cols = np.asarray(s) > tab.y_max
        if rows.any() or cols.any():
            extra.append(
                f"outside the whole law's table (V/V_y > {tab.x_max:g} or V_s/V_y > {tab.y_max:g}; its edge used, "
                f"flagged): {int(np.count_nonzero(rows))} rows, columns V_s/V_y = "
                + (", ".join(_fmt_num(x) for x in np.asarray(s)[cols]) or "none")
            )
    _write_csv(
        path,
        [
            "microimpact: normal restitution e against V/V_y, one column per V_s/V_y",
            *_universal_text(adhesion),
            "V: normal impact speed, V_y: yield velocity (eq. 28), V_s: sticking velocity",
            *extra,
        ],
        [_head("V/V_y", "normalized_velocity")] + [_head(f"e at V_s/V_y={_fmt_num(x)}", "restitution") for x in s],
        [v, *np.asarray(table).T],
    )
    return path


def write_size_table(path, pair, d, p, V, G, extra=(), adhesion="additive"):
    """One per-size table of :func:`write_tables` (``p`` is ``pair`` at diameter ``d``)."""
    Vy = p.yield_velocity
    Vs = float(sticking_velocity(G, p.effective_modulus, p.effective_radius, p.effective_mass))
    columns = [_head("normal speed", "velocity"), _head("restitution e", "restitution"), _head("stuck", "stuck")]
    if adhesion == "additive":
        e = adhesive_restitution(V, Vy, Vs)
        law = []
    else:
        e, outside = whole_law_restitution(V, Vy, Vs)
        Vc = float(
            _models.get(adhesion).sticking_velocity(
                p.effective_modulus, p.effective_radius, p.effective_mass, p.limiting_pressure, (G,)
            )
        )
        columns.append(_head("outside table", "outside_table"))
        law = [
            f"adhesion: {adhesion} (Thornton & Ning 1998, the whole law, through its table); its capture "
            f"velocity {Vc:.10g} m/s",
        ]
    stuck = (Vs > 0.0) & (e == 0.0)
    values = [V, e, np.broadcast_to(stuck, np.shape(V)).astype(np.int8)]
    if adhesion != "additive":
        values.append(np.broadcast_to(outside, np.shape(V)).astype(np.int8))
    _write_csv(
        path,
        [
            f"microimpact: normal restitution of {comment_text(pair.label or 'a sphere')} on a flat, "
            f"diameter {float(d):.6g} m",
            f"E* = {p.effective_modulus:.6g} Pa, p_y = {p.limiting_pressure:.6g} Pa, "
            f"density = {pair.density:.6g} kg/m^3, work of adhesion G = {G:.6g} J/m^2",
            f"yield velocity V_y = {Vy:.10g} m/s, sticking velocity V_s = {Vs:.10g} m/s",
            *law,
            *(comment_text(x) for x in extra),
        ],
        columns,
        values,
    )
