"""The formats microimpact writes: the project's CSV layout, JSON that is always valid, NetCDF, figures.

Every file is written whole or not at all (:func:`microimpact.io.atomic_write`); CSV and JSON also
go to an open file such as standard output.
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
from typing import TYPE_CHECKING

import numpy as np

from .. import _atomic
from ._files import atomic_write, check_output_path, naming_errors, replacing, resolve_link
from ._memory import progress_bar

if TYPE_CHECKING:
    from pathlib import Path

__all__ = [
    "compute_here",
    "check_figure_path",
    "csv_header",
    "csv_rows",
    "json_safe",
    "save_figure",
    "write_csv",
    "write_json",
    "write_netcdf",
    "write_table",
]


# ----------------------------------------------------------------------------- CSV
def _check_text(kind: str, text: str) -> str:
    text = str(text)
    bad = [c for c in text if c in "\r\n\x00" or (ord(c) < 32 and c != "\t")]
    if bad:
        raise ValueError(f"{kind} must be one line of text without control characters, got {text!r}")
    return text


def csv_header(columns) -> str:
    """The header line ``name [unit],...`` of the project's CSV layout.

    Parameters
    ----------
    columns : sequence of (str, str)
        ``(name, unit)`` pairs; ``unit`` ``"1"`` for dimensionless.

    Raises
    ------
    ValueError
        If a name or unit holds a comma, a quote, a bracket or a line break
        (they would change the meaning of the header).
    """
    parts = []
    for name, unit in columns:
        for kind, text in (("column name", name), ("unit", unit)):
            _check_text(kind, text)
            if any(c in str(text) for c in ',"[]'):
                raise ValueError(f"{kind} must not contain a comma, quote or bracket, got {text!r}")
        parts.append(f"{name} [{unit}]" if unit != "" else str(name))
    return ",".join(parts)


def _fmt_cell(x) -> str:
    if isinstance(x, (bool, np.bool_)):
        return "1" if x else "0"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, (float, np.floating)):
        x = float(x)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)  # shortest exact round trip
    s = str(x)
    if "\n" in s or "\r" in s:
        s = s.replace("\r", " ").replace("\n", " ")
    return '"' + s.replace('"', '""') + '"' if ("," in s or '"' in s) else s


def csv_rows(arrays):
    """The rows of the project's CSV layout, one string each (no line end), from columns of equal length.

    Floats in their shortest exact form (Python's ``repr``: they read back bit for bit), ``nan``,
    ``inf`` and ``-inf`` as such, booleans 0/1, integers as written; text quoted when it holds a
    comma or a quote. The rows of :func:`write_csv` and of :func:`microimpact.sweep.sweep_to_csv`.

    Parameters
    ----------
    arrays : sequence of array_like
        The columns, 1-D, all of one length.

    Yields
    ------
    str
        One row.
    """
    cols = [np.atleast_1d(np.asarray(c)) for c in arrays]
    if all(c.dtype.kind in "biuf" for c in cols):
        # numbers only: Python floats' repr is the shortest exact form ("nan", "inf" as _fmt_cell writes them)
        lists = [(c.astype(np.int64) if c.dtype.kind == "b" else c).tolist() for c in cols]
        for row in zip(*lists):
            yield ",".join(map(repr, row))
        return
    n = len(cols[0]) if cols else 0
    for i in range(n):
        yield ",".join(_fmt_cell(c[i].item() if hasattr(c[i], "item") else c[i]) for c in cols)


def _csv_rows(columns, n):
    return csv_rows([c for _, _, c in columns])


def write_csv(path, columns, comments=(), *, progress=False):
    """Write columns as CSV in the project's layout (header with units, ``#`` lines, rows).

    Parameters
    ----------
    path : str, os.PathLike or file object
        File to write (atomically, :func:`atomic_write`), or an open text file
        (e.g. :data:`sys.stdout`), written to directly.
    columns : sequence of (str, str, array_like)
        ``(name, unit, values)``; all of equal length. Bools are written 0/1,
        floats in their shortest exact form, text quoted when it holds a comma.
    comments : sequence of str, optional
        Lines written after the header, each prefixed by ``#`` and a space (one line each;
        a line break inside is refused).
    progress : bool, optional
        Show a progress bar (:func:`progress_bar`) while writing the rows.

    Returns
    -------
    pathlib.Path or None
        The file written (None for a file object).
    """
    from pathlib import Path

    columns = list(columns)
    header = csv_header([(name, unit) for name, unit, _ in columns])
    comments = [_check_text("comment", c) for c in comments]
    n = len(np.atleast_1d(columns[0][2])) if columns else 0
    for name, _, c in columns:
        if len(np.atleast_1d(c)) != n:
            raise ValueError(f"column {name!r} has {len(np.atleast_1d(c))} values, the first has {n}")

    def emit(fh):
        fh.write(header + "\n")
        for c in comments:
            fh.write(f"# {c}\n" if c else "#\n")
        step = 65536
        with progress_bar(n, "writing CSV", unit="rows", disable=not progress) as bar:
            for start in range(0, n, step):
                sub = [(a, b, np.atleast_1d(np.asarray(c))[start : start + step]) for a, b, c in columns]
                block = "\n".join(_csv_rows(sub, min(step, n - start)))
                fh.write(block + "\n")
                bar.update(min(step, n - start))

    if hasattr(path, "write"):
        with naming_errors(path):
            emit(path)
        return None
    with atomic_write(path) as fh:
        emit(fh)
    return Path(path)


# ----------------------------------------------------------------------------- JSON
def json_safe(obj):
    """``obj`` with every non-finite float replaced by ``None`` (JSON ``null``) and numpy types as Python ones.

    JSON has no NaN or infinity (RFC 8259, section 6); writing them as ``null``
    keeps every document valid JSON. Arrays become lists, numpy scalars Python
    numbers, paths strings.
    """
    if isinstance(obj, dict):
        return {str(k): json_safe(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [json_safe(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return json_safe(obj.tolist())
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        x = float(obj)
        return x if math.isfinite(x) else None
    if isinstance(obj, os.PathLike):
        return os.fspath(obj)
    return obj


def write_json(obj, path=None, *, indent: int = 2):
    """Write ``obj`` as valid JSON: to ``path`` (atomically), to an open file, or to stdout.

    NaN and infinities, which JSON cannot represent, are written as ``null``
    (:func:`json_safe`); ``allow_nan=False`` guarantees no ``NaN``/``Infinity``
    token is ever produced. The text is that of ``json.dumps(json_safe(obj), indent=indent,
    allow_nan=False)`` and a line end, written piece by piece: a numpy array is written a block
    of its values at a time, so a result of 10^7 values costs a block of text, not a Python
    float per value and the whole document as one string (several GB).

    Parameters
    ----------
    obj : dict, list, ...
        JSON-able data (numpy arrays and scalars allowed).
    path : str, os.PathLike, file object or None
        Destination; ``None`` or ``"-"``: :data:`sys.stdout`.
    indent : int or None, optional
        Indentation (default 2); None: one line.
    """
    from pathlib import Path

    def emit(fh):
        for piece in _json_pieces(obj, indent, 0):
            fh.write(piece)
        fh.write("\n")

    if path is None or (isinstance(path, str) and path == "-"):
        with naming_errors(sys.stdout):
            emit(sys.stdout)
            sys.stdout.flush()
        return None
    if hasattr(path, "write"):
        with naming_errors(path):
            emit(path)
        return None
    with atomic_write(path) as fh:
        emit(fh)
    return Path(path)


#: Values of a numpy array turned into text at once by :func:`write_json` (about 1 MB of text).
_JSON_BLOCK = 1 << 15


def _json_pieces(obj, indent, level):
    """The text of ``json.dumps(json_safe(obj), indent=indent, allow_nan=False)`` in pieces.

    Dicts, lists and arrays are laid out here as :mod:`json` lays them out (``indent`` spaces per
    level, ``","`` and ``": "`` between items, ``", "`` on one line without indent); every scalar
    and key is :func:`json.dumps` itself. A numeric numpy array of one dimension is turned into
    text :data:`_JSON_BLOCK` values at a time with :func:`_json_numbers`.
    """
    import json

    if isinstance(obj, np.ndarray) and not (obj.ndim >= 1 and obj.dtype.kind in "biuf"):
        obj = json_safe(obj)  # a scalar, or text or objects: small, as lists
    if isinstance(obj, np.ndarray):
        items = (obj[i] for i in range(len(obj))) if obj.ndim > 1 else None
        size = len(obj)
    elif isinstance(obj, (list, tuple)):
        items, size = iter(obj), len(obj)
    elif isinstance(obj, dict):
        items, size = None, len(obj)
    else:
        yield json.dumps(json_safe(obj), allow_nan=False)
        return
    opening, closing = ("{", "}") if isinstance(obj, dict) else ("[", "]")
    if size == 0:
        yield opening + closing
        return
    if indent is None:
        first, sep, last = "", ", ", ""
    else:
        inner = "\n" + " " * (indent * (level + 1))
        first, sep, last = inner, "," + inner, "\n" + " " * (indent * level)
    yield opening + first
    if isinstance(obj, dict):
        for i, (key, value) in enumerate(obj.items()):
            yield (sep if i else "") + json.dumps(str(key)) + ": "
            yield from _json_pieces(value, indent, level + 1)
    elif items is None:  # a 1-D numeric array
        for start in range(0, size, _JSON_BLOCK):
            yield (sep if start else "") + sep.join(_json_numbers(obj[start : start + _JSON_BLOCK]))
    else:
        for i, value in enumerate(items):
            if i:
                yield sep
            yield from _json_pieces(value, indent, level + 1)
    yield last + closing


def _json_numbers(values):
    """JSON's text of each value of a 1-D numeric array, as :func:`json.dumps` writes the Python
    number :func:`json_safe` makes of it: ``float.__repr__`` (the shortest exact form), ``null``
    where the value is not finite, ``int.__repr__``, ``true``/``false``."""
    if values.dtype.kind == "b":
        return ["true" if v else "false" for v in values.tolist()]
    if values.dtype.kind in "iu":
        return list(map(int.__repr__, values.tolist()))
    text = list(map(float.__repr__, values.tolist()))
    if not np.isfinite(values).all():
        for i in np.flatnonzero(~np.isfinite(values)).tolist():
            text[i] = "null"
    return text


# ----------------------------------------------------------------------------- NetCDF and figures
def compute_here(collection):
    """``collection.compute()`` (a dask collection), in this thread under dask's default scheduler.

    A sweep's block is mostly one task, which the default thread pool would run on another thread:
    each thread's allocations stay in a malloc arena of its own (about 160 MB more resident memory at
    2e6 points with the formatting threads), and a pool thread still computing a block at an
    interrupt is joined at exit. A scheduler the caller chose (a ``dask.distributed`` client sets
    one) is kept.
    """
    import dask

    if dask.config.get("scheduler", None) is None:
        return collection.compute(scheduler="synchronous")
    return collection.compute()


def write_netcdf(ds, path, *, engine=None, progress=False):
    """Write an :class:`xarray.Dataset` to NetCDF through a temporary file beside ``path``.

    A dask-backed dataset is computed and written block by block (bounded
    memory); with ``progress=True`` under :class:`dask.diagnostics.ProgressBar`.
    The temporary file is renamed to ``path`` only when the write completed.

    Parameters
    ----------
    ds : xarray.Dataset
    path : str or os.PathLike
    engine : str, optional
        xarray's back end (``"netcdf4"``, ``"scipy"``).
    progress : bool, optional
        Progress bar on stderr while a lazy dataset is written.

    Returns
    -------
    pathlib.Path
    """
    from pathlib import Path

    check_output_path(path)
    target = resolve_link(Path(path))
    # An uncompressed NetCDF file holds at least its data: a file-size limit it cannot fit under is
    # refused before anything is written. A write the NetCDF library fails part way leaves its file
    # open in xarray's file manager, which closes it again at garbage collection and prints there.
    limit = _file_size_limit()
    if limit is not None and ds.nbytes >= limit:
        raise _too_large(ds.nbytes, limit, target)
    with replacing(target) as (fd, tmp):
        os.close(fd)  # the NetCDF library writes the file by its name
        # A dask-backed dataset is written by a delayed write computed here: to_netcdf computing it
        # itself closes the file in a finally that takes xarray's file lock again, and an interrupt
        # that came while that lock was being taken left it held: the close then waited for ever.
        # Its blocks are computed one at a time in this thread (compute_here), as the CSV writer's are.
        try:
            if not ds.chunks:
                ds.to_netcdf(tmp, engine=engine)
            else:
                # Creating the file, its dimensions and variables takes xarray's file lock in Python:
                # an exception raised between an acquire and the try that releases it (a signal's,
                # raised there or in a file manager's __del__ running meanwhile) left the lock held,
                # and the next acquire waited for ever. A step (milliseconds) is not cut: a signal
                # during it is raised when it ends (microimpact._atomic).
                with _atomic.step():
                    delayed = ds.to_netcdf(tmp, engine=engine, compute=False)
                bar = contextlib.nullcontext()
                if progress:
                    from .._optional import require

                    bar = require("dask.diagnostics", "progress bars").ProgressBar(out=sys.stderr)
                with bar:
                    compute_here(delayed)
        except RuntimeError as exc:
            if not str(exc).startswith("NetCDF:"):
                raise
            raise _netcdf_write_error(exc, tmp, target, ds.nbytes) from None
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())
    return Path(path)


def _file_size_limit():
    """The process's file-size limit in bytes (``ulimit -f``, RLIMIT_FSIZE), or None where there is none."""
    try:
        import resource

        limit = resource.getrlimit(resource.RLIMIT_FSIZE)[0]
    except (ImportError, OSError, ValueError):  # pragma: no cover - not a POSIX system
        return None
    return None if limit == resource.RLIM_INFINITY else limit


def _too_large(nbytes, limit, target) -> OSError:
    """The EFBIG error naming ``target`` for about ``nbytes`` of data over the file-size limit."""
    import errno

    return OSError(
        errno.EFBIG,
        f"File too large: about {nbytes / 1e6:.3g} MB of data, more than the process's file-size limit "
        f"(ulimit -f) of {limit} bytes",
        os.fspath(target),
    )


def _netcdf_write_error(exc, tmp, target, nbytes) -> OSError:
    """The OSError naming ``target`` for a failed write of the NetCDF library (``netCDF4`` raises a
    RuntimeError, ``"NetCDF: HDF error"``, that names neither the file nor the system's error).

    The usual causes are told apart from what the system reports: the process's file-size limit
    (``ulimit -f``, RLIMIT_FSIZE: the system refuses the write with EFBIG, Python ignoring SIGXFSZ)
    and a full disk (ENOSPC). ``nbytes`` is the data's size, about the file's.
    """
    import errno

    try:
        written = os.stat(tmp).st_size
    except OSError:
        written = 0
    limit = _file_size_limit()
    if limit is not None and max(written, nbytes) >= limit:
        return _too_large(nbytes, limit, target)
    try:
        st = os.statvfs(os.path.dirname(os.fspath(tmp)) or ".")
        full = st.f_bavail * st.f_frsize < (1 << 20)
    except OSError:
        full = False
    if full:
        return OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), os.fspath(target))
    return OSError(errno.EIO, f"the NetCDF library could not write the file ({exc})", os.fspath(target))


def save_figure(fig, path, **kwargs):
    """``fig.savefig(path, **kwargs)`` through a temporary file beside ``path`` (format from the suffix).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    path : str or os.PathLike
        The image file; its suffix names the format unless ``format=`` is given.
    **kwargs
        Passed to :meth:`~matplotlib.figure.Figure.savefig`.

    Returns
    -------
    pathlib.Path
    """
    from pathlib import Path

    target = Path(path)
    fmt = kwargs.pop("format", None) or target.suffix.lstrip(".").lower() or None
    if fmt is None:
        raise ValueError(f"figure file needs a suffix naming its format (.png, .pdf, .svg), got {os.fspath(path)!r}")
    supported = fig.canvas.get_supported_filetypes()
    if fmt not in supported:
        raise ValueError(
            f"cannot write a figure as {fmt!r} ({os.fspath(path)}): use one of {', '.join(sorted(supported))}"
        )
    with atomic_write(target, "wb") as fh:
        fig.savefig(fh, format=fmt, **kwargs)
    return target


def check_figure_path(path) -> Path:
    """Check before computing that a figure can be written to ``path`` (its format and its directory)."""
    target = check_output_path(path)
    fmt = target.suffix.lstrip(".").lower()
    known = ("png", "pdf", "svg", "svgz", "eps", "ps", "jpg", "jpeg", "tif", "tiff", "webp", "pgf", "raw", "rgba")
    if fmt not in known:
        raise ValueError(f"figure file must end in .png, .pdf or .svg (or {', '.join(known[4:])}), got {str(path)!r}")
    return target


def write_table(path, table: dict, title: str = "", columns: dict | None = None, source: str = "") -> Path:
    """Write a dict of columns as CSV in the project's layout (see :func:`csv_header`).

    The first line is the header, each column named with its unit
    (``velocity_m_s [m/s]``; text columns bare); then ``#`` lines: the title,
    the provenance (``microimpact <version>``, then ``source``) and one line per
    column with its unit and description; then the rows. Floats are written with
    Python's shortest exact representation, so reading the file back
    (:func:`read_table`) gives the same numbers bit for bit. The file is written
    atomically (:func:`write_csv`).

    Parameters
    ----------
    path : str or os.PathLike
        File to write (overwritten).
    table : dict of str to array_like
        Columns of equal length, by name; bools are written as 0/1.
    title : str, optional
        First comment line of the file (one line).
    columns : dict of str to (str, str), optional
        Column name -> (unit, description) for the header and the ``#`` lines
        (e.g. :data:`microimpact.figures.paper.COLUMNS`), units spelled as the
        quantities table spells them (``"1"`` dimensionless, ``""`` text); ``"unit"``
        marks a column in the unit of another column (and ``"-"``, read as before,
        one without a unit of its own). Columns not named have no unit.
    source : str, optional
        Appended to the provenance line (``"; "`` between).

    Returns
    -------
    pathlib.Path
        The file written.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from microimpact.io import read_table
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     cols = {"velocity_m_s": ("m/s", "impact speed V"), "restitution": ("1", "e")}
    ...     path = write_table(Path(tmp) / "e.csv", {"velocity_m_s": [5.0, 20.0], "restitution": [1.0, 0.8836]}, columns=cols)
    ...     back = read_table(path)
    >>> back["velocity_m_s"].tolist(), back["restitution"].tolist()
    ([5.0, 20.0], [1.0, 0.8836])
    """
    from .._version import __version__

    columns = {} if columns is None else columns
    keys = list(table)
    comments = []
    if title:
        comments.append(str(title))
    comments.append(f"microimpact {__version__}" + (f"; {source}" if source else ""))
    comments.append("columns (SI units; a suffix names the unit, no suffix: dimensionless or text):")
    for k in keys:
        unit, desc = columns.get(k, ("", ""))
        comments.append(f"  {k} [{unit}]: {desc}")
    cols = []
    for k in keys:
        unit = columns.get(k, ("", ""))[0]
        cols.append((k, "" if unit in ("-", "unit") else unit, np.atleast_1d(np.asarray(table[k]))))
    return write_csv(path, cols, comments)
