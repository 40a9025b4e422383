"""Writing results: the one module through which microimpact writes every file.

Every file goes to a temporary name beside its target (same directory, so the
final :func:`os.replace` is a rename within one file system), is flushed and
``fsync``-ed, and is renamed into place only when complete. An exception of any
kind while writing -- including :class:`KeyboardInterrupt` (Ctrl-C, and SIGTERM
in the command line, which raises it too) and :class:`SystemExit` -- removes the
temporary file and leaves whatever was at the target before untouched.

* :func:`atomic_write` -- one file (a context manager yielding the open file).
* :func:`owned_directory` -- an output folder (``microimpact paper``,
  ``microimpact export``) that owns only what it wrote: a manifest
  (``.microimpact-manifest.json``) lists every file written with its SHA-256, and
  a later run replaces or deletes only the files listed there whose content is
  unchanged; anything else in the folder (or an input of the run) makes it
  refuse, naming the file.
* :func:`write_csv`, :func:`write_json`, :func:`write_netcdf`,
  :func:`save_figure` -- the writers every command uses.
* :func:`csv_header` -- the project's one CSV layout.
* :func:`check_output_path` -- the checks a command makes on an output path
  before it computes anything.
* :func:`memory_budget`, :func:`check_memory` -- refusing sizes that would not
  fit in memory, before allocating them.
* :func:`progress_bar` -- the one progress-bar style (:mod:`tqdm`).
* :func:`load_restitution_csv` -- reading measured restitution data (what
  :func:`microimpact.fitting.fit_restitution` takes in), as :class:`RestitutionData`.

CSV layout (all CSV files microimpact writes)
---------------------------------------------
Line 1 is the header: column names, comma separated, each followed by its unit
in brackets, ``name [unit]`` (SI; ``[1]`` for dimensionless quantities and
flags, as CF/UDUNITS write it). Then zero or more comment lines starting with
``#`` (title, provenance, scalars, column descriptions), then one row per
record: floats in their shortest exact form (they read back bit for bit),
booleans as ``0``/``1``, non-finite values as ``nan``/``inf``/``-inf``. The
header comes first so that every common reader takes it:
``numpy.genfromtxt(f, delimiter=",", names=True)``,
``pandas.read_csv(f, comment="#")``, :func:`csv.DictReader` over the lines not
starting with ``#``, :func:`read_table` and
:func:`load_restitution_csv`.
"""

from __future__ import annotations

import contextlib
import errno
import io as _stdio
import math
import os
import signal
import stat
import sys
import threading
from typing import TYPE_CHECKING

import numpy as np

from . import _signals
from ._validation import is_number_text
from .core import cache as _cache

if TYPE_CHECKING:  # pathlib, json, csv, shutil and tempfile load where used: every command checks memory here
    from pathlib import Path

__all__ = [
    "atomic_write",
    "owned_directory",
    "MANIFEST",
    "atomic_directory",
    "check_output_path",
    "check_input_file",
    "csv_header",
    "csv_rows",
    "write_csv",
    "write_table",
    "read_table",
    "write_json",
    "json_safe",
    "write_netcdf",
    "save_figure",
    "memory_budget",
    "check_memory",
    "MemoryBudgetError",
    "progress_bar",
    "MEMORY_ENV",
    "MEMORY_FRACTION",
]

#: Environment variable overriding the memory budget: bytes (``2e9``), or with a unit (``4GB``, ``512MiB``).
MEMORY_ENV = "MICROIMPACT_MAX_MEMORY"
#: Fraction of the available memory a single array allocation may use by default.
MEMORY_FRACTION = 0.5


# ----------------------------------------------------------------------------- signals
@contextlib.contextmanager
def _signals_deferred():
    """Hold SIGINT/SIGTERM during a few system calls that must not be split (a rename pair).

    A signal arriving inside is remembered and delivered (its old handler called)
    when the block ends. Only in the main thread; elsewhere a no-op. An interrupt
    that arrived earlier and whose exception was swallowed on the way (Python drops
    an exception raised in a ``__del__`` or a callback) is raised before the block
    (:func:`microimpact._signals.check`): nothing is renamed into place after a
    signal.
    """
    _signals.check()
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    pending = []
    old = {}

    def hold(signum, frame):
        pending.append((signum, frame))

    for sig in (signal.SIGINT, signal.SIGTERM):
        try:
            old[sig] = signal.signal(sig, hold)
        except (ValueError, OSError):  # pragma: no cover - not settable here
            pass
    try:
        yield
    finally:
        for sig, handler in old.items():
            signal.signal(sig, handler)
        for signum, frame in pending[:1]:
            handler = old.get(signum)
            if callable(handler):
                handler(signum, frame)
            elif handler == signal.SIG_DFL:
                if signum == signal.SIGINT:
                    raise KeyboardInterrupt
                signal.raise_signal(signum)  # pragma: no cover


# ----------------------------------------------------------------------------- paths
def _oserror(err, message, path):
    return _OSERRORS.get(err, OSError)(err, message, os.fspath(path))


_OSERRORS = {
    errno.ENOENT: FileNotFoundError,
    errno.EISDIR: IsADirectoryError,
    errno.ENOTDIR: NotADirectoryError,
    errno.EEXIST: FileExistsError,
    errno.EACCES: PermissionError,
}


def check_output_path(path, *, directory: bool = False) -> Path:
    """Check, before anything is computed, that ``path`` can be written.

    The parent must exist and be a directory. A file target must be absent or a
    regular file (a symbolic link is followed: its target is what is checked and,
    later, replaced); a directory, a device (``/dev/null``, ``/dev/full``), a FIFO
    or a socket is refused -- microimpact writes over regular files only. A
    directory target (``directory=True``) must be absent or a directory. Nothing
    is created.

    Parameters
    ----------
    path : str or os.PathLike
        The output file (or directory).
    directory : bool, optional
        ``path`` names an output folder (:func:`owned_directory`).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    OSError
        :class:`FileNotFoundError`, :class:`NotADirectoryError`,
        :class:`IsADirectoryError` or :class:`FileExistsError` (not a regular
        file) with the offending path as ``filename``.
    """
    from pathlib import Path

    if str(path) == "":
        raise FileNotFoundError(errno.ENOENT, "empty file name", "")
    target = Path(path)
    real = _resolve(target)
    parent = real.parent
    if not parent.exists():
        raise _oserror(errno.ENOENT, "directory does not exist", target.parent if real == target else parent)
    if not parent.is_dir():
        raise _oserror(errno.ENOTDIR, "not a directory", target.parent if real == target else parent)
    if directory:
        if real.exists() and not real.is_dir():
            raise _oserror(errno.ENOTDIR, "exists and is not a directory", target)
        return target
    if real.is_dir():
        raise _oserror(errno.EISDIR, "is a directory", target)
    if _special(real):
        raise _oserror(
            errno.EEXIST,
            "not a regular file (a device, FIFO or socket): microimpact writes over regular files only",
            target,
        )
    if not os.access(parent, os.W_OK | os.X_OK):
        raise _oserror(errno.EACCES, "directory is not writable", parent)
    return target


def _resolve(target: Path) -> Path:
    """``target`` with a symbolic link followed (to its final target, which may not exist yet)."""
    from pathlib import Path

    return Path(os.path.realpath(target)) if target.is_symlink() else target


def check_input_file(path, what: str = "file") -> Path:
    """Check that ``path`` is an existing, readable file of UTF-8 text; the error names the file.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    what : str, optional
        What it is, for the message (e.g. ``"data"``).

    Raises
    ------
    OSError
        When missing, a directory or unreadable (``filename`` set).
    ValueError
        When it is not UTF-8 text (binary), naming the file and the byte offset.
    """
    from pathlib import Path

    p = Path(path)
    if not p.exists():
        raise _oserror(errno.ENOENT, f"{what} file not found", p)
    if p.is_dir():
        raise _oserror(errno.EISDIR, f"{what} is a directory, not a file", p)
    import codecs

    decoder = codecs.getincrementaldecoder("utf-8")()
    offset = 0
    with open(p, "rb") as fh:
        while True:
            block = fh.read(1 << 20)
            try:
                text = decoder.decode(block, final=not block)
            except UnicodeDecodeError as exc:
                raise ValueError(
                    f"{p}: not a text file (UTF-8): byte 0x{exc.object[exc.start]:02x} at offset {offset + exc.start}"
                ) from None
            if "\x00" in text:
                raise ValueError(f"{p}: not a text file (NUL byte near offset {offset + text.index(chr(0))})")
            if not block:
                break
            offset += len(block)
    return p


def _special(path) -> bool:
    """True when ``path`` exists and is not a regular file or directory (a device, a pipe)."""
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return False
    return not (stat.S_ISREG(mode) or stat.S_ISDIR(mode))


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _umask_mode() -> int:
    return 0o666 & ~_umask()


@contextlib.contextmanager
def atomic_write(path, mode: str = "w", *, encoding: str | None = "utf-8", newline: str | None = ""):
    """Open a temporary file beside ``path``; rename it to ``path`` when the block succeeds.

    The temporary file is ``.<name>.<random>.tmp`` in the target's directory
    (created exclusively by :func:`microimpact.core.cache.mkstemp`, so the name is unique). On success it
    is flushed, ``fsync``-ed, given the target's permissions (an existing
    target's, else ``0666`` less the umask) and renamed over the target with
    :func:`os.replace` (atomic on POSIX; SIGINT/SIGTERM are held for that call).
    On any exception, including :class:`KeyboardInterrupt` and
    :class:`SystemExit`, the temporary file is removed and the target is left as
    it was. Only a regular file is written over (:func:`check_output_path`): a
    device (``/dev/null``, ``/dev/full``), a FIFO, a socket or a directory is
    refused before anything is written. A symbolic link is followed: the file it
    points to is replaced and the link stays a link.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.
    mode : str, optional
        ``"w"`` (text, default) or ``"wb"``.
    encoding, newline : str, optional
        For text mode (default UTF-8, no newline translation).

    Yields
    ------
    file object
    """
    from pathlib import Path

    if mode not in ("w", "wb"):
        raise ValueError(f"mode must be 'w' or 'wb', got {mode!r}")
    kw = {} if "b" in mode else {"encoding": encoding, "newline": newline}
    check_output_path(path)
    target = _resolve(Path(path))
    try:
        perm = stat.S_IMODE(os.stat(target).st_mode)
    except OSError:
        perm = _umask_mode()
    fd, tmp = _cache.mkstemp(target.parent, f".{target.name}.", ".tmp")
    _signals.track(tmp)
    try:
        with os.fdopen(fd, mode, **kw) as fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, perm)
        with _signals_deferred():
            os.replace(tmp, target)
            _signals.untrack(tmp)
            _signals.committed()
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        _signals.untrack(tmp)
        if isinstance(exc, OSError) and exc.filename is None:  # e.g. ENOSPC from write(): name the target
            exc.filename = os.fspath(target)
        raise


def _fsync_dir(path) -> None:
    with contextlib.suppress(OSError):
        fd = os.open(path, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


#: Name of the manifest an output folder's writer leaves in it (:func:`owned_directory`).
MANIFEST = ".microimpact-manifest.json"
_STAGING = ".microimpact-staging."


def _sha256(path) -> str:
    h = _cache.sha256()  # Python's own SHA-256 where it has one: not OpenSSL's 5 ms load (issue 25)
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _read_manifest(folder: Path):
    """The manifest in ``folder`` as ``(command, {name: {"size", "sha256"}})``, or None (absent or unreadable)."""
    import json

    try:
        doc = json.loads((folder / MANIFEST).read_text(encoding="utf-8"))
        files = doc["files"]
        command = str(doc["command"])
        if doc.get("format") != "microimpact-manifest" or not isinstance(files, dict):
            return None
        return command, {str(k): dict(v) for k, v in files.items()}
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None


def _foreign(folder: Path, command: str, inputs, shown) -> dict:
    """The files of ``folder`` that an earlier run of ``command`` wrote (its manifest), checked.

    Raises :class:`FileExistsError` naming the first entry that no manifest of this
    command lists with its present size and SHA-256 (a file's name proves nothing), and
    refuses any of ``inputs`` that lies inside ``folder``.
    """
    real = os.path.realpath(folder)
    for p in inputs:
        if p is None or str(p) == "-":
            continue
        rp = os.path.realpath(p)
        if os.path.commonpath([real, rp]) == real:
            raise FileExistsError(
                errno.EEXIST,
                f"holds {os.fspath(p)!r}, an input of this run: an input is never replaced; "
                "write the output to another folder",
                shown,
            )
    manifest = _read_manifest(folder)
    entries = sorted(os.scandir(folder), key=lambda e: e.name)
    if manifest is not None and manifest[0] != command:
        raise FileExistsError(
            errno.EEXIST,
            f"holds the output of 'microimpact {manifest[0]}' ({MANIFEST}), not of 'microimpact {command}'; "
            "give another folder",
            shown,
        )
    listed = manifest[1] if manifest is not None else {}
    owned = {}
    for entry in entries:
        if entry.name == MANIFEST and manifest is not None:
            continue
        info = listed.get(entry.name)
        ok = info is not None and entry.is_file(follow_symlinks=False)
        if ok:
            try:
                ok = entry.stat(follow_symlinks=False).st_size == info.get("size") and _sha256(entry.path) == info.get(
                    "sha256"
                )
            except OSError:
                ok = False
        if not ok:
            why = (
                "which has changed since microimpact wrote it"
                if info is not None
                else f"which no manifest of an earlier 'microimpact {command}' lists ({MANIFEST})"
            )
            raise FileExistsError(
                errno.EEXIST,
                f"holds {entry.name!r}, {why}: microimpact replaces only files it can prove it wrote; "
                "give a new or empty folder, or move the file",
                shown,
            )
        owned[entry.name] = info
    return owned


def _write_manifest(folder: Path, command: str, names) -> None:
    import json

    files = {}
    for name in sorted(names):
        p = folder / name
        files[name] = {"size": p.stat().st_size, "sha256": _sha256(p)}
    doc = {
        "format": "microimpact-manifest",
        "version": 1,
        "command": command,
        "note": "the files microimpact wrote here; a later run replaces or deletes only these "
        "(and only while their content is unchanged)",
        "files": files,
    }
    with atomic_write(folder / MANIFEST) as fh:
        fh.write(json.dumps(doc, indent=1) + "\n")


@contextlib.contextmanager
def owned_directory(path, command: str, *, inputs=()):
    """An output folder that owns only what it wrote: the one way microimpact writes a folder.

    The block receives a staging folder and writes every output file into it
    (flat: files only). When the block succeeds the files are committed with a
    manifest, :data:`MANIFEST` (``.microimpact-manifest.json``), listing each file
    written with its size and SHA-256. On any exception (including
    :class:`KeyboardInterrupt`) the staging folder is deleted and ``path`` is left
    as it was.

    Ownership rule. Before the block runs, an existing ``path`` is checked: every
    entry in it must be listed in a manifest that an earlier run of the same
    ``command`` wrote there, with the same size and SHA-256 now (a file's name
    proves nothing; a file edited since is the user's). Otherwise a
    :class:`FileExistsError` names the first foreign entry and nothing is written.
    A file of ``inputs`` inside ``path`` is refused the same way: an input is never
    replaced. A folder holding another command's manifest is refused.

    How it is committed:

    * ``path`` does not exist: the staging folder is made beside it and renamed to
      it (one atomic rename; the output appears whole or not at all);
    * ``path`` exists (an empty folder, or an earlier output): the staging folder
      is made inside it, and each file is renamed into place one by one (each
      rename atomic), the manifest is rewritten, and the files of the earlier run
      this run did not write again are deleted; SIGINT/SIGTERM are held during
      these renames. The folder itself is never replaced, so ``--out .`` or an
      ancestor of the working directory keeps its inode (a shell inside it is not
      left in a deleted folder).

    Parameters
    ----------
    path : str or os.PathLike
        The output folder.
    command : str
        Who writes it (e.g. ``"export"``), recorded in the manifest.
    inputs : sequence of path, optional
        Files this run reads; refused when inside ``path``.

    Yields
    ------
    pathlib.Path
        The staging folder to write the files into.
    """
    from pathlib import Path

    target = Path(os.path.abspath(path))  # "." and "dir/.." name their real parent
    check_output_path(target, directory=True)
    if target.is_dir():
        old = _foreign(target, command, inputs, os.fspath(path))
        stage = Path(_cache.mkdtemp(target, _STAGING, ".tmp"))
    else:
        old = None
        stage = Path(_cache.mkdtemp(target.parent, f".{target.name}.", ".tmp"))
    _signals.track(stage, "dir")
    try:
        yield stage
        names = sorted(e.name for e in os.scandir(stage))
        bad = [n for n in names if n == MANIFEST or not (stage / n).is_file() or (stage / n).is_symlink()]
        if bad:
            raise ValueError(f"an output folder holds files only, not {bad[0]!r}")
        _write_manifest(stage, command, names)
        if old is None:
            stage.chmod(0o777 & ~_umask())
            _fsync_dir(stage)
            with _signals_deferred():
                if target.exists():
                    raise _oserror(errno.EEXIST, "appeared while the output was written", target)
                os.rename(stage, target)
                _signals.untrack(stage)
                _signals.committed()
            stage = None
            _fsync_dir(target.parent)
        else:
            _fsync_dir(stage)
            with _signals_deferred():
                for name in names:
                    os.replace(stage / name, target / name)
                os.replace(stage / MANIFEST, target / MANIFEST)
                for name in old:
                    if name not in names:
                        with contextlib.suppress(FileNotFoundError):
                            os.unlink(target / name)
                _signals.committed()
            _fsync_dir(target)
    finally:
        if stage is not None:
            try:
                os.rmdir(stage)  # emptied: its files moved into the folder above
            except OSError:
                import shutil  # a failed run left files in it (shutil costs 4 ms to import: issue 25)

                shutil.rmtree(stage, ignore_errors=True)
            _signals.untrack(stage)


@contextlib.contextmanager
def atomic_directory(path, owned=None):
    """Deprecated: use :func:`owned_directory` (a manifest, not file-name patterns, proves ownership).

    Kept for one release; ``owned`` is ignored and the folder is written by
    :func:`owned_directory` with the command name ``"atomic_directory"``.
    """
    import warnings

    warnings.warn(
        "microimpact.io.atomic_directory is deprecated: use microimpact.io.owned_directory(path, command) "
        "(a manifest, not file-name patterns, proves which files it may replace)",
        DeprecationWarning,
        stacklevel=3,
    )
    with owned_directory(path, "atomic_directory") as tmp:
        yield tmp


@contextlib.contextmanager
def _naming(fh):
    """Give an OSError raised while writing to an open file the file's name (``<stdout>`` for stdout)."""
    try:
        yield
    except OSError as exc:
        if exc.filename is None and not isinstance(exc, BrokenPipeError):
            name = getattr(fh, "name", None)
            exc.filename = "<standard output>" if fh is sys.stdout or name == "<stdout>" else name
        raise


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
        with _naming(path):
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
    token is ever produced.

    Parameters
    ----------
    obj : dict, list, ...
        JSON-able data (numpy arrays and scalars allowed).
    path : str, os.PathLike, file object or None
        Destination; ``None`` or ``"-"``: :data:`sys.stdout`.
    indent : int, optional
        Indentation (default 2).
    """
    import json
    from pathlib import Path

    text = json.dumps(json_safe(obj), indent=indent, allow_nan=False) + "\n"
    if path is None or (isinstance(path, str) and path == "-"):
        with _naming(sys.stdout):
            sys.stdout.write(text)
            sys.stdout.flush()
        return None
    if hasattr(path, "write"):
        with _naming(path):
            path.write(text)
        return None
    with atomic_write(path) as fh:
        fh.write(text)
    return Path(path)


# ----------------------------------------------------------------------------- NetCDF and figures
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
    target = _resolve(Path(path))
    fd, tmp = _cache.mkstemp(target.parent, f".{target.name}.", ".tmp")
    os.close(fd)
    _signals.track(tmp)
    try:
        try:
            perm = stat.S_IMODE(os.stat(target).st_mode)
        except OSError:
            perm = _umask_mode()
        if not ds.chunks:
            ds.to_netcdf(tmp, engine=engine)
        else:
            delayed = ds.to_netcdf(tmp, engine=engine, compute=False)
            if progress:
                from ._optional import require

                diagnostics = require("dask.diagnostics", "progress bars")
                with diagnostics.ProgressBar(out=sys.stderr):
                    delayed.compute()
            else:
                delayed.compute()
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())
        os.chmod(tmp, perm)
        with _signals_deferred():
            os.replace(tmp, target)
            _signals.untrack(tmp)
            _signals.committed()
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        _signals.untrack(tmp)
        raise
    return Path(path)


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


# ----------------------------------------------------------------------------- memory
def _parse_bytes(text: str) -> float:
    s = str(text).strip().lower().replace(" ", "")
    units = {"kib": 2**10, "mib": 2**20, "gib": 2**30, "tib": 2**40, "kb": 1e3, "mb": 1e6, "gb": 1e9, "tb": 1e12}
    for u, f in units.items():
        if s.endswith(u):
            return float(s[: -len(u)]) * f
    if s.endswith("b"):
        s = s[:-1]
    return float(s)


def _available_memory() -> float:
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024.0
    except OSError:  # pragma: no cover - not Linux
        pass
    try:  # pragma: no cover - not Linux
        return float(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):  # pragma: no cover
        return 4e9


def memory_budget() -> float:
    """Bytes one command may allocate for its arrays.

    ``MICROIMPACT_MAX_MEMORY`` if set (bytes, or with a unit: ``4GB``,
    ``512MiB``); otherwise :data:`MEMORY_FRACTION` (half) of the memory the
    system reports available (``MemAvailable`` in ``/proc/meminfo``).
    """
    env = os.environ.get(MEMORY_ENV)
    if env:
        try:
            value = _parse_bytes(env)
        except ValueError:
            raise ValueError(f"{MEMORY_ENV} must be a number of bytes (e.g. 2e9 or 4GB), got {env!r}") from None
        if not (value > 0 and math.isfinite(value)):
            raise ValueError(f"{MEMORY_ENV} must be a positive number of bytes, got {env!r}")
        return value
    return MEMORY_FRACTION * _available_memory()


class MemoryBudgetError(ValueError):
    """A requested size would need more memory than :func:`memory_budget` allows."""


def _human(nbytes: float) -> str:
    for unit, f in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if nbytes >= f:
            return f"{nbytes / f:.3g} {unit}"
    return f"{nbytes:.0f} B"


def check_memory(nbytes: float, what: str, hint: str = "") -> None:
    """Raise :class:`MemoryBudgetError` when ``nbytes`` exceeds :func:`memory_budget`.

    Parameters
    ----------
    nbytes : float
        Estimated peak bytes of the operation.
    what : str
        What is being sized, naming the option (e.g. ``"--n 100000000"``).
    hint : str, optional
        How to proceed (e.g. "use --chunks").
    """
    budget = memory_budget()
    if nbytes > budget:
        source = (
            f"set by {MEMORY_ENV}" if os.environ.get(MEMORY_ENV) else f"half the available memory; {MEMORY_ENV} sets it"
        )
        raise MemoryBudgetError(
            f"{what} would need about {_human(nbytes)} of memory, more than the budget of {_human(budget)} "
            f"({source})" + (f"; {hint}" if hint else "")
        )


# ----------------------------------------------------------------------------- progress
class _NoBar:
    def update(self, n=1):
        pass

    def set_description(self, *args, **kwargs):
        pass

    def close(self):
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


def progress_bar(total, desc: str = "", *, unit: str = "it", disable: bool = False):
    """The project's one progress bar: :class:`tqdm.tqdm` on stderr.

    Quiet (a no-op object with the same ``update``/``close``) when ``disable``
    is true or tqdm is not installed. Callers in the command line pass
    ``disable=not stderr_is_terminal or quiet``.
    """
    if disable:
        return _NoBar()
    try:
        from tqdm.auto import tqdm
    except ImportError:  # pragma: no cover - tqdm is a dependency
        return _NoBar()
    return tqdm(total=total, desc=desc, unit=unit, file=sys.stderr, leave=False, dynamic_ncols=True)


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
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     cols = {"velocity_m_s": ("m/s", "impact speed V"), "restitution": ("1", "e")}
    ...     path = write_table(Path(tmp) / "e.csv", {"velocity_m_s": [5.0, 20.0], "restitution": [1.0, 0.8836]}, columns=cols)
    ...     back = read_table(path)
    >>> back["velocity_m_s"].tolist(), back["restitution"].tolist()
    ([5.0, 20.0], [1.0, 0.8836])
    """
    from ._version import __version__

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


# --------------------------------------------------------------------------- checks
