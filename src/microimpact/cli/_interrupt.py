"""How the ``microimpact`` command ends on SIGINT or SIGTERM: one line on stderr, exit ``128 + signal``.

The library changes nothing of the process (``import microimpact`` installs no handler and
replaces no hook); the command line does, for the time of one command (:func:`install` at the
start of :func:`microimpact.cli.main`, :func:`restore` at its end):

* the first SIGINT or SIGTERM raises :class:`Interrupted` where the command is. It is a
  :class:`KeyboardInterrupt`, so every ``finally`` block and context manager runs: each output is
  written to a temporary file in its destination folder and renamed into place when complete
  (:mod:`microimpact.io`), and the temporary file is removed in ``finally``. The signal is also
  remembered (:func:`pending`): where a library swallowed the exception (Python drops one raised in
  a ``__del__`` or a weakref callback) or turned it into another (a C extension's import into an
  ``ImportError``), :func:`check` and :func:`microimpact.cli.main` raise it again;
* a second signal ends the process at once (the one line, ``128 + signal``): the way out of a
  command stuck where an exception cannot reach it, such as a wait inside a C library;
* while an interrupt is pending, exceptions Python cannot raise (:data:`sys.unraisablehook`) are
  not printed: they come from what the interrupt cut short (an object of numba's compiler left
  half built, whose ``__del__`` then fails). Other unraisable exceptions are printed as before;
* nor is the interrupt's traceback where a C extension prints the exception it caught and raises
  another (:data:`sys.excepthook`, which C's ``PyErr_Print`` calls): numba's ``_dispatcher``
  module does so when the import of ``numba._devicearray`` inside its initialisation fails, so a
  signal during ``import numba`` printed a traceback before the one line. The other exceptions
  printed that way are printed as before.

A signal the process was started with ignored stays ignored, as Python itself keeps an ignored
SIGINT: a non-interactive shell starts a background job (``cmd &`` in a script) with SIGINT
ignored, so that a Ctrl-C meant for the foreground does not end it. Such a command runs to its
end; SIGTERM still ends it.
"""

from __future__ import annotations

import os
import signal
import sys
import threading

from .. import _atomic

__all__ = ["Interrupted", "check", "install", "message", "pending", "restore", "set_prefix"]

SIGNALS = (signal.SIGINT, signal.SIGTERM)

_state = {"pending": None, "old": {}, "hook": None, "excepthook": None, "prefix": "microimpact", "installed": False}


class Interrupted(KeyboardInterrupt):
    """SIGINT or SIGTERM during a command (a KeyboardInterrupt, so cleanup code runs); ``.signum``."""

    def __init__(self, signum=signal.SIGINT):
        super().__init__(signum)
        self.signum = int(signum)


def signal_name(signum) -> str:
    """``"Ctrl-C"`` for SIGINT, ``"SIGTERM"`` for SIGTERM."""
    return "SIGTERM" if int(signum) == signal.SIGTERM else "Ctrl-C"


def message(signum) -> str:
    """The one line printed for an interrupted command."""
    return f"{_state['prefix']}: interrupted ({signal_name(signum)}); nothing was left half-written"


def set_prefix(prefix: str) -> None:
    """Name the command in the interrupt message (``microimpact sweep``)."""
    _state["prefix"] = prefix


def pending():
    """The signal number received during the command, or None."""
    return _state["pending"]


def check() -> None:
    """Raise :class:`Interrupted` if a signal arrived (its exception may have been swallowed on the way)."""
    signum = _state["pending"]
    if signum is not None:
        raise Interrupted(signum)


def _end(signum) -> None:
    """End the process now (a second signal): the one line, exit ``128 + signal``."""
    try:
        os.write(2, (message(signum) + "\n").encode())
    except OSError:
        pass
    os._exit(128 + int(signum))


def _handler(signum, frame):
    if _state["pending"] is not None:  # a second signal: the command did not end on the first
        _end(_state["pending"])
    _state["pending"] = int(signum)
    if _atomic.busy():  # numba is building a loop: raised when it is done (check, on leaving the step)
        return
    raise Interrupted(signum)


def _unraisable(unraisable):
    """Say nothing of our interrupt where Python cannot raise it (it is pending: :func:`check` raises
    it), nor, once an interrupt is pending, of the others: they come from what it cut short."""
    if isinstance(unraisable.exc_value, Interrupted) or _state["pending"] is not None:
        return
    (_state["hook"] or sys.__unraisablehook__)(unraisable)


def _excepthook(exc_type, exc_value, exc_traceback):
    """Print no traceback of our interrupt (a C extension printing what it caught: module docstring);
    the command's one line says it."""
    if isinstance(exc_value, Interrupted):
        return
    (_state["excepthook"] or sys.__excepthook__)(exc_type, exc_value, exc_traceback)


def _silent(unraisable):
    """The hook of a process leaving after an interrupt (:func:`restore` with ``exiting``)."""


def _main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


def install() -> None:
    """For the time of a command: the first signal raises :class:`Interrupted`, a second ends the process."""
    _state["pending"] = None
    if not _main_thread() or _state["installed"]:
        return
    _state["installed"] = True
    _atomic.on_leave(check)
    _state["hook"] = sys.unraisablehook
    sys.unraisablehook = _unraisable
    _state["excepthook"] = sys.excepthook
    sys.excepthook = _excepthook
    for sig in SIGNALS:
        try:
            if signal.getsignal(sig) == signal.SIG_IGN:
                continue  # started ignoring it (a background job of a script, nohup): it stays ignored
            _state["old"][sig] = signal.signal(sig, _handler)
        except (ValueError, OSError):  # pragma: no cover - not settable here
            pass


def restore(exiting: bool = False) -> None:
    """Undo :func:`install`: the handlers and the unraisable hook from before, nothing pending.

    ``exiting``: the process leaves now (the command's entry point, :func:`microimpact.cli.console_main`):
    SIGINT and SIGTERM are ignored from here on instead (a signal in the last moments of a finished
    run must not kill it with a bare -15 once the default handler is back), and after an interrupt
    the unraisable exceptions of what it cut short stay unreported.
    """
    if not _state["installed"]:
        _state["pending"] = None
        return
    interrupted = _state["pending"] is not None
    for sig in SIGNALS:
        try:
            if exiting:
                signal.signal(sig, signal.SIG_IGN)
            elif sig in _state["old"]:
                signal.signal(sig, _state["old"][sig])
        except (ValueError, OSError, TypeError):  # pragma: no cover
            pass
    _state["old"] = {}
    if sys.unraisablehook is _unraisable:
        sys.unraisablehook = _silent if (exiting and interrupted) else (_state["hook"] or sys.__unraisablehook__)
    _state["hook"] = None
    if sys.excepthook is _excepthook:
        sys.excepthook = _state["excepthook"] or sys.__excepthook__
    _state["excepthook"] = None
    _atomic.off_leave(check)
    _state["pending"] = None
    _state["installed"] = False
