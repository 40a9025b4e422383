"""Mark plain scalar functions of the core as compilable by numba, without importing numba.

Every formula of the core is a plain Python function over floats that uses only :mod:`math`,
tuples and control flow (the subset numba compiles). ``@jitable`` returns the function itself,
so the scalar path calls it directly at Python speed and ``import microimpact`` never imports
numba. The first array call that needs compiled speed imports numba and registers every marked
function with :func:`numba.extending.register_jitable` (see :mod:`microimpact.core.arrays`), so the
compiled loops call the very same source.
"""

from __future__ import annotations

__all__ = ["jitable", "JITABLE"]

#: Functions marked with :func:`jitable`, in definition order.
JITABLE: list = []


def jitable(fn):
    """Mark ``fn`` (a scalar function written in numba's subset of Python) and return it unchanged."""
    JITABLE.append(fn)
    return fn
