"""5. Memory: peaks of traced allocations (tracemalloc) of array calls and of eager vs chunked sweeps.

tracemalloc sees every allocation numpy makes through Python's allocator hooks (array data
included), from all threads (dask's too). Peaks are measured above what was allocated before
the call; the inputs are allocated before tracing starts.
"""

import tracemalloc

import numpy as np
import pytest

KEY = "memory"


def traced_peak(fn):
    """Peak traced allocation [bytes] while ``fn()`` runs, above the level when it started."""
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        base, _ = tracemalloc.get_traced_memory()
        fn()
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return peak - base


def test_impact_array_peak(record, size, pair):
    n = size["memory"]
    speeds = np.linspace(0.5, 120.0, n)
    peak = traced_peak(lambda: pair.impact(speeds, warn=False))
    record.metric(KEY, "pair.impact_peak_bytes", peak)
    record.metric(KEY, "pair.impact_peak_per_point", peak / n)
    assert peak >= 16 * 8 * n  # at least the 16 float result arrays


def test_restitution_peak(record, size, pair):
    from microimpact.impact import restitution_coefficient

    n = size["memory"]
    speeds = np.linspace(0.5, 120.0, n)
    peak = traced_peak(lambda: restitution_coefficient(speeds, pair.yield_velocity))
    record.metric(KEY, "restitution_coefficient_peak_bytes", peak)
    record.metric(KEY, "restitution_coefficient_peak_per_point", peak / n)
    peak = traced_peak(lambda: pair.restitution(speeds))
    record.metric(KEY, "pair.restitution_peak_bytes", peak)
    record.metric(KEY, "pair.restitution_peak_per_point", peak / n)
    assert peak >= 8 * n  # the result itself


def test_sweep_eager_vs_chunked(record, size):
    pytest.importorskip("dask")
    pytest.importorskip("xarray")
    from microimpact.sweep import sweep

    n = size["sweep"]
    npy = max(int(round(n**0.5 / 3)), 2)
    nv = n // npy
    V = np.linspace(0.5, 120.0, nv)
    p = np.linspace(50e6, 250e6, npy)
    fields = ["restitution", "contact_time", "max_force"]
    out = {}

    def eager():
        out["eager"] = sweep(V, limiting_pressure=p)[fields].mean()

    def chunked():
        out["chunked"] = sweep(V, limiting_pressure=p, chunks="auto")[fields].mean().compute()

    record.metric(KEY, "sweep_points", nv * npy)
    record.metric(KEY, "sweep_chunked_peak_bytes", traced_peak(chunked))
    record.metric(KEY, "sweep_eager_peak_bytes", traced_peak(eager))
    for k in fields:
        assert float(out["chunked"][k]) == pytest.approx(float(out["eager"][k]), rel=1e-12)
