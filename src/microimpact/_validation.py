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

import math
import re
import sys

import numpy as np

from .core import constants as _constants

__all__ = [
    "check_number",
    "check_positive",
    "check_poisson",
    "check_velocity",
    "check_nonnegative",
    "check_pair_scales",
    "check_dem_words",
    "check_dem_lines",
    "first_duplicate",
    "check_not_subnormal",
    "check_in_range",
    "describe_value",
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


def first_duplicate(arr: np.ndarray):
    """The smallest value that ``arr`` (1-D) holds more than once, or None.

    Values from a range (``start:stop:count``) are strictly monotonic, which a pass over blocks of
    them shows without a copy; otherwise a sorted copy is compared (8 bytes a value, 80 MB at 10^7).
    """
    n = arr.shape[0]
    rising = falling = True
    for i in range(0, n - 1, 1 << 20):
        end = min(i + (1 << 20), n - 1)
        a, b = arr[i:end], arr[i + 1 : end + 1]
        rising = rising and bool((b > a).all())
        falling = falling and bool((b < a).all())
        if not (rising or falling):
            break
    if rising or falling:
        return None
    s = np.sort(arr)
    dup = s[1:][s[1:] == s[:-1]]
    return dup[0] if dup.size else None


def _first_bad(arr: np.ndarray, bad: np.ndarray):
    """Return the first offending element of ``arr`` (for the message)."""
    x = arr[bad].flat[0] if arr.ndim else arr[()]
    return float(x)


def _describe(value) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def describe_value(value) -> str:
    """``repr(value)`` cut to 60 characters: an input, maybe a long array, named in a one-line message."""
    return _describe(value)


_F64 = np.dtype(np.float64)
#: The smallest normal double. A positive input below it (subnormal) has lost precision, and every
#: quotient by it (``1/x``; the models divide by the radius, the mass, the speed) overflows to inf.
TINY_NORMAL = _constants.TINY_NORMAL


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

    A subnormal value (below :data:`TINY_NORMAL`) is refused too, naming it: it has lost
    precision and every quotient by it overflows. Not with ``allow_inf``: there the quantity's
    reciprocal tends to 0 as it grows, and a tiny one (a ``p_y`` whose ``V_y`` underflows) is
    named by the pair's check with what it breaks (:func:`check_pair`).
    """
    arr = _as_float_array(name, value)
    ext = _extremes(arr)
    if ext is not None and not (
        (ext[0] > 0.0 if allow_inf else ext[0] >= TINY_NORMAL) and (allow_inf or ext[1] < np.inf)
    ):
        bad = ~(arr > 0) | (np.isinf(arr) if not allow_inf else np.isnan(arr))
        if bad.any():
            raise ValueError(
                f"{name} must be positive and finite, got {_first_bad(arr, bad)!r}"
                if not allow_inf
                else f"{name} must be positive, got {_first_bad(arr, bad)!r}"
            )
        raise ValueError(
            f"{name} must be a normal float (at least {TINY_NORMAL!r}), got the subnormal "
            f"{_first_bad(arr, arr < TINY_NORMAL)!r}: it has lost precision and its reciprocal overflows"
        )
    return _scalar(name, arr, value) if scalar else arr


def check_not_subnormal(name: str, arr):
    """``arr`` (already checked, float) unchanged; ``ValueError`` naming ``name`` where it holds a
    nonzero subnormal: a quantity whose reciprocal enters a formula (``1/R1 + 1/R2``, ``V/V_y``)
    overflows there. For the checks that admit ``inf`` or zero, which :func:`check_positive` leaves
    to the caller."""
    a = np.asarray(arr)
    bad = (a != 0.0) & (np.abs(a) < TINY_NORMAL)
    if bad.any():
        raise ValueError(
            f"{name} must be 0 or a normal float (at least {TINY_NORMAL!r}), got the subnormal "
            f"{_first_bad(a, bad)!r}: it has lost precision and its reciprocal overflows"
        )
    return arr


def check_in_range(result, what: str, **inputs):
    """``result`` unchanged where every element is finite or NaN; else ``ValueError`` naming ``what``
    and every input with its value: the inputs, each in range, give a quantity double precision cannot
    hold (an overflow), which is no answer and must not pass as one."""
    r = np.asarray(result)
    if np.isinf(r).any():
        given = ", ".join(f"{k} {_describe(v)}" for k, v in inputs.items())
        raise ValueError(f"{given} give {what} beyond the largest double: give inputs in range")
    return result


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
        # the usual call (1-D float64 speeds): one pass over the bits instead of the general checks below
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
    check_pair_scales(*out)
    return out


_NAMES = ("effective_modulus", "effective_radius", "effective_mass", "limiting_pressure")
#: Decimal exponents of the yield point's factors that double precision holds with room to spare.
_EXPONENT_ROOM = 300.0


def check_pair_scales(E, R, m, p_y) -> None:
    """Raise a ValueError naming the most extreme input where the yield velocity ``V_y`` (eq. 28)
    underflows to 0 or a subnormal, or is NaN, for positive ``E*``, ``R*``, ``m*`` and ``p_y``.

    Every model divides by ``V_y`` (``V/V_y``; seed eqs. 22-27): a pair whose ``V_y`` is not a normal
    float (``E* = 1e308`` Pa: the yield approach ``alpha_y = (pi p_y/(2 E*))^2 R*`` underflows) gives
    a division by zero instead of a result. ``V_y = inf`` (``p_y`` or ``R*`` so large that the pair
    never yields at a finite speed) is the elastic limit and is kept, as is ``p_y = inf``. The
    decimal exponents of ``alpha_y``, ``P_y`` and ``P_y alpha_y/m*`` are estimated with logarithms
    (cheap, over arrays); only a pair whose estimate leaves ``10^(+-300)`` is evaluated exactly.
    """
    arrs = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (E, R, m, p_y)))
    if arrs[0].size == 0:
        return
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        lE, lR, lm, lp = (np.log10(a) for a in arrs)
        l_ay = lR + 2.0 * (lp - lE + math.log10(math.pi / 2.0))
        l_Py = math.log10(4.0 / 3.0) + lE + 0.5 * lR + 1.5 * l_ay
        l_v2 = math.log10(0.8) + l_Py + l_ay - lm
        worst = np.maximum(np.maximum(np.abs(l_ay), np.abs(l_Py)), np.abs(l_v2))
        suspect = (worst > _EXPONENT_ROOM) & ~np.isinf(arrs[3])
    if not suspect.any():
        return
    from .core.models.thornton_ning_2016 import yield_point

    for i in np.flatnonzero(suspect):
        args = tuple(float(a.flat[i]) for a in arrs)
        try:
            V_y = yield_point(*args)[2]
        except (ZeroDivisionError, OverflowError):
            V_y = math.nan
        if not V_y >= TINY_NORMAL:
            k = max(range(4), key=lambda j: abs(math.log10(args[j])))
            what = "underflows to 0" if V_y == 0.0 else ("is subnormal" if V_y > 0.0 else "is not a number")
            raise ValueError(
                f"{_NAMES[k]} {args[k]!r} is outside what double precision can model with the other inputs "
                f"(effective_modulus {args[0]!r} Pa, effective_radius {args[1]!r} m, effective_mass {args[2]!r} kg, "
                f"limiting_pressure {args[3]!r} Pa): the yield velocity V_y (eq. 28) {what}"
            )


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


# ------------------------------------------------------------------ text that enters a DEM input deck
#
# LAMMPS reads its input one line at a time and, before splitting a line into words, gives five
# characters a meaning of their own (the "Parsing rules" of its manual; LIGGGHTS-PUBLIC keeps
# LAMMPS's parser): a trailing ``&`` joins the next line to this one (before comments are
# stripped, so even a comment line ending in ``&`` swallows the next command), ``#`` starts a
# comment, ``$x``, ``${name}`` and ``$(expression)`` are replaced by a variable's value, and single,
# double and triple quotes make one word of several. A line break starts a new command, which may
# be ``shell`` (any program) or ``include``. So user text in a deck is held to the words the
# command's grammar takes there: IDs, keywords, numbers and ``NULL`` are ASCII letters, digits and
# ``_ . + -``; nothing else is needed for a wall style (``zplane 0.0 NULL``, ``zcylinder 1e-3``,
# ``region ID``, ``primitive type 1 zplane 0.0``, the ``v_name`` of an equal-style variable).

_DEM_WORDS = re.compile(r" *[A-Za-z0-9_.+-]+(?: +[A-Za-z0-9_.+-]+)* *")
_DEM_SPECIAL = "#&$'\""


def check_dem_words(name: str, value) -> str:
    """``value`` if it is one or more DEM input words (ASCII letters, digits, ``_ . + -``, separated by
    spaces), else a ValueError naming ``name`` and the value.

    Refused: line breaks (a new command), ``#`` (a comment), ``&`` (continuation), ``$``
    (substitution), quotes, any other character and the empty text (see the parsing rules above).
    """
    if not isinstance(value, str):
        raise ValueError(f"{name} must be text (DEM input words), got {_describe(value)}")
    if _DEM_WORDS.fullmatch(value) is None:
        raise ValueError(
            f"{name} must be DEM input words (ASCII letters, digits and _ . + - separated by spaces; no line break, "
            f"'#', '&', '$' or quote, which LAMMPS and LIGGGHTS read as a new command, comment, continuation, "
            f"substitution or quoting), got {value!r}"
        )
    return value


def check_dem_lines(lines, source: str) -> list:
    """``lines`` (a list of str) checked as input lines of LAMMPS or LIGGGHTS written by ``source``.

    Each must be one line of printable ASCII; no line may end in ``&``; a command line (not a
    ``#`` comment) may hold none of ``# & $`` or quotes. The last guard before a deck is written:
    user text is checked where it is given (:func:`check_dem_words`), this catches text that reached
    a line another way (a model or parameter name of a hand-built calibration, a face's line).
    """
    out = []
    for line in lines:
        if not isinstance(line, str) or not (line.isascii() and line.isprintable()):
            raise ValueError(f"{source} gave a DEM input line that is not one line of printable ASCII: {line!r}")
        body = line.strip()
        if body.endswith("&"):
            raise ValueError(f"{source} gave a DEM input line ending in '&' (it would swallow the next line): {line!r}")
        if not body.startswith("#") and any(c in body for c in _DEM_SPECIAL):
            raise ValueError(
                f"{source} gave a DEM command line holding one of # & $ ' \" (comment, continuation, "
                f"substitution, quoting): {line!r}"
            )
        out.append(line)
    return out
