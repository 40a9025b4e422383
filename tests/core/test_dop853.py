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


def _oscillator(x, v, p):
    """``x'' = -k x`` with the spring's energy ``w' = k x v`` (``p = (k,)``)."""
    return -p[0] * x, p[0] * x * v


def test_step_carries_a_third_state_to_eighth_order():
    """:func:`dp.step` on the harmonic oscillator from ``(1, 0, 0)``: the state after one step and the
    third state (the change of the spring's energy, ``-sin^2(h)/2`` exactly) have a local error of at
    least O(h^9): halving the step divides it by about 2^9 or more (a wrong weight of the third
    state's rates would leave a low order); the error estimators shrink with the step too."""
    errs = []
    for h in (0.8, 0.4):
        x, v, w, e5x, e5v, e3x, e3v = dp.step(_oscillator, 1.0, 0.0, 0.0, h, (1.0,))
        exact = (math.cos(h), -math.sin(h), -0.5 * math.sin(h) ** 2)
        errs.append((math.hypot(x - exact[0], v - exact[1]), abs(w - exact[2]), abs(e5x) + abs(e5v)))
    assert 2.0**9 / 2.5 < errs[0][0] / errs[1][0] < 2.0**9 * 2.5  # measured 524
    assert errs[0][1] / errs[1][1] > 2.0**9 / 2.5  # measured 5988: this quadrature gains orders
    assert errs[1][2] < errs[0][2] / 16.0


def test_hairer_error_is_the_rms_of_the_scaled_estimators():
    """Both estimators equal (``err5 = err3 = e``): ``|h| e^2 / sqrt(2 (1.01 e^2))`` for two components
    of scaled size ``e / sqrt(2)`` each; zero estimators give zero."""
    e = 3.0
    got = dp.hairer_error(-0.5, e, e, e, e, 2.0, 2.0)
    scaled = 2.0 * (e / 2.0) ** 2
    assert got == pytest.approx(0.5 * scaled / math.sqrt(2.0 * 1.01 * scaled), rel=1e-15)
    assert dp.hairer_error(0.5, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0) == 0.0


def test_the_stages_are_written_once():
    """Every model that integrates its equation of motion takes DOP853's step from :func:`dp.step`:
    no other module of the core writes out the last stage's coefficients."""
    import pathlib

    import microimpact.core as core

    root = pathlib.Path(core.__file__).parent
    copies = [p.name for p in root.rglob("*.py") if p.name != "dop853.py" and "A11_10" in p.read_text()]
    assert copies == []
