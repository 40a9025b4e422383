"""Closed-form outcome of a normal elastic-plastic impact (seed eqs. 16-29).

A sphere (or a pair of spheres, through the effective values) meets a surface
at normal speed ``V``. Below the yield velocity ``V_y`` (eq. 28) the impact is
Hertzian and perfectly elastic. Above it, with ``v = V / V_y``, the seed's
normalised solution gives (``^`` means divided by the yield value):

* maximum approach ``alpha^* = (1 + s)/3`` with ``s = ((24 v^2 - 4)/5)^(1/2)`` (eq. 22)
* maximum force ``P^* = (3 alpha^* - 1)/2 = s/2`` (eq. 14 at ``alpha^*``)
* plastic approach ``alpha^_p = alpha^* - P^*/alpha^*^(1/2)`` (eq. 11)
* unloading radius ``R_p/R* = alpha^*^(3/2)/P^*`` (eq. 9)
* restitution ``e = P^* / (alpha^*^(1/4) v)`` (eqs. 24, 25, 27)
* fraction of kinetic energy lost ``1 - e^2`` (eq. 29)

Everything depends on ``V`` only through ``v`` once lengths are scaled by
``alpha_y`` and forces by ``P_y``. The limits ``V -> 0`` (no contact) and
``V -> inf`` (``e -> 0``) are returned explicitly; ``p_y = inf`` gives the
"equivalent elastic impact" of the seed's Fig. 7.
"""

from __future__ import annotations

import numpy as np

from ._face import array_function
from ._validation import check_pair, check_positive, check_velocity
from .core import hertz
from .core.arrays import evaluate
from .core.constants import LARGE_STRAIN_RATIO
from .core.models import thornton_ning_2016 as _seed
from .core.quantities import OUTCOME_FIELDS

__all__ = [
    "LARGE_STRAIN_RATIO",
    "yield_velocity",
    "yield_velocity_sphere_on_flat",
    "elastic_max_approach",
    "normalized_max_approach",
    "normalized_max_force",
    "normalized_plastic_approach",
    "normalized_unloading_radius",
    "normalized_restitution",
    "restitution_coefficient",
    "thornton_ning_restitution",
    "energy_loss_fraction",
    "impact_outcome",
]


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
    return _restitution(V, Vy)


def _restitution(V, Vy):
    """Eq. 27 for checked speeds ``V`` and yield velocities ``V_y`` (used by :mod:`microimpact.adhesion`)."""
    return evaluate(_seed.restitution_at, V, Vy)[0]


def thornton_ning_restitution(velocity, yield_velocity):
    """Thornton & Ning's (1998) closed form of the restitution coefficient [-].

    ``e = (6 3^(1/2)/5)^(1/2) (1 - w^2/6)^(1/2) [w / (w + 2 (6/5 - w^2/5)^(1/2))]^(1/4)``
    with ``w = V_y/V`` for ``V > V_y``, and 1 otherwise. Written independently of
    :func:`restitution_coefficient` (seed eq. 27); the two are algebraically equal
    (see the :ref:`theory page <theory>`).

    Parameters
    ----------
    velocity : array_like
        Impact speed ``V`` [m/s], >= 0.
    yield_velocity : array_like
        Yield velocity ``V_y`` [m/s] (eq. 28); ``inf`` gives ``e = 1``.

    Returns
    -------
    ndarray
        Coefficient of restitution ``e`` [-].

    Raises
    ------
    ValueError
        If ``velocity`` is negative or ``yield_velocity`` not positive.

    Examples
    --------
    >>> e_tn = thornton_ning_restitution(20.0, 7.52)
    >>> bool(np.isclose(e_tn, restitution_coefficient(20.0, 7.52), rtol=1e-12))
    True
    """
    V = check_velocity("velocity", velocity)
    Vy = check_positive("yield_velocity", yield_velocity, allow_inf=True)
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.minimum(Vy / V, 1.0)
        e = (
            np.sqrt(6.0 * np.sqrt(3.0) / 5.0)
            * np.sqrt(1.0 - w**2 / 6.0)
            * (w / (w + 2.0 * np.sqrt(6.0 / 5.0 - w**2 / 5.0))) ** 0.25
        )
    return np.where(V <= Vy, 1.0, e)


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
    return _seed.energy_loss(np.asarray(restitution, dtype=float))


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


def outcome_arrays(model, V, E, R, m, p_y, params) -> dict:
    """Every field of ``model``'s outcome over checked, broadcast float arrays, as a dict of ndarrays.

    The array path of :meth:`microimpact.pair.ContactPair.impact`: one compiled (or, for small
    arrays, Python) loop over the model's scalar ``outcome``; flags become booleans.
    """
    values = evaluate(model.outcome, V, E, R, m, p_y, nout=len(OUTCOME_FIELDS), params=tuple(params))
    out = dict(zip(OUTCOME_FIELDS, values))
    for name in ("elastic", "large_strain"):
        out[name] = out[name] == 1.0
    return out


def restitution_arrays(model, V, E, R, m, p_y, params) -> np.ndarray:
    """The field ``restitution`` of :func:`outcome_arrays` alone, bit for bit, as an ndarray [-].

    Through the model's ``restitution_only`` hook where it declares one (a compiled, or for small
    arrays Python, loop over that scalar function, as for the outcome), which skips what only
    the other fields need (a contact time's quadrature); else the outcome's field.
    """
    if model.restitution_only is None:
        return outcome_arrays(model, V, E, R, m, p_y, params)["restitution"]
    return evaluate(model.restitution_only, V, E, R, m, p_y, params=tuple(params))[0]
