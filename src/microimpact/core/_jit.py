"""Mark plain scalar functions of the core as compilable by numba, without importing numba.

Every formula of the core is a plain Python function over floats that uses only :mod:`math`,
tuples and control flow (the subset numba compiles). ``@jitable`` returns the function itself,
so the scalar path calls it directly at Python speed and ``import microimpact`` never imports
numba. The first array call that needs compiled speed imports numba and registers every marked
function with :func:`numba.extending.register_jitable` (see :mod:`microimpact.core.arrays`), so the
compiled loops call the very same source.

:func:`for_numba` is what is registered: the function itself, or, where it reads a module-level
tuple of floats (a table of coefficients), a twin with the same code object whose globals hold
that tuple as a read-only numpy array. numba copies a tuple onto the stack at every call it
indexes with a variable (40 ns for a table of 110 numbers) but reads an array in place; Python
indexes a tuple fastest. Same code, same numbers, so the results are bitwise the same.

:func:`register_all` registers them, once per process (later marked functions when it is called
again), compiled with numba's ``error_model="numpy"`` like the loops that call them.
"""

from __future__ import annotations

__all__ = ["jitable", "JITABLE", "INLINE", "for_numba", "has_loop", "register_all"]

#: Functions marked with :func:`jitable`, in definition order.
JITABLE: list = []


#: Marked functions numba inlines into their callers (``@jitable(inline=True)``).
INLINE: set = set()


def jitable(fn=None, *, inline=False):
    """Mark ``fn`` (a scalar function written in numba's subset of Python) and return it unchanged.

    ``@jitable(inline=True)`` also asks numba to inline it into every compiled caller (its
    ``inline="always"``, at the level of numba's own code, before types are inferred): for small
    functions called in an inner loop with many arguments, such as the law dispatch of
    :func:`microimpact.core.tangential_laws.step_rates`, which the compiler would otherwise call
    with every argument passed anew. Same operations, so the same numbers.
    """
    if fn is None:
        return lambda f: jitable(f, inline=inline)
    JITABLE.append(fn)
    if inline:
        INLINE.add(fn)
    return fn


#: Tuples of floats at least this long that a function reads as globals become arrays for numba.
TABLE_MIN = 16


def for_numba(fn):
    """``fn``, or its twin reading its float tables as read-only arrays (module docstring)."""
    import types

    tables = {
        name: fn.__globals__[name]
        for name in fn.__code__.co_names
        if isinstance(fn.__globals__.get(name), tuple)
        and len(fn.__globals__[name]) >= TABLE_MIN
        and all(type(x) is float for x in fn.__globals__[name])
    }
    if not tables:
        return fn
    import numpy as np

    env = dict(fn.__globals__)
    for name, values in tables.items():
        arr = np.array(values, dtype=np.float64)
        arr.flags.writeable = False
        env[name] = arr
    twin = types.FunctionType(fn.__code__, env, fn.__name__, fn.__defaults__, fn.__closure__)
    twin.__qualname__ = fn.__qualname__
    twin.__module__ = fn.__module__
    return twin


def has_loop(fn) -> bool:
    """True where ``fn``'s bytecode jumps backwards (a ``for`` or ``while`` loop)."""
    import dis

    for ins in dis.get_instructions(fn):
        if ins.opname == "FOR_ITER" or ins.opname.startswith("JUMP_BACKWARD"):
            return True
        if ins.opname in ("JUMP_ABSOLUTE", "POP_JUMP_BACKWARD_IF_TRUE", "POP_JUMP_BACKWARD_IF_FALSE") and (
            ins.argval is not None and ins.argval < ins.offset
        ):
            return True
    return False


_REGISTERED: set = set()


def register_all() -> None:
    """Register every function marked so far with numba (as :func:`for_numba` gives it), once each."""
    from numba.extending import overload

    for fn in JITABLE:
        if fn in _REGISTERED:
            continue
        twin = for_numba(fn)
        inline = "always" if fn in INLINE else "never"
        overload(fn, jit_options={"error_model": "numpy"}, strict=False, inline=inline)(lambda *a, _t=twin, **k: _t)
        _REGISTERED.add(fn)
