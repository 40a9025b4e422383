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


def _fast_backends():
    """``(restitution_fast, backend)`` for each backend of the fused kernel, where it exists."""
    try:
        from microimpact import _kernels
    except ImportError:
        return []
    fast = getattr(_kernels, "restitution_fast", None)
    if fast is None:
        return []
    backends = getattr(_kernels, "available_backends", lambda: [None])()
    return [(fast, b) for b in backends]


@pytest.mark.parametrize(
    "backend",
    [b for _, b in _fast_backends()]
    or [pytest.param(None, marks=pytest.mark.skip(reason="microimpact._kernels.restitution_fast is not there"))],
)
def test_restitution_fast(timed, speeds, reference, pair, backend):
    from microimpact._kernels import restitution_fast

    kw = {} if backend is None else {"backend": backend}
    buf = np.empty_like(speeds)
    restitution_fast(speeds[:16], pair.yield_velocity, **kw)  # compiles (numba) outside the timing
    timed(
        KEY,
        f"_kernels.restitution_fast[{backend}]",
        lambda: restitution_fast(speeds, pair.yield_velocity, out=buf, **kw),
        rounds=11,
    )
    np.testing.assert_allclose(buf, reference, rtol=1e-13, atol=0)
