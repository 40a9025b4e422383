"""``microimpact history``: one impact's time history as CSV (and a plot like the seed's Fig. 10)."""

from __future__ import annotations

import math
import sys
import warnings

import numpy as np

from .._validation import check_velocity
from ..io import check_memory
from ._common import (
    add_model_arguments,
    add_pair_arguments,
    check_distinct_paths,
    check_outputs,
    pair_from_args,
    parse_float,
    parse_model_params,
    parse_models,
    show_progress,
)
from ._stdout import encodable_stdout


def register(sub) -> None:
    p = sub.add_parser(
        "history",
        help="time history of one impact (approach, velocity, force, stage) as CSV, optionally plotted",
        description="Approach, approach velocity, contact force and stage from first contact to separation "
        "for one impact, evaluated in closed form where the model has one, as the seed's (or by integrating "
        "Newton's equation with --method ode; the other models, --model, are integrated with their own force law). "
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
        default=None,
        help="closed form (the default where the model has one: the seed's) or numerical integration of "
        "Newton's equation (a cross-check; the only way for the other models)",
    )
    add_model_arguments(p, many=False)
    p.add_argument(
        "--quiet", "-q", action="store_true", help="no progress bar (shown for long histories on a terminal)"
    )
    p.set_defaults(func=encodable_stdout(run))


def _count(text: str) -> int:
    try:
        n = int(text)
    except (TypeError, ValueError):
        raise ValueError(f"--n must be an integer >= 2, got {text!r}") from None
    if n < 2:
        raise ValueError(f"--n must be an integer >= 2, got {n}")
    return n


#: Memory per history point [bytes]: five float64 columns, the stage evaluation's temporaries
#: (about 25 arrays of the same length) and the plot's copies.
BYTES_PER_POINT = 400


def _history(pair, V, n, method, model, params):
    """The history, refusing speeds where double precision under- or overflows (no numpy warnings leak)."""
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        history = pair.history(V, n=n, method=method, model=model, **params)
    cols = [history.time, history.approach, history.approach_velocity, history.force]
    scalars = [history.contact_time, history.max_force, history.rebound_velocity, history.max_approach]
    finite = all(bool(np.all(np.isfinite(c))) for c in cols) and all(math.isfinite(x) for x in scalars)
    if not finite or not history.contact_time > 0 or not history.max_approach > 0:
        raise ValueError(
            f"velocity {V:g} m/s is outside the range a time history can be computed in double precision "
            "(the approach, force or times under- or overflow); give a speed between about 1e-30 and 1e30 m/s"
        )
    return history


def run(args) -> int:
    V = parse_float(args.velocity, "velocity")
    check_velocity("velocity", V)
    if not V > 0:
        raise ValueError(f"velocity must be positive for a history (no contact at 0), got {V!r}")
    n = _count(args.n)
    from .. import models

    names = parse_models(args.model) or [models.DEFAULT]  # ValueError naming the models when unknown
    if len(names) != 1:
        raise ValueError(f"--model: a history is of one model, got {args.model!r}")
    name = names[0]
    module = models.get(name)
    params = parse_model_params(args.param, [name]).get(name, {})
    models.resolve_params(module, params)  # every input checked before anything is written
    if args.method == "closed" and models.face(module.NAME).closed_form_history is None:
        raise ValueError(f"--method closed: {module.NAME} has no closed-form history; it is integrated (--method ode)")
    if args.hertz and not args.plot:
        raise ValueError("--hertz draws into the plot: give --plot FILE.png with it")
    out = None if args.out == "-" else args.out
    check_outputs(files=[out], figures=[args.plot])
    check_distinct_paths(outputs=[("--out", out), ("--plot", args.plot)])
    check_memory(n * BYTES_PER_POINT, f"--n {n}", "give a smaller --n")
    pair = pair_from_args(args)
    history = _history(pair, V, n, args.method, module.NAME, params)
    if args.plot:
        from ..figures.history import plot_history
        from ..io import save_figure

        axes = plot_history(history, show_hertz=args.hertz)
        fig = axes[0].figure
        import matplotlib.pyplot as plt

        try:
            save_figure(fig, args.plot, dpi=300)
        finally:
            plt.close(fig)
    progress = show_progress(args) and n >= 1_000_000
    if out is None:
        history.to_csv(sys.stdout, progress=progress)
    else:
        history.to_csv(out, progress=progress)
        method = history.method
        print(
            f"wrote {len(history)} points ({method}, {module.NAME}) to {args.out}: "
            f"t_c = {history.contact_time * 1e9:.5g} ns, "
            f"P* = {history.max_force:.5g} N, V_r = {history.rebound_velocity:.5g} m/s"
            + (f"; plot in {args.plot}" if args.plot else "")
        )
    if bool(np.any(pair.impact(V, warn=False, model=module.NAME, **params).large_strain)):
        print("warning: the contact radius exceeds 0.3 R*: outside the model's small-strain range", file=sys.stderr)
    return 0
