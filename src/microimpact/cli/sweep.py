"""``microimpact sweep``: the impact model over ranges of inputs, written to NetCDF or CSV.

Every swept option takes numbers, comma lists or ranges ``start:stop:count``
(:func:`~microimpact.cli._common.parse_values`). Two or more values make a
dimension of the sweep; one value overrides the base pair. The sweep is
evaluated lazily in dask blocks and streamed to the file, so its size is
bounded by the disk, not the memory.
"""

from __future__ import annotations

import argparse
import pathlib
import sys

import numpy as np

from .. import models, quantities
from .._validation import check_positive
from ..materials import DEFAULT_K, PAPER_CASES, limiting_pressure, list_materials
from ..pair import ContactPair
from ..sweep import AUTO_BLOCK_POINTS, SWEEP_DIMENSIONS
from ._common import (
    add_model_arguments,
    check_distinct_paths,
    check_outputs,
    parse_float,
    parse_model_params,
    parse_models,
    parse_values,
    show_progress,
)
from ._stdout import encodable_stdout

# option dest -> (unit, help); the dest is the sweep() keyword.
SWEEP_OPTIONS = quantities.table(SWEEP_DIMENSIONS)


def register(sub) -> None:
    p = sub.add_parser(
        "sweep",
        help="restitution, energy loss and contact times over ranges of inputs, to NetCDF or CSV",
        description="Evaluate the impact model over every combination of the swept inputs and write "
        "the labelled result to NetCDF (.nc) or a long CSV table (.csv; one row per point, units in "
        "the header). Values: numbers, comma lists or ranges start:stop:count (inclusive), e.g. "
        "--velocity 1:120:500 --limiting-pressure 50e6:250e6:5. Two or more values sweep that "
        "input; one value overrides the base pair. Moduli with Poisson ratios left out take the "
        "base pair's materials, or for the paper cases nu = 0.3 and E2 = 150 GPa (the seed's Fig. 4).",
    )
    g = p.add_argument_group("swept inputs")
    for dest, (unit, text) in SWEEP_OPTIONS.items():
        g.add_argument(
            "--" + dest.replace("_", "-"),
            dest=dest,
            nargs="+",
            action=_Once,
            metavar="VALUES",
            required=dest == "velocity",
            help=f"{text} [{unit}]",
        )
    b = p.add_argument_group("base pair", "What the sweep starts from (default: the seed's NH4Fl-on-silicon case).")
    b.add_argument("--case", choices=sorted(PAPER_CASES), help="one of the seed paper's cases")
    b.add_argument("--particle", metavar="MATERIAL", help=f"particle material ({', '.join(list_materials())})")
    b.add_argument("--surface", metavar="MATERIAL", help="surface material (flat); needs --radius")
    b.add_argument(
        "--yield-strength", metavar="PA", help="yield strength Y [Pa]: p_y = k Y when --limiting-pressure is not given"
    )
    b.add_argument("--k", metavar="K", help=f"p_y / Y (default {DEFAULT_K})")
    add_model_arguments(p)
    o = p.add_argument_group("output")
    o.add_argument("--out", required=True, metavar="FILE", help="FILE.nc (NetCDF) or FILE.csv")
    o.add_argument(
        "--chunks", metavar="N", help="block size along each swept dimension (default: about 130 000 points per block)"
    )
    o.add_argument(
        "--no-progress",
        "--quiet",
        "-q",
        action="store_true",
        help="no progress bar (drawn only when stderr is a terminal)",
    )
    p.set_defaults(func=encodable_stdout(run))


class _Once(argparse.Action):
    """Store the values of a swept option; a second use of the option is an error (no silent last-wins)."""

    def __call__(self, parser, namespace, values, option_string=None):
        if getattr(namespace, self.dest, None) is not None:
            raise argparse.ArgumentError(self, "given more than once; give all its values in one option")
        setattr(namespace, self.dest, values)


def _base_pair(args, values):
    if args.case and (args.particle or args.surface):
        raise ValueError("--case and --particle/--surface cannot be used together (one names the base pair)")
    k = parse_float(args.k, "--k") if args.k is not None else None
    Y = parse_float(args.yield_strength, "--yield-strength") if args.yield_strength is not None else None
    if k is not None:
        check_positive("--k", k)
    if Y is not None:
        check_positive("--yield-strength", Y)
    if "limiting_pressure" in values and (k is not None or Y is not None):
        raise ValueError(
            f"--limiting-pressure and {'--k' if k is not None else '--yield-strength'} cannot be used together "
            "(p_y is given directly)"
        )
    if (args.particle or args.surface) and "effective_modulus" in values:
        raise ValueError("--particle/--surface and --effective-modulus cannot be used together")
    if args.particle or args.surface:
        if not (args.particle and args.surface):
            raise ValueError("give both --particle and --surface")
        if "radius" not in values:
            raise ValueError("--radius is needed with --particle/--surface")
        p_y = values.get("limiting_pressure")
        return ContactPair.from_materials(
            args.particle,
            args.surface,
            float(np.atleast_1d(values["radius"])[0]),
            limiting_pressure=None if p_y is None else float(np.atleast_1d(p_y)[0]),
            k=k,
            yield_strength=Y,
        )
    pair = ContactPair.paper_case(args.case or "silicon")
    if Y is not None and "limiting_pressure" not in values:
        pair = pair.replace(limiting_pressure=limiting_pressure(Y, k))
    elif k is not None and "limiting_pressure" not in values:
        Y = PAPER_CASES[args.case or "silicon"]["yield_strength"]
        pair = pair.replace(limiting_pressure=limiting_pressure(Y, k))
    return pair


def _chunks(text):
    if text is None:
        return "auto"
    try:
        n = int(text)
    except ValueError:
        raise ValueError(f"--chunks must be a positive integer, got {text!r}") from None
    if n < 1:
        raise ValueError(f"--chunks must be a positive integer, got {n}")
    return n


#: Points of ``large_strain`` read back at once (:func:`_count_large_strain`).
_COUNT_POINTS = 1 << 20
#: Rows of a CSV sweep read back at once (about 25 MB of text).
_COUNT_ROWS = 1 << 16


def _count_large_strain(path, kind, names) -> int:
    """Points flagged ``large_strain``, read back from the written file (no second evaluation), a
    block at a time: the whole flag, and the index xarray makes of each coordinate, cost 8 bytes a
    point (170 MB at 10^7 speeds). ``names``: the file's variables (all but the flag are not read)."""
    if kind == ".nc":
        import xarray as xr

        drop = [n for n in names if n != "large_strain"]  # no coordinate read, so no index made
        with xr.open_dataset(path, drop_variables=drop) as back:
            flag = back["large_strain"]
            if not flag.dims:
                return int(flag.values)
            first = flag.dims[0]
            step = max(1, _COUNT_POINTS // max(1, flag.size // flag.sizes[first]))
            return sum(
                int(np.count_nonzero(flag.isel({first: slice(i, i + step)}).values))
                for i in range(0, flag.sizes[first], step)
            )
    import pandas as pd

    total = 0
    for part in pd.read_csv(path, usecols=["large_strain [1]"], chunksize=_COUNT_ROWS):
        total += int(part.iloc[:, 0].sum())
    return total


def run(args) -> int:
    out = pathlib.Path(args.out)
    kind = out.suffix.lower()
    if kind not in (".nc", ".csv"):
        raise ValueError(f"--out must end in .nc (NetCDF) or .csv, got {args.out!r}")
    check_outputs(files=[out])
    check_distinct_paths(outputs=[("--out", out)])  # no input files: nothing else to collide with
    chunks = _chunks(args.chunks)
    values = _swept_values(args)
    names = parse_models(args.model)
    params = parse_model_params(args.param, names or [models.DEFAULT])
    npoints = int(np.prod([np.size(v) for v in values.values()])) * len(names or [0])
    if kind == ".csv":  # about 20 numbers of about 22 characters per row
        _check_disk(out, npoints * 520)
    else:
        _check_disk(out, npoints * 8 * 22)
    pair = _base_pair(args, values)
    if names is not None:  # two or more models make a dimension; one is a scalar coordinate
        values["model"] = names if len(names) > 1 else names[0]
    if args.chunks is None and npoints <= AUTO_BLOCK_POINTS:
        # one block either way: computed now, in numpy
        return _sweep_and_write(args, out, kind, values, pair, params, None, npoints)
    return _sweep_and_write(args, out, kind, values, pair, params, chunks, npoints)


def _swept_values(args) -> dict:
    """The swept options' values: an array for each dimension, a float for an input given once."""
    values = {}
    for dest in SWEEP_OPTIONS:
        texts = getattr(args, dest)
        if texts is None:
            continue
        v = parse_values(texts, "--" + dest.replace("_", "-"), unique=True)
        # velocity always becomes a dimension; other inputs only when two or more values are given
        values[dest] = v if (v.size > 1 or dest == "velocity") else float(v[0])
    return values


def _sweep_and_write(args, out, kind, values, pair, params, chunks, npoints) -> int:
    from ..sweep import sweep, sweep_to_csv, sweep_to_netcdf

    ds = sweep(**values, base=pair, model_params=params or None, chunks=chunks)
    values.clear()  # the sweep keeps its own copy of each swept input: the parsed ones are let go
    progress = show_progress(args)
    if not args.no_progress:
        dims = " x ".join(f"{d} {n}" for d, n in ds.sizes.items())
        print(f"sweep: {npoints} points ({dims}), {len(ds.data_vars)} variables -> {out}", file=sys.stderr)
    if kind == ".nc":
        sweep_to_netcdf(ds, out, progress=progress)
    else:
        sweep_to_csv(ds, out, progress=progress)
    names = list(ds.variables)
    del ds  # its coordinates, and the graph's views of them, are not held while the file is read back
    n_large = _count_large_strain(out, kind, names)
    if n_large:
        print(
            f"warning: {n_large} of {npoints} points reach a contact radius above 0.3 R*: outside the model's "
            "small-strain range (variable large_strain)",
            file=sys.stderr,
        )
    print(f"wrote {out}")
    return 0


def _check_disk(out, nbytes) -> None:
    """Refuse up front when the file would not fit on its disk (the estimate is printed)."""
    import errno
    import os
    import shutil

    try:
        free = shutil.disk_usage(out.parent if str(out.parent) else ".").free
    except OSError:
        return
    if nbytes > free:
        raise OSError(
            errno.ENOSPC,
            f"the sweep would write about {nbytes / 1e9:.3g} GB, more than the {free / 1e9:.3g} GB free there",
            os.fspath(out),
        )
