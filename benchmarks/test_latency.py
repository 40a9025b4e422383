"""3. One impact through the object API against plain-Python functions computing the same."""

import warnings

import pytest
from _reference import core_outcome, outcome_reference, restitution_reference

KEY = "impact_latency"


def test_pair_impact(timed, pair):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # 50 m/s is a large-strain impact: flagged and warned, silently here
        timed(KEY, "pair.impact(50.0)", lambda: pair.impact(50.0), rounds=25, iterations=40)


def test_pair_impact_no_warning(timed, pair):
    """The same without emitting the large-strain warning (50 m/s is flagged): the computation alone."""
    timed(KEY, "pair.impact(50.0, warn=False)", lambda: pair.impact(50.0, warn=False), rounds=25, iterations=40)


def test_pair_impact_every_field_read(timed, pair):
    """The same, then every one of the 18 fields read (each becomes a numpy scalar on first reading)."""
    from microimpact.core.quantities import OUTCOME_FIELDS

    def run():
        res = pair.impact(50.0, warn=False)
        return [getattr(res, f) for f in OUTCOME_FIELDS]

    timed(KEY, "pair.impact(50.0, warn=False), every field read", run, rounds=25, iterations=40)


def test_core_outcome(timed, pair):
    outcome = core_outcome()
    args = (50.0, pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure)
    out = timed(KEY, "core outcome (plain Python)", lambda: outcome(*args), rounds=25, iterations=200)
    from microimpact.core.quantities import OUTCOME_FIELDS

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        api = pair.impact(50.0)
    e = out[OUTCOME_FIELDS.index("restitution")]
    assert e == pytest.approx(float(api.restitution), rel=1e-12)


def test_pair_restitution(timed, pair):
    timed(KEY, "pair.restitution(50.0)", lambda: pair.restitution(50.0), rounds=15, iterations=20)


def test_restitution_reference(timed, pair):
    Vy = pair.yield_velocity
    e = timed(
        KEY, "restitution_reference (plain Python)", lambda: restitution_reference(50.0, Vy), rounds=25, iterations=2000
    )
    assert e == pytest.approx(float(pair.restitution(50.0)), rel=1e-12)
    assert restitution_reference(0.5 * Vy, Vy) == 1.0


def test_outcome_reference(timed, pair):
    """The plain-Python closed form returning the same 18 numbers: ``pair.impact(50.0)`` is timed against it."""
    args = (50.0, pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure)
    ref = timed(KEY, "outcome_reference (plain Python)", lambda: outcome_reference(*args), rounds=25, iterations=200)
    from microimpact.core.quantities import OUTCOME_FIELDS

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        api = pair.impact(50.0)
    for name, x in zip(OUTCOME_FIELDS, ref):
        assert float(getattr(api, name)) == x, name  # bitwise the same numbers
