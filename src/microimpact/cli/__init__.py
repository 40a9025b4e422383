"""Command-line interface: ``microimpact <command> ...``.

Each command lives in its own module of this package and registers itself
through ``register(subparsers)``; the commands only parse arguments, check every
input and output path before computing (:mod:`microimpact.cli._common`), and
call the public API, which writes every file through :mod:`microimpact.io`.

Failures (:func:`main`): every expected failure is one line on stderr naming the
option or the file, never a traceback --

* bad input (:class:`ValueError`, including a size over the memory budget) and
  missing optional extras: exit status 2;
* operating-system errors of any kind (:class:`OSError`: a missing or read-only
  directory, a full disk, a file where a directory is expected): exit 2, the
  message naming the file;
* an interrupt: Ctrl-C (SIGINT) and SIGTERM both raise :class:`Interrupted` (a
  :class:`KeyboardInterrupt`) inside the command, so every temporary file is
  removed and the previous output is left intact; one line ``interrupted``, exit
  ``128 + signal`` (130 for SIGINT, 143 for SIGTERM). The handlers are the
  command's (:mod:`microimpact.cli._interrupt`), installed by :func:`main` for
  its run only: ``import microimpact`` changes nothing of the process.

Any other exception is a bug: its traceback is printed, so it stays visible.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import os
import signal
import sys
import warnings

from .._optional import MissingExtraError
from . import _interrupt
from ._argv import NumberValuesParser
from ._interrupt import Interrupted  # noqa: F401  (re-exported: the exception a signal raises)

#: Subcommand modules, in the order ``--help`` lists them.
COMMANDS = [
    "impact",
    "history",
    "compare",
    "paper",
    "sweep",
    "fit",
    "export",
    "bench",
    "materials",
    "oblique",
    "stick",
    "dem_check",
    "cache",
]


class Parser(NumberValuesParser):
    """An ArgumentParser whose usage errors are one line on stderr (exit 2), and which reads
    ``-1e9`` or ``-5:5:11`` as a value rather than as an option (:mod:`microimpact.cli._argv`)."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


class _Version(argparse.Action):
    """``--version``: prints the version (:mod:`microimpact._version`) and exits."""

    def __call__(self, parser, namespace, values, option_string=None):
        from .._version import __version__

        print(f"microimpact {__version__}")  # stdout, as argparse's own version action
        parser.exit(0)


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The command-line parser; with ``only``, just that command's (the others are not imported)."""
    parser = Parser(
        prog="microimpact",
        description="Elastic-plastic impact of micro-particles on surfaces "
        "(Aerosol Sci. Tech. 50(4), 2016): restitution, energy loss, contact times, histories.",
    )
    parser.add_argument("--version", action=_Version, nargs=0, help="show the version and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in [only] if only in COMMANDS else COMMANDS:
        importlib.import_module(f".{name}", __name__).register(sub)
    return parser


def _short_warning(message, category, filename, lineno, file=None, line=None):
    return f"warning: {message}\n"


def error_message(exc: BaseException) -> str:
    """One line describing an expected failure, naming the file for an OSError."""
    if isinstance(exc, OSError):
        what = exc.strerror or (str(exc).splitlines()[0] if str(exc) else exc.__class__.__name__)
        if exc.filename is not None and exc.filename2 is not None:
            return f"{os.fsdecode(exc.filename)} -> {os.fsdecode(exc.filename2)}: {what}"
        if exc.filename is not None:
            return f"{os.fsdecode(exc.filename)}: {what}"
        return what
    if isinstance(exc, UnicodeDecodeError):
        return f"not UTF-8 text: byte 0x{exc.object[exc.start]:02x} at offset {exc.start}"
    text = str(exc).strip()
    return text.splitlines()[0] if text else exc.__class__.__name__


def _silence_stdout() -> None:
    """Point stdout at /dev/null so the interpreter's final flush does not fail again."""
    with contextlib.suppress(OSError, ValueError, AttributeError):
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())


class _NamedStdout:
    """Standard output whose write errors (a full disk, a closed pipe) name it in the message."""

    def __init__(self, stream):
        self._stream = stream

    def _call(self, name, *a):
        try:
            return getattr(self._stream, name)(*a)
        except OSError as exc:
            if exc.filename is None and not isinstance(exc, BrokenPipeError):
                exc.filename = "<standard output>"
                _silence_stdout()
            raise

    def write(self, text):
        return self._call("write", text)

    def writelines(self, lines):
        return self._call("writelines", lines)

    def flush(self):
        return self._call("flush")

    def __getattr__(self, name):
        return getattr(self._stream, name)


def main(argv=None, *, _exiting=False) -> int:
    """Entry point of the ``microimpact`` command; returns the exit status."""
    try:
        _interrupt.install()  # from the start: a signal while parsing is an interrupt too
        return _main(argv)
    except BaseException as exc:
        # an interrupt, or what a library made of one (a C extension's import turns it into
        # "ImportError: initialization failed"): one line and 128 + signal, never a traceback
        signum = getattr(exc, "signum", None) or _interrupt.pending()
        if signum is None and isinstance(exc, KeyboardInterrupt):
            signum = signal.SIGINT
        if signum is None:
            raise
        print(_interrupt.message(signum), file=sys.stderr)
        return 128 + int(signum)
    finally:
        _interrupt.restore(exiting=_exiting)


def _main(argv):
    argv = sys.argv[1:] if argv is None else list(argv)
    _interrupt.set_prefix("microimpact")
    # Import only the command being run: a command's dependencies cost more than its work.
    parser = build_parser(only=argv[0] if argv and argv[0] in COMMANDS else None)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version, or a usage error already printed
        return int(exc.code or 0) if not isinstance(exc.code, str) else 2
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    prefix = f"microimpact {args.command}"
    _interrupt.set_prefix(prefix)
    stdout = sys.stdout
    if stdout is None:  # started with standard output closed (microimpact impact 50 >&-): before any work
        print(
            f"{prefix}: error: <standard output>: closed (redirect it instead: > FILE or > /dev/null)", file=sys.stderr
        )
        return 2
    from ..io import commit_check

    try:
        sys.stdout = _NamedStdout(stdout)
        format_before = warnings.formatwarning
        try:
            # a swallowed interrupt stops the command before its outputs appear
            with warnings.catch_warnings(), commit_check(_interrupt.check):
                # while the command runs: each warning on one short line, and microimpact's deprecations
                # shown (Python's default filters show a DeprecationWarning only where __main__ calls the
                # deprecated name, never to the person at the command line)
                warnings.formatwarning = _short_warning
                warnings.filterwarnings("default", category=DeprecationWarning, module="microimpact")
                rc = args.func(args)
            sys.stdout.flush()
        finally:
            sys.stdout = stdout
            warnings.formatwarning = format_before
        _interrupt.check()  # an interrupt whose exception was swallowed on the way (in a __del__, a callback)
    except KeyboardInterrupt:
        raise
    except BrokenPipeError:  # e.g. piped into head: stop quietly
        _silence_stdout()
        return 0
    except (ValueError, MissingExtraError, OSError, MemoryError) as exc:
        if _interrupt.pending() is not None:  # what a library made of an interrupt
            raise Interrupted(_interrupt.pending()) from None
        if isinstance(exc, MemoryError):
            msg = "out of memory (see MICROIMPACT_MAX_MEMORY and give smaller sizes)"
        else:
            msg = error_message(exc)
        print(f"{prefix}: error: {msg}", file=sys.stderr)
        return 2
    return int(rc or 0)


def console_main() -> int:
    """The ``microimpact`` command (and ``python -m microimpact``): :func:`main`; returns its exit status.

    The process's entry point: once :func:`main` has returned, the work is done and every output
    in place (or cleaned up after an interrupt), and from then on the process ignores SIGINT and
    SIGTERM while it exits. Python's finalization puts the default handler back for every signal
    it handled (not for an ignored one) and then frees every module: a signal in that window (up
    to a tenth of a second after an export) killed a finished run with a bare -15 and no line.
    After an interrupt the process ends at once: it does not wait for worker threads of a chunked
    sweep that may still hold queued blocks (dask's pool finishes its queue at exit), which could
    keep a SIGTERM'd run alive. (Called in a running program, it leaves SIGINT and SIGTERM
    ignored: use :func:`main` there.)
    """
    rc = main(_exiting=True)
    for sig in (signal.SIGINT, signal.SIGTERM):
        try:
            signal.signal(sig, signal.SIG_IGN)
        except (ValueError, OSError):  # pragma: no cover - not the main thread
            pass
    if rc in (128 + signal.SIGINT, 128 + signal.SIGTERM):
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os._exit(rc)
    return rc


if __name__ == "__main__":  # pragma: no cover
    sys.exit(console_main())
