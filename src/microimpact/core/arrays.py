"""Array versions of the core's scalar functions, derived from them (never retyped).

:func:`evaluate` applies a scalar core function element by element over broadcast arrays. Two
engines give bitwise the same numbers, because both run the very same source:

* ``"python"``: a loop over the scalar function itself. Used for small arrays while numba is not
  yet imported in this process (importing numba costs ~0.35 s here, the loop ~1-3 us per element),
  unless one element, timed, shows that the loop would take longer than :data:`PYTHON_BUDGET`
  (a model that integrates its equation of motion: ~1 ms per element); and whenever
  ``MICROIMPACT_BACKEND=python``.
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

This is the fluids idea (one scalar source per formula, fast dialects generated from it) with
poliastro's split (compiled core on floats; wrappers only convert and call).
"""

from __future__ import annotations

import functools
import itertools
import os
import sys
import threading
import time
from pathlib import Path

import numpy as np

from ._jit import JITABLE

__all__ = [
    "evaluate",
    "backend_for",
    "BACKENDS",
    "SMALL",
    "PARALLEL_MIN",
    "PARALLEL_WORK",
    "PYTHON_BUDGET",
    "cache_dir",
]

#: Engines :func:`evaluate` can use.
BACKENDS = ("numba", "python")
#: Below this many elements, and while numba is not imported, the Python loop is used.
SMALL = 4096
#: From this many elements on, the compiled loop runs on all cores.
PARALLEL_MIN = 50_000
#: Estimated time [s] of the Python loop over a small array beyond which it is compiled instead
#: (importing numba and loading a cached loop cost about 0.4 s).
PYTHON_BUDGET = 0.25
#: Estimated work [s] of one array from which threads are used below PARALLEL_MIN (never below 2048).
PARALLEL_WORK = 2e-4
_COST: dict = {}  # measured serial time per element [s] of each compiled loop
_PY_COST: dict = {}  # measured time of one Python call [s] of each function

_CORE = Path(__file__).resolve().parent
_KERNELS: dict = {}
_LOCK = threading.Lock()  # dask evaluates blocks in threads: one thread builds a loop, the others wait


def _forced() -> str:
    forced = os.environ.get("MICROIMPACT_BACKEND", "").strip().lower()
    if forced and forced not in BACKENDS:
        raise ValueError(f"MICROIMPACT_BACKEND must be one of {', '.join(BACKENDS)}; got {forced!r}")
    return forced


def backend_for(n: int) -> str:
    """The engine :func:`evaluate` takes for ``n`` elements (see the module docstring)."""
    forced = _forced()
    if forced:
        return forced
    return "numba" if (n >= SMALL or "numba" in sys.modules) else "python"


def cache_dir() -> Path:
    """Where the generated loops (and numba's compiled code beside them) are kept.

    ``MICROIMPACT_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/microimpact`` (``~/.cache/microimpact``),
    else a folder in the temporary directory when the home folder cannot be written.
    """
    env = os.environ.get("MICROIMPACT_CACHE_DIR")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "microimpact"


@functools.lru_cache(maxsize=1)
def _source_hash() -> str:
    import hashlib

    h = hashlib.sha256()
    for path in sorted(_CORE.rglob("*.py")):
        h.update(path.relative_to(_CORE).as_posix().encode())
        h.update(path.read_bytes())
    import numba

    h.update(numba.__version__.encode())
    h.update(sys.version.encode())
    return h.hexdigest()[:16]


def _outside_hash(fn) -> str:
    """Hash of the file of ``fn`` when it lies outside the core (a model added with
    :func:`microimpact.models.register_path`): editing it must not reuse a loop compiled from the
    old source, as the core's own hash guarantees for the core."""
    import hashlib
    import inspect

    try:
        path = Path(inspect.getsourcefile(fn)).resolve()
        if _CORE in path.parents:
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
    import tempfile

    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name + ".", suffix=".tmp")
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _kernels(fn, kinds: str, nout: int, with_params: bool):
    key = (fn, kinds, nout, with_params)
    found = _KERNELS.get(key)
    if found is not None:
        return found
    with _LOCK:
        found = _KERNELS.get(key)
        if found is None:
            found = _KERNELS[key] = _build(fn, kinds, nout, with_params)
    return found


def _build(fn, kinds: str, nout: int, with_params: bool):
    import hashlib
    import importlib.util
    import tempfile

    import numba  # noqa: F401  (the first compiled call pays for this import, once per process)

    text = _generate(fn, kinds, nout, with_params)
    tag = hashlib.sha256((_source_hash() + _outside_hash(fn) + text).encode()).hexdigest()[:16]
    stem = f"{fn.__module__.replace('.', '_')}__{fn.__name__}_{kinds}_{tag}"
    for folder in (
        cache_dir(),
        Path(tempfile.gettempdir()) / f"microimpact-{os.getuid() if hasattr(os, 'getuid') else 0}",
    ):
        path = folder / "kernels" / f"{stem}.py"
        try:
            if not path.exists() or path.read_text() != text:
                _write_atomic(path, text)
            break
        except OSError:
            continue
    else:  # pragma: no cover - no writable folder at all
        raise OSError(f"no writable cache folder for compiled loops (tried {cache_dir()})")
    # numba's cache finds the module again by name when it loads the compiled code.
    name = f"_microimpact_kernel_{stem}"
    module = sys.modules.get(name)
    if module is None:
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return module.serial, module.parallel


def _flat(arrays, shape):
    """1-D float64 views (or copies) of each array over the broadcast ``shape``, with their steps."""
    n = int(np.prod(shape, dtype=np.int64))
    flats, steps = [], []
    for a in arrays:
        if a.size == 1 or (a.size > 1 and not any(a.strides)):  # one value, or one broadcast to many
            flats.append(np.array([a.flat[0]], dtype=np.float64))
            steps.append(0)
        elif a.ndim == 1 and a.shape == shape and a.dtype == np.float64:
            flats.append(a)  # a column of a table, say: the loop reads it in place, strided
            steps.append(1)
        else:
            b = np.broadcast_to(a, shape) if a.shape != shape else a
            flats.append(np.ascontiguousarray(b, dtype=np.float64).reshape(n))
            steps.append(1)
    return n, flats, steps


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
    shape = np.broadcast_shapes(*(a.shape for a in arrays))
    n, flats, steps = _flat(arrays, shape)
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
    elif fn not in JITABLE:
        engine = "python"
    else:
        engine = backend_for(n)
        if engine == "python" and not _forced() and n > 8:
            # A small array in Python only pays while the function is cheap: time one element once
            # per function (the same numbers either way) and compile when the loop would take longer.
            cost = _PY_COST.get(fn)
            if cost is None:
                t0 = time.perf_counter()
                fn(*(float(f[0]) for f in flats), *((tuple(params),) if params is not None else ()))
                cost = _PY_COST[fn] = time.perf_counter() - t0
            if cost * n > PYTHON_BUDGET:
                engine = "numba"
    with_params = params is not None
    if engine == "numba":
        kinds = "".join("s" if s == 0 else "a" for s in steps)
        serial, parallel = _kernels(fn, kinds, nout, with_params)
        cost = _COST.get(serial)
        threads = n >= PARALLEL_MIN or (cost is not None and n >= 2048 and n * cost >= PARALLEL_WORK)
        inputs = [float(f[0]) if s == 0 else f for f, s in zip(flats, steps)]
        if threads:
            parallel(n, *inputs, tuple(params) if with_params else (), out)
        else:
            measure = cost is None and n >= 256 and bool(serial.signatures)  # compiled already: time it
            t0 = time.perf_counter()
            serial(n, *inputs, tuple(params) if with_params else (), out)
            if measure:
                _COST[serial] = (time.perf_counter() - t0) / n
    elif engine == "python":
        cols = [itertools.repeat(float(f[0]), n) if s == 0 else f.tolist() for f, s in zip(flats, steps)]
        if with_params:
            p = tuple(params)
            res = [fn(*xs, p) for xs in zip(*cols)]
        else:
            res = [fn(*xs) for xs in zip(*cols)]
        out[...] = np.array(res, dtype=np.float64).reshape(n, nout).T if nout > 1 else np.array(res, dtype=np.float64)
    else:
        raise ValueError(f"backend must be one of {', '.join(BACKENDS)}; got {engine!r}")
    return out.reshape((nout,) + shape)


def registered() -> list:
    """The ``@jitable`` functions the compiled loops may call (for the documentation and tests)."""
    return list(JITABLE)
