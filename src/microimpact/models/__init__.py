"""Impact models by name: ``microimpact.models.available()``, what each one takes, and its face.

Each model lives in two rooms. Its physics is one file of :mod:`microimpact.core.models` (scalar,
compilable, the contract declared there). Everything else a user touches about it is its *face*,
a module of this package with the model's name: its calibration to a target ``e(V)`` and contact
time, its LAMMPS/LIGGGHTS input lines, its plot style. A face file is thin and optional: what it
leaves out comes from the defaults of :mod:`microimpact.models._base` (a model with no face file
gets all of them). :func:`face` returns one model's face with those defaults filled in.

Pick a model with ``pair.impact(V, model=NAME)`` (the default is the seed's, :data:`DEFAULT`).
Models outside this package are added with :func:`register_path`.
"""

from __future__ import annotations

import functools
import importlib
import importlib.util
from dataclasses import dataclass
from typing import Any

from ..core import models as _core
from ..core.models import (
    DEFAULT,
    available,
    get,
    parameters,
    register_path,
    resolve_params,
    unregister_path,
)

__all__ = [
    "available",
    "get",
    "parameters",
    "resolve_params",
    "DEFAULT",
    "register_path",
    "unregister_path",
    "face",
    "Face",
    "dem_models",
    "closed_form_histories",
]

_CORE_PACKAGE = "microimpact.core.models"


@dataclass(frozen=True, eq=False)
class Face:
    """One model's face: its face module's names, with the defaults of :mod:`microimpact.models._base`.

    ``calibrate`` takes ``(pair_values, velocity, target_restitution, target_contact_time,
    **options)``; ``own_calibration`` is True when the face file defines it (a DEM law of
    :func:`dem_models`). ``options``: the keyword options its ``calibrate`` takes.
    """

    name: str
    model: Any
    STYLE: dict
    COMPARE_OPTIONS: dict
    calibrate: Any
    own_calibration: bool
    options: tuple
    lammps: Any
    liggghts: Any
    restitution_of_yield_velocity: Any
    closed_form_history: Any
    module: Any


def _face_module(name: str):
    package = _core.package_of(name)
    where = __name__ if package == _CORE_PACKAGE else f"{package}.faces"
    try:
        found = importlib.util.find_spec(f"{where}.{name}")
    except ModuleNotFoundError:  # no faces package beside an added model package
        found = None
    return importlib.import_module(f"{where}.{name}") if found is not None else None


_FACES: dict = {}


def face(name: str = DEFAULT) -> Face:
    """The :class:`Face` of model ``name`` (ValueError if there is no such model)."""
    model = _core.get(name)  # through the module: a registry replaced in a test is asked too
    found = _FACES.get(name)
    if found is not None and found.model is model:
        return found
    from . import _base

    module = _face_module(name)
    ns = vars(module) if module is not None else {}
    own = ns.get("calibrate")
    if own is not None:
        import inspect

        options = tuple(
            p.name for p in inspect.signature(own).parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY
        )
    else:
        options = ()
    found = _FACES[name] = Face(
        name=name,
        model=model,
        STYLE=dict(ns.get("STYLE", _base.STYLE)),
        COMPARE_OPTIONS=dict(ns.get("COMPARE_OPTIONS", _base.COMPARE_OPTIONS)),
        calibrate=own if own is not None else functools.partial(_base.calibrate, model),
        own_calibration=own is not None,
        options=options,
        lammps=ns.get("lammps", _base.lammps),
        liggghts=ns.get("liggghts", _base.liggghts),
        restitution_of_yield_velocity=ns.get("restitution_of_yield_velocity", _base.restitution_of_yield_velocity),
        closed_form_history=ns.get("closed_form_history", _base.closed_form_history),
        module=module,
    )
    return found


def dem_models() -> tuple:
    """Names of the models whose face has a calibration of its own (the DEM laws), in :func:`available` order."""
    return tuple(n for n in _core.available() if face(n).own_calibration)


def closed_form_histories() -> tuple:
    """Names of the models whose face declares a ``closed_form_history``, in :func:`available` order."""
    return tuple(n for n in _core.available() if face(n).closed_form_history is not None)
