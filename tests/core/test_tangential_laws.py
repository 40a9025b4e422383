"""The DEM codes' tangential laws along the closed-form normal history (microimpact.core.tangential_laws).

The laws are checked against the DEM codes themselves in ``tests/test_oblique_laws.py``; here: the
generic integrator against the independent one of :mod:`microimpact.core.tangential` (another state
variable, another code) for the law they share, convergence, and the array paths bitwise.
"""

from __future__ import annotations

import numpy as np
import pytest

from microimpact.core import arrays
from microimpact.core import tangential as tg
from microimpact.core import tangential_laws as tl

KAPPA = 2 * (1 - 0.23) / (2 - 0.23)  # alumina on a rigid flat


@pytest.mark.parametrize("x", [2.0, 0.5, 0.05])
@pytest.mark.parametrize("psi", [0.3, 0.9, 1.2, 3.0, 6.0])
def test_rescale_force_law_equals_the_mindlin_integrator(x, psi):
    """LAMMPS mindlin_rescale/force in the generic form (state T/a^c, spin and centre apart) is the
    model "mindlin" (state T, then T/k_t; slip alone) to rounding, however u0 is split."""
    u0 = psi / KAPPA
    ref, regime = tg.integrate_tangential(u0, KAPPA, x, 400)
    for share in (1.0, 0.3, -0.5):
        v, w, rg = tl.integrate_law(
            tl.law_code("lammps_mindlin_rescale_force"), share * u0, (1 - share) * u0, KAPPA, x, 0.0, 400
        )
        assert v + w == pytest.approx(ref, abs=1e-12)
        assert rg == regime
        # the centre takes 2/7 of the slip change, the rim 5/7 (a solid sphere, arm R)
        assert (v - share * u0) == pytest.approx((ref - u0) / 3.5, abs=1e-12)


@pytest.mark.parametrize("law", tl.LAWS)
def test_fixed_steps_converge(law):
    code = tl.law_code(law)
    for x in (2.0, 0.1):
        for u0 in (0.4, 1.5, 4.0):
            coarse = tl.integrate_law(code, u0, 0.0, KAPPA, x, 3e-3, 400)
            fine = tl.integrate_law(code, u0, 0.0, KAPPA, x, 3e-3, 1600)
            assert coarse[0] == pytest.approx(fine[0], abs=1e-6)
            assert coarse[1] == pytest.approx(fine[1], abs=1e-6)


def test_the_laws_differ_where_the_codes_do():
    """Below the sliding-throughout angle the laws give different impulses (the reason to offer them)."""
    out = {law: tl.integrate_law(tl.law_code(law), 1.5, 0.0, KAPPA, 2.0, 0.0, 400)[0] for law in tl.LAWS}
    values = sorted(out.values())
    assert min(np.diff(values)) > 1e-4 or len(set(np.round(values, 6))) >= 5
    # far beyond it every law slides throughout: the Coulomb impulse mu (1 + e) m V = 2 mu m V
    for law in tl.LAWS:
        v, w, rg = tl.integrate_law(tl.law_code(law), 40.0, 0.0, KAPPA, 2.0, 0.0, 400)
        assert rg == tg.REGIME_SLIDING
        assert v == pytest.approx(40.0 - 2.0, abs=1e-9)


def test_paths_bitwise_equal():
    rng = np.random.default_rng(3)
    n = 24
    code = rng.integers(0, len(tl.LAWS), n).astype(float)
    v0 = rng.uniform(-3, 3, n)
    w0 = rng.uniform(-1, 1, n)
    kap = rng.uniform(0.6, 1.2, n)
    x = 10 ** rng.uniform(-2, 0.3, n)
    eps = rng.uniform(0, 1e-2, n)
    steps = np.full(n, 60.0)
    args = (code, v0, w0, kap, x, eps, steps)
    scalar = np.array([tl.integrate_law(*(float(a[i]) for a in args)) for i in range(n)]).T
    py = arrays.evaluate(tl.integrate_law, *args, nout=3, backend="python")
    serial = arrays.evaluate(tl.integrate_law, *args, nout=3, backend="numba")
    old = arrays.PARALLEL_MIN
    try:
        arrays.PARALLEL_MIN = 1
        parallel = arrays.evaluate(tl.integrate_law, *args, nout=3, backend="numba")
    finally:
        arrays.PARALLEL_MIN = old
    assert np.array_equal(py, scalar)
    assert np.array_equal(parallel, serial)
    # Compiled against Python: the transcendental functions (sin, asin, pow) of LLVM and of the C
    # library differ in the last bit now and then, and the integration carries that on (the
    # integrator of core.tangential shows the same, up to 5e-16).
    np.testing.assert_allclose(serial, scalar, rtol=0, atol=1e-13)


# ---------------------------------------------------------------- Stronge's compliant impact


def _stronge_closed_form(u0, kappa, e):
    """Stronge's impact piece by piece in closed form (the cases of pooltool's stronge_compliant.py):
    sliding ``u = u0 - 7/2 int P``, sticking the harmonic ``u = u1 cos(w s) - w x1 sin(w s)`` with
    ``w^2 = 7/2 kappa``, switches where ``|x|/eta^2 = P`` (slip) or ``cos s = (u0 - 7/2)/(eta^2 - 7/2)``
    (stick), the last slip to the end ``u_f = u - 7/2 e (1 + cos phase)``. Roots by brentq."""
    from scipy.optimize import brentq

    eta2 = 1.0 / kappa
    w = np.sqrt(3.5 * kappa)
    end = 0.5 * np.pi * (1 + e)

    def P(s):
        return np.sin(s) if s <= 0.5 * np.pi else np.sin(s / e + 0.5 * np.pi * (1 - 1 / e))

    def impulse(s):  # int_0^s P: 1 - cos s, then 1 + e (0 - cos phase) from the top
        if s <= 0.5 * np.pi:
            return 1 - np.cos(s)
        return 1 - e * np.cos(s / e + 0.5 * np.pi * (1 - 1 / e))

    def first_root(f, a, b, n=4000):
        grid = np.linspace(a, b, n)
        vals = [f(x) for x in grid]
        for i in range(n - 1):
            if vals[i] < 0 <= vals[i + 1]:
                return brentq(f, grid[i], grid[i + 1], xtol=1e-15)
        return None

    if u0 > eta2:  # slides from first touch (u0 > 0)
        x = (u0 - 3.5) / (eta2 - 3.5)
        u_slide = lambda s: u0 - 3.5 * impulse(s)  # noqa: E731

        # sticks where the stuck force's rate falls below the limit's
        def g(s):
            dP = np.cos(s) if s <= 0.5 * np.pi else np.cos(s / e + 0.5 * np.pi * (1 - 1 / e)) / e
            return dP - u_slide(s) / eta2

        s1 = first_root(g, 1e-9, end - 1e-9)
        if s1 is None:
            return u0 - 3.5 * (1 + e), x
        u1, x1 = u_slide(s1), eta2 * P(s1)
    else:
        s1, u1, x1 = 0.0, u0, 0.0

    def xs(s):
        return x1 * np.cos(w * (s - s1)) + u1 / w * np.sin(w * (s - s1))

    def us(s):
        return u1 * np.cos(w * (s - s1)) - w * x1 * np.sin(w * (s - s1))

    s2 = first_root(lambda s: abs(xs(s)) / eta2 - P(s), s1 + 1e-9, end - 1e-12)
    sign = np.sign(xs(s2))
    return us(s2) - 3.5 * sign * (impulse(end) - impulse(s2)), None


@pytest.mark.parametrize("e", [1.0, 0.7, 0.6])
def test_stronge_gross_slip_threshold_is_the_sources(e):
    """Gross slip beyond u0/(mu V) = (1 + e) beta_t/beta_n - eta^2/e (pooltool's is_gross_slip): the
    Coulomb impulse; just below, not. (The source's criterion looks at the last instant only; for
    ``e < omega_n/omega_t`` = 0.57 here the contact sticks again earlier, just above it: the closed
    forms below, which test the stick condition all along, agree with the integration there.)"""
    eta2 = 1.0 / KAPPA
    thr = 3.5 * (1 + e) - eta2 / e
    above = tl.integrate_stronge(thr * 1.001, KAPPA, e, 400)
    below = tl.integrate_stronge(thr * 0.999, KAPPA, e, 400)
    assert above[1] == tg.REGIME_SLIDING and above[0] == pytest.approx(thr * 1.001 - 3.5 * (1 + e), abs=1e-12)
    assert below[1] == tg.REGIME_MICROSLIP


@pytest.mark.parametrize("e", [1.0, 0.8, 0.5, 0.3])
@pytest.mark.parametrize("frac", [0.05, 0.3, 0.7, 0.95, 1.2, 2.0, 3.0, 4.5])
def test_stronge_equals_its_closed_forms(e, frac):
    """Stick-slip (u0 < eta^2), slip-stick-slip, gross slip: the integration against the piecewise closed forms."""
    eta2 = 1.0 / KAPPA
    u0 = frac * eta2
    ref, gross = _stronge_closed_form(u0, KAPPA, e)
    got, regime = tl.integrate_stronge(u0, KAPPA, e, 400)
    assert got == pytest.approx(ref, abs=1e-8)
    assert regime == (tg.REGIME_SLIDING if gross is not None else tg.REGIME_MICROSLIP)


def test_stronge_paths_bitwise_equal():
    rng = np.random.default_rng(5)
    n = 20
    args = (rng.uniform(-8, 8, n), rng.uniform(0.6, 1.2, n), rng.uniform(0.2, 1.0, n), np.full(n, 50.0))
    scalar = np.array([tl.integrate_stronge(*(float(a[i]) for a in args)) for i in range(n)]).T
    py = arrays.evaluate(tl.integrate_stronge, *args, nout=2, backend="python")
    serial = arrays.evaluate(tl.integrate_stronge, *args, nout=2, backend="numba")
    old = arrays.PARALLEL_MIN
    try:
        arrays.PARALLEL_MIN = 1
        parallel = arrays.evaluate(tl.integrate_stronge, *args, nout=2, backend="numba")
    finally:
        arrays.PARALLEL_MIN = old
    assert np.array_equal(py, scalar)
    assert np.array_equal(parallel, serial)
    np.testing.assert_allclose(serial, scalar, rtol=0, atol=1e-13)
