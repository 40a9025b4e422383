"""Coverage of the confidence intervals for every loss, and unbiased p_y from data with values above 1.

Synthetic data are the seed's e(V) (eq. 27) for the mica case plus seeded Gaussian noise
(numpy default_rng with fixed seeds), never clipped: with speeds from 0.8 V_y up, about 1.6
points per set lie above 1. The acceptance region of the number of covering intervals is the
binomial's central 99.9 % for the claimed level, so a correct interval fails with probability
< 0.001 and an interval with 80 % or 99.9 % actual coverage passes with probability < 0.02
(``test_coverage_bounds_cannot_pass_by_accident``).
"""

import warnings

import numpy as np
import pytest
from scipy import stats

import microimpact as mi
from microimpact.fitting import LOSSES, FitWarning, fit_restitution

MICA = mi.ContactPair.paper_case("mica")
TRUE_PY = MICA.limiting_pressure
N_DRAWS = 200
NOISE = 0.02
NEAR_AND_ABOVE_ONE = MICA.yield_velocity * np.geomspace(0.8, 12.0, 16)
FEW_ABOVE_YIELD = MICA.yield_velocity * np.array([0.5, 0.7, 0.9, 1.1, 1.5, 2.2, 3.5, 6.0])


def coverage_bounds(n=N_DRAWS, level=0.95, alpha=0.001):
    """Acceptance region [lo, hi] of hits for a correct interval, two-sided alpha."""
    lo = int(stats.binom.ppf(alpha / 2, n, level))
    hi = int(stats.binom.isf(alpha / 2, n, level))
    return lo, hi


def test_coverage_bounds_cannot_pass_by_accident():
    lo, hi = coverage_bounds()
    assert (lo, hi) == (179, 198)  # 0.895 ... 0.99
    p_pass = stats.binom.cdf(hi, N_DRAWS, 0.95) - stats.binom.cdf(lo - 1, N_DRAWS, 0.95)
    assert p_pass > 0.999
    for wrong in (0.80, 0.999):  # badly wrong intervals fail
        p_wrong = stats.binom.cdf(hi, N_DRAWS, wrong) - stats.binom.cdf(lo - 1, N_DRAWS, wrong)
        assert p_wrong < 0.02


def draws(V, seed0, n=N_DRAWS):
    for seed in range(seed0, seed0 + n):
        yield MICA.restitution(V) + np.random.default_rng(seed).normal(0.0, NOISE, V.size)


def run(V, seed0, **kw):
    hits, est, above = 0, [], 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FitWarning)  # a draw may hold a point > 3 sigma above 1
        for e in draws(V, seed0):
            above += int(np.sum(e > 1.0))
            fit = fit_restitution(V, e, MICA.replace(limiting_pressure=TRUE_PY * 0.5), **kw)
            lo, hi = fit.conf_int["limiting_pressure"]
            hits += lo <= TRUE_PY <= hi
            est.append(fit.params["limiting_pressure"])
    return hits, np.asarray(est), above, fit


@pytest.mark.parametrize(
    "kind, kw, seed0",
    [
        ("least squares, scale from residuals", {}, 10_000),
        ("least squares, absolute sigma", {"sigma": NOISE}, 20_000),
        *[(loss, {"loss": loss}, 30_000 + 1000 * i) for i, loss in enumerate(LOSSES[1:])],
    ],
)
def test_coverage_of_the_95_percent_interval_for_every_loss(kind, kw, seed0):
    hits, _, above, fit = run(NEAR_AND_ABOVE_ONE, seed0, **kw)
    assert fit.interval == "wald"  # 15 of 16 points above V_y
    assert above > N_DRAWS  # the data do contain values above 1
    lo, hi = coverage_bounds()
    assert lo <= hits <= hi, f"{kind}: {hits}/{N_DRAWS} intervals cover the truth"


@pytest.mark.parametrize("loss", ["linear", "soft_l1"])
def test_profile_interval_coverage_with_few_points_above_yield(loss):
    hits, _, _, fit = run(FEW_ABOVE_YIELD, 50_000 + 1000 * LOSSES.index(loss), loss=loss)
    assert fit.interval == "profile"  # auto: fewer than 10 points above V_y
    lo, hi = coverage_bounds()
    assert lo <= hits <= hi, f"profile, {loss}: {hits}/{N_DRAWS}"


def test_profile_interval_follows_the_curvature():
    """The profile interval is where the F statistic of the residual sum of squares equals t^2:
    checked by evaluating the RSS at its ends directly."""
    e = next(draws(FEW_ABOVE_YIELD, 60_000, 1))
    fit = fit_restitution(FEW_ABOVE_YIELD, e, MICA, interval="profile")
    wald = fit_restitution(FEW_ABOVE_YIELD, e, MICA, interval="wald")
    rss_hat = fit.rss
    s2 = rss_hat / fit.dof
    for end in fit.conf_int["limiting_pressure"]:
        r = e - MICA.replace(limiting_pressure=end).restitution(FEW_ABOVE_YIELD)
        assert (np.sum(r**2) - rss_hat) / s2 == pytest.approx(fit.quantile**2, rel=1e-6)
    assert fit.conf_int != wald.conf_int and wald.interval == "wald"
    assert fit.params == wald.params


def test_values_above_one_give_unbiased_p_y():
    """Mean of p_y over 200 draws within 3 standard errors of the mean of the truth (no clipping)."""
    _, est, above, _ = run(NEAR_AND_ABOVE_ONE, 70_000)
    assert above > N_DRAWS
    se = est.std(ddof=1) / np.sqrt(est.size)
    assert abs(est.mean() - TRUE_PY) < 3 * se, (est.mean() / TRUE_PY - 1, se / TRUE_PY)
