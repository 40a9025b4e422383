"""The calibrations of :func:`microimpact.calibrate.calibrate` kept on disk, so that a new process reads them.

A calibration costs a root search or a least-squares fit over integrated impacts (``compare``
calibrates four DEM laws: about a second, and the import of :mod:`scipy.optimize`), and its result
depends only on its inputs and on the code that computes it. It is kept in the cache folder of the
compiled loops and tables (:func:`microimpact.engine.cache.cache_dir`, ``calibrations/``), named by
the same rule as they are: a SHA-256 of

* the inputs: the model's name, the pair's four effective values, the calibration speeds, the
  targets ``e`` and contact time at them (their float64 bytes) and the options;
* the sources that compute it: the core's (:func:`microimpact.engine.cache.core_hash`, every model's
  physics), the faces' (``microimpact/models/*.py``: each law's inverse, the generic least
  squares), :mod:`microimpact.calibrate` (the driver and its monotonicity check), this module, and
  the files of a model added from outside the package;
* the versions of what else enters the numbers: Python, NumPy and SciPy.

What is kept is everything :func:`~microimpact.calibrate.calibrate` computes: the parameters, the
law's ``e`` and contact time at the speeds (float64, bit for bit) and the text of the warning it
gives (or none), so that a cached call returns and warns exactly as a computed one.

A cache is an optimisation: an entry that is missing, unreadable, truncated, corrupt (its SHA-256
is checked), of another layout or of the wrong sizes is computed again, and a folder that cannot
be written is left alone; nothing here raises. Entries are written atomically (a temporary file
beside them, then renamed), so processes writing the same entry at once leave one whole file.
Set ``MICROIMPACT_CACHE_DIR`` to move the folder; delete it to clear the cache.

An entry is read only when no one but the current user can have written it (the rule of
:func:`microimpact.engine.cache.trouble`: the folders and the file the user's own and writable by
no one else, a regular file no larger than :data:`MAX_BYTES`); else it is passed over with one
:class:`~microimpact.engine.cache.CacheWarning` and the calibration computed. The warning text an
entry holds is shown only without control characters (:func:`printable`): a file is no place for
a terminal's escape sequences.
"""

from __future__ import annotations

import functools
import hashlib
import json
import sys
from pathlib import Path

import numpy as np

from .engine import cache as _cache

__all__ = ["key", "load", "store", "owned_files", "printable", "MAX_BYTES"]

#: Bumped when the layout of an entry changes.
_FORMAT = "microimpact-calibration-1"
_HERE = Path(__file__).resolve().parent
#: The option values a key can name exactly; a calibration with any other is not cached.
_PLAIN = (bool, int, float, str, type(None))
#: Largest calibration entry read [bytes] (a calibration at 10^4 speeds is about 0.5 MB).
MAX_BYTES = 1 << 24


@functools.lru_cache(maxsize=1)
def _code_hash() -> str:
    h = hashlib.sha256(_cache.core_hash().encode())
    for path in [_HERE / "calibrate.py", Path(__file__).resolve(), *sorted((_HERE / "models").glob("*.py"))]:
        h.update(path.name.encode())
        h.update(path.read_bytes())
    h.update(f"{sys.version}|{np.__version__}|{_scipy_version()}".encode())
    return h.hexdigest()


def _scipy_version() -> str:
    """``scipy.__version__``, read from its ``.dist-info`` folder where scipy is not imported yet: a
    calibration found in the cache needs nothing of scipy, whose import is 6-9 ms of a ``compare``."""
    if "scipy" not in sys.modules:
        version = _cache.dist_version("scipy")
        if version:
            return version
    import scipy

    return scipy.__version__


def _outside_files(face):
    """The files of a model (and its face) added from outside the package, whose source enters the key;
    None when the model has no source file to hash (one built in memory): then nothing is cached."""
    files = []
    for module in (getattr(face.model, "module", face.model), face.module):  # a Model's module, its face's
        if module is None:  # no face file: the defaults of models/_base.py, hashed with the package
            continue
        name = getattr(module, "__file__", None)
        if not name:
            return None
        path = Path(name).resolve()
        if _HERE not in path.parents:
            files.append(path)
    return files


def key(face, pair_values, velocity, target_restitution, target_contact_time, options):
    """The name of the calibration of ``face``'s law with these inputs, or None when it is not to be cached
    (an option that is not a plain number, string or bool, a model without a source file, or a source
    file that cannot be read)."""
    if not all(type(v) in _PLAIN for v in options.values()):
        return None
    files = _outside_files(face)
    if files is None:
        return None
    try:
        h = hashlib.sha256(_code_hash().encode())
        for path in files:
            h.update(path.read_bytes())
    except OSError:
        return None
    h.update(repr((face.name, tuple(float(x).hex() for x in pair_values))).encode())
    h.update(repr(sorted((k, type(v).__name__, repr(v)) for k, v in options.items())).encode())
    for arr in (velocity, target_restitution, target_contact_time):
        arr = np.ascontiguousarray(arr, dtype=np.float64)
        h.update(repr(arr.shape).encode())
        h.update(arr.tobytes())
    return h.hexdigest()[:32]


def _path(name: str) -> Path:
    return _cache.cache_dir() / "calibrations" / f"{name}.json"


def _floats(values, size=None):
    out = [float.fromhex(v) for v in values]
    if size is not None and len(out) != size:
        raise ValueError("wrong size")
    return out


def load(name, n_params, n_speeds):
    """``(params, restitution, contact_time, warning)`` stored under ``name``, or None (absent, unreadable,
    corrupt or not of ``n_params`` parameters and ``n_speeds`` speeds)."""
    if name is None:
        return None
    path = _path(name)
    if not _cache.usable_folder(path.parent):
        return None
    data = _cache.read_entry(path, MAX_BYTES)
    if data is None:
        return None
    try:
        digest, _, body = data.partition(b"\n")
        if hashlib.sha256(body).hexdigest().encode() != digest:
            return None
        entry = json.loads(body)
        if entry["format"] != _FORMAT or entry["key"] != name:
            return None
        params = tuple(_floats(entry["params"], n_params))
        e = np.array(_floats(entry["restitution"], n_speeds), dtype=np.float64)
        t = np.array(_floats(entry["contact_time"], n_speeds), dtype=np.float64)
        warning = entry["warning"]
        if warning is not None and not isinstance(warning, str):
            return None
    except (OSError, ValueError, TypeError, KeyError, AttributeError):
        return None
    return params, e, t, None if warning is None else printable(warning)


def printable(text: str) -> str:
    """``text`` without control and format characters (Unicode categories ``Cc`` and ``Cf``: escape
    sequences, carriage returns, bells, direction overrides), line breaks and tabs aside: what a
    stored warning may show."""
    import unicodedata

    return "".join(c for c in text if c in "\n\t" or unicodedata.category(c) not in ("Cc", "Cf"))


def store(name, params, restitution, contact_time, warning) -> bool:
    """Keep a calibration under ``name`` (atomically); False, and nothing raised, where it cannot."""
    if name is None:
        return False
    entry = {
        "format": _FORMAT,
        "key": name,
        "params": [float(p).hex() for p in params],
        "restitution": [float(x).hex() for x in np.ravel(restitution)],
        "contact_time": [float(x).hex() for x in np.ravel(contact_time)],
        "warning": warning,
    }
    body = json.dumps(entry).encode()
    path = _path(name)
    try:
        if not _cache.usable_folder(path.parent, create=True):
            return False
        _cache.write_atomic(path, hashlib.sha256(body).hexdigest().encode() + b"\n" + body)
    except OSError:
        return False
    return True


def owned_files(folder=None) -> list:
    """The entries of ``folder/calibrations`` (default the cache folder) that :func:`store` wrote and can
    prove it: a first line that is the SHA-256 of the rest, which is this layout's JSON naming its own
    file. Anything else in the folder (a user's file, a damaged entry) is not counted."""
    root = Path(_cache.cache_dir() if folder is None else folder) / "calibrations"
    try:
        entries = sorted(root.iterdir())
    except OSError:
        return []
    owned = []
    for path in entries:
        if path.suffix != ".json" or path.is_symlink() or not path.is_file():
            continue
        try:
            digest, _, body = path.read_bytes().partition(b"\n")
            if hashlib.sha256(body).hexdigest().encode() != digest:
                continue
            entry = json.loads(body)
            if entry.get("format") == _FORMAT and entry.get("key") == path.stem:
                owned.append(path)
        except (OSError, ValueError, AttributeError):
            continue
    return owned
