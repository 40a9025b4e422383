"""Sections of the main thread that a signal must not cut: compiling or loading a compiled loop.

An interrupt raised inside numba's compiler leaves llvmlite objects half built; freeing them later
failed in two of 1,210 interrupted runs (a ``PassBuilder.__del__`` error printed after the
interrupt line; once glibc's "double free detected" abort, exit -6 instead of 130). While the
main thread is inside :func:`section`, the process's signal handling (``microimpact._signals``)
only records a signal; when the outermost section ends, :data:`on_leave` (set by that handling)
raises it. The handling's watchdog still ends a section that outlasts its grace time.

Plain Python, no import beyond the standard library: the core knows nothing of the command line.
"""

from __future__ import annotations

import contextlib
import threading

__all__ = ["active", "section"]

_depth = [0]
#: Called with no argument when the main thread leaves its outermost section (None: nothing to do).
on_leave = None


def _main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


def active() -> bool:
    """True while the main thread is inside a :func:`section`."""
    return _depth[0] > 0


@contextlib.contextmanager
def section():
    """Run the block with signals deferred to its end (in the main thread; elsewhere a no-op)."""
    if not _main_thread():
        yield
        return
    _depth[0] += 1
    try:
        yield
    finally:
        _depth[0] -= 1
        if _depth[0] == 0 and on_leave is not None:
            on_leave()
