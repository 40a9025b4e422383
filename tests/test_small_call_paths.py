"""The shortcuts of a small array call decide as the general code does.

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

from microimpact import engine
from microimpact._validation import check_velocity
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
    fast = engine.evaluate(seed.restitution_at, V, Vy, backend=backend)
    general = engine.evaluate(seed.restitution_at, V[None, :], np.float64(Vy), backend=backend)
    assert fast.shape == (1, V.size) and general.shape == (1, 1, V.size)
    assert fast.tobytes() == general.tobytes()
    one_by_one = np.array([seed.restitution_at(float(v), Vy) for v in V])
    assert fast[0].tobytes() == one_by_one.tobytes()


@pytest.mark.parametrize("value", ["", "python", " NUMBA ", "bogus"])
def test_backend_variable_is_read_at_every_call(monkeypatch, value):
    """``MICROIMPACT_BACKEND`` is read at every call: set, changed or removed at any time, the next call
    sees it, and a wrong value names the variable."""
    monkeypatch.delenv("MICROIMPACT_BACKEND", raising=False)
    assert engine.backend_for(10**6) == "numba" and engine.backend_for(1) == engine._unforced_engine(1)
    monkeypatch.setenv("MICROIMPACT_BACKEND", value)
    if value == "bogus":
        with pytest.raises(ValueError, match="MICROIMPACT_BACKEND.*'bogus'"):
            engine.backend_for(10)
    else:
        assert engine.backend_for(10**6) == (value.strip().lower() or "numba")
    monkeypatch.delenv("MICROIMPACT_BACKEND")
    assert engine.backend_for(10**6) == "numba"
