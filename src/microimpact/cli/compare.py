"""``microimpact compare``: several impact models for one pair, as a table, JSON, NetCDF/CSV and a figure."""

from __future__ import annotations

import math
import pathlib

import numpy as np

from .._validation import check_velocity
from ..io import write_json
from ..quantities import QUANTITIES
from ..quantities import header as heading
from ._common import (
    add_model_arguments,
    add_pair_arguments,
    check_distinct_paths,
    check_outputs,
    pair_from_args,
    parse_float,
    parse_model_params,
    parse_models,
    parse_tangential,
    parse_values,
)
from ._stdout import encodable_stdout

#: Memory per speed and model [bytes]: ten result arrays, their temporaries and the text.
BYTES_PER_SPEED = 4000


def register(sub) -> None:
    p = sub.add_parser(
        "compare",
        help="restitution, energy loss and contact time of several impact models for one pair",
        description="Compare impact models for one pair: e(V), energy loss 1-e^2 and contact time, as a "
        "table (default), JSON, a NetCDF or CSV file and a figure. DEM laws named without their "
        "parameters are calibrated to the seed's model at --reference-velocity (microimpact.calibrate); "
        "the output says which. Speeds: numbers, comma lists or ranges start:stop:count [m/s]. "
        "With --tangential LAWS it compares tangential laws instead: oblique impacts at one resultant speed V "
        "over --angles (microimpact.compare.compare_tangential).",
    )
    p.add_argument(
        "velocities",
        nargs="*",
        metavar="V",
        help="impact speed(s) [m/s], e.g. 10 30 50 or 1:120:240 (default: 10 20 30 50 70 100)",
    )
    add_pair_arguments(p)
    add_model_arguments(p)
    p.add_argument(
        "--reference-velocity",
        metavar="M/S",
        help="calibration speed of the DEM laws [m/s] (default: the median speed)",
    )
    o = p.add_argument_group("output")
    o.add_argument("--json", action="store_true", help="print JSON (SI units) instead of a table")
    o.add_argument("--out", metavar="FILE", help="also write the Dataset to FILE.nc (NetCDF) or FILE.csv")
    o.add_argument("--plot", metavar="FILE", help="also draw the comparison to this image (png, pdf, svg)")
    o.add_argument(
        "--dem-lines",
        action="store_true",
        help="also print the LAMMPS and LIGGGHTS input lines of the DEM laws compared (as calibrated or given)",
    )
    t = p.add_argument_group(
        "tangential laws",
        "--tangential compares tangential laws (microimpact oblique's models) on oblique impacts at one "
        "resultant speed V [m/s] (default 3.9 with --alumina); the other options here need it.",
    )
    t.add_argument(
        "--tangential",
        metavar="LAWS",
        help="tangential laws, comma-separated (mindlin, rigid, lammps_mindlin, lammps_mindlin_force, "
        "lammps_mindlin_rescale, lammps_mindlin_rescale_force, lammps_linear_history, liggghts_history, "
        "di_renzo_di_maio, mindlin_deresiewicz, stronge), or 'all'",
    )
    t.add_argument(
        "--angles",
        metavar="DEG",
        help="impact angles from the normal [deg]: list or start:stop:count (default 0:85:18)",
    )
    t.add_argument("--friction", metavar="MU", help="Coulomb friction coefficient (default 0.3; 0.092 with --alumina)")
    t.add_argument("--poisson", metavar="NU", help="Poisson's ratio for G* (default: from the pair's materials)")
    t.add_argument("--spin", metavar="RAD/S", help="incoming spin, positive adding to the slip (default 0)")
    t.add_argument("--alumina", action="store_true", help="the alumina case of microimpact oblique --alumina")
    p.set_defaults(func=encodable_stdout(run))


#: Options of the tangential mode (dest), refused without --tangential.
_TANGENTIAL_ONLY = ("angles", "friction", "poisson", "spin", "alumina")
#: Options of the normal-law mode (dest), refused with --tangential.
_NORMAL_ONLY = ("model", "param", "reference_velocity", "dem_lines")


def format_table(ds) -> str:
    """The comparison as an aligned text table, one row per model and speed (``*``: a*/R* > 0.3)."""
    header = ["model", *(heading(n) for n in ("velocity", "restitution", "energy_loss", "contact_time"))]
    rows = [header]
    # each array taken once: ds[name] builds a DataArray (35 us), and four a row were 20 ms of 144 rows
    restitution, energy_loss = ds["restitution"].values, ds["energy_loss"].values
    contact_time, large_strain = ds["contact_time"].values, ds["large_strain"].values
    for i, name in enumerate(ds["model"].values):
        for j, V in enumerate(ds["velocity"].values):
            e = float(restitution[i, j])
            loss = float(energy_loss[i, j])
            tc = float(contact_time[i, j]) * QUANTITIES["contact_time"].scale
            flag = " *" if bool(large_strain[i, j]) else ""
            rows.append([str(name), f"{V:.4g}", _f(e, "{:.5f}"), _f(loss, "{:.4f}"), _f(tc, "{:.4f}") + flag])
    widths = [max(len(r[k]) for r in rows) for k in range(len(header))]
    lines = ["  ".join(c.ljust(w) if k == 0 else c.rjust(w) for k, (c, w) in enumerate(zip(r, widths))) for r in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def _f(x, fmt):
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf"
    return fmt.format(x)


def _describe(ds) -> list[str]:
    lines = [
        f"pair: {ds.attrs['pair']}",
        f"  E* = {ds.attrs['effective_modulus']:.6g} Pa   R* = {ds.attrs['effective_radius']:.6g} m   "
        f"m* = {ds.attrs['effective_mass']:.6g} kg   p_y = {ds.attrs['limiting_pressure']:.6g} Pa   "
        f"V_y = {ds.attrs['yield_velocity']:.6g} m/s",
        "models:",
    ]
    for name, cal, params in zip(ds["model"].values, ds["calibrated"].values, ds["parameters"].values):
        lines.append(f"  {name}{' (calibrated)' if cal else ''}: {params}")
    lines.append(f"calibration: {ds.attrs['calibration']}")
    return lines


def run(args) -> int:
    if args.tangential is not None:
        return run_tangential(args)
    given = [d for d in _TANGENTIAL_ONLY if getattr(args, d) not in (None, False)]
    if given:
        raise ValueError(f"--{given[0]} is used with --tangential only (the tangential laws' comparison)")
    texts = args.velocities or ["10,20,30,50,70,100"]
    V = parse_values(texts, "velocity", bytes_per_value=BYTES_PER_SPEED * 8, unique=True)
    check_velocity("velocity", V)
    if not np.all(V > 0.0):
        raise ValueError(f"velocity must be positive (no impact at 0), got {float(V[V <= 0.0][0])!r}")
    out = pathlib.Path(args.out) if args.out else None
    if out is not None and out.suffix.lower() not in (".nc", ".csv"):
        raise ValueError(f"--out must end in .nc (NetCDF) or .csv, got {args.out!r}")
    check_outputs(files=[out], figures=[args.plot])
    check_distinct_paths(outputs=[("--out", out), ("--plot", args.plot)])
    names = parse_models(args.model)
    from ..compare import default_models

    params = parse_model_params(args.param, names or default_models())
    if names is None:
        names = default_models(params)
    ref = None
    if args.reference_velocity is not None:
        ref = parse_float(args.reference_velocity, "--reference-velocity")
    pair = pair_from_args(args)

    from ..compare import compare_models

    ds = compare_models(pair, V, names, params or None, reference_velocity=ref)

    if out is not None:
        from ..sweep import sweep_to_csv, sweep_to_netcdf

        (sweep_to_netcdf if out.suffix.lower() == ".nc" else sweep_to_csv)(ds, out)
    if args.plot:
        from ..figures.compare import plot_comparison
        from ..io import save_figure

        axes = plot_comparison(ds)
        save_figure(axes[0].figure, args.plot, dpi=300)
    lines = None
    if args.dem_lines:
        from ..compare import dem_input_lines

        lines = dem_input_lines(ds, pair, params or None)
    if args.json:
        doc = {
            "pair": {k: ds.attrs[k] for k in ("pair", "effective_modulus", "effective_radius", "effective_mass")}
            | {k: ds.attrs[k] for k in ("limiting_pressure", "yield_velocity")},
            "calibration": ds.attrs["calibration"],
            "reference_velocity": ds.attrs["reference_velocity"],
            "models": {
                str(n): {"title": str(t), "calibrated": bool(c), "parameters": str(p)}
                for n, t, c, p in zip(
                    ds["model"].values, ds["title"].values, ds["calibrated"].values, ds["parameters"].values
                )
            },
            "velocity": ds["velocity"].values.tolist(),
            "units": {k: ds[k].attrs["units"] for k in ("velocity", *ds.data_vars)},
            "results": {
                str(n): {k: np.asarray(ds[k].values[i]).tolist() for k in ds.data_vars}
                for i, n in enumerate(ds["model"].values)
            },
        }
        if lines is not None:
            doc["dem_lines"] = lines
        write_json(doc)
    else:
        print("\n".join(_describe(ds)))
        print()
        print(format_table(ds))
        if bool(ds["large_strain"].values.any()):
            print("* contact radius above 0.3 R*: outside the seed's small-strain range")
        if lines is not None:
            if not lines:
                from .. import models

                dem = ", ".join(models.dem_models())
                print(f"\nno DEM law compared: no input lines (--model with one of {dem})")
            for name, texts in lines.items():
                for code, text in texts.items():
                    print(f"\n# ---- {name}: {'LAMMPS' if code == 'lammps' else 'LIGGGHTS-PUBLIC'} input lines")
                    print(text)
        written = [str(p) for p in (out, args.plot) if p is not None]
        if written:
            print(f"wrote {', '.join(written)}")
    return 0


# ------------------------------------------------------------------ --tangential


def format_tangential_table(ds) -> str:
    """The tangential comparison as an aligned text table, one row per law and angle."""
    header = ["law", "angle [deg]", "e_t", "spin [rad/s]", "angle' [deg]", "contact angle' [deg]", "F", "regime"]
    rows = [header]
    for i, name in enumerate(ds["tangential"].values):
        for j, a in enumerate(ds["angle"].values):

            def v(k, fmt):
                return _f(float(ds[k].values[i, j]), fmt)

            rows.append(
                [
                    str(name),
                    f"{a:.4g}",
                    v("tangential_restitution", "{:.5f}"),
                    v("rebound_spin", "{:.5g}"),
                    v("rebound_angle", "{:.4f}"),
                    v("contact_rebound_angle", "{:.4f}"),
                    v("impulse_ratio", "{:.5f}"),
                    str(ds["regime"].values[i, j]),
                ]
            )
    widths = [max(len(r[k]) for r in rows) for k in range(len(header))]
    lines = [
        "  ".join(c.ljust(w) if k in (0, 7) else c.rjust(w) for k, (c, w) in enumerate(zip(r, widths))) for r in rows
    ]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(line.rstrip() for line in lines)


def run_tangential(args) -> int:
    """``compare --tangential``: :func:`microimpact.compare.compare_tangential` as a table, JSON, file, figure."""
    from .. import oblique as ob
    from ._common import PAIR_OPTIONS, refuse_together

    given = [d for d in _NORMAL_ONLY if getattr(args, d) not in (None, False, [])]
    if given:
        raise ValueError(
            f"--{given[0].replace('_', '-')} and --tangential cannot be used together "
            f"(--{given[0].replace('_', '-')} would be ignored)"
        )
    laws = parse_tangential(args.tangential, ob.TANGENTIAL_MODELS)
    if len(args.velocities) > 1:
        raise ValueError(
            f"--tangential takes one resultant speed V, got {len(args.velocities)}: {' '.join(args.velocities)}"
        )
    out = pathlib.Path(args.out) if args.out else None
    if out is not None and out.suffix.lower() not in (".nc", ".csv"):
        raise ValueError(f"--out must end in .nc (NetCDF) or .csv, got {args.out!r}")
    check_outputs(files=[out], figures=[args.plot])
    check_distinct_paths(outputs=[("--out", out), ("--plot", args.plot)])
    if args.alumina:
        refuse_together(args, ("alumina",), tuple(PAIR_OPTIONS))
        pair = ob.alumina_pair()
        nu, V, mu = None, ob.ALUMINA_CASE["velocity"], ob.ALUMINA_CASE["friction"]  # kappa: alumina and glass
    else:
        pair = pair_from_args(args)
        nu, V, mu = None, None, 0.3
    if args.velocities:
        V = parse_float(args.velocities[0], "velocity")
    if V is None:
        raise ValueError("--tangential needs the resultant impact speed V (or --alumina)")
    check_velocity("velocity", V)
    if not V > 0.0:
        raise ValueError(f"velocity must be positive (no impact at 0), got {V!r}")
    if args.friction is not None:
        mu = parse_float(args.friction, "friction")
    if args.poisson is not None:
        nu = parse_float(args.poisson, "poisson")
    if nu is None and (pair.particle is None or pair.surface is None):
        nu = 0.3  # the seed's value for both bodies, as microimpact oblique takes it
    angles = parse_values(args.angles or "0:85:18", "angles", bytes_per_value=BYTES_PER_SPEED * len(laws))
    spin = 0.0 if args.spin is None else parse_float(args.spin, "spin")

    from ..compare import compare_tangential

    ds = compare_tangential(pair, V, angles, mu, laws, poisson_ratio=nu, spin=spin)
    if out is not None:
        from ..sweep import sweep_to_csv, sweep_to_netcdf

        (sweep_to_netcdf if out.suffix.lower() == ".nc" else sweep_to_csv)(ds, out)
    if args.plot:
        from ..figures.oblique import plot_tangential_comparison
        from ..io import save_figure

        axes = plot_tangential_comparison(ds, measured=args.alumina)
        save_figure(axes[0].figure, args.plot, dpi=300)
    if args.json:
        doc = {
            "pair": str(ds.attrs["pair"]),
            "velocity": V,
            "friction": mu,
            "spin": spin,
            "kappa": ds.attrs["kappa"],
            "angle": ds["angle"].values.tolist(),
            "units": {k: ds[k].attrs["units"] for k in ds.data_vars if "units" in ds[k].attrs},
            "results": {
                str(n): {k: np.asarray(ds[k].values[i]).tolist() for k in ds.data_vars}
                for i, n in enumerate(ds["tangential"].values)
            },
        }
        write_json(doc)
    else:
        print(f"pair: {ds.attrs['pair']}")
        print(
            f"  V = {V:g} m/s, mu = {mu:g}, spin = {spin:g} rad/s, kappa = 4G*/E* = {ds.attrs['kappa']:.6g}, "
            f"V_y = {float(pair.yield_velocity):.6g} m/s"
        )
        print(
            "  F = |J_t|/(mu J_n); angle' and contact angle' are the rebound angles of the centre and the contact point"
        )
        print()
        print(format_tangential_table(ds))
        written = [str(p) for p in (out, args.plot) if p is not None]
        if written:
            print(f"wrote {', '.join(written)}")
    return 0
