"""Build-time pages computed from the installed package (no typed-in numbers).

On ``builder-inited`` this extension writes, into ``docs/_generated/``:

* ``comparison.rst``: a table of every number the seed paper quotes in its
  Section 3 beside the value :func:`microimpact.paper.compare_with_paper`
  computes now, with the relative difference and the note that explains it;
* ``cli_<command>.txt``: the ``--help`` text of each ``microimpact`` command,
  included by ``cli.rst``;
* ``microimpact_wall.c``: the exported C function (``howto/cfd.rst``);
* ``columns.rst``, ``figures.rst``: the report's file and column glossary
  (``howto/read_report.rst``).

A failure to compute the comparison is a Sphinx warning, hence an error under
``-W``: the page never shows stale or typed-in values.
"""

from __future__ import annotations

import math
from pathlib import Path

from sphinx.util import logging

logger = logging.getLogger(__name__)


def _cell(x) -> str:
    """A table cell: numbers to 5 significant figures, text on one line."""
    if x is None:
        return ""
    if isinstance(x, bool):
        return "yes" if x else "**no**"
    if isinstance(x, (int, float)):
        return "n/a" if math.isnan(x) else f"{x:.5g}"
    text = " ".join(str(x).split())
    for ch in "\\*`_|":  # plain text: no inline markup, substitutions or references
        text = text.replace(ch, "\\" + ch)
    return text


def _list_table(caption: str, header: list[str], rows: list[list[str]], widths: list[int]) -> str:
    lines = [f".. list-table:: {caption}", "   :header-rows: 1", "   :widths: " + " ".join(map(str, widths)), ""]
    for row in [header] + rows:
        lines.append("   * - " + (row[0] or "\\ "))
        lines += ["     - " + (cell or "\\ ") for cell in row[1:]]
    return "\n".join(lines) + "\n"


def comparison_rst() -> str:
    """Both tables of the comparison page, from :mod:`microimpact.paper` at build time."""
    from microimpact import paper

    rows = []
    for r in paper.compare_with_paper():
        rel = r.get("relative_difference")
        rows.append(
            [
                _cell(r["quantity"]),
                _cell(r.get("where")),
                _cell(r["quoted"]),
                _cell(r["computed"]),
                _cell(r.get("unit")),
                "" if rel is None else f"{100 * float(rel):+.2f} %",
                "yes" if r.get("agrees") else ("no: see note" if r.get("note") else "**no**"),
                _cell(r.get("note")),
            ]
        )
    out = _list_table(
        f"Numbers quoted in the paper's Section 3 against the model (computed when these pages were "
        f"built; 'within' means a relative difference of at most {100 * paper.TOLERANCE:g} %)",
        ["Quantity", "Where", "Paper", "Computed", "Unit", "Relative difference", "Within", "Note"],
        rows,
        [18, 9, 8, 8, 5, 9, 6, 37],
    )
    statements = [
        [_cell(r.get("where")), _cell(r.get("statement")), _cell(r.get("holds")), _cell(r.get("detail"))]
        for r in paper.check_statements()
    ]
    out += "\n.. _comparison-statements:\n\n" + _list_table(
        "Qualitative statements of the paper, checked against the model",
        ["Where", "Statement", "Holds", "Computed detail"],
        statements,
        [12, 35, 6, 47],
    )
    return out


def columns_rst() -> str:
    """The column glossary of the figure CSVs (microimpact.figures.paper.COLUMNS)."""
    from microimpact.figures import paper as figs

    rows = [[f"``{name}``", _cell(unit), _cell(desc)] for name, (unit, desc) in figs.COLUMNS.items()]
    return _list_table("Columns of the figure CSV files (figN.csv)", ["Column", "Unit", "Meaning"], rows, [25, 10, 65])


def figures_rst() -> str:
    """The list of figure files and what each shows (microimpact.paper.FIGURES)."""
    from microimpact import paper

    rows = [[f"``{key}.png``, ``{key}.csv``", _cell(title), _cell(caption)] for key, title, caption in paper.FIGURES]
    return _list_table("Figures written by microimpact paper", ["Files", "Figure", "What it shows"], rows, [20, 25, 55])


def cli_helps() -> dict[str, str]:
    from microimpact import cli

    parser = cli.build_parser()
    out = {"main": parser.format_help()}
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    for name, p in sub.choices.items():
        out[name] = p.format_help()
    return out


def c_source() -> str:
    """The exported C99 wall function for the paper's silicon case, G = 0.1 J/m^2, mu = 0.3."""
    from microimpact import cexport
    from microimpact.pair import ContactPair

    return cexport.generate_c_source(ContactPair.paper_case("silicon"), work_of_adhesion=0.1, friction=0.3)


def _write(path: Path, text: str) -> None:
    if not path.exists() or path.read_text() != text:  # keep mtimes stable: no needless rebuilds
        path.write_text(text)


def generate(app) -> None:
    gen = Path(app.srcdir) / "_generated"
    gen.mkdir(exist_ok=True)
    try:
        table = comparison_rst()
    except Exception as exc:  # noqa: BLE001 - reported as a (fatal under -W) warning
        logger.warning("paper comparison could not be computed: %s: %s", type(exc).__name__, exc)
        table = ".. warning:: The comparison could not be computed when these pages were built.\n"
    _write(gen / "comparison.rst", table)
    for name, func in (("columns.rst", columns_rst), ("figures.rst", figures_rst)):
        try:
            _write(gen / name, func())
        except Exception as exc:  # noqa: BLE001
            logger.warning("%s could not be generated: %s: %s", name, type(exc).__name__, exc)
            _write(gen / name, "")
    try:
        helps = cli_helps()
    except Exception as exc:  # noqa: BLE001
        logger.warning("CLI help could not be generated: %s: %s", type(exc).__name__, exc)
        helps = {}
    names = []
    for name, text in helps.items():
        # argparse wraps to $COLUMNS; the files are written at a fixed width by the caller
        _write(gen / f"cli_{name}.txt", text)
        if name != "main":
            names.append(name)
    index = ["", ".. literalinclude:: _generated/cli_main.txt", "   :language: none", ""]
    for name in names:
        index += [name, "-" * len(name), "", f".. literalinclude:: _generated/cli_{name}.txt", "   :language: none", ""]
    _write(gen / "cli_commands.rst", "\n".join(index))
    try:
        _write(gen / "microimpact_wall.c", c_source())
    except Exception as exc:  # noqa: BLE001
        logger.warning("C source could not be generated: %s: %s", type(exc).__name__, exc)


def setup(app):
    import os

    os.environ["COLUMNS"] = "100"  # argparse's wrap width, so the help text is reproducible
    app.connect("builder-inited", generate)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
