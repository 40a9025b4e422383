"""Standard output that a command's text always fits: what cannot be encoded is escaped.

Python writes ``sys.stdout`` in the locale's encoding (or ``PYTHONIOENCODING``) and raises
UnicodeEncodeError for a character outside it, where ``sys.stderr`` escapes it. A command that
prints a path or a label with such a character (``wrote hé.csv`` under ``PYTHONIOENCODING=ascii``)
would fail after its work is done and its files are written, and report the finished run as an
error. While a command runs, its standard output escapes such characters as stderr does
(``h\\xe9.csv``): the text says what was done, the exit status stays that of the work.
"""

from __future__ import annotations

import functools
import sys

__all__ = ["encodable_stdout"]


class _EscapingStdout:
    """Wraps a text stream: text the stream's encoding cannot hold is written with backslash escapes."""

    def __init__(self, stream):
        self._stream = stream

    def write(self, text):
        try:
            return self._stream.write(text)
        except UnicodeEncodeError:  # raised while encoding, before anything of ``text`` is written
            encoding = getattr(self._stream, "encoding", None) or "ascii"
            return self._stream.write(text.encode(encoding, "backslashreplace").decode(encoding))

    def writelines(self, lines):
        for line in lines:
            self.write(line)

    def __getattr__(self, name):
        return getattr(self._stream, name)


def encodable_stdout(run):
    """``run(args)`` with :data:`sys.stdout` escaping what its encoding cannot hold (restored after)."""

    @functools.wraps(run)
    def wrapped(args):
        stream = sys.stdout
        if stream is None:
            return run(args)
        sys.stdout = _EscapingStdout(stream)
        try:
            return run(args)
        finally:
            sys.stdout = stream

    return wrapped
