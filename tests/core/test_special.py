"""microimpact.core.special and its table (core.hertz_beta_table): against mpmath and scipy."""

import math

import numpy as np
import pytest
from scipy import special as sc

from microimpact.core import hertz_beta_table as table
from microimpact.core import special

mp = pytest.importorskip("mpmath")

A, B = 0.4, 0.5


def _edges():
    w = table.WIDTH
    knots = [k * w for k in range(table.PIECES + 1)]
    u_side = [x for k in knots for x in (k, math.nextafter(k, 0.0), math.nextafter(k, 1.0)) if 0.0 <= x < 1.0]
    s_side = [1.0 - s * s for s in knots if 1.0 - s * s > 0.0]
    split = [table.U_SPLIT, math.nextafter(table.U_SPLIT, 0.0), math.nextafter(table.U_SPLIT, 1.0)]
    ends = [0.0, 5e-324, 1e-300, 1e-16, 1e-8, 0.5, 1.0 - 1e-8, math.nextafter(1.0, 0.0), 1.0]
    return sorted(set(u_side + s_side + split + ends))


def _g_exact(u):
    """``G(u) = B(u; 2/5, 1/2)/u^(2/5) = (5/2) F(2/5, 1/2; 7/5; u)`` at 40 digits."""
    with mp.workdps(40):
        a = mp.mpf(2) / 5
        return mp.hyp2f1(a, mp.mpf(1) / 2, a + 1, mp.mpf(u)) / a


def test_table_is_what_its_generator_makes():
    """The stored coefficients are exactly those generate() computes (nothing edited by hand)."""
    u_coeffs, s_coeffs = table.generate()
    assert u_coeffs == table.U_COEFFS
    assert s_coeffs == table.S_COEFFS
    assert len(table.U_COEFFS) == len(table.S_COEFFS) == table.PIECES * (table.DEGREE + 1)
    # the pieces cover [0, U_SPLIT) in u and [0, (1 - U_SPLIT)^(1/2)] in s
    assert table.PIECES * table.WIDTH >= table.U_SPLIT
    assert table.PIECES * table.WIDTH >= math.sqrt(1.0 - table.U_SPLIT)


def test_scaled_integral_within_two_ulp_of_mpmath():
    rng = np.random.default_rng(11)
    us = list(rng.uniform(0.0, 1.0, 1500)) + list(10.0 ** rng.uniform(-12, 0, 300)) + _edges()
    us += list(1.0 - 10.0 ** rng.uniform(-15, -1, 300))
    worst = 0.0
    for u in us:
        u = float(u)
        g = special.hertz_beta_scaled(u)
        exact = _g_exact(u)
        worst = max(worst, float(abs((g - exact) / exact)))
    assert worst < 2 * 2.0**-52, worst


def test_scaled_integral_ends():
    assert special.hertz_beta_scaled(0.0) == 2.5  # 1/a
    assert special.hertz_beta_scaled(1.0) == pytest.approx(special.BETA_25_12, rel=2e-16)


def test_hertz_beta_against_scipy_and_the_continued_fraction():
    """B(u; 2/5, 1/2) from the tables, from DLMF 8.17.22 (the general function) and from scipy agree."""
    rng = np.random.default_rng(12)
    us = np.concatenate([rng.uniform(0.0, 1.0, 2000), np.array(_edges())])
    ours = np.array([special.hertz_beta(float(u)) for u in us])
    fraction = np.array([special.incomplete_beta(float(u), A, B) for u in us])
    scipy_values = sc.betainc(A, B, us) * sc.beta(A, B)
    np.testing.assert_allclose(ours, fraction, rtol=2e-15, atol=0)
    normal = us >= 2.2250738585072014e-308  # scipy is 3 % off at the subnormal 5e-324; mpmath decides there
    np.testing.assert_allclose(ours[normal], scipy_values[normal], rtol=1e-14, atol=0)
    tiny = 5e-324
    with mp.workdps(40):
        exact = mp.betainc(mp.mpf(2) / 5, mp.mpf(1) / 2, 0, mp.mpf(tiny))
    assert special.hertz_beta(tiny) == pytest.approx(float(exact), rel=1e-15)
    assert special.hertz_beta(0.0) == 0.0
    assert special.hertz_beta(1.0) == special.BETA_25_12


def test_scaled_integral_is_increasing_and_continuous_at_the_knots():
    """G grows with u (the integrand t^(-3/5)(1-t)^(-1/2) u^(...) weight); no jump where pieces meet."""
    us = np.linspace(0.0, 1.0, 4097)  # 1/4096 apart: far more than the rounding of G
    g = [special.hertz_beta_scaled(float(u)) for u in us]
    assert all(b > a for a, b in zip(g, g[1:]))
    for k in range(1, table.PIECES):
        x = k * table.WIDTH
        left, right = special.hertz_beta_scaled(math.nextafter(x, 0.0)), special.hertz_beta_scaled(x)
        assert abs(right - left) <= 4 * 2.0**-52 * right


def test_beta_is_the_complete_function():
    assert special.beta(A, B) == pytest.approx(sc.beta(A, B), rel=1e-15)
    assert special.BETA_25_12 == pytest.approx(float(mp.beta(mp.mpf(2) / 5, mp.mpf(1) / 2)), rel=2e-16)
    assert special.beta(200.0, 3.0) == pytest.approx(sc.beta(200.0, 3.0), rel=1e-12)  # the lgamma branch


@pytest.mark.parametrize("a, b", [(A, B), (B, A)])
def test_incomplete_beta_inverse_against_scipy_and_mpmath(a, b):
    """The inverse the closed-form history uses, on the half it is used on (x <= 1/2)."""
    beta_ab = special.beta(a, b)
    rng = np.random.default_rng(7)
    xs = np.concatenate([rng.random(400) * 0.5, 0.5 * 10.0 ** rng.uniform(-250, 0, 200), [0.5, 1e-300]])
    for x in xs:
        u = special.incomplete_beta_inverse(float(x), a, b, beta_ab)
        ref = sc.betaincinv(a, b, x)
        if ref > 1e-250:  # scipy floors results below 2.2e-308 (and loses digits near it)
            assert u == pytest.approx(ref, rel=1e-14), x
        if u > 1e-290:
            assert special.incomplete_beta_with(u, a, b, beta_ab) / beta_ab == pytest.approx(x, rel=1e-13), x
    for x in (1e-3, 0.1, 0.3, 0.5):  # mpmath's own inverse of its regularised incomplete beta
        with mp.workdps(30):
            ref = mp.findroot(lambda t: mp.betainc(a, b, 0, t, regularized=True) - x, sc.betaincinv(a, b, x))
        assert special.incomplete_beta_inverse(x, a, b, beta_ab) == pytest.approx(float(ref), rel=1e-14)
    assert special.incomplete_beta_inverse(0.0, a, b, beta_ab) == 0.0
    assert special.incomplete_beta_inverse(1.0, a, b, beta_ab) == 1.0


@pytest.mark.parametrize("p, start", [("5/3", 2), ("5/2", 0), ("1/2", 1), (3, 0)])
def test_binomial_series_sums_to_the_power(p, start):
    """The coefficients summed at small x give (1 - x)^p minus its first terms, in mpmath at 40 digits."""
    from fractions import Fraction

    q = Fraction(p)
    coeffs = special.binomial_series(q, start, start + 40, Fraction(3, 5))
    with mp.workdps(40):
        qm = mp.mpf(q.numerator) / q.denominator
        for x in ("0.01", "0.1", "0.3"):
            xm = mp.mpf(x)
            head = sum(mp.binomial(qm, k) * (-xm) ** k for k in range(start))
            ref = mp.mpf(3) / 5 * ((1 - xm) ** qm - head)
            got = sum(mp.mpf(c) * xm ** (k + start) for k, c in enumerate(coeffs))
            assert abs(got - ref) <= 1e-15 * abs(ref) + mp.mpf(10) ** -30
    if q.denominator == 1:  # an integer power: the series ends
        assert special.binomial_series(q, 0, 10)[4:] == (0.0,) * 6


def test_gauss_legendre_literals_are_numpys_rules():
    """The kept nodes and weights are numpy's ``leggauss`` within 2 units in the last place (they were
    generated from it, bit for bit; another LAPACK may round the eigenvalues otherwise), integrate
    polynomials up to degree 2n - 1 exactly (to rounding), and are the ones the laws use."""
    from microimpact.core import gauss_legendre as gl
    from microimpact.core.models import _fitted_laws, _jkr

    for n, (nodes, weights) in gl.RULES.items():
        x, w = np.polynomial.legendre.leggauss(n)
        assert len(nodes) == len(weights) == n and all(type(v) is float for v in nodes + weights)
        np.testing.assert_array_max_ulp(np.array(nodes), x, maxulp=2)
        np.testing.assert_array_max_ulp(np.array(weights), w, maxulp=2)
        for k in range(2 * n):  # int_-1^1 t^k dt = 2/(k+1) for even k, 0 for odd k
            exact = 2.0 / (k + 1) if k % 2 == 0 else 0.0
            assert math.fsum(wi * xi**k for xi, wi in zip(nodes, weights)) == pytest.approx(exact, abs=1e-14)
    assert (_jkr.GX, _jkr.GW) == gl.RULES[48]
    assert (_fitted_laws.GX, _fitted_laws.GW, _fitted_laws.GX6, _fitted_laws.GW6) == gl.RULES[24] + gl.RULES[6]


def test_importing_the_core_models_does_not_import_numpy_polynomial():
    """The rules are literals: importing the laws no longer costs numpy.polynomial (issue 25)."""
    import subprocess
    import sys

    code = "import sys, microimpact.core.models, microimpact.models; print('numpy.polynomial' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"
