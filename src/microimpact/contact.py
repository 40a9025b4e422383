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

The functions are the seed's array face, written once in :mod:`microimpact.models.thornton_ning_2016`
(generated from :mod:`microimpact.core.models.thornton_ning_2016`); this module names them.
"""

from __future__ import annotations

from .models.thornton_ning_2016 import (
    contact_force,
    equivalent_elastic_force,
    hertz_central_pressure,
    hertz_contact_radius,
    hertz_force,
    loading_force,
    normalized_loading_force,
    normalized_unloading_force,
    plastic_approach,
    plastic_loading_force,
    unloading_force,
    unloading_radius,
    yield_approach,
    yield_contact_radius,
    yield_force,
)

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
