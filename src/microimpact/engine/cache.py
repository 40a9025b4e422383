"""The on-disk cache shared by the compiled loops, the tables and the calibrations: folder, key,
lock, arrays, and the rule deciding which of its files may be used at all.

Everything here is an optimisation: a folder that cannot be created or written, a lock that cannot
be had, a file that is missing, truncated, corrupt or from another version all fall back to
computing (and to trying to write the result for the next process), never to an error.

* :func:`cache_dir` is the folder (``MICROIMPACT_CACHE_DIR``, else ``$XDG_CACHE_HOME/microimpact``,
  else ``~/.cache/microimpact``): the compiled loops live in ``kernels/``, tables in ``tables/``,
  calibrations in ``calibrations/``.
* :func:`core_hash` hashes the core's sources: a cached result's name carries it, so editing a
  formula can never leave a stale entry (the compiled loops add numba's and Python's versions).
* :func:`locked` is an advisory file lock (``fcntl.flock``) around a first computation, so that
  processes started together on an empty cache compute an entry once while the others wait and
  then read it; without a lock (no ``fcntl``, a read-only folder, a wait longer than ``timeout``)
  each computes on its own, as without a cache.
* :func:`load_array` / :func:`store_array` keep one float64 array per key, written atomically
  (temporary file beside it, then renamed) with a SHA-256 of its bytes that is checked on reading.

Whose files. What the cache holds is executed or believed: numba's index is a pickle and its data
file machine code, a table or a calibration becomes the numbers of a result. A checksum proves only
that a file is whole, not who wrote it. So a file is used only when no one but the current user can
have written it (:func:`trouble`): the cache folder and the sub-folder holding the file are owned by
the current user and writable by no one else (``mode & 0o022 == 0``), and the file itself is a
regular file (not a link, FIFO or device) owned likewise, writable by no one else and no larger than
:data:`MAX_BYTES`. Anything else is not used (nor written beside): one :class:`CacheWarning` per
process names it, and the computation runs as without a cache.
"""

from __future__ import annotations

import functools
import io
import os
import stat
import time
from contextlib import contextmanager
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pathlib import Path

# pathlib, hashlib and tempfile load where they are used: reading a stored table needs only hashlib,
# and a command that never touches the cache none of them.

__all__ = [
    "CacheWarning",
    "MAX_BYTES",
    "cache_dir",
    "core_hash",
    "dist_version",
    "locked",
    "load_array",
    "store_array",
    "write_atomic",
    "read_entry",
    "trouble",
    "current_user",
    "usable_folder",
    "folder_trouble",
    "entry_trouble",
    "warn_once",
    "owned_tables",
    "total_bytes",
]
#: Bumped when the file layout of :func:`store_array` changes.
_FORMAT = b"microimpact-array-1\n"
#: Largest cache file used [bytes]: a file beyond it is no entry this package wrote (the largest
#: are numba's machine code for a multi-threaded loop, a few MB, and the universal tables).
MAX_BYTES = 1 << 28
#: Mode bits of a file or folder that others could write through.
_OTHERS_WRITE = stat.S_IWGRP | stat.S_IWOTH


class CacheWarning(RuntimeWarning):
    """The on-disk cache could not be used; the computation ran without it (the message names the folder)."""


def cache_dir() -> Path:
    """Where the compiled loops, tables and calibrations are kept (module docstring)."""
    from pathlib import Path

    return Path(_folder())


def _folder() -> str:
    """:func:`cache_dir` as a string, for the paths that read without pathlib."""
    env = os.environ.get("MICROIMPACT_CACHE_DIR")
    if env:
        return env
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "microimpact")


# ----------------------------------------------------------------------------------- whose files
_WARNED: set = set()


def warn_once(folder, what: str, kind: str | None = None) -> None:
    """One :class:`CacheWarning` per cache folder and kind of trouble in a process (``kind``: the text
    of ``what`` up to its first parenthesis), attributed to the first caller outside this package."""
    import warnings

    key = (str(folder), kind or what.split(" (")[0])
    if key in _WARNED:
        return
    _WARNED.add(key)
    warnings.warn(
        f"cache {folder}: {what} (the cache only saves time: 'microimpact cache --info'; "
        "MICROIMPACT_CACHE_DIR moves it)",
        CacheWarning,
        stacklevel=_outside_level(),
    )


def _outside_level() -> int:
    """The ``stacklevel`` of :func:`warnings.warn` (called from :func:`warn_once`) that names the
    first frame outside the package: the caller's own line, not one of the package's."""
    import inspect

    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    frame = inspect.currentframe()
    level = 0
    try:
        while frame is not None and (
            level < 2 or os.path.abspath(frame.f_code.co_filename).startswith(package + os.sep)
        ):
            frame = frame.f_back
            level += 1
        return level if frame is not None else 2
    finally:
        del frame


def current_user():
    """The effective user id, or None where the system has none (then ownership is not checked)."""
    geteuid = getattr(os, "geteuid", None)
    return geteuid() if geteuid is not None else None


def trouble(st, *, folder: bool = False) -> str:
    """Why a file (``folder``: a folder) of status ``st`` (:func:`os.lstat` for a file, :func:`os.stat`
    for a folder) may not be used; "" when it may (module docstring)."""
    if folder:
        if not stat.S_ISDIR(st.st_mode):
            return "is no folder"
    elif not stat.S_ISREG(st.st_mode):
        return f"is no regular file ({_kind(st.st_mode)})"
    user = current_user()
    if user is not None and st.st_uid != user:
        return f"belongs to another user (uid {st.st_uid})"
    if st.st_mode & _OTHERS_WRITE:
        return f"can be written by others (mode {stat.S_IMODE(st.st_mode):o})"
    if not folder and st.st_size > MAX_BYTES:
        return f"is larger than any entry ({st.st_size} bytes)"
    return ""


def _kind(mode) -> str:
    """What a file of mode ``mode`` is, when it is no regular file."""
    for test, name in (
        (stat.S_ISLNK, "a link"),
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISDIR, "a folder"),
        (stat.S_ISSOCK, "a socket"),
        (stat.S_ISCHR, "a device"),
        (stat.S_ISBLK, "a device"),
    ):
        if test(mode):
            return name
    return "of another kind"  # pragma: no cover


def folder_trouble(path, *, create: bool = False) -> tuple[str, bool]:
    """Why the files of folder ``path`` (the cache folder or one inside it) may not be used, and
    whether that is a matter of whose the folder is (``("", False)`` when they may be used).

    The cache folder and every folder from it down to ``path`` must pass :func:`trouble`; a folder
    not there yet passes (it holds nothing), and ``create`` makes it, for its owner only."""
    root = _folder()
    chain = [root]
    rel = os.path.relpath(os.fspath(path), root)
    if rel != os.curdir and not rel.startswith(os.pardir):
        for part in rel.split(os.sep):
            chain.append(os.path.join(chain[-1], part))
    elif rel != os.curdir:  # pragma: no cover - a folder outside the cache folder: checked alone
        chain.append(os.fspath(path))
    for where in chain:
        try:
            if create:
                if where == root:
                    os.makedirs(os.path.dirname(os.path.abspath(root)), exist_ok=True)
                try:
                    os.mkdir(where, 0o700)
                except FileExistsError:
                    pass
            st = os.stat(where)
        except FileNotFoundError:
            return ("", False) if not create else (f"{where} could not be made", False)
        except OSError as exc:
            return f"{type(exc).__name__}: {exc.strerror or exc}", False
        why = trouble(st, folder=True)
        if why:
            return f"{where} {why}", True
    return "", False


def usable_folder(path, *, create: bool = False) -> bool:
    """True when the files of folder ``path`` may be used (:func:`folder_trouble`); where that is a
    matter of whose the folder is, one warning names it (a folder that cannot be made or reached
    holds nothing to use: the caller computes, as without a cache)."""
    why, unsafe = folder_trouble(path, create=create)
    if unsafe:
        warn_once(_folder(), f"{why}; not used", kind="unsafe")
    return not why


def read_entry(path, limit: int = MAX_BYTES):
    """The bytes of cache file ``path``, or None: absent, unreadable, or not to be used (:func:`trouble`,
    then with one warning). Opened without following a link or waiting on a FIFO, and checked on the
    open file itself, so what is read is what was checked."""
    flags = os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(path, flags)
    except FileNotFoundError:
        return None
    except OSError:  # a link (ELOOP under O_NOFOLLOW), or no permission
        try:
            st = os.lstat(path)
        except OSError:
            return None
        why = trouble(st)
        if why:
            warn_once(_folder(), f"{path} {why}; not used", kind="unsafe")
        return None
    try:
        st = os.fstat(fd)
        why = trouble(st) or ("" if st.st_size <= limit else f"is larger than any entry ({st.st_size} bytes)")
        if why:
            warn_once(_folder(), f"{path} {why}; not used", kind="unsafe")
            return None
        with os.fdopen(fd, "rb", closefd=False) as fh:
            data = fh.read(limit + 1)
        return data if len(data) <= limit else None
    except OSError:
        return None
    finally:
        os.close(fd)


def entry_trouble(path) -> str:
    """Why the existing cache file ``path`` may not be used ("" when it may, or is not there)."""
    try:
        return trouble(os.lstat(path))
    except FileNotFoundError:
        return ""
    except OSError as exc:
        return f"cannot be examined ({exc.strerror})"


# ----------------------------------------------------------------------------------- names
@functools.lru_cache(maxsize=1)
def core_hash() -> str:
    """SHA-256 (hex) of every source file of the core, with its relative path, in a fixed order
    (``sorted(Path.rglob("*.py"))``'s: by path components, not descending into linked folders)."""
    import hashlib

    core = os.path.join(os.path.dirname(os.path.dirname(os.path.realpath(__file__))), "core")
    found = []
    for folder, dirs, files in os.walk(core):
        rel = os.path.relpath(folder, core)
        parts = [] if rel == os.curdir else rel.split(os.sep)
        found += [(parts + [n], os.path.join(folder, n)) for n in dirs + files if os.path.normcase(n).endswith(".py")]
    h = hashlib.sha256()
    for parts, path in sorted(found, key=lambda item: [os.path.normcase(p) for p in item[0]]):
        h.update("/".join(parts).encode())
        with open(path, "rb") as fh:
            h.update(fh.read())
    return h.hexdigest()


def dist_version(package: str) -> str:
    """``package``'s installed version, read from its ``.dist-info`` folder name without importing it
    (``importlib.metadata`` costs 0.1 s, ``import scipy`` 6-9 ms); "" when it cannot be told (then a
    caller either keeps nothing or imports the package to ask it)."""
    import importlib.util
    from pathlib import Path

    try:
        spec = importlib.util.find_spec(package)
    except (ImportError, ValueError):
        return ""
    if spec is None or not spec.submodule_search_locations:
        return ""
    site = Path(next(iter(spec.submodule_search_locations))).parent
    try:
        names = [n for n in os.listdir(site) if n.startswith(package + "-") and n.endswith(".dist-info")]
    except OSError:
        return ""
    return names[0][len(package) + 1 : -len(".dist-info")] if len(names) == 1 else ""


# ----------------------------------------------------------------------------------- writing
def write_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder (for its owner only:
    :func:`tempfile.mkstemp`), then rename it."""
    import tempfile

    path.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


@contextmanager
def locked(folder: Path, name: str, timeout: float = 600.0):
    """Hold an exclusive advisory lock ``folder/name.lock`` while the block runs, if one can be had.

    Yields True when the lock is held, False when the block runs without it (see the module
    docstring); it never raises for want of a lock. Not re-entrant within one thread. No lock is
    taken in a folder whose files may not be used (:func:`usable_folder`).
    """
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX
        yield False
        return
    fd = None
    if usable_folder(folder, create=True):
        flags = os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0) | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0)
        try:
            fd = os.open(os.path.join(folder, f"{name}.lock"), flags, 0o600)
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                os.close(fd)
                fd = None
        except OSError:
            fd = None
    held = False
    if fd is not None:
        deadline = time.monotonic() + timeout
        pause = 0.005
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                held = True
                break
            except BlockingIOError:
                if time.monotonic() >= deadline:
                    break
                time.sleep(pause)
                pause = min(2 * pause, 0.1)
            except OSError:  # a file system without locks
                break
    try:
        yield held
    finally:
        if fd is not None:
            if held:
                try:
                    fcntl.flock(fd, fcntl.LOCK_UN)
                except OSError:  # pragma: no cover
                    pass
            os.close(fd)


# ----------------------------------------------------------------------------------- tables
def _tables() -> str:
    return os.path.join(_folder(), "tables")


def _path(kind: str, key: str) -> str:
    return os.path.join(_tables(), f"{kind}_{key}.npy")


def _stored(data: bytes | None) -> bytes | None:
    """The ``.npy`` body of a file :func:`store_array` wrote (format line, then the SHA-256 of the
    rest, which matches), else None."""
    import hashlib

    head = len(_FORMAT) + 32
    if data is None or len(data) <= head or not data.startswith(_FORMAT):
        return None
    body = data[head:]
    return body if hashlib.sha256(body).digest() == data[len(_FORMAT) : head] else None


def load_array(kind: str, key: str):
    """The float64 array stored under ``kind``/``key``, or None (absent, unreadable, corrupt, or not
    to be used: :func:`read_entry`)."""
    import numpy as np

    if not usable_folder(_tables()):
        return None
    body = _stored(read_entry(_path(kind, key)))
    if body is None:
        return None
    try:
        arr = np.load(io.BytesIO(body), allow_pickle=False)
    except (ValueError, OSError, EOFError, SyntaxError):  # a malformed header
        return None
    if not isinstance(arr, np.ndarray) or arr.dtype != np.float64:
        return None
    return arr


def store_array(kind: str, key: str, arr) -> bool:
    """Store ``arr`` under ``kind``/``key`` atomically; False (and nothing raised) where it cannot."""
    import hashlib
    from pathlib import Path

    import numpy as np

    buf = io.BytesIO()
    np.save(buf, np.ascontiguousarray(arr, dtype=np.float64), allow_pickle=False)
    body = buf.getvalue()
    try:
        if not usable_folder(_tables(), create=True):
            return False
        write_atomic(Path(_path(kind, key)), _FORMAT + hashlib.sha256(body).digest() + body)
    except OSError:
        return False
    return True


def owned_tables(folder: Path | None = None) -> list:
    """The files of ``folder/tables`` (default :func:`cache_dir`) that this module can prove it wrote:
    every array :func:`store_array` stored (checked by its content) and the lock file :func:`locked`
    made beside it under the same name. Nothing else: a file that only looks like one (a name, a
    suffix) is not counted, nor a damaged entry that no longer proves it."""
    from pathlib import Path

    tables = Path(cache_dir() if folder is None else folder) / "tables"
    try:
        entries = sorted(tables.iterdir())
    except OSError:
        return []
    owned = []
    for p in entries:
        if p.suffix != ".npy" or p.is_symlink() or not p.is_file():
            continue
        try:
            data = p.read_bytes() if p.stat().st_size <= MAX_BYTES else None
        except OSError:
            continue
        if _stored(data) is not None:
            owned.append(p)
    stems = {p.stem for p in owned}
    locks = [p for p in entries if p.suffix == ".lock" and p.stem in stems and p.is_file() and not p.is_symlink()]
    return owned + locks


def total_bytes(paths) -> int:
    """The summed size of ``paths`` in bytes (a file gone or unreadable meanwhile counts 0)."""
    size = 0
    for p in paths:
        try:
            size += p.stat().st_size
        except OSError:
            pass
    return size
