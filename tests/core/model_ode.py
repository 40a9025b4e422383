"""Independent check of the model files: Newton's equation with the model's own force law.

``m* alpha'' = -P(alpha, alpha', alpha_max)``, ``alpha(0) = 0``, ``alpha'(0) = V``, integrated with
scipy's DOP853 at tight tolerances; the loading ends at ``alpha' = 0`` (the maximum approach, from
where ``alpha_max`` is frozen), the contact ends at ``alpha = 0`` or, for laws whose force is
clipped at zero, when the force vanishes with the particle moving out.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

RTOL = 1e-13
ATOL_FRACTION = 1e-16


def integrate(model, V, E, R, m, p_y, params):
    """Return ``dict(restitution, max_approach, max_force, loading_time, contact_time, plastic_approach)``.

    The contact ends where ``model.signed_force`` vanishes with the particle moving out (or the
    approach returns to zero, whichever comes first) when ``model.ends_at_zero_force(params)``, and
    only where the approach returns to zero otherwise.
    """
    f = model.force
    g = model.signed_force
    separation = "force" if model.ends_at_zero_force(params) else "overlap"
    # time and length scales for the tolerances: the linear-spring estimate
    scale_t = 1.0
    y0 = [0.0, V]

    def rhs1(t, y):
        a = y[0] if y[0] > 0.0 else 0.0
        return [y[1], -f(a, y[1], a, E, R, m, p_y, params) / m]

    def top(t, y):
        return y[1]

    top.terminal = True
    top.direction = -1
    # a first guess of the loading time from an elastic (Hertz) estimate, generous
    t_end = 1.0
    s1 = solve_ivp(
        rhs1,
        (0.0, t_end),
        y0,
        method="DOP853",
        rtol=RTOL,
        atol=[ATOL_FRACTION * 1e-3, ATOL_FRACTION * V],
        events=top,
        dense_output=True,
    )
    assert s1.status == 1, s1.message
    tL = float(s1.t_events[0][0])
    a_star = float(s1.y_events[0][0][0])
    amax = a_star

    def rhs2(t, y):
        return [y[1], -f(y[0], y[1], amax, E, R, m, p_y, params) / m]

    def zero_overlap(t, y):
        return y[0]

    zero_overlap.terminal = True
    zero_overlap.direction = -1
    events = [zero_overlap]
    if separation == "force":

        def zero_force(t, y):
            return g(y[0], y[1], amax, E, R, m, p_y, params)

        zero_force.terminal = True
        zero_force.direction = -1
        events.append(zero_force)
    s2 = solve_ivp(
        rhs2,
        (tL, tL + 10 * tL + 1e-30),
        [a_star, 0.0],
        method="DOP853",
        rtol=RTOL,
        atol=[ATOL_FRACTION * a_star, ATOL_FRACTION * V],
        events=events,
        dense_output=True,
    )
    assert s2.status == 1, s2.message
    hits = [(float(te[0]), float(ye[0][0]), float(ye[0][1])) for te, ye in zip(s2.t_events, s2.y_events) if len(te)]
    tc, a_end, v_end = min(hits)

    # maximum force along the trajectory (loading and unloading), refined with the dense output
    def neg_force(t):
        if t <= tL:
            a, v = s1.sol(t)
            a = max(a, 0.0)
            return -f(a, v, a, E, R, m, p_y, params)
        a, v = s2.sol(t)
        return -f(a, v, amax, E, R, m, p_y, params)

    ts = np.concatenate([s1.t, s2.t])
    vals = [neg_force(t) for t in ts]
    i = int(np.argmin(vals))
    lo, hi = ts[max(i - 1, 0)], ts[min(i + 1, len(ts) - 1)]
    best = -vals[i]
    if hi > lo:
        r = minimize_scalar(neg_force, bounds=(lo, hi), method="bounded", options={"xatol": 1e-14 * hi})
        best = max(best, -r.fun)
    return {
        "restitution": -v_end / V,
        "max_approach": a_star,
        "max_force": best,
        "loading_time": tL,
        "contact_time": tc,
        "plastic_approach": a_end,
        "scale": scale_t,
    }


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def check_close(out, ref, keys, tol):
    for k in keys:
        assert rel(out[k], ref[k]) < tol, (k, out[k], ref[k], rel(out[k], ref[k]))
    return True


def fields(model, V, E, R, m, p_y, params):
    from microimpact.core.quantities import OUTCOME_FIELDS

    return dict(zip(OUTCOME_FIELDS, model.outcome(V, E, R, m, p_y, params)))


__all__ = ["integrate", "rel", "check_close", "fields", "math"]
