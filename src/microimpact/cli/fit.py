"""``microimpact fit``: fit the limiting contact pressure (or k, E*, density) to measured restitution,
or rank several models on the same data (``--models``)."""

from __future__ import annotations

import argparse
import sys
import warnings

from .._optional import require
from ..fitting import (
    FREE_PARAMETERS,
    INTERVALS,
    LOSSES,
    FitWarning,
    available_models,
    fit_restitution,
    rank_models,
)
from ..io import load_restitution_csv, save_figure, write_json
from ..materials import PAPER_CASES, get_material
from ._common import (
    add_pair_arguments,
    check_distinct_paths,
    check_input_file,
    check_outputs,
    pair_from_args,
    parse_float,
    parse_model_params,
    parse_names,
)
from ._stdout import encodable_stdout


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
        default=None,
        metavar="NAME",
        help=f"free parameter: one of {', '.join(FREE_PARAMETERS)} (default limiting_pressure)",
    )
    p.add_argument(
        "--models",
        metavar="A,B,C",
        help="rank these models on the data (AIC, AICc, BIC, Akaike weights, K-fold CV): each a model name "
        "(free p_y), NAME:PARAM+PARAM (those free) or NAME:none (nothing fitted); models: "
        + ", ".join(available_models()),
    )
    p.add_argument(
        "--param",
        action="append",
        default=[],
        metavar="MODEL:NAME=VALUE",
        help="with --models: a model parameter's value (its start value where NAME is fitted), as in compare, "
        "e.g. --param MODEL:restitution=0.7 (repeat for more)",
    )
    p.add_argument("--folds", default="5", metavar="K", help="folds of the cross-validation with --models (default 5)")
    p.add_argument(
        "--interval",
        default="auto",
        choices=INTERVALS,
        help="confidence intervals: wald, profile, or auto (profile when fewer than 10 points lie above V_y)",
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
    p.set_defaults(func=encodable_stdout(run))


def fit_pair(args, free):
    """The pair from the options; a provisional p_y when none is known (the fit starts from the data)."""
    if (
        args.particle
        and args.surface
        and args.limiting_pressure is None
        and args.yield_strength is None
        and free in ("limiting_pressure", "yield_velocity")
    ):
        known = [get_material(m).yield_strength for m in (args.particle, args.surface)]
        if not any(known):  # a reference value only: the fitted p_y does not depend on it (args is not changed)
            return pair_from_args(argparse.Namespace(**{**vars(args), "limiting_pressure": 1e8}))
    return pair_from_args(args)


def fit_yield_strength(args):
    """``Y`` [Pa] for a fit of ``k``: the option, the paper case's, or None (the materials')."""
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


def _rank(args, data, pair, f_scale_given, confidence) -> int:
    velocity, restitution, sigma = data
    if args.free is not None:
        raise ValueError("--free and --models conflict: name each model's free parameters as NAME:PARAM+PARAM")
    if args.fig2:
        raise ValueError("--fig2 and --models conflict: --fig2 draws one fitted model")
    if f_scale_given:
        raise ValueError("--f-scale and --models conflict: each model's fit sets its own scale")
    try:
        folds = int(args.folds)
    except ValueError:
        raise ValueError(f"--folds must be an integer, got {args.folds!r}") from None
    if folds < 2:
        raise ValueError(f"--folds must be >= 2, got {folds}")
    specs = _model_specs(args.models, args.param)
    with warnings.catch_warnings(record=True) as caught, _cli_words(specs):
        warnings.simplefilter("always", FitWarning)
        ranking = rank_models(
            velocity,
            restitution,
            pair,
            specs,
            sigma=sigma,
            loss=args.loss,
            k_folds=folds,
            confidence=confidence,
            yield_strength=fit_yield_strength(args),
            absolute_sigma=False if args.relative_sigma else None,
            line_numbers=data.lines,
        )
    if args.plot:
        plt = require("matplotlib.pyplot", "--plot")
        from ..figures.fit import plot_models

        ax, _ = plot_models(ranking)
        try:
            save_figure(ax.figure, args.plot, dpi=200)
        finally:
            plt.close(ax.figure)
    if args.json:
        doc = {"data": args.data, **ranking.to_dict()}
        if args.plot:
            doc["plot"] = args.plot
        write_json(doc)  # NaN/inf -> null: always valid JSON
    else:
        print(f"data: {args.data} ({len(velocity)} points{', with sigma' if sigma is not None else ''})")
        print(ranking.table())
        for row in ranking.rows:
            print()
            print(f"[{row['label']}]")
            print(ranking.fits[row["label"]].summary())
        if args.plot:
            print(f"plot written to {args.plot}")
    report_warnings(caught)
    if ranking.caveat and args.json:
        print("caveat: " + ranking.caveat, file=sys.stderr)
    return 0


def _model_specs(models, params):
    """``--models`` as rank_models specs, each with the values ``--param MODEL:NAME=VALUE`` gives its model."""
    texts = parse_names(models, "--models")
    names = [t.partition(":")[0].strip() for t in texts]  # checked by rank_models
    values = parse_model_params(params, sorted(set(names))) if params else {}
    specs = []
    for text, name in zip(texts, names):
        if name in values:
            rest = text.partition(":")[2].strip()
            free = () if rest.lower() == "none" else tuple(r.strip() for r in rest.split("+")) if rest else None
            spec = {"model": name, "model_params": dict(values[name]), "label": text}
            if free is not None:
                spec["params"] = free
            specs.append(spec)
        else:
            specs.append(text)
    return specs


class _cli_words:
    """Say ``--param MODEL:NAME=VALUE`` where the library's message says ``model_params={...}``."""

    def __init__(self, specs):
        self.models = [s["model"] if isinstance(s, dict) else s.partition(":")[0].strip() for s in specs]

    def __enter__(self):
        return self

    def __exit__(self, kind, exc, tb):
        import re

        if kind is not None and issubclass(kind, ValueError) and "model_params=" in str(exc):
            from ..models import parameters

            def option(m):
                name = m.group(1)
                model = next((x for x in self.models if name in parameters(x)), "MODEL")
                return f"give --param {model}:{name}=VALUE"

            raise ValueError(re.sub(r"give model_params=\{'(\w+)': \.\.\.\}", option, str(exc))) from None
        return False


def report_warnings(caught) -> None:
    """Each distinct recorded warning once on stderr."""
    seen = set()
    for w in caught:
        text = str(w.message)
        if text not in seen:
            seen.add(text)
            print(f"warning: {text}", file=sys.stderr)


def run(args) -> int:
    check_input_file(args.data, "data")  # errors name the file (missing, a directory, binary)
    check_outputs(figures=[args.plot, args.fig2])  # before fitting: nothing computed for an unwritable path
    check_distinct_paths(inputs=[("data", args.data)], outputs=[("--plot", args.plot), ("--fig2", args.fig2)])
    data = load_restitution_csv(args.data)
    velocity, restitution, sigma = data
    f_scale = None if args.f_scale is None else parse_float(args.f_scale, "--f-scale")
    confidence = parse_float(args.confidence, "--confidence")
    if args.param and not args.models:
        raise ValueError("--param sets the parameters of the models of --models (the single fit is the seed's)")
    if args.models:
        pair = fit_pair(args, "limiting_pressure")
        return _rank(args, data, pair, f_scale is not None, confidence)
    free = parse_names(args.free or "limiting_pressure", "--free")
    pair = fit_pair(args, free[0] if free else "")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", FitWarning)
        fit = fit_restitution(
            velocity,
            restitution,
            pair,
            sigma=sigma,
            params=free,
            loss=args.loss,
            f_scale=f_scale,
            confidence=confidence,
            interval=args.interval,
            yield_strength=fit_yield_strength(args) if "k" in free else None,
            absolute_sigma=False if args.relative_sigma else None,
            line_numbers=data.lines,
        )
    if args.plot:
        plt = require("matplotlib.pyplot", "--plot")
        from ..figures.fit import plot_fit

        ax, _ = plot_fit(fit, velocity, restitution)
        ax.set_title(f"{data.source}: {fit.pair.label}", fontsize="medium")
        try:
            save_figure(ax.figure, args.plot, dpi=200)
        finally:
            plt.close(ax.figure)
    if args.fig2:
        plot_fig2(fit, data, args.fig2)
    if args.json:
        doc = {"data": args.data, **fit.to_dict(lists=False)}  # residuals written a block at a time
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
    report_warnings(caught)
    return 0
