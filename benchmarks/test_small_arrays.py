"""14. The fixed cost of one array call on 10^3 speeds: ``pair.restitution(V)`` and
``pair.impact(V, warn=False)`` against the compiled loop alone on the same speeds (the serial
loop the library runs there, called directly into a preallocated array). The difference is what
the call adds around its loop: checking the speeds, choosing and calling the loop, building the
result."""

import numpy as np

KEY = "small_arrays"
N = 1000


def _loops(pair):
    from microimpact.core import arrays
    from microimpact.core.models import thornton_ning_2016 as seed

    V = np.linspace(1.0, 120.0, N)
    pair.impact(V, warn=False)
    pair.restitution(V)
    E, R, m, p = (float(x) for x in pair._args)
    e_loop, _ = arrays._kernels(seed.restitution_at, "as", 1, False)
    o_loop, _ = arrays._kernels(seed.outcome, "assss", 18, True)
    e_out, o_out = np.empty((1, N)), np.empty((18, N))
    return (
        V,
        lambda: e_loop(N, V, pair.yield_velocity, (), e_out),
        lambda: o_loop(N, V, E, R, m, p, (), o_out),
    )


def test_restitution_loop_alone(timed, pair):
    _, e_loop, _ = _loops(pair)
    timed(KEY, "restitution loop alone", e_loop, rounds=20, iterations=50)


def test_restitution_call(timed, pair):
    V, _, _ = _loops(pair)
    timed(KEY, "pair.restitution(V)", lambda: pair.restitution(V), rounds=20, iterations=50)


def test_outcome_loop_alone(timed, pair):
    _, _, o_loop = _loops(pair)
    timed(KEY, "outcome loop alone", o_loop, rounds=20, iterations=20)


def test_impact_call(timed, pair):
    V, _, _ = _loops(pair)
    timed(KEY, "pair.impact(V, warn=False)", lambda: pair.impact(V, warn=False), rounds=20, iterations=20)
