"""``microimpact compare`` and ``microimpact sweep --model``."""

from __future__ import annotations

import json

import numpy as np
import pytest

import microimpact as mi
from microimpact.cli import main

pytest.importorskip("xarray")
SILICON = mi.ContactPair.paper_case("silicon")


def test_table_names_the_calibration(capsys):
    assert main(["compare", "10,50", "--model", "thornton_ning_2016,hertz_tsuji"]) == 0
    out = capsys.readouterr().out
    assert "hertz_tsuji (calibrated): damping_ratio = " in out
    assert "calibration: hertz_tsuji calibrated to the seed's model (thornton_ning_2016) at V = 30 m/s" in out
    rows = [line.split() for line in out.splitlines() if line.startswith(("thornton_ning_2016 ", "hertz_tsuji "))]
    assert len(rows) == 4
    e = {(r[0], float(r[1])): float(r[2]) for r in rows}
    assert e[("thornton_ning_2016", 50.0)] == pytest.approx(
        float(SILICON.impact(50.0, warn=False).restitution), abs=5e-6
    )
    assert e[("hertz_tsuji", 10.0)] == e[("hertz_tsuji", 50.0)]  # Tsuji's e does not depend on the speed
    assert "* contact radius above 0.3 R*" in out  # 50 m/s is flagged


def test_json_matches_the_api(capsys):
    argv = ["compare", "20", "60", "--model", "thornton_ning_2016,linear_spring_dashpot"]
    argv += ["--param", "linear_spring_dashpot:stiffness=2000", "--param", "linear_spring_dashpot:restitution=0.5"]
    assert main([*argv, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    ds = mi.compare_models(
        SILICON,
        [20.0, 60.0],
        ["thornton_ning_2016", "linear_spring_dashpot"],
        {"linear_spring_dashpot": {"stiffness": 2000.0, "restitution": 0.5}},
    )
    assert doc["velocity"] == [20.0, 60.0]
    assert doc["units"]["contact_time"] == "s" and doc["units"]["restitution"] == "1"
    assert doc["reference_velocity"] is None  # nothing calibrated: NaN written as null
    assert doc["models"]["linear_spring_dashpot"]["calibrated"] is False
    for i, name in enumerate(ds["model"].values):
        for k in ("restitution", "contact_time", "energy_loss"):
            np.testing.assert_array_equal(doc["results"][name][k], ds[k].values[i])


def test_files_and_plot(tmp_path, capsys):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("matplotlib")
    nc, png, csv = tmp_path / "c.nc", tmp_path / "c.png", tmp_path / "c.csv"
    argv = ["compare", "5:100:4", "--model", "thornton_ning_2016,liggghts_thornton_ning,luding_hysteretic"]
    assert main([*argv, "--out", str(nc), "--plot", str(png), "--reference-velocity", "40"]) == 0
    assert f"wrote {nc}, {png}" in capsys.readouterr().out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with xr.open_dataset(nc) as back:
        assert [str(m) for m in back["model"].values] == [
            "thornton_ning_2016",
            "liggghts_thornton_ning",
            "luding_hysteretic",
        ]
        assert back.attrs["reference_velocity"] == 40.0
        e_seed = float(back["restitution"].sel(model="thornton_ning_2016").interp(velocity=40.0))
        assert back["contact_time"].attrs["units"] == "s"
    assert main([*argv, "--out", str(csv)]) == 0
    lines = csv.read_text().splitlines()
    assert lines[0].startswith("model,velocity [m/s],restitution [1],energy_loss [1],contact_time [s]")
    assert len(lines) == 1 + 3 * 4
    assert 0.0 < e_seed < 1.0


@pytest.mark.parametrize(
    "argv, match",
    [
        (["--model", "nope"], "--model: model must be one of"),
        (["--model", "jkr_elastic_adhesive"], "needs the parameter 'surface_energy'"),
        (["--param", "stiffness=1"], "must name its model"),
        (["--model", "hertz_tsuji", "--param", "linear_spring_dashpot:stiffness=1"], "not among --model hertz_tsuji"),
        (["--model", "hertz_tsuji", "--param", "hertz_tsuji:alpha=1"], "has no parameter 'alpha'"),
        (["--model", "hertz_tsuji", "--param", "hertz_tsuji:damping_ratio=x"], "must be a number, got 'x'"),
        (["--model", "hertz_tsuji", "--param", "hertz_tsuji"], "must be MODEL:NAME=VALUE"),
        (["--model", "hertz_tsuji", "--reference-velocity", "3"], "above the yield velocity"),
        (["--out", "c.txt"], "--out must end in .nc"),
        (["--plot", "c.xyz"], "xyz"),
    ],
)
def test_bad_options_are_one_line(argv, match, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["compare", "10,50", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("microimpact compare: error: ") and err.count("\n") == 1
    assert match in err
    assert list(tmp_path.iterdir()) == []  # nothing written


def test_single_model_param_without_prefix(capsys):
    assert main(["compare", "30", "--model", "jkr_elastic_adhesive", "--param", "surface_energy=0.05"]) == 0
    out = capsys.readouterr().out
    assert "jkr_elastic_adhesive: surface_energy = 0.05" in out
    assert "calibration: none" in out


def test_sweep_over_models(tmp_path, capsys):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("dask")
    out = tmp_path / "s.nc"
    argv = ["sweep", "--velocity", "10,50", "--limiting-pressure", "100e6,156e6", "--out", str(out), "-q"]
    argv += ["--model", "thornton_ning_2016,linear_spring_dashpot"]
    argv += ["--param", "linear_spring_dashpot:stiffness=1000", "--param", "linear_spring_dashpot:restitution=0.7"]
    assert main(argv) == 0
    with xr.open_dataset(out) as back:
        assert back["restitution"].dims == ("model", "velocity", "limiting_pressure")
        np.testing.assert_allclose(back["restitution"].sel(model="linear_spring_dashpot"), 0.7, rtol=1e-12)
        np.testing.assert_array_equal(
            back["restitution"].sel(model="thornton_ning_2016", limiting_pressure=156e6),
            SILICON.impact(np.array([10.0, 50.0]), warn=False).restitution,
        )
        assert "restitution = 0.7" in back.attrs["model_parameters"]
    capsys.readouterr()
    assert main(["sweep", "--velocity", "10,50", "--out", str(out), "--model", "linear_spring_dashpot", "-q"]) == 2
    assert "needs the parameter 'stiffness'" in capsys.readouterr().err


# ------------------------------------------------------------------ compare --tangential


def test_tangential_table_is_compare_tangential(capsys):
    """The table prints compare_tangential's numbers (oblique_impact per law) at their printed precision."""
    from microimpact import oblique as ob
    from microimpact.compare import compare_tangential

    laws = ["mindlin", "lammps_mindlin", "stronge", "rigid"]
    assert main(["compare", "--tangential", ",".join(laws), "--alumina", "--angles", "5,20,45"]) == 0
    out = capsys.readouterr().out
    assert "kappa = 4G*/E* = 0.875415" in out  # alumina on glass, both materials' G*
    rows = [line.split() for line in out.splitlines() if line.split() and line.split()[0] in laws]
    assert [r[0] for r in rows] == [n for n in laws for _ in range(3)]
    c = ob.ALUMINA_CASE
    ds = compare_tangential(ob.alumina_pair(), c["velocity"], [5.0, 20.0, 45.0], c["friction"], laws)
    for i, law in enumerate(laws):
        block = rows[3 * i : 3 * i + 3]
        assert [float(r[2]) for r in block] == pytest.approx(ds["tangential_restitution"].values[i], abs=6e-6)
        assert [float(r[3]) for r in block] == pytest.approx(ds["rebound_spin"].values[i], rel=1e-4)
        assert [r[7] for r in block] == list(ds["regime"].values[i])
    # the laws do differ where the issue says they do (small angles): a table of one law repeated would fail
    e5 = {r[0]: float(r[2]) for r in rows if r[1] == "5"}
    assert e5["lammps_mindlin"] - e5["mindlin"] > 0.05 and e5["mindlin"] - e5["rigid"] > 0.1


def test_tangential_json_files_and_plot(tmp_path, capsys):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("matplotlib")
    from microimpact import oblique as ob

    nc, png = tmp_path / "t.nc", tmp_path / "t.png"
    argv = ["compare", "2.5", "--tangential", "all", "--angles", "10,40", "--friction", "0.2", "--poisson", "0.25"]
    assert main([*argv, "--json", "--out", str(nc), "--plot", str(png)]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert list(doc["results"]) == list(ob.TANGENTIAL_MODELS) and doc["angle"] == [10.0, 40.0]
    assert doc["units"]["rebound_spin"] == "rad/s"
    for law in ("di_renzo_di_maio", "liggghts_history"):
        o = ob.oblique_impact(SILICON, 2.5, [10.0, 40.0], 0.2, poisson_ratio=0.25, tangential=law)
        np.testing.assert_array_equal(doc["results"][law]["rebound_spin"], o.rebound_spin)
        assert doc["results"][law]["regime"] == list(o.regime)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with xr.open_dataset(nc) as back:
        assert list(back["tangential"].values) == list(ob.TANGENTIAL_MODELS)
        np.testing.assert_array_equal(
            back["tangential_restitution"].values[1], doc["results"]["rigid"]["tangential_restitution"]
        )


@pytest.mark.parametrize(
    "argv, match",
    [
        (["--tangential", "mindlin,nope", "--alumina"], "got 'nope'"),
        (["--tangential", "", "--alumina"], "at least one model"),
        (["--tangential", "mindlin", "--alumina", "--model", "hertz_tsuji"], "--model and --tangential"),
        (
            ["--tangential", "mindlin", "--alumina", "--reference-velocity", "3"],
            "--reference-velocity and --tangential",
        ),
        (["--tangential", "mindlin", "--alumina", "--dem-lines"], "--dem-lines and --tangential"),
        (["10", "--angles", "5,10"], "--angles is used with --tangential only"),
        (["10", "--alumina"], "--alumina is used with --tangential only"),
        (["--tangential", "mindlin", "1", "2"], "one resultant speed"),
        (["--tangential", "mindlin"], "needs the resultant impact speed"),
        (["--tangential", "mindlin", "0"], "velocity must be positive"),
        (["--tangential", "mindlin", "--alumina", "--case", "silicon"], "--alumina and --case"),
        (["--tangential", "mindlin", "--alumina", "--angles", "95"], "angle must be in"),
        (["--tangential", "mindlin", "--alumina", "--friction", "-1"], "friction"),
        (["--tangential", "mindlin", "--alumina", "--poisson", "0.7"], "poisson"),
        (["--tangential", "mindlin", "--alumina", "--out", "t.txt"], "--out must end in"),
        (["--tangential", "mindlin", "--alumina", "--plot", "nodir/t.png"], "nodir"),
    ],
)
def test_tangential_bad_input_is_one_line_exit_2(argv, match, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["compare", *argv]) == 2
    err = capsys.readouterr().err
    assert match in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []  # nothing written
