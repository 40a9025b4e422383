"""Input checks shared by the physics functions.

Every check raises :class:`ValueError` whose message names the parameter and
the offending value, so that a user (and the CLI, which prints the message on
one line) can see at once what was wrong.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "check_positive",
    "check_poisson",
    "check_velocity",
    "check_nonnegative",
]


def _first_bad(arr: np.ndarray, bad: np.ndarray):
    """Return the first offending element of ``arr`` (for the message)."""
    x = arr[bad].flat[0] if arr.ndim else arr[()]
    return float(x)


def _as_float_array(name: str, value) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number or an array of numbers, got {value!r}") from None
    return arr


def check_positive(name: str, value, *, allow_inf: bool = False) -> np.ndarray:
    """``value`` as a float array; raise ``ValueError`` unless all > 0 and finite.

    ``allow_inf`` admits ``+inf`` (an infinite radius or mass is a flat, fixed wall).
    """
    arr = _as_float_array(name, value)
    bad = ~(arr > 0) | (np.isinf(arr) if not allow_inf else np.isnan(arr))
    if np.any(bad):
        raise ValueError(
            f"{name} must be positive and finite, got {_first_bad(arr, bad)!r}"
            if not allow_inf
            else f"{name} must be positive, got {_first_bad(arr, bad)!r}"
        )
    return arr


def check_nonnegative(name: str, value) -> np.ndarray:
    """``value`` as a float array; raise unless all >= 0 and not NaN (``inf`` allowed)."""
    arr = _as_float_array(name, value)
    bad = ~(arr >= 0)
    if np.any(bad):
        raise ValueError(f"{name} must be non-negative and not NaN, got {_first_bad(arr, bad)!r}")
    return arr


def check_poisson(name: str, value) -> np.ndarray:
    """Poisson ratio: raise unless every value lies in (-1, 0.5]."""
    arr = _as_float_array(name, value)
    bad = ~((arr > -1.0) & (arr <= 0.5))
    if np.any(bad):
        raise ValueError(f"{name} must lie in (-1, 0.5], got {_first_bad(arr, bad)!r}")
    return arr


def check_velocity(name: str, value) -> np.ndarray:
    """Impact speed: non-negative, not NaN; ``+inf`` is allowed (its limit is defined)."""
    return check_nonnegative(name, value)


def check_pair(effective_modulus, effective_radius, effective_mass, limiting_pressure):
    """``E*``, ``R*``, ``m*`` (positive, finite) and ``p_y`` (positive, ``inf`` allowed) as float arrays."""
    return (
        check_positive("effective_modulus", effective_modulus),
        check_positive("effective_radius", effective_radius),
        check_positive("effective_mass", effective_mass),
        check_positive("limiting_pressure", limiting_pressure, allow_inf=True),
    )
