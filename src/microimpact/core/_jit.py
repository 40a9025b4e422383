"""Mark plain scalar functions of the core as compilable, without importing numba.

Every formula of the core is a plain Python function over floats that uses only :mod:`math`,
tuples and control flow (the subset numba compiles). ``@jitable`` returns the function itself,
so the scalar path calls it directly at Python speed and ``import microimpact`` never imports
numba. The array engine (:mod:`microimpact.engine`) registers every marked function with numba
before it compiles a loop, so the compiled loops call the very same source.
"""

from __future__ import annotations

__all__ = ["jitable", "JITABLE", "INLINE"]

#: Functions marked with :func:`jitable`, in definition order.
JITABLE: list = []


#: Marked functions numba inlines into their callers (``@jitable(inline=True)``).
INLINE: set = set()


def jitable(fn=None, *, inline=False):
    """Mark ``fn`` (a scalar function written in numba's subset of Python) and return it unchanged.

    ``@jitable(inline=True)`` also asks for it to be inlined into every compiled caller: for small
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
