"""Steps a signal must not cut: numba building or loading a compiled function, and xarray creating a
NetCDF file.

Python runs a signal handler between any two bytecodes, and numba compiles (or loads from its cache)
in Python, through llvmlite. An exception raised there by a handler can leave an LLVM object owned
twice, half handed over: its later release frees it twice and the process aborts ("free(): double
free detected"), where an interrupted command should end with one line. xarray takes its NetCDF file
lock in Python too: an exception raised between an acquire and the ``try`` that releases it leaves
the lock held, and the next acquire waits for ever. The library marks such steps with :func:`step`
and changes nothing else in the process. A program whose handler raises (the
command line, :mod:`microimpact.cli._interrupt`) asks :func:`busy` there and, while a step runs in the
main thread, only remembers the signal; the callbacks given to :func:`on_leave` run when the step
ends, and raise it then. The delay is the step's: a compilation takes seconds, a load from the cache
a fraction of one; a compiled loop itself never runs a handler until it returns anyway.
"""

from __future__ import annotations

import contextlib
import threading

__all__ = ["busy", "on_leave", "off_leave", "step"]

_depth = [0]  # steps running in the main thread (nested: a loop's first call compiles the functions it calls)
_leave = []


def busy() -> bool:
    """True while a step runs in the main thread (where signal handlers run)."""
    return _depth[0] > 0


def on_leave(callback) -> None:
    """Call ``callback()`` each time the main thread leaves its outermost step."""
    if callback not in _leave:
        _leave.append(callback)


def off_leave(callback) -> None:
    """Stop calling ``callback`` (:func:`on_leave`)."""
    if callback in _leave:
        _leave.remove(callback)


@contextlib.contextmanager
def step():
    """Run the body as one step for a signal handler that asks :func:`busy`."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _depth[0] += 1
    try:
        yield
    finally:
        _depth[0] -= 1
        if _depth[0] == 0:
            for callback in tuple(_leave):
                callback()
