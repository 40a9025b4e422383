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
import math
import pkgutil

__all__ = ["available", "get", "parameters", "resolve_params", "DEFAULT"]

#: The seed's model (Aerosol Sci. Tech. 50(4), 2016), used when no model is named.
DEFAULT = "thornton_ning_2016"


_NAMES: list = []
_MODULES: dict = {}


def available() -> list[str]:
    """Names of the models, the seed's first, then alphabetical (the files, read once per process)."""
    if not _NAMES:
        names = sorted(m.name for m in pkgutil.iter_modules(__path__) if not m.name.startswith("_"))
        _NAMES.extend(sorted(names, key=lambda n: n != DEFAULT))
    return list(_NAMES)


def get(name: str = DEFAULT):
    """The module of model ``name`` (see :func:`available`); ValueError naming it if unknown."""
    found = _MODULES.get(name) if isinstance(name, str) else None
    if found is not None:
        return found
    names = available()
    if not isinstance(name, str) or name not in names:
        raise ValueError(f"model must be one of {', '.join(names)}; got {name!r}")
    found = _MODULES[name] = importlib.import_module(f"{__name__}.{name}")
    return found


def parameters(name: str = DEFAULT) -> dict:  # noqa: D401
    """``{parameter: (unit, description, default)}`` of model ``name`` (``nan`` default: required)."""
    mod = get(name)
    return {p[0]: (p[1], p[2], d) for p, d in zip(mod.PARAMETERS, mod.DEFAULTS)}


def resolve_params(module, given: dict) -> tuple:
    """The model's parameters as the float tuple its functions take, from keyword values and defaults.

    ValueError naming the parameter when one is unknown, missing (no default), not a real number,
    or not finite.
    """
    if not given and not module.PARAMETERS:  # the common case, on the path of one impact
        return ()
    names = [p[0] for p in module.PARAMETERS]
    unknown = sorted(set(given) - set(names))
    if unknown:
        raise ValueError(
            f"model {module.NAME!r} has no parameter {unknown[0]!r}; its parameters: {', '.join(names) or 'none'}"
        )
    out = []
    for name, default in zip(names, module.DEFAULTS):
        value = given.get(name, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)) and not hasattr(value, "__float__"):
            raise ValueError(f"{name} must be a real number, got {value!r}")
        value = float(value)
        if math.isnan(value):
            raise ValueError(f"model {module.NAME!r} needs the parameter {name!r} (no default)")
        if not math.isfinite(value):
            raise ValueError(f"{name} must be finite, got {value!r}")
        out.append(value)
    return tuple(module.validate(tuple(out)))
