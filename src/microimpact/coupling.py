"""Coupling to gas-particle flow codes: the names of :mod:`microimpact.adhesion`,
:mod:`microimpact.wall` and :mod:`microimpact.cexport` in one place, as before the split.

The seed's last conclusion is that its model "can be easily coupled to numerical
simulations of gas-particle flows to calculate whether the particles stick or
bounce off the impacting surface"; these three modules do that.
"""

from __future__ import annotations

from .adhesion import STICKING_CONSTANT, adhesive_restitution, sticking_velocity, work_of_adhesion  # noqa: F401
from .cexport import (  # noqa: F401
    DEFAULT_SPEEDS,
    DEFAULT_V_OVER_VY,
    DEFAULT_VS_OVER_VY,
    generate_c_source,
    restitution_table,
    write_c_source,
    write_tables,
)
from .wall import REGIMES, WallInteraction, wall_interaction

__all__ = [
    "work_of_adhesion",
    "sticking_velocity",
    "adhesive_restitution",
    "wall_interaction",
    "WallInteraction",
    "REGIMES",
    "restitution_table",
    "write_tables",
    "generate_c_source",
    "write_c_source",
]
