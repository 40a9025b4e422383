"""``microimpact export``: restitution tables (CSV) and a C99 wall function for CFD codes."""

from __future__ import annotations

from ..adhesion import work_of_adhesion
from ..cexport import DEFAULT_VS_OVER_VY, write_c_source, write_tables
from ._common import add_pair_arguments, pair_from_args, parse_float, parse_values


def register(sub) -> None:
    p = sub.add_parser(
        "export",
        help="restitution tables (CSV) and a C99 bounce/stick function for Fluent/OpenFOAM",
        description="Write (a) e against V/V_y with V_s/V_y as a parameter, (b) per-diameter tables of "
        "(normal speed [m/s], restitution, stuck), and (c) microimpact_wall.c, a self-contained C99 "
        "function giving the outgoing velocity, spin and stick flag of one particle at a wall "
        "(seed model + Thornton-Ning adhesion + Coulomb friction).",
    )
    p.add_argument("--out", default="microimpact_export", metavar="DIR", help="output directory (default: %(default)s)")
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
    diameters = parse_values(args.diameters, "diameters") if args.diameters else None
    if (args.particle or args.surface) and args.radius is None and args.diameter is None and diameters is not None:
        args.diameter = float(diameters[0])
    pair = pair_from_args(args)
    if args.surface_energy is not None:
        gammas = parse_values(args.surface_energy, "surface-energy")
        if gammas.size > 2:
            raise ValueError(f"surface-energy takes one or two values, got {gammas.size}")
        G = float(work_of_adhesion(gammas[0], gammas[-1]))
    else:
        G = parse_float(args.work_of_adhesion, "work-of-adhesion")
    mu = parse_float(args.friction, "friction")
    velocities = parse_values(args.velocities, "velocities") if args.velocities else None
    vs = parse_values(args.vs_over_vy, "vs-over-vy") if args.vs_over_vy else DEFAULT_VS_OVER_VY
    written = write_tables(args.out, pair, diameters, velocities, work_of_adhesion=G, vs_over_vy_values=vs)
    if not args.no_c:
        written.append(write_c_source(f"{args.out}/microimpact_wall.c", pair, work_of_adhesion=G, friction=mu))
    print(pair.describe())
    print(f"  work of adhesion G = {G:.6g} J/m^2, friction mu = {mu:.6g}")
    for path in written:
        print(f"wrote {path}")
    return 0
