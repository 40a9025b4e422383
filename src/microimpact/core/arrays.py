"""Array versions of the core's scalar functions, derived from them (never retyped).

:func:`evaluate` applies a scalar core function element by element over broadcast arrays. Two
engines give bitwise the same numbers, because both run the very same source:

* ``"python"``: a loop over the scalar function itself. Used for small arrays while no compiled
  loop is loaded in this process (numba not imported, no kept machine code run: importing numba
  costs ~0.35 s here, loading kept code ~0.1 s, the loop ~1-3 us per element),
  unless one element, timed, shows that the loop would take longer than :data:`PYTHON_BUDGET`
  (a model that integrates its equation of motion: ~1 ms per element), or that the Python loops
  over the function in this process would together pass it (many small calls: rent until the rent
  has paid the price of buying, then buy); and whenever ``MICROIMPACT_BACKEND=python``.
* ``"numba"``: a loop generated once per function as a small Python file in a cache directory,
  compiled by numba with ``cache=True`` (so a new process loads machine code instead of compiling);
  every ``@jitable`` function of the core is registered with
  numba first (:func:`~microimpact.core._jit.register_all`), so the compiled loop calls the same
  functions; the function itself is inlined into the loop, so that what depends on the pair alone
  is computed once per array.
  The file's name carries a hash of the core's sources and numba's version: editing a formula can
  never leave a stale compiled loop. Large arrays get a multi-threaded loop (``prange``), small
  ones a serial one, which is faster there: threads are used from :data:`PARALLEL_MIN` elements,
  or earlier once a serial call has shown that the array's work (elements times the measured time
  per element) exceeds :data:`PARALLEL_WORK`, several times what starting the threads costs. The
  choice never changes a result (both loops run the same function on each element).
  The loops are in fact compiled by numba as C-callable functions whose machine code is kept in
  the cache (:mod:`microimpact.core._native`): a new process runs that with llvmlite alone,
  without numba's start-up (~0.5 s beyond its import); numba's own loops (and numba's cache)
  serve the calls those cannot take.

This is the fluids idea (one scalar source per formula, fast dialects generated from it) with
poliastro's split (compiled core on floats; wrappers only convert and call).
"""

from __future__ import annotations

import functools
import itertools
import math
import os
import sys
import threading
import time
from typing import TYPE_CHECKING

import numpy as np

from . import _defer
from . import cache as _cache
from ._jit import JITABLE

if TYPE_CHECKING:  # hashlib and pathlib load where used: one impact on the command line needs neither
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
]

#: Engines :func:`evaluate` can use.
BACKENDS = ("numba", "python")
#: Below this many elements, while no compiled loop is loaded (numba not imported, no kept machine
#: code run: core._native), the Python loop is used.
SMALL = 4096
#: From this many elements on, the compiled loop runs on all cores.
PARALLEL_MIN = 50_000
#: Estimated time [s] of Python loops over small arrays of one function beyond which it is
#: compiled instead: one call's, or all the calls' in this process together (loading kept machine
#: code costs about 0.1 s, importing numba and loading its cached loop about 0.4 s).
PYTHON_BUDGET = 0.25
#: Estimated work [s] of one array from which threads are used below PARALLEL_MIN (never below 2048).
PARALLEL_WORK = 2e-4
_COST: dict = {}  # measured serial time per element [s] of each compiled loop
_PY_COST: dict = {}  # measured time of one Python call [s] of each function
_PY_SPENT: dict = {}  # estimated time [s] this process has spent on each function in Python loops

_KERNELS: dict = {}
_JITABLE_SET: set = set()  # JITABLE's functions as evaluate has met them (JITABLE is a list, in order)
_READY: set = set()  # compiled loops called once already in this process (loaded or compiled)
#: ``fn`` -> ``((number of inputs, nout, with params), run(n, inputs, params) -> out, kept)``: the
#: serial loop :func:`evaluate`'s usual call on fewer than 2048 elements has reached once, ready and
#: timed; ``kept`` is that loop where it is kept machine code of one result
#: (:class:`~microimpact.core._native.NativeLoop`, whose ufunc answers :func:`on_speeds`), else None.
#: Such a call can then only go there (the engine is "numba" once a loop is ready, threads start at
#: 2048 elements), so the next ones skip the way to it (1 us of a call on 1e3 speeds, issue 25).
_LANES: dict = {}
_LOCK_NAMES: dict = {}  # compiled loop -> (folder, name) of its file lock
_LOCK = threading.Lock()  # dask evaluates blocks in threads: one thread builds a loop, the others wait


try:  # os.environ's own key for the variable (bytes on POSIX): read below without encoding it each call
    _BACKEND_KEY = os.environ.encodekey("MICROIMPACT_BACKEND")
except AttributeError:  # pragma: no cover - an os.environ without it
    _BACKEND_KEY = None


def _forced() -> str:
    # Every array call asks (the variable may be set or unset at any time). os.environ.get encodes
    # the name, looks it up and decodes the value: about 1 us, a fifth of what a call on 1e3 speeds
    # may add to its loop (issue 25). The mapping os.environ keeps (and updates when it is set or
    # deleted) answers the usual "unset" in 0.07 us; os.environ.get stays the route everywhere else.
    try:
        if not os.environ._data.get(_BACKEND_KEY):
            return ""
    except (AttributeError, TypeError):  # pragma: no cover - os.environ replaced by a plain mapping
        pass
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


#: core._native's LOADED (true once a kept loop is loaded) from the first loop built on; empty before:
#: _native loads with the first loop (its hashlib, json and pathlib cost a command that never compiles).
_NATIVE_LOADED: list | tuple = ()


def _unforced_engine(n: int) -> str:
    """The engine for ``n`` elements when ``MICROIMPACT_BACKEND`` does not force one."""
    return "numba" if (n >= SMALL or "numba" in sys.modules or _NATIVE_LOADED) else "python"


def cache_dir() -> Path:
    """Where the generated loops (and numba's compiled code beside them) are kept.

    ``MICROIMPACT_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/microimpact`` (``~/.cache/microimpact``),
    else a folder in the temporary directory when the home folder cannot be written.
    """
    return _cache.cache_dir()


@functools.lru_cache(maxsize=1)
def _source_hash() -> str:
    import hashlib

    import numba

    h = hashlib.sha256(_cache.core_hash().encode())
    h.update(numba.__version__.encode())
    h.update(sys.version.encode())
    return h.hexdigest()[:16]


def _outside_hash(fn) -> str:
    """Hash of the file of ``fn`` when it lies outside the core (a model added with
    :func:`microimpact.models.register_path`): editing it must not reuse a loop compiled from the
    old source, as the core's own hash guarantees for the core."""
    import hashlib
    import inspect
    from pathlib import Path

    try:
        path = Path(inspect.getsourcefile(fn)).resolve()
        if Path(__file__).resolve().parent in path.parents:
            return ""
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except (TypeError, OSError):
        return ""


_TEMPLATE = '''"""Generated by microimpact.core.arrays from {module}.{name}: do not edit (it is regenerated)."""
import numba

from microimpact.core import _jit
from {module} import {name} as _fn

_jit.register_all()
# The function itself is inlined into the loop (numba's inline="always"): only then does the
# compiler see that what depends on the pair alone (a yield point) is the same for every element,
# and compute it once. Functions with a loop of their own are called instead.
_top = _fn if _jit.has_loop(_fn) else numba.njit(inline="always", error_model="numpy")(_jit.for_numba(_fn))


@numba.njit(cache=True, nogil=True, error_model="numpy")
def serial(n, {args}, params, out):
    for i in range(n):
        r = _top({calls}{params_arg})
{stores}


@numba.njit(parallel=True, cache=True, nogil=True, error_model="numpy")
def parallel(n, {args}, params, out):
    for i in numba.prange(n):
        r = _top({calls}{params_arg})
{stores}
'''


def _generate(fn, kinds: str, nout: int, with_params: bool) -> str:
    """Source of the loops over ``fn``; ``kinds`` has ``"a"`` (array) or ``"s"`` (scalar) per argument.

    A scalar argument is passed as a float, so the compiler hoists it out of the loop and can
    vectorise the loop; arrays are indexed directly.
    """
    args = ", ".join(f"a{k}" for k in range(len(kinds)))
    calls = ", ".join(f"a{k}[i]" if c == "a" else f"a{k}" for k, c in enumerate(kinds))
    if nout == 1:
        stores = "        out[0, i] = r"
    else:
        stores = "\n".join(f"        out[{j}, i] = r[{j}]" for j in range(nout))
    return _TEMPLATE.format(
        module=fn.__module__,
        name=fn.__name__,
        args=args,
        calls=calls,
        params_arg=", params" if with_params else "",
        stores=stores,
    )


def _write_atomic(path: Path, text: str) -> None:
    """Write a generated loop file atomically (:func:`microimpact.core.cache.write_atomic`; one seam for tests)."""
    _cache.write_atomic(path, text.encode())


def _kernels(fn, kinds: str, nout: int, with_params: bool):
    key = (fn, kinds, nout, with_params)
    found = _KERNELS.get(key)
    if found is not None:
        return found
    with _LOCK:
        found = _KERNELS.get(key)
        if found is None:
            with _defer.section():  # imports numba (llvmlite) and defines the loops
                found = _KERNELS[key] = _build(fn, kinds, nout, with_params)
    return found


class CacheWarning(RuntimeWarning):
    """The compiled-kernel cache could not be used; the computation ran without it (the message names the folder)."""


#: First line of every loop file microimpact generates (how :func:`clear_cache` knows its own files).
_MARK = '"""Generated by microimpact.core.arrays'


_WARNED: set = set()


def _warn_cache(folder, what) -> None:
    """One warning per folder and kind of trouble in a process."""
    import warnings

    key = (str(folder), what.split(" (")[0])
    if key in _WARNED:
        return
    _WARNED.add(key)

    warnings.warn(
        f"kernel cache {folder}: {what} (the cache only saves compile time: 'microimpact cache --info'; "
        "MICROIMPACT_CACHE_DIR moves it)",
        CacheWarning,
        stacklevel=4,
    )


def _reason(exc) -> str:
    text = getattr(exc, "strerror", None) or (str(exc).splitlines() or [""])[0]
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def _build(fn, kinds: str, nout: int, with_params: bool):
    """The loops over ``fn``: its machine code kept by :mod:`~microimpact.core._native` (loaded
    without numba's start-up, or compiled by numba and kept on the first call); numba's own loops
    where that cannot be (another object format, a version that cannot be told) and for the calls
    the kept loop cannot take."""
    global _NATIVE_LOADED
    from . import _native  # hashlib, json, pathlib: not for a command that never compiles

    _NATIVE_LOADED = _native.LOADED
    text = _generate(fn, kinds, nout, with_params)
    entry = _native.entry_path(fn, kinds, nout, with_params, text, _outside_hash(fn))
    if entry is None:
        return _numba_loops(fn, kinds, nout, with_params)

    def numba_loops():
        return _through_call(*_numba_loops(fn, kinds, nout, with_params))

    loops = _native.load(entry, kinds, nout, numba_loops)
    if loops is None:
        loops = _native.pending(
            entry, fn, kinds, nout, with_params, numba_loops, lambda what: _warn_cache(_native.folder(), what)
        )
    return loops


def _through_call(serial, parallel):
    """numba's loops, called through :func:`_call` (its lock and cache healing on a first call)."""
    return (
        lambda n, *rest: _call(serial, n, rest[:-2], rest[-2], rest[-1]),
        lambda n, *rest: _call(parallel, n, rest[:-2], rest[-2], rest[-1]),
    )


def _numba_loops(fn, kinds: str, nout: int, with_params: bool):
    import hashlib

    import numba  # noqa: F401  (the first compiled call pays for this import, once per process)

    text = _generate(fn, kinds, nout, with_params)
    tag = hashlib.sha256((_source_hash() + _outside_hash(fn) + text).encode()).hexdigest()[:16]
    stem = f"{fn.__module__.replace('.', '_')}__{fn.__name__}_{kinds}_{tag}"
    # numba's cache finds the module again by name when it loads the compiled code.
    name = f"_microimpact_kernel_{stem}"
    module = sys.modules.get(name)
    if module is not None:
        return module.serial, module.parallel
    folder = cache_dir() / "kernels"
    path = folder / f"{stem}.py"
    try:
        try:
            same = path.read_text() == text
        except (OSError, UnicodeDecodeError):
            same = False
        if not same:
            _write_atomic(path, text)
        module = _load_module(name, path, text, cache=True)
        _LOCK_NAMES[module.serial] = _LOCK_NAMES[module.parallel] = (folder, stem)
    except Exception as exc:  # a read-only or full cache folder, numba unable to cache there: compile in memory
        _warn_cache(folder, f"cannot be used ({_reason(exc)}); compiling in memory")
        module = _load_module(name, None, text, cache=False)
    return module.serial, module.parallel


def _load_module(name, path, text, *, cache):
    import importlib.util
    import types

    if cache:
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)  # numba raises RuntimeError "cannot cache function" here
        except BaseException:
            sys.modules.pop(name, None)
            raise
        return module
    module = types.ModuleType(name)
    module.__file__ = f"<microimpact kernel {name}>"
    sys.modules[name] = module
    exec(compile(text.replace("cache=True", "cache=False"), module.__file__, "exec"), module.__dict__)
    return module


def _cache_files(dispatcher):
    """``(folder, [paths])``: the index and data files numba keeps for ``dispatcher`` (empty if none)."""
    cache = getattr(dispatcher, "_cache", None)
    cfile = getattr(cache, "_cache_file", None)
    folder = getattr(cfile, "_cache_path", None)
    index = getattr(cfile, "_index_name", None)
    if folder is None or index is None:
        return folder, []
    base = index[: -len(".nbi")]
    try:
        names = os.listdir(folder)
    except OSError:
        return folder, []
    return folder, [
        os.path.join(folder, n) for n in names if n == index or (n.startswith(base + ".") and n.endswith(".nbc"))
    ]


def _heal_call(dispatcher, *args):
    """Call a compiled loop; on its first call, heal what its cache entry breaks.

    A corrupt entry (a truncated index: ``EOFError``, ``UnpicklingError``) is deleted and the
    loop compiled again (a new entry is saved); a cache that cannot be written (a full or
    read-only file system) is switched off for this process and the loop compiled in memory.
    Each with one warning naming the folder. A loop that fails again without its cache raises.
    """
    if dispatcher.signatures:
        return dispatcher(*args)
    try:
        return dispatcher(*args)
    except Exception as first:
        folder, files = _cache_files(dispatcher)
        if folder is None or not (files or isinstance(first, OSError)):
            raise  # not the cache's doing
        if not isinstance(first, OSError) and files:
            for f in files:
                try:
                    os.unlink(f)
                except OSError:
                    pass
            _warn_cache(folder, f"a corrupt entry ({_reason(first)}) was deleted and is rebuilt")
            try:
                return dispatcher(*args)
            except Exception as again:
                first = again
        from numba.core.caching import NullCache

        dispatcher._cache = NullCache()
        if isinstance(first, OSError):
            _warn_cache(folder, f"cannot be written ({_reason(first)}); compiling in memory")
        return dispatcher(*args)


def _call(kernel, n, inputs, params, out):
    """Run a compiled loop; its first call in this process holds the loop's file lock.

    That first call compiles the loop or loads it from numba's cache: processes started together
    on an empty cache so compile it once, the others wait and then load it (:func:`~.cache.locked`).
    """
    if kernel not in _READY:  # a set look-up: kernel.signatures builds a list of them (1.7 us a call)
        if not kernel.signatures:
            # compiled (or loaded) by a call over no element, in a section a signal does not cut
            # (core._defer: an interrupt inside numba's compiler leaves llvmlite objects half built)
            folder, stem = _LOCK_NAMES.get(kernel, (None, None))
            with _defer.section():
                if folder is None:  # compiled in memory (the cache folder could not be used)
                    _heal_call(kernel, 0, *inputs, params, out)
                else:
                    with _cache.locked(folder, stem):
                        _heal_call(kernel, 0, *inputs, params, out)
        _READY.add(kernel)
    kernel(n, *inputs, params, out)


def _shape(arrays):
    """The broadcast shape of ``arrays``; scalars (Python or numpy floats) add nothing to it."""
    shapes = [a.shape for a in arrays if not isinstance(a, _SCALARS)]
    if not shapes:
        return ()
    return shapes[0] if len(shapes) == 1 else np.broadcast_shapes(*shapes)


#: Scalars :func:`evaluate` takes as they are (``np.float64`` is a ``float``): asking a numpy scalar
#: for ``size``, ``strides`` or ``flat`` builds an array each time (5 us per call of 1e3 speeds).
_SCALARS = (float, np.floating)
_F64 = np.dtype(np.float64)  # native float64 arrays share this descriptor: "is" before "==" (0.15 us)
_NP_F64 = np.float64
_USUAL: dict = {}  # number of arguments -> (steps, kinds) of the usual call (evaluate)


def _flat(arrays, shape):
    """Each array as a float over ``shape`` (step 0: one value, or one broadcast to many) or a 1-D
    float64 view (or copy) of it (step 1), with the steps and their kinds (``"s"`` per step 0,
    ``"a"`` per step 1: the compiled loop's signature)."""
    n = math.prod(shape)  # Python ints: np.prod cost 5 us a call
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
        if usual and out is None and backend is None:  # the lane, once the loop is known (_LANES)
            lane = _LANES.get(fn)
            if lane is not None and lane[0] == (len(arrays), nout, params is not None):
                if first.shape[0] < 2048 and not _forced():
                    return lane[1](first.shape[0], arrays, () if params is None else tuple(params))
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
        quick = usual  # evaluate's own out, the speeds a 1-D float64 array, the rest floats
    else:
        quick = False
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
        serial, parallel = _kernels(fn, kinds, nout, with_params)
        cost = _COST.get(serial)
        threads = n >= PARALLEL_MIN or (cost is not None and n >= 2048 and n * cost >= PARALLEL_WORK)
        p = tuple(params) if with_params else ()
        if threads:
            _call(parallel, n, flats, p, out)
        elif cost is not None and serial in _READY:  # the usual call: straight to the loop (what _call ends in)
            serial(n, *flats, p, out)
            if quick and backend is None and n < 2048 and not forced:
                make = getattr(serial, "lane", None)  # a kept loop's own lane (core._native)
                run = make(nout) if make is not None else None
                kept = serial if run is not None and nout == 1 else None
                _LANES[fn] = (
                    (len(arrays), nout, with_params),
                    run or functools.partial(_lane_call, serial, nout),
                    kept,
                )
        elif cost is None and n >= 256 and bool(serial.signatures):  # compiled already: time it
            t0 = time.perf_counter()
            _call(serial, n, flats, p, out)
            _COST[serial] = (time.perf_counter() - t0) / n
        else:
            _call(serial, n, flats, p, out)
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


#: The bits of float64 ``+inf`` as an unsigned integer.
_INF_BITS = 0x7FF0000000000000
_U64 = np.dtype(np.uint64)


def nonnegative_finite(arr: np.ndarray) -> bool:
    """True when every element of the float64 ``arr`` lies in ``[+0, inf)``, in one read-only pass.

    IEEE 754: read as unsigned integers, the bit patterns of exactly those numbers (sign bit clear,
    exponent not all ones) lie below that of ``+inf``; a negative number (sign bit set), ``inf`` and
    every NaN lie at or above it. One integer maximum instead of a float minimum and maximum (1 us
    of the fixed cost of an array call, issue 25), found by ``argmax`` (0.24 us on 1e3 speeds,
    where the ufunc's reduction takes 0.95 us). ``-0.0`` reads as False: callers check again
    element by element. ``arr`` is not empty.
    """
    bits = arr.view(_U64)
    return bits.item(bits.argmax()) < _INF_BITS


def on_speeds(fn, speeds, *scalars, params=None):
    """``evaluate(fn, speeds, *scalars, params=params)[0]`` for speeds not checked yet, through the
    loop's ufunc alone; None where this cannot answer (then the caller checks the speeds and calls
    :func:`evaluate`, which gives the same numbers or raises).

    It answers a script's usual small call, once :func:`evaluate`'s lane runs ``fn``'s kept loop as
    a numpy ufunc (:meth:`~microimpact.core._native.NativeLoop.ufunc_if_made`): ``speeds`` a 1-D
    float64 array of 2 to 2047 elements, all in ``[+0, inf)`` (:func:`nonnegative_finite`, the
    check the caller would make: a speed outside is the caller's error to name), ``scalars`` and
    ``params`` floats as the loop was made for, no backend forced, and no call the loop refuses.
    Checking the speeds, finding the lane and shaping its result cost 4-6 us around a 5 us loop on
    1e3 speeds; here they are one look-up and one pass (issue 25)."""
    lane = _LANES.get(fn)
    if lane is None or lane[2] is None:
        return None
    signature, _, kept = lane
    made = kept.ufunc_if_made()
    if (
        made is None
        or type(speeds) is not np.ndarray
        or speeds.ndim != 1
        or speeds.dtype is not _F64
        or not 1 < speeds.shape[0] < 2048
        or signature != (1 + len(scalars), 1, params is not None)
        or _forced()
        or not nonnegative_finite(speeds)
    ):
        return None
    ufunc, refused = made
    before = refused.value
    try:
        result = ufunc(speeds, *scalars, *(params or ()))
    except TypeError:  # a scalar or parameter that is no number: evaluate's route decides
        return None
    return result if refused.value == before else None


def _lane_call(serial, nout, n, inputs, params):
    out = np.empty((nout, n))
    serial(n, *inputs, params, out)
    return out


def registered() -> list:
    """The ``@jitable`` functions the compiled loops may call (for the documentation and tests)."""
    return list(JITABLE)


def _owned_cache_files(folder: Path):
    """The loop files microimpact generated in ``folder`` (first line :data:`_MARK`) and numba's entries for them."""
    from . import _native

    kernels = folder / "kernels"
    stems, files = [], []
    try:
        entries = sorted(kernels.iterdir())
    except OSError:
        return files
    for p in entries:
        if p.suffix == ".py" and p.is_file() and not p.is_symlink():
            try:
                with open(p, encoding="utf-8") as fh:
                    first = fh.readline()
            except (OSError, UnicodeDecodeError):
                continue
            if first.startswith(_MARK):
                stems.append(p.stem)
                files.append(p)
    for stem in stems:  # the loop's file lock (core.cache.locked)
        lock = kernels / f"{stem}.lock"
        if lock.is_file() and not lock.is_symlink():
            files.append(lock)
    pycache = kernels / "__pycache__"
    try:
        cached = sorted(pycache.iterdir())
    except OSError:
        cached = []
    for p in cached:
        if p.is_file() and not p.is_symlink() and any(p.name.startswith(stem + ".") for stem in stems):
            files.append(p)
    return files + _native.owned_files(folder)


def cache_info() -> dict:
    """What the compiled-kernel cache holds: ``folder``, ``files``, ``bytes``, ``writable``.

    Only the files microimpact made there are counted (:func:`clear_cache` deletes just these).
    """
    folder = cache_dir()
    files = _owned_cache_files(folder)
    size = _cache.total_bytes(files)
    probe = folder if folder.exists() else next((p for p in folder.parents if p.exists()), folder)
    return {"folder": str(folder), "files": len(files), "bytes": size, "writable": os.access(probe, os.W_OK)}


def clear_cache() -> int:
    """Delete the cache's own files (generated loops and numba's entries for them); returns how many.

    Nothing else in the folder is touched: a file is the cache's when it is a loop file whose first
    line is microimpact's generated-file mark, or numba's index/data file named after such a loop.
    The compiled loops already loaded in this process stay usable.
    """
    from . import _native

    folder = cache_dir()
    n = 0
    for p in _owned_cache_files(folder):
        try:
            p.unlink()
            n += 1
        except FileNotFoundError:
            pass
    for d in (folder / "kernels" / "__pycache__", _native.folder(), folder / "kernels"):
        try:
            d.rmdir()  # only when empty
        except OSError:
            pass
    return n
