"""The package uses other projects only through their public API.

Scanned in ``src/`` with :mod:`ast` (a use in a docstring or comment aside), each a finding:

* an import of a private module or name of another project (``import _thread``,
  ``from numba.core.caching import _CacheLocator``);
* an underscore attribute read on anything that is not the package's own: a module or object of
  another project (``os.environ._data``, ``sys._getframe``, ``parser._negative_number_matcher``), or
  named as a string to ``getattr``/``setattr``/``hasattr``/``delattr``;
* an attribute set on another project's module or object (monkeypatching:
  ``MathTextParser._parse_cached = ...``, ``sys.unraisablehook = ...``);
* :mod:`ctypes` at all (a C calling convention is no public Python API), and ``os.fork`` (unsafe
  once any library has started a thread; :mod:`concurrent.futures` and :mod:`subprocess` do it).

:data:`EXPECTED` lists what remains, each with its reason: each entry must still occur (an entry that
no longer does is reported, so the set only shrinks), and a finding not listed fails.
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "microimpact"

#: Findings that remain, each with its reason: the command line's own process-wide settings while a
#: command runs (restored after it; ``import microimpact`` makes none).
EXPECTED = {
    # the command's own process, while a command runs (restored after it): its standard output wrapped
    # to name it in errors, and warnings printed on one line; no import makes either change
    "cli: sets an attribute of sys (sys.stdout)",
    "cli: sets an attribute of warnings (warnings.formatwarning)",
    # the command's own process while a command runs after an interrupt: what numba's compiler,
    # cut short, leaves to be freed says nothing (the interrupt's one line is the command's report)
    "cli: sets an attribute of sys (sys.unraisablehook)",
    # the same for the interrupt's traceback where a C extension prints the exception it caught (numba's
    # _dispatcher, when a signal cuts its import of numba._devicearray): the one line says it
    "cli: sets an attribute of sys (sys.excepthook)",
}

#: Calls of public names that are off limits all the same, and why.
FORBIDDEN_CALLS = {"os.fork": "calls os.fork", "os.forkpty": "calls os.forkpty"}


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


@functools.cache
def _trees() -> dict:
    return {path: ast.parse(path.read_text(), filename=str(path)) for path in sorted(SRC.rglob("*.py"))}


@functools.cache
def _own_private_names() -> frozenset:
    """Private names the package defines itself: functions, classes, assigned names, parameters,
    import aliases, ``__slots__`` entries, and attributes set on ``self``/``cls`` in its own classes
    (not in a subclass of another project's class: there an underscore attribute may be the base's)."""
    out = set()
    for tree in _trees().values():
        foreign = _foreign_names(tree)
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                out.add(node.name)
            elif isinstance(node, ast.arg):
                out.add(node.arg)
            elif isinstance(node, ast.alias):
                out.add(node.asname or node.name.split(".")[0])
            elif isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
                for t in node.targets if isinstance(node, ast.Assign) else [node.target]:
                    for n in ast.walk(t):
                        if isinstance(n, ast.Name):
                            out.add(n.id)
                if any(isinstance(t, ast.Name) and t.id == "__slots__" for t in getattr(node, "targets", [])):
                    out.update(c.value for c in ast.walk(node.value) if isinstance(c, ast.Constant))
        for cls in ast.walk(tree):
            if isinstance(cls, ast.ClassDef) and not any(_root(b) in foreign for b in cls.bases):
                for n in ast.walk(cls):
                    if isinstance(n, ast.Attribute) and isinstance(n.ctx, ast.Store) and _root(n) in ("self", "cls"):
                        out.add(n.attr)
    return frozenset(n for n in out if isinstance(n, str) and _private(n))


#: Underscore names that are their project's documented public API.
DOCUMENTED = {
    "_exit",  # os._exit: leave the process without cleanup (a forked child, a watchdog)
    "_replace",  # namedtuple's methods carry an underscore so as not to clash with field names
    "_asdict",
    "_fields",
    "_make",
    "_field_defaults",
}


def _foreign_names(tree) -> dict:
    """``{local name: what it names}`` for every import of another project in ``tree``."""
    names = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] != "microimpact":
                    names[alias.asname or alias.name.split(".")[0]] = (
                        alias.asname and alias.name or alias.name.split(".")[0]
                    )
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            if node.module.split(".")[0] not in ("microimpact", "__future__"):
                for alias in node.names:
                    names[alias.asname or alias.name] = alias.name
    return names


def _root(node):
    """The name at the bottom of ``a.b[c].d(...)``, or None."""
    while isinstance(node, (ast.Attribute, ast.Subscript, ast.Call)):
        node = node.func if isinstance(node, ast.Call) else node.value
    return node.id if isinstance(node, ast.Name) else None


def _where(path: Path) -> str:
    rel = path.relative_to(SRC)
    return "cli" if rel.parts[0] == "cli" else rel.as_posix()  # the CLI is one room: its files move


def _findings_in(path: Path, tree) -> set:
    where = _where(path)
    foreign = _foreign_names(tree)
    own = _own_private_names()
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                parts = alias.name.split(".")
                if parts[0] == "ctypes":
                    found.add(f"{where}: uses ctypes")
                elif parts[0] != "microimpact" and any(_private(p) for p in parts):
                    found.add(f"{where}: imports the private module {alias.name}")
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            parts = node.module.split(".")
            if parts[0] in ("microimpact", "__future__"):
                continue
            if parts[0] == "ctypes":
                found.add(f"{where}: uses ctypes")
            elif any(_private(p) for p in parts):
                found.add(f"{where}: imports from the private module {node.module}")
            for alias in node.names:
                if _private(alias.name):
                    found.add(f"{where}: imports the private name {alias.name} of {node.module}")
        elif isinstance(node, ast.Attribute) and _private(node.attr) and node.attr not in DOCUMENTED:
            root = _root(node.value)
            verb = "reads" if isinstance(node.ctx, ast.Load) else "sets"
            if root in foreign:
                found.add(f"{where}: {verb} the private attribute {node.attr} of {ast.unparse(node.value)}")
            elif node.attr not in own:
                whose = f"the base of {root}" if root in ("self", "cls") else "a foreign object"
                found.add(f"{where}: {verb} the private attribute {node.attr} of {whose}")
        elif isinstance(node, ast.Call):
            name = ast.unparse(node.func)
            if name in FORBIDDEN_CALLS and _root(node.func) in foreign:
                found.add(f"{where}: {FORBIDDEN_CALLS[name]}")
            if (
                isinstance(node.func, ast.Name)
                and node.func.id in ("getattr", "setattr", "hasattr", "delattr")
                and len(node.args) >= 2
                and isinstance(node.args[1], ast.Constant)
                and isinstance(node.args[1].value, str)
                and _private(node.args[1].value)
                and node.args[1].value not in own
                and _root(node.args[0]) not in ("self", "cls")
            ):
                found.add(f"{where}: {node.func.id} of the private attribute {node.args[1].value}")
            if (
                isinstance(node.func, ast.Attribute)
                and node.func.attr == "get"
                and isinstance(node.func.value, ast.Attribute)
                and node.func.value.attr == "__dict__"
                and node.args
                and isinstance(node.args[0], ast.Constant)
                and isinstance(node.args[0].value, str)
                and _private(node.args[0].value)
                and _root(node.func.value) in foreign
            ):
                found.add(
                    f"{where}: reads the private attribute {node.args[0].value} of {ast.unparse(node.func.value.value)}"
                )
        elif isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign, ast.Delete)):
            targets = node.targets if isinstance(node, (ast.Assign, ast.Delete)) else [node.target]
            for t in targets:
                if isinstance(t, ast.Attribute) and _root(t.value) in foreign and not _private(t.attr):
                    found.add(f"{where}: sets an attribute of {_root(t.value)} ({ast.unparse(t)})")
    return found


def findings() -> set:
    out = set()
    for path, tree in _trees().items():
        out |= _findings_in(path, tree)
    return out


def test_the_scan_sees_what_it_looks_for():
    """Each kind of finding, in a made-up module."""
    code = """
import ctypes
import os, sys, _thread
from numba.core.caching import _CacheLocator
from numba.core import dispatcher
from argparse import ArgumentParser
def f(parser, d):
    os.environ._data
    sys._getframe()
    parser._negative_number_matcher
    d._overloads
    getattr(d, "_cache_file")
    dispatcher.Dispatcher._cache = None
    sys.unraisablehook = print
    os.fork()
    ArgumentParser.__dict__.get("_parse")
    os._exit(0)
class P(ArgumentParser):
    def __init__(self):
        self._negative_number_matcher = None
"""
    got = _findings_in(SRC / "made_up.py", ast.parse(code))
    want = {
        "made_up.py: uses ctypes",
        "made_up.py: imports the private module _thread",
        "made_up.py: imports the private name _CacheLocator of numba.core.caching",
        "made_up.py: reads the private attribute _data of os.environ",
        "made_up.py: reads the private attribute _getframe of sys",
        "made_up.py: reads the private attribute _negative_number_matcher of a foreign object",
        "made_up.py: reads the private attribute _overloads of a foreign object",
        "made_up.py: sets the private attribute _negative_number_matcher of the base of self",
        "made_up.py: getattr of the private attribute _cache_file",
        "made_up.py: sets the private attribute _cache of dispatcher.Dispatcher",
        "made_up.py: sets an attribute of sys (sys.unraisablehook)",
        "made_up.py: calls os.fork",
        "made_up.py: reads the private attribute _parse of ArgumentParser",
    }
    assert got == want, sorted(got ^ want)


def test_other_projects_only_through_their_public_api():
    found = findings()
    new = sorted(found - EXPECTED)
    gone = sorted(EXPECTED - found)
    assert not new and not gone, (
        "uses of other projects' private ground not listed in EXPECTED:\n"
        + "\n".join(new)
        + "\nEXPECTED entries that no longer occur (remove them):\n"
        + "\n".join(gone)
    )


def test_the_engine_stands_on_public_ground_alone():
    """The array engine (``engine/``) and the core have nothing listed: no entry of EXPECTED is theirs."""
    assert not [e for e in EXPECTED if e.startswith(("engine/", "core/"))]
    assert not [f for f in findings() if f.startswith(("engine/", "core/"))]
