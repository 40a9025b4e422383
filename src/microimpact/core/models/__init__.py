"""Impact models: one file each, found by name.

A model module in this package defines (the contract every path relies on):

``NAME``
    The module's name, the string users pass as ``model=``.
``TITLE``
    One line: the law and its source.
``PARAMETERS``
    Tuple of ``(name, unit, description)`` for the model's own parameters beyond the pair's
    ``E*``, ``R*``, ``m*`` and ``p_y``, in the order :func:`outcome` reads them from ``params``.
``DEFAULTS``
    Tuple of floats, one per parameter (``nan`` where the user must give a value).
``outcome(V, E, R, m, p_y, params)``
    Marked ``@jitable``; plain floats in, a tuple of floats out in the order of
    :data:`microimpact.core.quantities.OUTCOME_FIELDS` (``nan`` where the model does not define a
    field; flags as 1.0/0.0).
``force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)``
    Marked ``@jitable``; the model's own normal force law [N] at approach ``alpha`` [m], approach rate
    ``alpha_dot`` [m/s] and largest approach so far ``alpha_max`` [m], which the numerical integration
    of Newton's equation uses as the independent check of :func:`outcome`.
"""

from __future__ import annotations

import importlib
import pkgutil

__all__ = ["available", "get", "DEFAULT"]

#: The seed's model (Aerosol Sci. Tech. 50(4), 2016), used when no model is named.
DEFAULT = "thornton_ning_2016"


def available() -> list[str]:
    """Names of the models, the seed's first, then alphabetical."""
    names = sorted(m.name for m in pkgutil.iter_modules(__path__) if not m.name.startswith("_"))
    return sorted(names, key=lambda n: n != DEFAULT)


def get(name: str = DEFAULT):
    """The module of model ``name`` (see :func:`available`); ValueError naming it if unknown."""
    names = available()
    if not isinstance(name, str) or name not in names:
        raise ValueError(f"model must be one of {', '.join(names)}; got {name!r}")
    return importlib.import_module(f"{__name__}.{name}")
