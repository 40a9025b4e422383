"""Compiled loops kept as machine code, loaded by a new process without numba's start-up.

A compiled loop of :mod:`microimpact.core.arrays` loaded from numba's own cache costs a new process
numba's whole start-up first: its typing and target contexts import every implementation numba
has (``numba.np.arraymath`` imports ``scipy.linalg`` to probe for BLAS), ~0.5 s on top of
``import numba`` itself, before a single cached loop can be used. This module keeps, beside
numba's entry, the machine code of the same loop as a plain C-callable function, and loads it with
llvmlite alone (the library numba compiles with), without importing numba.

* :func:`build` (numba imported, once per loop and cache): the loop, written as a
  :func:`numba.cfunc` over raw pointers and element strides, calls the very same ``@jitable``
  function as numba's loops (inlined, ``error_model="numpy"``); numba compiles it and its object
  code is written to the cache with the names it needs from outside (``pow``, ``atan2``, ...).
  Only the loop's own function is ever called (numba's calling convention: status, exception
  slot, arguments), never the ``cfunc`` wrapper around it, which reports errors through numba's
  helpers and Python; a loop whose own code (what it calls, transitively) needs any of those is
  not kept, and numba's route stays.
* :func:`load` (any process): the entry, checked (SHA-256 of its bytes, format, versions of numba,
  llvmlite and Python, the core's sources, the CPU name and features numba compiled for), goes
  into an llvmlite MCJIT engine and is called through :mod:`ctypes`, which releases the GIL: large
  arrays are split in contiguous blocks over threads, as many as numba would use.
  A call this loop cannot take (a strided or unaligned array, a parameter that is no float, a
  different number of parameters) or that reports an error goes through numba's loop instead.

The numbers are the same bit for bit: the same function, compiled by the same numba with the same
options for the same CPU (tests/core/test_paths.py compares every path). Like the rest of the
cache, everything here is an optimisation: an entry that is missing, corrupt, from another version
or CPU, or that cannot be written, only means numba's route.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import threading
from pathlib import Path

from . import cache as _cache

__all__ = ["build", "load", "sound", "owned_files", "folder", "entry_path", "NativeLoop"]

#: First bytes of an entry; bumped when its layout or the generated source changes.
FORMAT = b"microimpact-native-1\n"

#: numba's helpers and Python's C API: only the cfunc wrapper's error branch uses them.
_WRAPPER_ONLY = ("numba_", "NRT_", "Py", "_Py")

_TEMPLATE = """
from microimpact.core import _jit
from {module} import {name} as _fn
import numba

_jit.register_all()
_top = _fn if _jit.has_loop(_fn) else numba.njit(inline="always", error_model="numpy")(_jit.for_numba(_fn))


def loop(n, {args}, pp, po, so0, so1):
{params}    for i in range(n):
        r = _top({calls}{params_arg})
{stores}
"""


def folder() -> Path:
    """Where the entries are kept: ``kernels/native`` in the cache folder."""
    return _cache.cache_dir() / "kernels" / "native"


def _dist_version(package: str) -> str:
    """``package``'s installed version, read from its ``.dist-info`` folder name without importing it
    (``importlib.metadata`` costs 0.1 s); "" when it cannot be told (then nothing is kept)."""
    import importlib.util

    try:
        spec = importlib.util.find_spec(package)
    except (ImportError, ValueError):
        return ""
    if spec is None or not spec.submodule_search_locations:
        return ""
    site = Path(next(iter(spec.submodule_search_locations))).parent
    try:
        names = [n for n in os.listdir(site) if n.startswith(package + "-") and n.endswith(".dist-info")]
    except OSError:
        return ""
    return names[0][len(package) + 1 : -len(".dist-info")] if len(names) == 1 else ""


def _source(fn, kinds: str, nout: int, nparams) -> str:
    """The cfunc's source: an array argument is a pointer and a stride (elements), a scalar a float."""
    args = ", ".join(f"a{k}, s{k}" if c == "a" else f"a{k}" for k, c in enumerate(kinds))
    calls = ", ".join(f"a{k}[i * s{k}]" if c == "a" else f"a{k}" for k, c in enumerate(kinds))
    if nparams is None:
        params, params_arg = "", ""
    else:
        items = "".join(f"pp[{j}], " for j in range(nparams))
        params, params_arg = f"    params = ({items})\n", ", params"
    if nout == 1:
        stores = "        po[i * so1] = r"
    else:
        stores = "\n".join(f"        po[{j} * so0 + i * so1] = r[{j}]" for j in range(nout))
    return _TEMPLATE.format(
        module=fn.__module__,
        name=fn.__name__,
        args=args,
        calls=calls,
        params=params,
        params_arg=params_arg,
        stores=stores,
    )


def entry_path(fn, kinds: str, nout: int, with_params: bool, loop_text: str, outside: str):
    """The entry's file for numba's loop ``loop_text`` over ``fn`` (None when versions cannot be told).

    The name hashes the core's sources, numba's, llvmlite's and Python's versions, the loop's source
    (numba's and this module's), a file outside the core holding ``fn`` (``outside``, its hash),
    numba's settings from the environment (``NUMBA_*``) and the CPU (name and features).
    """
    numba_v, llvmlite_v = _dist_version("numba"), _dist_version("llvmlite")
    host = _host() if numba_v and llvmlite_v else None
    if host is None:
        return None
    h = hashlib.sha256(FORMAT)
    for part in (
        _cache.core_hash(),
        numba_v,
        llvmlite_v,
        sys.version,
        outside,
        loop_text,
        _source(fn, kinds, nout, 0 if with_params else None),
        repr(sorted((k, v) for k, v in os.environ.items() if k.startswith("NUMBA_"))),
        repr(host),
    ):
        h.update(part.encode())
        h.update(b"\0")
    stem = f"{fn.__module__.replace('.', '_')}__{fn.__name__}_{kinds}_{h.hexdigest()[:16]}"
    return folder() / f"{stem}.bin"


def _host():
    """``(triple, cpu name, features)`` as numba's JIT compiles for this machine, from llvmlite alone;
    None where numba's environment settings decide them (``NUMBA_CPU_NAME`` and the like)."""
    if any(k in os.environ for k in ("NUMBA_CPU_NAME", "NUMBA_CPU_FEATURES", "NUMBA_ENABLE_AVX")):
        return None
    import llvmlite.binding as ll

    _init_llvm()
    try:
        features = ll.get_host_cpu_features().flatten()
    except RuntimeError:
        features = ""
    return [ll.get_process_triple(), ll.get_host_cpu_name(), features]


_LLVM_READY = []


def _init_llvm():
    if not _LLVM_READY:
        import llvmlite.binding as ll

        ll.initialize_native_target()
        ll.initialize_native_asmprinter()
        _LLVM_READY.append(True)


def _calls(ir: str):
    """``({function: names it refers to}, declared names)`` of an LLVM module's text."""
    import re

    defined, declared, current = {}, set(), None
    name = r'@("(?:[^"\\]|\\.)*"|[-\w$.]+)'
    for line in ir.splitlines():
        if line.startswith("declare "):
            m = re.search(name, line)
            if m:
                declared.add(m.group(1).strip('"'))
        elif line.startswith("define "):
            m = re.search(name, line)
            current = m.group(1).strip('"') if m else None
            if current is not None:
                defined[current] = set()
        elif line.startswith("}"):
            current = None
        elif current is not None:
            defined[current].update(x.strip('"') for x in re.findall(name, line))
    return defined, declared


def build(fn, kinds: str, nout: int, nparams, path: Path) -> bool:
    """Compile the loop over ``fn`` as a C-callable function (numba imported) and write its entry to
    ``path`` atomically; False (nothing raised, nothing written) where it cannot be kept."""
    try:
        data = _compile(fn, kinds, nout, nparams)
        if data is None:
            return False
        _cache.write_atomic(path, data)
    except Exception:  # the cache is an optimisation: numba's loop has run already
        return False
    return True


def _compile(fn, kinds: str, nout: int, nparams):
    import numba
    from numba import types

    host = _host()
    if host is None:
        return None
    text = _source(fn, kinds, nout, nparams)
    namespace = {"__name__": f"_microimpact_native_{fn.__module__.replace('.', '_')}__{fn.__name__}_{kinds}"}
    exec(compile(text, f"<microimpact native loop over {fn.__module__}.{fn.__name__}>", "exec"), namespace)
    d, ptr, intp = types.float64, types.CPointer(types.float64), types.intp
    argtypes = [intp]
    for c in kinds:
        argtypes += [ptr, intp] if c == "a" else [d]
    argtypes += [ptr, ptr, intp, intp]
    compiled = numba.cfunc(types.void(*argtypes), nopython=True, error_model="numpy")(namespace["loop"])
    library = compiled._library
    wrapper = compiled._wrapper_name or ""
    if not wrapper.startswith("cfunc."):
        return None
    inner = wrapper[len("cfunc.") :]  # numba names its cfunc wrapper "cfunc." + the function's own name
    if list(library.codegen.magic_tuple()) != host:
        return None  # numba compiled for another CPU than the loader would check against
    ir = library.get_llvm_str()
    defined, declared = _calls(ir)
    if inner not in defined:
        return None
    reach, todo = set(), [inner]
    while todo:
        f = todo.pop()
        if f in reach:
            continue
        reach.add(f)
        todo.extend(g for g in defined.get(f, ()) if g in defined)
    needed = {g for f in reach for g in defined[f] if g in declared}
    if any(g.startswith(_WRAPPER_ONLY) for g in needed):
        return None  # the loop itself needs numba's runtime or Python: keep numba's route
    # numba's calling convention: i32 status (ptr retval, ptr exception slot, arguments...)
    want = ["ptr", "ptr"] + ["i64" if t is intp else "double" if t is d else "ptr" for t in argtypes]
    if str(library.get_function(inner).global_value_type) != f"i32 ({', '.join(want)})":
        return None
    obj = library.codegen._tm.emit_object(library._final_module)
    undefined = _undefined_symbols(obj)
    if undefined is None:
        return None
    header = {
        "inner": inner,
        "host": host,
        "kinds": kinds,
        "nout": nout,
        "nparams": nparams,
        # names the object code takes from outside: the loop's own (a C library's) must exist where it
        # is loaded; the wrapper's (numba's helpers, Python's API) may be absent: never called here
        "undefined": undefined,
        "wrapper_only": sorted(n for n in undefined if n.startswith(_WRAPPER_ONLY)),
    }
    body = json.dumps(header).encode() + b"\n" + obj
    return FORMAT + hashlib.sha256(body).digest() + body


def _undefined_symbols(obj: bytes):
    """The names an ELF-64 little-endian object file takes from outside (its undefined global or
    weak symbols), or None for any other object format (then nothing is kept)."""
    import struct

    if len(obj) < 64 or obj[:6] != b"\x7fELF\x02\x01":
        return None
    try:
        shoff, _, _, _, _, shentsize, shnum = struct.unpack_from("<QIHHHHH", obj, 0x28)
        sections = [struct.unpack_from("<IIQQQQIIQQ", obj, shoff + k * shentsize) for k in range(shnum)]
        names = set()
        for sh in sections:
            if sh[1] != 2:  # SHT_SYMTAB
                continue
            strtab = sections[sh[6]]
            strings = obj[strtab[4] : strtab[4] + strtab[5]]
            for off in range(sh[4], sh[4] + sh[5], sh[9] or 24):
                st_name, st_info, _, st_shndx = struct.unpack_from("<IBBH", obj, off)
                if st_shndx == 0 and st_name and (st_info >> 4) in (1, 2):
                    names.add(strings[st_name : strings.index(b"\0", st_name)].decode())
    except (struct.error, ValueError, IndexError, UnicodeDecodeError):
        return None
    return sorted(names)


def sound(path: Path) -> bool:
    """True when ``path`` holds an entry whose bytes are whole (format and SHA-256 checked)."""
    return _read(path) is not None


def _read(path: Path):
    """``(header, object code)`` of a sound entry, else None."""
    try:
        data = path.read_bytes()
    except OSError:
        return None
    head = len(FORMAT) + 32
    if len(data) <= head or not data.startswith(FORMAT):
        return None
    body = data[head:]
    if hashlib.sha256(body).digest() != data[len(FORMAT) : head]:
        return None
    line, _, obj = body.partition(b"\n")
    try:
        header = json.loads(line)
    except ValueError:
        return None
    return header, obj


_ENGINES: list = []  # MCJIT engines of the loaded entries: their code lives as long as they do
_TRAP: list = []


def _symbol(name: str):
    """The process's address of ``name`` (a C library's function, Python's API), or None."""
    import ctypes

    try:
        return ctypes.cast(getattr(ctypes.CDLL(None), name), ctypes.c_void_p).value
    except (AttributeError, OSError):
        return None


def load(path: Path, kinds: str, nout: int, fallback):
    """``(serial, parallel)`` callables like numba's loops (``(n, *inputs, params, out)``) running the
    entry at ``path``, or None (missing, corrupt, another version or CPU). ``fallback()`` gives
    numba's ``(serial, parallel)`` for a call the entry cannot take."""
    found = _read(path)
    if found is None:
        return None
    header, obj = found
    if header.get("kinds") != kinds or header.get("nout") != nout or header.get("host") != _host():
        return None
    import ctypes

    import llvmlite.binding as ll

    # every name the code takes from outside must resolve (else MCJIT ends the process): the loop's
    # own from the C library; the cfunc wrapper's (never called here) may point at abort()
    if not _TRAP:
        _TRAP.append(_symbol("abort"))
    resolved = {}
    for name in header["undefined"]:
        address = ll.address_of_symbol(name) or _symbol(name)
        if address is None and name in header["wrapper_only"]:
            address = _TRAP[0]
        if address is None:
            return None
        resolved[name] = address
    for name, address in resolved.items():
        if not ll.address_of_symbol(name):
            ll.add_symbol(name, address)
    try:
        tm = ll.Target.from_triple(ll.get_process_triple()).create_target_machine(
            cpu=header["host"][1], features=header["host"][2], reloc="static", codemodel="jitdefault", jit=True
        )
        engine = ll.create_mcjit_compiler(ll.parse_assembly(""), tm)
        engine.add_object_file(ll.ObjectFileRef.from_data(obj))
        engine.finalize_object()
        address = engine.get_function_address(header["inner"])
    except Exception:
        return None
    if not address:
        return None
    _ENGINES.append(engine)
    cargs = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_ssize_t]
    for c in kinds:
        cargs += [ctypes.c_void_p, ctypes.c_ssize_t] if c == "a" else [ctypes.c_double]
    cargs += [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_ssize_t, ctypes.c_ssize_t]
    function = ctypes.CFUNCTYPE(ctypes.c_int32, *cargs)(address)
    shared = _Shared(function, kinds, nout, header["nparams"], fallback)
    return NativeLoop(shared, False), NativeLoop(shared, True)


def _threads() -> int:
    """As many threads as numba's parallel loops would use (``NUMBA_NUM_THREADS``, else the CPUs)."""
    try:
        n = int(os.environ.get("NUMBA_NUM_THREADS", "0"))
    except ValueError:
        n = 0
    if n < 1:
        try:
            n = len(os.sched_getaffinity(0))
        except (AttributeError, OSError):
            n = os.cpu_count() or 1
    return max(1, n)


class _Shared:
    """One loaded loop: the C function and what a call must look like to take it."""

    def __init__(self, function, kinds, nout, nparams, fallback):
        self.function = function
        self.kinds = kinds
        self.nout = nout
        self.nparams = nparams
        self.fallback = fallback
        self.numba = None
        self.lock = threading.Lock()


class NativeLoop:
    """A loaded loop, called like numba's (``loop(n, *inputs, params, out)``); see the module docstring."""

    signatures = ("native",)  # what arrays asks of a loop that needs no compiling

    def __init__(self, shared: _Shared, threaded: bool):
        self._s = shared
        self._threaded = threaded

    def _args(self, n, inputs, params, out):
        """The C arguments after ``n`` (offsets in elements per array), or None."""
        import numpy as np

        s = self._s
        f8 = np.dtype(np.float64)
        if s.nparams is None:
            if params:
                return None
            pp = None
        else:
            if len(params) != s.nparams or not all(isinstance(x, float) for x in params):
                return None
            buf = np.array(params, dtype=np.float64) if params else np.zeros(1)
            pp = buf
        arrays, args = [], []
        for c, a in zip(s.kinds, inputs):
            if c == "a":
                if not (
                    isinstance(a, np.ndarray)
                    and a.dtype == f8
                    and a.ndim == 1
                    and a.shape[0] >= n
                    and a.flags.aligned
                    and a.strides[0] % 8 == 0
                ):
                    return None
                arrays.append((len(args), a))
                args += [a.ctypes.data, a.strides[0] // 8]
            else:
                if not isinstance(a, float):
                    return None
                args.append(a)
        if not (
            isinstance(out, np.ndarray)
            and out.dtype == f8
            and out.ndim == 2
            and out.shape == (s.nout, n)
            and out.flags.writeable
            and out.flags.aligned
            and out.strides[0] % 8 == 0
            and out.strides[1] % 8 == 0
        ):
            return None
        args += [0 if pp is None else pp.ctypes.data, out.ctypes.data, out.strides[0] // 8, out.strides[1] // 8]
        return args, arrays, (pp, inputs, out)

    def __call__(self, n, *rest):
        import ctypes

        *inputs, params, out = rest
        s = self._s
        prepared = self._args(n, inputs, params, out) if len(inputs) == len(s.kinds) else None
        if prepared is not None:
            args, arrays, keep = prepared
            blocks = _threads() if self._threaded else 1
            blocks = max(1, min(blocks, n // 1024))
            edges = [n * k // blocks for k in range(blocks + 1)]
            status = [0] * blocks

            def run(k):
                lo, hi = edges[k], edges[k + 1]
                a = list(args)
                for pos, arr in arrays:
                    a[pos] += lo * a[pos + 1] * 8
                a[-3] += lo * a[-1] * 8
                ret, exc = ctypes.c_void_p(), ctypes.c_void_p()
                status[k] = s.function(ctypes.byref(ret), ctypes.byref(exc), hi - lo, *a)

            workers = [threading.Thread(target=run, args=(k,), daemon=True) for k in range(1, blocks)]
            for w in workers:
                w.start()
            run(0)
            for w in workers:
                w.join()
            del keep
            if not any(status):
                return None
        # a call the entry cannot take, or an error in the loop: numba's loop (which raises it)
        with s.lock:
            if s.numba is None:
                s.numba = s.fallback()
        return s.numba[1 if self._threaded else 0](n, *inputs, params, out)


def owned_files(cache_folder: Path) -> list:
    """The entries this module wrote in ``cache_folder`` (their first bytes are :data:`FORMAT`)."""
    where = cache_folder / "kernels" / "native"
    found = []
    try:
        entries = sorted(where.iterdir())
    except OSError:
        return found
    for p in entries:
        if p.suffix == ".bin" and p.is_file() and not p.is_symlink():
            try:
                with open(p, "rb") as fh:
                    if fh.read(len(FORMAT)) == FORMAT:
                        found.append(p)
            except OSError:
                continue
    return found
