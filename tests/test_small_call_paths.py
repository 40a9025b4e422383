"""The shortcuts of a small array call (issue 25) decide as the general code does.

* ``check_velocity`` tests ``[+0, inf)`` with one integer maximum over the float64 bits; it accepts
  and refuses exactly the arrays that the float minimum and maximum did (``-0.0`` included, NaN and
  infinities of either sign refused, with the same message).
* ``evaluate``'s usual call (a 1-D float64 array and floats) gives bitwise what its general route
  gives for the same inputs (a 2-D view, float64 scalars), on either engine.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from microimpact._validation import check_velocity
from microimpact.core import arrays
from microimpact.core.models import thornton_ning_2016 as seed

_ANY_FLOAT = st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True, width=64)
_SPEEDS = hnp.arrays(
    np.float64,
    hnp.array_shapes(min_dims=0, max_dims=3, min_side=0, max_side=6),
    elements=st.one_of(_ANY_FLOAT, st.sampled_from([0.0, -0.0, np.inf, -np.inf, np.nan, 5e-324, -5e-324])),
)


def _old_rule(arr):
    """The rule as it was written: min >= 0 and max < inf (NaN fails both)."""
    return arr.size == 0 or bool(arr.min() >= 0 and arr.max() < np.inf)


@given(_SPEEDS)
def test_velocity_check_accepts_exactly_the_old_rule(arr):
    if _old_rule(arr):
        out = check_velocity("velocity", arr)
        assert out is arr or np.array_equal(out, arr)
    else:
        bad = arr[~(arr >= 0) | np.isinf(arr)].flat[0]
        with pytest.raises(ValueError, match="velocity must be") as info:
            check_velocity("velocity", arr)
        assert repr(float(bad)) in str(info.value)


def test_negative_zero_and_views_accepted():
    check_velocity("velocity", np.array([-0.0, 1.0]))
    check_velocity("velocity", np.broadcast_to(np.array(2.0), (3, 4)))
    check_velocity("velocity", np.arange(12.0).reshape(3, 4)[:, ::2])
    with pytest.raises(ValueError, match="finite .* got inf"):
        check_velocity("velocity", (np.arange(12.0).reshape(3, 4) + 1.0)[:, ::2] * np.inf)


@pytest.mark.parametrize("backend", ["python", "numba"])
@given(
    hnp.arrays(np.float64, st.integers(2, 40), elements=st.floats(0.0, 1e3, allow_subnormal=True)),
    st.floats(0.1, 100.0),
)
def test_usual_call_is_the_general_route(backend, V, Vy):
    fast = arrays.evaluate(seed.restitution_at, V, Vy, backend=backend)
    general = arrays.evaluate(seed.restitution_at, V[None, :], np.float64(Vy), backend=backend)
    assert fast.shape == (1, V.size) and general.shape == (1, 1, V.size)
    assert fast.tobytes() == general.tobytes()
    one_by_one = np.array([seed.restitution_at(float(v), Vy) for v in V])
    assert fast[0].tobytes() == one_by_one.tobytes()


@pytest.mark.parametrize("value", ["", "python", " NUMBA ", "bogus"])
def test_backend_variable_is_read_at_every_call(monkeypatch, value):
    """``MICROIMPACT_BACKEND`` is read from os.environ's own mapping (faster than os.environ.get): set,
    changed or removed at any time, the next call sees it, and a wrong value names the variable."""
    monkeypatch.delenv("MICROIMPACT_BACKEND", raising=False)
    assert arrays.backend_for(10**6) == "numba" and arrays.backend_for(1) == arrays._unforced_engine(1)
    monkeypatch.setenv("MICROIMPACT_BACKEND", value)
    if value == "bogus":
        with pytest.raises(ValueError, match="MICROIMPACT_BACKEND.*'bogus'"):
            arrays.backend_for(10)
    else:
        assert arrays.backend_for(10**6) == (value.strip().lower() or "numba")
    monkeypatch.delenv("MICROIMPACT_BACKEND")
    assert arrays.backend_for(10**6) == "numba"


class _Float(float):
    """A float subclass: not what the lane takes (its arithmetic could be anything)."""


def test_a_lane_goes_only_where_the_general_route_would(monkeypatch):
    """After evaluate's usual call has found its loop, the next ones take the lane straight to it:
    bitwise the general route's numbers, and only for the calls that route would send there (a
    backend forced by argument or by ``MICROIMPACT_BACKEND``, threads from 2048 elements, a float
    subclass, an ``out`` of one's own, a 2-D array all take the general route)."""
    V = np.linspace(0.5, 120.0, 700)
    Vy = 0.37
    arrays.evaluate(seed.restitution_at, V, Vy, backend="numba")  # compiled (or loaded)
    arrays.evaluate(seed.restitution_at, V, Vy)
    arrays.evaluate(seed.restitution_at, V, Vy)
    key = seed.restitution_at
    assert arrays._LANES[key][0] == (2, 1, False)
    want = np.array([seed.restitution_at(float(v), Vy) for v in V])
    lane, taken = arrays._LANES[key][1], []

    def spy(*args):
        taken.append(args[0])
        return lane(*args)

    monkeypatch.setitem(arrays._LANES, key, ((2, 1, False), spy, None))
    assert arrays.evaluate(seed.restitution_at, V, Vy)[0].tobytes() == want.tobytes()
    assert arrays.evaluate(seed.restitution_at, V, np.float64(Vy))[0].tobytes() == want.tobytes()
    assert taken == [V.size, V.size]  # a float64 scalar is typed as a float
    others = [
        lambda: arrays.evaluate(seed.restitution_at, V, Vy, backend="python"),
        lambda: arrays.evaluate(seed.restitution_at, V, _Float(Vy)),
        lambda: arrays.evaluate(seed.restitution_at, V, Vy, out=np.empty((1, V.size))),
        lambda: arrays.evaluate(seed.restitution_at, V[None, :], Vy)[:, 0],
    ]
    for other in others:
        assert other()[0].tobytes() == want.tobytes()
    big = np.linspace(0.5, 120.0, 4096)
    arrays.evaluate(seed.restitution_at, big, Vy)
    monkeypatch.setenv("MICROIMPACT_BACKEND", "python")
    assert arrays.evaluate(seed.restitution_at, V, Vy)[0].tobytes() == want.tobytes()
    assert taken == [V.size, V.size]


def _speeds_ufunc():
    """Make the seed's restitution lane reach its ufunc (``core._native.UFUNC_AFTER`` lane calls), or skip
    where this process runs numba's loops (no kept machine code: no ufunc to find)."""
    from microimpact.core import _native

    V = np.linspace(0.5, 120.0, 64)
    arrays.evaluate(seed.restitution_at, V, 0.37, backend="numba")  # compiled (or loaded)
    for _ in range(_native.UFUNC_AFTER + 3):
        arrays.evaluate(seed.restitution_at, V, 0.37)
    kept = arrays._LANES.get(seed.restitution_at, (None, None, None))[2]
    if kept is None or kept.ufunc_if_made() is None:
        pytest.skip("numba's loops run here: no kept loop, no ufunc")
    return kept


@given(
    hnp.arrays(np.float64, st.integers(2, 2047), elements=st.floats(0.0, 1e300, allow_subnormal=True)),
    st.floats(1e-3, 100.0),
)
def test_on_speeds_is_bitwise_evaluate(V, Vy):
    """``on_speeds`` (the loop's ufunc with the speeds' check folded in) gives bitwise what the checked
    general call gives, on speeds the check accepts."""
    _speeds_ufunc()
    got = arrays.on_speeds(seed.restitution_at, V, Vy)
    assert got is not None and got.shape == V.shape
    want = arrays.evaluate(seed.restitution_at, check_velocity("velocity", V)[None, :], np.float64(Vy))[0, 0]
    assert got.tobytes() == want.tobytes()
    assert got.tobytes() == np.array([seed.restitution_at(float(v), Vy) for v in V]).tobytes()


@pytest.mark.parametrize("bad", [-0.0, -1.0, -5e-324, np.nan, -np.nan, np.inf, -np.inf])
def test_on_speeds_leaves_every_speed_the_check_would_look_at_to_it(bad):
    """A speed outside ``[+0, inf)`` (-0.0 too, which the check then accepts) is not answered: the
    caller's check names it, and ``pair.restitution`` raises as before the shortcut."""
    from microimpact import ContactPair

    _speeds_ufunc()
    V = np.linspace(0.5, 120.0, 50)
    V[17] = bad
    assert arrays.on_speeds(seed.restitution_at, V, 0.37) is None
    pair = ContactPair.sphere_on_flat(radius=2.45e-6, density=1350.0, effective_modulus=1.31e9, limiting_pressure=156e6)
    for _ in range(3):
        pair.restitution(np.linspace(0.5, 120.0, 50))  # the pair's lane, past its ufunc
    if bad == 0.0:
        assert pair.restitution(V)[17] == seed.restitution_at(0.0, pair.yield_velocity)
    else:
        with pytest.raises(ValueError, match="velocity must be"):
            pair.restitution(V)


def test_on_speeds_answers_only_the_usual_small_call(monkeypatch):
    """Anything but a 1-D float64 array of 2 to 2047 speeds and the loop's own scalars, with no backend
    forced, goes back to the caller (None): evaluate's route decides it (threads, Python, an error)."""
    _speeds_ufunc()
    V = np.linspace(0.5, 120.0, 50)
    fn = seed.restitution_at
    assert arrays.on_speeds(fn, V, 0.37) is not None
    for other in (
        V[:1],
        np.linspace(0.5, 120.0, 2048),
        V[None, :],
        V.astype(np.float32),
        V.astype(V.dtype.newbyteorder()),
        list(V),
    ):
        assert arrays.on_speeds(fn, other, 0.37) is None
    assert arrays.on_speeds(fn, V, 0.37, 1.0) is None  # not the loop's count of inputs
    assert arrays.on_speeds(fn, V, 0.37, params=(1.0,)) is None
    assert arrays.on_speeds(fn, V, "0.37") is None  # no number: TypeError inside, evaluate's route decides
    assert arrays.on_speeds(seed.outcome, V, 1.0, 1.0, 1.0, 1.0) is None  # no lane of one result
    monkeypatch.setenv("MICROIMPACT_BACKEND", "python")
    assert arrays.on_speeds(fn, V, 0.37) is None


def test_on_speeds_gives_back_a_call_its_loop_refuses(monkeypatch):
    """A call the loop's ufunc refuses (its count grows) is not answered, whatever the ufunc returned."""
    import ctypes

    _speeds_ufunc()
    refused = ctypes.c_int64(0)

    def refusing(*args):
        refused.value += 1
        return np.zeros(args[0].shape)

    class Loop:
        def ufunc_if_made(self):
            return refusing, refused

    lane = arrays._LANES[seed.restitution_at]
    monkeypatch.setitem(arrays._LANES, seed.restitution_at, (lane[0], lane[1], Loop()))
    assert arrays.on_speeds(seed.restitution_at, np.linspace(0.5, 120.0, 50), 0.37) is None
    assert refused.value == 1
