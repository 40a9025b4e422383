"""PROVISIONAL stand-in for the seed's model file (the lead replaces it with the core's own).

Wraps :func:`microimpact._kernels.impact_scalar` (seed eqs. 5-33) so that the other model files,
:mod:`microimpact.calibrate` and their tests can be written against the model contract before
the core's version of the seed exists. Not ``@jitable`` (it calls scipy's ``betainc``).
"""

from __future__ import annotations

import math

from ..quantities import OUTCOME_FIELDS

NAME = "thornton_ning_2016"
TITLE = "Seed: Hertz, Thornton-Ning plastic loading, Hertz unloading with R_p (Aerosol Sci. Tech. 50(4), 2016)"
PARAMETERS = ()
DEFAULTS = ()


def validate(params):
    """The seed takes no parameters of its own."""
    if len(params):
        raise ValueError(f"params must be empty for {NAME}, got {params!r}")
    return ()


def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact, in OUTCOME_FIELDS order (flags as 1.0/0.0)."""
    from ..._kernels import impact_scalar

    d = impact_scalar(V, E, R, m, p_y)
    return tuple(float(d[k]) for k in OUTCOME_FIELDS)


def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Seed force law (eqs. 2, 8, 10) [N]; negative below the plastic approach on unloading."""
    a_y = (math.pi * p_y / (2.0 * E)) ** 2 * R
    p_y_force = 4.0 / 3.0 * E * math.sqrt(R) * a_y**1.5

    def loading(a):
        if a <= a_y:
            return 4.0 / 3.0 * E * math.sqrt(R) * max(a, 0.0) ** 1.5
        return p_y_force + math.pi * p_y * R * (a - a_y)

    amax = max(alpha, alpha_max)
    if alpha >= amax or amax <= a_y:
        return loading(alpha)
    p_star = loading(amax)
    f_e = 4.0 / 3.0 * E * math.sqrt(R) * amax**1.5
    r_p = R * f_e / p_star
    a_p = amax * (1.0 - p_star / f_e)
    d = alpha - a_p
    return 4.0 / 3.0 * E * math.sqrt(r_p) * d**1.5 if d > 0.0 else -1e-300 * (1.0 - d)


def ends_at_zero_force(params):
    """The particle leaves where the unloading force vanishes (at the plastic approach)."""
    return True


def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Seed force law [N], never negative."""
    return max(signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params), 0.0)
