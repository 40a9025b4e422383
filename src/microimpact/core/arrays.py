"""Deprecated: the array engine moved to :mod:`microimpact.engine` (it is no physics).

Every name this module released still resolves, through the engine, with a
:class:`DeprecationWarning` naming its new home; it will be removed after one release.
"""

from __future__ import annotations

#: The names this module released, all now in :mod:`microimpact.engine`.
_MOVED = ("BACKENDS", "PARALLEL_MIN", "PARALLEL_WORK", "PYTHON_BUDGET", "SMALL", "backend_for", "cache_dir", "evaluate")

__all__: list = []


def __getattr__(name):
    if name not in _MOVED:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    import warnings

    from .. import engine  # the one import of the core from above it (tests/test_architecture.py allows it)

    warnings.warn(
        f"microimpact.core.arrays.{name} moved to microimpact.engine.{name}; the old name goes after one release",
        DeprecationWarning,
        stacklevel=2,
    )
    return getattr(engine, name)


def __dir__():
    return sorted(_MOVED)
