"""Command-line interface: ``microimpact <command> ...``.

Each command lives in its own module of this package and registers itself
through ``register(subparsers)``; the commands only parse arguments and call
the public API. Errors in the input (``ValueError``) and missing optional
extras become one line on stderr and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import warnings

from .._optional import MissingExtraError

#: Subcommand modules, in the order ``--help`` lists them.
COMMANDS = ["impact", "history", "paper", "sweep", "fit", "export", "bench", "materials"]


def build_parser() -> argparse.ArgumentParser:
    from .. import __version__

    parser = argparse.ArgumentParser(
        prog="microimpact",
        description="Elastic-plastic impact of micro-particles on surfaces "
        "(Aerosol Sci. Tech. 50(4), 2016): restitution, energy loss, contact times, histories.",
    )
    parser.add_argument("--version", action="version", version=f"microimpact {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMANDS:
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
    parser = build_parser()
    args = parser.parse_args(argv)
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
