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
