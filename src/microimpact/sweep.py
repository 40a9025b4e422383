"""Parameter sweeps of the impact model as labelled arrays (:mod:`xarray`), eager or lazy (:mod:`dask`).

:func:`sweep` evaluates the closed-form outcome (seed eqs. 5-29,
:func:`microimpact.impact.impact_outcome`) and contact times (eqs. 20, 23, 26,
32, 33, :func:`microimpact.dynamics.contact_times`) over every combination of
the inputs given as 1-D arrays, by numpy broadcasting (no Python loop over
points). Each swept input becomes a dimension of the returned
:class:`xarray.Dataset`; every result of the impact is a data variable, with
its unit and description in ``attrs``.

Given ``chunks=``, nothing is computed: the Dataset holds dask arrays, built
with :func:`dask.array.blockwise` from the 1-D coordinates and a module-level
(picklable) kernel, so one block of the sweep lives in memory at a time and
the same graph runs unchanged on a ``dask.distributed`` cluster. The caller
computes it (``ds.compute()``, a reduction, or :func:`sweep_to_netcdf`, which
streams the blocks to disk).

xarray and dask are optional: ``pip install 'microimpact[sweep]'``.
"""

from __future__ import annotations

import contextlib
import math
import sys
import warnings

import numpy as np

from . import impact
from ._optional import require
from ._validation import check_pair, check_poisson, check_positive, check_velocity, first_duplicate
from .core import models, quantities
from .io import atomic_write, check_memory, compute_here, progress_bar, write_netcdf
from .pair import DEFAULT_POISSON, DEFAULT_SURFACE_MODULUS, RESULT_FIELDS, ContactPair

__all__ = [
    "SWEEP_DIMENSIONS",
    "SWEEP_VARIABLES",
    "DEFAULT_POISSON",
    "DEFAULT_SURFACE_MODULUS",
    "sweep",
    "sweep_to_netcdf",
    "sweep_to_csv",
]

#: The inputs that can be swept, in the order their dimensions appear: name -> (unit, description).
SWEEP_DIMENSIONS: dict[str, tuple[str, str]] = quantities.table(
    (
        "velocity",
        "limiting_pressure",
        "particle_modulus",
        "surface_modulus",
        "density",
        "radius",
        "particle_poisson",
        "surface_poisson",
        "effective_modulus",
    )
)

_MATERIAL_INPUTS = ("particle_modulus", "particle_poisson", "surface_modulus", "surface_poisson")

#: Results that depend on every swept input (one group, one evaluation per block).
_IMPACT_FIELDS = (
    "restitution",
    "rebound_velocity",
    "energy_loss",
    "max_approach",
    "plastic_approach",
    "max_force",
    "unloading_radius",
    "max_contact_radius",
    "elastic_stage_time",
    "plastic_stage_time",
    "loading_time",
    "unloading_time",
    "contact_time",
    "normalized_velocity",
    "elastic",
    "large_strain",
)
_BOOL_FIELDS = ("elastic", "large_strain")

_EXTRA_FIELDS: dict[str, tuple[str, str]] = quantities.table(
    ("yield_velocity", "effective_modulus", "effective_radius", "effective_mass")
)

#: Every data variable a sweep returns: name -> (unit, description).
SWEEP_VARIABLES: dict[str, tuple[str, str]] = {
    **{name: RESULT_FIELDS[name] for name in _IMPACT_FIELDS},
    **_EXTRA_FIELDS,
}


#: Points per block when ``chunks="auto"`` (about 40 MB of results and temporaries per block).
AUTO_BLOCK_POINTS = 1 << 17
#: Peak memory per evaluated point [bytes]: the ~20 stacked result fields and the kernel's temporaries.
_BYTES_PER_POINT = 600
#: Points per slab written to CSV: bounds the memory of :func:`sweep_to_csv`. A lazy sweep's block of the
#: first dimension up to this size is computed once (``chunks="auto"`` makes them 362 x the other
#: dimensions); a larger one in pieces, and a piece cut inside a dask chunk computes that chunk again.
_CSV_SLAB_POINTS = 1 << 19
#: Rows formatted per call of polars' CSV writer (about 6 MB of text for a sweep's 22 columns).
_CSV_FORMAT_ROWS = 1 << 14
#: Pieces of :data:`_CSV_FORMAT_ROWS` rows queued to be formatted or written at once (bounds memory).
_CSV_WINDOW = 4
#: Bytes written between two requests that the kernel start writing them to the disk.
_CSV_WRITEBACK_BYTES = 1 << 26


# --------------------------------------------------------------------------- kernel
# Module-level functions of plain arrays and dicts of floats: picklable, so the dask
# graph can be shipped to a distributed cluster. They hold no reference to the
# sweep's coordinates beyond the block they are given.


def _evaluate(group, p, spec):
    """The fields of ``group`` for inputs ``p`` (arrays that broadcast, or floats), as a dict of arrays."""
    pair = spec["pair"]
    E, R, m, p_y = pair.effective_values(**{k: x for k, x in p.items() if k != "velocity"})
    if group == "effective_modulus":
        return {"effective_modulus": E}
    if group == "effective_radius":
        return {"effective_radius": R}
    if group == "effective_mass":
        return {"effective_mass": m}
    if group == "yield_velocity":
        return {"yield_velocity": impact.yield_velocity(p_y, E, R, m)}
    if group == "impact":
        V = check_velocity("velocity", p["velocity"])
        return impact.outcome_arrays(models.get(spec["model"]), V, *check_pair(E, R, m, p_y), spec.get("params", ()))
    raise ValueError(f"unknown group {group!r}")  # pragma: no cover


def _block_inputs(dims, blocks, fixed):
    p = dict(fixed)
    n = len(dims)
    for i, (dim, b) in enumerate(zip(dims, blocks)):
        shape = [1] * n
        shape[i] = len(b)
        p[dim] = np.asarray(b, dtype=float).reshape(shape)
    return p


def _eval_block(group, fields, dims, fixed, spec, blocks):
    """Evaluate ``fields`` on the outer product of the 1-D ``blocks`` (one per dim)."""
    p = _block_inputs(dims, blocks, fixed)
    out = _evaluate(group, p, spec)
    shape = tuple(len(b) for b in blocks)
    return {f: np.broadcast_to(out[f], shape) for f in fields}


def _stacked_block(*blocks, group, fields, dims, fixed, spec):
    """dask kernel: the fields of one block stacked along a last axis (float64)."""
    out = _eval_block(group, fields, dims, fixed, spec, blocks)
    return np.stack([np.asarray(out[f], dtype=float) for f in fields], axis=-1)


# --------------------------------------------------------------------------- inputs
_CHECKS = {
    "velocity": lambda x: check_velocity("velocity", x),
    "limiting_pressure": lambda x: check_positive("limiting_pressure", x, allow_inf=True),
    "particle_modulus": lambda x: check_positive("particle_modulus", x),
    "surface_modulus": lambda x: check_positive("surface_modulus", x, allow_inf=True),
    "density": lambda x: check_positive("density", x),
    "radius": lambda x: check_positive("radius", x),
    "particle_poisson": lambda x: check_poisson("particle_poisson", x),
    "surface_poisson": lambda x: check_poisson("surface_poisson", x),
    "effective_modulus": lambda x: check_positive("effective_modulus", x),
}


def _check_input(name, value):
    arr = _CHECKS[name](value)
    if arr.ndim > 1:
        raise ValueError(f"{name} must be a scalar or a 1-D array, got an array of shape {arr.shape}")
    if arr.ndim == 1 and arr.size == 0:
        raise ValueError(f"{name} must not be empty")
    if arr.ndim == 1 and arr.size > 1:
        # the values label a dimension: a repeated one makes selection by value (ds.sel) return
        # several points for one label, and alignment with another sweep fail
        dup = first_duplicate(arr)
        if dup is not None:
            raise ValueError(
                f"{name} has the value {float(dup)!r} more than once (the values of a swept input label "
                "a dimension and must be distinct)"
            )
    return arr


def _base_pair(base):
    if base is None:
        return ContactPair.paper_case("silicon")
    if isinstance(base, ContactPair):
        return base
    if isinstance(base, str):
        return ContactPair.paper_case(base)
    raise ValueError(f"base must be a ContactPair or a paper case name, got {base!r}")


def _normalize_chunks(chunks, dims, shape):
    """dim -> block size along it, from an int, a dict or ``"auto"``."""
    if isinstance(chunks, str):
        if chunks != "auto":
            raise ValueError(f"chunks must be an int, a dict or 'auto', got {chunks!r}")
        da = require("dask.array", "lazy sweeps (chunks=)")
        norm = da.core.normalize_chunks("auto", shape, limit=AUTO_BLOCK_POINTS * 8, dtype=np.float64)
        return {d: c for d, c in zip(dims, norm)}
    if isinstance(chunks, dict):
        unknown = [k for k in chunks if k not in dims]
        if unknown:
            raise ValueError(
                f"chunks names {unknown[0]!r}, which is not a swept dimension (swept: {', '.join(dims) or 'none'})"
            )
        out = {}
        for d, n in zip(dims, shape):
            c = chunks.get(d, n)
            out[d] = _chunk_size(d, n if c in (None, -1) else c, n)
        return out
    if isinstance(chunks, (int, np.integer)) and not isinstance(chunks, bool):
        return {d: _chunk_size(d, chunks, n) for d, n in zip(dims, shape)}
    raise ValueError(f"chunks must be an int, a dict or 'auto', got {chunks!r}")


def _chunk_size(dim, c, n):
    if isinstance(c, tuple):
        if sum(c) != n or any(int(x) < 1 for x in c):
            raise ValueError(f"chunks for {dim} must be positive and sum to {n}, got {c!r}")
        return tuple(int(x) for x in c)
    try:
        c = int(c)
    except (TypeError, ValueError):
        raise ValueError(f"chunks for {dim} must be a positive integer, got {c!r}") from None
    if c < 1:
        raise ValueError(f"chunks for {dim} must be a positive integer, got {c}")
    return min(c, n)


# --------------------------------------------------------------------------- API
def sweep(
    velocity,
    *,
    limiting_pressure=None,
    particle_modulus=None,
    surface_modulus=None,
    density=None,
    radius=None,
    particle_poisson=None,
    surface_poisson=None,
    effective_modulus=None,
    base=None,
    model=None,
    model_params=None,
    chunks=None,
    progress=False,
):
    """Impact outcome and contact times over every combination of the swept inputs (and models).

    Each argument given as a 1-D array becomes a dimension of the result, with
    that array as its coordinate; a scalar overrides the base pair without
    becoming a dimension (it is kept as a scalar coordinate). Arguments left
    ``None`` take the base pair's value. The model is the seed's closed form
    (eqs. 5-29 via :func:`~microimpact.impact.impact_outcome`; times eqs. 20,
    23, 26, 32, 33 via :func:`~microimpact.dynamics.contact_times`), evaluated by
    broadcasting.

    Parameters
    ----------
    velocity : float or 1-D array_like
        Impact speed ``V`` [m/s], >= 0.
    limiting_pressure : float or 1-D array_like, optional
        ``p_y`` [Pa] (``inf``: elastic).
    particle_modulus, surface_modulus : float or 1-D array_like, optional
        Young's moduli ``E1``, ``E2`` [Pa] of particle and surface.
    particle_poisson, surface_poisson : float or 1-D array_like, optional
        Poisson ratios ``nu1``, ``nu2`` [-], in (-1, 0.5].
    density : float or 1-D array_like, optional
        Particle density [kg/m^3].
    radius : float or 1-D array_like, optional
        Particle radius [m].
    effective_modulus : float or 1-D array_like, optional
        ``E*`` [Pa] directly; not together with the four material inputs above.
    base : ContactPair or str, optional
        The pair the sweep starts from: a :class:`~microimpact.pair.ContactPair`
        or a paper case name (``"silicon"``, ``"mica"``); default the seed's
        NH4Fl-on-silicon case.
    model : str or list of str, optional
        The impact model (:func:`microimpact.models.available`; default the seed's,
        ``"thornton_ning_2016"``). A list makes a first dimension ``model`` whose coordinate
        holds the names (strings); a string is kept as a scalar coordinate. Fields a model does
        not define are NaN (see its model file).
    model_params : dict, optional
        The models' own parameters, ``{model name: {parameter: value}}``
        (:func:`microimpact.models.parameters`); parameters left out take the model's
        defaults, and a model whose parameter has no default needs it here. They are recorded
        in ``attrs["model_parameters"]``. To match a DEM law to the seed first, take its
        parameters from :func:`microimpact.calibrate.calibrate` (``.as_dict()``).
    chunks : int, dict or "auto", optional
        Evaluate lazily with dask in blocks of this size along each dimension
        (an int applies to every swept dimension; a dict maps dimension names to
        sizes, the others unchunked; ``"auto"`` picks about 130 000 points per
        block). The result holds dask arrays: the caller computes it.
    progress : bool
        Without ``chunks``: evaluate block by block under
        :class:`dask.diagnostics.ProgressBar` (on stderr), returning computed
        data. With ``chunks`` nothing is computed here, so there is nothing to
        show: pass ``progress=True`` to :func:`sweep_to_netcdf` /
        :func:`sweep_to_csv`, or wrap your own ``.compute()`` in a ProgressBar.

    Returns
    -------
    xarray.Dataset
        Dimensions: ``model`` when several models are given, then the swept inputs, in the
        order of :data:`SWEEP_DIMENSIONS`.
        Data variables (units and ``long_name`` in ``attrs``): ``restitution``,
        ``rebound_velocity``, ``energy_loss``, ``max_approach``,
        ``plastic_approach``, ``max_force``, ``unloading_radius``,
        ``max_contact_radius``, ``elastic_stage_time``, ``plastic_stage_time``,
        ``loading_time``, ``unloading_time``, ``contact_time``,
        ``normalized_velocity``, ``elastic`` (bool), ``large_strain`` (bool,
        ``a*/R* > 0.3``: outside the small-strain range), and on only the
        dimensions they depend on, ``yield_velocity``, ``effective_modulus``
        (unless swept), ``effective_radius`` and ``effective_mass``.

    Notes
    -----
    Effective values (seed, after eq. 2):

    * ``E*`` is the base pair's, or ``effective_modulus``; when any of
      ``particle_modulus``, ``particle_poisson``, ``surface_modulus``,
      ``surface_poisson`` is given, ``E* = 1/((1-nu1^2)/E1 + (1-nu2^2)/E2)``
      with the missing ones from the base pair's materials. A pair made from
      effective values only (the paper cases) has no materials; then
      ``nu1 = nu2 =`` :data:`DEFAULT_POISSON` (0.3) and ``E2 =``
      :data:`DEFAULT_SURFACE_MODULUS` (150 GPa), as the seed's Fig. 4 takes,
      and ``E1`` is chosen so that ``E*`` is the base pair's (1.2017 GPa for the
      silicon case). The choice is recorded in ``attrs["material_defaults"]``.
    * With ``radius`` or ``density`` given, the particle is a sphere on a flat:
      ``R* = R``, ``m* = 4/3 pi R^3 rho`` (missing one from the base pair).
      Otherwise ``R*`` and ``m*`` are the base pair's (two-sphere pairs too).

    Examples
    --------
    >>> import numpy as np
    >>> ds = sweep(np.array([30.0, 50.0, 70.0]), limiting_pressure=np.array([100e6, 156e6]))
    >>> dict(ds.sizes)
    {'velocity': 3, 'limiting_pressure': 2}
    >>> ds.restitution.sel(limiting_pressure=156e6).values.round(3)
    array([0.813, 0.725, 0.67 ])
    >>> ds.restitution.attrs["units"]
    '1'
    >>> two = sweep(np.array([30.0, 50.0]), model=["thornton_ning_2016", "liggghts_thornton_ning"])
    >>> two.restitution.sel(model="liggghts_thornton_ning").values.round(3)
    array([0.784, 0.69 ])
    """
    xr = require("xarray", "sweeps")
    names, params = _models_and_params(model, model_params)
    if not isinstance(model, str) and model is not None:
        return _sweep_models(
            names,
            params,
            dict(
                velocity=velocity,
                limiting_pressure=limiting_pressure,
                particle_modulus=particle_modulus,
                surface_modulus=surface_modulus,
                density=density,
                radius=radius,
                particle_poisson=particle_poisson,
                surface_poisson=surface_poisson,
                effective_modulus=effective_modulus,
                base=base,
                chunks=chunks,
                progress=progress,
            ),
        )
    name = names[0]
    pair = _base_pair(base)
    given = {
        "velocity": velocity,
        "limiting_pressure": limiting_pressure,
        "particle_modulus": particle_modulus,
        "surface_modulus": surface_modulus,
        "density": density,
        "radius": radius,
        "particle_poisson": particle_poisson,
        "surface_poisson": surface_poisson,
        "effective_modulus": effective_modulus,
    }
    if velocity is None:
        raise ValueError("velocity must be given")
    values = {k: _check_input(k, v) for k, v in given.items() if v is not None}
    dims = tuple(k for k in SWEEP_DIMENSIONS if k in values and values[k].ndim == 1)
    # One copy of each swept input, the sweep's own (the caller may change theirs later): the Dataset's
    # index and every block of the lazy graph are views of it, where each had made its copy (three
    # arrays of 8 bytes a value, 240 MB for 10^7 speeds).
    coords = {d: np.array(values[d], dtype=np.float64) for d in dims}

    material_given = [k for k in _MATERIAL_INPUTS if k in values]
    if material_given and "effective_modulus" in values:
        raise ValueError(
            f"effective_modulus was given together with {material_given[0]}: give E* directly, or the "
            "moduli and Poisson ratios it is made from, not both"
        )
    # Inputs not swept: floats. Everything else is the base pair's (ContactPair.effective_values).
    fixed = {k: float(v) for k, v in values.items() if v.ndim == 0}
    spec = {"pair": pair, "model": name, "params": params[name]}
    # Refuse bad combinations now, not inside a dask task (one value of each input is enough).
    pair.effective_values(**{k: v.reshape(-1)[:1] for k, v in values.items() if k != "velocity"})
    # V_y is a power law of each input, so its smallest value over the grid is at a corner: a p_y so tiny
    # that V_y underflows (the model divides by it) is refused now, naming it (2^k corners, k <= 8).
    ends = {k: np.unique([np.min(v), np.max(v)]) for k, v in values.items() if k != "velocity"}
    mesh = np.meshgrid(*ends.values(), indexing="ij") if ends else []
    check_pair(*pair.effective_values(**{k: g.ravel() for k, g in zip(ends, mesh)}))
    attrs = {
        "title": "microimpact parameter sweep",
        "model": _model_text(name),
        "model_parameters": _params_text(names, params),
        "base_pair": pair.label or "unnamed",
        "base_effective_modulus": pair.effective_modulus,
        "base_effective_radius": pair.effective_radius,
        "base_effective_mass": pair.effective_mass,
        "base_limiting_pressure": pair.limiting_pressure,
    }
    if pair.density is not None:
        attrs["base_density"] = pair.density
    if material_given:
        attrs["material_defaults"] = pair.material_inputs()[1]

    # Which inputs each variable depends on (only the swept ones become its dims).
    groups = [("impact", _IMPACT_FIELDS, dims)]
    groups.append(("yield_velocity", ("yield_velocity",), tuple(d for d in dims if d != "velocity")))
    if "effective_modulus" not in dims:
        groups.append(("effective_modulus", ("effective_modulus",), tuple(d for d in dims if d in _MATERIAL_INPUTS)))
    groups.append(("effective_radius", ("effective_radius",), tuple(d for d in dims if d == "radius")))
    groups.append(("effective_mass", ("effective_mass",), tuple(d for d in dims if d in ("radius", "density"))))

    lazy = chunks is not None
    if progress and not lazy:
        chunks, lazy = "auto", True
        compute_now = True
    else:
        compute_now = False
        if progress:
            warnings.warn(
                "progress=True has no effect with chunks=: the result is lazy and computed by the caller; "
                "use sweep_to_netcdf(..., progress=True) or dask.diagnostics.ProgressBar around .compute()",
                UserWarning,
                stacklevel=2,
            )
    npoints = math.prod(len(coords[d]) for d in dims)
    if lazy:
        block = _normalize_chunks(chunks, dims, tuple(len(coords[d]) for d in dims))
        points = math.prod(max(block[d]) if isinstance(block[d], tuple) else block[d] for d in dims)
        check_memory(points * _BYTES_PER_POINT, f"a sweep block of {points} points", "give smaller chunks")
    else:
        check_memory(
            npoints * _BYTES_PER_POINT,
            f"a sweep of {npoints} points without chunks",
            "give chunks= (or --chunks) to evaluate lazily in blocks",
        )

    data = {}
    for group, fields, gdims in groups:
        if lazy and gdims:
            arrays = _lazy_group(group, fields, gdims, coords, block, fixed, spec)
        else:
            arrays = _eval_block(group, fields, gdims, fixed, spec, [coords[d] for d in gdims])
            arrays = {f: np.array(a) for f, a in arrays.items()}
        for f in fields:
            unit, desc = SWEEP_VARIABLES[f]
            data[f] = (gdims, arrays[f], {"units": unit, "long_name": desc})

    ds_coords = {}
    for k, v in values.items():
        unit, desc = SWEEP_DIMENSIONS[k]
        # a swept input's index is made without a copy of its values (pandas copies an array it is given)
        label = require("pandas", "sweeps").Index(coords[k], copy=False) if k in coords else v
        ds_coords[k] = ((k,) if v.ndim == 1 else (), label, {"units": unit, "long_name": desc})
    if model is not None:
        ds_coords["model"] = ((), name, {"long_name": MODEL_COORDINATE})
    ordered = {f: data[f] for f in SWEEP_VARIABLES if f in data}
    ds = xr.Dataset(ordered, coords=ds_coords, attrs=attrs)
    if compute_now:
        diagnostics = require("dask.diagnostics", "sweep progress bars")
        with diagnostics.ProgressBar(out=sys.stderr):
            ds = ds.compute()
    return ds


#: ``long_name`` of the ``model`` coordinate.
MODEL_COORDINATE = "impact model (microimpact.models.available())"


def _models_and_params(model, model_params):
    """The model names (a list) and ``{name: parameter tuple}``, checked (ValueError naming what is wrong)."""
    if model is None:
        names = [models.DEFAULT]
    elif isinstance(model, str):
        names = [model]
    else:
        try:
            names = list(model)
        except TypeError:
            raise ValueError(f"model must be a model name or a list of names, got {model!r}") from None
        if not names:
            raise ValueError("model must name at least one model")
    for n in names:
        models.get(n)  # ValueError listing the known models
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ValueError(f"model {dup[0]!r} is given more than once")
    given = {} if model_params is None else model_params
    if not isinstance(given, dict):
        raise ValueError(f"model_params must be a dict {{model name: {{parameter: value}}}}, got {given!r}")
    extra = sorted(set(given) - set(names))
    if extra:
        raise ValueError(f"model_params names the model {extra[0]!r}, which is not swept (models: {', '.join(names)})")
    out = {}
    for n in names:
        p = given.get(n, {})
        if not isinstance(p, dict):
            raise ValueError(f"model_params[{n!r}] must be a dict {{parameter: value}}, got {p!r}")
        out[n] = models.resolve_params(models.get(n), p)
    return names, out


def _model_text(name) -> str:
    """``"name: title. Source: citation"`` of a model for the attributes, from its declaration
    (``TITLE``, ``CITATION``: :mod:`microimpact.core.models`)."""
    mod = models.get(name)
    return f"{name}: {mod.TITLE}" + (f". Source: {mod.CITATION}" if mod.CITATION else "")


def _params_text(names, params) -> str:
    """``"name: p = v, ...; name2: ..."`` for the attributes (models without parameters left out)."""
    parts = []
    for n in names:
        labels = [p[0] for p in models.get(n).PARAMETERS]
        if labels:
            parts.append(f"{n}: " + ", ".join(f"{k} = {float(v)!r}" for k, v in zip(labels, params[n])))
    return "; ".join(parts) or "none"


def _sweep_models(names, params, kwargs):
    """One sweep per model, joined along a first dimension ``model`` (lazy stays lazy)."""
    xr = require("xarray", "sweeps")
    sizes = [np.size(v) for k, v in kwargs.items() if k in SWEEP_DIMENSIONS and v is not None]
    npoints = len(names) * math.prod(sizes)
    if kwargs["chunks"] is None and not kwargs["progress"]:
        check_memory(
            npoints * _BYTES_PER_POINT,
            f"a sweep of {npoints} points without chunks",
            "give chunks= (or --chunks) to evaluate lazily in blocks",
        )
    parts = []
    for n in names:
        labels = [p[0] for p in models.get(n).PARAMETERS]
        ds = sweep(**kwargs, model=n, model_params={n: dict(zip(labels, params[n]))}).drop_vars("model")
        for f in _IMPACT_FIELDS:  # the other variables do not depend on the model
            ds[f] = ds[f].expand_dims(model=[n])
        parts.append(ds)
    out = xr.concat(parts, dim="model", data_vars="minimal", coords="minimal", compat="override", join="override")
    out = out.transpose("model", ...)
    out["model"].attrs["long_name"] = MODEL_COORDINATE
    out.attrs["model"] = " | ".join(_model_text(n) for n in names)
    out.attrs["model_parameters"] = _params_text(names, params)
    return out


def _lazy_group(group, fields, dims, coords, block, fixed, spec):
    """dask arrays of ``fields`` over ``dims``: one kernel task per block, fields sliced from its stack."""
    da = require("dask.array", "lazy sweeps (chunks=)")
    args = []
    for d in dims:
        args += [_coordinate_blocks(da, coords[d], block[d]), (d,)]
    stacked = da.blockwise(
        _stacked_block,
        tuple(dims) + ("field",),
        *args,
        new_axes={"field": len(fields)},
        dtype=np.float64,
        concatenate=True,
        meta=np.empty((0,) * (len(dims) + 1), dtype=np.float64),
        group=group,
        fields=tuple(fields),
        dims=tuple(dims),
        fixed=dict(fixed),
        spec=dict(spec),
    )
    out = {}
    for i, f in enumerate(fields):
        a = stacked[..., i]
        out[f] = a.astype(bool) if f in _BOOL_FIELDS else a
    return out


def _coordinate_blocks(da, values, chunk):
    """A dask array of the 1-D ``values`` in blocks of ``chunk`` (an int or a tuple of sizes), each block
    a view of ``values``: ``dask.array.from_array`` copies the whole array first. A view pickles as
    its own values only, so a block shipped to a ``dask.distributed`` worker carries no more."""
    import uuid

    sizes = da.core.normalize_chunks((chunk,), values.shape)
    name = f"microimpact-sweep-coordinate-{uuid.uuid4().hex}"
    graph, start = {}, 0
    for i, size in enumerate(sizes[0]):
        graph[(name, i)] = values[start : start + size]
        start += size
    return da.Array(graph, name, sizes, dtype=values.dtype, meta=values[:0])


# --------------------------------------------------------------------------- writers
def _netcdf_engine(engine):
    if engine is not None:
        return engine
    try:
        import netCDF4  # noqa: F401

        return "netcdf4"
    except ImportError:
        require("scipy.io", "NetCDF output")
        return "scipy"


def sweep_to_netcdf(ds, path, *, engine=None, progress=False):
    """Write a sweep to NetCDF, block by block when it is lazy (bounded memory).

    Booleans are stored as ``int8`` (xarray marks them and reads them back as
    bool). ``engine`` defaults to ``"netcdf4"`` (NetCDF-4) when netCDF4 is
    installed, else ``"scipy"`` (NetCDF-3). With ``progress=True`` a
    :class:`dask.diagnostics.ProgressBar` reports on stderr while the blocks are
    computed and written (the local scheduler; on a ``dask.distributed`` cluster
    use its dashboard or ``distributed.progress``).

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep from :func:`sweep`, eager or lazy (dask-backed); the units of its
        variables (SI) are kept in their ``units`` attributes.
    path : str or os.PathLike
        File to write: written to a temporary file beside it and renamed into
        place when complete, so an interrupted write leaves the previous file.
    engine : str, optional
        xarray's NetCDF back end (``"netcdf4"`` or ``"scipy"``); default as above.
    progress : bool, optional
        Show a progress bar on stderr while a lazy sweep is written (default False).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    engine = _netcdf_engine(engine)
    out = ds.copy()
    for name, var in out.data_vars.items():
        if var.dtype == bool:
            out[name].attrs.setdefault("flag_values", np.array([0, 1], dtype=np.int8))
            out[name].attrs.setdefault("flag_meanings", "false true")
    # a temporary file beside path, renamed into place only when every block is written (microimpact.io)
    return write_netcdf(out, path, engine=engine, progress=progress)


def _csv_header(ds, columns):
    names = []
    for c in columns:
        unit = ds[c].attrs.get("units", "")
        names.append(f"{c} [{unit}]" if unit else c)
    return names


def sweep_to_csv(ds, path, *, progress=False, rows_per_block=None):
    """Write a sweep as a long CSV table, one row per point, block by block.

    Columns: each swept input, then each data variable (broadcast over the
    swept inputs), named ``name [unit]`` (the project's CSV layout,
    :mod:`microimpact.io`, with no comment lines); floats in their shortest
    exact form (they read back exactly; formatted by polars, ``nan``, ``inf``
    and ``-inf`` as such); booleans as 0/1. Rows run over the
    last dimension fastest. A lazy sweep is computed one block of the first
    dimension at a time (split further when a block would exceed about 5.2e5
    points), so memory stays bounded (a peak of 430-490 MB RSS at 10^7 points, the process included). The next
    block is computed while the rows of the one before are formatted, in two
    threads, and written; the bytes are those that one thread would write.
    ``progress=True`` draws a bar on stderr
    (:func:`microimpact.io.progress_bar`). The file is written to a temporary
    name beside ``path`` and renamed into place when complete.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep from :func:`sweep`, eager or lazy (dask-backed).
    path : str or os.PathLike
        File to write (overwritten).
    progress : bool, optional
        Draw a progress bar on stderr, one step per slab (default False).
    rows_per_block : int, optional
        Entries of the first dimension per slab of an eager sweep; by default
        chosen to keep each slab to a bounded number of points. A lazy sweep uses
        its own chunks.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    import pathlib

    path = pathlib.Path(path)
    dims = list(ds.dims)
    variables = list(ds.data_vars)
    columns = dims + variables
    header = _csv_header(ds, columns)
    slabs = list(_slabs(ds, dims, rows_per_block))
    with atomic_write(path, "wb") as fh:  # bytes: polars' text is not made a Python string and encoded again
        fh.write((",".join(header) + "\n").encode("utf-8"))
        if not dims:
            sub = ds.compute()
            _write_rows(fh, [np.atleast_1d(np.asarray(sub[c].values)) for c in columns])
            return path

        def pieces():  # computed one block at a time, in the producer thread of _write_pieces
            for outer, inner in slabs:
                part = compute_here(ds.isel(outer))  # one block of the first dimension at a time
                for sel in inner:
                    yield from _piece_columns(part.isel(sel), dims, variables)
                part = None  # not held while the next block is computed
                yield None  # a block done: one step of the progress bar

        with progress_bar(len(slabs), "sweep to CSV", unit="block", disable=not progress) as bar:
            _write_pieces(fh, pieces(), lambda: bar.update(1))
    return path


def _write_rows(fh, cols):
    """Write the CSV rows of equal-length columns (numpy arrays) to the binary file ``fh`` (UTF-8):
    :func:`_format_rows` of every :data:`_CSV_FORMAT_ROWS` rows, in order, in this thread."""
    import io

    n = len(cols[0]) if cols else 0
    buf = io.BytesIO()
    for i in range(0, n, _CSV_FORMAT_ROWS):
        with _format_rows(cols, i, i + _CSV_FORMAT_ROWS, buf) as text:
            fh.write(text)


def _format_rows(cols, start, stop, buf):
    """The CSV text of rows ``start:stop`` of equal-length columns (numpy arrays), UTF-8: a
    memoryview of ``buf`` (an :class:`io.BytesIO`, reused from its start), to be released before
    ``buf`` is used again.

    Numbers go through polars' compiled CSV writer: floats in their shortest exact form (they read
    back bit for bit; the same digits as Python's ``repr``, positional notation down to 1e-5), NaN
    written ``nan`` (as a null), infinities ``inf`` and ``-inf``, booleans 0/1. Python's ``repr``
    costs about 20x the NetCDF write of the same sweep. Polars formats
    with the GIL released, so two threads format two pieces at once (:func:`_write_pieces`). Text
    columns (a ``model`` dimension) take :func:`microimpact.io.csv_rows`.
    """
    from .io import csv_rows

    buf.seek(0)
    if not all(c.dtype.kind in "biuf" for c in cols):
        buf.writelines((row + "\n").encode("utf-8") for row in csv_rows([c[start:stop] for c in cols]))
        return buf.getbuffer()[: buf.tell()]
    pl = require("polars", "CSV sweeps")
    names = [f"c{j}" for j in range(len(cols))]
    part = {
        name: (c[start:stop].astype(np.int8) if c.dtype.kind == "b" else c[start:stop]) for name, c in zip(names, cols)
    }
    frame = pl.DataFrame(part)
    floats = [name for name, c in zip(names, cols) if c.dtype.kind == "f"]
    if floats:
        frame = frame.with_columns(pl.col(floats).fill_nan(None))
    frame.write_csv(buf, include_header=False, null_value="nan", line_terminator="\n")
    return buf.getbuffer()[: buf.tell()]


def _write_pieces(fh, pieces, step):
    """Write the CSV rows of each list of equal-length columns that ``pieces`` yields to the binary
    file ``fh``, in order, as :func:`_write_rows` would; call ``step()`` for each ``None`` it yields.

    Three stages overlap on the machine's cores. A producer thread runs ``pieces`` (a lazy sweep's
    blocks are computed there) and cuts each into :data:`_CSV_FORMAT_ROWS` rows; two threads
    format them (:func:`_format_rows`: polars formats with the GIL released, so two pieces are
    formatted at once); this thread alone writes to ``fh``, in the order produced. Serially, at
    10^7 points, formatting takes half the time, writing a fifth and computing a sixth.
    At most :data:`_CSV_WINDOW` pieces wait between the stages, so memory stays bounded; the text
    buffers are reused. Every :data:`_CSV_WRITEBACK_BYTES` the kernel is asked to start writing
    the new bytes to the disk (``posix_fadvise(..., POSIX_FADV_DONTNEED)``, which never drops
    unwritten data): otherwise a few GB wait in the page cache, and the final ``fsync`` of
    :func:`microimpact.io.atomic_write` waits seconds for them after all the work is done.

    An exception in any stage, or an interrupt, is raised here once the formatting threads have
    stopped; the producer stops at its next piece (a block being computed is finished first).
    """
    import io
    import os
    import queue
    import threading
    from concurrent.futures import ThreadPoolExecutor

    end = object()
    stop = threading.Event()
    slots = queue.Queue(maxsize=_CSV_WINDOW)  # futures of formatted text, None (a block done), an exception
    spare = queue.SimpleQueue()  # text buffers written and free again

    def put(item):
        while not stop.is_set():
            try:
                slots.put(item, timeout=0.1)
                return True
            except queue.Full:
                pass
        return False

    def format_rows(cols, start):
        try:
            buf = spare.get_nowait()
        except queue.Empty:
            buf = io.BytesIO()
        return buf, _format_rows(cols, start, start + _CSV_FORMAT_ROWS, buf)

    def produce():
        try:
            for cols in pieces:
                if cols is None:
                    if not put(None):
                        return
                    continue
                for start in range(0, len(cols[0]) if cols else 0, _CSV_FORMAT_ROWS):
                    if stop.is_set() or not put(pool.submit(format_rows, cols, start)):
                        return
        except BaseException as exc:  # raised again in the writing thread
            put(exc)
        finally:
            put(end)

    fd, offset = _writeback_start(fh)
    asked = offset
    with ThreadPoolExecutor(2, thread_name_prefix="microimpact-csv-format") as pool:
        producer = threading.Thread(target=produce, name="microimpact-csv-blocks", daemon=True)
        producer.start()
        try:
            while (item := slots.get()) is not end:
                if item is None:
                    step()
                    continue
                if isinstance(item, BaseException):
                    raise item
                buf, text = item.result()
                with text:
                    fh.write(text)
                    offset += len(text)
                spare.put(buf)
                if fd is not None and offset - asked >= _CSV_WRITEBACK_BYTES:
                    with contextlib.suppress(OSError):  # an optimisation only
                        os.posix_fadvise(fd, asked, offset - asked, os.POSIX_FADV_DONTNEED)
                    asked = offset
            producer.join()  # it has put its end: no thread outlives a completed write
        finally:
            stop.set()
            pool.shutdown(wait=True, cancel_futures=True)


def _writeback_start(fh):
    """``(fd, offset)``: the descriptor of ``fh`` (None where the kernel cannot be asked to start
    writing back early) and its position, its buffer flushed."""
    import os

    try:
        fh.flush()
        return (fh.fileno() if hasattr(os, "posix_fadvise") else None), fh.tell()
    except (AttributeError, OSError, ValueError):  # not a file of the system (a BytesIO in tests)
        return None, 0


def _piece_columns(sub, dims, variables, rows=None):
    """The CSV columns of a computed piece of a sweep, in pieces of at most ``rows`` points
    (:data:`_CSV_FORMAT_ROWS`) in row-major order (the last dimension fastest): each a list of
    every swept input and every variable broadcast over the piece's points and raveled. Only one
    piece's columns are made at a time (a whole block's were 21 copies of its size)."""
    shape = tuple(sub.sizes[d] for d in dims)
    sources = []  # views that broadcast to shape
    for i, d in enumerate(dims):
        coord = np.asarray(sub[d].values) if d in sub.coords else np.arange(shape[i])
        index = [np.newaxis] * len(dims)
        index[i] = slice(None)
        sources.append(coord[tuple(index)])
    for c in variables:
        var = sub[c]
        values = np.asarray(var.transpose(*[d for d in dims if d in var.dims]).values)
        index = tuple(slice(None) if d in var.dims else np.newaxis for d in dims)
        sources.append(values[index])
    for sel in _row_major_pieces(shape, rows or _CSV_FORMAT_ROWS):
        sel = sel + (slice(None),) * (len(shape) - len(sel))
        piece = tuple(len(range(*s.indices(n))) for s, n in zip(sel, shape))
        cols = []
        for src in sources:  # a dimension the source does not vary along (length 1) is taken whole
            at = tuple(slice(None) if m == 1 else s for s, m in zip(sel, src.shape))
            cols.append(np.broadcast_to(src[at], piece).ravel())
        yield cols


def _row_major_pieces(shape, max_points):
    """Index tuples (slices) covering ``shape`` in row-major order, each at most ``max_points`` points."""
    if not shape:
        yield ()
        return
    inner = math.prod(shape[1:])
    if inner <= max_points:
        step = max(1, max_points // max(inner, 1))
        for i in range(0, shape[0], step):
            yield (slice(i, min(i + step, shape[0])),)
    else:
        for i in range(shape[0]):
            for rest in _row_major_pieces(shape[1:], max_points):
                yield (slice(i, i + 1), *rest)


def _slabs(ds, dims, rows_per_block=None):
    """``(outer, [inner, ...])``: the blocks of the first dimension computed at once, and the pieces
    written from each, in row-major order, each piece at most :data:`_CSV_SLAB_POINTS` points."""
    if not dims:
        return
    first = dims[0]
    n = ds.sizes[first]
    per_row = max(1, math.prod(ds.sizes[d] for d in dims[1:]))
    if ds.chunks and first in ds.chunks:
        sizes = list(ds.chunks[first])
    else:
        step = rows_per_block or max(1, _CSV_SLAB_POINTS // per_row)
        sizes = [min(step, n - i) for i in range(0, n, step)]
    start = 0
    for size in sizes:
        if size * per_row <= _CSV_SLAB_POINTS or not ds.chunks:
            # the computed block fits (or the data are already in memory): pieces of it
            shape = (size,) + tuple(ds.sizes[d] for d in dims[1:])
            pieces = [dict(zip(dims, p)) for p in _row_major_pieces(shape, max(_CSV_SLAB_POINTS, per_row))]
            yield {first: slice(start, start + size)}, pieces
        else:  # a block too large to hold: compute and write it piece by piece
            shape = (size,) + tuple(ds.sizes[d] for d in dims[1:])
            for p in _row_major_pieces(shape, _CSV_SLAB_POINTS):
                sel = dict(zip(dims, p))
                sel[first] = slice(start + sel[first].start, start + sel[first].stop)
                yield sel, [{}]
        start += size
