"""1. Outcome and contact times in closed form against Newton's equation integrated numerically."""

import numpy as np

KEY = "outcome_vs_ode"
ODE_KEYS = (
    "elastic_stage_time",
    "plastic_stage_time",
    "loading_time",
    "unloading_time",
    "contact_time",
    "max_approach",
    "plastic_approach",
    "max_force",
    "rebound_velocity",
)


def rel_diff(a, b):
    """Largest ``|a - b| / |b|`` over finite ``b`` (0 where both are equal)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(a == b, 0.0, np.abs(a - b) / np.abs(b))
    r = r[np.isfinite(r)]
    return float(r.max()) if r.size else 0.0


def test_closed_form(timed, record, size, pair):
    n = size["outcome"]
    speeds = np.random.default_rng(0).uniform(0.05, 16.0, n) * pair.yield_velocity  # 0.4-120 m/s
    timed(KEY, "closed", lambda: pair.impact(speeds, warn=False), rounds=3)
    record.time(KEY, "closed_per_impact", record.times[KEY].pop("closed") / n)
    record.metric(KEY, "n", n)


def test_ode(timed, record, size, pair):
    from microimpact.dynamics import integrate_impact

    n = size["ode"]
    rng = np.random.default_rng(1)
    # from just above V_y to 50 V_y (log-uniform): all three stages occur
    sample = pair.yield_velocity * np.exp(rng.uniform(np.log(1.01), np.log(50.0), n))
    args = (pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure)
    integrate_impact(2.0 * pair.yield_velocity, *args)  # first call (lazy imports) outside the timing
    runs = timed(KEY, "ode", lambda: [integrate_impact(float(V), *args) for V in sample], rounds=1, warmup_rounds=0)
    record.time(KEY, "ode_per_impact", record.times[KEY].pop("ode") / n)
    closed = pair.impact(sample, warn=False)
    diffs = {k: rel_diff([r[k] for r in runs], getattr(closed, k)) for k in ODE_KEYS}
    worst = max(diffs, key=diffs.get)
    record.metric(KEY, "n_ode", n)
    record.metric(KEY, "rel_diff", diffs)
    record.metric(KEY, "max_rel_diff", diffs[worst])
    record.metric(KEY, "worst_quantity", worst)
    assert diffs[worst] < 1e-8, diffs
