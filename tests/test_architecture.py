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
    "_face": 2,
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


def _core_constants() -> dict:
    """``{name: value}`` of the core's public float constants (the physics numbers named once)."""
    import importlib
    import math
    import pkgutil

    import microimpact.core as core

    found = {}
    for info in pkgutil.walk_packages(core.__path__, "microimpact.core."):
        if info.name.rsplit(".", 1)[-1] in ("arrays", "_jit"):  # engine settings, not physics
            continue
        module = importlib.import_module(info.name)
        for name, value in vars(module).items():
            if name.isupper() and isinstance(value, float) and math.isfinite(value) and value != int(value):
                found[name] = value
    return found


def _significant_digits(text: str) -> int:
    mantissa = text.lower().split("e")[0].lstrip("+-").replace(".", "").replace("_", "")
    return len(mantissa.lstrip("0"))


def test_physics_constants_live_only_in_the_core():
    """Outside ``core/`` no module assigns a core constant's name anew, nor writes a core constant's
    value (or its rounding to the digits written, such as 14.18 for 14.1844) as a literal of three
    or more significant digits: such a number is imported from the core, where it is derived once."""
    constants = _core_constants()
    assert {"STICKING_CONSTANT", "HERTZ_TIME_CONSTANT", "BETA_25_12"} <= set(constants)
    violations = []
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC)
        if rel.parts[0] == "core":
            continue
        text = path.read_text()
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.Assign, ast.AnnAssign)):
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                for t in targets:
                    if (
                        isinstance(t, ast.Name)
                        and t.id in constants
                        and not isinstance(node.value, (ast.Name, ast.Attribute))
                    ):
                        violations.append(f"{rel}:{node.lineno} redefines {t.id}")
            elif isinstance(node, ast.Constant) and type(node.value) is float:
                literal = ast.get_source_segment(text, node) or repr(node.value)
                if _significant_digits(literal) < 3:
                    continue
                decimals = len(literal.split(".")[1]) if "." in literal and "e" not in literal.lower() else None
                for name, value in constants.items():
                    if node.value == value or (decimals is not None and round(value, decimals) == node.value):
                        violations.append(f"{rel}:{node.lineno} writes {literal}, the core's {name}")
    assert not violations, "physics constants outside the core:\n" + "\n".join(violations)
