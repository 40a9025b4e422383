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

import sys
import warnings

import numpy as np

from . import impact
from ._optional import require
from ._validation import check_pair, check_poisson, check_positive, check_velocity
from .core import models, quantities
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
_AUTO_BLOCK_POINTS = 1 << 17


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
        return impact.outcome_arrays(models.get(spec["model"]), V, *check_pair(E, R, m, p_y), ())
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
        norm = da.core.normalize_chunks("auto", shape, limit=_AUTO_BLOCK_POINTS * 8, dtype=np.float64)
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
    chunks=None,
    progress=False,
):
    """Impact outcome and contact times over every combination of the swept inputs.

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
        Dimensions: the swept inputs, in the order of :data:`SWEEP_DIMENSIONS`.
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
    """
    xr = require("xarray", "sweeps")
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
    coords = {d: values[d] for d in dims}

    material_given = [k for k in _MATERIAL_INPUTS if k in values]
    if material_given and "effective_modulus" in values:
        raise ValueError(
            f"effective_modulus was given together with {material_given[0]}: give E* directly, or the "
            "moduli and Poisson ratios it is made from, not both"
        )
    # Inputs not swept: floats. Everything else is the base pair's (ContactPair.effective_values).
    fixed = {k: float(v) for k, v in values.items() if v.ndim == 0}
    spec = {"pair": pair, "model": models.DEFAULT}
    # Refuse bad combinations now, not inside a dask task (one value of each input is enough).
    pair.effective_values(**{k: v.reshape(-1)[:1] for k, v in values.items() if k != "velocity"})
    attrs = {
        "title": "microimpact parameter sweep",
        "model": "elastic-plastic impact of a sphere on a flat, Aerosol Sci. Tech. 50(4):321-330 (2016), "
        "closed forms (eqs. 5-33)",
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
    if lazy:
        block = _normalize_chunks(chunks, dims, tuple(len(coords[d]) for d in dims))

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
        ds_coords[k] = ((k,) if v.ndim == 1 else (), v, {"units": unit, "long_name": desc})
    ordered = {f: data[f] for f in SWEEP_VARIABLES if f in data}
    ds = xr.Dataset(ordered, coords=ds_coords, attrs=attrs)
    if compute_now:
        diagnostics = require("dask.diagnostics", "sweep progress bars")
        with diagnostics.ProgressBar(out=sys.stderr):
            ds = ds.compute()
    return ds


def _lazy_group(group, fields, dims, coords, block, fixed, spec):
    """dask arrays of ``fields`` over ``dims``: one kernel task per block, fields sliced from its stack."""
    da = require("dask.array", "lazy sweeps (chunks=)")
    args = []
    for d in dims:
        args += [da.from_array(coords[d], chunks=(block[d],), name=False), (d,)]
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
        File to write (overwritten).
    engine : str, optional
        xarray's NetCDF back end (``"netcdf4"`` or ``"scipy"``); default as above.
    progress : bool, optional
        Show a progress bar on stderr while a lazy sweep is written (default False).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    import pathlib

    path = pathlib.Path(path)
    engine = _netcdf_engine(engine)
    out = ds.copy()
    for name, var in out.data_vars.items():
        if var.dtype == bool:
            out[name].attrs.setdefault("flag_values", np.array([0, 1], dtype=np.int8))
            out[name].attrs.setdefault("flag_meanings", "false true")
    if not out.chunks:
        out.to_netcdf(path, engine=engine)
        return path
    delayed = out.to_netcdf(path, engine=engine, compute=False)
    if progress:
        diagnostics = require("dask.diagnostics", "sweep progress bars")
        with diagnostics.ProgressBar(out=sys.stderr):
            delayed.compute()
    else:
        delayed.compute()
    return path


def _csv_header(ds, columns):
    names = []
    for c in columns:
        unit = ds[c].attrs.get("units", "")
        names.append(f"{c} [{unit}]" if unit else c)
    return names


def sweep_to_csv(ds, path, *, progress=False, rows_per_block=None):
    """Write a sweep as a long CSV table, one row per point, block by block.

    Columns: each swept input, then each data variable (broadcast over the
    swept inputs), named ``name [unit]``; floats with 17 significant digits (they
    read back exactly); booleans as 0/1. Rows run over the last dimension
    fastest. A lazy sweep is computed one slab (a block of the first
    dimension) at a time; ``progress=True`` draws a bar on stderr.

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

    pd = require("pandas", "CSV output of sweeps")
    path = pathlib.Path(path)
    dims = list(ds.dims)
    variables = list(ds.data_vars)
    columns = dims + variables
    header = _csv_header(ds, columns)
    with open(path, "w", newline="") as fh:
        if not dims:
            sub = ds.compute()
            df = pd.DataFrame({c: [_csv_value(sub[c].values)] for c in columns})
            df.columns = header
            df.to_csv(fh, index=False)
            return path
        first = dims[0]
        n = ds.sizes[first]
        if ds.chunks:
            sizes = ds.chunks[first]
        else:
            per_row = max(1, int(np.prod([ds.sizes[d] for d in dims[1:]])))
            step = rows_per_block or max(1, _AUTO_BLOCK_POINTS // per_row)
            sizes = [min(step, n - i) for i in range(0, n, step)]
        start = 0
        for k, size in enumerate(sizes):
            sub = ds.isel({first: slice(start, start + size)}).compute()
            start += size
            sub = sub.reset_coords(drop=True)
            df = sub.to_dataframe(dim_order=dims).reset_index()[columns]
            for c in variables:
                if df[c].dtype == bool:
                    df[c] = df[c].astype(np.int8)
            df.columns = header
            df.to_csv(fh, index=False, header=(k == 0))
            if progress:
                _bar(k + 1, len(sizes))
    if progress:
        sys.stderr.write("\n")
    return path


def _csv_value(x):
    x = np.asarray(x)
    return int(x) if x.dtype == bool else x[()]


def _bar(done, total, width=40):
    frac = done / total
    fill = int(round(width * frac))
    sys.stderr.write(f"\r[{'#' * fill}{' ' * (width - fill)}] {100 * frac:5.1f}% ({done}/{total} blocks)")
    sys.stderr.flush()
