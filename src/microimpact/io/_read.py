"""Reading back: the project's CSV tables and measured restitution data (what the fits take in)."""

from __future__ import annotations

import io as _stdio
import math
import os

import numpy as np

from .._validation import is_number_text

__all__ = ["RestitutionData", "load_restitution_csv", "read_table"]


def read_table(path) -> dict:
    """Read a CSV written by :func:`write_table` (or :func:`write_csv`) back into a dict of arrays.

    Parameters
    ----------
    path : str or os.PathLike
        The file; ``#`` lines are skipped, and the ``[unit]`` of each header name
        is dropped from the key (files of the older layout, header after the
        ``#`` lines, read the same).

    Returns
    -------
    dict of str to ndarray
        One array per column, in file order: float where every cell is numeric,
        otherwise ``object`` (strings). Units are those of the header.
    """
    import csv
    import re

    with open(path, encoding="utf-8") as fh:
        rows = [r for r in csv.reader(line for line in fh if not line.startswith("#"))]
    header, body = rows[0], rows[1:]
    out = {}
    for j, k in enumerate(header):
        key = re.sub(r"\s*\[[^\]]*\]$", "", k)
        cells = [r[j] for r in body]
        if all(is_number_text(c) for c in cells):  # float() would also take 1_0 (as 10)
            out[key] = np.array([float(c) for c in cells])
        else:
            out[key] = np.array(cells, dtype=object)
    return out


# ----------------------------------------------------------------------------- reading measured restitution data
# Column names accepted by load_restitution_csv (lower case, units stripped).
_VELOCITY_NAMES = ("velocity", "v", "speed", "impact_velocity", "impact_speed")
_RESTITUTION_NAMES = ("restitution", "e", "cor", "coefficient_of_restitution")
_SIGMA_NAMES = ("sigma", "e_err", "uncertainty", "e_sigma", "restitution_err", "restitution_sigma")
_VELOCITY_UNITS = ("m/s", "m s-1", "m s^-1", "m.s-1", "m*s^-1", "m s**-1")


class RestitutionData(tuple):
    """``(velocity, restitution, sigma)`` as read from a file, plus where each point came from.

    Unpacks like a 3-tuple; ``.lines`` holds the 1-based line number of each
    point in the file and ``.source`` the file name (used in error messages).
    """

    def __new__(cls, velocity, restitution, sigma, lines, source=""):
        self = super().__new__(cls, (velocity, restitution, sigma))
        self.lines = lines
        self.source = source
        return self

    velocity = property(lambda self: self[0], doc="impact speeds [m/s]")
    restitution = property(lambda self: self[1], doc="restitution coefficients [-]")
    sigma = property(lambda self: self[2], doc="standard uncertainties of e [-], or None")


def _column_key(text: str) -> tuple[str, str]:
    """Header cell -> (name, unit): ``"Velocity [m/s]"`` -> ``("velocity", "m/s")``."""
    text = text.strip().strip('"').strip()
    unit = ""
    for open_, close in (("[", "]"), ("(", ")")):
        if open_ in text:
            head, _, rest = text.partition(open_)
            unit = rest.split(close)[0].strip()
            text = head
    name = text.strip().lower().replace(" ", "_").replace("-", "_")
    return name, unit


def _split(line: str, delimiter):
    import csv

    if delimiter is None:
        return line.split()
    return [c.strip() for c in next(csv.reader(_stdio.StringIO(line), delimiter=delimiter))]


def load_restitution_csv(path) -> RestitutionData:
    """Read measured impact speeds and restitution coefficients from a CSV file.

    The first non-comment line is a header naming the columns (case-insensitive,
    units in brackets allowed): the speed as ``velocity``, ``V`` or ``speed``
    [m/s]; the restitution coefficient as ``restitution`` or ``e``; optionally its
    standard uncertainty as ``sigma``, ``e_err`` or ``uncertainty``. Other columns
    are ignored. Lines starting with ``#`` and blank lines are skipped, text after
    a ``#`` is a comment. Cells are separated by commas (or semicolons, tabs, or
    blanks if the header uses them).

    Parameters
    ----------
    path : str or os.PathLike
        The file.

    Returns
    -------
    RestitutionData
        Unpacks as ``velocity, restitution, sigma`` (float arrays [m/s], [-], [-];
        ``sigma`` is None without that column); ``.lines`` gives each point's line.

    Raises
    ------
    ValueError
        With the file's line number: missing columns, a wrong number of cells,
        non-numeric or non-finite cells, negative (or zero) speeds, negative
        restitution, non-positive uncertainties, no data rows. Measured values
        above 1 are kept (scatter near the yield velocity); ``e = 0`` is kept as
        "stuck" (:func:`microimpact.fitting.fit_restitution` decides whether the model allows it).

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
    ...     _ = f.write("# speed in m/s\\nvelocity,e\\n20,0.88\\n40,0.78\\n")
    >>> V, e, sigma = load_restitution_csv(f.name)
    >>> V, e, sigma
    (array([20., 40.]), array([0.88, 0.78]), None)
    >>> os.unlink(f.name)
    """
    from array import array

    name = os.fspath(path)
    where = os.path.basename(name)
    # Streamed line by line into typed arrays (8 bytes a value, 4 a line number until a file passes
    # 2^31 lines): memory grows with the data by a small constant, not by Python objects per cell
    # (10^7 rows: 0.2 GB, not 3 GB).
    V, e, s, lines = array("d"), array("d"), array("d"), array("i")
    header = None
    with open(name, encoding="utf-8-sig") as fh:
        for lineno, line in enumerate(fh, start=1):
            text = line.split("#", 1)[0].strip()
            if not text:
                continue
            if header is None:
                header = (lineno, text)
                hline, htext = header
                delimiter = next((d for d in (",", ";", "\t") if d in htext), None)
                cells = _split(htext, delimiter)
                keys = [_column_key(c) for c in cells]
                iv = _find_column(keys, cells, where, hline, htext, _VELOCITY_NAMES, "velocity")
                ie = _find_column(keys, cells, where, hline, htext, _RESTITUTION_NAMES, "restitution")
                isg = _find_column(keys, cells, where, hline, htext, _SIGMA_NAMES, "sigma", required=False)
                unit = keys[iv][1].lower()
                if unit and unit not in _VELOCITY_UNITS:
                    raise ValueError(f"{where} line {hline}: velocity must be in m/s, the header says {cells[iv]!r}")
                continue
            row = text.split(delimiter) if delimiter and '"' not in text else _split(text, delimiter)
            if len(row) != len(cells):
                raise ValueError(
                    f"{where} line {lineno}: expected {len(cells)} cells like the header, found {len(row)}"
                )
            v = _cell_number(row[iv], where, lineno, "velocity")
            if v < 0:
                raise ValueError(f"{where} line {lineno}: negative impact speed {v:g} m/s")
            if v == 0:
                raise ValueError(f"{where} line {lineno}: impact speed must be positive, got 0")
            r = _cell_number(row[ie], where, lineno, "restitution")
            if r < 0.0:
                raise ValueError(f"{where} line {lineno}: restitution must be >= 0, got {r:g}")
            if isg is not None:
                sg = _cell_number(row[isg], where, lineno, "sigma")
                if sg <= 0:
                    raise ValueError(f"{where} line {lineno}: sigma must be positive, got {sg:g}")
                s.append(sg)
            V.append(v)
            e.append(r)
            try:
                lines.append(lineno)
            except OverflowError:  # past 2^31 - 1 lines: 8-byte line numbers from here on
                lines = array("q", lines)
                lines.append(lineno)
    if header is None:
        raise ValueError(f"{where}: no header line (expected columns velocity, restitution)")
    if not lines:
        raise ValueError(f"{where}: no data rows after the header on line {header[0]}")
    # numpy views of the arrays' buffers (no copy; each view keeps its array alive)
    sigma = np.frombuffer(s, dtype=float) if isg is not None else None
    return RestitutionData(
        np.frombuffer(V, dtype=float),
        np.frombuffer(e, dtype=float),
        sigma,
        np.frombuffer(lines, dtype=f"i{lines.itemsize}"),
        source=where,
    )


def _find_column(keys, cells, where, hline, htext, names, what, required=True):
    """The index of the header cell naming ``what`` (one of ``names``); errors name the file and line."""
    hits = [i for i, (k, _) in enumerate(keys) if k in names]
    if len(hits) > 1:
        raise ValueError(
            f"{where} line {hline}: more than one {what} column: " + ", ".join(repr(cells[i]) for i in hits)
        )
    if not hits:
        if required:
            raise ValueError(
                f"{where} line {hline}: missing column {what} (accepted names: {', '.join(names[:3])}); header is {htext!r}"
            )
        return None
    return hits[0]


def _cell_number(cell, where, lineno, what) -> float:
    """A finite decimal number from a data cell, or a ValueError naming the file, line and column."""
    cell = cell.strip()
    if cell == "":
        raise ValueError(f"{where} line {lineno}: empty {what} cell")
    if not is_number_text(cell):  # float() would also take 1_0 (as 10) and 0x1p3
        raise ValueError(f"{where} line {lineno}: {what} {cell!r} is not a number")
    x = float(cell)
    if not math.isfinite(x):
        raise ValueError(f"{where} line {lineno}: {what} {cell!r} is not a finite number")
    return x
