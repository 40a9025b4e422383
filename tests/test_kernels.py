"""Fast paths of microimpact._kernels against the reference array functions.

restitution_fast must equal impact.restitution_coefficient (seed eq. 27) to 1e-14
relative on every backend, and the backends must equal each other to 1e-15;
impact_scalar must equal impact_outcome + contact_times to 1e-13 for every key,
including the edge values 0, V_y, inf and p_y = inf.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microimpact import _kernels
from microimpact._kernels import available_backends, impact_scalar, restitution_fast
from microimpact.dynamics import contact_times
from microimpact.impact import impact_outcome, restitution_coefficient, thornton_ning_restitution
from microimpact.pair import ContactPair

BACKENDS = available_backends()
SILICON = ContactPair.paper_case("silicon")
ARGS = (SILICON.effective_modulus, SILICON.effective_radius, SILICON.effective_mass, SILICON.limiting_pressure)


def ref_e(V, Vy):
    with np.errstate(all="ignore"):  # the reference warns on overflow at huge speeds; its value is right
        return restitution_coefficient(V, Vy)


def assert_rel(a, b, rtol):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert a.shape == b.shape
    same = (a == b) | (np.isnan(a) & np.isnan(b))
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.abs(a - b) / np.abs(b)
    assert np.all(same | (rel <= rtol)), (a[~same], b[~same])


# ------------------------------------------------------------------ restitution_fast


def test_numpy_backend_always_available():
    assert BACKENDS[-1] == "numpy"
    assert _kernels.BACKEND in BACKENDS


@pytest.mark.parametrize("backend", BACKENDS)
def test_restitution_edge_values(backend):
    Vy = 7.5
    V = np.array([0.0, 1e-300, 1.0, Vy * (1 - 1e-16), Vy, Vy * (1 + 1e-15), 2 * Vy, 50.0, 1e6, 1e9, 1e150, 1e300])
    e = restitution_fast(V, Vy, backend=backend)
    ref = ref_e(V, Vy)
    assert_rel(e, ref, 1e-14)
    assert np.all(e[V <= Vy] == 1.0)  # exactly elastic at and below V_y
    assert 0.0 < e[-1] < 1e-70  # V = 1e300 (an infinite speed is refused by the reference: no outcome)
    assert np.all(np.diff(e[V > Vy]) < 0)  # strictly decreasing above yield


@pytest.mark.parametrize("backend", BACKENDS)
def test_restitution_infinite_yield_velocity(backend):
    V = np.array([0.0, 3.0, 1e300])
    assert_rel(restitution_fast(V, np.inf, backend=backend), ref_e(V, np.inf), 0)


@pytest.mark.parametrize("backend", BACKENDS)
def test_restitution_paper_value(backend):
    # seed: rebound 36.31 m/s at 50 m/s (its V_y 7.59 is rounded); eq. 27 from the inputs gives e = 0.7248
    e = restitution_fast(50.0, SILICON.yield_velocity, backend=backend)
    assert float(e) * 50.0 == pytest.approx(36.31, rel=0.01)
    # and Thornton & Ning's independent closed form
    assert float(e) == pytest.approx(float(thornton_ning_restitution(50.0, SILICON.yield_velocity)), rel=1e-12)


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.one_of(st.floats(0.0, 1e12), st.sampled_from([0.0, 1.0, 7.5, 1e300])), min_size=1, max_size=300),
    st.floats(1e-3, 1e3),
)
def test_restitution_matches_reference(speeds, Vy):
    V = np.array(speeds)
    ref = ref_e(V, Vy)
    results = [restitution_fast(V, Vy, backend=b) for b in BACKENDS]
    for e in results:
        assert_rel(e, ref, 1e-14)
        assert np.all(e > 0) and np.all(e <= 1.0)
    for e in results[1:]:  # the backends agree with each other
        assert_rel(e, results[0], 1e-15)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(st.floats(0.0, 1e4), st.floats(1e-2, 1e2)), min_size=1, max_size=100))
def test_restitution_array_yield_velocity(pairs):
    V, Vy = np.array(pairs).T
    for b in BACKENDS:
        assert_rel(restitution_fast(V, Vy, backend=b), ref_e(V, Vy), 1e-14)


@pytest.mark.parametrize("backend", BACKENDS)
def test_restitution_large_array_blocks_and_out(backend):
    # longer than one numpy block, with an uneven tail; written into a given buffer
    V = np.random.default_rng(3).uniform(0.0, 200.0, 3 * _kernels.BLOCK + 17)
    out = np.empty_like(V)
    res = restitution_fast(V, 7.5, out=out, backend=backend)
    assert res is out
    assert_rel(out, ref_e(V, 7.5), 1e-14)


@pytest.mark.parametrize("backend", BACKENDS)
def test_restitution_shapes_and_broadcasting(backend):
    V = np.linspace(0.0, 100.0, 12).reshape(3, 4)
    Vy = np.array([5.0, 7.5, 10.0])[:, None]
    assert_rel(restitution_fast(V, Vy, backend=backend), ref_e(V, Vy), 1e-14)
    assert restitution_fast(V.T, 7.5, backend=backend).shape == (4, 3)  # non-contiguous input
    assert restitution_fast(30.0, 7.5, backend=backend).shape == ()
    assert restitution_fast([1, 20, 30], 7.5, backend=backend).dtype == np.float64  # integer speeds
    out = np.empty((4, 3)).T  # non-contiguous out
    restitution_fast(V, 7.5, out=out, backend=backend)
    assert_rel(out, ref_e(V, 7.5), 1e-14)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("bad", [-1.0, np.nan])
def test_restitution_bad_velocity(backend, bad):
    V = np.full(2 * _kernels.BLOCK, 10.0)
    V[-5] = bad
    with pytest.raises(ValueError, match="velocity"):
        restitution_fast(V, 7.5, backend=backend)


@pytest.mark.parametrize("bad", [0.0, -2.0, np.nan])
def test_restitution_bad_yield_velocity(bad):
    with pytest.raises(ValueError, match="yield_velocity"):
        restitution_fast([10.0], bad)


def test_restitution_bad_backend_and_out():
    with pytest.raises(ValueError, match="backend"):
        restitution_fast([10.0], 7.5, backend="fortran")
    with pytest.raises(ValueError, match="out"):
        restitution_fast([10.0, 20.0], 7.5, out=np.empty(3))
    with pytest.raises(ValueError, match="out"):
        restitution_fast([10.0, 20.0], 7.5, out=np.empty(2, dtype=np.float32))


# ------------------------------------------------------------------ impact_scalar


def reference(V, E, R, m, p_y):
    with np.errstate(all="ignore"):
        out = impact_outcome(V, E, R, m, p_y)
        out.update(contact_times(V, E, R, m, p_y, outcome=out))
    return out


def assert_scalar_matches(V, E, R, m, p_y, rtol=1e-13):
    d = impact_scalar(V, E, R, m, p_y)
    ref = reference(V, E, R, m, p_y)
    assert set(d) == set(ref)
    for k, x in d.items():
        r = ref[k][()]
        if isinstance(x, bool):
            assert x == bool(r), k
        else:
            assert type(x) is float, k
            assert x == r or (math.isnan(x) and np.isnan(r)) or abs(x - r) <= rtol * abs(r), (k, x, r)
    return d


@pytest.mark.parametrize("p_y", [SILICON.limiting_pressure, math.inf])
@pytest.mark.parametrize("V", [0.0, 1e-30, 1.0, "Vy-", "Vy", "Vy+", 7.6, 30.0, 50.0, 70.0, 120.0, 1e6, 1e300])
def test_impact_scalar_edges(V, p_y):
    Vy = SILICON.yield_velocity
    V = {"Vy-": Vy * (1 - 1e-15), "Vy": Vy, "Vy+": Vy * (1 + 1e-12)}.get(V, V)
    d = assert_scalar_matches(V, *ARGS[:3], p_y)
    if V == 0.0:
        assert d["contact_time"] == math.inf and d["max_approach"] == 0.0
    if V == 1e300 and math.isfinite(p_y):  # Ning's loading time (eq. 31) in the limit
        assert d["loading_time"] == pytest.approx(SILICON.ning_loading_time(), rel=1e-12)
        assert 0.0 < d["restitution"] < 1e-70


@pytest.mark.parametrize("V", [math.inf, math.nan, -1.0])
def test_reference_refuses_infinite_and_nan_speed(V):
    # an infinite speed has no outcome (e = 0 with V_r = inf contradicts V_r = e V): refused, naming velocity
    with pytest.raises(ValueError, match=r"velocity .*got (inf|nan|-1\.0)"):
        impact_outcome(V, *ARGS)


def test_impact_scalar_paper_numbers():
    # seed Sec. 3: rebound 36.31 m/s, loading 0.01365 us and unloading 0.01115 us at 50 m/s (within 1 %)
    d = impact_scalar(50.0, *ARGS)
    assert d["rebound_velocity"] == pytest.approx(36.31, rel=0.01)
    assert d["loading_time"] * 1e6 == pytest.approx(0.01365, rel=0.01)
    assert d["unloading_time"] * 1e6 == pytest.approx(0.01115, rel=0.01)
    assert d["large_strain"] is True and d["elastic"] is False


@settings(max_examples=80, deadline=None)
@given(
    st.one_of(st.floats(0.0, 1e6), st.sampled_from([0.0, 1e300])),
    st.floats(1e8, 5e11),  # E*
    st.floats(1e-8, 1e-3),  # R*
    st.floats(500.0, 2e4),  # density -> m*
    st.one_of(st.floats(1e7, 5e9), st.just(math.inf)),  # p_y
)
def test_impact_scalar_matches_array_path(V, E, R, rho, p_y):
    m = 4.0 / 3.0 * math.pi * R**3 * rho
    assert_scalar_matches(V, E, R, m, p_y)


@settings(max_examples=40, deadline=None)
@given(st.floats(0.0, 3.0))
def test_impact_scalar_around_yield(x):
    # speeds within a factor 3 of V_y on both sides, where the branches switch
    assert_scalar_matches(x * SILICON.yield_velocity, *ARGS)


@pytest.mark.parametrize(
    "args, name",
    [
        ((-1.0, *ARGS), "velocity"),
        ((math.nan, *ARGS), "velocity"),
        ((10.0, 0.0, *ARGS[1:]), "effective_modulus"),
        ((10.0, math.inf, *ARGS[1:]), "effective_modulus"),
        ((10.0, ARGS[0], -1.0, *ARGS[2:]), "effective_radius"),
        ((10.0, *ARGS[:2], math.nan, ARGS[3]), "effective_mass"),
        ((10.0, *ARGS[:3], 0.0), "limiting_pressure"),
        ((10.0, *ARGS[:3], math.nan), "limiting_pressure"),
    ],
)
def test_impact_scalar_bad_input(args, name):
    with pytest.raises(ValueError, match=name):
        impact_scalar(*args)
