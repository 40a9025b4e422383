"""7. The full outcome with times over an array of speeds against copying the array; threads at 1e3."""

import math
import warnings

import numpy as np

KEY = "outcome_vs_copy"


def _speeds(n):
    return np.linspace(1.0, 120.0, n)


def test_copy(timed, size):
    V = _speeds(size["restitution"])
    out = np.empty_like(V)
    timed(KEY, "copy", lambda: np.copyto(out, V), rounds=5)


def test_outcome(timed, size, pair):
    V = _speeds(size["restitution"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pair.impact(V[:100_000])  # loads the compiled loops
        timed(KEY, "pair.impact (18 fields)", lambda: pair.impact(V, warn=False), rounds=3)


def _run_1e3(pair):
    from microimpact.core import arrays
    from microimpact.core.models import thornton_ning_2016 as seed

    V = _speeds(1000)
    E, R, m, p = (
        np.float64(x)
        for x in (pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure)
    )
    return lambda: arrays.evaluate(seed.outcome, V, E, R, m, p, nout=18, params=(), backend="numba")


def test_default_at_1e3(timed, pair):
    """The compiled loop over 1e3 speeds as the library runs it."""
    run = _run_1e3(pair)
    run()
    run()
    timed("threads_1e3", "default", run, rounds=20, iterations=20)


def test_serial_at_1e3(timed, pair, monkeypatch):
    """The same with the serial loop forced."""
    from microimpact.core import arrays

    monkeypatch.setattr(arrays, "PARALLEL_MIN", 10**12)
    monkeypatch.setattr(arrays, "PARALLEL_WORK", math.inf)
    run = _run_1e3(pair)
    run()
    timed("threads_1e3", "serial forced", run, rounds=20, iterations=20)


def test_threads_at_1e3(timed, pair, monkeypatch):
    """The same with the multi-threaded loop forced."""
    from microimpact.core import arrays

    monkeypatch.setattr(arrays, "PARALLEL_MIN", 1)
    run = _run_1e3(pair)
    run()
    timed("threads_1e3", "threads forced", run, rounds=20, iterations=20)
