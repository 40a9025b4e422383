"""14. The fixed cost of one array call on 10^3 speeds: ``pair.restitution(V)`` and
``pair.impact(V, warn=False)`` against the compiled loop alone on the same speeds (numba's serial
loop called directly into a preallocated array: the floor of a compiled call). The difference is
what the call adds around the loop's own work: checking the speeds, choosing and calling the loop
(the machine code kept by ``core._native`` where there is some: for one result as a numpy ufunc
once a script has made ``UFUNC_AFTER`` such calls, else through ctypes), building the result. The
calls are timed in that steady state, each one beside its loop round by round (interleaved: the
difference is of two times taken under the same load), best round of each. The kept loop called
directly (through ``NativeLoop``'s general route) is reported beside it."""

import time

import numpy as np

KEY = "small_arrays"
N = 1000


def _loops(pair):
    from microimpact.core import _native, arrays
    from microimpact.core.models import thornton_ning_2016 as seed

    V = np.linspace(1.0, 120.0, N)
    pair.impact(V, warn=False)
    # a script's steady state: past the lane's first calls through ctypes (core._native.UFUNC_AFTER,
    # before it makes the loop's ufunc, which pays back only over thousands of calls)
    for _ in range(_native.UFUNC_AFTER + 300):
        pair.restitution(V)
    E, R, m, p = (float(x) for x in pair._args)
    # numba's own loops, not the library's (which may be the kept machine code, called through ctypes:
    # measured against itself, its call overhead would vanish from the difference)
    e_loop, _ = arrays._numba_loops(seed.restitution_at, "as", 1, False)
    o_loop, _ = arrays._numba_loops(seed.outcome, "assss", 18, True)
    e_kept, _ = arrays._kernels(seed.restitution_at, "as", 1, False)
    e_out, o_out = np.empty((1, N)), np.empty((18, N))
    e_loop(N, V, pair.yield_velocity, (), e_out)  # compiled (or loaded) before it is timed
    o_loop(N, V, E, R, m, p, (), o_out)
    return (
        V,
        lambda: e_loop(N, V, pair.yield_velocity, (), e_out),
        lambda: o_loop(N, V, E, R, m, p, (), o_out),
        lambda: e_kept(N, V, pair.yield_velocity, (), e_out),
    )


def _interleaved(record, variants, rounds, iterations):
    """Time the variants round by round, one after the other in each round (side by side, so that a
    change of the machine's load falls on all of them), and record each one's best round per call."""
    best = dict.fromkeys(variants, float("inf"))
    for _ in range(rounds):
        for name, fn in variants.items():
            t0 = time.perf_counter()
            for _ in range(iterations):
                fn()
            best[name] = min(best[name], (time.perf_counter() - t0) / iterations)
    for name, seconds in best.items():
        record.time(KEY, name, seconds)


def test_restitution_call(record, pair):
    V, e_loop, _, e_kept = _loops(pair)
    variants = {
        "restitution loop alone": e_loop,
        "pair.restitution(V)": lambda: pair.restitution(V),
        "restitution loop the library runs": e_kept,
    }
    _interleaved(record, variants, rounds=60, iterations=200)


def test_impact_call(record, pair):
    V, _, o_loop, _ = _loops(pair)
    variants = {"outcome loop alone": o_loop, "pair.impact(V, warn=False)": lambda: pair.impact(V, warn=False)}
    _interleaved(record, variants, rounds=30, iterations=50)
