"""The on-disk cache (an optimisation: never needed), for users and the command line.

The array computations compile their loops with numba once and keep the machine code in a cache
folder, so that a new process loads instead of compiling; the same folder keeps the tables of the
oblique and adhesive laws (``tables/``) and the calibrations of ``compare`` (``calibrations/``).
:func:`cache_dir` and :class:`CacheWarning` are those of :mod:`microimpact.engine`;
:func:`cache_info` and :func:`clear_cache` cover the whole folder, so that code outside the physics
core, ``microimpact cache`` above all, reaches it without importing the core's internals.

A file counts as the cache's only when it proves it was written by microimpact: a generated loop
file by its first line (and numba's entries and the lock named after such a loop), a table by its
format line and the SHA-256 of its contents, a calibration by its checksum line and the key it
names. Nothing else in the folder is counted or deleted. And a file is used only when no one but
the current user can have written it (:mod:`microimpact.engine.cache`: the folder and the file the
user's own and writable by no one else, a regular file of bounded size); else it is passed over,
with one :class:`CacheWarning`, and the computation runs without it.
"""

from __future__ import annotations

from . import _calibration_cache
from . import engine as _engine
from .engine import CacheWarning, cache_dir
from .engine import cache as _engine_cache

__all__ = ["cache_dir", "cache_info", "clear_cache", "CacheWarning"]


def _owned_tables_and_calibrations(folder) -> list:
    """The files of ``folder``'s tables/ and calibrations/ that microimpact can prove it wrote."""
    return [*_engine_cache.owned_tables(folder), *_calibration_cache.owned_files(folder)]


def cache_info() -> dict:
    """What the cache holds: ``folder``, ``files``, ``bytes``, ``writable``.

    Only the files microimpact made there are counted (:func:`clear_cache` deletes just these):
    compiled loops (:func:`microimpact.engine.cache_info`), tables and calibrations.
    """
    info = _engine.cache_info()
    files = _owned_tables_and_calibrations(cache_dir())
    return {**info, "files": info["files"] + len(files), "bytes": info["bytes"] + _engine_cache.total_bytes(files)}


def clear_cache() -> int:
    """Delete the cache's own files (compiled loops, tables, calibrations); returns how many.

    Nothing else in the folder is touched (module docstring); a sub-folder is removed only when
    that leaves it empty. The loops and tables already loaded in this process stay usable.
    """
    n = _engine.clear_cache()
    folder = cache_dir()
    for p in _owned_tables_and_calibrations(folder):
        try:
            p.unlink()
            n += 1
        except FileNotFoundError:
            pass
    for d in (folder / "tables", folder / "calibrations"):
        try:
            d.rmdir()  # only when empty
        except OSError:
            pass
    return n
