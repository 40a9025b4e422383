"""Sizes checked against the memory before any large array is made, and the one progress bar.

Imported by every command before it computes: the standard library and nothing else at import.
"""

from __future__ import annotations

import math
import os
import sys

__all__ = ["MEMORY_ENV", "MEMORY_FRACTION", "MemoryBudgetError", "check_memory", "memory_budget", "progress_bar"]

#: Environment variable overriding the memory budget: bytes (``2e9``), or with a unit (``4GB``, ``512MiB``).
MEMORY_ENV = "MICROIMPACT_MAX_MEMORY"
#: Fraction of the available memory a single array allocation may use by default.
MEMORY_FRACTION = 0.5


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
