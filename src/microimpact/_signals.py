"""How a command ends on SIGINT or SIGTERM: always, within seconds, leaving no temporary file.

Shared by :mod:`microimpact.io` (which registers every temporary file and folder it is writing,
and checks for a pending interrupt before it renames anything into place) and
:mod:`microimpact.cli` (which installs the handlers). Three stages:

* :func:`install_early` -- from the first line of ``import microimpact`` when the process is the
  ``microimpact`` command: until the command starts, a signal ends the process at once with one
  line and exit status ``128 + signal`` (nothing has been written yet; no traceback, no bare -15).
* :func:`install` -- while the command runs: the first signal raises :class:`Interrupted` (a
  :class:`KeyboardInterrupt`, so every ``finally`` and context manager cleans up), is remembered
  (:func:`check` raises it again where Python swallowed it: in a ``__del__``, a callback), and arms
  a watchdog: if the command has not ended :data:`GRACE` seconds later (a deadlock in a library's
  lock, a blocking call), the registered temporary files are removed and the process exits with
  ``128 + signal``. A second signal ends it at once the same way.
* :func:`restore` -- the previous handlers back, the watchdog disarmed.

A signal the process was started with ignored stays ignored in every stage, as Python itself
keeps an ignored SIGINT: a non-interactive shell starts a background job (``cmd &`` in a script)
with SIGINT ignored, and ``nohup``-like launchers do the same, so that a Ctrl-C meant for the
foreground does not end it. Such a command runs to its end; SIGTERM still ends it.
"""

from __future__ import annotations

import os
import signal
import sys

try:  # already imported by the interpreter's start in most programs; cheap
    import _thread
except ImportError:  # pragma: no cover
    _thread = None

__all__ = ["GRACE", "Interrupted", "install_early", "install", "restore", "check", "pending", "track", "untrack"]

#: Seconds a command has to end by itself after SIGINT/SIGTERM before it is ended for it.
GRACE = 3.0
SIGNALS = (signal.SIGINT, signal.SIGTERM)

_state = {
    "pending": None,
    "timer": None,
    "old": {},
    "prefix": "microimpact",
    "hook": None,
    "committed": False,
}
_live: dict = {}  # temporary path -> "file" or "dir", while it is being written
_lock = _thread.allocate_lock()


class Interrupted(KeyboardInterrupt):
    """SIGINT or SIGTERM during a command (a KeyboardInterrupt, so cleanup code runs)."""

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


def track(path, kind: str = "file") -> None:
    """Register a temporary file (``kind="file"``) or folder (``"dir"``) being written."""
    with _lock:
        _live[os.fspath(path)] = kind


def untrack(path) -> None:
    """It was renamed into place or removed."""
    with _lock:
        _live.pop(os.fspath(path), None)


def cleanup() -> None:
    """Remove every registered temporary file and folder."""
    with _lock:
        items = list(_live.items())
        _live.clear()
    for path, kind in items:
        try:
            if kind == "dir":
                import shutil

                shutil.rmtree(path, ignore_errors=True)
            else:
                os.unlink(path)
        except OSError:
            pass


def committed() -> None:
    """An output was renamed into place (:mod:`microimpact.io`, with signals held).

    From then on a signal no longer interrupts the command where it is: the output in place is
    complete and new, and an exit status of ``128 + signal`` would say the old one was kept. The
    signal is remembered (:func:`late`), the watchdog armed, and the command goes on to its end
    (exit 0) -- or to its next output, which :func:`check` then refuses to put in place.
    """
    _state["committed"] = True


def late() -> bool:
    """True if the pending signal came after an output was put in place (see :func:`committed`).

    A signal pending before that is raised before the rename (:func:`check`), so an output is
    never committed with a signal already pending: pending and committed means late.
    """
    return _state["committed"] and _state["pending"] is not None


def pending():
    """The signal number received during the command and not yet reported, or None."""
    return _state["pending"]


def check() -> None:
    """Raise :class:`Interrupted` if a signal arrived (its exception may have been swallowed)."""
    signum = _state["pending"]
    if signum is not None:
        raise Interrupted(signum)


def _end(signum) -> None:
    """End the process now: temporary files removed, one line, exit ``128 + signal``."""
    cleanup()
    try:
        os.write(2, (message(signum) + "\n").encode())
    except OSError:
        pass
    os._exit(128 + int(signum))


def _early(signum, frame):
    _end(signum)


def _raise(signum, frame):
    if _state["pending"] is not None:  # a second signal: end now
        _end(_state["pending"])
    _state["pending"] = int(signum)
    import threading

    timer = threading.Timer(GRACE, _end, args=(int(signum),))
    timer.daemon = True
    timer.start()
    _state["timer"] = timer
    if _state["committed"]:  # an output is in place, complete: see committed() and late()
        return
    raise Interrupted(signum)


def _in_main_thread() -> bool:
    threading = sys.modules.get("threading")
    return threading is None or threading.current_thread() is threading.main_thread()


def install_early() -> None:
    """Until the command starts: a signal ends the process at once (nothing written yet)."""
    if not _in_main_thread():
        return
    for sig in SIGNALS:
        try:
            if signal.getsignal(sig) in (signal.default_int_handler, signal.SIG_DFL):
                signal.signal(sig, _early)
        except (ValueError, OSError):  # pragma: no cover - not settable here
            pass


def running_as_command() -> bool:
    """True while ``python -m microimpact`` locates the package, or when the process is ``microimpact``."""
    argv0 = sys.argv[0] if sys.argv else ""
    return argv0 == "-m" or os.path.basename(argv0) in ("microimpact", "microimpact.exe")


def _unraisable(unraisable):
    """Python prints an exception raised where it cannot propagate (a weakref callback, a ``__del__``):
    for our interrupt, say nothing -- it is pending, and :func:`check` or the watchdog acts on it. Once
    an interrupt is pending, say nothing of the others either: they come from what the interrupt cut
    short (an object half built when it came, whose ``__del__`` then fails: llvmlite's ``PassBuilder``
    interrupted inside numba's compiler)."""
    if isinstance(unraisable.exc_value, Interrupted) or _state["pending"] is not None:
        return
    (_state["hook"] or sys.__unraisablehook__)(unraisable)


def _silent(unraisable):
    """The hook of a process leaving after an interrupt (:func:`restore` with ``exiting``)."""


def install() -> None:
    """During a command: the first signal raises :class:`Interrupted` and arms the watchdog."""
    if not _in_main_thread():
        return
    _state["pending"] = None
    _state["committed"] = False
    if sys.unraisablehook is not _unraisable:
        _state["hook"] = sys.unraisablehook
        sys.unraisablehook = _unraisable
    for sig in SIGNALS:
        try:
            if signal.getsignal(sig) == signal.SIG_IGN:
                continue  # started ignoring it (a background job of a script, nohup): it stays ignored
            _state["old"][sig] = signal.signal(sig, _raise)
        except (ValueError, OSError):  # pragma: no cover
            pass


def restore(exiting: bool = False) -> None:
    """The handlers from before :func:`install`; the watchdog disarmed; nothing pending.

    ``exiting``: the process ends now after an interrupt (the command's entry point): exceptions
    Python cannot raise (in a ``__del__`` the garbage collector runs on the way out) stay unreported,
    for they come from what the interrupt cut short.
    """
    timer = _state["timer"]
    if timer is not None:
        timer.cancel()
        _state["timer"] = None
    if _in_main_thread():
        for sig, handler in _state["old"].items():
            try:
                signal.signal(sig, handler)
            except (ValueError, OSError, TypeError):  # pragma: no cover
                pass
    _state["old"] = {}
    _state["pending"] = None
    _state["committed"] = False
    if sys.unraisablehook is _unraisable:
        sys.unraisablehook = _silent if exiting else (_state["hook"] or sys.__unraisablehook__)
        _state["hook"] = None
