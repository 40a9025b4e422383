"""Optional dependencies (extras): import them with a clear message when missing."""

from __future__ import annotations

import importlib

__all__ = ["MissingExtraError", "require"]

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
