"""14. The fixed cost of one array call on 10^3 speeds: ``pair.restitution(V)`` and
``pair.impact(V, warn=False)`` against the compiled loop alone on the same speeds (numba's serial
loop called directly into a preallocated array: the floor of a compiled call). The difference is
what the call adds around the loop's own work: checking the speeds, choosing and calling the loop,
building the result. The calls are timed in a script's steady state (the loop compiled or loaded
before), each one beside its loop round by round (interleaved: the difference is of two times taken
under the same load), best round of each."""

import time

import numpy as np

KEY = "small_arrays"
N = 1000


def _loops(pair):
    from microimpact.core.models import thornton_ning_2016 as seed
    from microimpact.engine import loops

    V = np.linspace(1.0, 120.0, N)
    pair.impact(V, warn=False)
    for _ in range(300):  # a script's steady state
        pair.restitution(V)
    E, R, m, p = (float(x) for x in pair._args)
    e_loop, _ = loops.loops(seed.restitution_at, "as", 1, False)
    o_loop, _ = loops.loops(seed.outcome, "assss", 18, True)
    e_out, o_out = np.empty((1, N)), np.empty((18, N))
    e_args, o_args = (V, pair.yield_velocity, e_out), (V, E, R, m, p, (), o_out)
    e_loop.prepare(e_args)  # compiled (or loaded) before it is timed
    o_loop.prepare(o_args)
    return (
        V,
        lambda: e_loop.run(N, *e_args),
        lambda: o_loop.run(N, *o_args),
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
    V, e_loop, _ = _loops(pair)
    variants = {"restitution loop alone": e_loop, "pair.restitution(V)": lambda: pair.restitution(V)}
    _interleaved(record, variants, rounds=60, iterations=200)


def test_impact_call(record, pair):
    V, _, o_loop = _loops(pair)
    variants = {"outcome loop alone": o_loop, "pair.impact(V, warn=False)": lambda: pair.impact(V, warn=False)}
    _interleaved(record, variants, rounds=30, iterations=50)
