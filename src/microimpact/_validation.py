"""Input checks shared by the physics functions.

Every check raises :class:`ValueError` whose message names the parameter and
the offending value, so that a user (and the CLI, which prints the message on
one line) can see at once what was wrong.

What counts as a number: Python and numpy integers and floats, arrays of them,
and objects numpy converts to a float array (``Fraction``, ``Decimal``).
Refused, with the parameter named: ``None`` ("got None"), booleans (``True`` is
not 1 m), complex numbers (even with a zero imaginary part: the model is real),
masked arrays with masked entries (the mask would be ignored), text, and ragged
sequences. With ``scalar=True`` a check also refuses anything but a single
number and returns a Python ``float``.
"""

from __future__ import annotations

import re
import sys

import numpy as np

__all__ = [
    "check_number",
    "check_positive",
    "check_poisson",
    "check_velocity",
    "check_nonnegative",
]

#: The bits of float64 ``+inf`` as an unsigned integer.
_INF_BITS = 0x7FF0000000000000
_U64 = np.dtype(np.uint64)


def nonnegative_finite(arr: np.ndarray) -> bool:
    """True when every element of the float64 ``arr`` lies in ``[+0, inf)``, in one read-only pass.

    IEEE 754: read as unsigned integers, the bit patterns of exactly those numbers (sign bit clear,
    exponent not all ones) lie below that of ``+inf``; a negative number (sign bit set), ``inf`` and
    every NaN lie at or above it. One integer maximum instead of a float minimum and maximum.
    ``-0.0`` reads as False: callers check again element by element. ``arr`` is not empty.
    """
    bits = arr.view(_U64)
    return bits.item(bits.argmax()) < _INF_BITS


def _first_bad(arr: np.ndarray, bad: np.ndarray):
    """Return the first offending element of ``arr`` (for the message)."""
    x = arr[bad].flat[0] if arr.ndim else arr[()]
    return float(x)


def _describe(value) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


_F64 = np.dtype(np.float64)


def _as_float_array(name: str, value) -> np.ndarray:
    if type(value) is np.ndarray and value.dtype is _F64:  # the common case, as below at once (0.4 us)
        return value
    if value is None:
        raise ValueError(f"{name} must be a number, got None")
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be a number, got the boolean {value!r} (booleans are not numbers)")
    if isinstance(value, (str, bytes)):
        raise ValueError(f"{name} must be a number, got the text {_describe(value)}")
    ma = sys.modules.get("numpy.ma")  # no masked array can exist before numpy.ma is imported (6 ms)
    if ma is not None and ma.isMaskedArray(value):
        if ma.is_masked(value):
            raise ValueError(
                f"{name} is a masked array with {int(ma.count_masked(value))} masked value(s): "
                "fill or drop them first (the mask would be ignored)"
            )
        value = ma.getdata(value)
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number or an array of numbers, got {_describe(value)}") from None
    kind = raw.dtype.kind
    if kind == "b":
        raise ValueError(f"{name} must be numbers, got booleans {_describe(value)} (booleans are not numbers)")
    if kind == "c":
        raise ValueError(f"{name} must be real, got the complex value(s) {_describe(value)}")
    if kind in "USV":
        raise ValueError(f"{name} must be a number or an array of numbers, got {_describe(value)}")
    if kind == "O":
        for x in raw.flat:
            if x is None or isinstance(x, (bool, np.bool_, str, bytes, complex, np.complexfloating)):
                what = "None" if x is None else _describe(x)
                raise ValueError(f"{name} must be a number or an array of numbers, got {what} in {_describe(value)}")
    if kind in "mM":
        raise ValueError(f"{name} must be a number, got the date/time {_describe(value)}")
    try:
        return raw.astype(float, copy=False)  # no copy of a float array: the checks only read it
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number or an array of numbers, got {_describe(value)}") from None


def _extremes(arr: np.ndarray):
    """``(min, max)`` of ``arr`` in two read-only passes (NaN if any element is NaN); ``None`` if empty.

    The checks below first test these against the bounds (one pass each, no temporary arrays) and
    only build the mask of offending elements, for the message, when they fail.
    """
    if arr.size == 0:
        return None
    return np.minimum.reduce(arr, axis=None), np.maximum.reduce(arr, axis=None)  # arr.min(), arr.max() less a wrapper


def _scalar(name: str, arr: np.ndarray, value):
    if arr.ndim != 0:
        if arr.size == 1:
            return float(arr.reshape(()))
        raise ValueError(
            f"{name} must be a single number, got {arr.size} values of shape {arr.shape}: {_describe(value)}"
        )
    return float(arr)


def check_number(name: str, value, *, scalar: bool = False):
    """``value`` as a float array (or float with ``scalar=True``), refusing the non-numbers above (NaN passes)."""
    arr = _as_float_array(name, value)
    return _scalar(name, arr, value) if scalar else arr


def check_positive(name: str, value, *, allow_inf: bool = False, scalar: bool = False):
    """``value`` as a float array; raise ``ValueError`` unless all > 0 and finite.

    ``allow_inf`` admits ``+inf`` (an infinite radius or mass is a flat, fixed wall).
    ``scalar=True`` requires a single number and returns a ``float``.
    """
    arr = _as_float_array(name, value)
    ext = _extremes(arr)
    if ext is not None and not (ext[0] > 0 and (allow_inf or ext[1] < np.inf)):
        bad = ~(arr > 0) | (np.isinf(arr) if not allow_inf else np.isnan(arr))
        raise ValueError(
            f"{name} must be positive and finite, got {_first_bad(arr, bad)!r}"
            if not allow_inf
            else f"{name} must be positive, got {_first_bad(arr, bad)!r}"
        )
    return _scalar(name, arr, value) if scalar else arr


def check_nonnegative(name: str, value, *, scalar: bool = False):
    """``value`` as a float array; raise unless all >= 0 and not NaN (``inf`` allowed)."""
    arr = _as_float_array(name, value)
    ext = _extremes(arr)
    if ext is not None and not ext[0] >= 0:
        bad = ~(arr >= 0)
        raise ValueError(f"{name} must be non-negative and not NaN, got {_first_bad(arr, bad)!r}")
    return _scalar(name, arr, value) if scalar else arr


def check_poisson(name: str, value, *, scalar: bool = False):
    """Poisson ratio: raise unless every value lies in (-1, 0.5]."""
    arr = _as_float_array(name, value)
    ext = _extremes(arr)
    if ext is not None and not (ext[0] > -1.0 and ext[1] <= 0.5):
        bad = ~((arr > -1.0) & (arr <= 0.5))
        raise ValueError(f"{name} must lie in (-1, 0.5], got {_first_bad(arr, bad)!r}")
    return _scalar(name, arr, value) if scalar else arr


def check_velocity(name: str, value, *, scalar: bool = False):
    """Impact speed: finite and non-negative.

    NaN and infinities are refused: an infinite speed has no outcome (the
    closed form's limit gives ``e = 0`` with an infinite rebound speed, which
    contradicts ``V_r = e V``), so it is an error rather than a result.
    """
    if type(value) is np.ndarray and value.dtype is _F64 and value.ndim == 1 and not scalar:
        # the usual call, as below without three calls (a tenth of what a call on 1e3 speeds adds, issue 25)
        if not value.shape[0] or nonnegative_finite(value):
            return value
    arr = _as_float_array(name, value)
    if arr.size and not nonnegative_finite(arr):
        bad = ~(arr >= 0) | np.isinf(arr)
        if bad.any():  # not only -0.0, which the bit test below sends here
            x = _first_bad(arr, bad)
            why = "non-negative and not NaN" if not x > 0 else "finite (an infinite impact speed has no outcome)"
            raise ValueError(f"{name} must be {why}, got {x!r}")
    return _scalar(name, arr, value) if scalar else arr


#: Below this ``p_y`` [Pa] the yield velocity is checked for underflow (no real material comes near it).
TINY_LIMITING_PRESSURE = 1e-3


def check_pair(effective_modulus, effective_radius, effective_mass, limiting_pressure):
    """``E*``, ``R*``, ``m*`` (positive, finite) and ``p_y`` (positive, ``inf`` allowed) as float arrays.

    A ``p_y`` so small that the yield velocity ``V_y`` (proportional to ``p_y^(5/2)``, seed eq. 28)
    underflows to 0 in double precision is refused, naming it (the model divides by ``V_y``).
    """
    out = (
        check_positive("effective_modulus", effective_modulus),
        check_positive("effective_radius", effective_radius),
        check_positive("effective_mass", effective_mass),
        check_positive("limiting_pressure", limiting_pressure, allow_inf=True),
    )
    p_y = out[3]
    if p_y.size and np.min(p_y) < TINY_LIMITING_PRESSURE:
        check_yield_velocity(*out)
    return out


def check_yield_velocity(E, R, m, p_y) -> None:
    """Raise a ValueError naming ``limiting_pressure`` where ``V_y`` underflows to 0 (only tiny ``p_y``)."""
    from .core.models.thornton_ning_2016 import yield_point

    E, R, m, p_y = np.broadcast_arrays(E, R, m, p_y)
    for i in np.flatnonzero(p_y < TINY_LIMITING_PRESSURE):
        args = (float(E.flat[i]), float(R.flat[i]), float(m.flat[i]), float(p_y.flat[i]))
        if not yield_point(*args)[2] > 0.0:
            raise ValueError(
                f"limiting_pressure {args[3]!r} Pa is too small: the yield velocity V_y (proportional to "
                f"p_y^(5/2), eq. 28) underflows to 0 in double precision"
            )


_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|[+-]?(?:inf|infinity|nan)", re.IGNORECASE)


def is_number_text(text) -> bool:
    """True when ``text`` (surrounding blanks allowed) is a decimal number as a person writes it.

    ``12``, ``-1.5``, ``.5``, ``2e9``, ``inf``, ``nan``; not Python's extras that :class:`float`
    also takes (``1_0`` is 10 to Python, a typo to a person; ``0x1p3``).
    """
    return _NUMBER.fullmatch(str(text).strip()) is not None


def parse_number(text, name: str = "value") -> float:
    """``float(text)`` for a decimal number (:func:`is_number_text`), else a ValueError naming ``name``."""
    if not is_number_text(text):
        raise ValueError(f"{name} must be a number, got {text!r}")
    return float(str(text).strip())
