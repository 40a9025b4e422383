"""The array engine's own contract: its deprecated old home, and the loop source it generates."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from microimpact import engine
from microimpact.core.models import thornton_ning_2016 as seed
from microimpact.engine import loops

MOVED = ("BACKENDS", "PARALLEL_MIN", "PARALLEL_WORK", "PYTHON_BUDGET", "SMALL", "backend_for", "cache_dir", "evaluate")


@pytest.mark.parametrize("name", MOVED)
def test_the_old_home_hands_out_the_engines_names_and_says_where_they_went(name):
    import microimpact.core.arrays as old

    with pytest.warns(DeprecationWarning, match=rf"microimpact\.engine\.{name}\b"):
        got = getattr(old, name)
    assert got is getattr(engine, name)


def test_the_old_home_knows_no_other_name():
    import microimpact.core.arrays as old

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(AttributeError, match="on_speeds"):
            old.on_speeds  # noqa: B018
        assert sorted(dir(old)) == sorted(MOVED)


def test_one_generated_source_serves_both_loops_and_compiles_as_python():
    """The source calls the function with each array indexed and each scalar as it is, params last;
    it is valid Python, and a module made from it in memory gives the scalar function's bits."""
    text = loops.generate(seed.outcome, "assss", 18, True)
    assert text.startswith(loops.MARK)
    assert text.count("r = _top(a0[i], a1, a2, a3, a4, params)") == 2
    assert "def serial(n, a0, a1, a2, a3, a4, params, out):" in text
    assert "def parallel(n, a0, a1, a2, a3, a4, params, out):" in text
    assert "out[17, i] = r[17]" in text and "out[18," not in text
    plain = loops.generate(seed.restitution_at, "as", 1, False)
    assert "def serial(n, a0, a1, out):" in plain and "r = _top(a0[i], a1)" in plain and "params" not in plain
    compile(text, "<generated>", "exec")


def test_an_empty_array_returns_its_shape_without_compiling():
    out = engine.evaluate(seed.restitution_at, np.empty((0, 3)), 1.0, backend="numba")
    assert out.shape == (1, 0, 3)


def test_a_function_not_marked_runs_in_python():
    def double(x):
        return 2.0 * x

    V = np.linspace(0.0, 1.0, 5000)  # beyond SMALL: the compiled engine for a marked function
    assert np.array_equal(engine.evaluate(double, V)[0], 2.0 * V)


def test_registered_lists_the_marked_functions():
    names = {f.__name__ for f in engine.registered()}
    assert {"restitution_at", "outcome", "sphere_mass"} <= names
