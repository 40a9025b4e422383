"""Command-line interface: ``microimpact <command> ...``.

Each command lives in its own module of this package and registers itself
through ``register(subparsers)``; the commands only parse arguments and call
the public API. Errors in the input (``ValueError``) and missing optional
extras become one line on stderr and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import re
import sys
import warnings

from .._optional import MissingExtraError

#: Subcommand modules, in the order ``--help`` lists them.
COMMANDS = ["impact", "history", "paper", "sweep", "fit", "export", "bench", "materials"]


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

        parser.exit(0, f"microimpact {__version__}\n")


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


def main(argv=None) -> int:
    """Entry point of the ``microimpact`` command; returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    # Import only the command being run: a command's dependencies cost more than its work.
    parser = build_parser(only=argv[0] if argv and argv[0] in COMMANDS else None)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version, or a usage error already printed
        return int(exc.code or 0)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    warnings.formatwarning = _short_warning
    try:
        rc = args.func(args)
    except (ValueError, MissingExtraError, FileNotFoundError, IsADirectoryError) as exc:
        msg = str(exc).splitlines()[0] if str(exc) else exc.__class__.__name__
        print(f"microimpact {args.command}: error: {msg}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # e.g. piped into head
        return 0
    return int(rc or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
