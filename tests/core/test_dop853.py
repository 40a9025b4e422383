"""The DOP853 tableau of :mod:`microimpact.core.dop853` against scipy's table and the method's order.

The viscoelastic and Hertz-Tsuji laws integrate their equation of motion with it; a mistyped
coefficient would still converge (the step control hides it) but lose its order, which
:func:`test_steps_have_eighth_order` would see, and differ from scipy's table, which
:func:`test_values_are_scipys_table` sees first.
"""

from __future__ import annotations

import math
from fractions import Fraction

import pytest

from microimpact.core import dop853 as dp
from microimpact.core.models import hertz_viscoelastic as hv

coefficients = pytest.importorskip("scipy.integrate._ivp.dop853_coefficients")


def _names(prefix):
    return [n for n in vars(dp) if n.startswith(prefix) and n[len(prefix)].isdigit()]


def test_values_are_scipys_table():
    n = coefficients.N_STAGES
    B = coefficients.A[n, :n]
    seen = 0
    for s in range(1, n):
        for j in range(s):
            name = f"A{s}_{j}"
            assert getattr(dp, name, 0.0) == coefficients.A[s, j], name
            seen += coefficients.A[s, j] != 0.0
    for j in range(n):
        assert getattr(dp, f"B{j}", 0.0) == B[j], f"B{j}"
        assert getattr(dp, f"E5_{j}", 0.0) == coefficients.E5[j], f"E5_{j}"
        assert getattr(dp, f"E3_{j}", 0.0) == coefficients.E3[j], f"E3_{j}"
    assert coefficients.E5[n] == coefficients.E3[n] == 0.0  # the slope at the new point is not used
    assert len(_names("A")) == seen  # no coefficient beyond scipy's


def _tableau():
    A = {(int(k[1:].split("_")[0]), int(k.split("_")[1])): Fraction(getattr(dp, k)) for k in _names("A")}
    B = [Fraction(getattr(dp, f"B{j}", 0.0)) for j in range(12)]
    c = [sum((a for (s, _), a in A.items() if s == i), Fraction(0)) for i in range(12)]
    return A, B, c


def test_order_conditions():
    """Quadrature conditions ``sum b_i c_i^(k-1) = 1/k`` up to k = 8 and ``sum b_i a_ij c_j^(k-1) = 1/(k(k+1))``
    up to k = 7 (to the doubles' rounding), and both error estimators vanish on constants."""
    A, B, c = _tableau()
    for k in range(1, 9):
        assert float(sum(b * ci ** (k - 1) for b, ci in zip(B, c))) == pytest.approx(1.0 / k, abs=1e-14), k
    for k in range(1, 8):
        total = sum(B[i] * a * c[j] ** (k - 1) for (i, j), a in A.items())
        assert float(total) == pytest.approx(1.0 / (k * (k + 1)), abs=1e-14), k
    for name in ("E5_", "E3_"):
        assert abs(sum(getattr(dp, n) for n in _names(name))) < 1e-14, name


def test_steps_have_eighth_order():
    """One step of the viscoelastic law's integrator from inside the contact: halving the step
    divides its error (against 64 steps of a 64th of it) by about 2^9, a local error O(h^9)
    (measured 425; a fifth-order pair gives 2^6)."""

    def run(x, v, h, n):
        for _ in range(n):
            x, v, _ = hv._step(x, v, h / n, 0.3, 0.5)
        return x, v

    x0, v0 = 0.5, 0.6
    errs = []
    for h in (0.8, 0.4):
        ref = run(x0, v0, h, 64)
        got = hv._step(x0, v0, h, 0.3, 0.5)
        errs.append(math.hypot(got[0] - ref[0], got[1] - ref[1]))
    assert 2.0**9 / 2.5 < errs[0] / errs[1] < 2.0**9 * 2.5
