"""The README's numbers and example stay true: they are checked against the model here."""

import re
from pathlib import Path

import numpy as np

import microimpact as mi

README = Path(__file__).resolve().parents[1] / "README.md"


def _silicon_table():
    text = README.read_text()
    start = text.index("| V [m/s] | e |")
    rows = []
    for line in text[start:].splitlines()[2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip("|").split("|")]
        rows.append([float(re.match(r"[-\d.]+", c).group()) for c in cells])
    return np.array(rows)


def test_readme_silicon_table_matches_model():
    table = _silicon_table()
    assert table.shape == (4, 6)
    out = mi.ContactPair.paper_case("silicon").impact(table[:, 0], warn=False)
    cols = [
        out.restitution,
        out.rebound_velocity,
        out.plastic_approach * 1e9,
        out.loading_time * 1e6,
        out.unloading_time * 1e6,
    ]
    for j, model in enumerate(cols, start=1):
        printed = table[:, j]
        # each printed value is the model's, rounded to the digits shown (at most 5e-4 relative here)
        np.testing.assert_allclose(printed, model, rtol=6e-4, atol=6e-4, err_msg=f"column {j}")


def test_readme_example_runs():
    text = README.read_text()
    code = text.split("```python", 1)[1].split("```", 1)[0]
    import contextlib
    import io
    import warnings

    with warnings.catch_warnings(), contextlib.redirect_stdout(io.StringIO()) as buf:
        warnings.simplefilter("ignore", mi.LargeStrainWarning)
        exec(compile(code, "README", "exec"), {})
    assert "7.52" in buf.getvalue()


def test_readme_commands_exist():
    import contextlib
    import io

    from microimpact.cli import main

    text = README.read_text()
    commands = set(re.findall(r"^[ \t]+microimpact ([\w-]+)", text, flags=re.M))
    unknown = []
    for command in sorted(commands):  # a command's --help exits 0; an unknown command is a usage error (2)
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            if main([command, "--help"]) != 0:
                unknown.append(command)
    assert commands and unknown == [], unknown
    head = "\n".join(text.splitlines()[:10])  # the two commands come first
    assert 'pip install ".[paper]" && microimpact paper' in head
    assert 'pip install ".[test]" && python -m pytest' in head
