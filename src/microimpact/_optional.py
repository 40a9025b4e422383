"""Optional dependencies (extras): import them with a clear message when missing."""

from __future__ import annotations

import contextlib
import importlib
import sys

__all__ = ["MissingExtraError", "require", "without_dask_probe"]

_EXTRA_OF = {
    "matplotlib": "plot",
    "xarray": "sweep",
    "dask": "sweep",
    "netCDF4": "sweep",
    "polars": "sweep",
}


class MissingExtraError(ImportError):
    """An optional dependency is not installed; the message names the extra to install."""


def require(module: str, purpose: str = ""):
    """Import ``module`` or raise :class:`MissingExtraError` naming the pip extra that provides it."""
    try:
        return importlib.import_module(module)
    except ImportError:
        top = module.split(".")[0]
        extra = _EXTRA_OF.get(top, "all")
        what = f" for {purpose}" if purpose else ""
        raise MissingExtraError(
            f"{top} is needed{what} but is not installed: pip install 'microimpact[{extra}]'"
        ) from None


@contextlib.contextmanager
def without_dask_probe():
    """While dask is not imported, tell xarray that no dask array or collection exists (true then).

    xarray asks, for every variable it builds, whether the data are a dask array, and imports
    :mod:`dask.array` to know (``xarray.namedarray.pycompat.array_type("dask")``): about half a
    second, more than a small eager sweep costs altogether (issue 25). Building an index it asks
    whether the data are a dask collection and imports :mod:`dask.base` to know
    (``xarray.namedarray.utils.is_dask_collection``): another 0.1-0.2 s. No object can be a dask
    array before that module is imported, so inside this context xarray's cached answer is "dask
    absent"; it is withdrawn on the way out (a later lazy sweep imports dask as before). Likewise,
    while dask itself is not imported, the collection check answers False without importing it, and
    the question which dask scheduler is active (asked by ``to_netcdf``, which imports dask for it)
    answers None, xarray's own answer without dask: none is; both ask dask as before once anything
    has imported it. A no-op once dask is imported, or where xarray keeps no such cache or check.
    """
    with _answered_without_dask(), _no_dask_array_probe():
        yield


#: xarray's checks that import dask to answer, and their answer while dask is not imported: no dask
#: collection exists (``is_dask_collection``) and no dask scheduler is active (``get_dask_scheduler``,
#: whose name ``writers`` holds apart from ``locks``).
_DASK_CHECKS = (
    ("xarray.namedarray.utils", "is_dask_collection", False),
    ("xarray.backends.locks", "get_dask_scheduler", None),
    ("xarray.backends.writers", "get_dask_scheduler", None),
)


@contextlib.contextmanager
def _answered_without_dask():
    """Each of :data:`_DASK_CHECKS` answers its value without importing dask while dask is not imported
    (by anyone, in any thread), and asks dask as before once it is; given back on the way out."""
    swapped = []
    for where, name, answer in _DASK_CHECKS:
        try:
            module = importlib.import_module(where)
        except ImportError:  # pragma: no cover - another xarray layout: nothing to skip
            continue
        original = getattr(module, name, None)
        if "dask" in sys.modules or not callable(original):
            continue

        def check(*args, _original=original, _answer=answer, **kwargs):
            return _original(*args, **kwargs) if "dask" in sys.modules else _answer

        setattr(module, name, check)
        swapped.append((module, name, original, check))
    try:
        yield
    finally:
        for module, name, original, ours in swapped:
            if getattr(module, name) is ours:
                setattr(module, name, original)


@contextlib.contextmanager
def _no_dask_array_probe():
    try:
        from xarray.namedarray import pycompat
    except ImportError:  # pragma: no cover - another xarray layout: nothing to skip
        yield
        return
    cache = getattr(pycompat, "_cached_duck_array_modules", None)
    known = isinstance(cache, dict) and hasattr(pycompat, "DuckArrayModule") and hasattr(pycompat, "Version")
    if "dask.array" in sys.modules or not known or "dask" in cache:
        yield
        return
    absent = object.__new__(pycompat.DuckArrayModule)
    absent.module, absent.type, absent.available = None, (), False
    absent.version = pycompat.Version("0.0.0")  # what xarray records for a module it cannot import
    cache["dask"] = absent
    try:
        yield
    finally:
        if cache.get("dask") is absent:
            del cache["dask"]
