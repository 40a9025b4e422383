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
* an interrupt: Ctrl-C (SIGINT) and SIGTERM both raise :class:`KeyboardInterrupt`
  inside the command, so every temporary file is removed and the previous
  output is left intact; one line ``interrupted``, exit ``128 + signal``
  (130 for SIGINT, 143 for SIGTERM).

Any other exception is a bug: its traceback is printed, so it stays visible.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import os
import re
import signal
import sys
import warnings

from .._optional import MissingExtraError

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
]


class Parser(argparse.ArgumentParser):
    """An ArgumentParser whose usage errors are one line on stderr (exit 2), and which reads
    ``-1e9`` as a negative number rather than as an option."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


class _Version(argparse.Action):
    """``--version``: reads the version from the package metadata only when asked."""

    def __call__(self, parser, namespace, values, option_string=None):
        from .. import __version__

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
        try:
            mod = importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as exc:  # a command not yet built
            if exc.name == f"{__name__}.{name}":
                continue
            raise
        mod.register(sub)
    return parser


def _short_warning(message, category, filename, lineno, file=None, line=None):
    return f"warning: {message}\n"


class Interrupted(KeyboardInterrupt):
    """SIGINT or SIGTERM during a command (a KeyboardInterrupt, so cleanup code runs)."""

    def __init__(self, signum=signal.SIGINT):
        super().__init__(signum)
        self.signum = int(signum)


def _raise_interrupt(signum, frame):
    raise Interrupted(signum)


@contextlib.contextmanager
def _interrupts_raise():
    """During a command, SIGINT and SIGTERM raise :class:`Interrupted` (main thread only)."""
    old = {}
    for sig in (signal.SIGINT, signal.SIGTERM):
        try:
            old[sig] = signal.signal(sig, _raise_interrupt)
        except (ValueError, OSError):  # not the main thread: leave the handlers alone
            pass
    try:
        yield
    finally:
        for sig, handler in old.items():
            signal.signal(sig, handler)


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


def main(argv=None) -> int:
    """Entry point of the ``microimpact`` command; returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    # Import only the command being run: a command's dependencies cost more than its work.
    parser = build_parser(only=argv[0] if argv and argv[0] in COMMANDS else None)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version, or a usage error already printed
        return int(exc.code or 0) if not isinstance(exc.code, str) else 2
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    warnings.formatwarning = _short_warning
    prefix = f"microimpact {args.command}"
    stdout = sys.stdout
    try:
        with _interrupts_raise():
            sys.stdout = _NamedStdout(stdout)
            try:
                rc = args.func(args)
                sys.stdout.flush()
            finally:
                sys.stdout = stdout
    except KeyboardInterrupt as exc:
        signum = getattr(exc, "signum", signal.SIGINT)
        name = "SIGTERM" if signum == signal.SIGTERM else "Ctrl-C"
        print(f"{prefix}: interrupted ({name}); nothing was left half-written", file=sys.stderr)
        return 128 + int(signum)
    except BrokenPipeError:  # e.g. piped into head: stop quietly
        _silence_stdout()
        return 0
    except (ValueError, MissingExtraError, OSError, MemoryError) as exc:
        if isinstance(exc, MemoryError):
            msg = "out of memory (see MICROIMPACT_MAX_MEMORY and give smaller sizes)"
        else:
            msg = error_message(exc)
        print(f"{prefix}: error: {msg}", file=sys.stderr)
        return 2
    return int(rc or 0)


def console_main() -> int:
    """The ``microimpact`` command (and ``python -m microimpact``): :func:`main`, then exit.

    After an interrupt the process ends at once, once :func:`main` has returned (every output is
    cleaned up by then): it does not wait for worker threads of a chunked sweep that may still hold
    queued blocks (dask's pool finishes its queue at exit), which could keep a SIGTERM'd run alive.
    """
    rc = main()
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
