"""The layering of the package, as docs/architecture.rst states it, enforced on every import.

Layers, bottom up: ``core`` (the physics, one scalar source per formula and model) -> ``base``
(validation, optional extras, materials) -> ``object`` (the array functions and the objects users
hold) -> ``applications`` -> ``cli``. A module imports only from its own layer or below (imports
inside functions count too); no module imports a private name (``_x``) of another module; the core
imports nothing of microimpact outside the core.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "microimpact"

LAYERS = {
    "core": 0,
    "_validation": 1,
    "_optional": 1,
    "materials": 1,
    "io": 1,
    "_signals": 1,
    "contact": 2,
    "impact": 2,
    "dynamics": 2,
    "models": 2,
    "pair": 2,
    "cli": 4,
    "__main__": 4,
}
APPLICATION = 3  # every other top-level module or package: sweep, fitting, wall, figures, paper, ...


def _module_name(path: Path) -> str:
    rel = path.relative_to(SRC.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _layer(modname: str) -> int:
    parts = modname.split(".")
    if len(parts) == 1:  # the package itself: may import anything lazily
        return 5
    return LAYERS.get(parts[1], APPLICATION)


def _resolve(modname: str, is_package: bool, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    base = modname.split(".")
    if not is_package:
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _imports():
    for path in sorted(SRC.rglob("*.py")):
        modname = _module_name(path)
        tree = ast.parse(path.read_text(), filename=str(path))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                target = _resolve(modname, path.name == "__init__.py", node)
                for alias in node.names:
                    yield modname, target, alias.name, node.lineno
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    yield modname, alias.name, None, node.lineno


IMPORTS = [i for i in _imports() if i[1] == "microimpact" or i[1].startswith("microimpact.")]


def _full(target: str, name: str | None) -> str:
    """The module an import reaches: ``from microimpact import sweep`` reaches ``microimpact.sweep``."""
    if name is None:
        return target
    path = SRC.parent / Path(*target.split("."), name)
    return f"{target}.{name}" if path.with_suffix(".py").exists() or path.is_dir() else target


def test_the_scan_sees_the_package():
    assert len({i[0] for i in IMPORTS}) > 20
    assert any(i[0] == "microimpact.pair" and _full(i[1], i[2]) == "microimpact.core.models" for i in IMPORTS)


@pytest.mark.parametrize("importer, target, name, line", IMPORTS)
def test_no_import_goes_upward(importer, target, name, line):
    full = _full(target, name)
    if full == "microimpact" and name == "__version__":  # package metadata, read lazily
        return
    assert _layer(full) <= _layer(importer), (
        f"{importer} (layer {_layer(importer)}) imports {full} (layer {_layer(full)}) at line {line}"
    )


@pytest.mark.parametrize("importer, target, name, line", IMPORTS)
def test_no_private_name_of_another_module(importer, target, name, line):
    if name is None or not name.startswith("_") or name.startswith("__"):
        return
    # a private *module* of the package (``from . import _validation``) is the package's own helper
    if (SRC.parent / Path(*target.split("."), name + ".py")).exists():
        return
    assert target == importer, f"{importer} imports the private name {name} of {target} at line {line}"


@pytest.mark.parametrize("importer, target, name, line", [i for i in IMPORTS if i[0].startswith("microimpact.core")])
def test_core_imports_only_the_core(importer, target, name, line):
    assert target.startswith("microimpact.core"), f"{importer} imports {target} at line {line}"


def test_import_microimpact_loads_no_application():
    import subprocess
    import sys

    code = (
        "import sys, microimpact; "
        "print(','.join(m for m in ('scipy', 'xarray', 'matplotlib', 'numba', 'microimpact.deposition', "
        "'microimpact.fitting', 'microimpact.sweep', 'microimpact.paper') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "", f"import microimpact loaded {out}"
