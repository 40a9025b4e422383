"""``microimpact history``: one impact's time history as CSV (and a plot like the seed's Fig. 10)."""

from __future__ import annotations

import sys

import numpy as np

from ._common import add_pair_arguments, pair_from_args, parse_float


def register(sub) -> None:
    p = sub.add_parser(
        "history",
        help="time history of one impact (approach, velocity, force, stage) as CSV, optionally plotted",
        description="Approach, approach velocity, contact force and stage from first contact to separation "
        "for one impact, evaluated in closed form (or by integrating Newton's equation with --method ode). "
        "Writes CSV with units in the header; --plot draws velocity, force and approach against time "
        "(seed Fig. 10).",
    )
    p.add_argument("velocity", metavar="V", help="impact speed [m/s]")
    add_pair_arguments(p)
    p.add_argument(
        "--n",
        default="1001",
        metavar="N",
        help="number of points spaced uniformly from contact to separation (default 1001; "
        "the stage boundaries are added)",
    )
    p.add_argument("--out", "-o", default="-", metavar="FILE.csv", help="CSV file to write (default: stdout)")
    p.add_argument("--plot", metavar="FILE.png", help="also draw the history to this image (png, pdf, svg)")
    p.add_argument(
        "--hertz",
        action="store_true",
        help="in the plot, also draw the Hertz force of the same approach during loading (Fig. 7)",
    )
    p.add_argument(
        "--method",
        choices=["closed", "ode"],
        default="closed",
        help="closed form (default) or numerical integration of Newton's equation (cross-check)",
    )
    p.set_defaults(func=run)


def _count(text: str) -> int:
    try:
        n = int(text)
    except (TypeError, ValueError):
        raise ValueError(f"--n must be an integer >= 2, got {text!r}") from None
    if n < 2:
        raise ValueError(f"--n must be an integer >= 2, got {n}")
    return n


def run(args) -> int:
    V = parse_float(args.velocity, "velocity")
    n = _count(args.n)
    pair = pair_from_args(args)
    history = pair.history(V, n=n, method=args.method)
    if args.plot:
        from ..figures.history import plot_history

        axes = plot_history(history, show_hertz=args.hertz)
        fig = axes[0].figure
        fig.savefig(args.plot, dpi=300)
        import matplotlib.pyplot as plt

        plt.close(fig)
    if args.out == "-":
        history.to_csv(sys.stdout)
    else:
        history.to_csv(args.out)
        print(
            f"wrote {len(history)} points ({args.method}) to {args.out}: t_c = {history.contact_time * 1e9:.5g} ns, "
            f"P* = {history.max_force:.5g} N, V_r = {history.rebound_velocity:.5g} m/s"
            + (f"; plot in {args.plot}" if args.plot else "")
        )
    if bool(np.any(pair.impact(V, warn=False).large_strain)):
        print("warning: the contact radius exceeds 0.3 R*: outside the model's small-strain range", file=sys.stderr)
    return 0
