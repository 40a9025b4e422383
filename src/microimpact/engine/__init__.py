"""How a core function runs over an array: one scalar source, a Python loop or a compiled one.

:func:`evaluate` applies a scalar core function element by element over broadcast arrays. Two
engines give bitwise the same numbers, because both run the very same source:

* ``"python"``: a loop over the scalar function itself. Used for small arrays (below
  :data:`SMALL`) while numba is not imported in the process (importing it costs about 0.35 s, the
  loop 1-3 us per element), unless one element, timed, shows that the loop would take longer than
  :data:`PYTHON_BUDGET` (a model that integrates its equation of motion: ~1 ms per element), or
  that the Python loops over the function in this process would together pass it (many small
  calls: rent until the rent has paid the price of buying, then buy); and whenever
  ``MICROIMPACT_BACKEND=python``.
* ``"numba"``: a loop generated once per function as a small Python file in the cache folder and
  compiled by numba with ``cache=True``, so a new process loads machine code instead of compiling
  (:mod:`microimpact.engine.loops`). Every ``@jitable`` function of the core is registered with
  numba first (:mod:`microimpact.engine.registry`), so the compiled loop calls the same functions;
  the function itself is inlined into the loop, so that what depends on the pair alone is computed
  once per array. Large arrays get a multi-threaded loop (``prange``), small ones a serial one,
  which is faster there: threads are used from :data:`PARALLEL_MIN` elements, or earlier once a
  serial call has shown that the array's work (elements times the measured time per element)
  exceeds :data:`PARALLEL_WORK`, several times what starting the threads costs. The choice never
  changes a result (both loops run the same function on each element).

The on-disk cache (:mod:`microimpact.engine.cache`) only saves time: a folder that cannot be
written, or whose files another user could have written, is not used (one :class:`CacheWarning`),
and the loops are compiled in memory instead.

This is the fluids idea (one scalar source per formula, fast dialects generated from it) with
poliastro's split (compiled core on floats; wrappers only convert and call).
"""

from __future__ import annotations

import itertools
import math
import os
import sys
import time
from typing import TYPE_CHECKING

import numpy as np

from ..core._jit import JITABLE
from . import cache as _cache
from .cache import CacheWarning

if TYPE_CHECKING:  # pathlib loads where used: one impact on the command line needs none of it
    from pathlib import Path

__all__ = [
    "evaluate",
    "backend_for",
    "BACKENDS",
    "SMALL",
    "PARALLEL_MIN",
    "PARALLEL_WORK",
    "PYTHON_BUDGET",
    "cache_dir",
    "cache_info",
    "clear_cache",
    "CacheWarning",
    "registered",
]

#: Engines :func:`evaluate` can use.
BACKENDS = ("numba", "python")
#: Below this many elements, while numba is not imported in the process, the Python loop is used.
SMALL = 4096
#: From this many elements on, the compiled loop runs on all cores.
PARALLEL_MIN = 50_000
#: Estimated time [s] of Python loops over small arrays of one function beyond which it is
#: compiled instead: one call's, or all the calls' in this process together (importing numba and
#: loading a cached loop costs about 0.4 s).
PYTHON_BUDGET = 0.25
#: Estimated work [s] of one array from which threads are used below PARALLEL_MIN (never below 2048).
PARALLEL_WORK = 2e-4
_PY_COST: dict = {}  # measured time of one Python call [s] of each function
_PY_SPENT: dict = {}  # estimated time [s] this process has spent on each function in Python loops
_JITABLE_SET: set = set()  # JITABLE's functions as evaluate has met them (JITABLE is a list, in order)


def _forced() -> str:
    """The engine ``MICROIMPACT_BACKEND`` forces ("" for none); read on every call (it may change)."""
    forced = os.environ.get("MICROIMPACT_BACKEND")
    if not forced:
        return ""
    forced = forced.strip().lower()
    if forced and forced not in BACKENDS:
        raise ValueError(f"MICROIMPACT_BACKEND must be one of {', '.join(BACKENDS)}; got {forced!r}")
    return forced


def backend_for(n: int) -> str:
    """The engine :func:`evaluate` takes for ``n`` elements (see the module docstring)."""
    return _forced() or _unforced_engine(n)


def _unforced_engine(n: int) -> str:
    """The engine for ``n`` elements when ``MICROIMPACT_BACKEND`` does not force one."""
    return "numba" if (n >= SMALL or "numba" in sys.modules) else "python"


def cache_dir() -> Path:
    """Where the generated loops (and numba's compiled code beside them) are kept.

    ``MICROIMPACT_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/microimpact``, else
    ``~/.cache/microimpact``.
    """
    return _cache.cache_dir()


def registered() -> list:
    """The ``@jitable`` functions the compiled loops may call (for the documentation and tests)."""
    return list(JITABLE)


def _shape(arrays):
    """The broadcast shape of ``arrays``; scalars (Python or numpy floats) add nothing to it."""
    shapes = [a.shape for a in arrays if not isinstance(a, _SCALARS)]
    if not shapes:
        return ()
    return shapes[0] if len(shapes) == 1 else np.broadcast_shapes(*shapes)


#: Scalars :func:`evaluate` takes as they are (``np.float64`` is a ``float``): asking a numpy scalar
#: for ``size``, ``strides`` or ``flat`` builds an array each time.
_SCALARS = (float, np.floating)
_F64 = np.dtype(np.float64)  # native float64 arrays share this descriptor: "is" before "=="
_NP_F64 = np.float64
_USUAL: dict = {}  # number of arguments -> (steps, kinds) of the usual call (evaluate)


def _flat(arrays, shape):
    """Each array as a float over ``shape`` (step 0: one value, or one broadcast to many) or a 1-D
    float64 view (or copy) of it (step 1), with the steps and their kinds (``"s"`` per step 0,
    ``"a"`` per step 1: the compiled loop's signature)."""
    n = math.prod(shape)
    flats, steps, kinds = [], [], ""
    for a in arrays:
        if isinstance(a, _SCALARS):
            flats.append(float(a))
            steps.append(0)
            kinds += "s"
        elif a.size == 1 or (a.size > 1 and not any(a.strides)):  # one value, or one broadcast to many
            flats.append(float(np.array([a.flat[0]], dtype=np.float64)[0]))
            steps.append(0)
            kinds += "s"
        elif a.ndim == 1 and a.shape == shape and (a.dtype is _F64 or a.dtype == _F64):
            flats.append(a)  # a column of a table, say: the loop reads it in place, strided
            steps.append(1)
            kinds += "a"
        else:
            b = np.broadcast_to(a, shape) if a.shape != shape else a
            flats.append(np.ascontiguousarray(b, dtype=np.float64).reshape(n))
            steps.append(1)
            kinds += "a"
    return n, flats, steps, kinds


def _jitable(fn) -> bool:
    """``fn in JITABLE`` (a scan of the list), remembered in a set when true (a look-up next time)."""
    if fn in JITABLE:
        _JITABLE_SET.add(fn)
        return True
    return False


def _loops(fn, kinds, nout, with_params):
    from . import loops  # numba's side: not loaded by a process that never compiles

    return loops.loops(fn, kinds, nout, with_params)


_LOOPS: dict = {}  # (fn, kinds, nout, with params) -> (serial, parallel), once built


def evaluate(fn, *arrays, nout: int = 1, params=None, backend: str | None = None, out=None) -> np.ndarray:
    """Apply the scalar core function ``fn`` element by element over broadcast float arrays.

    Parameters
    ----------
    fn : callable
        A ``@jitable`` core function of ``len(arrays)`` floats (then ``params`` if given) returning a
        float (``nout = 1``) or a tuple of ``nout`` floats.
    *arrays : ndarray
        float64 inputs, already checked by the caller; they broadcast against each other.
    nout : int
        Number of results of ``fn``.
    params : tuple of float, optional
        Passed unchanged as ``fn``'s last argument (a model's own parameters).
    backend : {"numba", "python"}, optional
        Default: :func:`backend_for` the number of elements.
    out : ndarray, optional
        Where to write the results: float64 of shape ``(nout,) + broadcast shape`` (for ``nout = 1``
        also the broadcast shape itself), C-contiguous unless it is 2-D ``(nout, n)`` (then any
        strides: ``buf.T`` of an ``(n, nout)`` table fills its rows). Saves allocating (and first
        touching) the result; returned, reshaped as without it.

    Returns
    -------
    ndarray
        Shape ``(nout,) + broadcast shape``, float64.
    """
    first = arrays[0] if arrays else None
    usual = type(first) is np.ndarray and first.ndim == 1 and first.dtype is _F64 and first.size > 1
    if usual:  # the usual call: speeds as a 1-D float64 array (not a broadcast one), the rest floats
        for a in arrays[1:]:
            if type(a) is not float and type(a) is not _NP_F64:  # float64 scalars are typed as floats
                usual = False
                break
        usual = usual and first.strides[0] != 0
    if usual:
        shape = first.shape
        n, flats = first.size, [*arrays]
        steps, kinds = _USUAL.get(len(arrays)) or _USUAL.setdefault(
            len(arrays), ((1,) + (0,) * (len(arrays) - 1), "a" + "s" * (len(arrays) - 1))
        )
    else:  # the general case, which gives the same for the usual call
        shape = _shape(arrays)
        n, flats, steps, kinds = _flat(arrays, shape)
    if out is None:
        out = np.empty((nout, n))
    else:
        if not (
            isinstance(out, np.ndarray)
            and out.dtype == np.float64
            and (out.flags.c_contiguous or out.shape == (nout, n))
            and out.flags.writeable
            and out.shape in ((nout,) + shape, shape if nout == 1 else None)
        ):
            raise ValueError(
                f"out must be a writeable C-contiguous float64 array of shape {(nout,) + shape}, "
                f"got {getattr(out, 'dtype', type(out).__name__)} of shape {getattr(out, 'shape', None)}"
            )
        if out.shape != (nout, n):
            out = out.reshape(nout, n)  # a view: out is C-contiguous here
    if n == 0:
        return out.reshape((nout,) + shape)
    # a function not marked @jitable (a user's model, say) can only run in Python
    if backend:
        engine = backend
    elif fn not in _JITABLE_SET and not _jitable(fn):
        engine = "python"
    else:
        forced = _forced()
        engine = forced or _unforced_engine(n)  # backend_for(n), reading the environment once
        if engine == "python" and not forced and n > 8:
            # A small array in Python only pays while the function is cheap: time one element once
            # per function (the same numbers either way) and compile when the loop would take longer,
            # or when this process has already spent that long on the function in Python (many small
            # calls: a script's loop over 1e3 speeds goes compiled after ~0.25 s, not never).
            cost = _PY_COST.get(fn)
            if cost is None:
                t0 = time.perf_counter()
                fn(
                    *(f if s == 0 else float(f[0]) for f, s in zip(flats, steps)),
                    *((tuple(params),) if params is not None else ()),
                )
                cost = _PY_COST[fn] = time.perf_counter() - t0
            spent = _PY_SPENT.get(fn, 0.0) + cost * n
            if spent > PYTHON_BUDGET:
                engine = "numba"
            else:
                _PY_SPENT[fn] = spent
    with_params = params is not None
    if engine == "numba":
        key = (fn, kinds, nout, with_params)
        pair = _LOOPS.get(key)
        if pair is None:
            pair = _LOOPS[key] = _loops(fn, kinds, nout, with_params)
        serial = pair[0]
        cost = serial.cost
        if n >= PARALLEL_MIN or (cost is not None and n >= 2048 and n * cost >= PARALLEL_WORK):
            loop = pair[1]
        else:
            loop = serial
        args = (*flats, tuple(params), out) if with_params else (*flats, out)
        if not loop.ready:
            loop.prepare(args)
        if cost is None and loop is serial and n >= 256:  # time it once, on a call big enough to tell
            t0 = time.perf_counter()
            serial.run(n, *args)
            serial.cost = (time.perf_counter() - t0) / n
        else:
            loop.run(n, *args)
    elif engine == "python":
        cols = [itertools.repeat(f, n) if s == 0 else f.tolist() for f, s in zip(flats, steps)]
        if with_params:
            p = tuple(params)
            res = [fn(*xs, p) for xs in zip(*cols)]
        else:
            res = [fn(*xs) for xs in zip(*cols)]
        out[...] = np.array(res, dtype=np.float64).reshape(n, nout).T if nout > 1 else np.array(res, dtype=np.float64)
    else:
        raise ValueError(f"backend must be one of {', '.join(BACKENDS)}; got {engine!r}")
    return out if len(shape) == 1 else out.reshape((nout,) + shape)  # out is (nout, n) here


def _owned_files() -> list:
    from . import loops

    return loops.owned_files(cache_dir())


def cache_info() -> dict:
    """What the compiled-loop cache holds: ``folder``, ``files``, ``bytes``, ``writable``.

    Only the files the engine made there are counted (:func:`clear_cache` deletes just these); the
    tables and calibrations beside them are counted by :func:`microimpact.cache.cache_info`.
    """
    folder = cache_dir()
    files = _owned_files()
    size = _cache.total_bytes(files)
    probe = folder if folder.exists() else next((p for p in folder.parents if p.exists()), folder)
    return {"folder": str(folder), "files": len(files), "bytes": size, "writable": os.access(probe, os.W_OK)}


def clear_cache() -> int:
    """Delete the compiled-loop cache's own files (generated loops, numba's entries for them); returns
    how many.

    Nothing else in the folder is touched: a file is the cache's when it is a loop file whose first
    line is the engine's generated-file mark, or numba's index/data file or the lock named after
    such a loop. The compiled loops already loaded in this process stay usable.
    """
    folder = cache_dir()
    n = 0
    for p in _owned_files():
        try:
            p.unlink()
            n += 1
        except FileNotFoundError:
            pass
    for d in (folder / "kernels" / "__pycache__", folder / "kernels" / "native", folder / "kernels"):
        try:
            d.rmdir()  # only when empty
        except OSError:
            pass
    return n
