"""The documentation covers the public API, and builds without warnings.

* Every name in ``__all__`` of :mod:`microimpact` and of each public module
  (collected by walking the package, so a new module or name is checked without
  editing this file) has a non-empty docstring, and is listed in an
  ``autosummary`` block of the API reference sources ``docs/api/*.rst``.
* The Sphinx build with ``-W`` (warnings are errors) succeeds; it runs only when
  Sphinx and numpydoc are installed (the ``docs`` extra), and is skipped with
  that reason otherwise.

Doctests of the package run in ``tests/test_doctests.py``.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import os
import pkgutil
import re
import shutil
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

import microimpact

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
API = DOCS / "api"

pytestmark = pytest.mark.skipif(not (DOCS / "conf.py").is_file(), reason="no docs/ in this tree")


# --------------------------------------------------------------------------- public names
def _public_modules() -> list[str]:
    """``microimpact`` and every submodule without a leading underscore in its path (not the CLI)."""
    names = ["microimpact"]
    for m in pkgutil.walk_packages(microimpact.__path__, prefix="microimpact."):
        parts = m.name.split(".")
        if any(p.startswith("_") for p in parts) or parts[1] == "cli":
            continue
        names.append(m.name)
    return sorted(names)


def _import(name):
    try:
        return importlib.import_module(name)
    except ImportError as exc:  # an optional extra is missing
        pytest.skip(f"{name} cannot be imported here: {exc}")


def _public_names() -> list[tuple[str, str]]:
    """(module, name) for every name in a public module's ``__all__`` (modules and dunders excluded)."""
    out = []
    for modname in _public_modules():
        try:
            mod = importlib.import_module(modname)
        except ImportError:
            continue
        for name in getattr(mod, "__all__", []):
            if name.startswith("__") or inspect.ismodule(getattr(mod, name, None)):
                continue
            out.append((modname, name))
    return out


PUBLIC = _public_names()


# --------------------------------------------------------------------------- the API sources
_DIRECTIVE = re.compile(r"^(\s*)\.\. (\w+(?::\w+)?)::\s*(.*)$")


def _autosummary_entries(pages=None) -> list[str]:
    """Full dotted names listed in autosummary blocks of docs/api/*.rst (with their currentmodule)."""
    entries = []
    for path in pages or sorted(API.glob("*.rst")):
        current = None
        lines = path.read_text().splitlines()
        i = 0
        while i < len(lines):
            m = _DIRECTIVE.match(lines[i])
            if m and m.group(2) in ("currentmodule", "py:currentmodule", "module", "automodule"):
                current = m.group(3).strip()
            if m and m.group(2) == "autosummary":
                indent = len(m.group(1))
                i += 1
                while i < len(lines) and (not lines[i].strip() or len(lines[i]) - len(lines[i].lstrip()) > indent):
                    item = lines[i].strip()
                    if item and not item.startswith(":"):
                        item = item.lstrip("~").split()[0]
                        entries.append(f"{current}.{item}" if current else item)
                    i += 1
                continue
            i += 1
    return entries


def _resolve(dotted: str):
    """The object a dotted name refers to (module prefix imported), or a sentinel when it does not resolve."""
    parts = dotted.split(".")
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        try:
            for attr in parts[k:]:
                obj = getattr(obj, attr)
        except AttributeError:
            return _MISSING
        return obj
    return _MISSING


_MISSING = object()
ENTRIES = _autosummary_entries() if API.is_dir() else []
#: The entries of the top-level page, which must list everything ``import microimpact as mi`` offers.
TOP_ENTRIES = _autosummary_entries([API / "microimpact.rst"]) if (API / "microimpact.rst").is_file() else []


def test_api_sources_exist_and_resolve():
    """Every autosummary entry names an object that exists (a stale entry would break the build)."""
    assert ENTRIES, "no autosummary entries found in docs/api/*.rst"
    stale = [e for e in ENTRIES if _resolve(e) is _MISSING and not e.startswith(_optional_prefixes())]
    assert not stale, f"autosummary entries that do not resolve: {stale}"


def _optional_prefixes() -> tuple[str, ...]:
    missing = []
    for modname in ("microimpact.sweep",):
        try:
            importlib.import_module(modname)
        except ImportError:
            missing.append(modname)
    return tuple(missing) or ("\0",)


@pytest.mark.parametrize("modname,name", PUBLIC, ids=[f"{m}.{n}" for m, n in PUBLIC])
def test_public_name_in_api_reference(modname, name):
    """Listed under its own module, or (for re-exports) as the very same object in the reference.

    Names of the top-level package must be on the top-level page, docs/api/microimpact.rst.
    """
    full = f"{modname}.{name}"
    entries = TOP_ENTRIES if modname == "microimpact" else ENTRIES
    where = "docs/api/microimpact.rst" if modname == "microimpact" else "docs/api/*.rst"
    if full in entries:
        return
    obj = getattr(_import(modname), name)
    if not isinstance(obj, (int, float, str, bool, type(None))):
        if any(_resolve(e) is obj for e in entries):
            return
    pytest.fail(f"{full} is public (in __all__) but not in any autosummary of {where}")


def _attribute_docstring(module, name) -> str:
    """The ``#:`` comment above, or the string literal below, a module-level assignment to ``name``."""
    try:
        source = inspect.getsource(module)
    except (OSError, TypeError):
        return ""
    tree = ast.parse(source)
    lines = source.splitlines()
    body = tree.body
    for i, node in enumerate(body):
        targets = []
        if isinstance(node, ast.Assign):
            targets = [t.id for t in node.targets if isinstance(t, ast.Name)]
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            targets = [node.target.id]
        if name not in targets:
            continue
        if (
            i + 1 < len(body)
            and isinstance(body[i + 1], ast.Expr)
            and isinstance(body[i + 1].value, ast.Constant)
            and isinstance(body[i + 1].value.value, str)
        ):
            return body[i + 1].value.value.strip()
        comment = []
        j = node.lineno - 2
        while j >= 0 and lines[j].lstrip().startswith("#:"):
            comment.insert(0, lines[j].lstrip()[2:].strip())
            j -= 1
        return " ".join(comment).strip()
    return ""


def _defining_module(module, name):
    """The module whose source assigns ``name`` (for re-exported constants; a package's private
    submodule, such as ``microimpact.paper._setup``, counts)."""
    obj = getattr(module, name)
    every = [m.name for m in pkgutil.walk_packages(microimpact.__path__, prefix="microimpact.")]
    for modname in _public_modules() + [m for m in every if ".cli" not in m and "__main__" not in m]:
        try:
            mod = importlib.import_module(modname)
        except ImportError:
            continue
        with warnings.catch_warnings():  # a deprecated alias (coupling.REGIMES) warns when read: not the subject
            warnings.simplefilter("ignore", DeprecationWarning)
            found = getattr(mod, name, _MISSING)
        if found is obj and f"\n{name}" in "\n" + inspect.getsource(mod):
            return mod
    return module


#: Public names known to lack a docstring, reported to their owners. Strict xfail:
#: once documented, the test passes unexpectedly and fails, so the entry is removed.
KNOWN_UNDOCUMENTED: set = set()  # names reported as undocumented, expected (strictly) to fail


@pytest.mark.parametrize("modname,name", PUBLIC, ids=[f"{m}.{n}" for m, n in PUBLIC])
def test_public_name_has_docstring(modname, name, request):
    """Functions and classes have their own docstring; constants a ``#:`` comment or docstring."""
    if name in KNOWN_UNDOCUMENTED:
        request.applymarker(pytest.mark.xfail(strict=True, reason=f"{name}: docstring missing, reported"))
    module = _import(modname)
    obj = getattr(module, name)
    if inspect.isclass(obj) or inspect.isroutine(obj):
        doc = inspect.getdoc(obj) or ""
        if inspect.isclass(obj) and doc == inspect.getdoc(object):
            doc = ""
    else:
        doc = _attribute_docstring(_defining_module(module, name), name)
    assert doc.strip(), f"{modname}.{name} has no docstring"


def test_public_modules_have_api_pages():
    """Every public module is the subject of an ``automodule`` in docs/api."""
    text = "\n".join(p.read_text() for p in API.glob("*.rst"))
    documented = set(re.findall(r"^\.\. automodule:: (\S+)", text, flags=re.M))
    missing = []
    for modname in _public_modules():
        try:
            importlib.import_module(modname)
        except ImportError:
            continue
        if modname not in documented:
            missing.append(modname)
    assert not missing, f"public modules without an API page: {missing}"


# --------------------------------------------------------------------------- the build
def _sphinx_missing() -> str | None:
    for mod in ("sphinx", "numpydoc", "matplotlib", "sphinx_gallery", "furo", "sphinx-mathjax-offline"):
        try:
            importlib.import_module(mod)
        except ImportError:
            return f"{mod} is not installed (pip install 'microimpact[docs]'); CI builds the docs separately"
    return None


@pytest.mark.skipif(_sphinx_missing() is not None, reason=_sphinx_missing() or "")
def test_docs_build_without_warnings(tmp_path):
    """``sphinx-build -W --keep-going -b html`` exits 0: no warnings, all pages and figures made.

    The sources are copied to ``tmp_path`` first (without build products), so the
    build starts clean, leaves the tree alone, and documents the installed package.
    """
    src = tmp_path / "docs"
    shutil.copytree(
        DOCS, src, ignore=shutil.ignore_patterns("_build", "_generated", "generated", "gallery", "__pycache__")
    )
    shutil.copytree(ROOT / "examples", tmp_path / "examples", ignore=shutil.ignore_patterns("__pycache__"))
    out = tmp_path / "html"
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "sphinx",
            "-W",
            "--keep-going",
            "-q",
            "-b",
            "html",
            "-d",
            str(tmp_path / "doctrees"),
            str(src),
            str(out),
        ],
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
    )
    assert proc.returncode == 0, f"sphinx-build failed:\n{proc.stderr[-5000:]}"
    # the build-time pages hold computed values, and the gallery its figures
    comparison = (out / "comparison.html").read_text()
    from microimpact.paper import compare_with_paper

    first = compare_with_paper()[0]
    assert f"{first['computed']:.5g}" in comparison
    # the sphinx-gallery index shows a thumbnail per example, and each example page its figure(s)
    gallery = (out / "gallery" / "index.html").read_text()
    examples = sorted((ROOT / "examples").rglob("plot_*.py"))
    assert len(examples) >= 13
    assert gallery.count("<img") >= len(examples)
    for ex in examples:
        page = out / "gallery" / ex.parent.relative_to(ROOT / "examples") / f"{ex.stem}.html"
        assert "sphx-glr-single-img" in page.read_text() or "sphx-glr-multi-img" in page.read_text(), page
    for name in ("theory", "api/index", "howto/cfd", "cli"):
        assert (out / f"{name}.html").is_file()
