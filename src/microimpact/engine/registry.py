"""The core's ``@jitable`` functions as numba sees them: registered through numba's public API.

Every formula of the core is a plain Python function over floats, marked with
:func:`microimpact.core._jit.jitable` (which returns it unchanged and knows nothing of numba). The
first compiled loop (:mod:`microimpact.engine.loops`) calls :func:`register_all`, which hands every
marked function to :func:`numba.extending.overload` with an implementation that is the function
itself (or its table twin, below), so the compiled loops call the very same source.

:func:`for_numba` is what is registered: the function itself, or, where it reads a module-level
tuple of floats (a table of coefficients), a twin with the same code object whose globals hold
that tuple as a read-only numpy array. numba copies a tuple onto the stack at every call it
indexes with a variable (40 ns for a table of 110 numbers) but reads an array in place; Python
indexes a tuple fastest. Same code, same numbers, so the results are bitwise the same.

Functions marked ``@jitable(inline=True)`` are inlined by numba into their compiled callers
(``inline="always"``, at the level of numba's own code, before types are inferred); the others are
compiled once and called. All are compiled with ``error_model="numpy"`` like the loops that call
them (a division by zero gives inf or nan, as numpy's arrays do, not an exception).
"""

from __future__ import annotations

from ..core._jit import INLINE, JITABLE

__all__ = ["TABLE_MIN", "for_numba", "has_loop", "register_all", "registered"]


#: Tuples of floats at least this long that a function reads as globals become arrays for numba.
TABLE_MIN = 16


def registered() -> list:
    """The ``@jitable`` functions the compiled loops may call, in definition order."""
    return list(JITABLE)


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
    """True where ``fn``'s bytecode jumps backwards (a ``for`` or ``while`` loop): such a function is
    called by the compiled loop rather than inlined into it (inlining a loop gains nothing)."""
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
