"""Force-displacement laws of the three contact stages and the yield point.

All functions take array_like arguments and broadcast them against each other
(numpy rules). Symbols follow the seed paper (Aerosol Sci. Tech. 50(4), 2016)
and the :ref:`theory page <theory>`:

``alpha``  relative approach (overlap) of the two centres [m]
``E*``     effective modulus [Pa], ``R*`` effective radius [m]
``p_y``    limiting contact pressure [Pa]

Stage 1, Hertz (eqs. 1-4); the yield point (eqs. 5, 7); stage 2, plastic
loading of Thornton & Ning (1998) (eqs. 6, 8); stage 3, elastic unloading
with a flattened contact of radius ``R_p`` from a plastic approach
``alpha_p`` (eqs. 9-11). Normalised forms: eqs. 12-15.
"""

from __future__ import annotations

import numpy as np

from ._face import array_function
from ._validation import check_nonnegative, check_positive
from .core import hertz as _hertz
from .core.arrays import evaluate
from .core.models import thornton_ning_2016 as _seed


def _E(x):
    return check_positive("effective_modulus", x)


def _R(x):
    return check_positive("effective_radius", x)


def _py(x):
    return check_positive("limiting_pressure", x, allow_inf=True)


__all__ = [
    "hertz_force",
    "hertz_contact_radius",
    "hertz_central_pressure",
    "yield_contact_radius",
    "yield_approach",
    "yield_force",
    "plastic_loading_force",
    "loading_force",
    "equivalent_elastic_force",
    "unloading_radius",
    "plastic_approach",
    "unloading_force",
    "contact_force",
    "normalized_loading_force",
    "normalized_unloading_force",
]


hertz_force = array_function(
    globals(),
    "hertz_force",
    _hertz.force,
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
    _hertz.contact_radius,
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
    _hertz.central_pressure,
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


def yield_force(limiting_pressure, effective_modulus, effective_radius):
    """Force at first yield, ``P_y = 4/3 E* R*^(1/2) alpha_y^(3/2)`` [N] (seed eq. 7).

    Parameters
    ----------
    limiting_pressure : array_like
        Limiting contact pressure ``p_y`` [Pa], positive (``inf``: never yields).
    effective_modulus : array_like
        Effective modulus ``E*`` [Pa].
    effective_radius : array_like
        Effective radius ``R*`` [m].

    Returns
    -------
    ndarray
        Yield force ``P_y`` [N].

    Raises
    ------
    ValueError
        If an argument is not positive (``p_y`` may be ``inf``).

    Examples
    --------
    >>> round(float(yield_force(156e6, 1.31e9, 2.45e-6)) * 1e6, 3)  # uN, silicon case
    68.622
    """
    E, R = _E(effective_modulus), _R(effective_radius)
    return evaluate(_hertz.force, evaluate(_seed.yield_approach, _py(limiting_pressure), E, R)[0], E, R)[0]


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


def equivalent_elastic_force(max_approach, effective_modulus, effective_radius):
    """Hertz force at the maximum approach, ``F_e = 4/3 E* R*^(1/2) alpha*^(3/2)`` [N] (seed, after eq. 9).

    The force the maximum approach would need if the contact had stayed elastic;
    it fixes the unloading radius (eq. 9) and the plastic approach (eq. 11).

    Parameters
    ----------
    max_approach : array_like
        Maximum approach ``alpha*`` [m], >= 0.
    effective_modulus : array_like
        Effective modulus ``E*`` [Pa].
    effective_radius : array_like
        Effective radius ``R*`` [m].

    Returns
    -------
    ndarray
        Equivalent elastic force ``F_e`` [N].
    """
    return hertz_force(max_approach, effective_modulus, effective_radius)


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


def unloading_force(alpha, plastic_approach, unloading_radius, effective_modulus):
    """Elastic unloading force ``P = 4/3 E* R_p^(1/2) (alpha - alpha_p)^(3/2)`` [N] (seed eq. 10).

    Zero for ``alpha <= alpha_p`` (the bodies have separated).

    Parameters
    ----------
    alpha : array_like
        Approach ``alpha`` [m].
    plastic_approach : array_like
        Plastic approach ``alpha_p`` [m] (eq. 11, :func:`plastic_approach`).
    unloading_radius : array_like
        Unloading radius ``R_p`` [m] (eq. 9, :func:`unloading_radius`).
    effective_modulus : array_like
        Effective modulus ``E*`` [Pa].

    Returns
    -------
    ndarray
        Unloading force ``P`` [N], >= 0.
    """
    return evaluate(
        _seed.unloading_force,
        np.asarray(alpha, dtype=float),
        np.asarray(plastic_approach, dtype=float),
        check_positive("unloading_radius", unloading_radius),
        _E(effective_modulus),
    )[0]


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
        _E(effective_modulus),
        _R(effective_radius),
        _py(limiting_pressure),
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


def normalized_unloading_force(alpha_hat, max_alpha_hat):
    """Normalised unloading force ``P/P_y`` [-] (seed eq. 15).

    ``(R_p/R*)^(1/2) (alpha_hat - alpha_hat_p)^(3/2)`` with ``R_p/R* = alpha_hat*^(3/2)/P_hat*``
    and ``alpha_hat_p = alpha_hat* - P_hat*/alpha_hat*^(1/2)``.

    Parameters
    ----------
    alpha_hat : array_like
        Normalised approach ``alpha/alpha_y`` [-].
    max_alpha_hat : array_like
        Normalised maximum approach ``alpha*/alpha_y`` [-], > 0.

    Returns
    -------
    ndarray
        Normalised unloading force ``P/P_y`` [-], 0 below the plastic approach.
    """
    return evaluate(
        _seed.normalized_unloading_force,
        np.asarray(alpha_hat, dtype=float),
        check_positive("max_alpha_hat", max_alpha_hat),
    )[0]
