"""Contact times of an elastic-plastic impact, in closed form (seed eqs. 20, 23, 26, 30-33).

The seed integrates the times numerically ("no simple expressions are
available"). They exist (THEORY.md §4):

* stage 1, Hertz loading to ``alpha_1 = min(alpha_y, alpha_m)``:
  ``t1 = (2/5)(alpha_m/V) B(u; 2/5, 1/2)``, ``u = (alpha_1/alpha_m)^(5/2) = min(1, (V_y/V)^2)``
* stage 2, plastic loading, a harmonic oscillation of angular frequency
  ``omega = (pi p_y R*/m*)^(1/2)`` about ``alpha_y/3``:
  ``t2 = (pi/2 - atan2(2 omega alpha_y / 3, (V^2 - V_y^2)^(1/2))) / omega``
* stage 3, Hertz unloading with ``R_p`` from ``alpha*`` to ``alpha_p``:
  ``t_U = (2/5) B(2/5, 1/2) (alpha* - alpha_p) / V_r``

``B(u; a, b)`` is the incomplete beta function (not regularised).
"""

from __future__ import annotations

import numpy as np
from scipy import special

from ._validation import check_positive, check_velocity
from .impact import _check_pair, impact_outcome, yield_velocity

__all__ = [
    "BETA_25_12",
    "HERTZ_TIME_CONSTANT",
    "incomplete_beta",
    "hertz_contact_time",
    "deresiewicz_contact_time",
    "ning_loading_time",
    "plastic_frequency",
    "elastic_stage_time",
    "plastic_stage_time",
    "unloading_time",
    "contact_times",
]

#: Complete beta function ``B(2/5, 1/2) = 3.67909...``, the Hertz time integral.
BETA_25_12 = float(special.beta(0.4, 0.5))
#: Exact constant of Hertz's contact time, ``(4/5) B(2/5,1/2) (15/16)^(2/5) = 2.868``
#: (the seed's eq. 30 prints it as 2.87).
HERTZ_TIME_CONSTANT = 0.8 * BETA_25_12 * (15.0 / 16.0) ** 0.4


def incomplete_beta(u, a=0.4, b=0.5):
    """Non-regularised incomplete beta function ``B(u; a, b) = I_u(a, b) B(a, b)``."""
    return special.betainc(a, b, u) * special.beta(a, b)


def _time_scale(velocity, effective_modulus, effective_radius, effective_mass):
    """``alpha_m / V = (15 m*/(16 E* R*^(1/2)))^(2/5) V^(-1/5)`` [s]; ``inf`` at ``V = 0``, 0 at ``inf``."""
    with np.errstate(divide="ignore"):
        return (15.0 * effective_mass / (16.0 * effective_modulus * np.sqrt(effective_radius))) ** 0.4 * (
            velocity ** (-0.2)
        )


def hertz_contact_time(velocity, effective_modulus, effective_radius, effective_mass):
    """Duration of a perfectly elastic Hertz impact, ``(4/5) B(2/5,1/2) alpha_m / V`` [s].

    Equals ``2.868 (m*^2/(R* E*^2 V))^(1/5)``: eq. 30 with its exact constant.
    ``inf`` at ``V = 0`` (the limit), 0 at ``V = inf``.
    """
    V = check_velocity("velocity", velocity)
    E, R, m, _ = _check_pair(effective_modulus, effective_radius, effective_mass, 1.0)
    return 0.8 * BETA_25_12 * _time_scale(V, E, R, m)


def deresiewicz_contact_time(velocity, effective_modulus, effective_radius, effective_mass, constant=2.87):
    """Deresiewicz's (1968) elastic contact time, ``t_c = 2.87 (m*^2/(R* E*^2 V))^(1/5)`` [s] (seed eq. 30).

    ``constant`` is the seed's printed 2.87 by default; the exact value is
    :data:`HERTZ_TIME_CONSTANT` (2.8683), which makes this :func:`hertz_contact_time`.

    Examples
    --------
    >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350
    >>> round(float(deresiewicz_contact_time(7.6, 1.31e9, 2.45e-6, m)) * 1e6, 5)  # us; seed: 0.03348
    0.03349
    """
    V = check_velocity("velocity", velocity)
    E, R, m, _ = _check_pair(effective_modulus, effective_radius, effective_mass, 1.0)
    with np.errstate(divide="ignore"):
        return constant * (m**2 / (R * E**2 * V)) ** 0.2


def plastic_frequency(limiting_pressure, effective_radius, effective_mass):
    """Angular frequency of the plastic stage, ``omega = (pi p_y R*/m*)^(1/2)`` [rad/s].

    The plastic loading force (eq. 8) is linear in the approach with stiffness ``pi p_y R*``.
    """
    p_y = check_positive("limiting_pressure", limiting_pressure, allow_inf=True)
    R = check_positive("effective_radius", effective_radius)
    m = check_positive("effective_mass", effective_mass)
    return np.sqrt(np.pi * p_y * R / m)


def ning_loading_time(limiting_pressure, effective_radius, effective_mass):
    """Ning's (1995) loading time at high impact speed, ``t_L = (pi/2)(m*/(pi p_y R*))^(1/2)`` [s] (seed eq. 31).

    The quarter period of the plastic-stage oscillation: the limit of ``t1 + t2`` as ``V -> inf``.

    Examples
    --------
    >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350
    >>> round(float(ning_loading_time(156e6, 2.45e-6, m)) * 1e6, 5)  # us; seed: 0.01307
    0.01307
    """
    return 0.5 * np.pi / plastic_frequency(limiting_pressure, effective_radius, effective_mass)


def elastic_stage_time(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure):
    """Duration ``t1`` of stage 1, Hertz loading up to yield or to rest (seed eq. 20) [s].

    ``(2/5) (alpha_m/V) B(min(1, (V_y/V)^2); 2/5, 1/2)``.
    """
    V = check_velocity("velocity", velocity)
    E, R, m, p_y = _check_pair(effective_modulus, effective_radius, effective_mass, limiting_pressure)
    Vy = yield_velocity(p_y, E, R, m)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        u = np.where(V > Vy, (Vy / V) ** 2, 1.0)
    t = 0.4 * _time_scale(V, E, R, m) * incomplete_beta(u)
    return np.where(np.isinf(V), 0.0, t)


def plastic_stage_time(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure):
    """Duration ``t2`` of stage 2, plastic loading to the maximum approach (seed eq. 23) [s].

    ``(pi/2 - atan2(2 omega alpha_y/3, (V^2 - V_y^2)^(1/2))) / omega``; 0 for ``V <= V_y``;
    tends to Ning's loading time (eq. 31) as ``V -> inf``.
    """
    V = check_velocity("velocity", velocity)
    E, R, m, p_y = _check_pair(effective_modulus, effective_radius, effective_mass, limiting_pressure)
    Vy = yield_velocity(p_y, E, R, m)
    plastic = V > Vy
    p_fin = np.where(plastic, p_y, 1.0)  # finite wherever it is used
    omega = plastic_frequency(p_fin, R, m)
    a_y = (np.pi * p_fin / (2.0 * E)) ** 2 * R
    with np.errstate(invalid="ignore", over="ignore"):
        v1 = np.sqrt(np.maximum(np.where(plastic, V**2 - Vy**2, 1.0), 0.0))
        t = (0.5 * np.pi - np.arctan2(2.0 * omega * a_y / 3.0, v1)) / omega
    return np.where(plastic, t, 0.0)


def unloading_time(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure):
    """Duration ``t_U`` of stage 3, elastic unloading from ``alpha*`` to ``alpha_p`` (seed eq. 26) [s].

    ``(2/5) B(2/5, 1/2) (alpha* - alpha_p) / V_r``; equals the loading time for ``V <= V_y``.
    """
    out = impact_outcome(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure)
    return _unloading_time_from(out, effective_modulus, effective_radius, effective_mass)


def _unloading_time_from(out, E, R, m):
    V = out["velocity"]
    with np.errstate(invalid="ignore", divide="ignore"):
        t_pl = 0.4 * BETA_25_12 * (out["max_approach"] - out["plastic_approach"]) / out["rebound_velocity"]
        t_el = 0.4 * BETA_25_12 * _time_scale(V, E, R, m)
    t = np.where(out["elastic"], t_el, t_pl)
    return np.where(np.isinf(V), 0.0, t)


def contact_times(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure, outcome=None):
    """All contact times of an impact, in closed form (seed eqs. 20, 23, 26, 32, 33) [s].

    Parameters
    ----------
    velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure : array_like
        As for :func:`microimpact.impact.impact_outcome`; they broadcast.
    outcome : dict, optional
        The result of :func:`~microimpact.impact.impact_outcome` for the same inputs,
        to avoid computing it again.

    Returns
    -------
    dict of ndarray
        ``elastic_stage_time`` ``t1``, ``plastic_stage_time`` ``t2``,
        ``loading_time`` ``t_L = t1 + t2`` (eq. 32), ``unloading_time`` ``t_U``,
        ``contact_time`` ``t_c = t_L + t_U`` (eq. 33). At ``V = 0`` every time
        is ``inf`` (the elastic limit ``t ~ V^(-1/5)``); at ``V = inf``,
        ``t1 = t_U = 0`` and ``t2`` is Ning's time (eq. 31).
    """
    if outcome is None:
        outcome = impact_outcome(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure)
    E = np.asarray(effective_modulus, dtype=float)
    R = np.asarray(effective_radius, dtype=float)
    m = np.asarray(effective_mass, dtype=float)
    t1 = elastic_stage_time(velocity, E, R, m, limiting_pressure)
    t2 = plastic_stage_time(velocity, E, R, m, limiting_pressure)
    tU = _unloading_time_from(outcome, E, R, m)
    tL = t1 + t2
    return {
        "elastic_stage_time": t1,
        "plastic_stage_time": t2,
        "loading_time": tL,
        "unloading_time": tU,
        "contact_time": tL + tU,
    }
