"""``microimpact dem-check``: run a calibrated DEM law in the installed LAMMPS or LIGGGHTS and compare."""

from __future__ import annotations

import math

import numpy as np

from .. import models
from ..quantities import header
from ._common import (
    add_pair_arguments,
    check_pair_options,
    pair_from_args,
    parse_float,
    parse_values,
)
from ._stdout import encodable_stdout


def register(sub) -> None:
    p = sub.add_parser(
        "dem-check",
        help="run a calibrated DEM law in the installed LAMMPS or LIGGGHTS and compare e and t_c",
        description="Bounce check for DEM users: calibrate MODEL to the seed's model (or take its "
        "parameters from --param), write a one-impact deck with the printed input lines, run it in "
        "the installed code at each speed and print the law's e and contact time against the measured "
        "ones, with the time step used against the contact time; for a law that captures particles, "
        "the capture velocity the code gives beside the law's.",
    )
    laws = models.dem_line_models()  # the laws with DEM lines (their faces; nothing heavy imported)
    p.add_argument("model", choices=laws, metavar="MODEL", help=f"the DEM law: {', '.join(laws)}")
    p.add_argument("--code", required=True, choices=("lammps", "liggghts"), help="the DEM code to run")
    p.add_argument("--speeds", nargs="+", metavar="V", help="impact speeds [m/s] (default: 10,30,100)")
    p.add_argument("--reference-velocity", metavar="M/S", help="calibration speed [m/s] (default: the median speed)")
    p.add_argument(
        "--param",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="the law's parameters instead of a calibration (give all of them; e.g. stiffness=1000)",
    )
    p.add_argument(
        "--geometry", choices=("wall", "sphere"), default="wall", help="sphere on wall (default) or two spheres"
    )
    p.add_argument("--steps-per-contact", metavar="N", help="time steps per contact time (default 5000)")
    p.add_argument("--time-step", metavar="S", help="time step [s] (instead of --steps-per-contact)")
    add_pair_arguments(p)
    p.set_defaults(func=encodable_stdout(run))


def _calibration(args, pair, V):
    from ..calibrate import Calibration, calibrate
    from ..models import parameters

    if args.param:
        known = parameters(args.model)
        given = {}
        for text in args.param:
            name, eq, value = str(text).partition("=")
            name = name.strip()
            if not eq or name not in known:
                raise ValueError(f"--param must be NAME=VALUE with NAME one of {', '.join(known)}; got {text!r}")
            given[name] = parse_float(value, f"--param {name}")
        return Calibration.of(pair, args.model, given, V)
    if args.model not in models.dem_models():
        raise ValueError(f"model {args.model!r} has no calibration: give its parameters with --param")
    ref = (
        float(np.median(V))
        if args.reference_velocity is None
        else parse_float(args.reference_velocity, "--reference-velocity")
    )
    if not (math.isfinite(ref) and ref > pair.yield_velocity):
        raise ValueError(
            f"--reference-velocity must be finite and above the yield velocity {pair.yield_velocity:.6g} m/s "
            f"(the seed's e is 1 below it), got {ref!r}; or give the law's parameters with --param"
        )
    return calibrate(pair, args.model, ref, **models.face(args.model).COMPARE_OPTIONS)


def run(args) -> int:
    from .. import dem

    check_pair_options(args)
    V = parse_values(args.speeds or ["10,30,100"], "--speeds", unique=True)
    if not np.all((V > 0.0) & np.isfinite(V)):
        raise ValueError(f"--speeds must be positive and finite, got {float(V[~((V > 0) & np.isfinite(V))][0])!r}")
    if args.time_step is not None and args.steps_per_contact is not None:
        raise ValueError("give --time-step or --steps-per-contact, not both")
    dt = None if args.time_step is None else parse_float(args.time_step, "--time-step")
    n = 5000
    if args.steps_per_contact is not None:
        x = parse_float(args.steps_per_contact, "--steps-per-contact")
        if not (math.isfinite(x) and x == int(x) and x >= 20):
            raise ValueError(f"--steps-per-contact must be an integer >= 20, got {args.steps_per_contact!r}")
        n = int(x)
    exe = dem.find_code(args.code)
    if exe is None:
        raise ValueError(f"--code {args.code}: not installed here ({dem.INSTALL[args.code]})")
    pair = pair_from_args(args)
    cal = _calibration(args, pair, V)
    for v in V:  # every deck is checked before anything runs: a step the box or a run's length cannot hold
        try:
            dem.deck(cal, args.code, float(v), geometry=args.geometry, time_step=dt, steps_per_contact=n)
        except ValueError as exc:
            msg = str(exc)
            for name, option in (("time_step", "--time-step"), ("steps_per_contact", "--steps-per-contact")):
                if msg.startswith(name + " "):
                    raise ValueError(f"{option} {msg[len(name) + 1 :]} (at --speeds {float(v):g})") from None
            raise
    rows = dem.check(cal, args.code, V, geometry=args.geometry, time_step=dt, steps_per_contact=n, executable=exe)
    print(pair.describe())
    print(f"{cal.model}: {', '.join(f'{k} = {v:.10g}' for k, v in cal.as_dict().items())}")
    print(f"{rows[0]['version']}, {'sphere on a flat wall' if args.geometry == 'wall' else 'two equal spheres'}")
    print()
    head = f"{header('velocity'):>8s} {'e law':>10s} {'e run':>10s} {'diff':>9s} {'t_c law [s]':>12s} {'t_c run [s]':>12s} {'diff':>9s} {'dt [s]':>10s} {'t_c/dt':>8s}"
    print(head)
    worst = 0.0
    for r in rows:
        law_kept = not math.isfinite(r["predicted_contact_time"])
        if law_kept or r["captured"]:  # a captured particle has no e to compare: say who kept it
            e_law, t_law = ("captured", "") if law_kept else (f"{r['predicted_restitution']:.6f}", "")
            e_run = "captured" if r["captured"] else f"{r['restitution']:.6f}"
            same = "same" if law_kept == r["captured"] else "DIFFERS"
            print(
                f"{r['velocity']:8.4g} {e_law:>10s} {e_run:>10s} {same:>9s} {t_law:>12s} {'':>12s} {'':>9s} "
                f"{r['time_step']:10.3e} {r['steps_per_contact']:8.0f}"
            )
            if law_kept != r["captured"]:
                worst = math.inf
            continue
        de = r["restitution"] / r["predicted_restitution"] - 1.0
        dtc = r["contact_time"] / r["predicted_contact_time"] - 1.0
        worst = max(worst, abs(de), abs(dtc))
        print(
            f"{r['velocity']:8.4g} {r['predicted_restitution']:10.6f} {r['restitution']:10.6f} {de:+9.1e} "
            f"{r['predicted_contact_time']:12.5e} {r['contact_time']:12.5e} {dtc:+9.1e} {r['time_step']:10.3e} "
            f"{r['steps_per_contact']:8.0f}"
        )
    print()
    if math.isinf(worst):
        print("the code and the law disagree on capture at a speed above (see the rows marked DIFFERS)")
    else:
        print(
            f"largest relative difference {worst:.1e}; for the damped laws both codes' error falls as the "
            "step, below about t_c/dt steps^-1 for e >= 0.3 (see ContactPair.dem_time_step)"
        )
    if dem.capture_velocity(cal) > 0.0:
        c = dem.capture(cal, args.code, geometry=args.geometry, steps_per_contact=n, time_step=dt, executable=exe)
        lo, hi = c["bracket"]
        print(
            f"capture velocity: the law's {c['capture_velocity']:.6g} m/s; {args.code} keeps the particle at "
            f"{lo:.6g} m/s and lets it go at {hi:.6g} m/s"
            + (
                f" (the law's to {dem.CAPTURE_REL:g})"
                if c["agrees"]
                else f": its capture velocity {c['measured_capture_velocity']:.6g} m/s, "
                f"{c['measured_capture_velocity'] / c['capture_velocity'] - 1.0:+.2e} relative to the law's"
            )
            + f"; {c['runs']} runs at time step {c['time_step']:.3e} s"
        )
    return 0
