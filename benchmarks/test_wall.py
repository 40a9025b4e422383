"""4. The wall interaction for many particles against copying its inputs."""

import numpy as np

KEY = "wall_vs_copy"


def _inputs(n):
    rng = np.random.default_rng(3)
    vel = rng.normal(0.0, 5.0, (n, 3))
    vel[:, 2] = -rng.uniform(1.0, 120.0, n)  # towards the wall
    normal = np.broadcast_to([0.0, 0.0, 1.0], (n, 3)).copy()
    return vel, normal, rng.uniform(1e-6, 20e-6, n), rng.uniform(1000.0, 3000.0, n)


def test_copy(timed, size):
    inputs = _inputs(size["wall"])
    bufs = [np.empty_like(x) for x in inputs]

    def copy():
        for b, x in zip(bufs, inputs):
            np.copyto(b, x)

    timed(KEY, "copy", copy, rounds=7)


def test_wall_interaction(timed, size):
    from microimpact.coupling import wall_interaction

    vel, normal, d, rho = _inputs(size["wall"])
    out = timed(
        KEY,
        "wall_interaction (friction 0.3, no adhesion)",
        lambda: wall_interaction(vel, normal, d, rho, effective_modulus=1.31e9, limiting_pressure=156e6, friction=0.3),
        rounds=3,
    )
    assert np.all(out.velocity[:, 2] >= 0.0)  # every particle leaves the wall
