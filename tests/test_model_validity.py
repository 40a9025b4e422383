"""What the published laws say about themselves: the numbers their docstrings quote, and the ranges
outside which their unloadings stop being a law (flagged and warned, not refused)."""

from __future__ import annotations

import re

import numpy as np
import pytest

import microimpact as mi
from microimpact.core.models import thornton_ning_1998_adhesive_plastic as ap


def test_tn98_docstring_example_holds_at_the_speed_it_names():
    """The docstring's weak-adhesion example (e rises with G) at the speed it names, to its 4 digits; and
    that speed is three times the law's own V_y with that G (not the seed's V_y: 0.8640 there)."""
    doc = " ".join(ap.__doc__.split())
    m = re.search(
        r"at ``V = ([0-9.]+)`` m/s, three times this law's own ``V_y`` with ``G = ([0-9.]+)`` \(([0-9.]+) m/s;"
        r".*?\(([0-9.]+) against ([0-9.]+) without it\)",
        doc,
    )
    assert m, "the example names its speed, G and both restitutions"
    V, G, Vy_own, e_adh, e_0 = (float(x) for x in m.groups())
    pair = mi.ContactPair.paper_case("silicon")
    model = "thornton_ning_1998_adhesive_plastic"
    with_g = pair.impact(V, model=model, work_of_adhesion=G, warn=False)
    without = pair.impact(V, model=model, work_of_adhesion=0.0, warn=False)
    assert float(with_g.yield_velocity) == pytest.approx(Vy_own, abs=5e-4)
    assert V == pytest.approx(3 * float(with_g.yield_velocity), abs=5e-3)
    assert float(with_g.restitution) == pytest.approx(e_adh, abs=5e-5)
    assert float(without.restitution) == pytest.approx(e_0, abs=5e-5)
    assert e_adh > e_0


PAIR = mi.ContactPair.paper_case("silicon")
Y300 = PAIR.effective_modulus / 300.0  # E*/S_y = 300: Jackson-Green's loading jumps up at 1.9 delta_c


def _yield_velocity(model, y):
    return float(PAIR.impact(1.0, model=model, yield_strength=y, warn=False).yield_velocity)


@pytest.mark.parametrize(("model", "band"), [("kogut_etsion_ekk", (1.0, 1.66)), ("jackson_green_brake", (2.23, 2.38))])
def test_unloading_that_would_create_energy_is_flagged_and_warned(model, band):
    """Where the published unloading would give e > 1 the outcome keeps e = 1 (unchanged) and the impact is
    flagged with reason 1: exactly the plastic impacts whose e is 1, inside the band the docstrings state."""
    vy = _yield_velocity(model, Y300)
    V = vy * np.linspace(0.5, 3.0, 251)
    res = PAIR.impact(V, model=model, yield_strength=Y300, warn=False)
    with pytest.warns(mi.models.OutsideValidityWarning, match=r"e > 1; e = 1 is returned"):
        flags = mi.models.outside_validity(PAIR, V, model=model, yield_strength=Y300)
    plastic_e1 = (res.restitution == 1.0) & ~np.asarray(res.elastic, dtype=bool)
    assert flags.any() and np.array_equal(flags, plastic_e1)
    lo, hi = V[flags].min() / vy, V[flags].max() / vy
    assert band[0] - 0.02 <= lo and hi <= band[1] + 0.02
    mod = mi.models.get(model)
    pv = (PAIR.effective_modulus, PAIR.effective_radius, PAIR.effective_mass, PAIR.limiting_pressure)
    codes = mi.models.validity_codes(mod, V, *pv, mi.models.resolve_params(mod, {"yield_strength": Y300}))
    assert set(np.unique(codes)) <= {0.0, 1.0}


def test_contact_radius_beyond_the_sphere_is_flagged():
    """Jackson-Green's contact radius passes R* near 59 V_y for the seed's silicon pair at S_y = 54 MPa; there
    (reason 2) its e rises with V again; below it nothing is flagged. e itself is unchanged."""
    model, y = "jackson_green_brake", 5.4e7
    V = _yield_velocity(model, y) * np.geomspace(3.0, 3000.0, 60)
    res = PAIR.impact(V, model=model, yield_strength=y, warn=False)
    beyond = np.asarray(res.max_contact_radius) > PAIR.effective_radius
    assert beyond.any() and not beyond.all()
    with pytest.warns(mi.models.OutsideValidityWarning, match="exceeds the sphere's radius"):
        flags = mi.models.outside_validity(PAIR, V, model=model, yield_strength=y)
    assert np.array_equal(flags, beyond)
    e = np.asarray(res.restitution)
    assert np.max(np.diff(e[beyond])) > 0.0  # what the flag is for: e rises there


def test_models_without_the_hook_are_inside_and_silent():
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        flags = mi.models.outside_validity(PAIR, [1.0, 50.0, 500.0], model="thornton_ning_2016")
    assert not flags.any()
    assert mi.models.get("thornton_ning_2016").outside_validity is None
    assert mi.models.validity_text("x", [1.0], [0.0]) is None


@pytest.mark.parametrize("model", ["kogut_etsion_ekk", "jackson_green_brake"])
def test_pair_impact_carries_the_flag_and_its_warning(model):
    """``pair.impact`` flags the impacts :func:`outside_validity` names and warns, with the outcome
    unchanged (e = 1 kept); a model without the hook is never flagged."""
    vy = _yield_velocity(model, Y300)
    V = vy * np.linspace(0.5, 3.0, 51)
    expected = mi.models.outside_validity(PAIR, V, model=model, yield_strength=Y300, warn=False)
    assert expected.any()
    with pytest.warns(mi.OutsideValidityWarning):
        res = PAIR.impact(V, model=model, yield_strength=Y300)
    assert np.array_equal(res.outside_validity, expected)
    quiet = PAIR.impact(V, model=model, yield_strength=Y300, warn=False)
    assert np.array_equal(quiet.restitution, res.restitution) and np.all(res.restitution[expected] == 1.0)
    assert not np.any(PAIR.impact(V, warn=False).outside_validity)
