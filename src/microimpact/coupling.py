"""Deprecated: the names of :mod:`microimpact.adhesion`, :mod:`microimpact.wall` and
:mod:`microimpact.cexport`, in one place as before their split (kept one release).

Each name still works here and warns (:class:`DeprecationWarning`) naming its home; import it from
there instead.
"""

from __future__ import annotations

import importlib
import warnings

#: Where each name of this module lives now.
MOVED = {
    "STICKING_CONSTANT": "adhesion",
    "adhesive_restitution": "adhesion",
    "sticking_velocity": "adhesion",
    "work_of_adhesion": "adhesion",
    "DEFAULT_SPEEDS": "cexport",
    "DEFAULT_V_OVER_VY": "cexport",
    "DEFAULT_VS_OVER_VY": "cexport",
    "generate_c_source": "cexport",
    "restitution_table": "cexport",
    "write_c_source": "cexport",
    "write_tables": "cexport",
    "REGIMES": "wall",
    "WallInteraction": "wall",
    "wall_interaction": "wall",
}

__all__: list = []


def __getattr__(name):
    home = MOVED.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    warnings.warn(
        f"microimpact.coupling.{name} is deprecated; use microimpact.{home}.{name}", DeprecationWarning, stacklevel=2
    )
    return getattr(importlib.import_module(f"microimpact.{home}"), name)


def __dir__():
    return sorted(MOVED)
