"""``microimpact stick``: capture velocity against diameter as a table, JSON and CSV; one-line errors."""

from __future__ import annotations

import json

import pytest

import microimpact as mi
from microimpact.cli import main

SILICON = mi.ContactPair.paper_case("silicon")


def test_table_is_the_api(capsys):
    assert main(["stick", "1e-7,2e-6", "-G", "1"]) == 0
    out = capsys.readouterr().out
    rows = [line.split() for line in out.splitlines() if line.strip()[:1].isdigit()]
    assert len(rows) == 2
    full = SILICON.sticking_velocity([1e-7, 2e-6], work_of_adhesion=1.0)
    add = SILICON.sticking_velocity([1e-7, 2e-6], model="additive", work_of_adhesion=1.0)
    for r, f, a in zip(rows, full, add):
        assert float(r[1]) == pytest.approx(a, rel=1e-4) and float(r[3]) == pytest.approx(f, rel=1e-4)
    assert "part by more than 10 % below d = 1.659e-06 m" in out


def test_json_and_csv(capsys, tmp_path):
    csv = tmp_path / "stick.csv"
    assert main(["stick", "5e-7", "--work-of-adhesion", "0.5", "--json", "--out", str(csv)]) == 0
    doc = json.loads(capsys.readouterr().out)
    v = doc["laws"]["thornton_ning_1998_adhesive_plastic"]["capture_velocity"][0]
    assert (
        doc["units"]
        == {  # from the quantities table, not typed in the command
            q: mi.quantities.QUANTITIES[q].unit
            for q in ("diameter", "capture_velocity", "yield_velocity", "parting_diameter")
        }
        == {"diameter": "m", "capture_velocity": "m/s", "yield_velocity": "m/s", "parting_diameter": "m"}
    )
    assert v == SILICON.sticking_velocity(5e-7, work_of_adhesion=0.5)
    lines = csv.read_text().splitlines()
    assert lines[0].startswith("diameter [m],capture_velocity_additive [m/s]")
    assert float(lines[-1].split(",")[3]) == v


@pytest.mark.parametrize(
    "argv, message",
    [
        (["stick", "1e-7"], "the following arguments are required: --work-of-adhesion"),
        (["stick", "-G", "-1"], "--work-of-adhesion must be non-negative and finite, got -1.0"),
        (["stick", "-G", "1", "--law", "jkr"], "--law must name laws among additive, "),
        (["stick", "-G", "1", "0"], "diameter must be positive and finite, got 0.0"),
        (["stick", "-G", "1", "--out", "x.txt"], "--out must end in .csv"),
    ],
)
def test_errors_are_one_line(argv, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1
    assert not list(tmp_path.iterdir())  # nothing written


def test_any_capturing_law_with_its_parameters(capsys, tmp_path, monkeypatch):
    """``--law`` takes every law that captures a particle; ``--param`` sets a law's other inputs."""
    monkeypatch.chdir(tmp_path)
    assert main(["stick", "-G", "0.2", "--law", "jkr_elastic_adhesive", "--json", "1e-6"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert (
        set(doc["laws"]) == {"jkr_elastic_adhesive"} and doc["laws"]["jkr_elastic_adhesive"]["capture_velocity"][0] > 0
    )
    argv = ["stick", "-G", "0.2", "--law", "jkr_elastic_adhesive", "--param", "jkr_elastic_adhesive:nothing=1", "1e-6"]
    assert main(argv) == 2
    assert "has no parameter 'nothing'" in capsys.readouterr().err
    assert main(["stick", "-G", "0.2", "--param", "additive:x=1", "1e-6"]) == 2
    assert "additive rule takes no parameters" in capsys.readouterr().err


def test_a_law_with_an_input_without_default_needs_it(capsys, tmp_path, monkeypatch):
    """A liquid bridge's liquid has no default and no work of adhesion sets it: refused naming it and
    the option that gives it; given, the table holds the law's own capture velocity."""
    monkeypatch.chdir(tmp_path)
    assert main(["stick", "-G", "0.2", "--law", "willett_capillary", "1e-6"]) == 2
    err = capsys.readouterr().err
    assert "needs 'liquid_volume' (no default)" in err and "--param willett_capillary:liquid_volume=" in err
    assert len(err.strip().splitlines()) == 1
    argv = ["stick", "-G", "0.2", "--law", "willett_capillary", "--param", "liquid_volume=5e-22", "--json", "1e-6"]
    assert main(argv) == 0
    doc = json.loads(capsys.readouterr().out)
    want = SILICON.resized(radius=0.5e-6).sticking_velocity(model="willett_capillary", liquid_volume=5e-22)
    assert doc["laws"]["willett_capillary"]["capture_velocity"][0] == want
