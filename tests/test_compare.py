"""``mi.compare_models`` and its figure; ``sweep(model=...)``, the sweep's model dimension."""

from __future__ import annotations

import math

import numpy as np
import pytest

import microimpact as mi
from microimpact.calibrate import calibrate
from microimpact.compare import COMPARED_FIELDS, default_models, seed_large_strain_velocity
from microimpact.core import quantities
from microimpact.core.models import thornton_ning_2016 as seed

pytest.importorskip("xarray")

SILICON = mi.ContactPair.paper_case("silicon")
V = np.array([5.0, 10.0, 30.0, 50.0, 100.0])


@pytest.fixture(scope="module")
def ds():
    return mi.compare_models(SILICON, V)


def test_layout_units_and_coordinates(ds):
    assert dict(ds.sizes) == {"model": len(default_models()), "velocity": V.size}
    assert list(ds["model"].values) == default_models()
    assert "jkr_elastic_adhesive" not in default_models()  # cannot be calibrated to a model without adhesion
    from microimpact.calibrate import DEM_MODELS

    left_out = set(mi.models.available()) - set(default_models())
    assert "jkr_elastic_adhesive" in left_out
    for name in left_out:  # only models with a required parameter that no calibration can supply
        required = [p for p, (_, _, d) in mi.models.parameters(name).items() if d != d]
        assert required and name not in DEM_MODELS, name
    for name, (unit, _) in COMPARED_FIELDS.items():
        assert ds[name].dims == ("model", "velocity")
        assert ds[name].attrs["units"] == quantities.QUANTITIES[name].unit
    assert ds["velocity"].attrs["units"] == "m/s"
    assert ds["large_strain"].dtype == bool
    cal = dict(zip(ds["model"].values, ds["calibrated"].values))
    assert cal == {
        "thornton_ning_2016": False,
        "liggghts_thornton_ning": False,
        "liggghts_hertz_sjkr": True,
        "linear_spring_dashpot": True,
        "hertz_viscoelastic": True,
        "hertz_tsuji": True,
        "luding_hysteretic": True,
        "liggghts_edinburgh": False,
        "lammps_jkr": True,
        "lammps_dmt": True,
        "lammps_mdr": False,  # every input has a default and its face no calibration: compared as it is
    }
    assert ds.attrs["reference_velocity"] == float(np.median(V)) == 30.0
    assert "calibrated to the seed's model (thornton_ning_2016) at V = 30 m/s" in ds.attrs["calibration"]


def test_seed_row_is_the_seed_closed_form(ds):
    # eq. 27 in its normalised form, evaluated independently of the object layer
    Vy = SILICON.yield_velocity
    e = [seed.restitution(v / Vy) for v in V]
    np.testing.assert_allclose(ds["restitution"].sel(model="thornton_ning_2016"), e, rtol=1e-14)
    np.testing.assert_allclose(ds["energy_loss"].sel(model="thornton_ning_2016"), 1.0 - np.square(e), rtol=1e-13)


def test_calibrated_laws_give_the_seed_e_at_the_reference_speed(ds):
    e_seed = float(ds["restitution"].sel(model="thornton_ning_2016", velocity=30.0))
    for name in ("linear_spring_dashpot", "hertz_viscoelastic", "hertz_tsuji", "luding_hysteretic"):
        assert abs(float(ds["restitution"].sel(model=name, velocity=30.0)) - e_seed) < 1e-10, name
    # the laws with a free stiffness also match the seed's contact time there
    t_seed = float(ds["contact_time"].sel(model="thornton_ning_2016", velocity=30.0))
    for name in ("linear_spring_dashpot", "luding_hysteretic"):
        assert float(ds["contact_time"].sel(model=name, velocity=30.0)) == pytest.approx(t_seed, rel=1e-9)
    # the parameters recorded are those of the calibration
    cal = calibrate(SILICON, "linear_spring_dashpot", 30.0)
    text = str(ds["parameters"].sel(model="linear_spring_dashpot").values)
    assert f"stiffness = {cal.params[0]:.10g}" in text


def test_given_parameters_are_used_and_not_calibrated():
    out = mi.compare_models(
        SILICON,
        [20.0, 60.0],
        ["linear_spring_dashpot", "jkr_elastic_adhesive"],
        {
            "linear_spring_dashpot": {"stiffness": 2e3, "restitution": 0.5},
            "jkr_elastic_adhesive": {"surface_energy": 0.1},
        },
    )
    assert not out["calibrated"].values.any()
    assert math.isnan(out.attrs["reference_velocity"])
    np.testing.assert_allclose(out["restitution"].sel(model="linear_spring_dashpot"), 0.5, rtol=1e-12)
    # JKR: e = (1 - V_s^2/V^2)^(1/2) above the sticking speed (its model file), V_s from the work of adhesion
    jkr = mi.models.get("jkr_elastic_adhesive")
    e20 = jkr.outcome(20.0, *SILICON._args, (0.1,))[4]
    assert float(out["restitution"].sel(model="jkr_elastic_adhesive", velocity=20.0)) == e20
    # a partly given law: the rest calibrated, the given value kept
    part = mi.compare_models(SILICON, [50.0], ["linear_spring_dashpot"], {"linear_spring_dashpot": {"limit_force": 1}})
    assert bool(part["calibrated"].values[0]) and "limit_force = 1" in str(part["parameters"].values[0])
    e_seed = float(SILICON.impact(50.0, warn=False).restitution)
    assert abs(float(part["restitution"].values[0, 0]) - e_seed) < 1e-10


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"models": ["nope"]}, "model must be one of"),
        ({"models": ["jkr_elastic_adhesive"]}, "needs the parameter 'surface_energy'"),
        ({"models": ["hertz_tsuji"], "reference_velocity": 5.0}, "above the yield velocity 7.52267 m/s"),
        ({"models": ["hertz_tsuji"], "reference_velocity": True}, "reference_velocity must be a number"),
        ({"models": "thornton_ning_2016", "params": {"hertz_tsuji": {}}}, "names the model 'hertz_tsuji'"),
        ({"models": ["hertz_tsuji", "hertz_tsuji"]}, "more than once"),
        ({"models": ["linear_spring_dashpot"], "params": {"linear_spring_dashpot": {"k": 1.0}}}, "no parameter 'k'"),
        ({"velocity": [0.0, 10.0]}, "velocity must be positive"),
        (
            {"models": ["linear_spring_dashpot"], "params": {"linear_spring_dashpot": {"restitution": 0.5}}},
            "give all of stiffness, restitution or none of them",
        ),
        ({"velocity": [-1.0]}, "velocity"),
    ],
)
def test_bad_input_is_named(kwargs, match):
    kwargs = {"velocity": [10.0, 50.0], **kwargs}
    with pytest.raises(ValueError, match=match):
        mi.compare_models(SILICON, **kwargs)


def test_seed_large_strain_velocity_is_where_a_over_r_is_03():
    V_ls = seed_large_strain_velocity(SILICON)
    assert V_ls == pytest.approx(23.27, abs=0.01)  # the paper figures' 23.3 m/s
    a = float(SILICON.impact(V_ls, warn=False).max_contact_radius)
    assert a / SILICON.effective_radius == pytest.approx(0.3, rel=1e-10)
    assert seed_large_strain_velocity(SILICON.elastic_equivalent()) > 0.0


def test_default_speeds_and_reference():
    out = mi.compare_models(models=["thornton_ning_2016", "hertz_tsuji"])
    assert out.attrs["reference_velocity"] == 50.0
    assert out["velocity"].values[0] == 1.0 and out["velocity"].values[-1] == 120.0
    assert SILICON.yield_velocity in out["velocity"].values


def test_figure_data_and_plot(ds):
    pytest.importorskip("matplotlib")
    from microimpact.figures.compare import COMPARISON_COLUMNS, comparison_data, plot_comparison

    data = comparison_data(ds)
    assert set(data) == set(COMPARISON_COLUMNS)
    n = ds.sizes["model"] * ds.sizes["velocity"]
    assert all(len(v) == n for v in data.values())
    rows = data["model"] == "luding_hysteretic"
    np.testing.assert_allclose(data["contact_time_ns"][rows], ds["contact_time"].sel(model="luding_hysteretic") * 1e9)
    axes = plot_comparison(ds)
    assert len(axes) == 3
    for ax in axes:
        assert len(ax.get_lines()) >= ds.sizes["model"]
        assert ax.get_xlabel() == "Impact velocity, $V$ (m/s)"
    labels = [t.get_text() for t in axes[0].figure.legends[0].get_texts()]
    assert "seed (Thornton-Ning 2016)" in labels and "linear spring-dashpot (cal.)" in labels
    with pytest.raises(ValueError, match="not both"):
        comparison_data(ds, models=["hertz_tsuji"])
    import matplotlib.pyplot as plt

    plt.close("all")


# ----------------------------------------------------------------------------- sweeps over models


def test_sweep_model_dimension_equals_one_sweep_per_model():
    from microimpact.sweep import sweep

    cal = calibrate(SILICON, "linear_spring_dashpot", 50.0).as_dict()
    names = ["thornton_ning_2016", "liggghts_thornton_ning", "linear_spring_dashpot"]
    pressures = np.array([100e6, 156e6])
    both = sweep(V, limiting_pressure=pressures, model=names, model_params={"linear_spring_dashpot": cal})
    assert both["restitution"].dims == ("model", "velocity", "limiting_pressure")
    assert list(both["model"].values) == names
    assert both["yield_velocity"].dims == ("limiting_pressure",)  # not per model
    for n in names:
        one = sweep(V, limiting_pressure=pressures, model=n, model_params={n: cal} if n == names[2] else None)
        assert str(one["model"].values) == n
        for f in ("restitution", "contact_time", "max_force"):
            np.testing.assert_array_equal(both[f].sel(model=n).values, one[f].values)
    # each model's own closed form through the object layer
    p = SILICON.replace(limiting_pressure=100e6)
    np.testing.assert_array_equal(
        both["restitution"].sel(model="liggghts_thornton_ning", limiting_pressure=100e6),
        p.impact(V, model="liggghts_thornton_ning", warn=False).restitution,
    )
    assert "linear_spring_dashpot: stiffness = " in both.attrs["model_parameters"]


def test_sweep_over_models_lazy_and_written(tmp_path):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("dask")
    from microimpact.sweep import sweep, sweep_to_csv, sweep_to_netcdf

    names = ["thornton_ning_2016", "liggghts_thornton_ning"]
    eager = sweep(V, model=names)
    lazy = sweep(V, model=names, chunks=2)
    assert lazy["restitution"].chunks is not None
    np.testing.assert_array_equal(lazy["restitution"].values, eager["restitution"].values)
    nc = sweep_to_netcdf(lazy, tmp_path / "m.nc")
    with xr.open_dataset(nc) as back:
        assert [str(x) for x in back["model"].values] == names
        np.testing.assert_array_equal(back["restitution"].values, eager["restitution"].values)
    csv = sweep_to_csv(eager, tmp_path / "m.csv")
    lines = csv.read_text().splitlines()
    assert lines[0].startswith("model,velocity [m/s],restitution [1]")
    assert len(lines) == 1 + len(names) * V.size
    assert lines[-1].startswith("liggghts_thornton_ning,100.0,")


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"model": ["nope"]}, "model must be one of"),
        ({"model": []}, "at least one model"),
        ({"model": ["hertz_tsuji", "hertz_tsuji"]}, "more than once"),
        ({"model": "linear_spring_dashpot"}, "needs the parameter 'stiffness'"),
        ({"model": "thornton_ning_2016", "model_params": {"hertz_tsuji": {}}}, "which is not swept"),
        ({"model": "thornton_ning_2016", "model_params": [1]}, "model_params must be a dict"),
    ],
)
def test_sweep_model_errors(kwargs, match):
    from microimpact.sweep import sweep

    with pytest.raises(ValueError, match=match):
        sweep(V, **kwargs)
