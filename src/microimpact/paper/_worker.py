"""Figures of :func:`~microimpact.paper.reproduce` drawn in other processes, beside the calling one.

The other processes are a :class:`concurrent.futures.ProcessPoolExecutor` (:class:`Pool`). Each
figure is a job, :func:`draw`: its stem and table in, its image bytes out (the same function the
caller draws its own figures with, :func:`._draw.draw_figure`: a figure's bytes depend neither on
the process that draws it nor on the figures drawn before it), with the warnings raised while
drawing, which the caller raises again. A worker writes no file.

The caller draws the figures from the first on; a :class:`Feeder` hands them to a worker from the
last on, one at a time and only once the worker has started (:func:`prepare`), so that a worker
still starting never holds a figure the caller could draw itself, and the two meet in the middle.
A job the worker fails (its error, or its process ending) is the caller's to draw.

The processes (:class:`Pool`) are started with the ``spawn`` method, on every platform. ``fork`` starts fastest
(the child shares the parent's imports) but copies a process in whatever state it is: the locks
held by its other threads (a numerical library's thread pool, an application's threads) stay held
in the child, and the font files it has open are shared with it, one read position for both.
``forkserver`` forks from a clean server, but each child still imports the plotting stack, as a
spawned one does, and it exists on POSIX only. ``spawn`` costs a fresh interpreter and its imports
(about a second of CPU, paid while the caller computes the tables), and gives the same, clean
worker wherever it runs; the caller's rcParams travel with each job.

A spawned interpreter first runs the caller's main module again, as ``__mp_main__`` (that is how
the ``spawn`` method finds what the caller defined there). For ``python -m microimpact``, for
``python -c`` or an interactive session that is nothing; for a script it is the script's top level,
which is harmless only behind an ``if __name__ == "__main__":`` guard. :func:`can_start` tells which:
where the worker would run the caller's own code again, the figures are drawn in one process.

Interrupts belong to the caller: a worker ignores SIGINT (a Ctrl-C at a terminal reaches the whole
process group), from as soon as the pool starts it (the pool's initializer is ``signal.signal``
itself, so that nothing of this package is imported before it); it installs no handler. The caller
ends the workers when it is done or unwinds (:meth:`Pool.stop`).
"""

from __future__ import annotations

import ast
import multiprocessing
import signal
import sys
import threading
import time
import warnings
from concurrent.futures import ProcessPoolExecutor


def can_start() -> bool:
    """Whether a spawned worker can start without running the calling program's code again.

    The rule is :mod:`multiprocessing`'s (``spawn``): a main module without a file (``python -c``, an
    interactive session) or a package's ``__main__`` (``python -m microimpact``) is not run again;
    any other main module is, as ``__mp_main__``, and is harmless only when its top level defines
    and imports but computes nothing: definitions, imports, assignments without a call, and
    ``if __name__ == "__main__":`` blocks (a console script's wrapper is one).
    """
    main = sys.modules.get("__main__")
    name = getattr(getattr(main, "__spec__", None), "name", None)
    if name is None and getattr(main, "__file__", None) is None:
        return True
    if name is not None and (name == "__main__" or name.endswith(".__main__")):
        return True
    try:
        with open(main.__file__, "rb") as fh:
            tree = ast.parse(fh.read())
    except (OSError, SyntaxError, ValueError, TypeError):
        return False
    return all(_defines_only(node) for node in tree.body)


def _defines_only(node) -> bool:
    """Whether a top-level statement of a main module only defines or imports something."""
    if isinstance(node, (ast.Import, ast.ImportFrom, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return True
    if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant):  # a docstring
        return True
    if isinstance(node, (ast.Assign, ast.AnnAssign)):
        return node.value is None or not any(isinstance(n, ast.Call) for n in ast.walk(node.value))
    if isinstance(node, ast.If):  # if __name__ == "__main__": (either way round)
        test = node.test
        if isinstance(test, ast.Compare) and len(test.ops) == 1 and isinstance(test.ops[0], ast.Eq):
            sides = [test.left, test.comparators[0]]
            names = [n for n in sides if isinstance(n, ast.Name) and n.id == "__name__"]
            texts = [n for n in sides if isinstance(n, ast.Constant) and n.value == "__main__"]
            return len(names) == 1 and len(texts) == 1 and all(_defines_only(n) for n in node.orelse)
    return False


class Pool:
    """``workers`` spawned processes, started now (their imports overlap the caller's work), each
    told at once to :func:`prepare`: :attr:`ready` holds those futures, :attr:`executor` the pool.

    :meth:`stop` ends them at once, whatever they are doing: they hold nothing the caller needs by
    then (every answer it wanted is in, or it is unwinding from an interrupt), and waiting for a
    worker to finish a figure, or its imports on a busy machine, would hold an interrupted command
    for seconds. :class:`~concurrent.futures.ProcessPoolExecutor` has no public way to end a
    running worker before Python 3.14, so the processes are the children it started, as
    :func:`multiprocessing.active_children` lists them.
    """

    def __init__(self, workers: int):
        self._before = set(multiprocessing.active_children())
        self.executor = ProcessPoolExecutor(
            max_workers=workers,
            mp_context=multiprocessing.get_context("spawn"),
            initializer=signal.signal,
            initargs=(signal.SIGINT, signal.SIG_IGN),
        )
        self.ready = [self.executor.submit(prepare) for _ in range(workers)]

    def stop(self) -> None:
        """End the workers now, then the pool (its threads and queues)."""
        for proc in multiprocessing.active_children():
            if proc not in self._before:
                proc.terminate()
        self.executor.shutdown(wait=True, cancel_futures=True)


def prepare() -> None:
    """What the first figure needs: pyplot and the default formats' printers."""
    import matplotlib.backends.backend_agg  # noqa: F401
    import matplotlib.backends.backend_pdf  # noqa: F401

    from ..figures import style

    style.pyplot()


def draw(stem, table, formats, rc):
    """``(images, warnings, seconds)`` of figure ``stem`` drawn from ``table`` with the caller's ``rc``."""
    from ._draw import draw_figure

    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        images = draw_figure(stem, table, formats, rc)
    said = [(w.message, w.category, w.filename, w.lineno) for w in caught]
    return images, said, time.perf_counter() - t0


class Feeder:
    """The thread that hands one worker its figures, from the back of the caller's list.

    ``jobs`` is shared with the caller: ``jobs["lo"]`` is the next figure the caller draws,
    ``jobs["hi"]`` the next one for a worker; both move under ``lock`` until they cross. A figure
    taken by a worker is recorded in ``taken`` (index -> future) in the same step, so that once the
    caller finds nothing left to draw, ``taken`` names every figure it must collect.
    """

    def __init__(self, pool, ready, jobs, lock, taken, tables, formats, rc):
        self.pool, self.ready, self.jobs, self.lock, self.taken = pool, ready, jobs, lock, taken
        self.tables, self.formats, self.rc = tables, formats, rc
        self.stop = False
        self.thread = threading.Thread(target=self._run, name="microimpact-paper-feeder", daemon=True)
        self.thread.start()

    def _run(self) -> None:
        try:
            self._feed()
        except BaseException:  # noqa: BLE001 - a future cancelled by the pool's shutdown: nothing more to feed
            pass

    def _feed(self) -> None:
        if self.ready.exception() is not None:  # the worker did not start: the caller draws everything
            return
        while True:
            with self.lock:  # taken and recorded in one step: the caller sees it either to draw or taken
                if self.stop or self.jobs["hi"] < self.jobs["lo"]:
                    return
                i = self.jobs["hi"]
                try:
                    future = self.pool.submit(draw, *self.tables[i], self.formats, self.rc)
                except RuntimeError:  # the pool is shut down or broken: the figure stays the caller's
                    return
                self.jobs["hi"] -= 1
                self.taken[i] = future
            if future.exception() is not None:  # no more jobs for a worker that failed one (the caller redraws it)
                return
