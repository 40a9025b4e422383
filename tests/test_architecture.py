"""The layering of the package, as docs/architecture.rst states it, enforced on every import.

Layers, bottom up: ``core`` (the physics, one scalar source per formula and model) -> ``engine``
(how a core function runs over an array: the compiled loops and the on-disk cache) -> ``base``
(validation, optional extras, materials) -> ``object`` (the array functions and the objects users
hold) -> ``applications`` -> ``cli``. A module imports only from its own layer or below (imports
inside functions count too); no module imports a private name (``_x``) of another module; the core
imports nothing of microimpact outside the core. A model's name is written only in its two files
(its physics, ``core/models/NAME.py``, and its face, ``models/NAME.py``), and no other module
branches on a model's identity (the seed's included: what is special about a model is declared);
no module reads another module's private attributes; the CLI calls the public API, not the core; the application modules
keep an order among themselves (:data:`APPLICATION_ORDER`). Each rule is one test that lists every
violation at once. No two modules import each other, directly or round a longer circle (imports
inside functions count); no module is longer than :data:`MAX_LINES`; the one import that may go
upward or close a circle is a deprecation shim that says so (:data:`DEPRECATION_SHIMS`).
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "microimpact"

LAYERS = {
    "core": 0,
    "_atomic": 0,  # the steps a signal must not cut (numba building a loop): the standard library only
    "engine": 0.5,  # between the core and the base: runs the core's functions, knows nothing above
    "_validation": 1,
    "_optional": 1,
    "materials": 1,
    "io": 1,
    "_version": 1,
    "_face": 2,
    "contact": 2,
    "impact": 2,
    "dynamics": 2,
    "models": 2,
    "pair": 2,
    "cache": 2,
    "_calibration_cache": 2,  # the calibrations' files on disk: imports only the engine's cache
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


@functools.cache
def _trees() -> dict:
    """``{path: parsed module}`` of every source file, parsed once for all the tests here (read only)."""
    return {path: ast.parse(path.read_text(), filename=str(path)) for path in sorted(SRC.rglob("*.py"))}


def _imports():
    for path, tree in _trees().items():
        modname = _module_name(path)
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


def _report(title, violations):
    assert not violations, f"{title} ({len(violations)}):\n" + "\n".join(violations)


#: Imports allowed to go upward, and why (``(importer, module reached)``).
UPWARD_ALLOWED = {
    # the deprecated home of the array engine: its module __getattr__ hands out the engine's names
    ("microimpact.core.arrays", "microimpact.engine"),
}


def test_no_import_goes_upward():
    violations = []
    for importer, target, name, line in IMPORTS:
        full = _full(target, name)
        if (importer, full) in UPWARD_ALLOWED:
            continue
        if _layer(full) > _layer(importer):
            violations.append(
                f"{importer} (layer {_layer(importer)}) imports {full} (layer {_layer(full)}) at line {line}"
            )
    _report("imports that go upward", violations)


def test_no_private_name_of_another_module():
    violations = []
    for importer, target, name, line in IMPORTS:
        if name is None or not name.startswith("_") or name.startswith("__"):
            continue
        # a private *module* of the package (``from . import _validation``) is the package's own helper
        if (SRC.parent / Path(*target.split("."), name + ".py")).exists():
            continue
        if target != importer:
            violations.append(f"{importer} imports the private name {name} of {target} at line {line}")
    _report("private names imported from another module", violations)


#: The application modules (layer 3), bottom up: each imports only those before it (each other's
#: names never in a circle), so that one can be read, tested and moved knowing only what is below.
APPLICATION_ORDER = (
    "quantities",  # the one table of quantities, re-exported above the core
    "adhesion",  # the adhesion rules (from the models' declarations)
    "oblique",  # oblique impacts, the tangential laws' tables
    "stick",  # stick or bounce: the additive rule against the whole law
    "calibrate",  # the DEM laws calibrated to a target e(V)
    "wall",  # one particle at a wall (adhesion, oblique)
    "fitting",  # fits and rankings of e(V) data
    "compare",  # the models side by side (calibrate, oblique)
    "sweep",  # parameter sweeps
    "dem",  # runs in LAMMPS/LIGGGHTS
    "deposition",  # an example application (wall)
    "openfoam",  # the OpenFOAM hand-off (wall)
    "cexport",  # CSV tables and the C source (adhesion, oblique, fitting)
    "figures",  # every plot (compare, oblique, stick)
    "paper",  # the seed paper reproduced (figures, fitting)
    "coupling",  # deprecated: re-exports adhesion, wall and cexport
)


def test_application_modules_keep_their_order():
    """An application module imports only application modules before it in :data:`APPLICATION_ORDER`
    (and every application module is listed there, so a new one is placed)."""
    top = {p.name if p.is_dir() else p.stem for p in SRC.iterdir() if p.suffix == ".py" or (p / "__init__.py").exists()}
    apps = {m for m in top if m not in LAYERS and not m.startswith("__")}
    violations = [
        f"{m} is an application module missing from APPLICATION_ORDER" for m in sorted(apps - set(APPLICATION_ORDER))
    ]
    violations += [
        f"{m} is listed in APPLICATION_ORDER but is no application module" for m in APPLICATION_ORDER if m not in apps
    ]
    rank = {m: i for i, m in enumerate(APPLICATION_ORDER)}
    for importer, target, name, line in IMPORTS:
        full = _full(target, name)
        a, b = importer.split("."), full.split(".")
        if len(a) < 2 or len(b) < 2 or a[1] == b[1] or a[1] not in rank or b[1] not in rank:
            continue
        if rank[b[1]] > rank[a[1]] and (importer, full) not in DEPRECATION_SHIMS:
            violations.append(f"{importer} imports {full} (later in APPLICATION_ORDER) at line {line}")
    _report("application modules out of order", violations)


#: Imports that may go upward, and so close a circle, because they are deprecation shims: each is an
#: import inside a module-level ``__getattr__`` that warns (:class:`DeprecationWarning`) naming the new
#: home of a name that moved up, and goes when that name's one release is over (then remove the entry).
DEPRECATION_SHIMS = {
    ("microimpact.fitting", "microimpact.figures.fit"): "plot_fit, plot_residuals, plot_models moved to figures.fit",
}


def _shim_imports() -> set:
    """``(importer, module)`` of every import inside a module-level ``__getattr__`` that warns with a
    :class:`DeprecationWarning`: the only imports :data:`DEPRECATION_SHIMS` may name."""
    found = set()
    for path, tree in _trees().items():
        modname = _module_name(path)
        for fn in tree.body:
            if not (isinstance(fn, ast.FunctionDef) and fn.name == "__getattr__"):
                continue
            warns = any(
                isinstance(n, ast.Call)
                and ast.unparse(n.func).endswith("warn")
                and any(ast.unparse(a) == "DeprecationWarning" for a in (*n.args, *(k.value for k in n.keywords)))
                for n in ast.walk(fn)
            )
            for node in ast.walk(fn):
                if warns and isinstance(node, ast.ImportFrom):
                    target = _resolve(modname, path.name == "__init__.py", node)
                    found.update((modname, _full(target, alias.name)) for alias in node.names)
    return found


def test_deprecation_shims_are_shims():
    """Each entry of :data:`DEPRECATION_SHIMS` is an import inside a module-level ``__getattr__`` that
    warns with a :class:`DeprecationWarning` (so no ordinary import hides behind the list), and it is
    still there (a shim removed leaves no stale entry)."""
    shims = _shim_imports()
    violations = [
        f"DEPRECATION_SHIMS lists {a} -> {b}, which is no import inside a __getattr__ that warns (DeprecationWarning)"
        for a, b in sorted(set(DEPRECATION_SHIMS) - shims)
    ]
    _report("deprecation shims that are none", violations)


def _import_graph() -> dict:
    """``{module: {module it imports: [line, ...]}}`` over the package's modules, every import
    counted (at module level, inside functions, under ``TYPE_CHECKING``), deprecation shims aside.
    The package itself (``microimpact``, whose lazy names load everything) is left out."""
    modules = {_module_name(p) for p in _trees()}
    graph = {m: {} for m in modules}
    for importer, target, name, line in IMPORTS:
        full = _full(target, name)
        if importer == "microimpact" or full == "microimpact" or (importer, full) in DEPRECATION_SHIMS:
            continue
        if full in modules and full != importer:
            lines = graph[importer].setdefault(full, [])
            if line not in lines:
                lines.append(line)
    return graph


def _circles(graph) -> list:
    """The strongly connected components of more than one module (Tarjan's algorithm), sorted."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                out.append(sorted(group))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(out)


def test_no_import_circle():
    """No modules of the package import each other, directly or round a longer circle: each can be read
    and tested knowing only what it imports. Imports inside functions count (a lazy import is still a
    dependency); a package's ``__init__`` and its submodules are separate modules (a submodule that
    imports its package's names, which import it, is a circle too). Each circle is listed with the
    imports that close it."""
    graph = _import_graph()
    violations = []
    for group in _circles(graph):
        ties = [
            f"{a} -> {b} (line {', '.join(map(str, graph[a][b]))})"
            for a in group
            for b in sorted(graph[a])
            if b in group
        ]
        violations.append(" <-> ".join(group) + ":\n    " + "\n    ".join(ties))
    _report("import circles", violations)


def test_the_circle_scan_sees_a_circle():
    """The scan above finds a circle where one is: two modules importing each other, and three in a ring."""
    assert _circles({"a": {"b": [1]}, "b": {"a": [2]}, "c": {"a": [3]}}) == [["a", "b"]]
    assert _circles({"a": {"b": [1]}, "b": {"c": [1]}, "c": {"a": [1]}, "d": {}}) == [["a", "b", "c"]]
    assert _circles({"a": {"b": [1]}, "b": {}}) == []


def test_no_module_loads_another_by_a_name_string():
    """An import is an import statement: no module hands the name of one of the package's modules, as a
    string written out, to :func:`importlib.import_module` or ``__import__`` (which would hide it from
    the rules above). Names made at run time (a registry's model files, the CLI's commands) are not
    written out, and are not seen here."""
    violations = []
    for path, tree in _trees().items():
        for node in ast.walk(tree):
            if not (
                isinstance(node, ast.Call) and ast.unparse(node.func).split(".")[-1] in ("import_module", "__import__")
            ):
                continue
            first = node.args[0] if node.args else None
            if isinstance(first, ast.Constant) and isinstance(first.value, str):
                if first.value.startswith(("microimpact", ".")):
                    violations.append(f"{path.relative_to(SRC)}:{node.lineno} loads {first.value!r} by name")
    _report("modules loaded by a name string", violations)


#: No module of the package is longer than this many lines: a longer one holds more than one subject
#: (split it by subject, as :mod:`microimpact.pair` and :mod:`microimpact.figures.paper` are).
MAX_LINES = 1000

#: Modules allowed above :data:`MAX_LINES` for now, and why.
LONG_MODULES: dict = {}


def test_no_module_above_the_line_limit():
    """Every module is at most :data:`MAX_LINES` lines (:data:`LONG_MODULES` aside, each with its reason)."""
    violations = []
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC).as_posix()
        n = len(path.read_text().splitlines())
        if n > MAX_LINES and rel not in LONG_MODULES:
            violations.append(f"{rel}: {n} lines")
    _report(f"modules above {MAX_LINES} lines", violations)


def test_core_imports_only_the_core():
    violations = [
        f"{importer} imports {target} at line {line}"
        for importer, target, name, line in IMPORTS
        if importer.startswith("microimpact.core")
        and not target.startswith("microimpact.core")
        and (importer, _full(target, name)) not in UPWARD_ALLOWED
    ]
    _report("core modules importing outside the core", violations)


# ----------------------------------------------------------------------------- the model's two rooms


def _docstring_nodes(tree) -> set:
    """ids of the string constants that are documentation: docstrings and bare string statements."""
    return {
        id(node.value)
        for node in ast.walk(tree)
        if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant) and isinstance(node.value.value, str)
    }


#: Where a model's name may be written as a string, apart from its own two files, and why.
MODEL_NAME_ALLOWED = {
    # the registry names its default once (the seed's module cannot be imported there: it imports the registry)
    ("core/models/__init__.py", "thornton_ning_2016"),
    # comments of the generated C source naming the core function or law it translates (text, not a lookup)
    ("cexport/_csource.py", "thornton_ning_2016"),
}


def test_no_model_name_as_a_string_outside_its_two_files():
    """A model is found by its name in two rooms only: its physics (``core/models/NAME.py``) and its
    face (``models/NAME.py``). Anywhere else a name is reached through the module (``law.NAME``), the
    registry (``models.DEFAULT``, ``models.available()``) or the declaration, never written out:
    so no other room branches on a model, and a new model needs no edit elsewhere. Docstrings aside."""
    import re

    from microimpact.core import models

    names = models.available()
    word = re.compile(r"\b(" + "|".join(map(re.escape, names)) + r")\b")
    violations = []
    used = set()
    for path, tree in _trees().items():
        rel = path.relative_to(SRC)
        if rel.parts[0] in ("core", "models") and rel.stem in names and rel.parts[-2] == "models":
            continue  # the model's own two rooms
        docs = _docstring_nodes(tree)
        for node in ast.walk(tree):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
                for name in sorted(set(word.findall(node.value))):
                    if (rel.as_posix(), name) not in MODEL_NAME_ALLOWED:
                        violations.append(f"{rel}:{node.lineno} writes the model name {name!r}")
                    used.add((rel.as_posix(), name))
    violations += [f"MODEL_NAME_ALLOWED lists {entry}, which no longer occurs" for entry in MODEL_NAME_ALLOWED - used]
    _report("model names written outside their two files", violations)


def test_no_model_module_imported_outside_the_core():
    """Outside the core (where physics composes physics: the wall's table is the whole law's correction)
    and a model's two rooms, a model other than the seed (whose array face is the library's own) is
    reached through the registry and its declaration (``models.get(name)``, its hooks and flags such as
    ``WALL_ADHESION`` or ``COST``), never by importing its module: what a room does with a model then
    follows the model's declarations, and a new model needs no edit there (the whole adhesive law of
    ``pair.sticking_velocity`` and of the stick/bounce maps is the model declaring ``WALL_ADHESION``,
    :func:`microimpact.core.models.whole_law`). No exceptions."""
    from microimpact.core import models

    names = set(models.available()) - {models.DEFAULT}
    violations = []
    for importer, target, name, line in IMPORTS:
        if importer.startswith("microimpact.core"):
            continue
        full = _full(target, name)
        reached = (
            full.rsplit(".", 1)[-1] if full.startswith(("microimpact.core.models.", "microimpact.models.")) else None
        )
        if reached in names and not importer.endswith("models." + reached):
            violations.append(f"{importer} imports the model module {full} at line {line}")
    _report("model modules imported outside the core", violations)


def _private_names(tree) -> set:
    """Private names a module defines: functions, classes, module, class and instance attributes."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            out.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
            for t in node.targets if isinstance(node, ast.Assign) else [node.target]:
                for n in ast.walk(t):
                    if isinstance(n, ast.Name):
                        out.add(n.id)
                    elif isinstance(n, ast.Attribute):
                        out.add(n.attr)
    return {n for n in out if n.startswith("_") and not n.startswith("__")}


def test_no_private_attribute_of_another_module():
    """``x._name`` where ``_name`` is private to another module of the package (the CLI read
    ``ContactPair._limiting_pressure``; it calls :func:`microimpact.materials.limiting_pressure` now)."""
    trees = _trees()
    own = {path: _private_names(tree) for path, tree in trees.items()}
    everywhere = set().union(*own.values())
    violations = []
    for path, tree in trees.items():
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Attribute) and node.attr.startswith("_") and not node.attr.startswith("__")):
                continue
            if ast.unparse(node.value) in ("self", "cls") or node.attr in own[path] or node.attr not in everywhere:
                continue
            where = sorted(p.relative_to(SRC).as_posix() for p, names in own.items() if node.attr in names)
            violations.append(
                f"{path.relative_to(SRC)}:{node.lineno} reads {ast.unparse(node)}, private to {', '.join(where)}"
            )
    _report("private attributes of another module", violations)


def test_the_cli_calls_the_public_api():
    """The CLI parses arguments and calls the public API: it imports nothing of ``microimpact.core``
    (the models through :mod:`microimpact.models`, not :mod:`microimpact.core.models`)."""
    violations = [
        f"{importer} imports {target} at line {line}"
        for importer, target, name, line in IMPORTS
        if importer.startswith("microimpact.cli") and _full(target, name).startswith("microimpact.core")
    ]
    _report("CLI modules importing the core", violations)


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
        lines = text.encode().split(b"\n")
        for node in ast.walk(_trees()[path]):
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
                if node.lineno == node.end_lineno:  # as ast.get_source_segment, without splitting the file each time
                    literal = lines[node.lineno - 1][node.col_offset : node.end_col_offset].decode()
                else:
                    literal = ast.get_source_segment(text, node) or repr(node.value)
                if _significant_digits(literal) < 3:
                    continue
                decimals = len(literal.split(".")[1]) if "." in literal and "e" not in literal.lower() else None
                for name, value in constants.items():
                    if node.value == value or (decimals is not None and round(value, decimals) == node.value):
                        violations.append(f"{rel}:{node.lineno} writes {literal}, the core's {name}")
    assert not violations, "physics constants outside the core:\n" + "\n".join(violations)


# ----------------------------------------------------------------------------- the seed's array face
#: Modules that only name the seed's array functions (re-exports of its face, models/thornton_ning_2016.py).
SEED_NAME_ROOMS = ("contact.py", "impact.py", "dynamics.py")


def test_the_seed_array_face_is_one_room():
    """Each seed formula's array function is written once, in the seed's face: the modules users know
    (contact, impact, dynamics) import it from there and generate or wrap nothing of their own."""
    violations = []
    for rel in SEED_NAME_ROOMS:
        tree = ast.parse((SRC / rel).read_text(), filename=rel)
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and getattr(node.func, "id", "") in ("array_function", "outcome_function"):
                violations.append(f"{rel}:{node.lineno} generates an array function (belongs in the face)")
            if isinstance(node, ast.FunctionDef) and rel != "dynamics.py":
                violations.append(f"{rel}:{node.lineno} defines {node.name} (belongs in the face)")
            if isinstance(node, ast.Attribute) and getattr(node.value, "id", "") == "_seed" and rel != "dynamics.py":
                violations.append(f"{rel}:{node.lineno} calls the seed's core ({node.attr})")
    _report("seed array functions outside the seed's face", violations)


# ----------------------------------------------------------------------------- one table labels everything
#: Hand-typed labels of a tabled quantity allowed to stay, and why (``(file, label): reason``).
LABELS_ALLOWED = {
    ("figures/fit.py", "$V$ [m/s]"): "the fit plots' own style (lower case, bracketed units): text would change",
    ("openfoam.py", "d [um]"): "the OpenFOAM report's style across its three panels (lower case, bracketed units)",
    (
        "deposition.py",
        "$d$ [$\\mu$m]",
    ): "the deposition plot's style (lower case, bracketed units), as the OpenFOAM report's",
    ("oblique/_csource.py", "V [m/s]"): "a comment of the generated C table (C source text, not a label)",
    ("cexport/_csource.py", "G [J/m^2]"): "a comment of the generated C source (C source text, not a label)",
    ("oblique/_csource.py", "V_y [m/s]"): "a comment of the generated C table (C source text, not a label)",
}
#: Calls whose string arguments are help text for people, not labels of numbers (argparse).
_HELP_CALLS = {"add_argument", "add_argument_group", "add_parser", "add_mutually_exclusive_group"}


def _label_patterns() -> dict:
    """``{(kind, text): quantity}``: for every quantity with a unit, its CSV column names (``"col"``,
    the whole string) and the tails of its labels (``"sub"``: ``$V$ (m/s)``, ``$V$ [m/s]``, ``V [m/s]``)."""
    from microimpact.core.quantities import QUANTITIES, column, tex_unit

    out = {}
    for n, q in QUANTITIES.items():
        if q.unit in ("", "1"):  # no unit: the column is the bare name, the label the symbol alone
            continue
        out.setdefault(("col", column(n)), n)
        out.setdefault(("col", column(n, display=True)), n)
        u = q.shown_unit
        if q.tex:
            tu = tex_unit(u)
            mu = tu.replace("\u00b5", r"$\mu$")  # the same unit in TeX's spelling: $\mu$m for um
            for tail in (f"{q.tex} ({tu})", f"{q.tex} [{u}]", f"{q.tex} [{tu}]", f"{q.tex} ({mu})", f"{q.tex} [{mu}]"):
                out.setdefault(("sub", tail), n)
        if q.symbol:
            out.setdefault(("sub", f"{q.symbol} [{u}]"), n)
    return out


def test_labels_come_from_the_quantities_table():
    """No module outside ``core/quantities.py`` types a tabled quantity's CSV column (``velocity_m_s``)
    or label (``$V$ (m/s)``, ``V [m/s]``) by hand: CLI tables, CSV headers, figure labels and
    attributes take them from :mod:`microimpact.quantities` (``column``, ``header``, ``axis_label``),
    so that a unit or symbol changed in the table changes everywhere. Docstrings and argparse help
    text aside; :data:`LABELS_ALLOWED` lists the rest with a reason."""
    import re

    patterns = _label_patterns()
    columns = {text: name for (kind, text), name in patterns.items() if kind == "col"}
    tails = {text: name for (kind, text), name in patterns.items() if kind == "sub"}
    tail_re = re.compile("|".join(re.escape(t) for t in sorted(tails, key=len, reverse=True)))
    violations = []
    used = set()
    for path, tree in _trees().items():
        rel = path.relative_to(SRC).as_posix()
        if rel == "core/quantities.py":
            continue
        skip = set(_docstring_nodes(tree))
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and getattr(node.func, "attr", "") in _HELP_CALLS:
                skip.update(id(n) for arg in (*node.args, *node.keywords) for n in ast.walk(arg))
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Constant) and isinstance(node.value, str)) or id(node) in skip:
                continue
            found = {m.group(0): tails[m.group(0)] for m in tail_re.finditer(node.value)}
            if node.value in columns:
                found[node.value] = columns[node.value]
            for text, name in found.items():
                if (rel, text) not in LABELS_ALLOWED:
                    violations.append(f"{rel}:{node.lineno} types {text!r} (quantity {name!r})")
                used.add((rel, text))
    violations += [f"LABELS_ALLOWED lists {entry}, which no longer occurs" for entry in set(LABELS_ALLOWED) - used]
    _report("hand-typed labels of tabled quantities", violations)


def test_the_label_scan_sees_hand_typed_labels():
    """The scan above finds what it looks for: a column name and an axis label typed by hand."""
    patterns = _label_patterns()
    assert ("col", "velocity_m_s") in patterns and ("sub", "$V$ (m/s)") in patterns and ("sub", "t_c [ns]") in patterns
    assert ("sub", r"$d$ ($\mu$m)") in patterns and ("sub", "$d$ (\u00b5m)") in patterns  # both spellings of um


# ----------------------------------------------------------------------------- the seed is a model like the others
#: Names that stand for a model's identity: the default model and the released tuple of the models that
#: declare a closed-form history (a branch on either asks "is this that model?").
_IDENTITY_NAMES = {"DEFAULT", "SEED_MODEL", "CLOSED_FORM_HISTORY", "_DEFAULT_MODEL"}
_IDENTITY_OPS = (ast.Eq, ast.NotEq, ast.In, ast.NotIn)


def _model_module_aliases(tree, names) -> set:
    """Local names bound to a model module by an import (``from .core.models import thornton_ning_2016 as _seed``)."""
    aliases = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            for a in node.names:
                if a.name in names:
                    aliases.add(a.asname or a.name)
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.rsplit(".", 1)[-1] in names and a.asname:
                    aliases.add(a.asname)
    return aliases


def _identity_branches(tree, names) -> list:
    """``(line, text)`` of each comparison ``==``/``!=``/``in``/``not in`` of which one side is a model's
    identity: a model name written out, ``DEFAULT``, ``SEED_MODEL``, ``CLOSED_FORM_HISTORY`` (bare or
    as an attribute), or ``X.NAME`` of a model module ``X``."""
    aliases = _model_module_aliases(tree, names)

    def identity(node) -> bool:
        if isinstance(node, ast.Constant):
            return isinstance(node.value, str) and node.value in names
        if isinstance(node, ast.Name):
            return node.id in _IDENTITY_NAMES
        if isinstance(node, ast.Attribute):
            if node.attr in _IDENTITY_NAMES:
                return True
            return node.attr == "NAME" and isinstance(node.value, ast.Name) and node.value.id in aliases
        if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
            return any(identity(e) for e in node.elts)
        return False

    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Compare) and any(isinstance(op, _IDENTITY_OPS) for op in node.ops):
            if any(identity(side) for side in (node.left, *node.comparators)):
                found.append((node.lineno, ast.unparse(node)))
    return found


def test_no_branch_on_a_models_identity_outside_its_two_rooms():
    """The seed is a model like the others: outside a model's two rooms (its physics,
    ``core/models/NAME.py``, and its face, ``models/NAME.py``) no code asks "is this that model?"
    (``model == DEFAULT``, ``name != SEED_MODEL``, ``mod.NAME in CLOSED_FORM_HISTORY``,
    ``_seed.NAME == ...``), nor does a model's room ask it of another model. What is special about
    a model is a declaration of the model contract
    (:mod:`microimpact.core.models`: ``CITATION``, ``C_EXPORT``, ``WALL_ADHESION``; the face's
    ``closed_form_history``), read by the generic machinery; the default model is only a default
    argument. No exceptions."""
    from microimpact.core import models

    names = set(models.available())
    violations = []
    for path, tree in _trees().items():
        rel = path.relative_to(SRC)
        own = rel.parts[0] in ("core", "models") and rel.stem in names and rel.parts[-2] == "models"
        others = names - {rel.stem} if own else names  # in a model's own rooms, another model's identity
        violations += [
            f"{rel}:{line} branches on a model's identity: {text}" for line, text in _identity_branches(tree, others)
        ]
    _report("branches on a model's identity outside its two rooms", violations)


def test_the_identity_scan_sees_a_branch():
    """The scan above finds each kind of branch it looks for (and not a plain use of the default)."""
    names = {"thornton_ning_2016", "hertz_tsuji"}
    code = (
        "from .core.models import thornton_ning_2016 as _seed\n"
        "a = model == 'hertz_tsuji'\n"
        "b = name != models.DEFAULT\n"
        "c = mod.NAME in dynamics.CLOSED_FORM_HISTORY\n"
        "d = _seed.NAME == model\n"
        "e = fit.model not in (SEED_MODEL,)\n"
        "f = models.get(models.DEFAULT)\n"
        "g = mod.NAME == other.NAME\n"
    )
    lines = [line for line, _ in _identity_branches(ast.parse(code), names)]
    assert lines == [2, 3, 4, 5, 6]
