"""Adhesion at impact: Thornton & Ning's (1998) sticking velocity and the adhesive restitution.

The seed's elastic-plastic restitution ``e_p(V/V_y)`` (eqs. 22, 27, 28) of the normal impact
speed ``V`` combined with the adhesion loss of Thornton & Ning (1998): the elastic-adhesive
sticking velocity ``V_s`` (:func:`sticking_velocity`) enters as an additional energy loss,
``e^2 = e_p^2 - (V_s/V)^2``; the particle sticks when ``e_p V <= V_s``
(:func:`adhesive_restitution`). With no adhesion (``G = 0``) nothing sticks and ``e = e_p``,
the seed's model unchanged.
"""

from __future__ import annotations

import numpy as np

from ._validation import check_nonnegative, check_positive
from .core import adhesion as _core
from .core.adhesion import STICKING_CONSTANT  # noqa: F401  (its old home; the core's is the one)
from .core.arrays import evaluate

__all__ = ["work_of_adhesion", "sticking_velocity", "adhesive_restitution"]


# ----------------------------------------------------------------------------- adhesion
def work_of_adhesion(surface_energy_1, surface_energy_2=None):
    """Work of adhesion ``G`` [J/m^2] from the surface energies of the two solids.

    Dupre: ``G = gamma_1 + gamma_2 - gamma_12``. Without a measured interface
    energy ``gamma_12`` the usual estimate is the geometric mean (Berthelot /
    Fowkes rule for dispersive solids), ``G = 2 (gamma_1 gamma_2)^(1/2)``, and for
    two identical surfaces ``G = 2 gamma``.

    **The factor 2 that trips users**: a *surface energy* ``gamma`` is a
    property of one free surface (energy per area to create it); the *work of
    adhesion* ``G`` is the energy per area to separate an interface, which
    creates two surfaces. The JKR pull-off force is ``1.5 pi G R* = 3 pi gamma
    R*`` (identical solids). :func:`sticking_velocity` and
    :func:`wall_interaction` take the **work of adhesion** ``G``; this function
    takes **surface energies per surface** ``gamma`` and returns ``G``.

    Parameters
    ----------
    surface_energy_1 : array_like
        Surface energy ``gamma_1`` of the particle [J/m^2], >= 0.
    surface_energy_2 : array_like, optional
        Surface energy ``gamma_2`` of the wall [J/m^2]; default: same as the particle.

    Returns
    -------
    ndarray
        ``G = 2 (gamma_1 gamma_2)^(1/2)`` [J/m^2].

    Examples
    --------
    >>> float(work_of_adhesion(0.05))  # identical surfaces: G = 2 gamma
    0.1
    """
    g1 = check_nonnegative("surface_energy_1", surface_energy_1)
    g2 = g1 if surface_energy_2 is None else check_nonnegative("surface_energy_2", surface_energy_2)
    return 2.0 * np.sqrt(g1 * g2)


def sticking_velocity(work_of_adhesion, effective_modulus, effective_radius, effective_mass):
    """Elastic-adhesive sticking velocity of Thornton & Ning (1998) [m/s].

    ``V_s = (14.1844 / m*)^(1/2) (G^5 R*^4 / E*^2)^(1/6)``

    the normal impact speed below which an elastic JKR contact cannot separate
    again: ``1/2 m* V_s^2`` is the work needed to break the adhesive contact.

    Parameters
    ----------
    work_of_adhesion : array_like
        ``G`` [J/m^2], the **work of adhesion** (energy per area to separate the
        interface; JKR pull-off force ``1.5 pi G R*``), **not** the surface
        energy per surface ``gamma``: for identical surfaces ``G = 2 gamma``
        (see :func:`work_of_adhesion`). ``G = 0`` gives ``V_s = 0``.
    effective_modulus : array_like
        ``E*`` [Pa].
    effective_radius : array_like
        ``R*`` [m].
    effective_mass : array_like
        ``m*`` [kg].

    Returns
    -------
    ndarray
        ``V_s`` [m/s].

    Notes
    -----
    Thornton & Ning (1998), Powder Technol. 99:154-162, eq. 54; the constant
    is twice the JKR separation work 7.0922 (see :data:`STICKING_CONSTANT`:
    derived, where the paper prints the rounded 14.18), checked in the tests by
    integrating the JKR force-approach curve.

    Examples
    --------
    >>> import math
    >>> m = 4 / 3 * math.pi * 0.5e-6**3 * 1350.0   # 1 um NH4Fl sphere
    >>> round(float(sticking_velocity(0.1, 1.31e9, 0.5e-6, m)), 3)
    1.197
    """
    G = check_nonnegative("work_of_adhesion", work_of_adhesion)
    E = check_positive("effective_modulus", effective_modulus)
    R = check_positive("effective_radius", effective_radius)
    m = check_positive("effective_mass", effective_mass)
    return evaluate(_core.sticking_velocity, G, E, R, m)[0]


def adhesive_restitution(velocity, yield_velocity, sticking_velocity):
    """Normal restitution with plastic and adhesive losses (Thornton & Ning 1998).

    ``e^2 = e_p^2 - (V_s / V)^2``, where ``e_p`` is the seed's elastic-plastic
    restitution (eq. 27, :func:`~microimpact.impact.restitution_coefficient`)
    and ``V_s`` the sticking velocity (:func:`sticking_velocity`). The two
    losses add as energies. The particle sticks (``e = 0``) when
    ``e_p V <= V_s``. With ``V_s = 0`` (no adhesion) nothing sticks and
    ``e = e_p``: the seed's model unchanged.

    Parameters
    ----------
    velocity : array_like
        Normal impact speed ``V`` [m/s], finite, >= 0.
    yield_velocity : array_like
        ``V_y`` [m/s] (eq. 28); ``inf`` for a wall that never yields.
    sticking_velocity : array_like
        ``V_s`` [m/s], >= 0.

    Returns
    -------
    ndarray
        ``e`` [-], 0 where the particle sticks.

    Examples
    --------
    >>> adhesive_restitution([0.5, 2.0, 50.0], 7.52, 1.0).round(4)
    array([0.    , 0.866 , 0.7245])
    """
    V = check_nonnegative("velocity", velocity)
    if np.any(np.isinf(V)):
        raise ValueError(f"velocity must be finite, got {float(V[np.isinf(V)].flat[0])!r}")
    Vy = check_positive("yield_velocity", yield_velocity, allow_inf=True)
    Vs = check_nonnegative("sticking_velocity", sticking_velocity)
    return evaluate(_core.restitution, V, Vy, Vs, nout=2)[0]
