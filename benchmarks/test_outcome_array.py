"""7. The full outcome with times over an array of speeds against copying the array; threads at 1e3."""

import math
import time
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
    from microimpact import engine as arrays
    from microimpact.core.models import thornton_ning_2016 as seed

    V = _speeds(1000)
    E, R, m, p = (
        np.float64(x)
        for x in (pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure)
    )
    return lambda: arrays.evaluate(seed.outcome, V, E, R, m, p, nout=18, params=(), backend="numba")


def test_threads_at_1e3(record, pair):
    """The compiled loop over 1e3 speeds as the library runs it ("default"), with the serial loop
    forced and with the multi-threaded loop forced: timed round by round, interleaved (each round
    sets the thresholds its variant needs), so that the three bests are taken under the same load."""
    from microimpact import engine as arrays

    variants = {
        "default": (arrays.PARALLEL_MIN, arrays.PARALLEL_WORK),
        "serial forced": (10**12, math.inf),
        "threads forced": (1, arrays.PARALLEL_WORK),
    }
    saved = variants["default"]
    run = _run_1e3(pair)
    best = dict.fromkeys(variants, math.inf)
    try:
        for thresholds in variants.values():
            arrays.PARALLEL_MIN, arrays.PARALLEL_WORK = thresholds
            run()  # compiled (or loaded), and timed once by evaluate, before any round
            run()
        for _ in range(40):
            for name, thresholds in variants.items():
                arrays.PARALLEL_MIN, arrays.PARALLEL_WORK = thresholds
                t0 = time.perf_counter()
                for _ in range(20):
                    run()
                best[name] = min(best[name], (time.perf_counter() - t0) / 20)
    finally:
        arrays.PARALLEL_MIN, arrays.PARALLEL_WORK = saved
    for name, seconds in best.items():
        record.time("threads_1e3", name, seconds)
