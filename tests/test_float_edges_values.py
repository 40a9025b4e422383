"""What the laws return at the edges of the float range, beyond "no exception" (``tests/test_float_range.py``).

Each edge case is compared with the law's own value in its normal range or its known limit, so that a
fix that only silenced an exception (a clipped value, a 0 for an underflow, a spurious capture) fails.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import microimpact as mi
from microimpact import stick
from microimpact.fitting import fit_restitution

PAIR = mi.ContactPair.paper_case()
TINY = float(np.finfo(float).tiny)
HUGE = float(np.finfo(float).max)
EXTREME_SPEEDS = (5e-324, 1e-310, TINY, 1e-300, 1e-200, 1e200, 1e300, HUGE)


def _impact(v, model, **params):
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        return PAIR.impact(v, model=model, warn=False, **params)


@pytest.mark.parametrize("v", EXTREME_SPEEDS)
def test_hertz_tsuji_restitution_does_not_depend_on_the_speed_at_any_speed(v):
    # the scaled equation's damping is alpha_T whatever the speed: e equals its value at 10 m/s to rounding
    e10 = _impact(10.0, "hertz_tsuji", damping_ratio=0.3).restitution
    assert _impact(v, "hertz_tsuji", damping_ratio=0.3).restitution == pytest.approx(e10, rel=1e-14)


@pytest.mark.parametrize("v", [5e-324, 1e-300, 1e-100, 1e-20])
def test_dmt_loading_time_tends_to_the_pull_in_from_rest(v):
    # as K -> 0 the adhesion pulls the particle in from rest in a finite time: continuous with slow impacts
    slow = _impact(1e-12, "dmt_elastic_adhesive", surface_energy=0.05)
    out = _impact(v, "dmt_elastic_adhesive", surface_energy=0.05)
    assert out.restitution == 1.0
    assert out.contact_time == pytest.approx(slow.contact_time, rel=1e-10)
    assert math.isfinite(out.contact_time) and out.contact_time > 0.0


LUDING = dict(loading_stiffness=1e3, unloading_stiffness=4e3, adhesion_stiffness=50.0, plasticity_depth=0.2)


@pytest.mark.parametrize("v", [5e-324, 1e-320, 1e-310, TINY, 1e-300, 1e-20])
def test_luding_adhesive_tiny_impacts_rebound_elastically(v):
    # a vanishing impact is elastic (the plastic share of the approach is O(a1/dp)): e = 1, not a capture,
    # and never above 1 (rounding once gave 1.0000000054 at the smallest normal speed)
    out = _impact(v, "luding_adhesive", **LUDING)
    assert out.restitution == 1.0
    assert out.contact_time == pytest.approx(_impact(0.0, "luding_adhesive", **LUDING).contact_time, rel=1e-14)
    assert _impact(1e-10, "luding_adhesive", **LUDING).restitution < 1.0  # the law's loss is still resolved there


@pytest.mark.parametrize("k2", [1e250, 1e300, HUGE])
def test_luding_adhesive_stiff_unloading_captures(k2):
    # k2 -> inf: the unloading gives back no energy, so the adhesive branch holds the particle (e = 0),
    # where the rounded x = ac - a0 > 0 used to take a square root of a negative number
    out = _impact(10.0, "luding_adhesive", **dict(LUDING, unloading_stiffness=k2))
    assert out.restitution == 0.0


@pytest.mark.parametrize("model", ["jackson_green_brake", "kogut_etsion_ekk"])
def test_fitted_laws_say_nan_where_double_precision_cannot(model):
    # a yield strength whose critical interference underflows, a speed whose square overflows: NaN, the law
    # cannot say; the scalar, array and restitution-only paths agree
    for kw in (dict(velocity=10.0, yield_strength=1e-300), dict(velocity=1e200, yield_strength=54e6)):
        v = kw.pop("velocity")
        assert math.isnan(_impact(v, model, **kw).restitution)
        assert math.isnan(PAIR.impact(np.array([v]), model=model, warn=False, **kw).restitution[0])
    assert 0.0 < _impact(100.0, model, yield_strength=54e6).restitution < 1.0  # the normal range untouched


def test_parting_diameter_checks_its_bracket():
    for kw, word in (
        (dict(lo=0.0), "lo"),
        (dict(hi=math.inf), "hi"),  # the bisection ran for ever
        (dict(lo=1e-3, hi=1e-6), "lo must be below hi"),
        (dict(hi=1e300), "hi"),  # its mass 4/3 pi R^3 rho overflows
    ):
        with pytest.raises(ValueError, match=word):
            stick.parting_diameter(PAIR, 0.1, 1.1, **kw)


def test_capture_velocities_names_a_diameter_whose_mass_overflows():
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        with pytest.raises(ValueError, match=r"diameter 1e\+300 m is outside what double precision can model"):
            stick.capture_velocities(PAIR, [5e-6, 1e300], 0.1)


@pytest.mark.parametrize("v", [5e-324, 1e-310, HUGE])
def test_a_fit_refuses_speeds_outside_the_doubles_it_searches(v):
    with pytest.raises(ValueError, match=r"velocity .*point 2.* outside what double precision can fit"):
        fit_restitution([5.0, 10.0, v, 20.0, 40.0], [0.8, 0.72, 0.65, 0.6, 0.5], PAIR)


def test_a_fit_with_an_absurd_restitution_warns_instead_of_overflowing():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.simplefilter("error", RuntimeWarning)
        fit_restitution([5.0, 10.0, 15.0, 20.0, 40.0], [0.8, 0.72, 1e300, 0.6, 0.5], PAIR)
    assert any("not finite at the start" in str(w.message) for w in caught)
