"""What the published laws say about themselves: the numbers their docstrings quote, and the ranges
outside which their unloadings stop being a law (flagged and warned, not refused)."""

from __future__ import annotations

import re

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
