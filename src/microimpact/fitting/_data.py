"""Checking measured points: what :func:`~microimpact.fitting.fit_restitution` takes in.

Reading them from a file is :func:`microimpact.io.load_restitution_csv` (reading and writing live in
:mod:`microimpact.io`).
"""

from __future__ import annotations

import numpy as np

from .._validation import TINY_NORMAL

#: The largest speed [m/s] a fit takes: its search for the yield velocity runs to twice the largest speed.
_LARGEST_SPEED = 0.5 * float(np.finfo(float).max)


class FitWarning(UserWarning):
    """Something in the data or the fit the user should look at (points far above 1, ...)."""


def point_name(i, line_numbers):
    return f"line {int(line_numbers[i])}" if line_numbers is not None else f"point {int(i)}"


def check_data(velocity, restitution, sigma, line_numbers):
    for what, x in (("velocity", velocity), ("restitution", restitution), ("sigma", sigma)):
        if x is None:
            continue
        if isinstance(x, bool) or (isinstance(x, np.ndarray) and x.dtype == bool):
            raise ValueError(f"{what} must be numbers, got booleans")
        if np.iscomplexobj(x):
            raise ValueError(f"{what} must be real numbers, got complex values")
        if np.ma.isMaskedArray(x):
            raise ValueError(f"{what}: masked arrays are not accepted; drop the masked points first")
    V = np.asarray(velocity, dtype=float).ravel()
    e = np.asarray(restitution, dtype=float).ravel()
    if V.size != e.size:
        raise ValueError(f"velocity and restitution must have the same length, got {V.size} and {e.size}")
    if V.size == 0:
        raise ValueError("no data points")
    if line_numbers is not None:
        line_numbers = np.asarray(line_numbers).ravel()
        if line_numbers.size != V.size:
            raise ValueError("line_numbers must have one entry per data point")
    bad = ~(np.isfinite(V) & (V > 0))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"velocity must be positive and finite, got {float(V[i])!r} ({point_name(i, line_numbers)})")
    # the start's search for V_y runs from 1e-3 of the smallest speed to twice the largest: both in the doubles
    bad = (V < TINY_NORMAL) | (V > _LARGEST_SPEED)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(
            f"velocity {float(V[i])!r} ({point_name(i, line_numbers)}) is outside what double precision can fit: "
            f"speeds must lie in [{TINY_NORMAL!r}, {_LARGEST_SPEED!r}] m/s (a subnormal speed has lost its precision, "
            "and the search for the yield velocity runs to twice the largest speed)"
        )
    bad = ~(np.isfinite(e) & (e >= 0))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"restitution must be finite and >= 0, got {float(e[i])!r} ({point_name(i, line_numbers)})")
    if sigma is not None:
        s = np.broadcast_to(np.asarray(sigma, dtype=float), V.shape).copy()
        bad = ~(np.isfinite(s) & (s > 0))
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"sigma must be positive and finite, got {float(s[i])!r} ({point_name(i, line_numbers)})")
        sigma = s
    return V, e, sigma, line_numbers
