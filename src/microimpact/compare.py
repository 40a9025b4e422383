"""Several impact models side by side for one pair: ``e(V)``, energy loss and contact time.

:func:`compare_models` evaluates the models of :mod:`microimpact.core.models` (each its own closed
form or built-in quadrature, :meth:`ContactPair.impact <microimpact.pair.ContactPair.impact>`) for
one :class:`~microimpact.pair.ContactPair` over a set of impact speeds, and returns the result as a
labelled :class:`xarray.Dataset` with dimensions ``model`` x ``velocity``. Units and descriptions
come from the one table of quantities (:mod:`microimpact.core.quantities`).

Parameters of the models
------------------------
A model whose parameters all have defaults (the seed's ``thornton_ning_2016``,
``liggghts_thornton_ning``) needs nothing. The DEM laws whose parameters have no default
(``linear_spring_dashpot``, ``hertz_viscoelastic``, ``hertz_tsuji``, ``luding_hysteretic``) are,
unless their parameters are given, **calibrated to the seed's model at a reference speed**
(:func:`microimpact.calibrate.calibrate`: the seed's ``e`` matched to 1e-10, and where the law
has a free stiffness the seed's contact time too; ``luding_hysteretic`` with Luding's
``plasticity_depth``, the variant whose ``e`` falls with speed). The Dataset records which models
were calibrated, at which speed, and every parameter used. The adhesive
``jkr_elastic_adhesive`` cannot be calibrated to a model without adhesion: it is compared only
when its ``surface_energy`` is given.

xarray is needed (``pip install 'microimpact[sweep]'``).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from . import calibrate as _calibrate
from . import models as _models
from ._optional import require
from ._validation import check_velocity
from .core import quantities
from .pair import ContactPair, LargeStrainWarning

__all__ = [
    "compare_models",
    "compare_tangential",
    "TANGENTIAL_FIELDS",
    "dem_input_lines",
    "default_models",
    "seed_large_strain_velocity",
    "COMPARED_FIELDS",
    "MODEL_COORDINATES",
    "DEFAULT_REFERENCE_VELOCITY",
]

#: Calibration speed [m/s] with the default speeds (1-120 m/s): the middle of the seed's range.
DEFAULT_REFERENCE_VELOCITY = 50.0

#: Data variables of a comparison (dims ``model`` x ``velocity``): name -> (unit, description).
COMPARED_FIELDS: dict[str, tuple[str, str]] = quantities.table(
    (
        "restitution",
        "energy_loss",
        "contact_time",
        "loading_time",
        "unloading_time",
        "rebound_velocity",
        "max_approach",
        "plastic_approach",
        "max_force",
        "large_strain",
    )
)

#: Coordinates along ``model``: name -> description.
MODEL_COORDINATES = {
    "title": "the model's law and source",
    "calibrated": "True where the parameters were calibrated to the seed's model at reference_velocity",
    "parameters": "the model's parameters as used, 'name = value' [SI units of the model file]",
}


def default_models(params=None) -> list[str]:
    """The models :func:`compare_models` compares by default.

    Every model of :func:`microimpact.models.available` whose parameters have defaults or can be
    calibrated to the seed (:data:`microimpact.calibrate.DEM_MODELS`), and any other model named in
    ``params`` (``jkr_elastic_adhesive`` with its ``surface_energy``).
    """
    params = params or {}
    out = []
    for name in _models.available():
        needs = [p for p, (_, _, d) in _models.parameters(name).items() if math.isnan(d)]
        if not needs or _models.face(name).own_calibration or name in params:
            out.append(name)
    return out


def _needs_calibration(name, given) -> bool:
    """True when model ``name`` lacks a parameter with no default and can be calibrated."""
    missing = [p for p, (_, _, d) in _models.parameters(name).items() if math.isnan(d) and p not in given]
    return bool(missing) and _models.face(name).own_calibration


def compare_models(pair=None, velocity=None, models=None, params=None, *, reference_velocity=None):
    """Restitution, energy loss and contact time of several impact models for one pair.

    Parameters
    ----------
    pair : ContactPair or str, optional
        The particle and surface, or a paper case name; default the seed's NH4Fl-on-silicon case.
    velocity : float or 1-D array_like, optional
        Impact speeds ``V`` [m/s], positive and finite; default 1 to 120 m/s (the seed's range),
        240 points, plus the pair's yield velocity.
    models : str or list of str, optional
        Model names (:func:`microimpact.models.available`); default :func:`default_models`.
    params : dict, optional
        ``{model name: {parameter: value}}``. A DEM law named without its parameters is
        calibrated to the seed's model at ``reference_velocity`` (see the module's notes), with
        the ``limit_force`` convention given here if any; otherwise the parameters given are
        used as they are and the others take the model's defaults.
    reference_velocity : float, optional
        Calibration speed [m/s], above the pair's yield velocity; default the median of
        ``velocity``, or 50 m/s with the default speeds.

    Returns
    -------
    xarray.Dataset
        Dimensions ``model`` (string coordinate) and ``velocity`` [m/s]. Data variables
        (units and ``long_name`` in ``attrs``): ``restitution``, ``energy_loss``,
        ``contact_time``, ``loading_time``, ``unloading_time``, ``rebound_velocity``,
        ``max_approach``, ``plastic_approach``, ``max_force``, ``large_strain`` (bool: the
        contact radius ``(R* alpha*)^(1/2)`` exceeds ``0.3 R*``, the seed's small-strain limit;
        for the DEM laws it is that geometry only). Coordinates along ``model``: ``title``,
        ``calibrated`` (bool) and ``parameters`` (text). ``attrs``: the pair's effective
        values, its ``yield_velocity`` [m/s], ``seed_large_strain_velocity`` [m/s]
        (:func:`seed_large_strain_velocity`),
        ``reference_velocity`` [m/s] and a ``calibration`` sentence naming the calibrated models.

    Raises
    ------
    ValueError
        Unknown model or parameter (named), a model that needs a parameter without a default
        and cannot be calibrated (named), a bad speed, or a calibration that cannot be made
        (a reference speed at or below the yield velocity, where the seed's ``e`` is 1).

    Examples
    --------
    >>> import microimpact as mi
    >>> ds = mi.compare_models("silicon", [10.0, 50.0], ["thornton_ning_2016", "liggghts_thornton_ning"])
    >>> ds.restitution.values.round(3)
    array([[0.985, 0.725],
           [0.981, 0.69 ]])
    >>> ds.contact_time.attrs["units"]
    's'
    """
    xr = require("xarray", "model comparisons")
    pair = _pair(pair)
    if velocity is None:
        Vy = pair.yield_velocity
        V = np.unique(np.concatenate([np.linspace(1.0, 120.0, 240), [Vy] if 1.0 < Vy < 120.0 else []]))
    else:
        V = np.atleast_1d(check_velocity("velocity", velocity)).astype(float)
        if V.ndim != 1:
            raise ValueError(f"velocity must be a number or a 1-D array, got shape {V.shape}")
        if not np.all(V > 0.0):
            raise ValueError(f"velocity must be positive (no impact at 0), got {float(V[V <= 0.0][0])!r}")
    names = _names(models, params)
    given = _given(params, names)

    if reference_velocity is not None:
        ref = reference_velocity
    else:
        ref = DEFAULT_REFERENCE_VELOCITY if velocity is None else float(np.median(V))
    calibrated = [n for n in names if _needs_calibration(n, given.get(n, {}))]
    if calibrated:
        if isinstance(ref, bool) or not isinstance(ref, (int, float, np.floating, np.integer)):
            raise ValueError(f"reference_velocity must be a number, got {ref!r}")
        ref = float(ref)
        if not (math.isfinite(ref) and ref > pair.yield_velocity):
            raise ValueError(
                f"reference_velocity must be finite and above the yield velocity {pair.yield_velocity:.6g} m/s "
                f"(the seed's e is 1 below it, which {calibrated[0]!r} cannot be calibrated to), got {ref!r}"
            )
    used = {}
    for n in names:
        p = dict(given.get(n, {}))
        known = _models.parameters(n)
        unknown = sorted(set(p) - set(known))
        if unknown:
            raise ValueError(
                f"model {n!r} has no parameter {unknown[0]!r}; its parameters: {', '.join(known) or 'none'}"
            )
        if n in calibrated:
            face = _models.face(n)
            chosen = set(p) & set(face.options)  # a parameter that is also a calibration option (limit_force)
            other = sorted(set(p) - chosen)
            if other:
                need = [q for q, (_, _, d) in _models.parameters(n).items() if math.isnan(d)]
                also = f"only {', '.join(sorted(face.options))} may" if face.options else "nothing may"
                raise ValueError(
                    f"model {n!r}: give all of {', '.join(need)} or none of them (then calibrated to the seed; "
                    f"{also} be chosen with a calibration), got {other[0]!r} alone"
                )
            options = {**face.COMPARE_OPTIONS, **{k: p[k] for k in chosen}}
            cal = _calibrate.calibrate(pair, n, ref, **options)
            p = cal.as_dict()
        mod = _models.get(n)
        used[n] = dict(zip([q[0] for q in mod.PARAMETERS], _models.resolve_params(mod, p)))

    data = {f: np.empty((len(names), V.size), dtype=bool if f == "large_strain" else float) for f in COMPARED_FIELDS}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", LargeStrainWarning)
        for i, n in enumerate(names):
            res = pair.impact(V, model=n, **used[n])
            for f in COMPARED_FIELDS:
                data[f][i] = np.asarray(getattr(res, f))
    V_ls = seed_large_strain_velocity(pair)

    unit, desc = quantities.table(["velocity"])["velocity"]
    coords = {
        "model": (
            "model",
            np.array(names, dtype=object),
            {"long_name": "impact model (microimpact.models.available())"},
        ),
        "velocity": ("velocity", V, {"units": unit, "long_name": desc}),
        "title": (
            "model",
            np.array([_models.get(n).TITLE for n in names], dtype=object),
            {"long_name": MODEL_COORDINATES["title"]},
        ),
        "calibrated": (
            "model",
            np.array([n in calibrated for n in names]),
            {"long_name": MODEL_COORDINATES["calibrated"]},
        ),
        "parameters": (
            "model",
            np.array([", ".join(f"{k} = {v:.10g}" for k, v in used[n].items()) or "none" for n in names], dtype=object),
            {"long_name": MODEL_COORDINATES["parameters"]},
        ),
    }
    variables = {
        f: (("model", "velocity"), data[f], {"units": u, "long_name": d}) for f, (u, d) in COMPARED_FIELDS.items()
    }
    if calibrated:
        note = (
            f"{', '.join(calibrated)} calibrated to the seed's model ({_models.DEFAULT}) at "
            f"V = {ref:.6g} m/s (microimpact.calibrate)"
        )
    else:
        note = "none: every model's parameters were given or defaulted"
    attrs = {
        "title": "microimpact model comparison",
        "pair": pair.label or "unnamed",
        "effective_modulus": pair.effective_modulus,
        "effective_radius": pair.effective_radius,
        "effective_mass": pair.effective_mass,
        "limiting_pressure": pair.limiting_pressure,
        "yield_velocity": pair.yield_velocity,
        "seed_large_strain_velocity": V_ls,
        "reference_velocity": ref if calibrated else math.nan,
        "calibration": note,
    }
    return xr.Dataset(variables, coords=coords, attrs=attrs)


def dem_input_lines(ds, pair=None, params=None) -> dict:
    """The LAMMPS and LIGGGHTS input lines of the DEM laws of a comparison, as used in it.

    Parameters
    ----------
    ds : xarray.Dataset
        A result of :func:`compare_models`.
    pair : ContactPair or str, optional
        The pair the comparison was made for (default the seed's case, as there).
    params : dict, optional
        The ``params`` given to :func:`compare_models`.

    Returns
    -------
    dict
        ``{model: {"lammps": text, "liggghts": text}}`` for each DEM law of ``ds``
        (:data:`microimpact.calibrate.DEM_MODELS`): the lines of
        :meth:`Calibration.lammps <microimpact.calibrate.Calibration.lammps>` and
        :meth:`~microimpact.calibrate.Calibration.liggghts`, or a ``#`` comment saying why the code
        has no such law. Calibrated laws are calibrated again as :func:`compare_models` did (the
        same parameters).
    """
    pair = _pair(pair)
    params = params or {}
    out = {}
    for n, cal_flag in zip(ds["model"].values, ds["calibrated"].values):
        n = str(n)
        if n not in _calibrate.DEM_MODELS:
            continue
        given = dict(params.get(n, {}))
        if bool(cal_flag):
            face = _models.face(n)
            options = {**face.COMPARE_OPTIONS, **{k: given[k] for k in face.options if k in given}}
            with warnings.catch_warnings():  # compare_models warned already
                warnings.simplefilter("ignore", _calibrate.CalibrationWarning)
                cal = _calibrate.calibrate(pair, n, float(ds.attrs["reference_velocity"]), **options)
        else:
            cal = _calibrate.Calibration.of(pair, n, given)
        texts = {}
        for code, method in (("lammps", cal.lammps), ("liggghts", cal.liggghts)):
            try:
                texts[code] = method()
            except ValueError as exc:
                texts[code] = f"# {exc}"
        out[n] = texts
    return out


def seed_large_strain_velocity(pair) -> float:
    """Impact speed [m/s] above which the seed's model leaves its small-strain range (``a*/R* > 0.3``).

    Where ``(R* alpha*(V))^(1/2) / R* = 0.3`` (:data:`~microimpact.core.constants.LARGE_STRAIN_RATIO`)
    with the seed's ``alpha*`` (eq. 22), in closed form
    (:func:`~microimpact.core.models.thornton_ning_2016.large_strain_velocity`); ``inf`` if above
    1e6 m/s.
    """
    from .core.models.thornton_ning_2016 import large_strain_velocity

    E, R, m = float(pair.effective_modulus), float(pair.effective_radius), float(pair.effective_mass)
    V = large_strain_velocity(E, R, m, float(pair.limiting_pressure))
    return V if V <= 1e6 else math.inf


def _pair(pair):
    if pair is None:
        return ContactPair.paper_case("silicon")
    if isinstance(pair, str):
        return ContactPair.paper_case(pair)
    if isinstance(pair, ContactPair):
        return pair
    raise ValueError(f"pair must be a ContactPair or a paper case name, got {pair!r}")


def _names(models, params):
    if models is None:
        return default_models(params)
    names = [models] if isinstance(models, str) else list(models)
    if not names:
        raise ValueError("models must name at least one model")
    for n in names:
        _models.get(n)
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ValueError(f"models names {dup[0]!r} more than once")
    return names


def _given(params, names):
    if params is None:
        return {}
    if not isinstance(params, dict):
        raise ValueError(f"params must be a dict {{model name: {{parameter: value}}}}, got {params!r}")
    extra = sorted(set(params) - set(names))
    if extra:
        raise ValueError(f"params names the model {extra[0]!r}, which is not compared (models: {', '.join(names)})")
    for n, p in params.items():
        if not isinstance(p, dict):
            raise ValueError(f"params[{n!r}] must be a dict {{parameter: value}}, got {p!r}")
    return params


#: Data variables of :func:`compare_tangential` (dims ``tangential`` x ``angle``): name -> (unit, description).
TANGENTIAL_FIELDS: dict[str, tuple[str, str]] = {
    "tangential_restitution": ("1", "tangential restitution of the centre v_t'/v_t"),
    "rebound_spin": ("rad/s", "rebound spin, positive adding to the contact point's slip"),
    "rebound_angle": ("deg", "rebound angle of the centre from the normal"),
    "contact_rebound_angle": ("deg", "rebound angle of the contact point from the normal"),
    "impulse_ratio": ("1", "|J_t| / (mu J_n)"),
    "normal_restitution": ("1", "normal restitution e"),
}


def compare_tangential(
    pair,
    velocity,
    angle,
    friction,
    tangential=None,
    *,
    poisson_ratio=None,
    effective_shear_modulus=None,
    spin=0.0,
    method="table",
):
    """Several tangential laws side by side for oblique impacts of one pair (an :class:`xarray.Dataset`).

    Each law is :func:`microimpact.oblique.oblique_impact` with ``tangential=`` that law, at the
    resultant speed ``velocity`` [m/s], the impact angles ``angle`` [deg] from the normal and the
    friction coefficient ``friction``; the Dataset has dimensions ``tangential`` x ``angle`` and the
    variables of :data:`TANGENTIAL_FIELDS` (plus ``regime``).

    Parameters
    ----------
    pair : ContactPair
        Sphere on a flat.
    velocity : float
        Resultant impact speed [m/s].
    angle : array_like
        Impact angles from the normal [deg], in [0, 90).
    friction : float
        Coulomb friction coefficient [-].
    tangential : sequence of str, optional
        Laws of :data:`microimpact.oblique.TANGENTIAL_MODELS` (default: all of them).
    poisson_ratio, effective_shear_modulus, spin, method : optional
        As :func:`~microimpact.oblique.oblique_impact`.
    """
    from . import oblique as ob

    xr = require("xarray", "tangential comparisons")
    names = list(ob.TANGENTIAL_MODELS if tangential is None else tangential)
    if not names:
        raise ValueError("tangential must name at least one law, got an empty list")
    for n in names:
        if n not in ob.TANGENTIAL_MODELS:
            raise ValueError(f"tangential must be among {ob.TANGENTIAL_MODELS}, got {n!r}")
    ang = np.atleast_1d(np.asarray(angle, dtype=float))
    if ang.ndim != 1:
        raise ValueError(f"angle must be a list of angles, got shape {np.shape(angle)}")
    outs = [
        ob.oblique_impact(
            pair,
            velocity,
            ang,
            friction,
            poisson_ratio=poisson_ratio,
            effective_shear_modulus=effective_shear_modulus,
            tangential=n,
            spin=spin,
            method=method,
        )
        for n in names
    ]
    data = {
        k: (
            ("tangential", "angle"),
            np.stack([np.broadcast_to(getattr(o, k), ang.shape) for o in outs]),
            {"units": u, "description": d},
        )
        for k, (u, d) in TANGENTIAL_FIELDS.items()
    }
    data["regime"] = (("tangential", "angle"), np.stack([np.broadcast_to(o.regime, ang.shape) for o in outs]))
    return xr.Dataset(
        data,
        coords={"tangential": names, "angle": ("angle", ang, {"units": "deg"})},
        attrs={
            "pair": str(getattr(pair, "label", "") or ""),
            "velocity": float(velocity),
            "friction": float(friction),
            "kappa": float(outs[0].kappa),
        },
    )
