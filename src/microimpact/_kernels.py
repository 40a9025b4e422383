"""Fast paths: a fused restitution kernel for large arrays and a scalar path for one impact.

The physics is the same as in :mod:`microimpact.impact` and :mod:`microimpact.dynamics`
(seed eqs. 5-33); only the evaluation differs. Two things are made fast here:

* :func:`restitution_fast`, the restitution coefficient (seed eq. 27) of many
  impacts in one pass over memory. Backends, chosen once at import:

  - ``"numba"`` when `numba <https://numba.pydata.org>`_ is installed
    (``pip install 'microimpact[fast]'``): one fused, multi-threaded loop
    (``parallel=True``, ``fastmath=False``, so IEEE results), compiled on the first
    call and cached by numba (in ``__pycache__`` or its user-wide cache directory);
  - ``"numpy"`` otherwise: the same operations in the same order, evaluated block by
    block in cache-sized buffers so that each element crosses main memory once.

  Both backends give bitwise the same numbers on this machine and agree with
  :func:`microimpact.impact.restitution_coefficient` to 1e-14 relative (they use
  ``sqrt(sqrt(x))`` where that function uses ``x**0.25``). The environment variable
  ``MICROIMPACT_BACKEND=numpy`` (or ``numba``) forces the choice; :data:`BACKEND` says
  which is in use, and ``backend=`` selects one per call.

* :func:`impact_scalar`, the full outcome and contact times of one impact with the
  ``math`` module (and one call of :func:`scipy.special.betainc`), in a few
  microseconds instead of the ~0.4 ms that numpy's per-call overhead costs on
  0-d arrays. Every key agrees with :func:`~microimpact.impact.impact_outcome` and
  :func:`~microimpact.dynamics.contact_times` to 1e-13 relative (in practice bitwise),
  including the limits ``V = 0``, ``V = V_y``, ``V = inf`` and ``p_y = inf``.
"""

from __future__ import annotations

import importlib.util
import math
import os

import numpy as np
from scipy import special

from ._validation import check_positive, check_velocity
from .dynamics import BETA_25_12 as _BETA_25_12
from .impact import LARGE_STRAIN_RATIO

__all__ = ["BACKEND", "available_backends", "restitution_fast", "impact_scalar"]

#: Block length of the numpy backend: three float64 buffers of this length stay in L2 cache.
BLOCK = 16384
#: Iterations each numba thread takes at a time (dynamic scheduling).
_CHUNK = 65536

# e = P^*/(alpha^*^(1/4) v) = _C s / ((1 + s)^(1/4) v) with s = 2 P^*/P_y, _C = 3^(1/4)/2; written
# so that v = 1 gives s = 2 and e = 1 exactly (0.5 * x is exact, so _C * 2 == sqrt(sqrt(3.0))).
_C = 0.5 * math.sqrt(math.sqrt(3.0))
# Above v = 1e8, 6 v^2 - 1 rounds to 6 v^2: s = v 4.8^(1/2) there, which cannot overflow.
_BIG = 1e8
_SQ48 = math.sqrt(4.8)


def available_backends() -> list[str]:
    """Backends :func:`restitution_fast` can use here, fastest first (``"numpy"`` always)."""
    try:
        found = ["numba"] if importlib.util.find_spec("numba") is not None else []
    except (ImportError, ValueError):  # e.g. numba blocked by sys.modules["numba"] = None
        found = []
    return found + ["numpy"]


def _select_backend() -> str:
    forced = os.environ.get("MICROIMPACT_BACKEND", "").strip().lower()
    avail = available_backends()
    if forced:
        if forced not in ("numba", "numpy"):
            raise ValueError(f"MICROIMPACT_BACKEND must be 'numba' or 'numpy', got {forced!r}")
        return forced if forced in avail else "numpy"
    return avail[0]


#: Backend :func:`restitution_fast` uses by default: ``"numba"`` if installed, else ``"numpy"``.
BACKEND: str = _select_backend()

_NUMBA = {}


def _numba_kernels():
    """Compile (once, lazily: importing numba costs ~0.3 s) the fused loops."""
    if not _NUMBA:
        import numba

        @numba.njit(inline="always", fastmath=False, error_model="numpy")
        def _e(x, w):
            # Same operations, same order, as _numpy_block below.
            v = x * w
            if v != v:  # inf * 0 (V = inf, V_y = inf): p_y = inf is elastic at every speed
                v = 0.0
            vp = v if v > 1.0 else 1.0
            big = vp > _BIG
            s = vp * _SQ48 if big else math.sqrt(0.8 * (6.0 * (vp * vp) - 1.0))
            r = math.sqrt(math.sqrt(s + 1.0))
            # e = C s / (r vp); for big vp, s/vp = 4.8^(1/2) exactly enough, and r vp could overflow
            num = _C * _SQ48 if big else _C * s
            den = r if big else r * vp
            return 0.0 if vp == np.inf else num / den

        @numba.njit(parallel=True, fastmath=False, error_model="numpy", cache=True)
        def scalar_vy(V, w, out):
            bad = 0
            for i in numba.prange(V.size):
                x = V[i]
                if not x >= 0.0:
                    bad += 1
                out[i] = _e(x, w)
            return bad

        @numba.njit(parallel=True, fastmath=False, error_model="numpy", cache=True)
        def array_vy(V, Vy, out):
            bad = 0
            for i in numba.prange(V.size):
                x = V[i]
                if not x >= 0.0:
                    bad += 1
                out[i] = _e(x, 1.0 / Vy[i])
            return bad

        _NUMBA["scalar"] = scalar_vy
        _NUMBA["array"] = array_vy
        _NUMBA["chunksize"] = numba.parallel_chunksize
    return _NUMBA


def _numpy_block(V, w, out, t, s, big, inf):
    """Restitution of one block into ``out`` (``w = 1/V_y``); ``t``, ``s``: scratch of the same length.

    ``big``: some ``v`` may exceed :data:`_BIG`; ``inf``: some ``V`` or ``V_y`` is infinite.
    """
    np.multiply(V, w, out=t)  # v = V/V_y
    if inf:
        np.copyto(t, 0.0, where=np.isnan(t))  # inf * 0 (V = inf, V_y = inf): p_y = inf is elastic
    np.maximum(t, 1.0, out=t)  # vp = max(v, 1): the formula gives e = 1 exactly at vp = 1
    np.multiply(t, t, out=s)
    s *= 6.0
    s -= 1.0
    s *= 0.8
    np.sqrt(s, out=s)  # s = 2 P^*/P_y = ((24 v^2 - 4)/5)^(1/2); alpha^*/alpha_y = (1 + s)/3  (eq. 22)
    if big:
        mask = t > _BIG
        np.copyto(s, t * _SQ48, where=mask)
    np.add(s, 1.0, out=out)
    np.sqrt(out, out=out)
    np.sqrt(out, out=out)  # r = (1 + s)^(1/4)
    if big:
        r_big = out[mask]
    out *= t
    if big:
        out[mask] = r_big
        s[mask] = _SQ48
    np.multiply(s, _C, out=s)
    np.divide(s, out, out=out)  # e = P^* / (alpha^*^(1/4) v)  (eq. 27)
    if inf:
        np.copyto(out, 0.0, where=np.isinf(t))


def _restitution_numpy(V, Vy, out):
    n = V.size
    scalar = Vy.size == 1
    w = 1.0 / Vy if scalar else None
    k = min(BLOCK, n)
    t, s = np.empty(k), np.empty(k)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for i in range(0, n, BLOCK):
            j = min(i + BLOCK, n)
            blk = V[i:j]
            lo, hi = blk.min(), blk.max()
            if not lo >= 0.0:  # negative or NaN (min propagates NaN)
                return 1
            m = j - i
            wb = w if scalar else 1.0 / Vy[i:j]
            big = (hi * w > _BIG) if scalar else bool(np.any(blk * wb > _BIG))
            inf = hi == np.inf or (not scalar and bool(np.any(wb == 0.0))) or (scalar and w == 0.0)
            _numpy_block(blk, wb, out[i:j], t[:m], s[:m], big, inf)
    return 0


def restitution_fast(velocity, yield_velocity, out=None, *, backend=None):
    """Restitution coefficient ``e`` of many impacts, fused into one pass (seed eq. 27).

    Same result as :func:`microimpact.impact.restitution_coefficient` (to 1e-14
    relative), several times faster on large arrays: ``e = P^* / (alpha^*^(1/4) v)``
    with ``v = V/V_y``, ``alpha^* = (1 + s)/3``, ``P^* = s/2``, ``s = ((24 v^2 - 4)/5)^(1/2)``
    for ``v > 1``; 1 for ``v <= 1``; 0 for ``V = inf`` (1 if also ``V_y = inf``: no yielding).

    Parameters
    ----------
    velocity : array_like
        Impact speeds ``V`` [m/s], >= 0 (``inf`` allowed).
    yield_velocity : array_like
        ``V_y`` [m/s], > 0 (``inf`` allowed: every finite impact elastic); broadcasts
        against ``velocity``.
    out : ndarray, optional
        float64 array of the broadcast shape to write into (no allocation).
    backend : {"numba", "numpy"}, optional
        Defaults to :data:`BACKEND`.

    Returns
    -------
    ndarray
        ``e`` [-], shaped like the broadcast of the inputs (``out`` if given).

    Raises
    ------
    ValueError
        A negative or NaN speed, or a non-positive/NaN yield velocity (named).

    Examples
    --------
    >>> restitution_fast([1.0, 7.5, 50.0, float("inf")], 7.523).round(4)
    array([1.    , 1.    , 0.7248, 0.    ])
    """
    backend = BACKEND if backend is None else backend
    if backend not in ("numba", "numpy"):
        raise ValueError(f"backend must be 'numba' or 'numpy', got {backend!r}")
    if backend == "numba" and "numba" not in available_backends():
        raise ValueError("backend 'numba' is not available: pip install 'microimpact[fast]'")
    V = np.asarray(velocity)
    if V.dtype != np.float64:
        V = check_velocity("velocity", V)
    Vy = check_positive("yield_velocity", yield_velocity, allow_inf=True)
    shape = np.broadcast_shapes(V.shape, Vy.shape)
    if out is None:
        out = np.empty(shape)
    elif not (isinstance(out, np.ndarray) and out.dtype == np.float64 and out.shape == shape):
        raise ValueError(f"out must be a float64 array of shape {shape}, got {getattr(out, 'shape', out)!r}")
    if V.shape != shape:
        V = np.broadcast_to(V, shape)
    Vflat = np.ascontiguousarray(V).reshape(-1)
    dest = out if out.flags.c_contiguous else np.empty(shape)
    oflat = dest.reshape(-1)
    if Vy.size == 1:
        vy = float(Vy.reshape(-1)[0])
        if backend == "numba":
            kern = _numba_kernels()
            with kern["chunksize"](_CHUNK):  # dynamic scheduling: a busy core does not hold up the other
                bad = kern["scalar"](Vflat, 1.0 / vy, oflat)
        else:
            bad = _restitution_numpy(Vflat, np.float64(vy), oflat)
    else:
        Vyflat = np.ascontiguousarray(np.broadcast_to(Vy, shape)).reshape(-1)
        if backend == "numba":
            kern = _numba_kernels()
            with kern["chunksize"](_CHUNK):
                bad = kern["array"](Vflat, Vyflat, oflat)
        else:
            bad = _restitution_numpy(Vflat, Vyflat, oflat)
    if bad:
        check_velocity("velocity", V)  # raises, naming the first bad value
    if dest is not out:
        out[...] = dest
    return out


# --------------------------------------------------------------------- one impact


def _positive(name, x, allow_inf=False):
    x = float(x)
    if not x > 0.0 or (not allow_inf and math.isinf(x)):
        raise ValueError(
            f"{name} must be positive, got {x!r}" if allow_inf else f"{name} must be positive and finite, got {x!r}"
        )
    return x


def _pow(x, y):
    """``x**y`` that overflows to ``inf`` like numpy instead of raising."""
    try:
        return x**y
    except OverflowError:
        return math.inf


def impact_scalar(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure) -> dict:
    """Outcome and contact times of one impact, with plain floats (seed eqs. 5-33).

    The scalar twin of :func:`microimpact.impact.impact_outcome` followed by
    :func:`microimpact.dynamics.contact_times`: the same formulas in the same order,
    written with :mod:`math`, so one impact costs microseconds. The keys are those
    two functions' keys; values are Python floats (``elastic`` and ``large_strain``
    are bools).

    Parameters
    ----------
    velocity : float
        Impact speed ``V`` [m/s], >= 0 (``inf`` allowed).
    effective_modulus, effective_radius, effective_mass : float
        ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], positive and finite.
    limiting_pressure : float
        ``p_y`` [Pa], positive (``inf``: elastic impact).

    Returns
    -------
    dict
        ``velocity, yield_velocity, normalized_velocity, elastic, restitution,
        rebound_velocity, max_approach, plastic_approach, max_force, unloading_radius,
        energy_loss, max_contact_radius, large_strain, elastic_stage_time,
        plastic_stage_time, loading_time, unloading_time, contact_time``.

    Examples
    --------
    >>> m = 4 / 3 * math.pi * 2.45e-6**3 * 1350
    >>> out = impact_scalar(50.0, 1.31e9, 2.45e-6, m, 156e6)
    >>> round(out["rebound_velocity"], 2), round(out["contact_time"] * 1e9, 3)  # m/s, ns
    (36.24, 24.761)
    """
    V = float(velocity)
    if not V >= 0.0:
        raise ValueError(f"velocity must be non-negative and not NaN, got {V!r}")
    E = _positive("effective_modulus", effective_modulus)
    R = _positive("effective_radius", effective_radius)
    m = _positive("effective_mass", effective_mass)
    p_y = _positive("limiting_pressure", limiting_pressure, allow_inf=True)
    inf = math.inf
    sqR = math.sqrt(R)

    # Yield point (eqs. 4, 5, 7) and yield velocity (eq. 28, energy form).
    if p_y == inf:
        a_y = P_y = Vy = inf
    else:
        ac = math.pi * p_y * R / (2.0 * E)
        a_y = ac * ac / R
        P_y = 4.0 / 3.0 * E * sqR * _pow(a_y, 1.5)
        Vy = math.sqrt(0.8 * P_y * a_y / m)
    v = 0.0 if Vy == inf else V / Vy
    elastic = v <= 1.0
    infinite = v == inf

    # Time scale alpha_m / V of the Hertz stages (eq. 30 family).
    ts = (15.0 * m / (16.0 * E * sqR)) ** 0.4 * (V ** (-0.2) if V > 0.0 else inf)

    if elastic:
        alpha_m = (15.0 * m * (V * V) / (16.0 * E * sqR)) ** 0.4
        e = 1.0
        max_approach = alpha_m
        max_force = 4.0 / 3.0 * E * sqR * _pow(alpha_m, 1.5)
        plastic = 0.0
        R_p = R
    elif infinite:
        e = 0.0
        max_approach = max_force = plastic = R_p = inf
    else:
        q = math.sqrt((24.0 - 4.0 / (v * v)) / 5.0)  # s/v, with s = ((24 v^2 - 4)/5)^(1/2)
        A = (1.0 + v * q) / 3.0  # eq. 22
        Phat = 0.5 * v * q  # eq. 14 at alpha^*
        sqA = math.sqrt(A)
        e = 0.5 * q / math.sqrt(sqA)  # eq. 27, P^*/(alpha^*^(1/4) v) with the v cancelled
        max_approach = a_y * A
        max_force = P_y * Phat
        plastic = a_y * max(A - Phat / sqA, 0.0)  # eq. 11
        R_p = R * A * sqA / Phat  # eq. 9
    rebound = inf if infinite else e * V
    a_max = math.sqrt(R * max_approach)

    # Contact times (eqs. 20, 23, 26, 32, 33).
    if V == inf:
        t1 = 0.0
    else:
        u = (Vy / V) ** 2 if V > Vy else 1.0
        t1 = 0.4 * ts * (float(special.betainc(0.4, 0.5, u)) * _BETA_25_12)
    if V > Vy:
        omega = math.sqrt(math.pi * p_y * R / m)
        v1 = math.sqrt(max(V * V - Vy * Vy, 0.0))
        t2 = math.atan2(v1, 2.0 * omega * a_y / 3.0) / omega
    else:
        t2 = 0.0
    if V == inf:
        tU = 0.0
    elif elastic:
        tU = 0.4 * _BETA_25_12 * ts
    else:
        tU = 0.4 * _BETA_25_12 * (max_approach - plastic) / rebound
    tL = t1 + t2
    return {
        "velocity": V,
        "yield_velocity": Vy,
        "normalized_velocity": v,
        "elastic": elastic,
        "restitution": e,
        "rebound_velocity": rebound,
        "max_approach": max_approach,
        "plastic_approach": plastic,
        "max_force": max_force,
        "unloading_radius": R_p,
        "energy_loss": 1.0 - e * e,
        "max_contact_radius": a_max,
        "large_strain": a_max / R > LARGE_STRAIN_RATIO,
        "elastic_stage_time": t1,
        "plastic_stage_time": t2,
        "loading_time": tL,
        "unloading_time": tU,
        "contact_time": tL + tU,
    }
