"""Files and folders written whole or not at all, and the checks made on a path before any work.

The plain rule, for a file and for a folder alike: write under a temporary name in the destination
folder (:func:`tempfile.mkstemp`, :func:`tempfile.mkdtemp`: same file system, so the final
:func:`os.replace` is a rename), then rename into place; remove the temporary in ``finally``. An
interrupt is a :class:`KeyboardInterrupt` (the command line turns SIGINT and SIGTERM into one), so
those blocks run on Ctrl-C as on any error. Nothing here touches the process's signal handling.
"""

from __future__ import annotations

import contextlib
import contextvars
import errno
import os
import stat
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # pathlib, json, shutil and tempfile load where used: every command checks memory through io
    from pathlib import Path

__all__ = [
    "MANIFEST",
    "MANIFEST_MAX_BYTES",
    "atomic_directory",
    "atomic_write",
    "check_input_file",
    "check_output_path",
    "commit_check",
    "name_the_target",
    "naming_errors",
    "oserror",
    "owned_directory",
    "replacing",
    "resolve_link",
    "umask_mode",
]


# ----------------------------------------------------------------------------- commits
# The caller's last word before an output takes its place (None: none). A context variable, set only
# inside :func:`commit_check`: nothing of the process changes, and a thread started meanwhile has none.
_COMMIT_CHECK = contextvars.ContextVar("microimpact_commit_check", default=None)


@contextlib.contextmanager
def commit_check(check):
    """Call ``check()`` just before each output of the block is put in place (a file renamed over its
    target, a folder committed); an exception it raises leaves the output as it was.

    The command line passes a check that raises an interrupt whose exception a library swallowed (one
    raised inside a ``__del__`` or a weakref callback is printed and dropped by Python): the command
    then stops before its outputs appear, instead of finishing them and reporting the interrupt after.
    """
    token = _COMMIT_CHECK.set(check)
    try:
        yield
    finally:
        _COMMIT_CHECK.reset(token)


def _before_commit() -> None:
    check = _COMMIT_CHECK.get()
    if check is not None:
        check()


# ----------------------------------------------------------------------------- paths
def oserror(err, message, path):
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
    real = resolve_link(target)
    parent = real.parent
    if not parent.exists():
        raise oserror(errno.ENOENT, "directory does not exist", target.parent if real == target else parent)
    if not parent.is_dir():
        raise oserror(errno.ENOTDIR, "not a directory", target.parent if real == target else parent)
    if directory:
        if real.exists() and not real.is_dir():
            raise oserror(errno.ENOTDIR, "exists and is not a directory", target)
        return target
    if real.is_dir():
        raise oserror(errno.EISDIR, "is a directory", target)
    if _special(real):
        raise oserror(
            errno.EEXIST,
            "not a regular file (a device, FIFO or socket): microimpact writes over regular files only",
            target,
        )
    if not os.access(parent, os.W_OK | os.X_OK):
        raise oserror(errno.EACCES, "directory is not writable", parent)
    return target


def resolve_link(target: Path) -> Path:
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
        raise oserror(errno.ENOENT, f"{what} file not found", p)
    if p.is_dir():
        raise oserror(errno.EISDIR, f"{what} is a directory, not a file", p)
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


def umask_mode() -> int:
    return 0o666 & ~_umask()


@contextlib.contextmanager
def atomic_write(path, mode: str = "w", *, encoding: str | None = "utf-8", newline: str | None = ""):
    """Open a temporary file beside ``path``; rename it to ``path`` when the block succeeds.

    The temporary file is ``.<name>.<random>.tmp`` in the target's directory
    (created exclusively by :func:`tempfile.mkstemp`, so the name is unique). On
    success it is flushed, ``fsync``-ed, given the target's permissions (an
    existing target's, else ``0666`` less the umask) and renamed over the target
    with :func:`os.replace` (atomic on POSIX). On any exception, including
    :class:`KeyboardInterrupt` and :class:`SystemExit`, the temporary file is
    removed and the target is left as it was. Only a regular file is written
    over (:func:`check_output_path`): a device (``/dev/null``, ``/dev/full``), a
    FIFO, a socket or a directory is refused before anything is written. A
    symbolic link is followed: the file it points to is replaced and the link
    stays a link.

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
    with replacing(resolve_link(Path(path))) as (fd, _tmp):
        with os.fdopen(fd, mode, **kw) as fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())


@contextlib.contextmanager
def replacing(target):
    """``(fd, tmp)``: a new temporary file beside ``target`` (created exclusively, its descriptor open);
    on a clean exit it takes ``target``'s place with ``target``'s mode (else the umask's), so the file
    appears whole or not at all; on any exception, an interrupt too, it is removed and an OSError names
    ``target``. The caller writes the file and makes it durable (``fsync``) inside the block."""
    import tempfile

    try:
        perm = stat.S_IMODE(os.stat(target).st_mode)
    except OSError:
        perm = umask_mode()
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        yield fd, tmp
        os.chmod(tmp, perm)
        _before_commit()
        os.replace(tmp, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        name_the_target(exc, tmp, target)
        raise


def name_the_target(exc: BaseException, tmp, target) -> None:
    """Make an OSError raised while ``tmp`` was written or renamed name ``target``, the user's path
    (``ENOSPC`` from ``write()`` names no file; a failed rename names the temporary file too)."""
    if isinstance(exc, OSError) and (exc.filename is None or os.fspath(exc.filename) == os.fspath(tmp)):
        exc.filename = os.fspath(target)
        exc.filename2 = None


def _fsync_dir(path) -> None:
    with contextlib.suppress(OSError):
        fd = os.open(path, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


def _remove_tree(path) -> None:
    """Remove a temporary folder: ``rmdir`` when it is empty, else :func:`shutil.rmtree` (loaded only then)."""
    try:
        os.rmdir(path)
    except FileNotFoundError:
        pass
    except OSError:
        import shutil

        shutil.rmtree(path, ignore_errors=True)


#: Name of the manifest an output folder's writer leaves in it (:func:`owned_directory`).
MANIFEST = ".microimpact-manifest.json"
#: The largest manifest read back: one line of about 120 bytes a file, so some 10^5 files.
MANIFEST_MAX_BYTES = 1 << 24
_STAGING = ".microimpact-staging."
_ASIDE = ".microimpact-old."
_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)


def _sha256(path) -> str:
    import hashlib

    h = hashlib.sha256()
    with os.fdopen(os.open(path, os.O_RDONLY | _NOFOLLOW), "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _read_regular(path, limit: int, shown: str, what: str) -> bytes | None:
    """The bytes of ``path`` if it is a regular file of at most ``limit`` bytes; None if it is absent.

    A symbolic link is not followed, and anything but a regular file (a FIFO would block the read, a
    device never end it) or a file over ``limit`` bytes is refused: a :class:`ValueError` naming
    ``shown``. The file is opened without following a link and checked again once open, so a link
    or a FIFO swapped in between the two looks is refused too.
    """
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return None
    if stat.S_ISLNK(st.st_mode):
        raise ValueError(f"{shown}: the {what} is a symbolic link, which microimpact does not follow; remove it")
    if not stat.S_ISREG(st.st_mode):
        raise ValueError(f"{shown}: the {what} is not a regular file; remove it")
    try:
        fd = os.open(path, os.O_RDONLY | _NOFOLLOW | getattr(os, "O_NONBLOCK", 0))
    except FileNotFoundError:
        return None
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise ValueError(
                f"{shown}: the {what} is a symbolic link, which microimpact does not follow; remove it"
            ) from None
        raise
    with os.fdopen(fd, "rb") as fh:
        if not stat.S_ISREG(os.fstat(fh.fileno()).st_mode):
            raise ValueError(f"{shown}: the {what} is not a regular file; remove it")
        data = fh.read(limit + 1)
    if len(data) > limit:
        raise ValueError(f"{shown}: the {what} is larger than {limit} bytes, more than microimpact writes; remove it")
    return data


def _read_manifest(folder: Path, shown: str):
    """The manifest in ``folder`` as ``(command, {name: {"size", "sha256"}})``, or None (absent, or not
    a manifest: then it is a file like any other, which no manifest lists). A manifest that is a
    symbolic link, not a regular file, or too large is refused (:func:`_read_regular`)."""
    import json

    data = _read_regular(folder / MANIFEST, MANIFEST_MAX_BYTES, os.path.join(shown, MANIFEST), "manifest")
    if data is None:
        return None
    try:
        doc = json.loads(data.decode("utf-8"))
        files = doc["files"]
        command = str(doc["command"])
        if doc.get("format") != "microimpact-manifest" or not isinstance(files, dict):
            return None
        return command, {str(k): dict(v) for k, v in files.items()}
    except (ValueError, KeyError, TypeError, AttributeError):
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
    manifest = _read_manifest(folder, shown)
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


def _place_folder(stage: Path, target: Path, shown: str) -> None:
    """Rename the complete staging folder to ``target``, which must still be absent."""
    if os.path.lexists(target):
        raise oserror(errno.EEXIST, "appeared while the output was written; nothing was written", shown)
    try:
        os.rename(stage, target)
    except OSError as exc:
        raise oserror(exc.errno, f"could not be put in place ({exc.strerror}); nothing was written", shown) from exc


def _commit_files(stage: Path, target: Path, names, old, shown: str) -> None:
    """Put the staged files of a run in the existing folder ``target``: all of them, or none.

    The earlier run's files (``old``, and its manifest) are first renamed aside, into a folder
    inside ``target``; then each new file is renamed into place, the manifest last. If any rename
    fails, or an interrupt comes, every step is undone in reverse (the new files back to the
    stage, the earlier ones back in place), so the folder holds the earlier output and its
    manifest as before and a later run can replace it. On success the earlier files set aside
    are deleted. Each step is a rename within one folder's file system: nothing is copied.
    """
    import tempfile
    from pathlib import Path

    aside = Path(tempfile.mkdtemp(dir=target, prefix=_ASIDE, suffix=".tmp"))
    moved, placed = [], []
    current = None
    undone = True
    try:
        for name in [*sorted(old), MANIFEST]:
            current = name
            try:
                os.rename(target / name, aside / name)
            except FileNotFoundError:
                continue
            moved.append(name)
        for name in [*names, MANIFEST]:
            current = name
            os.rename(stage / name, target / name)
            placed.append(name)
    except BaseException as exc:
        for name in reversed(placed):
            try:
                os.rename(target / name, stage / name)
            except OSError:
                undone = False
        for name in reversed(moved):
            try:
                os.rename(aside / name, target / name)
            except OSError:
                undone = False
        if not undone:  # keep what could not be put back: the earlier output is the user's
            aside = None
        if isinstance(exc, OSError):
            kept = (
                "the folder is as it was before this run" if undone else "the earlier files are kept in a folder beside"
            )
            raise oserror(
                exc.errno, f"could not be written ({exc.strerror}); {kept}", os.path.join(shown, current)
            ) from exc
        raise
    finally:
        if aside is not None:
            _remove_tree(aside)


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
    replaced. A folder holding another command's manifest is refused, and so is a
    manifest that is a symbolic link, not a regular file, or larger than
    :data:`MANIFEST_MAX_BYTES` (a :class:`ValueError`; a link is never followed).

    How it is committed, all or nothing:

    * ``path`` does not exist: the staging folder is made beside it and renamed to
      it (one atomic rename; the output appears whole or not at all);
    * ``path`` exists (an empty folder, or an earlier output): the staging folder
      is made inside it; the earlier run's files and manifest are renamed aside
      (into a temporary folder inside ``path``), the new files renamed into place,
      the new manifest last, and the files set aside deleted. If a rename fails
      (a directory in the way, a full disk's metadata) or an interrupt comes, every
      step is undone, so the folder holds the earlier output and its manifest, and
      the error names the file of ``path`` that could not be written. The folder
      itself is never replaced, so ``--out .`` or an ancestor of the working
      directory keeps its inode (a shell inside it is not left in a deleted folder).

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
    import tempfile
    from pathlib import Path

    shown = os.fspath(path)
    target = Path(os.path.abspath(path))  # "." and "dir/.." name their real parent
    check_output_path(target, directory=True)
    if target.is_dir():
        old = _foreign(target, command, inputs, shown)
        stage = Path(tempfile.mkdtemp(dir=target, prefix=_STAGING, suffix=".tmp"))
    else:
        old = None
        stage = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp"))
    try:
        try:
            yield stage
        except OSError as exc:  # a file written into the staging folder: name it where it was to go
            _name_in_folder(exc, stage, shown)
            raise
        names = sorted(e.name for e in os.scandir(stage))
        bad = [n for n in names if n == MANIFEST or not (stage / n).is_file() or (stage / n).is_symlink()]
        if bad:
            raise ValueError(f"an output folder holds files only, not {bad[0]!r}")
        _write_manifest(stage, command, names)
        _before_commit()
        if old is None:
            stage.chmod(0o777 & ~_umask())
            _fsync_dir(stage)
            _place_folder(stage, target, shown)
            stage = None
            _fsync_dir(target.parent)
        else:
            _fsync_dir(stage)
            _commit_files(stage, target, names, old, shown)
            _fsync_dir(target)
    finally:
        if stage is not None:
            _remove_tree(stage)


def _name_in_folder(exc: OSError, stage, shown: str) -> None:
    """Make ``exc`` name the file of the output folder ``shown`` for a file of its staging folder (a full
    disk or the file-size limit while a file is written there), not the staging folder's own path."""
    for attr in ("filename", "filename2"):
        name = getattr(exc, attr)
        if name is None:
            continue
        rel = os.path.relpath(os.path.abspath(os.fsdecode(name)), stage)
        if rel != ".." and not rel.startswith(".." + os.sep):
            setattr(exc, attr, os.path.join(shown, rel) if rel != "." else shown)


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
def naming_errors(fh):
    """Give an OSError raised while writing to an open file the file's name (``<stdout>`` for stdout)."""
    try:
        yield
    except OSError as exc:
        if exc.filename is None and not isinstance(exc, BrokenPipeError):
            name = getattr(fh, "name", None)
            exc.filename = "<standard output>" if fh is sys.stdout or name == "<stdout>" else name
        raise
