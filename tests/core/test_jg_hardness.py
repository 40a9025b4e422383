"""Jackson & Green's two hardness fits: the default (Ghaednia et al. 2019 eq. 28, the cosine form of
Jackson & Green 2006, as ``GHAEDNIA_ET_AL_FLATTENING.m`` writes it) and the option ``hardness=1``
(Jackson & Green 2005, ``2.84 [1 - exp(-0.82 (a/R)^-0.7)]``), each against its source's formula
written out here term by term, and the option reaching the impact through every path."""

from __future__ import annotations

import math

import numpy as np
import pytest

import microimpact as mi
from microimpact.core.models import _fitted_laws as fl
from microimpact.core.models import jackson_green_brake as jg

from .model_ode import fields, integrate, rel

R0 = 10e-6
M0 = 4.0 / 3.0 * math.pi * R0**3 * 7800.0
E0 = 110e9
Y0 = 300e6
RATIOS = (1e-3, 0.01, 0.05, 0.1, 0.2, 0.3, 0.5, 0.8, 1.0)


@pytest.mark.parametrize("r", RATIOS)
def test_hardness_fits_are_their_sources_formulas(r):
    """Eq. 28 as the tmd-lab code prints it (``2.84 - 0.92*(1-cos(pi*a/R))``) and the 2005 fit as the
    source list quotes it, at the same ``a/R``; both 2.84 in the limit ``a/R -> 0``."""
    a, R = r * R0, R0
    assert fl.jg_hardness_ratio(a, R) == pytest.approx(2.84 - 0.92 * (1.0 - math.cos(math.pi * a / R)), rel=1e-15)
    assert fl.jg_hardness_ratio_2005(a, R) == pytest.approx(2.84 * (1.0 - math.exp(-0.82 * (a / R) ** -0.7)), rel=1e-15)


def test_hardness_fits_agree_where_compared_and_part_beyond():
    """Within 2 % up to ``a/R = 0.3`` (the law's compared range), apart beyond it: a wrong exponent or
    sign in either would break one of the two."""
    for r in (1e-3, 0.05, 0.1, 0.2, 0.3):
        c, e = fl.jg_hardness_ratio(r, 1.0), fl.jg_hardness_ratio_2005(r, 1.0)
        assert abs(e - c) < 0.02 * c, (r, c, e)
    assert fl.jg_hardness_ratio_2005(0.0, 1.0) == 2.84
    assert fl.jg_hardness_ratio(1.0, 1.0) == pytest.approx(1.0)
    assert fl.jg_hardness_ratio_2005(1.0, 1.0) == pytest.approx(2.84 * (1.0 - math.exp(-0.82)))
    values = [fl.jg_hardness_ratio_2005(r, 1.0) for r in RATIOS]
    assert all(b < a for a, b in zip(values, values[1:]))  # falls monotonically with a/R


@pytest.mark.parametrize("x", [2.5, 10.0, 80.0])
def test_eq_27_with_the_2005_hardness(x):
    """The loading force of the option is eq. 27 with the 2005 hardness at eq. 23's radius, term by term."""
    nu = 0.3
    c = fl.law_constants(fl.JACKSON_GREEN_2005, E0, R0, Y0, nu, 0.0)
    dc = fl.jg_critical_interference(E0, R0, Y0, nu)
    C = 1.295 * math.exp(0.736 * nu)
    B = 0.14 * math.exp(23 * Y0 / E0)
    a = R0 * math.pi * C * Y0 / (2 * E0) * math.sqrt(x * (x / 1.9) ** B)
    H = 2.84 * (1.0 - math.exp(-0.82 * (a / R0) ** -0.7))
    Fc = 4.0 / 3.0 * (R0 / E0) ** 2 * (C * math.pi * Y0 / 2) ** 3
    by_hand = Fc * (math.exp(-0.25 * x ** (5 / 12)) * x**1.5 + 4 * H / C * (1 - math.exp(-(x ** (5 / 9)) / 25)) * x)
    assert fl._force(fl.JACKSON_GREEN_2005, x * dc, c) == pytest.approx(by_hand, rel=1e-13)
    # the default keeps eq. 28
    H28 = 2.84 - 0.92 * (1.0 - math.cos(math.pi * a / R0))
    default = Fc * (math.exp(-0.25 * x ** (5 / 12)) * x**1.5 + 4 * H28 / C * (1 - math.exp(-(x ** (5 / 9)) / 25)) * x)
    assert fl.jg_plastic_force(x, E0, R0, Y0, nu) == pytest.approx(default, rel=1e-13)


@pytest.mark.parametrize("V", [3.0, 12.0])
def test_outcome_of_the_2005_fit_equals_the_ode_of_its_force(V):
    """The closed path of the option against DOP853 with the option's own force."""
    p = (Y0, 0.3, 0.0, 1.0)
    o = fields(jg, V, E0, R0, M0, 1e9, p)
    d = integrate(jg, V, E0, R0, M0, 1e9, p)
    assert abs(o["restitution"] - d["restitution"]) < 1e-8
    for k in ("max_approach", "max_force", "contact_time"):
        assert rel(o[k], d[k]) < 1e-8, (k, o[k], d[k])
    assert o["restitution"] != fields(jg, V, E0, R0, M0, 1e9, p[:3] + (0.0,))["restitution"]  # past the switch


def test_the_option_through_the_pair_scalar_and_array():
    """``hardness=1`` changes ``e`` in the plastic range only, the default is ``hardness=0`` exactly,
    and the scalar and array paths agree."""
    pair = mi.ContactPair.paper_case()
    V = np.array([0.05, 5.0, 20.0, 50.0])
    kw = dict(model="jackson_green_brake", yield_strength=54e6, warn=False)
    base = np.asarray(pair.impact(V, **kw).restitution)
    zero = np.asarray(pair.impact(V, hardness=0, **kw).restitution)
    new = np.asarray(pair.impact(V, hardness=1, **kw).restitution)
    assert np.array_equal(base, zero)
    assert new[0] == base[0] == 1.0  # below 1.9 delta_c: Hertz, no hardness
    assert np.all(new[1:] != base[1:])
    scalar = [float(pair.impact(float(v), hardness=1, **kw).restitution) for v in V]
    assert np.allclose(scalar, new, rtol=1e-12, atol=0.0)
    with pytest.raises(ValueError, match="hardness must be 0 or 1"):
        pair.impact(5.0, hardness=2, **kw)
