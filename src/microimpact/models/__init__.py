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
    "dem_line_models",
    "OutsideValidityWarning",
    "outside_validity",
    "validity_codes",
    "validity_text",
    "closed_form_histories",
    "adhesion_inputs",
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
    params_for_work_of_adhesion: Any
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
        params_for_work_of_adhesion=ns.get(
            "params_for_work_of_adhesion", functools.partial(_base.params_for_work_of_adhesion, model)
        ),
        module=module,
    )
    return found


def dem_models() -> tuple:
    """Names of the models whose face has a calibration of its own (the DEM laws), in :func:`available` order."""
    return tuple(n for n in _core.available() if face(n).own_calibration)


def dem_line_models() -> tuple:
    """Names of the models whose face prints DEM input lines (its own ``lammps`` or ``liggghts``): the DEM
    laws and the laws whose inputs are physics the user gives (a liquid bridge's liquid), which
    :meth:`Calibration.of <microimpact.calibrate.Calibration.of>` takes with their parameters."""
    from . import _base

    return tuple(
        n for n in _core.available() if face(n).lammps is not _base.lammps or face(n).liggghts is not _base.liggghts
    )


# ----------------------------------------------------------------------------- outside validity


class OutsideValidityWarning(UserWarning):
    """Some impact lies outside what its published law can say (the model's ``outside_validity`` hook,
    :data:`microimpact.core.models.VALIDITY_REASONS`): an unloading that would return more work than
    the loading stored (``e > 1``; ``e = 1`` is returned) or a contact radius beyond the sphere's.
    The results are kept as computed and flagged, not refused, as :class:`~microimpact.LargeStrainWarning`'s."""


def validity_codes(model, V, E, R, m, p_y, params):
    """The ``outside_validity`` codes [-] (0: inside; bits of :data:`~microimpact.core.models.VALIDITY_REASONS`)
    of ``model`` (a :class:`~microimpact.core.models.Model`) at the checked, broadcast speeds ``V``
    [m/s] and pair floats, as a float ndarray of ``V``'s shape; zeros for a model without the hook."""
    import numpy as np

    from ..engine import evaluate

    V = np.asarray(V, dtype=float)
    if model.outside_validity is None:
        return np.zeros(V.shape)
    return np.asarray(evaluate(model.outside_validity, V, E, R, m, p_y, params=tuple(params))[0], dtype=float)


def validity_text(name, V, codes):
    """The :class:`OutsideValidityWarning` message of model ``name`` for the speeds ``V`` [m/s] and their
    codes (:func:`validity_codes`), or None where every impact lies inside."""
    import numpy as np

    codes = np.atleast_1d(np.asarray(codes, dtype=float))
    V = np.broadcast_to(np.atleast_1d(np.asarray(V, dtype=float)), codes.shape)
    out = codes != 0.0
    if not out.any():
        return None
    parts = []
    for bit, text in _core.VALIDITY_REASONS.items():
        sel = (codes.astype(np.int64) & bit) != 0
        if sel.any():
            lo, hi = float(V[sel].min()), float(V[sel].max())
            where = f"at {lo:.4g} m/s" if lo == hi else f"between {lo:.4g} and {hi:.4g} m/s"
            parts.append(f"{where}: {text}")
    return (
        f"{int(out.sum())} of {out.size} impacts of {name!r} lie outside what the law can say (results kept as "
        "computed, flagged in outside_validity): " + "; ".join(parts)
    )


def outside_validity(pair, velocity, *, model, warn=True, **params):
    """Where impacts of ``pair`` at ``velocity`` [m/s] lie outside what ``model``'s published law can say.

    Returns a bool ndarray of ``velocity``'s shape (the model's ``outside_validity`` hook, nonzero;
    all False for a model without one) and, with ``warn``, issues an :class:`OutsideValidityWarning`
    naming the speeds and reasons (:data:`~microimpact.core.models.VALIDITY_REASONS`): Kogut-Etsion +
    Etsion-Kligerman-Kadin just past ``V_y`` and Jackson-Green + Brake just past 1.9 ``delta_c``, where
    the published unloading would give ``e > 1`` (``pair.impact`` returns 1), and Jackson-Green where
    ``a* > R``, where its ``e`` rises with the speed again. The outcome itself is unchanged.
    """
    import warnings

    from .._validation import check_velocity

    mod = get(model)
    p = resolve_params(mod, params)
    V = check_velocity("velocity", velocity)
    E, R, m, p_y = (
        float(pair.effective_modulus),
        float(pair.effective_radius),
        float(pair.effective_mass),
        float(pair.limiting_pressure),
    )
    codes = validity_codes(mod, V, E, R, m, p_y, p)
    if warn:
        text = validity_text(mod.NAME, V, codes)
        if text is not None:
            warnings.warn(text, OutsideValidityWarning, stacklevel=2)
    return codes != 0.0


def closed_form_histories() -> tuple:
    """Names of the models whose face declares a ``closed_form_history``, in :func:`available` order."""
    return tuple(n for n in _core.available() if face(n).closed_form_history is not None)


def adhesion_inputs(name: str, work_of_adhesion, pair_values, given=None) -> tuple:
    """The parameter tuple of model ``name`` for the work of adhesion ``G`` [J/m^2] at ``pair_values =
    (E*, R*, m*, p_y)``: its adhesion input set from ``G`` by its face (``params_for_work_of_adhesion``),
    the others from ``given`` (name -> value) or their defaults (NaN where there is none); unchecked.
    A law without such an input keeps what ``given`` and its defaults set. ValueError for a parameter
    the model does not have."""
    model = _core.get(name)
    names = [p.name for p in model.PARAMETERS]
    given = dict(given or {})
    unknown = sorted(set(given) - set(names))
    if unknown:
        raise ValueError(
            f"model {name!r} has no parameter {unknown[0]!r}; its parameters: {', '.join(names) or 'none'}"
        )
    start = tuple(float(given.get(n, d)) for n, d in zip(names, model.DEFAULTS))
    mapped = face(name).params_for_work_of_adhesion(float(work_of_adhesion), tuple(pair_values), start)
    return start if mapped is None else tuple(float(v) for v in mapped)
