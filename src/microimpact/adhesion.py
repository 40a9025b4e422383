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
from .impact import _restitution

__all__ = ["STICKING_CONSTANT", "work_of_adhesion", "sticking_velocity", "adhesive_restitution"]

#: ``14.18``: the constant of Thornton & Ning's (1998) sticking velocity. It is
#: ``2 x 7.092``, the JKR work (in units of ``(G^5 R*^4 / E*^2)^(1/3)``) needed to pull
#: a contact from zero approach (contact radius ``a_0``) to separation at
#: ``a_0 / 4^(2/3)``, with ``G`` the work of adhesion (pull-off force ``1.5 pi G R*``).
STICKING_CONSTANT = 14.18


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

    ``V_s = (14.18 / m*)^(1/2) (G^5 R*^4 / E*^2)^(1/6)``

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
    Thornton & Ning (1998), Powder Technol. 99:154-162, eq. for ``V_s``; the
    constant 14.18 is twice the JKR separation work 7.09 (see
    :data:`STICKING_CONSTANT`), checked in the tests by integrating the JKR
    force-approach curve.

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
    return np.sqrt(STICKING_CONSTANT / m) * (G**5 * R**4 / E**2) ** (1.0 / 6.0)


def _adhesive(V, e_p, Vs):
    """``(e, stuck)`` from the plastic restitution ``e_p`` and ``V_s`` (no checks)."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        stuck = (Vs > 0.0) & (e_p * V <= Vs)
        ratio = np.where(stuck, 0.0, Vs / np.where(V > 0.0, V, 1.0))
        e = np.sqrt(np.maximum(e_p * e_p - ratio * ratio, 0.0))
    return np.where(stuck, 0.0, e), stuck


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
    e, _ = _adhesive(V, _restitution(V, Vy), Vs)
    return e
