"""2. Restitution alone for many speeds against copying the same array (the memory-bandwidth limit)."""

import numpy as np
import pytest

from microimpact.impact import restitution_coefficient

KEY = "restitution_vs_copy"


@pytest.fixture(scope="module")
def speeds(size, pair):
    return np.random.default_rng(2).uniform(0.0, 16.0, size["restitution"]) * pair.yield_velocity


@pytest.fixture(scope="module")
def reference(speeds, pair):
    return restitution_coefficient(speeds, pair.yield_velocity)


def test_copy(timed, speeds):
    buf = np.empty_like(speeds)
    timed(KEY, "copy", lambda: np.copyto(buf, speeds), rounds=11)


def test_restitution_coefficient(timed, speeds, pair):
    timed(KEY, "impact.restitution_coefficient", lambda: restitution_coefficient(speeds, pair.yield_velocity), rounds=5)


def test_pair_restitution(timed, record, speeds, reference, pair):
    e = timed(KEY, "pair.restitution", lambda: pair.restitution(speeds), rounds=7)
    np.testing.assert_allclose(e, reference, rtol=1e-13, atol=0)


def test_pair_restitution_into_out(timed, speeds, reference, pair):
    """The same into a preallocated array (``out=``), as the copy writes into one: inputs checked."""
    buf = np.empty_like(speeds)
    timed(KEY, "pair.restitution(V, out=buf)", lambda: pair.restitution(speeds, out=buf), rounds=11)
    np.testing.assert_array_equal(buf, reference)


def test_compiled_loop_into_out(timed, speeds, reference, pair):
    """The compiled loop alone (no input checks) into a preallocated array: the physics' own cost."""
    from microimpact import engine as arrays
    from microimpact.core.models import thornton_ning_2016 as seed

    buf = np.empty_like(speeds)
    Vy = np.float64(pair.yield_velocity)
    arrays.evaluate(seed.restitution_at, speeds[:16], Vy)  # compiled outside the timing
    timed(
        KEY,
        "compiled loop, out=buf (no checks)",
        lambda: arrays.evaluate(seed.restitution_at, speeds, Vy, out=buf),
        rounds=11,
    )
    np.testing.assert_array_equal(buf, reference)
