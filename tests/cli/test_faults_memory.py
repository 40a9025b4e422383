"""Fault corpus, part 6 (issue 24): memory bounded everywhere; newcomer frictions of ``fit``.

On the code before: the CSV reader of ``fit`` held every line as a Python string and every cell as
a Python float (a 10^7-row fit peaked at 3 GB; ``benchmarks/fit_memory.py --csv`` measures it);
``wall_interaction`` allocated whatever it was given (10^8 particles: 17 GB) with no budget check;
``fit --models`` could not rank a law that needs a start value (no ``--param``), and the error asked
for Python syntax (``model_params={...}``).
"""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from microimpact.io import MemoryBudgetError, load_restitution_csv
from microimpact.wall import wall_interaction

from .test_faults import assert_one_line, run


def test_the_csv_reader_streams(tmp_path):
    n = 200_000
    rng = np.random.default_rng(3)
    V = rng.uniform(2.0, 100.0, n)
    e = rng.uniform(0.3, 1.0, n)
    path = tmp_path / "big.csv"
    with open(path, "w") as fh:
        fh.write("# measured\nvelocity [m/s],restitution\n")
        np.savetxt(fh, np.column_stack([V, e]), delimiter=",", fmt="%.17g")
    tracemalloc.start()
    try:
        data = load_restitution_csv(path)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert np.array_equal(data.velocity, V) and np.array_equal(data.restitution, e)  # every digit read back
    assert data.lines[0] == 3 and data.lines[-1] == n + 2
    assert peak / n < 80, f"{peak / n:.0f} bytes per row"  # the values and line numbers, with one copy


def test_the_fit_holds_no_jacobian_of_the_data():
    """Beyond its inputs the fit keeps its residuals (8 bytes a point, a result attribute) and works
    in blocks: scipy's least_squares held the n x p Jacobian and several other n-sized arrays
    (130 bytes a point traced; a 10^7-row ``microimpact fit`` peaked at 1.7 GB)."""
    import warnings

    import microimpact as mi
    from microimpact.fitting import FitWarning, fit_restitution

    n = 400_000
    pair = mi.ContactPair.paper_case("silicon")
    rng = np.random.default_rng(4)
    V = rng.uniform(2.0, 100.0, n)
    e = pair.restitution(V) + rng.normal(0.0, 0.02, n)
    fit_restitution(V[:50], e[:50], pair)  # compiled loops loaded outside the measurement
    tracemalloc.start()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", FitWarning)
            fit = fit_restitution(V, e, pair.replace(limiting_pressure=80e6))
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert fit.residuals.shape == (n,) and 150e6 < fit.params["limiting_pressure"] < 160e6
    assert peak < 8 * n + 4e6, f"{peak / n:.0f} bytes per point"


def test_wall_interaction_over_the_budget_is_refused_before_allocating(monkeypatch):
    monkeypatch.setenv("MICROIMPACT_MAX_MEMORY", "10MB")
    v = np.broadcast_to(np.array([1.0, -5.0, 0.0]), (1_000_000, 3))  # 10^6 particles: ~170 MB of results
    tracemalloc.start()
    try:
        with pytest.raises(MemoryBudgetError, match="1000000 particles"):
            wall_interaction(v, [0.0, 1.0, 0.0], 5e-6, 2000.0, effective_modulus=1e9, limiting_pressure=1e8)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 10e6  # refused before the result table was made
    out = wall_interaction(v[:1000], [0.0, 1.0, 0.0], 5e-6, 2000.0, effective_modulus=1e9, limiting_pressure=1e8)
    assert out.velocity.shape == (1000, 3)  # within the budget: computed


DATA = "velocity,restitution\n5,0.95\n10,0.9\n20,0.86\n30,0.8\n50,0.72\n60,0.7\n80,0.64\n90,0.62\n"


def test_fit_models_take_param_like_compare(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "r.csv").write_text(DATA)
    models = "thornton_ning_2016,hertz_tsuji:damping_ratio"
    rc, out, err = run(["fit", "r.csv", "--models", models], capsys)
    assert_one_line(rc, err, "--param hertz_tsuji:damping_ratio=VALUE")
    assert "model_params" not in err and "{" not in err
    rc, out, err = run(["fit", "r.csv", "--models", models, "--param", "hertz_tsuji:damping_ratio=0.1"], capsys)
    assert rc == 0, err
    assert "hertz_tsuji:damping_ratio" in out and "thornton_ning_2016" in out
    rc, out, err = run(["fit", "r.csv", "--param", "hertz_tsuji:damping_ratio=0.1"], capsys)
    assert_one_line(rc, err, "--param", "--models")
    rc, out, err = run(["fit", "r.csv", "--models", models, "--param", "hertz_tsuji:nonsense=1"], capsys)
    assert_one_line(rc, err, "nonsense", "damping_ratio")
