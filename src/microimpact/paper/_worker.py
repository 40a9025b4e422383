"""Figures of :func:`~microimpact.paper.reproduce` drawn in a second process, beside the first.

The worker is forked from the caller where that is safe (:func:`can_fork`: Linux, no other thread),
once the caller has imported matplotlib, so that it shares the caller's imports; elsewhere it is a
new interpreter (:func:`main`, started by :class:`Helper` as ``python -c`` code, never by hand).
Either reads pickled jobs from a pipe and writes pickled answers to another (:func:`_serve`); it
writes no file. The first message is the caller's rcParams and image formats; each job is a
figure's stem and table, answered with the figure's image bytes (:func:`._draw.draw_figure`, the same
function the caller draws its own figures with: a figure's bytes do not depend on the process
that draws it nor on the figures drawn before it) and the warnings raised while drawing, which
the caller raises again. SIGINT is ignored (a Ctrl-C reaches the whole process group; the caller
handles it and ends this process); SIGTERM ends it at once; an end of input ends it. A forked worker
leaves by ``os._exit`` whatever happens: it never runs the caller's code after the fork.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import signal
import subprocess
import sys
import threading
import time
import warnings
from pathlib import Path

_READY = "ready"


def main() -> int:
    """The worker's loop (the child side), in a new interpreter."""
    _worker_signals()
    # The answers go to the pipe that was the standard output; anything a library prints goes to stderr.
    out = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)
    inp = sys.stdin.buffer
    from ._draw import defer_font_subsetting

    defer_font_subsetting()
    _prepare()
    return _ready_then_serve(inp, out)


def _worker_signals() -> None:
    """SIGINT ignored (a Ctrl-C reaches the whole process group: the caller ends this process);
    SIGTERM ends it at once."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _ready_then_serve(inp, out) -> int:
    """Say the worker is ready, then answer jobs (:func:`_serve`)."""
    pickle.dump(_READY, out)
    out.flush()
    return _serve(inp, out)


def _prepare() -> None:
    """What the first figure needs: pyplot and the default formats' printers."""
    import matplotlib.backends.backend_agg  # noqa: F401
    import matplotlib.backends.backend_pdf  # noqa: F401

    from ..figures import style

    style.pyplot()


def _serve(inp, out) -> int:
    """Answer jobs read from ``inp`` on ``out`` until the end of ``inp``."""
    from ._draw import draw_figure, one_mathtext_cache

    try:
        rc, formats = pickle.load(inp)
    except EOFError:
        return 0
    with one_mathtext_cache():  # mathtext parsed once for all the figures this process draws
        while True:
            try:
                stem, table = pickle.load(inp)
            except EOFError:
                return 0
            t0 = time.perf_counter()
            try:
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    images = draw_figure(stem, table, formats, rc)
                said = [(w.message, w.category, w.filename, w.lineno) for w in caught]
                answer = ("ok", images, said, time.perf_counter() - t0)
            except Exception as exc:  # the caller draws this figure itself, and meets the error there
                answer = ("error", repr(exc), [], 0.0)
            try:
                pickle.dump(answer, out)
            except Exception:  # an answer that does not pickle (a warning's odd message): the caller redraws
                pickle.dump(("error", "answer not picklable", [], 0.0), out)
            out.flush()


# ----------------------------------------------------------------------------- a forked worker
# The ends of the pipes this process keeps for its forked workers: a worker forked later closes them
# (else a worker would not see the end of its input when this process ends).
_KEPT_FDS: set = set()


def can_fork() -> bool:
    """True where a worker is forked from this process rather than started as a new interpreter: Linux
    (macOS's system libraries do not survive a fork), and no thread but this one (a lock another
    thread held at the fork would stay held in the worker), numba's threading layer included: its
    threads are not Python's, and of its layers only ``workqueue`` and TBB are fork-safe on Linux,
    GNU OpenMP is not (numba 0.68, ``numba/np/ufunc/parallel.py``, the "forksafe" choice). So no
    fork once that layer has started (a compiled loop over 50,000 values or more)."""
    parallel = sys.modules.get("numba.np.ufunc.parallel")
    started = bool(getattr(parallel, "_is_initialized", False))
    return sys.platform.startswith("linux") and hasattr(os, "fork") and threading.active_count() == 1 and not started


class _Forked:
    """A forked worker, with the part of :class:`subprocess.Popen`'s interface :class:`Helper` uses."""

    def __init__(self, pid, stdin, stdout):
        self.pid, self.stdin, self.stdout = pid, stdin, stdout
        self.returncode = None

    def poll(self):
        if self.returncode is None:
            try:
                pid, status = os.waitpid(self.pid, os.WNOHANG)
            except ChildProcessError:  # pragma: no cover - reaped elsewhere
                self.returncode = -1
            else:
                if pid:
                    self.returncode = os.waitstatus_to_exitcode(status)
        return self.returncode

    def kill(self):
        with contextlib.suppress(ProcessLookupError):
            os.kill(self.pid, signal.SIGKILL)

    def wait(self, timeout=None):
        end = None if timeout is None else time.monotonic() + timeout
        while self.poll() is None:
            if end is not None and time.monotonic() > end:
                raise subprocess.TimeoutExpired(f"worker {self.pid}", timeout)
            time.sleep(0.005)
        return self.returncode


def _fork():
    """A worker forked from this process once it has imported what the figures need: it shares this
    process's imports (a new interpreter imports them again, about 1 CPU-s). The child answers jobs
    until the end of its input and leaves with ``os._exit``: it never returns into this process's
    code (its ``finally`` blocks, its staging folder), whatever happens."""
    from ._draw import forget_open_fonts

    _prepare()
    jobs_r, jobs_w = os.pipe()
    answers_r, answers_w = os.pipe()
    for stream in (sys.stdout, sys.stderr):  # nothing buffered here is written twice
        with contextlib.suppress(Exception):
            stream.flush()
    try:
        pid = os.fork()
    except OSError:
        for fd in (jobs_r, jobs_w, answers_r, answers_w):
            os.close(fd)
        raise
    if pid == 0:  # the worker
        code = 1
        try:
            _worker_signals()
            for fd in (jobs_w, answers_r, *_KEPT_FDS):
                os.close(fd)
            os.dup2(2, 1)  # the caller's standard output is its own
            forget_open_fonts()  # their files' read position is the caller's too
            code = _ready_then_serve(os.fdopen(jobs_r, "rb"), os.fdopen(answers_w, "wb"))
        except BaseException:  # noqa: BLE001 - whatever it is, this process leaves here
            pass
        finally:
            os._exit(code)
    os.close(jobs_r)
    os.close(answers_w)
    _KEPT_FDS.update((jobs_w, answers_r))
    return _Forked(pid, os.fdopen(jobs_w, "wb"), os.fdopen(answers_r, "rb"))


def _boot() -> str:
    """The worker's ``python -c`` code: it imports the caller's microimpact, wherever the caller found it.

    The path's first entry (the working directory, for ``-c``) becomes the folder holding the
    caller's package, or goes when that folder is a site directory the child searches anyway
    (an installed package), so that nothing in the working directory shadows a module.
    """
    import site
    import sysconfig

    root = os.path.realpath(Path(__file__).resolve().parents[2])  # .../microimpact/paper/_worker.py
    sites = set()
    with contextlib.suppress(Exception):
        sites.update(site.getsitepackages())
    with contextlib.suppress(Exception):
        sites.add(site.getusersitepackages())
    sites.update(sysconfig.get_paths().get(k, "") for k in ("purelib", "platlib"))
    first = "del sys.path[0]" if root in {os.path.realpath(p) for p in sites if p} else f"sys.path[0] = {root!r}"
    return f"import sys; {first}; from microimpact.paper._worker import main; sys.exit(main())"


class Helper:
    """One worker process and the thread that feeds it figures from the back of a shared queue.

    :meth:`start` launches the process at once (its imports overlap the caller's work);
    :meth:`feed` starts the thread, which takes a job only once the worker is ready, so that a
    worker still starting never holds a figure the caller could have drawn; :meth:`finish` waits
    for the job it holds; :meth:`close` ends both (always called, in a ``finally``). Any failure
    of the worker (it cannot start, dies, answers an error) leaves its job in ``failed``: the
    caller draws it.
    """

    def __init__(self):
        self.proc = None
        self.thread = None
        self.failed = []
        self.holding = None
        self._stop = False

    def start(self) -> None:
        if can_fork():
            try:
                self.proc = _fork()
                return
            except OSError:  # no fork here (a process limit): a new interpreter, as elsewhere
                self.proc = None
        try:
            self.proc = subprocess.Popen(
                [sys.executable, "-c", _boot()],
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                stderr=subprocess.DEVNULL,
            )
        except OSError:
            self.proc = None

    def feed(self, queue, lock, tables, rc, formats, done) -> None:
        """Start feeding: jobs are indices taken from the back of ``queue`` (a deque shared with the
        caller, under ``lock``) into ``tables``; ``done(i, answer)`` takes each answer."""
        if self.proc is None:
            return
        self.thread = threading.Thread(
            target=self._run,
            args=(queue, lock, tables, rc, formats, done),
            name="microimpact-paper-worker",
            daemon=True,
        )
        self.thread.start()

    def _run(self, queue, lock, tables, rc, formats, done) -> None:
        try:
            if pickle.load(self.proc.stdout) != _READY:
                return
            pickle.dump((rc, formats), self.proc.stdin)
            self.proc.stdin.flush()
            while not self._stop:
                with lock:  # taken and held in one step: the caller sees either the job queued or held
                    if not queue:
                        return
                    self.holding = i = queue.pop()
                pickle.dump(tables[i], self.proc.stdin)
                self.proc.stdin.flush()
                answer = pickle.load(self.proc.stdout)
                if answer[0] != "ok":
                    return  # no more jobs for a worker that failed one
                done(i, answer)
                self.holding = None
        except Exception:  # the worker died or closed its pipe
            pass
        finally:
            if self.holding is not None:  # the caller draws what the worker held
                self.failed.append(self.holding)
                self.holding = None

    def finish(self) -> None:
        """Wait until the worker holds no figure: its answer is in, or its failure noted in ``failed``.
        (A worker still starting holds none: it is not waited for.) Short waits, so that a signal's
        handler runs between them."""
        while self.thread is not None and self.thread.is_alive() and self.holding is not None:
            self.thread.join(0.05)

    def close(self) -> None:
        """End the worker (at once, if it is still drawing) and then the thread, which its end unblocks."""
        self._stop = True
        proc = self.proc
        if proc is None:
            return
        if proc.poll() is None:
            proc.kill()
        try:
            proc.wait(timeout=5)
        except subprocess.TimeoutExpired:  # pragma: no cover - a killed process that does not end
            pass
        if self.thread is not None:
            self.thread.join(1.0)
        for pipe in (proc.stdin, proc.stdout):
            with contextlib.suppress(Exception):
                _KEPT_FDS.discard(pipe.fileno())
            try:
                pipe.close()
            except Exception:
                pass


if __name__ == "__main__":
    sys.exit(main())
