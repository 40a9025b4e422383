"""The seed's face (:mod:`microimpact.core.models.thornton_ning_2016`): every array function of its
formulas, in one room, with its style and its ``e(V)`` through ``V_y`` for fitting.

The public names live on in the modules users know, which re-export them from here:
:mod:`microimpact.contact` (the force laws, seed eqs. 1-15), :mod:`microimpact.impact` (the
closed-form outcome, eqs. 16-29) and :mod:`microimpact.dynamics` (the contact times and the
closed-form history, eqs. 17-26, 30-33). Most are generated from the scalar core function by
:func:`microimpact._face.array_function` (checked, broadcast inputs; parameters and units of the
docstring from :data:`~microimpact.core.quantities.QUANTITIES`) or, for a field of the outcome, by
:func:`microimpact._face.outcome_function`; the few written out here compose core functions
(``contact_force``, ``impact_outcome``, ``contact_times``, the closed-form history) or take
what the generator does not (``restitution_coefficient``'s ``out=``, ``incomplete_beta``'s range
check and defaults, ``energy_loss_fraction``'s range check).
"""

from __future__ import annotations

import math

import numpy as np

from .._face import array_function, free_flight, outcome_arrays, outcome_function, scalar_pair, stage_of, time_grid
from .._validation import check_in_range, check_nonnegative, check_number, check_pair, check_positive, check_velocity
from ..core import hertz
from ..core import special as _special
from ..core.models import thornton_ning_2016 as _seed
from ..core.quantities import OUTCOME_FIELDS
from ..core.special import BETA_25_12
from ..engine import evaluate

#: The face's own names (its contract, :mod:`microimpact.models._base`); the array functions below are
#: public, and documented, as the names of :mod:`microimpact.contact`, :mod:`microimpact.impact` and
#: :mod:`microimpact.dynamics`.
__all__ = ["STYLE", "restitution_of_yield_velocity", "closed_form_history"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#000000", "linestyle": "-", "linewidth": 1.6}


# ============================================================================ force laws (contact)
hertz_force = array_function(
    globals(),
    "hertz_force",
    hertz.force,
    [("alpha", "nonnegative"), ("effective_modulus", "positive"), ("effective_radius", "positive")],
    ("force", "Contact force ``P``"),
    "Hertz normal force ``P = 4/3 E* R*^(1/2) alpha^(3/2)`` [N] (seed eq. 2).",
    examples="""
        >>> float(hertz_force(1e-8, 1.31e9, 2.45e-6))  # doctest: +ELLIPSIS
        2.73...e-06
    """,
)


hertz_contact_radius = array_function(
    globals(),
    "hertz_contact_radius",
    hertz.contact_radius,
    [("alpha", "nonnegative"), ("effective_radius", "positive")],
    ("max_contact_radius", "Contact radius ``a``"),
    "Hertz contact radius ``a = (R* alpha)^(1/2)`` [m] (seed eq. 3).",
    examples="""
        >>> round(float(hertz_contact_radius(1e-8, 2.45e-6)) * 1e9, 1)  # nm
        156.5
    """,
)


hertz_central_pressure = array_function(
    globals(),
    "hertz_central_pressure",
    hertz.central_pressure,
    [("alpha", "nonnegative"), ("effective_modulus", "positive"), ("effective_radius", "positive")],
    ("limiting_pressure", "Central (maximum) contact pressure ``p0``"),
    "Hertz pressure at the contact centre [Pa] (seed eqs. 1, 4).",
    notes="``p0 = 3P/(2 pi a^2) = 2 E* a/(pi R*)`` with ``a = (R* alpha)^(1/2)`` (eq. 3).",
    examples="""
        At the yield approach the central pressure is the limiting pressure ``p_y``:

        >>> a_y = yield_approach(156e6, 1.31e9, 2.45e-6)
        >>> round(float(hertz_central_pressure(a_y, 1.31e9, 2.45e-6)) / 1e6, 6)  # MPa
        156.0
    """,
)


yield_contact_radius = array_function(
    globals(),
    "yield_contact_radius",
    _seed.yield_contact_radius,
    [
        ("limiting_pressure", "positive_or_inf", "``inf``: never yields"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
    ],
    ("max_contact_radius", "Contact radius at yield ``a_y``"),
    "Contact radius at first yield, ``a_y = pi p_y R* / (2 E*)`` [m] (seed eq. 4 with ``p0 = p_y``).",
)


yield_approach = array_function(
    globals(),
    "yield_approach",
    _seed.yield_approach,
    [
        ("limiting_pressure", "positive_or_inf", "``inf``: never yields"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
    ],
    ("approach", "Yield approach ``alpha_y``"),
    "Approach at first yield, ``alpha_y = (pi p_y / (2 E*))^2 R*`` [m] (seed eq. 5).",
    examples="""
        >>> round(float(yield_approach(156e6, 1.31e9, 2.45e-6)) * 1e9, 2)  # nm, silicon case
        85.73
    """,
)


yield_force = array_function(
    globals(),
    "yield_force",
    _seed.yield_force,
    [
        ("limiting_pressure", "positive_or_inf", "``inf``: never yields"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
    ],
    ("force", "Yield force ``P_y``"),
    "Force at first yield, ``P_y = 4/3 E* R*^(1/2) alpha_y^(3/2)`` [N] (seed eq. 7).",
    examples="""
        >>> round(float(yield_force(156e6, 1.31e9, 2.45e-6)) * 1e6, 3)  # uN, silicon case
        68.622
    """,
)


plastic_loading_force = array_function(
    globals(),
    "plastic_loading_force",
    _seed.plastic_loading_force,
    [
        ("alpha", "nonnegative", "meaningful for ``alpha >= alpha_y``"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
        ("limiting_pressure", "positive_or_inf"),
    ],
    ("force", "Contact force ``P`` on the plastic branch"),
    "Plastic loading force ``P = P_y + pi p_y R* (alpha - alpha_y)`` [N] (seed eqs. 6, 8).",
    notes="""
        Thornton & Ning (1998): once the central pressure reaches ``p_y`` the force
        grows linearly with the approach. Valid for ``alpha >= alpha_y``.
    """,
)


loading_force = array_function(
    globals(),
    "loading_force",
    _seed.loading_force,
    [
        ("alpha", "nonnegative"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
        ("limiting_pressure", "positive_or_inf", "``inf``: Hertz throughout"),
    ],
    ("force", "Loading force ``P``: :func:`hertz_force` for ``alpha <= alpha_y``, :func:`plastic_loading_force` above"),
    "Force on the loading path: Hertz up to ``alpha_y``, then plastic [N] (seed eqs. 2, 8).",
    examples="""
        At twice the yield approach the force is ``(3*2 - 1)/2 = 2.5`` yield forces (eq. 14):

        >>> a_y = yield_approach(156e6, 1.31e9, 2.45e-6)
        >>> P_y = yield_force(156e6, 1.31e9, 2.45e-6)
        >>> round(float(loading_force(2 * a_y, 1.31e9, 2.45e-6, 156e6) / P_y), 12)
        2.5
    """,
)


equivalent_elastic_force = array_function(
    globals(),
    "equivalent_elastic_force",
    hertz.force,
    [("max_approach", "nonnegative"), ("effective_modulus", "positive"), ("effective_radius", "positive")],
    ("force", "Equivalent elastic force ``F_e``"),
    "Hertz force at the maximum approach, ``F_e = 4/3 E* R*^(1/2) alpha*^(3/2)`` [N] (seed, after eq. 9).",
    notes="""
        The force the maximum approach would need if the contact had stayed elastic;
        it fixes the unloading radius (eq. 9) and the plastic approach (eq. 11).
    """,
)


unloading_radius = array_function(
    globals(),
    "unloading_radius",
    _seed.unloading_radius,
    [
        ("max_approach", "nonnegative"),
        ("max_force", "nonnegative"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
    ],
    ("unloading_radius", "Unloading radius ``R_p``"),
    "Radius of curvature of the flattened contact, ``R_p = R* F_e / P*`` [m] (seed eq. 9).",
    notes="""
        ``R_p >= R*``: plastic loading flattens the contact. For an elastic impact
        (``P* = F_e``) ``R_p = R*``. Where both forces are zero (no contact), ``R*``.
    """,
)


plastic_approach = array_function(
    globals(),
    "plastic_approach",
    _seed.plastic_approach,
    [
        ("max_approach", "nonnegative"),
        ("max_force", "nonnegative"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
    ],
    ("plastic_approach", "Plastic approach ``alpha_p``, >= 0 (0 for an elastic contact, ``P* = F_e``)"),
    "Plastic (unrecoverable) approach ``alpha_p = alpha* (1 - P*/F_e)`` [m] (seed eq. 11).",
)


unloading_force = array_function(
    globals(),
    "unloading_force",
    _seed.unloading_force,
    [
        ("alpha", "any"),
        ("plastic_approach", "any", "eq. 11, :func:`plastic_approach`"),
        ("unloading_radius", "positive", "eq. 9, :func:`unloading_radius`"),
        ("effective_modulus", "positive"),
    ],
    ("force", "Unloading force ``P``, >= 0"),
    "Elastic unloading force ``P = 4/3 E* R_p^(1/2) (alpha - alpha_p)^(3/2)`` [N] (seed eq. 10).",
    notes="Zero for ``alpha <= alpha_p`` (the bodies have separated).",
)


def contact_force(alpha, effective_modulus, effective_radius, limiting_pressure, max_approach=None):
    """The whole history-dependent force law [N] (seed eqs. 2, 8, 10).

    With ``max_approach=None`` the contact is loading: Hertz below ``alpha_y``,
    plastic above (eqs. 2, 8). With the maximum approach ``alpha*`` reached so
    far, the contact is unloading from ``alpha*``: eq. 10 with ``R_p`` (eq. 9)
    and ``alpha_p`` (eq. 11) fixed by ``alpha*``.

    Parameters
    ----------
    alpha : array_like
        Approach ``alpha`` [m].
    effective_modulus : array_like
        Effective modulus ``E*`` [Pa].
    effective_radius : array_like
        Effective radius ``R*`` [m].
    limiting_pressure : array_like
        Limiting contact pressure ``p_y`` [Pa] (``inf``: elastic throughout).
    max_approach : array_like or None, optional
        Maximum approach ``alpha*`` [m] reached so far when unloading; ``None``
        (default) for the loading path.

    Returns
    -------
    ndarray
        Contact force ``P`` [N].

    Examples
    --------
    Unloading from ``alpha* = 3 alpha_y`` the force vanishes at the plastic approach:

    >>> E, R, p_y = 1.31e9, 2.45e-6, 156e6
    >>> a_m = 3 * yield_approach(p_y, E, R)
    >>> P_m = loading_force(a_m, E, R, p_y)
    >>> a_p = plastic_approach(a_m, P_m, E, R)
    >>> float(contact_force(a_p, E, R, p_y, max_approach=a_m))
    0.0
    >>> bool(np.isclose(contact_force(a_m, E, R, p_y, max_approach=a_m), P_m))
    True
    """
    if max_approach is None:
        return loading_force(alpha, effective_modulus, effective_radius, limiting_pressure)
    return evaluate(
        _seed.unloading_force_from,
        check_nonnegative("alpha", alpha),
        check_nonnegative("max_approach", max_approach),
        check_positive("effective_modulus", effective_modulus),
        check_positive("effective_radius", effective_radius),
        check_positive("limiting_pressure", limiting_pressure, allow_inf=True),
    )[0]


normalized_loading_force = array_function(
    globals(),
    "normalized_loading_force",
    _seed.normalized_loading_force,
    [("alpha_hat", "nonnegative")],
    ("normalized_velocity", "Normalised force ``P/P_y``"),
    "Normalised loading force ``P/P_y`` against ``alpha/alpha_y`` [-] (seed eqs. 13, 14).",
    notes="``alpha_hat^(3/2)`` up to 1 (eq. 13), then ``(3 alpha_hat - 1)/2`` (eq. 14).",
    examples="""
        >>> normalized_loading_force([0.25, 1.0, 3.0]).tolist()
        [0.125, 1.0, 4.0]
    """,
)


normalized_unloading_force = array_function(
    globals(),
    "normalized_unloading_force",
    _seed.normalized_unloading_force,
    [("alpha_hat", "any", "``alpha/alpha_y``"), ("max_alpha_hat", "positive", "``alpha*/alpha_y``")],
    ("normalized_force", "Normalised unloading force ``P/P_y``, 0 below the plastic approach"),
    "Normalised unloading force ``P/P_y`` [-] (seed eq. 15).",
    notes="""
        ``(R_p/R*)^(1/2) (alpha_hat - alpha_hat_p)^(3/2)`` with ``R_p/R* = alpha_hat*^(3/2)/P_hat*``
        and ``alpha_hat_p = alpha_hat* - P_hat*/alpha_hat*^(1/2)``.
    """,
)


# ============================================================================ outcome (impact)
yield_velocity = array_function(
    globals(),
    "yield_velocity",
    _seed.yield_point,
    [
        ("limiting_pressure", "positive_or_inf", "``inf`` gives ``V_y = inf``"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
        ("effective_mass", "positive"),
    ],
    ("yield_velocity", "Yield velocity ``V_y``"),
    "Yield velocity [m/s], general energy form: ``1/2 m* V_y^2 = 2/5 P_y alpha_y``.",
    notes="""
        The impact speed at which the Hertz pressure at the contact centre just
        reaches ``p_y`` (Davies 1949; Thornton & Ning 1998). Valid for two spheres
        with the effective radius and mass. For a sphere on a flat it is the seed's
        eq. 28 (:func:`yield_velocity_sphere_on_flat`); ``alpha_y`` and ``P_y`` are
        eqs. 5 and 7.
    """,
    examples="""
        >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350
        >>> round(float(yield_velocity(156e6, 1.31e9, 2.45e-6, m)), 3)
        7.523
    """,
    output=(2, 3),
    order=("effective_modulus", "effective_radius", "effective_mass", "limiting_pressure"),
)


yield_velocity_sphere_on_flat = array_function(
    globals(),
    "yield_velocity_sphere_on_flat",
    _seed.yield_velocity_sphere_on_flat,
    [("limiting_pressure", "positive_or_inf"), ("effective_modulus", "positive"), ("density", "positive")],
    ("yield_velocity", "Yield velocity ``V_y``"),
    "Yield velocity of a sphere on a flat, ``V_y = (pi^4/40)^(1/2) (p_y^5/(E*^4 rho))^(1/2)`` [m/s] (seed eq. 28).",
    notes="""
        ``(pi^4/40)^(1/2) = 1.5605``: the seed prints 1.56. Independent of the radius.
    """,
    examples="""
        >>> round(float(yield_velocity_sphere_on_flat(156e6, 1.31e9, 1350.0)), 2)  # seed prints 7.59
        7.52
    """,
)


elastic_max_approach = array_function(
    globals(),
    "elastic_max_approach",
    hertz.max_approach,
    [
        ("velocity", "velocity"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
        ("effective_mass", "positive"),
    ],
    ("max_approach", "Maximum approach ``alpha_m``"),
    "Maximum approach of a purely elastic (Hertz) impact [m].",
    notes="""
        ``alpha_m = (15 m* V^2 / (16 E* R*^(1/2)))^(2/5)``: the energy balance
        ``1/2 m* V^2 = 8/15 E* R*^(1/2) alpha_m^(5/2)`` of Hertz's force (seed eq. 2):
        the seed's stage-1 velocity (eq. 17) vanishes there.
    """,
    examples="""
        At the yield velocity the elastic maximum approach is the yield approach (eq. 5):

        >>> from microimpact.contact import yield_approach
        >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350
        >>> V_y = yield_velocity(156e6, 1.31e9, 2.45e-6, m)
        >>> a_m = elastic_max_approach(V_y, 1.31e9, 2.45e-6, m)
        >>> round(float(a_m / yield_approach(156e6, 1.31e9, 2.45e-6)), 12)
        1.0
    """,
)


normalized_max_approach = array_function(
    globals(),
    "normalized_max_approach",
    _seed.normalized_outcome,
    [("v", "velocity")],
    ("normalized_approach", "``alpha*/alpha_y``"),
    "Normalised maximum approach ``alpha*/alpha_y`` against ``v = V/V_y`` [-] (seed eq. 22).",
    notes="""
        ``(1 + s)/3`` with ``s = ((24 v^2 - 4)/5)^(1/2)`` for ``v > 1``; the Hertz
        value ``v^(4/5)`` for ``v <= 1``.
    """,
    examples="""
        >>> normalized_max_approach([1.0, 2.0]).round(6).tolist()
        [1.0, 1.763174]
    """,
    output=(0, 5),
)


normalized_max_force = array_function(
    globals(),
    "normalized_max_force",
    _seed.normalized_outcome,
    [("v", "velocity")],
    ("normalized_force", "``P*/P_y``"),
    "Normalised maximum force ``P*/P_y`` against ``v = V/V_y`` [-] (seed eq. 14 at the maximum approach).",
    notes="""
        ``(3 alpha^* - 1)/2 = s/2`` for ``v > 1`` (``alpha^*`` from eq. 22);
        ``v^(6/5)`` for ``v <= 1``.
    """,
    output=(1, 5),
)


normalized_plastic_approach = array_function(
    globals(),
    "normalized_plastic_approach",
    _seed.normalized_outcome,
    [("v", "velocity")],
    ("normalized_approach", "``alpha_p/alpha_y``, >= 0"),
    "Normalised plastic approach ``alpha_p/alpha_y = alpha^* - P^*/alpha^*^(1/2)`` [-] (seed eq. 11, normalised).",
    notes="""
        0 for ``v <= 1`` (elastic impact), ``inf`` at ``v = inf``.
    """,
    output=(2, 5),
)


normalized_unloading_radius = array_function(
    globals(),
    "normalized_unloading_radius",
    _seed.normalized_outcome,
    [("v", "velocity")],
    ("normalized_approach", "``R_p/R*``, >= 1"),
    "Normalised unloading radius ``R_p/R* = alpha^*^(3/2)/P^*`` [-] (seed eq. 9, normalised).",
    notes="""
        1 for ``v <= 1`` (elastic impact), ``inf`` at ``v = inf``.
    """,
    output=(3, 5),
)


normalized_restitution = array_function(
    globals(),
    "normalized_restitution",
    _seed.normalized_outcome,
    [("v", "velocity")],
    ("restitution", "Coefficient of restitution ``e = V_r/V``, in [0, 1]"),
    "Restitution coefficient against ``v = V/V_y`` [-] (seed eq. 27).",
    notes="""
        ``e = P^* / (alpha^*^(1/4) v)`` for ``v > 1``, 1 for ``v <= 1``, 0 at ``v = inf``.
    """,
    examples="""
        >>> float(normalized_restitution(1.0))
        1.0
        >>> round(float(normalized_restitution(1e8) * 1e8**0.25), 3)  # high-speed limit 1.185 v^(-1/4)
        1.185
    """,
    output=(4, 5),
)


def restitution_coefficient(velocity, yield_velocity, *, out=None):
    """Restitution coefficient ``e`` of an impact at ``velocity`` [-] (seed eq. 27).

    Parameters
    ----------
    velocity : array_like
        Impact speed ``V`` [m/s], >= 0.
    yield_velocity : array_like
        ``V_y`` [m/s] (eq. 28 or :func:`yield_velocity`); ``inf`` gives ``e = 1``.
    out : ndarray, optional
        Float64 array, C-contiguous, of the broadcast shape, to write ``e`` into (as numpy's ``out``).

    Returns
    -------
    ndarray
        Coefficient of restitution ``e = V_r/V`` [-]: 1 for ``V <= V_y``; ``out`` if given.

    Raises
    ------
    ValueError
        If ``velocity`` is negative or ``yield_velocity`` not positive.

    Examples
    --------
    >>> round(float(restitution_coefficient(20.0, 7.52)), 4)
    0.8836
    """
    V = check_velocity("velocity", velocity)
    Vy = check_positive("yield_velocity", yield_velocity, allow_inf=True)
    if out is not None:
        evaluate(_seed.restitution_at, V, Vy, out=out)
        return out
    return evaluate(_seed.restitution_at, V, Vy)[0]


thornton_ning_restitution = array_function(
    globals(),
    "thornton_ning_restitution",
    _seed.thornton_ning_restitution,
    [("velocity", "velocity"), ("yield_velocity", "positive_or_inf", "``inf`` gives ``e = 1``")],
    ("restitution", "Coefficient of restitution ``e``"),
    "Thornton & Ning's (1998) closed form of the restitution coefficient [-].",
    notes="""
        ``e = (6 3^(1/2)/5)^(1/2) (1 - w^2/6)^(1/2) [w / (w + 2 (6/5 - w^2/5)^(1/2))]^(1/4)``
        with ``w = V_y/V`` for ``V > V_y``, and 1 otherwise. Written independently of
        :func:`restitution_coefficient` (seed eq. 27); the two are algebraically equal
        (see the :ref:`theory page <theory>`).
    """,
    examples="""
        >>> e_tn = thornton_ning_restitution(20.0, 7.52)
        >>> bool(np.isclose(e_tn, restitution_coefficient(20.0, 7.52), rtol=1e-12))
        True
    """,
)


def energy_loss_fraction(restitution):
    """Fraction of the incident kinetic energy lost to plastic deformation, ``1 - e^2`` [-] (seed eq. 29).

    Parameters
    ----------
    restitution : array_like
        Coefficient of restitution ``e`` [-].

    Returns
    -------
    ndarray
        Energy-loss fraction ``1 - e^2`` [-].

    Examples
    --------
    >>> float(energy_loss_fraction(0.5))
    0.75
    """
    e = check_number("restitution", restitution)
    with np.errstate(over="ignore"):  # |e| past 1e154: e^2 leaves the float range, refused below
        loss = _seed.energy_loss(e)
    return check_in_range(loss, "the energy loss 1 - e^2", restitution=restitution)


def impact_outcome(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure):
    """Outcome of a normal impact at ``velocity``, in closed form (seed eqs. 5-29).

    All arguments broadcast against each other.

    Parameters
    ----------
    velocity : array_like
        Normal impact speed ``V`` [m/s], >= 0 (``inf`` gives the limits).
    effective_modulus : array_like
        ``E*`` [Pa].
    effective_radius : array_like
        ``R*`` [m].
    effective_mass : array_like
        ``m*`` [kg].
    limiting_pressure : array_like
        ``p_y`` [Pa]; ``inf`` makes every impact elastic.

    Returns
    -------
    dict of ndarray
        ``velocity`` ``V`` [m/s] (broadcast), ``yield_velocity`` [m/s],
        ``normalized_velocity`` ``V/V_y`` [-],
        ``elastic`` (bool, ``V <= V_y``), ``restitution`` [-], ``rebound_velocity`` [m/s],
        ``max_approach`` ``alpha*`` [m], ``plastic_approach`` ``alpha_p`` [m],
        ``max_force`` ``P*`` [N], ``unloading_radius`` ``R_p`` [m],
        ``energy_loss`` ``1 - e^2`` [-], ``max_contact_radius`` ``a* = (R* alpha*)^(1/2)`` [m],
        ``large_strain`` (bool, ``a*/R* > 0.3``).
    """
    V = check_velocity("velocity", velocity)
    E, R, m, p_y = check_pair(effective_modulus, effective_radius, effective_mass, limiting_pressure)
    out = outcome_arrays(_seed, V, E, R, m, p_y, ())
    return {name: out[name] for name in OUTCOME_FIELDS[: OUTCOME_FIELDS.index("large_strain") + 1]}


#: ``e(V)`` through ``V_y`` alone (seed eq. 27), for fitting's grid search (the face's contract).
restitution_of_yield_velocity = restitution_coefficient


# ============================================================================ times and history (dynamics)
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


deresiewicz_contact_time = array_function(
    globals(),
    "deresiewicz_contact_time",
    hertz.deresiewicz_contact_time,
    [
        ("velocity", "velocity"),
        ("effective_modulus", "positive"),
        ("effective_radius", "positive"),
        ("effective_mass", "positive"),
        ("constant", "any", "default 2.87, as printed in the seed"),
    ],
    ("contact_time", "Elastic contact time ``t_c``"),
    "Deresiewicz's (1968) elastic contact time, ``t_c = 2.87 (m*^2/(R* E*^2 V))^(1/5)`` [s] (seed eq. 30).",
    notes="""
        ``constant`` is the seed's printed 2.87 by default; the exact value is
        :data:`HERTZ_TIME_CONSTANT` (2.8683), which makes this :func:`hertz_contact_time`.
    """,
    examples="""
        >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350  # kg, 4.9 um NH4Fl sphere
        >>> round(float(deresiewicz_contact_time(7.6, 1.31e9, 2.45e-6, m)) * 1e6, 5)  # us; seed: 0.03348
        0.03349
    """,
    defaults={"constant": _special.HERTZ_TIME_CONSTANT_PRINTED},
    described={"constant": ("Prefactor", "1")},
)


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


elastic_stage_time = outcome_function(
    globals(),
    "elastic_stage_time",
    _seed,
    "Duration ``t1`` of stage 1, Hertz loading up to yield or to rest [s] (seed eq. 20).",
    notes="""
        ``(2/5) (alpha_m/V) B(min(1, (V_y/V)^2); 2/5, 1/2)``, with ``alpha_m`` the
        maximum approach of a purely elastic impact.
    """,
    returns="Stage-1 time ``t1`` [s]; ``inf`` at ``V = 0``.",
    examples="""
        Below the yield velocity stage 1 is the whole loading, half the Hertz contact time:

        >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350  # kg, 4.9 um NH4Fl sphere
        >>> t1 = elastic_stage_time(5.0, 1.31e9, 2.45e-6, m, 156e6)
        >>> bool(np.isclose(2 * t1, hertz_contact_time(5.0, 1.31e9, 2.45e-6, m)))
        True
    """,
)


plastic_stage_time = outcome_function(
    globals(),
    "plastic_stage_time",
    _seed,
    "Duration ``t2`` of stage 2, plastic loading to the maximum approach [s] (seed eq. 23).",
    notes="""
        ``(pi/2 - atan2(2 omega alpha_y/3, (V^2 - V_y^2)^(1/2))) / omega``
        ``= atan2((V^2 - V_y^2)^(1/2), 2 omega alpha_y/3) / omega``; 0 for ``V <= V_y``;
        tends to Ning's loading time (eq. 31) as ``V -> inf``.
    """,
    returns="Stage-2 time ``t2`` [s].",
    examples="""
        >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350  # kg, 4.9 um NH4Fl sphere
        >>> float(plastic_stage_time(5.0, 1.31e9, 2.45e-6, m, 156e6))  # elastic impact
        0.0
        >>> round(float(plastic_stage_time(20.0, 1.31e9, 2.45e-6, m, 156e6)) * 1e6, 5)  # us
        0.01012
    """,
)


unloading_time = outcome_function(
    globals(),
    "unloading_time",
    _seed,
    "Duration ``t_U`` of stage 3, elastic unloading from ``alpha*`` to ``alpha_p`` [s] (seed eq. 26).",
    notes="""
        ``(2/5) B(2/5, 1/2) (alpha* - alpha_p) / V_r``; equals the loading time for ``V <= V_y``.
    """,
    returns="Unloading time ``t_U`` [s].",
)


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
    V, E, R, m, p_y = scalar_pair(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure)
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
    if not (alpha_m > 0.0 and T_m > 0.0 and math.isfinite(T_m)):
        # V^2 underflowed (V below about 1e-154 m/s) or the scales overflowed: every time divides by them
        raise ValueError(
            f"velocity {V!r} m/s with effective_modulus {E!r}, effective_radius {R!r} and effective_mass {m!r} "
            f"gives no time history: the elastic maximum approach {alpha_m!r} m and its rise time {T_m!r} s "
            "leave the float range"
        )

    t = time_grid(n, times, (t1, t_L), t_c)
    stage = stage_of(t, t1, t_L, t_c)
    approach, vel = free_flight(t, V, t_c, a_p, V_r)
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
        a_y = float(yield_approach(p_y, E, R))
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


def closed_form_history(velocity, pair_values, params, n=1001, times=None):
    """The face's closed-form history (its contract, :mod:`microimpact.models._base`): :func:`impact_history`
    at ``velocity`` [m/s] for ``pair_values = (E*, R*, m*, p_y)``; ``params`` is the law's empty tuple."""
    return impact_history(velocity, *pair_values, n=n, times=times)


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
    E, R = (np.asarray(get(k), dtype=float) for k in ("effective_modulus", "effective_radius"))
    F = evaluate(hertz.force, alpha, E, R)[0]
    if loading_only:
        stage = np.asarray(get("stage"))
        F = np.where((stage == 1) | (stage == 2), F, np.nan)
    return F
