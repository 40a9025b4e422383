"""The on-disk cache shared by the compiled loops and the tabulated results: folder, key, lock, arrays.

Everything here is an optimisation: a folder that cannot be created or written, a lock that cannot
be had, a file that is missing, truncated, corrupt or from another version all fall back to
computing (and to trying to write the result for the next process), never to an error.

* :func:`cache_dir` is the folder (``MICROIMPACT_CACHE_DIR``, else ``$XDG_CACHE_HOME/microimpact``,
  else ``~/.cache/microimpact``): the compiled loops live in ``kernels/``, tables in ``tables/``.
* :func:`core_hash` hashes the core's sources: a cached result's name carries it, so editing a
  formula can never leave a stale entry (the compiled loops add numba's and Python's versions).
* :func:`sha256` makes every hash here (names and checksums): ``hashlib.sha256``'s digests, without
  loading OpenSSL where Python has its own implementation.
* :func:`locked` is an advisory file lock (``fcntl.flock``) around a first computation, so that
  processes started together on an empty cache compute an entry once while the others wait and
  then read it; without a lock (no ``fcntl``, a read-only folder, a wait longer than ``timeout``)
  each computes on its own, as without a cache.
* :func:`load_array` / :func:`store_array` keep one float64 array per key, written atomically
  (temporary file beside it, then renamed) with a SHA-256 of its bytes that is checked on reading.
"""

from __future__ import annotations

import errno
import functools
import io
import os
import time
from contextlib import contextmanager
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pathlib import Path

# pathlib loads where it is used, OpenSSL's hashlib not at all (sha256): reading a stored table needs
# neither, and a script's first read of a warm table must take 0.3 s at most in a new process (row 11
# of the benchmarks), of which pathlib would be 7-15 ms and OpenSSL's hashlib 5-8 ms.

__all__ = [
    "cache_dir",
    "core_hash",
    "sha256",
    "locked",
    "load_array",
    "store_array",
    "write_atomic",
    "owned_tables",
    "total_bytes",
    "dist_version",
]
#: Bumped when the file layout of :func:`store_array` changes.
_FORMAT = b"microimpact-array-1\n"


def cache_dir() -> Path:
    """Where the compiled loops and tables are kept (module docstring)."""
    from pathlib import Path

    return Path(_folder())


def _folder() -> str:
    """:func:`cache_dir` as a string, for the paths that read without pathlib (above)."""
    env = os.environ.get("MICROIMPACT_CACHE_DIR")
    if env:
        return env
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "microimpact")


def sha256(data: bytes = b""):
    """A ``hashlib.sha256`` object of ``data``: Python's own implementation where it has one (the
    same digests; a few ms less than loading OpenSSL, and 1 ms slower on the core's 0.4 MB), else hashlib's."""
    try:
        from _sha2 import sha256 as new  # CPython 3.12 and later
    except ImportError:
        try:
            from _sha256 import sha256 as new  # CPython 3.10, 3.11
        except ImportError:  # pragma: no cover - a Python built without its own hashes
            from hashlib import sha256 as new
    return new(data)


@functools.lru_cache(maxsize=1)
def core_hash() -> str:
    """SHA-256 (hex) of every source file of the core, with its relative path, in a fixed order.

    Walked with ``os.walk``, not pathlib (see the imports), in ``sorted(Path.rglob("*.py"))``'s
    order and with its files: by path components, not descending into linked folders."""
    core = os.path.dirname(os.path.realpath(__file__))
    found = []
    for folder, dirs, files in os.walk(core):
        rel = os.path.relpath(folder, core)
        parts = [] if rel == os.curdir else rel.split(os.sep)
        found += [(parts + [n], os.path.join(folder, n)) for n in dirs + files if os.path.normcase(n).endswith(".py")]
    h = sha256()
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


#: Flags of :func:`mkstemp`'s open: those of :func:`tempfile.mkstemp` (binary).
_TEMP_FLAGS = (
    os.O_RDWR
    | os.O_CREAT
    | os.O_EXCL
    | getattr(os, "O_NOFOLLOW", 0)
    | getattr(os, "O_CLOEXEC", 0)
    | getattr(os, "O_BINARY", 0)
)


def _create_unique(folder, prefix: str, suffix: str, make):
    """``make(path)`` for ``path = folder/prefix<12 random hex digits>suffix``, a new name tried while
    ``make`` finds the name taken (as :mod:`tempfile`, up to its ``TMP_MAX`` tries)."""
    folder = os.path.abspath(os.fspath(folder))
    for _ in range(10000):
        name = os.path.join(folder, f"{prefix}{os.urandom(6).hex()}{suffix}")
        try:
            return make(name)
        except FileExistsError:
            continue
    raise FileExistsError(errno.EEXIST, "no unused temporary name", folder)


def mkstemp(folder, prefix: str = "", suffix: str = "") -> tuple[int, str]:
    """``(fd, path)`` of a new file ``folder/prefix<12 random hex digits>suffix``, created exclusively,
    readable and writable by its owner only: :func:`tempfile.mkstemp`'s contract, without importing
    :mod:`tempfile`, which brings ``shutil``, ``random``, ``bz2`` and ``lzma`` with it: 7 ms of a
    command's 0.3 s warm start (issue 25)."""
    return _create_unique(folder, prefix, suffix, lambda name: (os.open(name, _TEMP_FLAGS, 0o600), name))


def _new_folder(name: str) -> str:
    os.mkdir(name, 0o700)
    return name


def mkdtemp(folder, prefix: str = "", suffix: str = "") -> str:
    """Path of a new folder ``folder/prefix<12 random hex digits>suffix``, created exclusively, for its
    owner only: :func:`tempfile.mkdtemp`'s contract without the import (:func:`mkstemp`)."""
    return _create_unique(folder, prefix, suffix, _new_folder)


def write_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder, then rename it."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = mkstemp(path.parent, path.name + ".", ".tmp")
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
    docstring); it never raises for want of a lock. Not re-entrant within one thread.
    """
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX
        yield False
        return
    fd = None
    try:
        folder.mkdir(parents=True, exist_ok=True)
        fd = os.open(folder / f"{name}.lock", os.O_RDWR | os.O_CREAT, 0o644)
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


def _path(kind: str, key: str) -> str:
    return os.path.join(_folder(), "tables", f"{kind}_{key}.npy")


def load_array(kind: str, key: str):
    """The float64 array stored under ``kind``/``key``, or None (absent, unreadable or corrupt)."""
    import numpy as np

    try:
        with open(_path(kind, key), "rb") as fh:
            data = fh.read()
    except OSError:
        return None
    head = len(_FORMAT) + 32
    if len(data) <= head or data[: len(_FORMAT)] != _FORMAT:
        return None
    body = data[head:]
    if sha256(body).digest() != data[len(_FORMAT) : head]:
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
    from pathlib import Path

    import numpy as np

    buf = io.BytesIO()
    np.save(buf, np.ascontiguousarray(arr, dtype=np.float64), allow_pickle=False)
    body = buf.getvalue()
    try:
        write_atomic(Path(_path(kind, key)), _FORMAT + sha256(body).digest() + body)
    except OSError:
        return False
    return True


def _is_stored_array(path) -> bool:
    """True when ``path`` is a regular file :func:`store_array` wrote: its format line, then the
    SHA-256 of the rest, which matches (a file of another origin cannot pass by chance)."""
    if path.is_symlink() or not path.is_file():
        return False
    try:
        data = path.read_bytes()
    except OSError:
        return False
    head = len(_FORMAT) + 32
    return len(data) > head and data.startswith(_FORMAT) and sha256(data[head:]).digest() == data[len(_FORMAT) : head]


def owned_tables(folder: Path | None = None) -> list:
    """The files of ``folder/tables`` (default :func:`cache_dir`) that this module can prove it wrote:
    every array :func:`store_array` stored (checked by its content, see :func:`_is_stored_array`) and
    the lock file :func:`locked` made beside it under the same name. Nothing else: a file that only
    looks like one (a name, a suffix) is not counted, nor a damaged entry that no longer proves it."""
    from pathlib import Path

    tables = Path(cache_dir() if folder is None else folder) / "tables"
    try:
        entries = sorted(tables.iterdir())
    except OSError:
        return []
    owned = [p for p in entries if p.suffix == ".npy" and _is_stored_array(p)]
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
