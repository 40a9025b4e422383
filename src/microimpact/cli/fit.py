"""``microimpact fit``: fit the limiting contact pressure (or k, E*, density) to measured restitution."""

from __future__ import annotations

import sys

from .._optional import require
from ..fitting import FREE_PARAMETERS, LOSSES, fit_restitution, load_restitution_csv, plot_fit
from ..io import save_figure, write_json
from ..materials import PAPER_CASES, get_material
from ._common import add_pair_arguments, check_input_file, check_outputs, pair_from_args, parse_float


def register(sub) -> None:
    p = sub.add_parser(
        "fit",
        help="fit the limiting contact pressure (or k, E*, density) to measured restitution data",
        description="Fit one parameter of the contact pair to a CSV of impact speeds [m/s] and "
        "restitution coefficients (columns velocity|V|speed, restitution|e, optional sigma|e_err|"
        "uncertainty; '#' starts a comment). Prints the estimate with its standard error and "
        "confidence interval. Restitution data determine only the yield velocity, so exactly one "
        "parameter can be free.",
    )
    p.add_argument("data", metavar="DATA.csv", help="measured impact speeds and restitution coefficients")
    add_pair_arguments(p)
    p.add_argument(
        "--free",
        default="limiting_pressure",
        metavar="NAME",
        help=f"free parameter: one of {', '.join(FREE_PARAMETERS)} (default limiting_pressure)",
    )
    p.add_argument(
        "--loss",
        default="linear",
        choices=LOSSES,
        help="least-squares loss; soft_l1, huber, cauchy, arctan limit outliers (default linear)",
    )
    p.add_argument(
        "--f-scale",
        metavar="X",
        help="residual size where a robust loss starts to down-weight (units of e, or of sigma)",
    )
    p.add_argument("--confidence", default="0.95", metavar="P", help="confidence level (default 0.95)")
    p.add_argument(
        "--relative-sigma",
        action="store_true",
        help="treat the sigma column as relative weights (scale by the reduced chi-square)",
    )
    p.add_argument("--plot", metavar="FIT.png", help="write a plot of data, fit, confidence band and residuals")
    p.add_argument(
        "--fig2", metavar="FILE.png", help="also draw the fitted curve with the data in the layout of the seed's Fig. 2"
    )
    p.add_argument("--json", action="store_true", help="print JSON (SI units) instead of text")
    p.set_defaults(func=run)


def _fit_pair(args, free):
    """The pair from the options; a provisional p_y when none is known (the fit starts from the data)."""
    if (
        args.particle
        and args.surface
        and args.limiting_pressure is None
        and args.yield_strength is None
        and free in ("limiting_pressure", "yield_velocity")
    ):
        known = [get_material(m).yield_strength for m in (args.particle, args.surface)]
        if not any(known):
            args.limiting_pressure = 1e8  # only a reference value: the fitted p_y does not depend on it
    return pair_from_args(args)


def _yield_strength(args):
    if args.yield_strength is not None:
        return args.yield_strength
    if not (args.particle or args.surface or args.effective_modulus is not None):
        return PAPER_CASES[args.case or "silicon"]["yield_strength"]
    return None


def plot_fig2(fit, data, path) -> None:
    """The fitted curve and the measurements in the layout of the seed's Fig. 2 (log speed axis)."""
    plt = require("matplotlib.pyplot", "--fig2")
    from ..figures.paper import plot_restitution

    name, value = next(iter(fit.params.items()))
    info = FREE_PARAMETERS[name]
    unit = f" {info['unit']}" if info["unit"] else ""
    label = f"fit, {info['tex']} = {value * info['scale']:.4g}{unit}"
    ax = plot_restitution({label: fit.pair}, {data.source or "data": (data.velocity, data.restitution)})
    try:
        save_figure(ax.figure, path, dpi=200)
    finally:
        plt.close(ax.figure)


def run(args) -> int:
    check_input_file(args.data, "data")  # errors name the file (missing, a directory, binary)
    check_outputs(figures=[args.plot, args.fig2])  # before fitting: nothing computed for an unwritable path
    free = [s.strip() for s in args.free.split(",") if s.strip()]
    data = load_restitution_csv(args.data)
    velocity, restitution, sigma = data
    pair = _fit_pair(args, free[0] if free else "")
    f_scale = None if args.f_scale is None else parse_float(args.f_scale, "--f-scale")
    confidence = parse_float(args.confidence, "--confidence")
    fit = fit_restitution(
        velocity,
        restitution,
        pair,
        sigma=sigma,
        params=free,
        loss=args.loss,
        f_scale=f_scale,
        confidence=confidence,
        yield_strength=_yield_strength(args) if "k" in free else None,
        absolute_sigma=False if args.relative_sigma else None,
        line_numbers=data.lines,
    )
    if args.plot:
        plt = require("matplotlib.pyplot", "--plot")
        ax, _ = plot_fit(fit, velocity, restitution)
        ax.set_title(f"{data.source}: {fit.pair.label}", fontsize="medium")
        try:
            save_figure(ax.figure, args.plot, dpi=200)
        finally:
            plt.close(ax.figure)
    if args.fig2:
        plot_fig2(fit, data, args.fig2)
    if args.json:
        doc = {"data": args.data, **fit.to_dict()}
        if args.plot:
            doc["plot"] = args.plot
        if args.fig2:
            doc["fig2"] = args.fig2
        write_json(doc)  # NaN/inf -> null: always valid JSON
    else:
        print(f"data: {args.data} ({fit.n_points} points{', with sigma' if sigma is not None else ''})")
        print(fit.pair.describe())
        print()
        print(fit.summary())
        for what, path in (("plot", args.plot), ("Fig. 2 layout", args.fig2)):
            if path:
                print(f"{what} written to {path}")
    if not fit.success:
        print(f"warning: the fit did not converge: {fit.message}", file=sys.stderr)
    return 0
