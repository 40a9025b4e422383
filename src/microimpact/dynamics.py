"""Contact times of an elastic-plastic impact, in closed form (seed eqs. 20, 23, 26, 30-33).

The seed integrates the times numerically ("no simple expressions are
available"). They exist; the derivation is on the theory page, section
"Contact times in closed form" (:ref:`theory-times`):

* stage 1, Hertz loading to ``alpha_1 = min(alpha_y, alpha_m)``:
  ``t1 = (2/5)(alpha_m/V) B(u; 2/5, 1/2)``, ``u = (alpha_1/alpha_m)^(5/2) = min(1, (V_y/V)^2)``
* stage 2, plastic loading, a harmonic oscillation of angular frequency
  ``omega = (pi p_y R*/m*)^(1/2)`` about ``alpha_y/3``:
  ``t2 = (pi/2 - atan2(2 omega alpha_y / 3, (V^2 - V_y^2)^(1/2))) / omega``
* stage 3, Hertz unloading with ``R_p`` from ``alpha*`` to ``alpha_p``:
  ``t_U = (2/5) B(2/5, 1/2) (alpha* - alpha_p) / V_r``

``B(u; a, b)`` is the incomplete beta function (not regularised).

Time histories of one impact (:func:`impact_history`, :class:`ImpactHistory`)
follow from the same integrals by inverting the incomplete beta function
(stages 1 and 3) and as a sinusoid (stage 2). :func:`integrate_impact`
integrates Newton's equation with the force law of :mod:`microimpact.contact`
numerically: the seed's own route, kept as an independent check.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from . import _history, contact
from ._face import array_function
from ._validation import check_nonnegative, check_pair, check_positive, check_velocity
from .core import hertz, quantities
from .core import models as _models
from .core import special as _special
from .core.arrays import evaluate
from .core.models import thornton_ning_2016 as _seed
from .core.special import BETA_25_12, HERTZ_TIME_CONSTANT
from .impact import elastic_max_approach, impact_outcome, outcome_arrays

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
    "STAGE_NAMES",
    "GENERIC_STAGE_NAMES",
    "stage_names",
    "HISTORY_COLUMNS",
    "HISTORY_SCALARS",
    "impact_history",
    "hertz_force_along",
    "ImpactHistory",
    "integrate_impact",
    "integrate_model",
    "CLOSED_FORM_HISTORY",
]

#: Models whose time history exists in closed form (:func:`impact_history`); the others are
#: integrated numerically (:func:`integrate_model`).
CLOSED_FORM_HISTORY = (_seed.NAME,)


def incomplete_beta(u, a=0.4, b=0.5):
    """Non-regularised incomplete beta function ``B(u; a, b) = I_u(a, b) B(a, b)`` [-].

    With the defaults ``a = 2/5``, ``b = 1/2`` it is the Hertz time integral of
    the stage-1 and stage-3 times (seed eqs. 20, 26).

    Parameters
    ----------
    u : array_like
        Upper limit of the integral, in [0, 1] [-].
    a, b : array_like, optional
        Positive shape parameters [-] (default ``2/5`` and ``1/2``).

    Returns
    -------
    ndarray
        ``B(u; a, b) = int_0^u t^(a-1) (1 - t)^(b-1) dt`` [-].

    Examples
    --------
    >>> bool(np.isclose(incomplete_beta(1.0), BETA_25_12))
    True
    """
    u = check_nonnegative("u", u)
    if np.any(u > 1.0):
        raise ValueError(f"u must lie in [0, 1], got {float(np.max(u))!r}")
    a = check_positive("a", a)
    b = check_positive("b", b)
    return evaluate(_special.incomplete_beta, u, a, b)[0]


hertz_contact_time = array_function(
    globals(),
    "hertz_contact_time",
    hertz.contact_time,
    [
        ("velocity", "velocity"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
        ("effective_mass", "positive"),
    ],
    ("contact_time", "Contact time ``t_c`` of the elastic impact"),
    "Duration of a perfectly elastic Hertz impact, ``(4/5) B(2/5,1/2) alpha_m / V`` [s].",
    notes="""
        Equals ``2.868 (m*^2/(R* E*^2 V))^(1/5)``: the seed's eq. 30 with its exact
        constant :data:`HERTZ_TIME_CONSTANT`. ``inf`` at ``V = 0`` (the limit), 0 at
        ``V = inf``.
    """,
    examples="""
        >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350  # kg, 4.9 um NH4Fl sphere
        >>> round(float(hertz_contact_time(7.6, 1.31e9, 2.45e-6, m)) * 1e6, 5)  # us
        0.03347
    """,
)


def deresiewicz_contact_time(
    velocity, effective_modulus, effective_radius, effective_mass, constant=_special.HERTZ_TIME_CONSTANT_PRINTED
):
    """Deresiewicz's (1968) elastic contact time, ``t_c = 2.87 (m*^2/(R* E*^2 V))^(1/5)`` [s] (seed eq. 30).

    ``constant`` is the seed's printed 2.87 by default; the exact value is
    :data:`HERTZ_TIME_CONSTANT` (2.8683), which makes this :func:`hertz_contact_time`.

    Parameters
    ----------
    velocity : array_like
        Impact speed ``V`` [m/s], >= 0.
    effective_modulus : array_like
        Effective modulus ``E*`` [Pa].
    effective_radius : array_like
        Effective radius ``R*`` [m].
    effective_mass : array_like
        Effective mass ``m*`` [kg].
    constant : float, optional
        Prefactor [-]; default 2.87, as printed in the seed.

    Returns
    -------
    ndarray
        Elastic contact time ``t_c`` [s].

    Raises
    ------
    ValueError
        If ``velocity`` is negative or a pair property is not positive.

    Examples
    --------
    >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350  # kg, 4.9 um NH4Fl sphere
    >>> round(float(deresiewicz_contact_time(7.6, 1.31e9, 2.45e-6, m)) * 1e6, 5)  # us; seed: 0.03348
    0.03349
    """
    V = check_velocity("velocity", velocity)
    E, R, m, _ = check_pair(effective_modulus, effective_radius, effective_mass, 1.0)
    with np.errstate(divide="ignore", over="ignore"):  # huge V: the time tends to 0
        return constant * (m**2 / (R * E**2 * V)) ** 0.2


plastic_frequency = array_function(
    globals(),
    "plastic_frequency",
    _seed.plastic_frequency,
    [("limiting_pressure", "positive_or_inf"), ("effective_radius", "positive"), ("effective_mass", "positive")],
    ("plastic_frequency", "Angular frequency ``omega``"),
    "Angular frequency of the plastic stage, ``omega = (pi p_y R*/m*)^(1/2)`` [rad/s].",
    notes="""
        The plastic loading force (seed eq. 8) is linear in the approach with
        stiffness ``pi p_y R*``, so stage 2 is a harmonic oscillation (eqs. 18-23).
    """,
)


ning_loading_time = array_function(
    globals(),
    "ning_loading_time",
    _seed.ning_loading_time,
    [("limiting_pressure", "positive_or_inf"), ("effective_radius", "positive"), ("effective_mass", "positive")],
    ("loading_time", "Loading time ``t_L`` in the limit ``V -> inf``"),
    "Ning's (1995) loading time at high impact speed, ``t_L = (pi/2)(m*/(pi p_y R*))^(1/2)`` [s] (seed eq. 31).",
    notes="""
        The quarter period of the plastic-stage oscillation: the limit of ``t1 + t2`` as ``V -> inf``.
    """,
    examples="""
        >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350  # kg, 4.9 um NH4Fl sphere
        >>> round(float(ning_loading_time(156e6, 2.45e-6, m)) * 1e6, 5)  # us; seed: 0.01307
        0.01307
    """,
)


def elastic_stage_time(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure):
    """Duration ``t1`` of stage 1, Hertz loading up to yield or to rest [s] (seed eq. 20).

    ``(2/5) (alpha_m/V) B(min(1, (V_y/V)^2); 2/5, 1/2)``, with ``alpha_m`` the
    maximum approach of a purely elastic impact.

    Parameters
    ----------
    velocity : array_like
        Impact speed ``V`` [m/s], >= 0.
    effective_modulus : array_like
        Effective modulus ``E*`` [Pa].
    effective_radius : array_like
        Effective radius ``R*`` [m].
    effective_mass : array_like
        Effective mass ``m*`` [kg].
    limiting_pressure : array_like
        Limiting contact pressure ``p_y`` [Pa] (``inf``: elastic impact).

    Returns
    -------
    ndarray
        Stage-1 time ``t1`` [s]; ``inf`` at ``V = 0``, 0 at ``V = inf``.

    Raises
    ------
    ValueError
        If ``velocity`` is negative or a pair property is not positive.

    Examples
    --------
    Below the yield velocity stage 1 is the whole loading, half the Hertz contact time:

    >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350  # kg, 4.9 um NH4Fl sphere
    >>> t1 = elastic_stage_time(5.0, 1.31e9, 2.45e-6, m, 156e6)
    >>> bool(np.isclose(2 * t1, hertz_contact_time(5.0, 1.31e9, 2.45e-6, m)))
    True
    """
    return contact_times(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure)[
        "elastic_stage_time"
    ]


def plastic_stage_time(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure):
    """Duration ``t2`` of stage 2, plastic loading to the maximum approach [s] (seed eq. 23).

    ``(pi/2 - atan2(2 omega alpha_y/3, (V^2 - V_y^2)^(1/2))) / omega``
    ``= atan2((V^2 - V_y^2)^(1/2), 2 omega alpha_y/3) / omega``; 0 for ``V <= V_y``;
    tends to Ning's loading time (eq. 31) as ``V -> inf``.

    Parameters
    ----------
    velocity : array_like
        Impact speed ``V`` [m/s], >= 0.
    effective_modulus : array_like
        Effective modulus ``E*`` [Pa].
    effective_radius : array_like
        Effective radius ``R*`` [m].
    effective_mass : array_like
        Effective mass ``m*`` [kg].
    limiting_pressure : array_like
        Limiting contact pressure ``p_y`` [Pa] (``inf``: elastic impact).

    Returns
    -------
    ndarray
        Stage-2 time ``t2`` [s].

    Raises
    ------
    ValueError
        If ``velocity`` is negative or a pair property is not positive.

    Examples
    --------
    >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350  # kg, 4.9 um NH4Fl sphere
    >>> float(plastic_stage_time(5.0, 1.31e9, 2.45e-6, m, 156e6))  # elastic impact
    0.0
    >>> round(float(plastic_stage_time(20.0, 1.31e9, 2.45e-6, m, 156e6)) * 1e6, 5)  # us
    0.01012
    """
    return contact_times(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure)[
        "plastic_stage_time"
    ]


def unloading_time(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure):
    """Duration ``t_U`` of stage 3, elastic unloading from ``alpha*`` to ``alpha_p`` [s] (seed eq. 26).

    ``(2/5) B(2/5, 1/2) (alpha* - alpha_p) / V_r``; equals the loading time for ``V <= V_y``.

    Parameters
    ----------
    velocity : array_like
        Impact speed ``V`` [m/s], >= 0.
    effective_modulus : array_like
        Effective modulus ``E*`` [Pa].
    effective_radius : array_like
        Effective radius ``R*`` [m].
    effective_mass : array_like
        Effective mass ``m*`` [kg].
    limiting_pressure : array_like
        Limiting contact pressure ``p_y`` [Pa] (``inf``: elastic impact).

    Returns
    -------
    ndarray
        Unloading time ``t_U`` [s]; 0 at ``V = inf``.

    Raises
    ------
    ValueError
        If ``velocity`` is negative or a pair property is not positive.
    """
    return contact_times(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure)[
        "unloading_time"
    ]


def contact_times(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure, outcome=None):
    """All contact times of an impact, in closed form (seed eqs. 20, 23, 26, 32, 33) [s].

    Parameters
    ----------
    velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure : array_like
        As for :func:`microimpact.impact.impact_outcome`; they broadcast.
    outcome : dict, optional
        The result of :func:`~microimpact.impact.impact_outcome` for the same inputs,
        to avoid computing it again (its velocity and yield velocity are reused, and the
        inputs, which it checked, are not checked again).

    Returns
    -------
    dict of ndarray
        ``elastic_stage_time`` ``t1``, ``plastic_stage_time`` ``t2``,
        ``loading_time`` ``t_L = t1 + t2`` (eq. 32), ``unloading_time`` ``t_U``,
        ``contact_time`` ``t_c = t_L + t_U`` (eq. 33). At ``V = 0`` every time
        is ``inf`` (the elastic limit ``t ~ V^(-1/5)``); at ``V = inf``,
        ``t1 = t_U = 0`` and ``t2`` is Ning's time (eq. 31).
    """
    if outcome is None or "contact_time" not in outcome:
        V = check_velocity("velocity", velocity)
        E, R, m, p_y = check_pair(effective_modulus, effective_radius, effective_mass, limiting_pressure)
        outcome = outcome_arrays(_seed, V, E, R, m, p_y, ())
    return {name: outcome[name] for name in TIME_FIELDS}


#: The contact times of an impact (seed eqs. 20, 23, 32, 26, 33), in the order of the outcome.
TIME_FIELDS = ("elastic_stage_time", "plastic_stage_time", "loading_time", "unloading_time", "contact_time")


#: Stage codes of a history.
STAGE_NAMES = {
    0: "no contact (free flight before first contact or after separation)",
    1: "Hertz loading (eq. 2)",
    2: "plastic loading (eq. 8)",
    3: "elastic unloading (eq. 10)",
}
#: Stage codes of a history of any other model (loading to the maximum approach, then unloading).
GENERIC_STAGE_NAMES = {0: STAGE_NAMES[0], 1: "loading", 3: "unloading"}


def stage_names(model=None) -> dict:
    """``{stage code: name}`` of a history of ``model`` (a name; default the seed's): code 0, no
    contact, and the model's own ``STAGES`` (:mod:`microimpact.core.models`)."""
    from .core import models as _models

    return {0: STAGE_NAMES[0], **_models.get(_seed.NAME if model is None else model).STAGES}


def __getattr__(name):
    if name == "SEED_STAGE_MODELS":  # deprecated: each model declares its STAGES
        import warnings

        from .core import models as _models

        warnings.warn(
            "microimpact.dynamics.SEED_STAGE_MODELS is deprecated; use microimpact.dynamics.stage_names(model) "
            "(each model declares its STAGES in microimpact.core.models)",
            DeprecationWarning,
            stacklevel=2,
        )
        return tuple(n for n in _models.available() if _models.get(n).STAGES == _seed.STAGES)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


#: Columns of a history: name -> (unit, description), from the one table of quantities.
HISTORY_COLUMNS: dict[str, tuple[str, str]] = quantities.table(quantities.HISTORY_FIELDS)

#: Scalars of a history: name -> (unit, description), from the one table of quantities.
HISTORY_SCALARS: dict[str, tuple[str, str]] = quantities.table(
    (
        "velocity",
        "rebound_velocity",
        "max_approach",
        "plastic_approach",
        "max_force",
        "elastic_stage_time",
        "plastic_stage_time",
        "loading_time",
        "unloading_time",
        "contact_time",
        "yield_velocity",
        "effective_modulus",
        "effective_radius",
        "effective_mass",
        "limiting_pressure",
    )
)


def _hertz_fraction(x, xc):
    """``u = I^-1_x(2/5, 1/2)`` and ``1 - u``, given ``x`` and its complement ``xc = 1 - x`` (both exact).

    The core's :func:`~microimpact.core.special.incomplete_beta_inverse` (no scipy: importing
    ``scipy.special`` cost more than the rest of ``microimpact history``).
    """
    x = np.clip(x, 0.0, 1.0)
    xc = np.clip(xc, 0.0, 1.0)
    low = x <= 0.5
    u = np.empty_like(x)
    w = np.empty_like(x)
    B = np.asarray(BETA_25_12)
    u[low] = evaluate(_special.incomplete_beta_inverse, x[low], np.asarray(0.4), np.asarray(0.5), B)[0]
    w[low] = 1.0 - u[low]
    w[~low] = evaluate(_special.incomplete_beta_inverse, xc[~low], np.asarray(0.5), np.asarray(0.4), B)[0]
    u[~low] = 1.0 - w[~low]
    return u, w


def impact_history(
    velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure, n=1001, times=None
):
    """Time history of one impact in closed form: approach, velocity, force and stage (seed eqs. 17-26).

    Stages 1 (Hertz loading) and 3 (elastic unloading) follow by inverting the
    incomplete beta function of the contact-time integrals (eqs. 20, 26), stage 2
    (plastic loading, eq. 8) is a sinusoid about ``alpha_y/3`` (eqs. 21-23). An
    elastic impact (``V <= V_y``, or ``p_y = inf``: the seed's "equivalent elastic
    impact") has stages 1 and 3 only, symmetric about ``t_L``.

    Parameters
    ----------
    velocity : float
        Impact speed ``V`` [m/s], positive and finite.
    effective_modulus, effective_radius, effective_mass, limiting_pressure : float
        ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], ``p_y`` [Pa] (``inf`` allowed).
    n : int, optional
        Number of points spaced uniformly on ``[0, t_c]``; the stage boundaries
        ``t1`` and ``t_L`` are added to them (so the grid may hold ``n + 2`` points).
    times : array_like, optional
        Times [s] since first contact at which to evaluate instead (any order).
        Outside ``[0, t_c]`` the bodies are apart (stage 0, force 0): the approach is
        ``V t`` (negative, a gap) before contact and ``alpha_p - V_r (t - t_c)`` after
        separation, the velocity ``V`` and ``-V_r``.

    Returns
    -------
    dict
        Arrays ``time`` [s], ``approach`` ``alpha`` [m], ``approach_velocity``
        ``dalpha/dt`` [m/s] (``+V`` at first contact, ``-V_r`` at separation),
        ``force`` ``P`` [N], ``stage`` (int: 0 no contact, 1 Hertz loading, 2 plastic
        loading, 3 elastic unloading; a boundary time belongs to the stage it ends),
        and the scalars of :data:`HISTORY_SCALARS` (``rebound_velocity``,
        ``max_approach``, ``max_force``, ``loading_time``, ``contact_time``, ...).
        :class:`ImpactHistory` takes it as keyword arguments.

    Examples
    --------
    >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350
    >>> h = impact_history(50.0, 1.31e9, 2.45e-6, m, 156e6, n=5)
    >>> h["stage"].tolist()
    [1, 1, 2, 2, 2, 3, 3]
    >>> round(float(h["approach_velocity"][-1]), 2)  # -V_r; seed: 36.31
    -36.24
    """
    V, E, R, m, p_y = _history.scalar_pair(
        velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure
    )
    outcome = impact_outcome(V, E, R, m, p_y)
    out = {k: float(np.asarray(v)) for k, v in outcome.items()}
    tm = contact_times(V, E, R, m, p_y, outcome=outcome)
    t1, t2, t_L, t_U, t_c = (
        float(tm[k])
        for k in ("elastic_stage_time", "plastic_stage_time", "loading_time", "unloading_time", "contact_time")
    )
    elastic = bool(out["elastic"])
    a_star, a_p, P_star, V_r = out["max_approach"], out["plastic_approach"], out["max_force"], out["rebound_velocity"]
    alpha_m = float(elastic_max_approach(V, E, R, m))
    T_m = hertz.rise_time(alpha_m, V)  # time of a purely elastic impact to reach alpha_m

    t = _history.time_grid(n, times, (t1, t_L), t_c)
    stage = _history.stage_of(t, t1, t_L, t_c)
    approach, vel = _history.free_flight(t, V, t_c, a_p, V_r)
    force = np.zeros_like(t)

    # Stage 1: Hertz loading (eqs. 2, 17, 20).
    s1 = stage == 1
    if elastic:  # x reaches 1 at t_L = T_m
        u, w = _hertz_fraction(t[s1] / T_m, (t_L - t[s1]) / T_m)
    else:
        u, w = _hertz_fraction(t[s1] / T_m, 1.0 - t[s1] / T_m)
    approach[s1] = alpha_m * u**0.4
    vel[s1] = V * np.sqrt(w)
    force[s1] = hertz.force(alpha_m, E, R) * u**0.6  # P = P_m (alpha/alpha_m)^(3/2)

    # Stage 2: plastic loading, harmonic about alpha_y/3 (eqs. 8, 18-23).
    s2 = stage == 2
    if np.any(s2):
        omega = float(plastic_frequency(p_y, R, m))
        a_y = float(contact.yield_approach(p_y, E, R))
        amp = a_star - a_y / 3.0
        phase = omega * (t_L - t[s2])
        approach[s2] = a_y / 3.0 + amp * np.cos(phase)
        vel[s2] = amp * omega * np.sin(phase)
        force[s2] = np.pi * p_y * R * amp * np.cos(phase)

    # Stage 3: elastic unloading, the time reverse of a Hertz impact at V_r (eqs. 10, 24-26).
    s3 = stage == 3
    u, w = _hertz_fraction((t_c - t[s3]) / t_U, (t[s3] - t_L) / t_U)
    approach[s3] = a_p + (a_star - a_p) * u**0.4
    vel[s3] = -V_r * np.sqrt(w)
    force[s3] = P_star * u**0.6

    return {
        "time": t,
        "approach": approach,
        "approach_velocity": vel,
        "force": force,
        "stage": stage,
        "velocity": V,
        "rebound_velocity": V_r,
        "max_approach": a_star,
        "plastic_approach": a_p,
        "max_force": P_star,
        "elastic_stage_time": t1,
        "plastic_stage_time": t2,
        "loading_time": t_L,
        "unloading_time": t_U,
        "contact_time": t_c,
        "yield_velocity": out["yield_velocity"],
        "effective_modulus": E,
        "effective_radius": R,
        "effective_mass": m,
        "limiting_pressure": p_y,
    }


def hertz_force_along(history, loading_only=True):
    """Hertz force ``4/3 E* R*^(1/2) alpha^(3/2)`` evaluated along an elastic-plastic history [N] (eq. 2).

    The seed's Fig. 7 "equivalent Hertz force during the loading process": the
    force the same approach would need if the contact stayed elastic. It exceeds
    the actual force once the contact yields (``t > t1``).

    Parameters
    ----------
    history : ImpactHistory or dict
        From :func:`impact_history`, :func:`integrate_impact` or :meth:`ContactPair.history`.
    loading_only : bool
        If True (default), NaN outside the loading stages 1 and 2.

    Returns
    -------
    ndarray
        Force [N] at each time of the history.
    """
    get = history.get if isinstance(history, dict) else (lambda k: getattr(history, k))
    alpha = np.maximum(np.asarray(get("approach"), dtype=float), 0.0)
    F = 4.0 / 3.0 * get("effective_modulus") * np.sqrt(get("effective_radius")) * alpha**1.5
    if loading_only:
        stage = np.asarray(get("stage"))
        F = np.where((stage == 1) | (stage == 2), F, np.nan)
    return F


# ============================================================================ the history object


@dataclass(frozen=True, eq=False)
class ImpactHistory:
    """Time history of one impact: what :meth:`ContactPair.history` returns.

    Attributes
    ----------
    time : ndarray
        Time since first contact [s].
    approach : ndarray
        Approach ``alpha`` [m] (negative outside the contact: a gap).
    approach_velocity : ndarray
        ``dalpha/dt`` [m/s]: ``+V`` at first contact, 0 at the maximum approach,
        ``-V_r`` at separation.
    force : ndarray
        Contact force ``P`` [N].
    stage : ndarray of int
        0 no contact, 1 Hertz loading, 2 plastic loading, 3 elastic unloading.
    velocity, rebound_velocity : float
        Impact speed ``V`` and rebound speed ``V_r`` [m/s].
    max_approach, plastic_approach : float
        ``alpha*`` and ``alpha_p`` [m].
    max_force : float
        ``P*`` [N].
    elastic_stage_time, plastic_stage_time, loading_time, unloading_time, contact_time : float
        ``t1, t2, t_L, t_U, t_c`` [s].
    yield_velocity : float
        ``V_y`` [m/s].
    effective_modulus, effective_radius, effective_mass, limiting_pressure : float
        The pair [Pa, m, kg, Pa].
    method : str
        ``"closed"`` (closed form) or ``"ode"`` (numerical integration).
    model : str
        Name of the impact model (:func:`microimpact.models.available`); for a model other than
        the seed's, ``stage`` is 1 while loading and 3 while unloading, and
        ``elastic_stage_time``, ``plastic_stage_time``, ``yield_velocity`` are those of the
        model's outcome (NaN where it does not define them).
    """

    time: np.ndarray
    approach: np.ndarray
    approach_velocity: np.ndarray
    force: np.ndarray
    stage: np.ndarray
    velocity: float
    rebound_velocity: float
    max_approach: float
    plastic_approach: float
    max_force: float
    elastic_stage_time: float
    plastic_stage_time: float
    loading_time: float
    unloading_time: float
    contact_time: float
    yield_velocity: float
    effective_modulus: float
    effective_radius: float
    effective_mass: float
    limiting_pressure: float
    method: str = "closed"
    model: str = _seed.NAME

    def __post_init__(self):
        for name in HISTORY_COLUMNS:
            arr = np.array(getattr(self, name), dtype=np.int8 if name == "stage" else float)
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        for name in HISTORY_SCALARS:
            object.__setattr__(self, name, float(getattr(self, name)))

    @classmethod
    def from_dict(cls, data: dict, method: str = "closed") -> ImpactHistory:
        """Build from the dict of :func:`impact_history` or :func:`integrate_impact` (extra keys ignored)."""
        keys = [f.name for f in fields(cls) if f.name not in ("method", "model")]
        return cls(**{k: data[k] for k in keys}, method=data.get("method", method), model=data.get("model", _seed.NAME))

    def __len__(self):
        return int(self.time.size)

    def to_dict(self) -> dict:
        """All arrays and scalars as a dict."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def hertz_force(self):
        """Hertz force along the loading stages, the seed's Fig. 7 comparison [N]: :func:`hertz_force_along`."""
        return hertz_force_along(self)

    def to_csv(self, path_or_buffer, *, progress=False) -> None:
        """Write the history as CSV: a header row with units, ``#`` lines with the scalars, then the rows.

        ``path_or_buffer`` is a file name (written through a temporary file renamed into
        place when complete, :func:`microimpact.io.write_csv`) or an open text file. The
        first line names the columns with their units (``time [s],approach [m],...``);
        the ``#`` lines that follow give the impact's scalars (``# name = value unit``);
        floats are written in their shortest exact form. Read it back with
        ``numpy.genfromtxt(f, delimiter=",", names=True)``, ``numpy.loadtxt(f,
        delimiter=",", skiprows=1)`` or ``pandas.read_csv(f, comment="#")``.
        ``progress=True`` shows a progress bar while the rows are written.
        """
        from .io import write_csv

        if self.model == _seed.NAME:
            comments = [f"microimpact impact history ({self.method}; seed eqs. 17-26)"]
        else:
            comments = [
                f"microimpact impact history ({self.method}; model {self.model}; each quantity as this model "
                "defines it, nan where it defines none; equation numbers are the seed's)"
            ]
        for name, (unit, desc) in HISTORY_SCALARS.items():
            comments.append(f"{name} = {getattr(self, name):.17g} {unit}  ({desc})")
        stages = stage_names(self.model)
        comments.append("stage: " + "; ".join(f"{k} = {v}" for k, v in stages.items()))
        columns = [(name, unit, getattr(self, name)) for name, (unit, _) in HISTORY_COLUMNS.items()]
        stage = columns[-1]
        columns[-1] = (stage[0], stage[1], np.asarray(stage[2]).astype(np.int64))
        write_csv(path_or_buffer, columns, comments, progress=progress)


# ============================================================================ Newton's equation, numerically


def integrate_impact(
    velocity,
    effective_modulus,
    effective_radius,
    effective_mass,
    limiting_pressure,
    *,
    rtol=1e-12,
    atol=1e-17,
    method="DOP853",
    n=None,
    times=None,
):
    """One impact by integrating Newton's equation ``m* d2alpha/dt2 = -P`` numerically (seed eqs. 16-26).

    The independent check of the closed forms (:func:`contact_times`,
    :func:`impact_history`), following the seed's own route: :func:`integrate_model` applied to
    the seed's model (the one integrator, :mod:`microimpact.core.models.thornton_ning_2016`). The
    force is its history-dependent law: Hertz (eq. 2) up to the yield approach, plastic loading
    (eq. 8) up to the maximum approach, then elastic unloading (eq. 10) with ``R_p`` (eq. 9) and
    ``alpha_p`` (eq. 11) fixed by the maximum approach the integration reached.
    :func:`scipy.integrate.solve_ivp` locates, with terminal events, the yield (``alpha =
    alpha_y``, the model's ``stage_two_approach``), the maximum approach (``dalpha/dt = 0``) and
    the separation (``alpha = alpha_p``, its ``separation_approach_after``).

    The equation is integrated in scaled variables (time in units of the loading time of a first,
    loose run, length in units of ``V`` times that), so that the tolerances act on numbers of
    order one.

    Parameters
    ----------
    velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure : float
        ``V`` [m/s] (positive, finite), ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], ``p_y`` [Pa].
    rtol, atol : float
        Tolerances of the solver (``atol`` on the scaled variables; 1e-17 as for
        :func:`integrate_model`, whose integrator this is: with 1e-14 the scaled state near the
        first contact, where the force grows as ``alpha^(3/2)``, is controlled too loosely and
        the rebound speed is 1e-10 off the closed form instead of 1e-11).
    method : str
        A :func:`~scipy.integrate.solve_ivp` method; ``"DOP853"`` (default) or ``"Radau"``.
    n, times : optional
        If either is given, also return the history on that grid, as :func:`impact_history`.

    Returns
    -------
    dict
        The scalars of :data:`HISTORY_SCALARS` (``elastic_stage_time``,
        ``plastic_stage_time``, ``loading_time``, ``unloading_time``, ``contact_time``
        [s], ``max_approach``, ``plastic_approach`` [m], ``max_force`` [N],
        ``rebound_velocity`` [m/s], ...), ``nfev`` (right-hand-side evaluations of the
        precise run), ``method`` = ``"ode"``, and with ``n`` or ``times`` the arrays ``time``,
        ``approach``, ``approach_velocity``, ``force``, ``stage``.
    """
    V, E, R, m, p_y = _history.scalar_pair(
        velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure
    )
    out = _history.integrate(
        _models.get(_seed.NAME), (), V, E, R, m, p_y, rtol=rtol, atol=atol, method=method, n=n, times=times
    )
    del out["model"]  # the seed's: this function's result has always been the seed's alone
    return out


def integrate_model(
    model,
    velocity,
    effective_modulus,
    effective_radius,
    effective_mass,
    limiting_pressure,
    params=None,
    *,
    rtol=1e-12,
    atol=1e-17,
    method="DOP853",
    n=None,
    times=None,
):
    """One impact of any model by integrating Newton's equation with the model's own force law.

    ``m* d2alpha/dt2 = -P(alpha, dalpha/dt, alpha_max)``, ``alpha(0) = 0``, ``dalpha/dt(0) = V``,
    with ``P`` the model file's ``force`` (:mod:`microimpact.core.models`). The loading ends at the
    maximum approach (``dalpha/dt = 0``, located by a terminal event of
    :func:`scipy.integrate.solve_ivp`), from where ``alpha_max`` is frozen; the contact ends where
    the approach falls to the model's ``separation_approach`` (0 unless the model defines one) or,
    when ``ends_at_zero_force(params)``, where its ``signed_force`` vanishes, whichever comes first;
    a model that declares ``stage_two_approach`` (the seed: its yield approach) has its loading
    split there into stages 1 and 2. The equation is scaled by the loading time of a first, loose
    run, so that the tolerances act on numbers of order one. The one integrator (also behind
    :func:`integrate_impact`). It is the independent check of
    every model's closed form (:meth:`ContactPair.impact <microimpact.pair.ContactPair.impact>`).

    Parameters
    ----------
    model : str
        Name of the model (:func:`microimpact.models.available`).
    velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure : float
        ``V`` [m/s] (positive, finite), ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], ``p_y`` [Pa].
    params : dict or tuple, optional
        The model's parameters by name (defaults filled in) or as its tuple.
    rtol, atol : float
        Tolerances of the solver (``atol`` on the scaled variables; 1e-17, not 1e-14, so that a
        force that jumps at a small approach, as the fitted laws do at their regime limits, is
        crossed at the right place: at ``E*/Y = 2500`` Kogut-Etsion's maximum approach was 1.3e-7
        off with 1e-14, 5e-12 with 1e-17; the seed's cost is unchanged).
    method : str
        A :func:`~scipy.integrate.solve_ivp` method; ``"DOP853"`` (default) or ``"Radau"``.
    n, times : optional
        If either is given, also return the history on that grid, as :func:`impact_history`.

    Returns
    -------
    dict
        The scalars of :data:`HISTORY_SCALARS` (``rebound_velocity`` [m/s], ``max_approach``,
        ``plastic_approach`` (the approach where the contact ends) [m], ``max_force`` [N],
        ``loading_time``, ``unloading_time``, ``contact_time`` [s]; ``elastic_stage_time``,
        ``plastic_stage_time`` and ``yield_velocity`` from the model's outcome, NaN where it
        does not define them), ``model``, ``method`` = ``"ode"``, ``nfev``, and with ``n`` or
        ``times`` the arrays ``time``, ``approach``, ``approach_velocity``, ``force`` and
        ``stage`` (1 loading, 2 the second loading stage where the model has one, 3 unloading,
        0 apart). ``elastic_stage_time`` and ``plastic_stage_time`` are the integration's own
        where the model declares ``stage_two_approach``.

    Raises
    ------
    ValueError
        Bad inputs or parameters (named), or a particle that does not leave the surface (an
        adhesive or strongly damped model below its sticking speed: ``e = 0``, no finite history).

    Examples
    --------
    >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350
    >>> r = integrate_model("liggghts_thornton_ning", 50.0, 1.31e9, 2.45e-6, m, 156e6)
    >>> round(r["rebound_velocity"] / 50.0, 4)  # the model's closed form: 0.6905
    0.6905
    """
    mod, p = _history.model_and_params(model, params)
    V, E, R, m, p_y = _history.scalar_pair(
        velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure
    )
    return _history.integrate(mod, p, V, E, R, m, p_y, rtol=rtol, atol=atol, method=method, n=n, times=times)
