"""One table labels every number: model parameters, the pair's card, the C export's CSV headers, the
OpenFOAM report's attributes and the paper's quoted numbers take their units (and symbols) from
:data:`microimpact.core.quantities.QUANTITIES`, and dimensionless is spelled one way in data
(``"1"``) and one way where people read it (``"-"``)."""

from __future__ import annotations

import ast
import csv
import re
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

import microimpact as mi
from microimpact.core import models
from microimpact.core.quantities import (
    DIMENSIONLESS,
    DIMENSIONLESS_SHOWN,
    QUANTITIES,
    axis_label,
    header,
    tex_unit,
    unit_text,
)

SRC = Path(__file__).resolve().parents[1] / "src" / "microimpact"
SYMBOLS = {q.symbol: q for q in QUANTITIES.values() if q.symbol}


# ----------------------------------------------------------------------------- model parameters
def _all_parameters():
    """``(name, Parameter)`` of every model and of the rules for ``e`` fitting takes beside them."""
    from microimpact.adhesion import FIT_RULES

    decls = [models.get(n) for n in models.available()] + list(FIT_RULES)
    return [(d.NAME, p) for d in decls for p in d.PARAMETERS]


def _names_the_quantity(text: str, q) -> bool:
    """``text`` names quantity ``q``: its plain symbol as a word, or its description's words before
    the symbol (``yield strength`` of ``yield strength Y of ...``)."""
    if q.symbol and re.search(rf"(?<![\w]){re.escape(q.symbol)}(?![\w])", text):
        return True
    words = q.description.split(",")[0].split(" (")[0]
    if q.symbol and f" {q.symbol}" in words:
        words = words.split(f" {q.symbol}")[0]
    return words.lower() in text.lower()


@pytest.mark.parametrize("model, p", _all_parameters(), ids=lambda x: getattr(x, "name", x))
def test_a_parameter_that_is_a_quantity_has_its_rows_unit(model, p):
    """The unit is the row's; the description is the row's, or the model's own that states bounds and
    the part the quantity plays in that law, and names the quantity (symbol or words)."""
    if p.name not in QUANTITIES:
        pytest.skip(f"{p.name} of {model} is the model's own (no row)")
    q = QUANTITIES[p.name]
    assert p.unit == q.unit, f"{model}.{p.name}: unit {p.unit!r}, the table's {q.unit!r}"
    assert p.description == q.description or _names_the_quantity(p.description, q), (model, p.description)
    if q.check == "flag":
        assert p.flag
    if q.check == "nonnegative":
        assert p.low == 0.0 and p.high == np.inf  # the row's check is the widest a model may take
    if q.check == "poisson":
        assert p.low >= -1.0 and p.high <= 0.5


def test_parameters_several_models_share_are_rows():
    """A parameter name that two models declare is one quantity: it has a row, so its unit is written once."""
    counts = Counter(p.name for _, p in _all_parameters())
    shared = sorted(n for n, k in counts.items() if k > 1)
    assert shared and not [n for n in shared if n not in QUANTITIES]


def test_parameter_of_takes_the_rows_unit_and_description():
    p = models.Parameter.of("work_of_adhesion", low=0.0)
    q = QUANTITIES["work_of_adhesion"]
    assert p == models.Parameter("work_of_adhesion", q.unit, q.description, low=0.0)
    own = models.Parameter.of("yield_strength", "S_y > 0", low=0.0, low_open=True)
    assert own.unit == "Pa" and own.description == "S_y > 0" and own.low_open
    with pytest.raises(ValueError, match="quantity must name a row of QUANTITIES, got 'no_such_quantity'"):
        models.Parameter.of("no_such_quantity")


def _parameter_calls():
    """``(file, line, first argument)`` of every ``Parameter(...)`` call of the source (not ``.of``)."""
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "Parameter" and node.args:
                first = node.args[0]
                if isinstance(first, ast.Constant):
                    yield path.relative_to(SRC).as_posix(), node.lineno, first.value


#: ``Parameter(...)`` calls that spell a tabled quantity's unit, with why (their unit and description
#: still equal the row's: the test above).
SPELLED_OUT = {
    ("core/models/__init__.py", "limit_force"): "LIMIT_FORCE sits beside the contract, declared before the rows",
}


def test_model_files_take_a_tabled_quantitys_unit_from_the_table():
    """A model file writes ``Parameter.of(name, ...)`` for a tabled quantity, never its unit again."""
    spelled = [(f, n, line) for f, line, n in _parameter_calls() if n in QUANTITIES and (f, n) not in SPELLED_OUT]
    assert not spelled


# ----------------------------------------------------------------------------- the pair's card
def _pair_entries(text):
    return re.findall(r"(\S+) = (\S+) (\S+)", text)


def test_describe_labels_come_from_the_table():
    """Every ``symbol = value unit`` of :meth:`ContactPair.describe` is a row's symbol with that row's
    unit, and the value is the pair's attribute of that name."""
    pair = mi.ContactPair.paper_case("silicon")
    text = pair.describe()
    entries = _pair_entries(text)
    assert len(entries) == 7
    for sym, value, unit in entries:
        q = SYMBOLS[sym]
        assert unit == unit_text(q.unit), (sym, unit)
        assert float(value) == pytest.approx(getattr(pair, q.name), rel=1e-5)
    assert "yield" not in pair.elastic_equivalent().describe()


def test_html_card_labels_come_from_the_table():
    pair = mi.ContactPair.paper_case("silicon")
    rows = re.findall(r"<tr><td>([^<]+)</td><td>([^<]+)</td><td>([^<]*)</td></tr>", pair._repr_html_())
    assert len(rows) == 7  # E*, R*, m*, p_y, rho, V_y, alpha_y
    for sym, value, unit in rows:
        q = SYMBOLS[sym]
        assert unit == unit_text(q.unit)
        assert float(value) == pytest.approx(getattr(pair, q.name), rel=1e-5)


# ----------------------------------------------------------------------------- the C export's tables
#: The released column names of the restitution tables and the quantity each holds.
TABLE_COLUMNS = {
    "V/V_y": "normalized_velocity",
    "normal speed": "velocity",
    "restitution e": "restitution",
    "stuck": "stuck",
    "outside table": "outside_table",
}


@pytest.mark.parametrize("adhesion", ["additive", "thornton_ning_1998_adhesive_plastic"])
def test_restitution_table_headers_carry_the_tables_units(tmp_path, adhesion):
    from microimpact.cexport import write_tables

    pair = mi.ContactPair.from_materials("nh4fl", "silicon", radius=1e-6)
    files = write_tables(tmp_path, pair, work_of_adhesion=0.01, adhesion=adhesion, velocities=[1.0, 10.0])
    seen = set()
    for path in files:
        with open(path, newline="") as fh:
            head = next(csv.reader(fh))
        for cell in head:
            name, unit = re.fullmatch(r"(.+) \[(.*)\]", cell).groups()
            quantity = "restitution" if name.startswith("e at V_s/V_y=") else TABLE_COLUMNS[name]
            assert unit == QUANTITIES[quantity].unit, cell
            seen.add(name if quantity != "restitution" or name == "restitution e" else "e at")
    expected = {"V/V_y", "e at", "normal speed", "restitution e", "stuck"}
    assert seen == expected | ({"outside table"} if adhesion != "additive" else set())


# ----------------------------------------------------------------------------- the OpenFOAM report
def test_openfoam_report_units_come_from_the_table():
    pytest.importorskip("xarray")
    from microimpact import openfoam

    n = 3
    hits = openfoam.PatchHits(
        time=np.arange(n, dtype=float),
        position=np.zeros((n, 3)),
        velocity=np.array([[0.0, 0.0, -5.0], [0.0, 1.0, -0.1], [1.0, 0.0, -20.0]]),
        diameter=np.full(n, 2e-6),
        density=np.full(n, 1350.0),
        n_particle=np.ones(n),
        orig_id=np.arange(n),
        orig_proc=np.zeros(n, int),
        age=np.zeros(n),
        patch=np.array(["wall"] * n, dtype=object),
    )
    ds = openfoam.deposition_report(hits, openfoam.decide(hits, work_of_adhesion=0.1), {2e-6: 10})
    quantity = {"diameter": "diameter", "speed": "velocity", "mean_impact_speed": "velocity", "angle": "angle"}
    names = [*ds.data_vars, *ds.coords]
    assert len(names) == 13
    for name in names:
        unit = ds[name].attrs["units"]
        assert unit == (QUANTITIES[quantity[name]].unit if name in quantity else DIMENSIONLESS), name
        assert ds[name].attrs["long_name"]


# ----------------------------------------------------------------------------- the paper's quotes
#: Units the paper prints in that scale a row's SI unit (microseconds, percent).
PRINTED = {"us": "s", "%": DIMENSIONLESS}


def test_paper_quotes_take_their_units_from_the_table():
    """Each quote's unit is its quantity's display unit as people read it (``-`` dimensionless), or a
    unit the paper prints that scales the row's SI unit; the symbols in the texts are the rows'."""
    from microimpact.paper import PAPER_QUOTES

    rows = sorted(QUANTITIES, key=len, reverse=True)
    for quote in PAPER_QUOTES:
        field = next((r for r in rows if quote["name"] == r or quote["name"].startswith(r + "_")), None)
        unit = quote["unit"]
        if field is None:  # a pure number (the high-speed constant)
            assert unit == unit_text(DIMENSIONLESS), quote["name"]
            continue
        q = QUANTITIES[field]
        assert unit == unit_text(q.shown_unit) or PRINTED.get(unit) == q.unit, (quote["name"], unit)
        if " t_" in quote["quantity"]:
            assert f" {q.symbol} " in quote["quantity"]
    assert {q["unit"] for q in PAPER_QUOTES} == {"m/s", DIMENSIONLESS_SHOWN, "nm", "%", "us"}


# ----------------------------------------------------------------------------- one spelling of dimensionless
#: Spellings of "dimensionless" a unit field must not use: the table's is ``"1"``.
OTHER_SPELLINGS = {"-", "[-]", "(-)", "[1]", "dimensionless", "–", "none", "None"}
#: Keyword and key names whose value is a unit (``"units"``: NetCDF attributes).
UNIT_KEYS = {"unit", "units", "si"}


def _unit_fields(tree):
    """String constants of the unit fields of a module: a ``Parameter``'s and a table row's unit,
    ``unit=``/``units=`` keywords, ``"units"`` keys, the units of ``described=`` and ``columns=``."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            name = getattr(node.func, "attr", "") or getattr(node.func, "id", "")
            if name in ("Parameter", "_q") and len(node.args) > 1:
                yield node.args[1]
            for kw in node.keywords:
                if kw.arg in UNIT_KEYS:
                    yield kw.value
                if kw.arg in ("described", "columns") and isinstance(kw.value, ast.Dict):
                    for v in kw.value.values:
                        if isinstance(v, ast.Tuple) and len(v.elts) == 2:
                            yield v.elts[1] if kw.arg == "described" else v.elts[0]
        if isinstance(node, ast.Dict):
            for k, v in zip(node.keys, node.values):
                if isinstance(k, ast.Constant) and k.value in UNIT_KEYS:
                    yield v


def test_dimensionless_is_spelled_one_way_in_unit_fields():
    """Every unit field of the source that is a string spells dimensionless ``"1"`` (the table's); a
    parameter's unit is never empty (it is a number: ``"1"`` if dimensionless)."""
    bad, seen = [], 0
    for path in sorted(SRC.rglob("*.py")):
        tree = ast.parse(path.read_text())
        for node in _unit_fields(tree):
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                seen += 1
                if node.value.strip() in OTHER_SPELLINGS:
                    bad.append(f"{path.relative_to(SRC)}:{node.lineno}: {node.value!r}")
    assert seen > 50 and not bad
    for model, p in _all_parameters():
        assert p.unit, f"{model}.{p.name}: empty unit"


def test_dimensionless_is_shown_one_way():
    """People read ``-`` (typeset as a dash in figures) wherever the table says ``"1"``: docstrings of
    the generated functions, the CLI's model list, headers and axis labels all derive it from the table."""
    assert unit_text(DIMENSIONLESS) == DIMENSIONLESS_SHOWN == "-"
    assert unit_text("m/s") == "m/s" and unit_text("") == ""
    assert tex_unit(DIMENSIONLESS) == tex_unit(DIMENSIONLESS_SHOWN) == "–"
    assert axis_label("restitution").endswith(" (–)") and header("restitution") == "e"
    assert axis_label("model") == "Name of the impact model"
    assert "Prefactor [-]" in mi.deresiewicz_contact_time.__doc__
    # docstrings mark dimensionless [-], never [1]
    marks = Counter()
    for path in sorted(SRC.rglob("*.py")):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.ClassDef, ast.Module, ast.AsyncFunctionDef)):
                doc = ast.get_docstring(node) or ""
                marks.update(re.findall(r"(?<![\w\]`])\[(1|-)\](?![\w(])", doc))
    assert marks["-"] > 100 and marks["1"] == 0, marks


def test_cli_model_list_shows_dimensionless_as_people_read_it(capsys):
    from microimpact.cli import main

    assert main(["impact", "1", "--model", "list"]) == 0
    out = capsys.readouterr().out
    assert "restitution [-]:" in out and "work_of_adhesion [J/m^2]:" in out
    assert not re.search(r"\[1\]:", out)
