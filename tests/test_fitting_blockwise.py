"""The fit's own minimiser (Levenberg-Marquardt on normal equations accumulated block by block).

``fit_restitution`` no longer holds an n x p Jacobian (scipy's least_squares did, with several
other n-sized arrays: a 10^7-point fit peaked at 1.7 GB). These tests hold it to what it replaced:
the same minimum as :func:`scipy.optimize.least_squares` run here on the same objective (its own
losses), the textbook covariance at that minimum, and the same result whatever the block size.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy import optimize

import microimpact as mi
from microimpact import fitting
from microimpact.adhesion import adhesive_restitution, sticking_velocity
from microimpact.engine import evaluate
from microimpact.fitting import LOSSES, FitWarning, _models, _solver, fit_restitution

SILICON = mi.ContactPair.paper_case("silicon")


def seed_data(n=40, noise=0.02, seed=5, outliers=True):
    rng = np.random.default_rng(seed)
    V = np.geomspace(2.0, 120.0, n)
    e = SILICON.restitution(V) + rng.normal(0.0, noise, n)
    if outliers:
        e[[7, 23]] -= 0.2  # two gross errors: where the robust losses differ from least squares
    return V, np.abs(e)


def model_seed(theta, V):
    """e(V) of the seed with p_y = theta[0] (the public pair, not fitting's internals)."""
    return SILICON.replace(limiting_pressure=float(theta[0])).restitution(V)


def model_additive(theta, V):
    """Thornton & Ning's additive rule with p_y = theta[0], G = theta[1] (public functions)."""
    pair = SILICON.replace(limiting_pressure=float(theta[0]))
    Vs = sticking_velocity(float(theta[1]), pair.effective_modulus, pair.effective_radius, pair.effective_mass)
    return adhesive_restitution(V, pair.yield_velocity, Vs)


def additive_data(n=36, noise=0.01, seed=2):
    rng = np.random.default_rng(seed)
    V = np.geomspace(0.05, 60.0, n)
    e = model_additive((156e6, 0.05), V)
    plastic = e > 0
    e[plastic] = np.abs(e[plastic] + rng.normal(0.0, noise, plastic.sum()))
    return V, e


def scipy_fit(model, refs, V, e, loss, f_scale, u0):
    """scipy's least_squares on the objective fit_restitution documents (ln parameters, its losses)."""

    def resid(u):
        return model(refs * np.exp(u), V) - e

    sol = optimize.least_squares(
        resid, u0, jac="3-point", loss=loss, f_scale=f_scale, x_scale=1.0, xtol=1e-15, ftol=1e-15, gtol=1e-15
    )
    return sol.x, resid


CASES = {
    "seed p_y": (model_seed, ("limiting_pressure",), seed_data, {}),
    "additive p_y + G": (
        model_additive,
        ("limiting_pressure", "work_of_adhesion"),
        additive_data,
        {"work_of_adhesion": 0.2},
    ),
}


@pytest.mark.parametrize("loss", LOSSES)
@pytest.mark.parametrize("case", list(CASES))
def test_the_minimum_is_least_squares_minimum(case, loss):
    model, names, data, start = CASES[case]
    V, e = data()
    pair = SILICON.replace(limiting_pressure=100e6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FitWarning)
        fit = fit_restitution(
            V,
            e,
            pair,
            params=names,
            loss=loss,
            model="additive" if len(names) > 1 else fitting.SEED_MODEL,
            model_params=start,
        )
    assert fit.success
    theta = np.array([fit.params[n] for n in names])
    refs = np.array([100e6, 0.2][: len(names)])
    # scipy from a start 20 % off the solution, with the fit's own f_scale (set from the data)
    u_sp, resid = scipy_fit(model, refs, V, e, loss, fit.f_scale, np.log(theta / refs) + 0.2)
    np.testing.assert_allclose(theta, refs * np.exp(u_sp), rtol=1e-7)
    np.testing.assert_allclose(fit.residuals, -resid(u_sp), rtol=0, atol=1e-7)
    if loss == "linear":  # the textbook covariance s^2 (J^T J)^-1 at scipy's minimum (J by its own differences)
        J = optimize._numdiff.approx_derivative(resid, u_sp, method="3-point")
        r = resid(u_sp)
        C = float(r @ r) / (V.size - len(names)) * np.linalg.inv(J.T @ J)
        np.testing.assert_allclose(fit.log_covariance, C, rtol=1e-5)
        se = theta * np.sqrt(np.diag(C))
        np.testing.assert_allclose([fit.stderr[n] for n in names], se, rtol=1e-5)


@pytest.mark.parametrize("loss", ["linear", "soft_l1"])
@pytest.mark.parametrize("sigma", [None, 0.02])
def test_the_result_does_not_depend_on_the_block_size(monkeypatch, loss, sigma):
    """Blocks of 7 points (and the median of the residual scatter by selection above 50 points)
    give what one block gives, to rounding."""
    V, e = seed_data(n=300, outliers=True)
    e[::37] = 1.0 + 0.2  # points far above 1: the warning's scale is the median-based scatter
    s = None if sigma is None else np.full(V.size, sigma)
    pair = SILICON.replace(limiting_pressure=100e6)

    def run():
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", FitWarning)
            fit = fit_restitution(V, e, pair, sigma=s, loss=loss, interval="profile")
        return fit, [str(w.message) for w in caught]

    one, said = run()
    monkeypatch.setattr(_solver, "_BLOCK", 7)
    monkeypatch.setattr(_solver, "_GATHER", 50)
    many, said_many = run()
    assert said == said_many and one.n_far_above_one == many.n_far_above_one > 0
    p = "limiting_pressure"
    assert many.params[p] == pytest.approx(one.params[p], rel=1e-10)
    assert many.conf_int[p] == pytest.approx(one.conf_int[p], rel=1e-9)
    np.testing.assert_allclose(many.log_covariance, one.log_covariance, rtol=1e-9)
    np.testing.assert_allclose(many.residuals, one.residuals, rtol=0, atol=1e-11)
    assert many.chi2 == pytest.approx(one.chi2, rel=1e-10) and many.n_elastic == one.n_elastic


@pytest.mark.parametrize("kind", ["normal", "ties", "mostly zero", "heavy tails"])
@pytest.mark.parametrize("n", [1001, 5000, 12345])
def test_the_median_by_selection_is_numpys(monkeypatch, kind, n):
    monkeypatch.setattr(_solver, "_BLOCK", 777)
    monkeypatch.setattr(_solver, "_GATHER", 1000)
    rng = np.random.default_rng(n)
    r = {
        "normal": lambda: rng.normal(size=n),
        "ties": lambda: np.round(rng.normal(size=n), 2),
        "mostly zero": lambda: np.where(np.arange(n) < 10, 1.0, 0.0),
        "heavy tails": lambda: rng.standard_cauchy(n) * 1e10,
    }[kind]()
    assert _solver._median(lambda s: r[s], n) == np.median(r)
    assert _solver.mad_scale(r) == 1.4826 * float(np.median(np.abs(r - np.median(r))))


def test_max_nfev_stops_the_fit_with_a_warning():
    V, e = seed_data(outliers=False)
    with pytest.warns(FitWarning, match="did not converge"):
        fit = fit_restitution(V, e, SILICON.replace(limiting_pressure=30e6), max_nfev=1)
    assert not fit.success and fit.nfev == 1 and math.isfinite(fit.params["limiting_pressure"])


def test_the_two_parameter_band_of_the_contact_time_is_the_delta_method():
    """predict(band=True) with two free parameters: e's band is confidence_band's, V_r's is V times
    it, the contact time's (forward differences, 1 + p whole outcomes) is the delta method computed
    here by central differences of the public pair.impact at the perturbed parameters."""
    name = "thornton_ning_1998_adhesive_plastic"
    V = np.geomspace(0.05, 60.0, 30)
    e = np.asarray(SILICON.impact(V, model=name, warn=False, work_of_adhesion=0.1).restitution)
    e = np.where(e > 0, np.abs(e + np.random.default_rng(0).normal(0.0, 0.01, V.size)), 0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit = fit_restitution(
            V,
            e,
            SILICON.replace(limiting_pressure=100e6),
            model=name,
            params=("limiting_pressure", "work_of_adhesion"),
            model_params={"work_of_adhesion": 0.3},
        )
    grid = np.array([0.5, 2.0, 10.0, 40.0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pred = fit.predict(grid, band=True)
    lo, hi = fit.confidence_band(grid)
    assert pred.method == "delta method"
    np.testing.assert_allclose(pred.restitution_lo, lo, rtol=1e-12)
    np.testing.assert_allclose(
        pred.rebound_velocity_hi - pred.rebound_velocity, grid * (hi - pred.restitution), rtol=1e-9
    )
    p_y, G = fit.params["limiting_pressure"], fit.params["work_of_adhesion"]

    def t_c(p, g):
        return np.asarray(
            SILICON.replace(limiting_pressure=p).impact(grid, model=name, warn=False, work_of_adhesion=g).contact_time
        )

    h = 1e-5
    g = np.stack(
        [
            (t_c(p_y * math.exp(h), G) - t_c(p_y * math.exp(-h), G)) / (2 * h),
            (t_c(p_y, G * math.exp(h)) - t_c(p_y, G * math.exp(-h))) / (2 * h),
        ],
        axis=-1,
    )
    half = fit.quantile * np.sqrt(np.einsum("ni,ij,nj->n", g, fit.log_covariance, g))
    np.testing.assert_allclose(pred.contact_time, t_c(p_y, G), rtol=1e-12)
    np.testing.assert_allclose(pred.contact_time_hi - pred.contact_time, half, rtol=1e-4)
    np.testing.assert_allclose(pred.contact_time - pred.contact_time_lo, half, rtol=1e-4)


def _e_by_groups_is_the_outcomes(monkeypatch, name, params, backend):
    """``(model, (V, E*, R*, m*, p_y), outcome's e)`` on speeds from 1e-3 to 1e3 m/s (one repeated), the
    silicon pair, on ``backend``, after asserting that fitting's e by distinct groups is the outcome's
    field bit for bit."""
    from microimpact.core import models as zoo
    from microimpact.impact import outcome_arrays

    monkeypatch.setenv("MICROIMPACT_BACKEND", backend)
    mod = zoo.get(name)
    V = np.concatenate([np.geomspace(1e-3, 1e3, 40), [7.0, 7.0, 50.0]])
    args = (
        V,
        *(np.asarray(x) for x in (SILICON.effective_modulus, SILICON.effective_radius, SILICON.effective_mass, 1e8)),
    )
    full = outcome_arrays(mod, *args, params)["restitution"]
    np.testing.assert_array_equal(_models._restitution_by_group(mod, *args, params), full)
    return mod, args, full


@pytest.mark.parametrize("backend", ["python", "numba"])
@pytest.mark.parametrize("params", [(0.0, 1.0), (0.3, 1.0), (0.3, 0.0), (2.5, 1.0), (-1.0, 1.0)])
def test_e_by_distinct_groups_is_the_outcomes_field_bit_for_bit(monkeypatch, params, backend):
    """Hertz-Tsuji's e depends on its damping ratio alone: fitting integrates once per distinct
    scaled damping kappa of the data (alpha_T up to rounding: at most 8 values over 1e-3..1e3 m/s) and must give the
    outcome's field exactly, on either engine (out-of-bounds parameters: NaN, as the outcome)."""
    mod, args, full = _e_by_groups_is_the_outcomes(monkeypatch, "hertz_tsuji", params, backend)
    g = evaluate(mod.restitution_group, *args, params=params)[0]
    assert np.unique(g).size <= 10 < args[0].size  # the point of it: a handful of integrations, not one per speed


@pytest.mark.parametrize("backend", ["python", "numba"])
@pytest.mark.parametrize("params", [(0.0, 1.0), (1e-9, 1.0), (1e-9, 0.0), (3e-7, 1.0), (3e-6, 0.0), (-1.0, 1.0)])
def test_viscoelastic_e_by_groups_is_the_outcomes_field_bit_for_bit(monkeypatch, params, backend):
    """The viscoelastic law's e is one function of kappa = A/T (distinct at each speed): fitting
    integrates once per distinct kappa of the data and must give the outcome's field exactly, on
    either engine, with the force clipped or not, where a particle is captured (e = 0 without
    clipping at large kappa: 6 of these speeds with A = 3e-6 s) and for out-of-bounds parameters (NaN, as the outcome)."""
    mod, args, full = _e_by_groups_is_the_outcomes(monkeypatch, "hertz_viscoelastic", params, backend)
    alone = evaluate(mod.restitution_only, *args, params=params)[0]
    np.testing.assert_array_equal(alone, full)


@pytest.mark.parametrize(
    "model, name, params",
    [
        ("thornton_ning_1998_adhesive_plastic", "limiting_pressure", {"work_of_adhesion": 0.001}),
        ("liggghts_thornton_ning", "k", None),
        ("liggghts_thornton_ning", "density", None),
        ("thornton_ning_1998_adhesive_plastic", "yield_velocity", {"work_of_adhesion": 0.001}),
        ("liggghts_thornton_ning", "effective_modulus", None),
        ("hertz_viscoelastic", "effective_modulus", {"dissipative_constant": 1e-9}),
        ("kogut_etsion_ekk", "density", {"yield_strength": 5e7}),
    ],
)
def test_a_fits_evaluations_skip_the_pair_and_give_its_numbers(model, name, params):
    """A fit of a pair parameter evaluates e from the pair's four values (values_at: the
    effective_values call that ContactPair.vary makes) rather than a validated pair per evaluation,
    and its start's grid in one array call (restitution_rows): both bit for bit the route through
    the pair, at every u of a grid and beyond it."""
    from microimpact.fitting._models import FitModel, restitution_of

    mdl = FitModel(SILICON, (name,), model=model, model_params=params, yield_strength=1e8)
    V = np.array([0.5, 3.0, 7.0, 7.0, 20.0, 60.0, 150.0])
    us = np.linspace(-3.0, 3.0, 13)[:, None]
    rows = mdl.restitution_rows(us, V)
    for u, row in zip(us, rows):
        pair, own = mdl.split(u)
        assert mdl.values_at(u[0]) == (
            pair.effective_modulus,
            pair.effective_radius,
            pair.effective_mass,
            pair.limiting_pressure,
        )
        through_pair = restitution_of(model, pair, own, V)
        np.testing.assert_array_equal(mdl.restitution(u, V), through_pair)
        np.testing.assert_array_equal(row, through_pair)
