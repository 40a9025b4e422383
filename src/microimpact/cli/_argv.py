"""Command-line values that begin with a minus sign: ``-1e-3``, ``-.5``, a range ``-5:5:11``, a list ``-1,2``.

argparse reads a token that begins with ``-`` as an option unless it is a plain negative number
(``-5``, ``-.5``): ``--radius -1e-3`` or ``sweep --velocity -5:5:11`` would fail with "expected one
argument" instead of reaching the parameter's own check, whose message names the parameter and
its value. :class:`NumberValuesParser` reads every token that looks like a number, a range or a
list of them (:data:`NUMBER_LIKE`) as a value, wherever it stands, through argparse's public
interface only:

* before parsing, each such token (before a ``--``) gets a marker in front, a NUL character, which
  no real command-line argument can hold; a token not starting with ``-`` is a value for argparse;
* every argument the parser (or one of its groups) adds converts its values through
  :class:`_Unmarked`, which drops the marker before the argument's own ``type``, so each action
  sees exactly the token the user gave (and a conversion error quotes it as given);
* the parser's :meth:`~NumberValuesParser.exit` drops the marker from any usage error.

No option of the command line looks like a negative number, so no option is read as a value.
"""

from __future__ import annotations

import argparse
import re
import sys

#: A number, a range ``start:stop:count`` or a comma list starting with a negative number.
NUMBER_LIKE = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?([:,].*)?$")

_MARK = "\0"
# argparse actions that take values (and so a type); the others (store_true, count, help, ...) take none
_VALUE_ACTIONS = (None, "store", "append", "extend")


def mark_values(argv) -> list:
    """``argv`` with a marker in front of each number-like token before the first ``--``."""
    out = list(argv)
    for k, token in enumerate(out):
        if token == "--":
            break
        if isinstance(token, str) and NUMBER_LIKE.match(token):
            out[k] = _MARK + token
    return out


def unmark(text: str) -> str:
    """``text`` without markers, as the user typed it (also inside a quoted repr)."""
    return text.replace(repr(_MARK)[1:-1], "").replace(_MARK, "")


class _Unmarked:
    """An argument's ``type``: the token without its marker, then the argument's own ``type``."""

    def __init__(self, type_):
        self.type = type_
        self.__name__ = getattr(type_, "__name__", repr(type_))  # argparse names the type in its errors

    def __call__(self, text):
        if not (isinstance(text, str) and text.startswith(_MARK)):
            return text if self.type is None else self.type(text)
        text = text[len(_MARK) :]
        if self.type is None:
            return text
        try:
            return self.type(text)
        except (TypeError, ValueError):  # argparse's own message, with the token as given
            raise argparse.ArgumentTypeError(f"invalid {self.__name__} value: {text!r}") from None


def _with_unmarking(kwargs: dict) -> dict:
    action = kwargs.get("action")
    takes_values = action in _VALUE_ACTIONS or (isinstance(action, type) and issubclass(action, argparse.Action))
    if takes_values and kwargs.get("nargs") != 0 and not isinstance(kwargs.get("type"), _Unmarked):
        kwargs = dict(kwargs, type=_Unmarked(kwargs.get("type")))
    return kwargs


class _Group:
    """An argument group (or mutually exclusive group) of a :class:`NumberValuesParser`: its arguments
    unmark their values too. Everything else is the group's own."""

    def __init__(self, group):
        self._group = group

    def add_argument(self, *args, **kwargs):
        return self._group.add_argument(*args, **_with_unmarking(kwargs))

    def add_argument_group(self, *args, **kwargs):
        return _Group(self._group.add_argument_group(*args, **kwargs))

    def add_mutually_exclusive_group(self, *args, **kwargs):
        return _Group(self._group.add_mutually_exclusive_group(*args, **kwargs))

    def __getattr__(self, name):
        return getattr(self._group, name)


class NumberValuesParser(argparse.ArgumentParser):
    """An ArgumentParser that reads ``-1e-3``, ``-.5``, ``-5:5:11`` and ``-1,2`` as values (module docstring)."""

    def parse_known_args(self, args=None, namespace=None):
        return super().parse_known_args(mark_values(sys.argv[1:] if args is None else args), namespace)

    def add_argument(self, *args, **kwargs):
        return super().add_argument(*args, **_with_unmarking(kwargs))

    def add_argument_group(self, *args, **kwargs):
        return _Group(super().add_argument_group(*args, **kwargs))

    def add_mutually_exclusive_group(self, *args, **kwargs):
        return _Group(super().add_mutually_exclusive_group(*args, **kwargs))

    def exit(self, status=0, message=None):
        super().exit(status, None if message is None else unmark(message))
