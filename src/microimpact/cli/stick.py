"""``microimpact stick``: capture (sticking) velocity against particle diameter for one pair, as a
table, JSON, CSV and a stick/bounce map."""

from __future__ import annotations

import argparse
import math

import numpy as np

from ..io import write_csv, write_json
from ..quantities import QUANTITIES
from ..quantities import header as heading
from ._common import (
    add_pair_arguments,
    check_distinct_paths,
    check_outputs,
    pair_from_args,
    parse_float,
    parse_model_params,
    parse_names,
    parse_values,
)
from ._stdout import encodable_stdout

#: Memory per diameter [bytes]: a few result arrays and the text.
BYTES_PER_DIAMETER = 400
DEFAULT_DIAMETERS = "5e-8,1e-7,2e-7,5e-7,1e-6,2e-6,5e-6,1e-5,2e-5"


def register(sub) -> None:
    from ..stick import ADHESION_LAWS, FULL_LAW, adhesion_laws

    p = sub.add_parser(
        "stick",
        help="capture (sticking) velocity against particle diameter: additive rule and Thornton & Ning's whole law",
        description="The impact speed at and below which a particle sticks, over particle diameters, for "
        "Thornton & Ning's (1998) additive rule (the seed's plastic loss plus the elastic adhesive one) and "
        f"their whole adhesive elastic-plastic law ({FULL_LAW}), with each law's "
        "yield velocity. The pair's E*, p_y and density are kept and the particle resized. Diameters [m]: "
        "numbers, comma lists or ranges start:stop:count.",
    )
    p.add_argument("diameters", nargs="*", metavar="D", help=f"particle diameter(s) [m] (default: {DEFAULT_DIAMETERS})")
    p.add_argument(
        "--work-of-adhesion",
        "-G",
        required=True,
        metavar="J/M2",
        help="work of adhesion G [J/m^2] (2x a surface energy)",
    )
    p.add_argument(
        "--law",
        default=",".join(ADHESION_LAWS),
        metavar="NAME[,NAME]",
        help=f"the laws, comma-separated, among {', '.join(adhesion_laws())} (default: {','.join(ADHESION_LAWS)})",
    )
    p.add_argument(
        "--param",
        action="append",
        default=[],
        metavar="LAW:NAME=VALUE",
        help="a parameter of a law other than its adhesion input, which -G sets (repeat for more; LAW: may be "
        "left out when one law is named)",
    )
    add_pair_arguments(p)
    o = p.add_argument_group("output")
    o.add_argument("--json", action="store_true", help="print JSON (SI units) instead of a table")
    o.add_argument("--out", metavar="FILE.csv", help="also write the table to a CSV file")
    o.add_argument("--plot", metavar="FILE", help="also draw the stick/bounce map to this image (png, pdf, svg)")
    p.set_defaults(func=encodable_stdout(run))


def _laws(text):
    from ..stick import adhesion_laws

    names = parse_names(text, "--law")
    for n in names:
        if n not in adhesion_laws():
            raise ValueError(f"--law must name laws among {', '.join(adhesion_laws())}; got {n!r}")
    if len(set(names)) != len(names):
        raise ValueError(f"--law names a law more than once: {text!r}")
    return names


def _f(x, fmt="{:.5g}"):
    return "nan" if math.isnan(x) else ("inf" if math.isinf(x) else fmt.format(x))


def format_table(res, laws) -> str:
    """The capture velocities as an aligned text table, one row per diameter."""
    return "\n".join(table_lines(res, laws))


#: Rows of the table formatted at once (:func:`table_lines`).
_ROWS = 1 << 14


def table_lines(res, laws):
    """The lines of :func:`format_table`, one at a time: the column widths are found in a first pass
    over the rows and each row formatted again when written, so no text of the whole table is held
    (a million diameters made some 5 million strings)."""
    header = [heading("diameter")]
    from ..stick import FULL_LAW

    for law in laws:
        short = {"additive": "additive", FULL_LAW: "whole law"}.get(law, law)
        header += [f"V_s {short} [m/s]", f"V_y {short} [m/s]"]
    widths = [len(h) for h in header]
    for rows in _row_blocks(res, laws):
        for row in rows:
            widths = [max(w, len(c)) for w, c in zip(widths, row)]
    yield "  ".join(c.rjust(w) for c, w in zip(header, widths))
    yield "  ".join("-" * w for w in widths)
    for rows in _row_blocks(res, laws):
        for row in rows:
            yield "  ".join(c.rjust(w) for c, w in zip(row, widths))


def _row_blocks(res, laws):
    """The table's cells, :data:`_ROWS` rows at a time (lists of lists of str)."""
    n = len(res["diameter"])
    for start in range(0, n, _ROWS):
        stop = min(start + _ROWS, n)
        columns = [[f"{d * 1e6:.4g}" for d in res["diameter"][start:stop].tolist()]]
        for law in laws:
            for q in ("capture_velocity", "yield_velocity"):
                columns.append([_f(x) for x in np.asarray(res[law][q][start:stop], dtype=float).tolist()])
        yield [list(row) for row in zip(*columns)]


def run(args) -> int:
    d = parse_values(args.diameters or [DEFAULT_DIAMETERS], "diameter", bytes_per_value=BYTES_PER_DIAMETER, unique=True)
    if not np.all(np.isfinite(d) & (d > 0.0)):
        raise ValueError(f"diameter must be positive and finite, got {float(d[~(np.isfinite(d) & (d > 0.0))][0])!r}")
    G = parse_float(args.work_of_adhesion, "--work-of-adhesion")
    if not (G >= 0.0 and math.isfinite(G)):
        raise ValueError(f"--work-of-adhesion must be non-negative and finite, got {G!r}")
    laws = _laws(args.law)
    from ..stick import ADDITIVE_RULE, ADHESION_LAWS

    if any(t.split("=")[0].strip().rpartition(":")[0].strip() == ADDITIVE_RULE for t in args.param):
        raise ValueError("--param: the additive rule takes no parameters beyond --work-of-adhesion")
    params = parse_model_params(args.param, [n for n in laws if n != ADDITIVE_RULE]) if args.param else None
    check_outputs(files=[args.out], figures=[args.plot])
    check_distinct_paths(outputs=[("--out", args.out), ("--plot", args.plot)])
    if args.out is not None and not str(args.out).lower().endswith(".csv"):
        raise ValueError(f"--out must end in .csv, got {args.out!r}")
    pair_args = args  # the particle is resized to every diameter: the positional ones size the pair too
    if (args.particle or args.surface) and args.radius is None and args.diameter is None:
        pair_args = argparse.Namespace(**{**vars(args), "diameter": float(d[0])})
    pair = pair_from_args(pair_args)
    if pair.density is None:
        raise ValueError("stick needs a sphere-on-flat pair with a particle density")
    from ..stick import capture_velocities, parting_diameter

    res = capture_velocities(pair, d, G, laws, params)
    both = sorted(laws) == sorted(ADHESION_LAWS)  # the comparison the parting diameter is made for
    part = parting_diameter(pair, G, 1.1, lo=1e-9, hi=1e-3) if both else math.nan
    if args.plot:
        from ..figures.stick import plot_stick_map
        from ..io import save_figure

        lo, hi = float(d.min()), float(d.max())
        if hi <= lo:
            lo, hi = lo / 3.0, hi * 3.0
        axes = plot_stick_map(pair, G, diameter=np.geomspace(lo, hi, 120), laws=laws, params=params)
        import matplotlib.pyplot as plt

        try:
            save_figure(axes[0].figure, args.plot, dpi=300)
        finally:
            plt.close(axes[0].figure)
    if args.out is not None:
        cols = [("diameter", QUANTITIES["diameter"].unit, res["diameter"])]
        for law in laws:
            cols += [(f"{q}_{law}", QUANTITIES[q].unit, res[law][q]) for q in ("capture_velocity", "yield_velocity")]
        write_csv(
            args.out,
            cols,
            comments=[f"pair: {pair.label}", f"work_of_adhesion = {G!r} J/m^2", "microimpact stick"],
        )
    if args.json:
        write_json(
            {
                "pair": {
                    "label": pair.label,
                    "effective_modulus": pair.effective_modulus,
                    "limiting_pressure": pair.limiting_pressure,
                    "density": pair.density,
                },
                "work_of_adhesion": G,
                "units": {
                    q: QUANTITIES[q].unit
                    for q in ("diameter", "capture_velocity", "yield_velocity", "parting_diameter")
                },
                "diameter": res["diameter"],
                "laws": {law: {k: res[law][k] for k in ("capture_velocity", "yield_velocity")} for law in laws},
                "parting_diameter": part,
            }
        )
    else:
        print(
            f"pair: {pair.label}; E* = {pair.effective_modulus:.6g} Pa, p_y = {pair.limiting_pressure:.6g} Pa, "
            f"density {pair.density:.6g} kg/m^3; G = {G:g} J/m^2"
        )
        print("the particle sticks at and below V_s (V_y = 0: the contact yields at any speed)")
        print()
        for line in table_lines(res, laws):
            print(line)
        if both:
            print()
            print(
                "the capture velocities part by more than 10 % below d = "
                + (f"{part:.4g} m" if math.isfinite(part) else "(nowhere between 1 nm and 1 mm)")
            )
        written = [str(p) for p in (args.out, args.plot) if p is not None]
        if written:
            print(f"wrote {', '.join(written)}")
    return 0
