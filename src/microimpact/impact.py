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

The seed's functions are its array face, written once in :mod:`microimpact.models.thornton_ning_2016`
(generated from :mod:`microimpact.core.models.thornton_ning_2016`); this module names them, beside
the array path of any model's outcome (:func:`outcome_arrays`, :func:`restitution_arrays`).
"""

from __future__ import annotations

from ._face import outcome_arrays, restitution_arrays
from .core.constants import LARGE_STRAIN_RATIO
from .models.thornton_ning_2016 import (
    elastic_max_approach,
    energy_loss_fraction,
    impact_outcome,
    normalized_max_approach,
    normalized_max_force,
    normalized_plastic_approach,
    normalized_restitution,
    normalized_unloading_radius,
    restitution_coefficient,
    thornton_ning_restitution,
    yield_velocity,
    yield_velocity_sphere_on_flat,
)

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
    "outcome_arrays",
    "restitution_arrays",
]
