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
    """While dask.array is not imported, tell xarray that no dask array exists (true then).

    xarray asks, for every variable it builds, whether the data are a dask array, and imports
    :mod:`dask.array` to know (``xarray.namedarray.pycompat.array_type("dask")``): about half a
    second, more than a small eager sweep costs altogether (issue 25). No object can be a dask array
    before that module is imported, so inside this context xarray's cached answer is "dask absent";
    it is withdrawn on the way out (a later lazy sweep imports dask as before). A no-op once
    dask.array is imported, or where xarray keeps no such cache.
    """
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
