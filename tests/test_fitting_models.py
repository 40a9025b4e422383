"""Fitting through the model hook, ranking of models, the confidence band over all parameters,
uncertainty carried forward (Prediction, band_ends) and the result's reprs.

Until the model zoo lands on main, two stand-in zoo models are registered here by monkeypatching
``microimpact.core.models``: a power law ``e = (V/V_y)^-a`` above ``V_y`` (a second, *different* law
with its own parameter) and a constant ``e = e0`` (a deliberately wrong model). They follow the zoo's
contract (NAME, PARAMETERS, DEFAULTS, scalar ``outcome`` in OUTCOME_FIELDS order), so the fitting
code under test is the same that will evaluate the real zoo.
"""

import math
import types
import warnings

import numpy as np
import pytest

import microimpact as mi
from microimpact.core import models as zoo
from microimpact.core.quantities import OUTCOME_FIELDS
from microimpact.figures.fit import plot_models
from microimpact.fitting import (
    SEED_MODEL,
    FitWarning,
    Prediction,
    available_models,
    fit_restitution,
    rank_models,
)
from microimpact.impact import yield_velocity

SILICON = mi.ContactPair.paper_case("silicon")
I_E, I_VR = OUTCOME_FIELDS.index("restitution"), OUTCOME_FIELDS.index("rebound_velocity")


def _row(V, e):
    row = [math.nan] * len(OUTCOME_FIELDS)
    row[OUTCOME_FIELDS.index("velocity")] = V
    row[I_E], row[I_VR] = e, e * V
    return tuple(row)


# V_y ~ p_y^(5/2) E*^(-2) m*^(-1/2) (seed eq. 28), scaled from the silicon case: fast in plain floats
VY_REF = SILICON.yield_velocity
REF = (SILICON.limiting_pressure, SILICON.effective_modulus, SILICON.effective_mass)


def _power_law_outcome(V, E, R, m, p_y, params):
    (a,) = params
    vy = VY_REF * (p_y / REF[0]) ** 2.5 * (E / REF[1]) ** -2 * (m / REF[2]) ** -0.5
    return _row(V, 1.0 if V <= vy else (V / vy) ** (-a))


def _constant_outcome(V, E, R, m, p_y, params):
    return _row(V, params[0])


FAKE = {
    "power_law": types.SimpleNamespace(
        NAME="power_law",
        TITLE="e = (V/V_y)^-a above V_y (test stand-in)",
        PARAMETERS=(("a", "", "exponent of the power law"),),
        DEFAULTS=(0.3,),
        outcome=_power_law_outcome,
        force=None,
    ),
    "constant": types.SimpleNamespace(
        NAME="constant",
        TITLE="e = e0 at every speed (deliberately wrong)",
        PARAMETERS=(("e0", "", "the constant restitution"),),
        DEFAULTS=(0.8,),
        outcome=_constant_outcome,
        force=None,
    ),
}


@pytest.fixture
def fake_zoo(monkeypatch):
    real_available, real_get = zoo.available, zoo.get

    def available():
        return [*real_available(), *FAKE]

    def get(name=zoo.DEFAULT):
        if name not in FAKE:
            return real_get(name)
        fake = FAKE[name]
        return fake if isinstance(fake, zoo.Model) else zoo.declare(fake)

    monkeypatch.setattr(zoo, "available", available)
    monkeypatch.setattr(zoo, "get", get)
    return FAKE


def power_law_data(pair, a, noise, seed, V):
    vy = pair.yield_velocity
    e = np.where(V <= vy, 1.0, (V / vy) ** (-a))
    return e + np.random.default_rng(seed).normal(0.0, noise, V.size)


# ----------------------------------------------------------------------------- the hook
#: Every model that can stick (``STICKS``), with the parameter to recover, two true values and the
#: other parameters held fixed: chosen so that 0.05-5 m/s includes stuck points for the silicon pair.
STICKING = {
    "jkr_elastic_adhesive": ("surface_energy", (0.05, 0.2), {}),
    "thornton_ning_1998_elastic_adhesive": ("work_of_adhesion", (0.05, 0.2), {}),
    "thornton_ning_1998_adhesive_plastic": ("work_of_adhesion", (0.05, 0.2), {}),
    "luding_adhesive": (
        "adhesion_stiffness",
        (200.0, 1000.0),
        {"loading_stiffness": 50.0, "unloading_stiffness": 200.0, "plasticity_depth": 0.01},
    ),
    "lammps_jkr": ("surface_energy", (0.05, 0.2), {"viscoelastic_damping": 2e13}),
    "lammps_dmt": ("surface_energy", (0.05, 0.2), {"viscoelastic_damping": 2e13}),
    "lethe_dmt_vdw": ("effective_surface_energy", (0.05, 0.2), {"restitution": 0.6}),
    # the liquid bridges: the liquid sets the adhesion (capture at 0.7-2.4 m/s for these amounts)
    "willett_capillary": ("liquid_volume", (2e-21, 2e-20), {}),
    "rabinovich_capillary": ("liquid_volume", (2e-21, 2e-20), {}),
}
#: Sticking models whose adhesion input a fit of positive parameters cannot recover here, and why.
NOT_FITTED = {
    "liggghts_edinburgh": "its pull-off force f0 is negative (fits search positive parameters in log scale), and "
    "its kn2kc adhesion captures nothing at 0.05-5 m/s for this pair",
    "liggghts_hertz_sjkr": "from the test's start, three times the true cohesion energy density, every point of "
    "0.05-5 m/s is stuck: e(V) is flat there and the fit has no gradient to follow",
    "liggghts_easo_capillary": "LIGGGHTS gives a bridge below 1e-17 m^3 no force, and above it (a liquid content "
    "of 0.32 here) the bridge captures up to 3-4 m/s: e(V) bounces at the top three speeds of 0.05-5 m/s only, and "
    "the fit's start, three times the content, lies beyond the 0.5 the law takes",
    "liggghts_washino_capillary": "its bridge, 5 % of the particle's liquid, stays below LIGGGHTS' 1e-17 m^3 floor at "
    "a wall for any liquid content up to the 0.5 it takes (no force: nothing is captured), and between two spheres "
    "the smallest bridge above it captures every point of 0.05-5 m/s",
}


def test_every_sticking_model_is_fitted_here():
    assert sorted([*STICKING, *NOT_FITTED]) == sorted(n for n in zoo.available() if zoo.get(n).STICKS)


@pytest.mark.parametrize("name", sorted(STICKING))
def test_an_adhesive_model_fits_its_own_data_with_stuck_points(name):
    """Data made by the model itself at 0.05-5 m/s, stuck points (e = 0) included, give back its
    parameter from a start three times too large. (Fitting refused such data before: it asked the
    model for a STICKS flag that no model file set.)"""
    param, values, fixed = STICKING[name]
    V = np.geomspace(0.05, 5.0, 25)
    for true in values:
        e = np.asarray(SILICON.impact(V, model=name, warn=False, **fixed, **{param: true}).restitution)
        assert (e == 0.0).sum() >= 3 and (e > 0.0).sum() >= 3
        fit = fit_restitution(V, e, SILICON, model=name, params=(param,), model_params={**fixed, param: 3.0 * true})
        assert fit.params[param] == pytest.approx(true, rel=1e-8)


def test_the_fit_compiles_by_the_declared_cost_class_not_by_a_clock():
    """Whether a fit imports numba (its loops then run compiled, the same numbers bit for bit) follows
    the model's declared cost class and the number of points, never a timing: a cheap law's e on 500
    points stays in Python, one point more compiles; the LIGGGHTS law's e (cheap, its hook) on 31
    points stays in Python, its outcome (OUTCOME_COST slow: the contact times' quadrature) compiles."""
    import os
    import subprocess
    import sys

    code = """
import sys
from microimpact import engine
from microimpact.core import models
from microimpact.fitting import _models as fitting
limit = engine.PYTHON_BUDGET / (models.COST_CLASSES["cheap"] * fitting._FIT_CALLS)
seed, liggghts = models.get(models.DEFAULT), models.get("liggghts_thornton_ning")
fitting._compile_if_costly(seed, int(limit), outcome=False)
fitting._compile_if_costly(liggghts, 31, outcome=False)
print(int(limit), "numba" in sys.modules)
fitting._compile_if_costly(liggghts, 31, outcome=True)
print("numba" in sys.modules)
"""
    env = {k: v for k, v in os.environ.items() if k != "MICROIMPACT_BACKEND"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env).stdout
    assert out.split() == ["500", "False", "True"]
    code2 = code.replace("int(limit)", "int(limit) + 1").split("fitting._compile_if_costly(liggghts")[0]
    out = subprocess.run(
        [sys.executable, "-c", code2 + "print('numba' in sys.modules)"],
        capture_output=True,
        text=True,
        check=True,
        env=env,
    )
    assert out.stdout.split() == ["True"]


def test_a_model_that_never_sticks_refuses_stuck_points():
    with pytest.raises(ValueError, match="never sticks"):
        fit_restitution([10.0, 20.0, 30.0, 40.0], [0.9, 0.0, 0.7, 0.6], SILICON)


def test_models_are_found_through_the_zoo_registry(fake_zoo):
    names = available_models()
    assert names[0] == SEED_MODEL and "power_law" in names and "constant" in names
    with pytest.raises(ValueError, match="model must be one of"):
        fit_restitution([10.0, 20.0, 30.0], [0.9, 0.8, 0.7], SILICON, model="nonesuch")
    with pytest.raises(ValueError, match="has no parameter 'b'"):
        fit_restitution([10.0, 20.0, 30.0], [0.9, 0.8, 0.7], SILICON, model="power_law", model_params={"b": 1.0})
    with pytest.raises(ValueError, match="params must be among"):
        fit_restitution([10.0, 20.0, 30.0], [0.9, 0.8, 0.7], SILICON, params="a")  # the seed has no 'a'


def test_zoo_model_with_two_free_parameters_recovers_both(fake_zoo):
    V = SILICON.yield_velocity * np.geomspace(1.5, 15.0, 14)
    e = power_law_data(SILICON, 0.4, 0.0, 0, V)
    fit = fit_restitution(
        V, e, SILICON.replace(limiting_pressure=90e6), model="power_law", params=("limiting_pressure", "a")
    )
    assert fit.params["limiting_pressure"] == pytest.approx(156e6, rel=1e-6)
    assert fit.params["a"] == pytest.approx(0.4, rel=1e-6)
    assert fit.model == "power_law" and fit.model_params["a"] == pytest.approx(fit.params["a"], rel=1e-12)
    assert fit.units == {"limiting_pressure": "Pa", "a": ""}
    assert "a=0.4" in repr(fit) and "power_law" in fit._repr_html_()


def test_confidence_band_differentiates_with_respect_to_every_parameter(fake_zoo):
    """Independent delta method over both parameters. The old band took the first parameter's
    derivative for every column (the second column was zero), so it came out too narrow."""
    V = SILICON.yield_velocity * np.geomspace(1.5, 15.0, 14)
    e = power_law_data(SILICON, 0.4, 0.01, 3, V)
    fit = fit_restitution(V, e, SILICON, model="power_law", params=("limiting_pressure", "a"))
    grid = SILICON.yield_velocity * np.array([2.0, 5.0, 12.0, 20.0])
    C = fit.log_covariance
    p_y, a = fit.params["limiting_pressure"], fit.params["a"]
    vy = float(yield_velocity(p_y, SILICON.effective_modulus, SILICON.effective_radius, SILICON.effective_mass))
    # analytic gradient of e = (V/V_y)^-a in (ln p_y, ln a): V_y ~ p_y^(5/2)
    e0 = (grid / vy) ** (-a)
    g = np.stack([e0 * a * 2.5, -e0 * a * np.log(grid / vy)], axis=-1)
    half = fit.quantile * np.sqrt(np.einsum("ni,ij,nj->n", g, C, g))
    lo, hi = fit.confidence_band(grid)
    np.testing.assert_allclose(hi - e0, half, rtol=1e-4)
    np.testing.assert_allclose(e0 - lo, half, rtol=1e-4)
    first_only = fit.quantile * np.abs(g[:, 0]) * math.sqrt(C[0, 0])
    assert np.max(np.abs(first_only / half - 1)) > 0.3  # what the old code gave is far off


def test_predict_band_with_two_parameters_uses_the_delta_method(fake_zoo):
    V = SILICON.yield_velocity * np.geomspace(1.5, 15.0, 14)
    e = power_law_data(SILICON, 0.4, 0.01, 4, V)
    fit = fit_restitution(V, e, SILICON, model="power_law", params=("limiting_pressure", "a"))
    pred = fit.predict(V, band=True)
    lo, hi = fit.confidence_band(V)
    assert pred.method == "delta method"
    np.testing.assert_allclose(pred.restitution_lo, lo, rtol=1e-9)
    np.testing.assert_allclose(pred.rebound_velocity_hi - pred.rebound_velocity, V * (hi - pred.restitution), rtol=1e-6)
    with pytest.raises(ValueError, match="exactly one free parameter"):
        fit.band_ends()


# ----------------------------------------------------------------------------- uncertainty forward (seed)
def test_predict_band_is_the_model_at_the_interval_ends():
    rng = np.random.default_rng(12)
    V = np.geomspace(5.0, 120.0, 18)
    e = SILICON.restitution(V) + rng.normal(0, 0.02, V.size)
    fit = fit_restitution(V, e, SILICON)
    grid = np.array([3.0, 10.0, 40.0, 100.0])
    pred = fit.predict(grid, band=True)
    assert isinstance(pred, Prediction) and pred.method == "interval ends"
    lo_py, hi_py = fit.conf_int["limiting_pressure"]
    at_lo = SILICON.replace(limiting_pressure=lo_py).impact(grid, warn=False)
    at_hi = SILICON.replace(limiting_pressure=hi_py).impact(grid, warn=False)
    # larger p_y -> larger V_y -> larger e and rebound speed (eq. 27)
    np.testing.assert_allclose(pred.restitution_lo, at_lo.restitution, rtol=1e-12)
    np.testing.assert_allclose(pred.restitution_hi, at_hi.restitution, rtol=1e-12)
    np.testing.assert_allclose(pred.rebound_velocity_hi, grid * at_hi.restitution, rtol=1e-12)
    ct = np.stack([at_lo.contact_time, at_hi.contact_time])
    np.testing.assert_allclose(pred.contact_time_lo, ct.min(axis=0), rtol=1e-12)
    np.testing.assert_allclose(pred.contact_time_hi, ct.max(axis=0), rtol=1e-12)
    assert np.all(pred.contact_time_lo[1:] < pred.contact_time_hi[1:])  # 3 m/s < V_y: Hertz, no p_y
    np.testing.assert_allclose(pred.restitution, fit.predict(grid), rtol=1e-14)
    ends = fit.band_ends()
    assert [d["end"] for d in ends] == ["lower", "upper"]
    assert ends[0]["pair"].limiting_pressure == pytest.approx(lo_py, rel=1e-12)
    assert ends[1]["pair"].limiting_pressure == pytest.approx(hi_py, rel=1e-12)
    assert ends[0]["model"] == SEED_MODEL and ends[0]["model_params"] == {}


def test_repr_and_html_are_readable():
    V = np.geomspace(5.0, 120.0, 12)
    fit = fit_restitution(V, SILICON.restitution(V), SILICON.replace(limiting_pressure=80e6))
    text = repr(fit)
    assert text.startswith("FitResult(model='thornton_ning_2016', limiting_pressure=156 MPa [95%: 156, 156]")
    assert "yield_velocity=7.523 m/s" in text and len(text) < 300
    html = fit._repr_html_()
    assert html.startswith("<table>") and "limiting_pressure" in html and "MPa" in html


# ----------------------------------------------------------------------------- values above 1
def test_far_above_one_warns_and_names_the_line():
    V = np.geomspace(5.0, 120.0, 16)
    e = SILICON.restitution(V) + np.random.default_rng(1).normal(0, 0.01, V.size)
    e[1] = 1.2  # 20 sigma above 1
    with pytest.warns(FitWarning, match=r"1 point\(s\) lie more than 3 x sigma above e = 1: line 12 \(e = 1\.2\)"):
        fit = fit_restitution(V, e, SILICON, sigma=0.01, line_numbers=np.arange(11, 27))
    assert fit.n_far_above_one == 1
    e[1] = 1.015  # 1.5 sigma: ordinary scatter, no warning
    with warnings.catch_warnings():
        warnings.simplefilter("error", FitWarning)
        fit = fit_restitution(V, e, SILICON, sigma=0.01)
    assert fit.n_far_above_one == 0


# ----------------------------------------------------------------------------- ranking
def test_two_parametrisations_of_the_seed_cannot_be_told_apart_and_a_wrong_fixed_model_ranks_last():
    rng = np.random.default_rng(8)
    V = np.geomspace(5.0, 120.0, 20)
    e = SILICON.restitution(V) + rng.normal(0, 0.02, V.size)
    wrong = SILICON.replace(limiting_pressure=60e6)
    ranking = rank_models(
        V,
        e,
        wrong,
        [f"{SEED_MODEL}:limiting_pressure", f"{SEED_MODEL}:effective_modulus", f"{SEED_MODEL}:none"],
    )
    labels = [r["label"] for r in ranking.rows]
    assert labels[2] == f"{SEED_MODEL}:none"
    a, b, c = ranking.rows
    assert a["aicc"] == pytest.approx(b["aicc"], abs=1e-6)  # the same V_y: the same fit
    assert a["weight"] == pytest.approx(0.5, abs=1e-6) and c["weight"] < 1e-6
    assert "cannot tell" in ranking.caveat and "cannot tell" in ranking.table()
    assert sum(r["weight"] for r in ranking.rows) == pytest.approx(1.0)
    # AIC with estimated scale: n ln(RSS/n) + 2(p + 1); AICc adds 2K(K+1)/(n-K-1); BIC K ln n
    n, k = V.size, 2
    aic = n * math.log(a["rss"] / n) + 2 * k
    assert a["aic"] == pytest.approx(aic, rel=1e-12)
    assert a["aicc"] == pytest.approx(aic + 2 * k * (k + 1) / (n - k - 1), rel=1e-12)
    assert a["bic"] == pytest.approx(n * math.log(a["rss"] / n) + k * math.log(n), rel=1e-12)
    assert a["k"] == 2 and c["k"] == 1
    assert ranking.to_dict()["ranking"][0]["label"] == labels[0]


def test_cross_validated_error_by_hand():
    rng = np.random.default_rng(21)
    V = np.geomspace(5.0, 120.0, 12)
    e = SILICON.restitution(V) + rng.normal(0, 0.02, V.size)
    ranking = rank_models(V, e, SILICON, [SEED_MODEL], k_folds=3, seed=5)
    folds = np.array_split(np.random.default_rng(5).permutation(V.size), 3)
    sq = []
    for idx in folds:
        keep = np.setdiff1d(np.arange(V.size), idx)
        f = fit_restitution(V[keep], e[keep], SILICON)
        sq.extend((e[idx] - f.predict(V[idx])) ** 2)
    assert ranking.rows[0]["cv_error"] == pytest.approx(math.sqrt(np.mean(sq)), rel=1e-6)


RANK_DRAWS = 20
SPEC = [SEED_MODEL, "power_law:limiting_pressure+a", "constant:e0"]


def rank_first_counts(truth, noise, seed0, draws=RANK_DRAWS):
    V = SILICON.yield_velocity * np.geomspace(0.8, 14.0, 18)
    counts = dict.fromkeys(SPEC, 0)
    for s in range(draws):
        if truth == SEED_MODEL:
            e = SILICON.restitution(V) + np.random.default_rng(seed0 + s).normal(0, noise, V.size)
        else:
            e = power_law_data(SILICON, 0.5, noise, seed0 + s, V)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", FitWarning)
            ranking = rank_models(V, e, SILICON, SPEC, k_folds=3)
        counts[ranking.best] += 1
    return counts


@pytest.mark.parametrize("truth, noise", [(SEED_MODEL, 0.01), (SEED_MODEL, 0.03), ("power_law", 0.01)])
def test_the_model_that_made_the_data_ranks_first_in_most_draws(fake_zoo, truth, noise):
    counts = rank_first_counts(truth, noise, seed0=int(noise * 1e4) + 100 * len(truth))
    label = SEED_MODEL if truth == SEED_MODEL else SPEC[1]
    # "most draws": more than half with a margin (a coin gives 10 of 20; 15 or more has p = 0.02)
    assert counts[label] >= 15, counts
    assert counts["constant:e0"] == 0, counts


def test_plot_models_draws_each_model_and_residuals(fake_zoo, tmp_path):
    plt = pytest.importorskip("matplotlib.pyplot")
    V = SILICON.yield_velocity * np.geomspace(0.8, 14.0, 18)
    e = SILICON.restitution(V) + np.random.default_rng(2).normal(0, 0.02, V.size)
    ranking = rank_models(V, e, SILICON, SPEC)
    ax, rax = plot_models(ranking)
    for row in ranking.rows:
        (line,) = [ln for ln in ax.get_lines() if ln.get_label().startswith(row["label"] + ": ")]
        x, y = line.get_data()
        np.testing.assert_allclose(y, ranking.fits[row["label"]].predict(x))
        assert f"w = {row['weight']:.2f}" in line.get_label()
    assert len(rax.get_lines()) == 3 + 1  # one residual series per model and the zero line
    assert "[m/s]" in rax.get_xlabel()
    ax.figure.savefig(tmp_path / "models.png", dpi=100)
    plt.close("all")


def test_the_seed_through_the_zoo_path_fits_like_the_seed_array_path(fake_zoo, monkeypatch):
    """The real seed module under another name goes through the zoo's outcome loop: same fit."""
    monkeypatch.setitem(FAKE, "seed_via_zoo", zoo.get(SEED_MODEL))
    rng = np.random.default_rng(31)
    V = np.geomspace(5.0, 120.0, 14)
    e = SILICON.restitution(V) + rng.normal(0, 0.02, V.size)
    direct = fit_restitution(V, e, SILICON)
    via_zoo = fit_restitution(V, e, SILICON, model="seed_via_zoo")
    assert via_zoo.params["limiting_pressure"] == pytest.approx(direct.params["limiting_pressure"], rel=1e-9)
    assert via_zoo.conf_int["limiting_pressure"] == pytest.approx(direct.conf_int["limiting_pressure"], rel=1e-7)
    pred, ref = via_zoo.predict(V, band=True), direct.predict(V, band=True)
    np.testing.assert_allclose(pred.contact_time_hi, ref.contact_time_hi, rtol=1e-9)
