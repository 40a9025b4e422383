"""Every integration bounds its work and says so when it reaches the bound: a flagged result with a
warning (the viscoelastic laws' scaled integration, the deposition tracking) or a ValueError naming
the bound (the oblique ODE, the ODE history's time span), never a result taken mid-way in silence."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import microimpact as mi
from microimpact import deposition, dynamics, oblique
from microimpact.core.models import hertz_viscoelastic as hv
from microimpact.models import OutsideValidityWarning


@pytest.mark.parametrize("q, kappa", [(0.5, 1000.0), (0.25, 3.0)])
def test_scaled_damped_hertz_reaches_its_bound_and_says_so(q, kappa):
    """Unclipped, heavily damped: the particle creeps out and never ends the contact; the integration
    stops at its bound with ``e = 0``, ``t_end = inf`` and :func:`reaches_bound` True. A lighter
    damping, or the clipped force, ends within the bounds."""
    out = hv.scaled_damped_hertz(kappa, False, q)
    assert out[0] == 0.0 and out[4] == math.inf
    assert hv.reaches_bound(kappa, False, q)
    assert not hv.reaches_bound(kappa, True, q)
    assert not hv.reaches_bound(1.0, False, q)
    assert hv.scaled_damped_hertz(1.0, False, q)[4] < hv.T_MAX


def test_the_pair_flags_and_warns_where_the_integration_reached_its_bound():
    pair = mi.ContactPair.paper_case()
    with pytest.warns(OutsideValidityWarning, match="the integration reached its bound"):
        res = pair.impact(np.array([1.0, 2.0]), model="hertz_tsuji", damping_ratio=3.0, limit_force=0)
    assert np.all(res.outside_validity)
    assert np.all(np.asarray(res.restitution) == 0.0) and np.all(np.isinf(res.contact_time))
    with pytest.warns(OutsideValidityWarning, match="reached its bound"):
        one = pair.impact(1.0, model="hertz_tsuji", damping_ratio=3.0, limit_force=0)
    assert bool(one.outside_validity)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # clipped, or lightly damped: inside the bound, no warning
        assert not bool(pair.impact(1.0, model="hertz_tsuji", damping_ratio=3.0).outside_validity)
        assert not bool(pair.impact(1.0, model="hertz_tsuji", damping_ratio=1.0, limit_force=0).outside_validity)
        assert not bool(pair.impact(1.0, model="hertz_viscoelastic", dissipative_constant=1e-9).outside_validity)


def test_integrate_oblique_ode_refuses_a_result_past_its_segment_bound(monkeypatch):
    """A sliding-then-sticking impact takes several segments; with a bound of two it is a ValueError
    naming the bound, where the loop used to return the state in the middle of the contact."""
    full = oblique.integrate_oblique_ode(0.5, 1.0, 0.5)
    assert full["switches"] >= 1
    monkeypatch.setattr(oblique, "ODE_MAX_SEGMENTS", 2)
    with pytest.raises(ValueError, match="reached its bound of 2 segments"):
        oblique.integrate_oblique_ode(0.5, 1.0, 0.5)


def test_ode_phase_reaching_its_span_bound_is_a_value_error():
    """An event that never comes: the span doubles ``tries`` times, then a ValueError names the bound."""

    def never(t, y):
        return 1.0

    never.terminal = True
    with pytest.raises(ValueError, match="reached its bound of 3 extensions"):
        dynamics._integrate_phase(lambda t, y: [0.0], 0.0, np.array([0.0]), 1.0, [never], "RK45", 1e-6, 1e-9, tries=3)


def test_deposition_reaching_max_impacts_warns_and_reports_the_unresolved():
    kw = dict(n_particles=4, plate_radius=math.inf, height=0.01)
    with pytest.warns(deposition.DepositionBoundWarning, match="max_impacts=2 with 4 of 4 particles still bouncing"):
        res = deposition.simulate_deposition([2e-5], [5.0], max_impacts=2, **kw)
    assert res.unresolved_fraction[0, 0] == 1.0
    assert res.deposited_fraction[0, 0] == 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the first impact decides by choice: no bound reached
        first = deposition.simulate_deposition([2e-5], [5.0], max_impacts=1, **kw)
    assert first.unresolved_fraction[0, 0] == 1.0
