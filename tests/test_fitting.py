"""Fitting p_y (and k, E*, density, V_y) to restitution data: microimpact.fitting and ``microimpact fit``.

Synthetic data are the model's own e(V) (seed eq. 27) plus seeded Gaussian noise
(numpy default_rng with fixed seeds), so the true parameters are known exactly.
"""

import json
import math
import re

import numpy as np
import pytest
from scipy import stats

import microimpact as mi
from microimpact.cli import main
from microimpact.figures.fit import plot_fit, plot_residuals
from microimpact.fitting import (
    FREE_PARAMETERS,
    TUNING,
    FitResult,
    FitWarning,
    fit_restitution,
)
from microimpact.io import load_restitution_csv

SILICON = mi.ContactPair.paper_case("silicon")


def pairs():
    """Several pairs with very different yield velocities (7.5 m/s ... 0.7 mm/s)."""
    return {
        "silicon": SILICON,
        "mica": mi.ContactPair.paper_case("mica"),
        "nh4fl_on_silicon_materials": mi.ContactPair.from_materials("nh4fl", "silicon", radius=2.45e-6),
        "copper_on_steel": mi.ContactPair.from_materials("copper", "steel", radius=5e-6),
    }


def synthetic(pair, noise, seed, n=24, span=(2.5, 14.0)):
    """Speeds from span[0] V_y to span[1] V_y (all plastic), e = model + N(0, noise)."""
    rng = np.random.default_rng(seed)
    V = pair.yield_velocity * np.geomspace(*span, n)
    e = pair.restitution(V) + rng.normal(0.0, noise, n)
    assert np.all((e > 0) & (e <= 1))  # the data are valid as drawn, never clipped
    return V, e


def start(pair, name):
    """A deliberately wrong reference value of the free parameter (the fit must not depend on it)."""
    if name == "limiting_pressure":
        return pair.replace(limiting_pressure=pair.limiting_pressure * 0.4)
    if name == "effective_modulus":
        return pair.replace(effective_modulus=pair.effective_modulus * 3.0)
    if name == "density":
        rho = pair.density * 2.0
        return pair.replace(density=rho, effective_mass=4 / 3 * math.pi * pair.effective_radius**3 * rho)
    return pair


def true_value(pair, name, yield_strength=None):
    return {
        "limiting_pressure": pair.limiting_pressure,
        "effective_modulus": pair.effective_modulus,
        "density": pair.density,
        "yield_velocity": pair.yield_velocity,
        "k": pair.limiting_pressure / yield_strength if yield_strength else None,
    }[name]


# ----------------------------------------------------------------------------- recovery
@pytest.mark.parametrize("name", ["limiting_pressure", "effective_modulus", "density", "yield_velocity", "k"])
@pytest.mark.parametrize("case", ["silicon", "mica", "copper_on_steel"])
def test_noise_free_data_give_the_parameter_back_to_1e6(case, name):
    pair = pairs()[case]
    # include elastic points (e = 1 exactly) below V_y: they must not disturb the fit
    V = pair.yield_velocity * np.concatenate([[0.3, 0.7, 0.95], np.geomspace(1.5, 20.0, 12)])
    e = pair.restitution(V)
    Y = 74e6 if name == "k" else None
    fit = fit_restitution(V, e, start(pair, name), params=(name,), yield_strength=Y)
    truth = true_value(pair, name, Y)
    assert fit.success
    assert fit.params[name] == pytest.approx(truth, rel=1e-6)
    assert fit.yield_velocity == pytest.approx(pair.yield_velocity, rel=1e-6)
    assert fit.n_elastic == 3 and fit.n_points == 15 and fit.dof == 14
    # the fitted pair is ready to use and reproduces the data
    np.testing.assert_allclose(fit.pair.restitution(V), e, atol=1e-8)
    np.testing.assert_allclose(fit.residuals, 0.0, atol=1e-8)


@pytest.mark.parametrize("case", list(pairs()))
@pytest.mark.parametrize("noise", [0.005, 0.02, 0.05])
def test_noisy_data_interval_contains_the_truth(case, noise):
    pair = pairs()[case]
    V, e = synthetic(pair, noise, seed=1000 * list(pairs()).index(case) + int(noise * 1000), span=(3.0, 14.0))
    for sigma in (None, np.full(V.size, noise)):
        fit = fit_restitution(V, e, start(pair, "limiting_pressure"), sigma=sigma)
        lo, hi = fit.conf_int["limiting_pressure"]
        assert lo < pair.limiting_pressure < hi
        lo, hi = fit.yield_velocity_conf_int
        assert lo < pair.yield_velocity < hi
        # the error shrinks with the noise: relative standard error about noise-proportional
        rel = fit.stderr["limiting_pressure"] / fit.params["limiting_pressure"]
        assert 0.02 * noise < rel < 2.0 * noise


def test_interval_is_symmetric_in_log_p_y_with_student_t():
    V, e = synthetic(SILICON, 0.03, seed=7)
    fit = fit_restitution(V, e, SILICON)
    est, (lo, hi), se = (
        fit.params["limiting_pressure"],
        fit.conf_int["limiting_pressure"],
        fit.stderr["limiting_pressure"],
    )
    q = stats.t.ppf(0.975, fit.dof)
    # symmetric in ln p_y, with the Student t quantile of n - 1 degrees of freedom
    assert math.log(hi / est) == pytest.approx(math.log(est / lo), rel=1e-12)
    assert math.log(hi / est) == pytest.approx(q * se / est, rel=1e-12)
    assert fit.covariance[0, 0] == pytest.approx(se**2, rel=1e-12)
    # V_y ~ p_y^(5/2): its relative error is 5/2 that of p_y
    assert fit.yield_velocity_stderr / fit.yield_velocity == pytest.approx(2.5 * se / est, rel=1e-12)


def test_stderr_matches_the_scatter_of_repeated_fits():
    """Independent check of the Jacobian-based standard error: the spread of 200 estimates."""
    V = SILICON.yield_velocity * np.geomspace(2.5, 14.0, 20)
    est, se = [], []
    for seed in range(200):
        e = SILICON.restitution(V) + np.random.default_rng(5000 + seed).normal(0, 0.02, V.size)
        fit = fit_restitution(V, e, SILICON, sigma=np.full(V.size, 0.02))
        est.append(fit.params["limiting_pressure"])
        se.append(fit.stderr["limiting_pressure"])
    # sd of 200 draws is known to about 1/sqrt(2*199) = 5 %; 15 % is 3 of those
    assert np.std(est, ddof=1) == pytest.approx(np.mean(se), rel=0.15)
    assert np.mean(est) == pytest.approx(SILICON.limiting_pressure, abs=4 * np.mean(se) / math.sqrt(200))


# ----------------------------------------------------------------------------- identifiability
def test_p_y_and_E_star_are_not_separately_identifiable():
    """Why only one parameter can be free: E* -> lam E*, p_y -> lam^(4/5) p_y leaves e(V) unchanged."""
    V = np.geomspace(1, 200, 50)
    for lam in (0.3, 2.0, 10.0):
        other = SILICON.replace(
            effective_modulus=SILICON.effective_modulus * lam, limiting_pressure=SILICON.limiting_pressure * lam**0.8
        )
        np.testing.assert_allclose(other.restitution(V), SILICON.restitution(V), rtol=1e-12)
    V = SILICON.yield_velocity * np.geomspace(1.2, 100, 30)  # however wide the range
    e = SILICON.restitution(V)
    with pytest.raises(ValueError, match="not separately identifiable"):
        fit_restitution(V, e, SILICON, params=("limiting_pressure", "effective_modulus"))
    with pytest.raises(ValueError, match="only one parameter"):
        fit_restitution(V, e, SILICON, params="limiting_pressure,density")


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"params": ("youngs_modulus",)}, "params must be among"),
        ({"params": ()}, "at least one"),
        ({"loss": "l2"}, "loss must be one of"),
        ({"confidence": 1.5}, "confidence"),
        ({"f_scale": -1.0, "loss": "huber"}, "f_scale"),
        ({"params": ("k",)}, "yield_strength"),  # the paper case has no materials
        ({"params": ("k",), "yield_strength": -3.0}, "yield_strength"),
        ({"sigma": [0.01, 0.0, 0.01, 0.01, 0.01]}, r"sigma.*point 1"),
    ],
)
def test_bad_arguments_raise(kwargs, match):
    V = np.array([10.0, 20.0, 30.0, 40.0, 50.0])
    with pytest.raises(ValueError, match=match):
        fit_restitution(V, SILICON.restitution(V), SILICON, **kwargs)


def test_density_needs_a_sphere_on_flat():
    pair = mi.ContactPair.two_spheres("glass", "glass", 1e-6, 2e-6, limiting_pressure=3e9)
    V = pair.yield_velocity * np.geomspace(2, 10, 8)
    with pytest.raises(ValueError, match="density can be fitted only"):
        fit_restitution(V, pair.restitution(V), pair, params="density")
    # p_y of two spheres fits fine (R*, m* are effective values)
    fit = fit_restitution(V, pair.restitution(V), pair.replace(limiting_pressure=1e9))
    assert fit.params["limiting_pressure"] == pytest.approx(3e9, rel=1e-6)


def test_k_from_the_pair_materials():
    pair = mi.ContactPair.from_materials("nh4fl", "silicon", radius=2.45e-6, k=2.11)
    V = pair.yield_velocity * np.geomspace(2, 10, 8)
    fit = fit_restitution(
        V, pair.restitution(V), mi.ContactPair.from_materials("nh4fl", "silicon", radius=2.45e-6), params="k"
    )
    assert fit.params["k"] == pytest.approx(2.11, rel=1e-6)  # Y = 74 MPa from the nh4fl entry
    assert fit.pair.limiting_pressure == pytest.approx(2.11 * 74e6, rel=1e-6)


def test_api_bad_data_names_the_point():
    V = np.array([10.0, 20.0, -30.0])
    with pytest.raises(ValueError, match=r"velocity.*-30.*point 2"):
        fit_restitution(V, [0.9, 0.8, 0.7], SILICON)
    with pytest.raises(ValueError, match=r"restitution.*-0\.2.*line 9"):
        fit_restitution([10.0, 20.0, 30.0], [0.9, -0.2, 0.7], SILICON, line_numbers=[7, 9, 11])
    with pytest.raises(ValueError, match=r"restitution 0 \(stuck\) at line 11.*never sticks"):
        fit_restitution([10.0, 20.0, 30.0], [0.9, 0.8, 0.0], SILICON, line_numbers=[7, 9, 11])
    with pytest.raises(ValueError, match=r"restitution.*nan.*point 1"):
        fit_restitution([10.0, 20.0, 30.0], [0.9, np.nan, 0.7], SILICON)
    with pytest.raises(ValueError, match="complex"):
        fit_restitution([10.0, 20.0, 30.0], np.array([0.9, 0.8, 0.7]) + 0j, SILICON)
    with pytest.raises(ValueError, match="masked"):
        fit_restitution([10.0, 20.0, 30.0], np.ma.masked_array([0.9, 0.8, 0.7], [0, 1, 0]), SILICON)
    with pytest.raises(ValueError, match="same length"):
        fit_restitution([10.0, 20.0], [0.9], SILICON)


def test_too_few_points_above_yield():
    V = np.array([2.0, 3.0, 4.0, 5.0, 30.0])
    e = np.array([1.0, 1.0, 1.0, 1.0, 0.8])
    with pytest.raises(ValueError, match=r"too few points above the yield velocity.*line 15.*need at least 2"):
        fit_restitution(V, e, SILICON, line_numbers=[11, 12, 13, 14, 15])


# ----------------------------------------------------------------------------- robust loss
@pytest.mark.parametrize("loss", ["soft_l1", "huber", "cauchy"])
def test_robust_loss_limits_an_outlier(loss):
    V, e = synthetic(SILICON, 0.01, seed=42, n=25)
    e[12] = 0.25  # one grossly wrong point (a particle that hit a dust grain)
    plain = fit_restitution(V, e, SILICON)
    robust = fit_restitution(V, e, SILICON, loss=loss)
    err_plain = abs(plain.params["limiting_pressure"] / SILICON.limiting_pressure - 1)
    err_robust = abs(robust.params["limiting_pressure"] / SILICON.limiting_pressure - 1)
    assert err_robust < err_plain / 5
    lo, hi = robust.conf_int["limiting_pressure"]
    assert lo < SILICON.limiting_pressure < hi
    assert (
        not plain.conf_int["limiting_pressure"][0] < SILICON.limiting_pressure < plain.conf_int["limiting_pressure"][1]
        or err_plain > 0.02
    )
    # tuning constant x 1.4826 MAD, the MAD estimating the noise level 0.01
    assert robust.f_scale / TUNING[loss] == pytest.approx(0.01, rel=0.5)


def test_robust_loss_equals_least_squares_without_outliers_in_the_limit_of_large_f_scale():
    V, e = synthetic(SILICON, 0.02, seed=3)
    plain = fit_restitution(V, e, SILICON)
    robust = fit_restitution(V, e, SILICON, loss="huber", f_scale=10.0)  # every |r| < f_scale
    assert robust.params["limiting_pressure"] == pytest.approx(plain.params["limiting_pressure"], rel=1e-8)
    assert robust.stderr["limiting_pressure"] == pytest.approx(plain.stderr["limiting_pressure"], rel=1e-6)


# ----------------------------------------------------------------------------- result object
def test_fit_result_predict_band_and_summary():
    V, e = synthetic(SILICON, 0.02, seed=11)
    fit = fit_restitution(V, e, SILICON, sigma=0.02)
    assert isinstance(fit, FitResult)
    grid = np.linspace(1, 120, 50)
    # predict goes through the fitting's one model function; equal to the pair's own path to rounding
    np.testing.assert_allclose(fit.predict(grid), fit.pair.restitution(grid), rtol=1e-14, atol=0)
    lo, hi = fit.confidence_band(grid)
    mid = fit.predict(grid)
    assert np.all(lo <= mid) and np.all(mid <= hi)
    below = grid <= fit.yield_velocity
    np.testing.assert_array_equal(lo[below], 1.0)  # e = 1 exactly there
    # independent delta method: e at the interval ends of p_y brackets the band at high speed
    e_lo = fit.pair.replace(limiting_pressure=fit.conf_int["limiting_pressure"][0]).restitution(100.0)
    e_hi = fit.pair.replace(limiting_pressure=fit.conf_int["limiting_pressure"][1]).restitution(100.0)
    blo, bhi = fit.confidence_band(100.0)
    assert float(blo) == pytest.approx(e_lo, abs=2e-4) and float(bhi) == pytest.approx(e_hi, abs=2e-4)
    text = fit.summary()
    assert f"{fit.params['limiting_pressure'] / 1e6:.6g} MPa" in text
    assert "absolute sigma" in text and "normal quantile" in text
    assert fit.chi2 == pytest.approx(np.sum((fit.residuals / 0.02) ** 2))
    assert fit.rss == pytest.approx(np.sum(fit.residuals**2))
    doc = fit.to_dict()
    json.dumps(doc)
    assert doc["params"]["limiting_pressure"] == fit.params["limiting_pressure"]


def test_free_parameter_table_matches_eq_28_exponents():
    """V_y ~ p_y^(5/2) E*^(-2) rho^(-1/2) (seed eq. 28): the exponents the fit uses."""
    for name, attr, scale in [
        ("limiting_pressure", "limiting_pressure", 1.3),
        ("effective_modulus", "effective_modulus", 1.3),
    ]:
        other = SILICON.replace(**{attr: getattr(SILICON, attr) * scale})
        c = math.log(other.yield_velocity / SILICON.yield_velocity) / math.log(scale)
        assert c == pytest.approx(FREE_PARAMETERS[name]["exponent"], rel=1e-12)
    rho = SILICON.density * 1.3
    other = SILICON.replace(density=rho, effective_mass=SILICON.effective_mass * 1.3)
    c = math.log(other.yield_velocity / SILICON.yield_velocity) / math.log(1.3)
    assert c == pytest.approx(FREE_PARAMETERS["density"]["exponent"], rel=1e-12)


# ----------------------------------------------------------------------------- CSV loading
def write(tmp_path, text, name="data.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_load_csv_aliases_comments_units(tmp_path):
    path = write(
        tmp_path,
        "# Wall-like data\n\n# units m/s\nV [m/s]; e ; e_err;note\n"
        "10;0.95;0.02;a\n20 ; 0.85 ; 0.03;b # trailing comment\n",
    )
    data = load_restitution_csv(path)
    V, e, sigma = data
    np.testing.assert_array_equal(V, [10.0, 20.0])
    np.testing.assert_array_equal(e, [0.95, 0.85])
    np.testing.assert_array_equal(sigma, [0.02, 0.03])
    np.testing.assert_array_equal(data.lines, [5, 6])
    V, e, sigma = load_restitution_csv(write(tmp_path, "speed restitution\n5 1.0\n30 0.8\n", "ws.csv"))
    assert sigma is None and V.tolist() == [5.0, 30.0]


def test_load_csv_keeps_values_above_one_and_stuck_points(tmp_path):
    V, e, _ = load_restitution_csv(write(tmp_path, "velocity,e\n8,1.013\n12,0.99\n30,0\n"))
    np.testing.assert_array_equal(e, [1.013, 0.99, 0.0])


@pytest.mark.parametrize(
    "text, match",
    [
        ("velocity,sigma\n10,0.01\n", r"line 1: missing column restitution"),
        ("# c\nspeed_kmh,e\n10,0.9\n", r"line 2: missing column velocity"),
        ("velocity,e\n10,0.9\n20,abc\n", r"line 3: restitution 'abc' is not a number"),
        ("velocity,e\n10,0.9\n\n#x\nfast,0.8\n", r"line 5: velocity 'fast' is not a number"),
        ("velocity,e\n10,0.9\n-20,0.8\n", r"line 3: negative impact speed -20"),
        ("velocity,e\n0,0.9\n", r"line 2: impact speed must be positive"),
        ("velocity,e\n10,0.9\n20,-0.3\n", r"line 3: restitution must be >= 0, got -0.3"),
        ("velocity,e\n10,nan\n", r"line 2: restitution 'nan' is not a finite"),
        ("velocity,e\n10,0.9\n20\n", r"line 3: expected 2 cells"),
        ("velocity,e\n10,\n", r"line 2: empty restitution"),
        ("velocity,e,sigma\n10,0.9,0\n", r"line 2: sigma must be positive"),
        ("velocity [cm/s],e\n1000,0.9\n", r"line 1: velocity must be in m/s"),
        ("V,velocity,e\n1,1,0.9\n", r"line 1: more than one velocity column"),
        ("# only comments\n", r"no header"),
        ("velocity,e\n# nothing\n", r"no data rows after the header on line 1"),
    ],
)
def test_load_csv_bad_data_gives_the_line(tmp_path, text, match):
    with pytest.raises(ValueError, match=match):
        load_restitution_csv(write(tmp_path, text))


def test_example_file_recovers_the_silicon_case():
    data = load_restitution_csv("examples/synthetic_silicon.csv")
    V, e, sigma = data
    fit = fit_restitution(V, e, SILICON, sigma=sigma, line_numbers=data.lines)
    lo, hi = fit.conf_int["limiting_pressure"]
    assert lo < 156e6 < hi  # the file was drawn from p_y = 156 MPa (see its header)
    assert fit.n_elastic >= 4


# ----------------------------------------------------------------------------- plot
def test_plot_fit_draws_the_fit(tmp_path):
    plt = pytest.importorskip("matplotlib.pyplot")
    V, e = synthetic(SILICON, 0.02, seed=5)
    fit = fit_restitution(V, e, SILICON, sigma=0.02)
    ax, rax = plot_fit(fit, V, e)
    assert ax.get_ylim() == (0.0, 1.05)
    assert "[m/s]" in rax.get_xlabel() and "restitution" in ax.get_ylabel()
    line = [ln for ln in ax.get_lines() if ln.get_label().startswith("model fit")][0]
    x, y = line.get_data()
    np.testing.assert_allclose(y, fit.predict(x))
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("confidence band" in t for t in labels) and "measured" in labels
    ax2 = plot_residuals(fit, V, e)
    pts = [c for c in ax2.containers][0].lines[0].get_data()[1]
    np.testing.assert_allclose(pts, fit.residuals)
    plt.close("all")


def test_the_plots_moved_to_figures_and_warn_from_fitting():
    """Plots live in figures: the fit plots' old home still gives them for one release, warning
    with the new path; they are not in fitting's ``__all__`` (a star import does not warn)."""
    import microimpact.fitting as fitting
    from microimpact.figures import fit as fig_fit

    for name in ("plot_fit", "plot_residuals", "plot_models"):
        with pytest.warns(
            DeprecationWarning, match=rf"fitting\.{name} is deprecated; use microimpact\.figures\.fit\.{name}"
        ):
            assert getattr(fitting, name) is getattr(fig_fit, name)
        assert name not in fitting.__all__ and name in fig_fit.__all__
    with pytest.raises(AttributeError):
        fitting.plot_nothing  # noqa: B018


# ----------------------------------------------------------------------------- CLI
def test_cli_fit_end_to_end(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    rng = np.random.default_rng(2024)
    V = np.concatenate([[3.0, 5.0], np.geomspace(12, 90, 15)])
    e = SILICON.restitution(V) + np.concatenate([[0, 0], rng.normal(0, 0.02, 15)])
    csv = write(tmp_path, "velocity,restitution\n" + "".join(f"{float(v)!r},{float(x)!r}\n" for v, x in zip(V, e)))
    png = tmp_path / "fit.png"
    rc = main(["fit", str(csv), "--case", "silicon", "--plot", str(png)])
    out = capsys.readouterr().out
    assert rc == 0
    api = fit_restitution(*load_restitution_csv(csv)[:2], SILICON)
    m = re.search(r"^limiting_pressure\s+(\S+) MPa\s+(\S+) MPa\s+\[(\S+), (\S+)\] MPa", out, re.M)
    assert m, out
    assert m.group(1) == f"{api.params['limiting_pressure'] * 1e-6:.6g}"
    assert float(m.group(3)) * 1e6 == pytest.approx(api.conf_int["limiting_pressure"][0], rel=1e-5)
    assert abs(float(m.group(1)) - 156.0) < 3 * float(m.group(2))
    img = __import__("matplotlib.image", fromlist=["imread"]).imread(png)
    assert img.shape[0] > 800 and img.shape[1] > 800  # a real figure at 200 dpi

    rc = main(
        [
            "fit",
            str(csv),
            "--particle",
            "nh4fl",
            "--surface",
            "silicon",
            "--diameter",
            "4.9e-6",
            "--loss",
            "soft_l1",
            "--json",
        ]
    )
    doc = json.loads(capsys.readouterr().out)
    pair = mi.ContactPair.from_materials("nh4fl", "silicon", radius=2.45e-6)
    api = fit_restitution(*load_restitution_csv(csv)[:2], pair, loss="soft_l1")
    assert rc == 0
    assert doc["params"]["limiting_pressure"] == api.params["limiting_pressure"]
    assert doc["conf_int"]["limiting_pressure"] == list(api.conf_int["limiting_pressure"])


def test_cli_fit_fig2_layout_draws_the_fitted_curve(tmp_path, capsys, monkeypatch):
    pytest.importorskip("matplotlib")
    paper = pytest.importorskip("microimpact.figures.paper")
    V = SILICON.yield_velocity * np.geomspace(0.5, 12, 12)
    csv = write(tmp_path, "V,e\n" + "".join(f"{float(v)!r},{float(x)!r}\n" for v, x in zip(V, SILICON.restitution(V))))
    seen = {}
    original = paper.plot_restitution

    def spy(pairs, data, *a, **k):
        seen.update(pairs=pairs, data=data)
        return original(pairs, data, *a, **k)

    monkeypatch.setattr(paper, "plot_restitution", spy)
    png = tmp_path / "fig2.png"
    assert main(["fit", str(csv), "--case", "mica", "--fig2", str(png)]) == 0
    assert "Fig. 2 layout written" in capsys.readouterr().out
    (fitted,) = seen["pairs"].values()
    # data are the silicon case's; mica's E* = 1.30 GPa (not 1.31) needs p_y scaled by (1.30/1.31)^(4/5)
    assert fitted.yield_velocity == pytest.approx(SILICON.yield_velocity, rel=1e-6)
    assert fitted.limiting_pressure == pytest.approx(156e6 * (1.30 / 1.31) ** 0.8, rel=1e-6)
    np.testing.assert_array_equal(seen["data"]["data.csv"][0], V)
    assert png.stat().st_size > 10_000


def test_cli_fit_k_and_modulus(tmp_path, capsys):
    V = SILICON.yield_velocity * np.geomspace(2, 12, 10)
    csv = write(tmp_path, "V,e\n" + "".join(f"{float(v)!r},{float(x)!r}\n" for v, x in zip(V, SILICON.restitution(V))))
    assert main(["fit", str(csv), "--free", "k", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["params"]["k"] == pytest.approx(156 / 74, rel=1e-6)  # Y = 74 MPa of the silicon case
    assert main(["fit", str(csv), "--free", "effective_modulus", "--limiting-pressure", "156e6"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"^effective_modulus\s+1\.31 GPa", out, re.M), out


def test_cli_fit_errors_exit_2_with_the_line(tmp_path, capsys):
    csv = write(tmp_path, "velocity,e\n10,0.9\n20,x\n")
    assert main(["fit", str(csv)]) == 2
    err = capsys.readouterr().err
    assert "line 3" in err and len(err.strip().splitlines()) == 1
    csv = write(tmp_path, "velocity,e\n10,0.9\n20,0.8\n30,0.7\n", "ok.csv")
    assert main(["fit", str(csv), "--free", "limiting_pressure,effective_modulus"]) == 2
    assert "not separately identifiable" in capsys.readouterr().err


def test_cli_fit_models_ranks_prints_the_caveat_and_draws(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    rng = np.random.default_rng(3)
    V = np.geomspace(4, 110, 22)
    e = SILICON.restitution(V) + rng.normal(0, 0.02, V.size)
    assert np.any(e > 1)
    csv = write(tmp_path, "V,e\n" + "".join(f"{float(v)!r},{float(x)!r}\n" for v, x in zip(V, e)))
    png = tmp_path / "models.png"
    models = "thornton_ning_2016,thornton_ning_2016:effective_modulus,thornton_ning_2016:none"
    args = ["fit", str(csv), "--case", "silicon", "--limiting-pressure", "80e6", "--models", models]
    assert main([*args, "--plot", str(png)]) == 0
    out = capsys.readouterr().out
    table = out.split("\n\n")[0]
    lines = table.splitlines()
    assert lines[3].split()[:2] == ["1", "thornton_ning_2016"]  # a tie keeps the order given
    assert lines[5].split()[1] == "thornton_ning_2016:none"
    assert "caveat: the data cannot tell thornton_ning_2016 from thornton_ning_2016:effective_modulus" in out
    assert png.stat().st_size > 20_000 and not list(tmp_path.glob(".tmp-*"))
    assert main([*args, "--json"]) == 0
    captured = capsys.readouterr()
    doc = json.loads(captured.out)
    assert [r["label"] for r in doc["ranking"]][2] == "thornton_ning_2016:none"
    assert doc["ranking"][0]["weight"] == pytest.approx(0.5, abs=1e-6)
    assert "caveat" in captured.err
    with pytest.warns(FitWarning, match="above e = 1"):  # e = 1.041 at 4 m/s: 3.1 x the MAD scatter
        api = fit_restitution(V, e, SILICON)
    assert doc["fits"]["thornton_ning_2016"]["params"]["limiting_pressure"] == pytest.approx(
        api.params["limiting_pressure"], rel=1e-9
    )


@pytest.mark.parametrize(
    "extra, match",
    [
        (["--models", "thornton_ning_2016", "--free", "k"], "--free and --models conflict"),
        (["--models", "thornton_ning_2016", "--f-scale", "0.1"], "--f-scale and --models conflict"),
        (["--models", "nonesuch"], "model must be one of"),
        (["--models", "thornton_ning_2016", "--folds", "1"], "--folds must be >= 2"),
        (["--plot", "/nonexistent-folder/x.png"], "/nonexistent-folder: directory does not exist"),
    ],
)
def test_cli_fit_conflicts_exit_2(tmp_path, capsys, extra, match):
    V = np.geomspace(4, 110, 12)
    csv = write(tmp_path, "V,e\n" + "".join(f"{float(v)!r},{float(x)!r}\n" for v, x in zip(V, SILICON.restitution(V))))
    assert main(["fit", str(csv), *extra]) == 2
    err = capsys.readouterr().err
    assert match in err and len(err.strip().splitlines()) == 1


def test_cli_fit_warns_in_one_line_about_points_far_above_one(tmp_path, capsys):
    V = np.geomspace(4, 110, 14)
    e = SILICON.restitution(V)
    text = "V,e,sigma\n" + "".join(f"{float(v)!r},{float(x)!r},0.01\n" for v, x in zip(V, e))
    text = text.replace(f"{float(e[0])!r},0.01", "1.25,0.01", 1)
    csv = write(tmp_path, text)
    assert main(["fit", str(csv), "--case", "silicon", "--interval", "profile"]) == 0
    captured = capsys.readouterr()
    assert "(profile)" in captured.out
    (warning,) = captured.err.strip().splitlines()
    assert warning.startswith("warning: 1 point(s) lie more than 3 x sigma above e = 1: line 2 (e = 1.25)")


def test_example_with_values_above_one_writes_only_to_its_folder(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    import importlib.util
    import pathlib

    path = pathlib.Path(__file__).resolve().parents[1] / "examples" / "fit_values_above_one.py"
    spec = importlib.util.spec_from_file_location("fit_values_above_one", path)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    assert example.main(str(tmp_path / "out")) == 0
    out = capsys.readouterr().out
    assert "3 of 24 measured values lie above 1" in out and "caveat" in out
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["fit.png", "ranking.png", "synthetic_rebounds.csv"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
    # the robust fit finds p_y = 156 MPa within its interval despite the outlier
    m = re.search(r"soft_l1: +FitResult\(.*limiting_pressure=\S+ MPa \[95%: (\S+), (\S+)\]", out)
    assert float(m.group(1)) < 156 < float(m.group(2).rstrip("]"))


def test_the_reader_lives_in_io_and_its_old_names_warn(tmp_path):
    """Reading lives in :mod:`microimpact.io` (issue 20); ``fitting``'s names keep working one release."""
    import warnings

    import microimpact as mi
    import microimpact.fitting as fitting
    import microimpact.io as mio

    path = write(tmp_path, "velocity,e\n8,1.013\n12,0.99\n30,0\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the new homes give no warning
        new = mio.load_restitution_csv(path)
        assert mi.load_restitution_csv is mio.load_restitution_csv
    for name in ("load_restitution_csv", "RestitutionData"):
        with pytest.warns(DeprecationWarning, match=rf"use microimpact\.io\.{name}\b"):
            assert getattr(fitting, name) is getattr(mio, name)
    with pytest.warns(DeprecationWarning):
        old = fitting.load_restitution_csv(path)
    assert isinstance(old, mio.RestitutionData) and old.lines.tolist() == new.lines.tolist() == [2, 3, 4]
    for a, b in zip(old[:2], new[:2]):
        np.testing.assert_array_equal(a, b)
