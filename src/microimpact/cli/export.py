"""``microimpact export``: restitution tables (CSV) and a C99 wall function for CFD codes."""

from __future__ import annotations

import math
from pathlib import Path

from ..adhesion import work_of_adhesion
from ..cexport import DEFAULT_VS_OVER_VY, write_c_source, write_tables
from ._common import add_pair_arguments, check_outputs, check_pair_options, pair_from_args, parse_float, parse_values


def register(sub) -> None:
    p = sub.add_parser(
        "export",
        help="restitution tables (CSV) and a C99 bounce/stick function for Fluent/OpenFOAM",
        description="Write (a) e against V/V_y with V_s/V_y as a parameter, (b) per-diameter tables of "
        "(normal speed [m/s], restitution, stuck), and (c) microimpact_wall.c, a self-contained C99 "
        "function giving the outgoing velocity, spin and stick flag of one particle at a wall "
        "(seed model + Thornton-Ning adhesion + Coulomb friction).",
    )
    p.add_argument(
        "--out",
        default="microimpact_export",
        metavar="DIR",
        help="output directory (default: %(default)s), written whole: built beside it and swapped into place "
        "when complete",
    )
    add_pair_arguments(p)
    g = p.add_mutually_exclusive_group()
    g.add_argument(
        "--work-of-adhesion",
        metavar="G",
        default="0",
        help="work of adhesion G [J/m^2] (= 2 gamma for identical surfaces; default 0: no adhesion)",
    )
    g.add_argument(
        "--surface-energy",
        metavar="GAMMA",
        help="surface energy per surface gamma [J/m^2] of particle and wall (one value, or "
        "gamma1,gamma2); G = 2 (gamma1 gamma2)^(1/2)",
    )
    p.add_argument("--friction", metavar="MU", default="0", help="Coulomb friction coefficient (default 0)")
    p.add_argument("--diameters", metavar="D", help="particle diameters [m], e.g. 1e-6,5e-6 (default: the pair's)")
    p.add_argument("--velocities", metavar="V", help="normal speeds [m/s] of the per-size tables, e.g. 0.01:200:400")
    p.add_argument(
        "--vs-over-vy",
        metavar="S",
        help=f"V_s/V_y columns of the dimensionless table (default {','.join(str(x) for x in DEFAULT_VS_OVER_VY)})",
    )
    p.add_argument("--no-c", action="store_true", help="do not write the C file")
    p.set_defaults(func=run)


def run(args) -> int:
    from .._validation import check_nonnegative, check_positive
    from ..io import atomic_directory

    check_pair_options(args)
    check_outputs(directories=[args.out])
    diameters = parse_values(args.diameters, "--diameters") if args.diameters else None
    if diameters is not None:
        check_positive("--diameters", diameters)
    if (args.particle or args.surface) and args.radius is None and args.diameter is None and diameters is not None:
        args.diameter = float(diameters[0])
    if args.surface_energy is not None:
        gammas = parse_values(args.surface_energy, "--surface-energy")
        if gammas.size > 2:
            raise ValueError(f"--surface-energy takes one or two values, got {gammas.size}")
        check_nonnegative("--surface-energy", gammas)
        G = float(work_of_adhesion(gammas[0], gammas[-1]))
    else:
        G = parse_float(args.work_of_adhesion, "--work-of-adhesion")
    mu = parse_float(args.friction, "--friction")
    # checked whether or not the C file is written (--no-c): no option is silently ignored
    for name, value in (("--work-of-adhesion", G), ("--friction", mu)):
        check_nonnegative(name, value)
        if math.isinf(value):
            raise ValueError(f"{name} must be finite, got {value!r}")
    velocities = parse_values(args.velocities, "--velocities") if args.velocities else None
    if velocities is not None:
        check_nonnegative("--velocities", velocities)
    vs = parse_values(args.vs_over_vy, "--vs-over-vy") if args.vs_over_vy else DEFAULT_VS_OVER_VY
    check_nonnegative("--vs-over-vy", vs)
    pair = pair_from_args(args)
    if diameters is not None:
        rho = pair.density if pair.density is not None else float("nan")
        for d in diameters:
            try:
                m = 4.0 / 3.0 * math.pi * (0.5 * float(d)) ** 3 * rho
            except OverflowError:
                m = math.inf
            if not (m > 0 and math.isfinite(m)):
                raise ValueError(
                    f"--diameters {float(d):g} m is outside what double precision can model: the particle mass "
                    f"is {m:g} kg"
                )
    out = Path(args.out)
    with atomic_directory(out, owned=("restitution_*.csv", "microimpact_wall.c")) as tmp:
        written = write_tables(tmp, pair, diameters, velocities, work_of_adhesion=G, vs_over_vy_values=vs)
        if not args.no_c:
            written.append(write_c_source(tmp / "microimpact_wall.c", pair, work_of_adhesion=G, friction=mu))
    print(pair.describe())
    print(f"  work of adhesion G = {G:.6g} J/m^2, friction mu = {mu:.6g}")
    for path in written:
        print(f"wrote {out / Path(path).name}")
    return 0
