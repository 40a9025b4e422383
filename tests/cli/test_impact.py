"""The ``microimpact impact`` and ``materials`` commands."""

import json
import subprocess
import sys

import numpy as np
import pytest

import microimpact as mi
from microimpact.cli import main


def run(argv, capsys):
    rc = main(argv)
    cap = capsys.readouterr()
    return rc, cap.out, cap.err


def test_json_equals_api(capsys):
    rc, out, err = run(["impact", "10", "30,50", "60:80:3", "--json"], capsys)
    assert rc == 0
    doc = json.loads(out)
    V = np.array([10, 30, 50, 60, 70, 80.0])
    ref = mi.ContactPair.paper_case("silicon").impact(V, warn=False)
    for name in ("restitution", "rebound_velocity", "plastic_approach", "contact_time", "max_force"):
        np.testing.assert_array_equal(doc["results"][name], getattr(ref, name))
    assert doc["units"]["max_force"] == "N"
    assert doc["pair"]["yield_velocity"] == pytest.approx(ref.yield_velocity[0])
    # every one of these speeds except 10 m/s is beyond a/R* = 0.3: the CLI warns on stderr
    assert "warning" in err and "5 of 6" in err


def test_table_shows_values_and_flags(capsys):
    rc, out, err = run(["impact", "5", "50", "--case", "silicon"], capsys)
    assert rc == 0
    ref = mi.ContactPair.paper_case("silicon").impact(50.0, warn=False)
    assert f"{float(ref.restitution):.5f}" in out
    assert f"{float(ref.plastic_approach) * 1e9:.5g}" in out
    assert "t_c [ns]" in out
    lines = out.splitlines()
    assert lines[-1].endswith("*") and not lines[-2].endswith("*")  # 50 m/s flagged, 5 m/s not


def test_materials_pair(capsys):
    rc, out, _ = run(
        [
            "impact",
            "50",
            "--particle",
            "nh4fl",
            "--surface",
            "mica",
            "--diameter",
            "4.9e-6",
            "--limiting-pressure",
            "158e6",
            "--json",
        ],
        capsys,
    )
    assert rc == 0
    ref = mi.ContactPair.from_materials("nh4fl", "mica", radius=2.45e-6, limiting_pressure=158e6)
    assert json.loads(out)["results"]["restitution"][0] == pytest.approx(float(ref.restitution(50.0)), rel=1e-15)


def test_effective_values_pair(capsys):
    rc, out, _ = run(
        [
            "impact",
            "20",
            "--effective-modulus",
            "2e9",
            "--radius",
            "1e-6",
            "--density",
            "2000",
            "--limiting-pressure",
            "2e8",
            "--json",
        ],
        capsys,
    )
    ref = mi.ContactPair.sphere_on_flat(1e-6, 2000.0, 2e9, 2e8).impact(20.0, warn=False)
    assert json.loads(out)["results"]["rebound_velocity"][0] == pytest.approx(float(ref.rebound_velocity), rel=1e-15)


@pytest.mark.parametrize(
    "argv, word",
    [
        (["impact", "-5"], "velocity"),
        (["impact", "nan"], "velocity"),
        (["impact", "abc"], "velocity"),
        (["impact", "1:2"], "range"),
        (
            [
                "impact",
                "10",
                "--effective-modulus",
                "-1e9",
                "--radius",
                "1e-6",
                "--density",
                "1000",
                "--limiting-pressure",
                "1e8",
            ],
            "--effective-modulus",
        ),
        (["impact", "10", "--particle", "nh4fl", "--surface", "kryptonite", "--radius", "1e-6"], "kryptonite"),
        (["impact", "10", "--particle", "nh4fl", "--surface", "silicon"], "radius"),
        (["impact", "10", "--particle", "glass", "--surface", "silicon", "--radius", "1e-6"], "limiting_pressure"),
    ],
)
def test_bad_input_one_line_exit_2(argv, word, capsys):
    rc, out, err = run(argv, capsys)
    assert rc == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and word in lines[0] and "Traceback" not in err


def test_console_script_exit_status():
    proc = subprocess.run([sys.executable, "-m", "microimpact", "impact", "-1"], capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stderr.strip().count("\n") == 0 and "velocity" in proc.stderr


def test_materials_command(capsys):
    rc, out, _ = run(["materials"], capsys)
    assert rc == 0 and "nh4fl" in out and "fly_ash" in out
    rc, out, _ = run(["materials", "silicon"], capsys)
    assert "Hopcroft" in out


def test_model_option_gives_the_model_outcome(capsys):
    """``--model NAME --param k=v`` evaluates that model: the linear spring-dashpot returns its e_n."""
    import json

    from microimpact.cli import main

    rc = main(["impact", "10", "50", "--model", "linear_spring_dashpot", "--param", "stiffness=1000",
               "--param", "restitution=0.7", "--json"])  # fmt: skip
    doc = json.loads(capsys.readouterr().out)
    assert rc == 0 and doc["model"]["name"] == "linear_spring_dashpot"
    assert doc["results"]["restitution"] == pytest.approx([0.7, 0.7], rel=1e-14)
    assert doc["results"]["elastic_stage_time"] == [None, None]  # not defined by that model: NaN -> null


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--model", "nope"], "model must be one of"),
        (["--model", "hertz_viscoelastic"], "dissipative_constant"),
        (["--model", "linear_spring_dashpot", "--param", "stiffness"], "NAME=VALUE"),
        (["--param", "x=1"], "has no parameter 'x'"),
    ],
)
def test_model_option_refuses_bad_input(capsys, argv, words):
    from microimpact.cli import main

    rc = main(["impact", "50", *argv])
    err = capsys.readouterr().err
    assert rc == 2 and words in err and len(err.strip().splitlines()) == 1


def test_model_list(capsys):
    from microimpact.cli import main
    from microimpact.models import available

    assert main(["impact", "1", "--model", "list"]) == 0
    out = capsys.readouterr().out
    assert all(f"{name}:" in out for name in available())
