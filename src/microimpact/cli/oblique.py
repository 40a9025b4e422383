"""``microimpact oblique``: tangential restitution, rebound spin and angle against the impact angle."""

from __future__ import annotations

import json
import math
import sys

import numpy as np

from ..quantities import column
from ._common import (
    PAIR_OPTIONS,
    add_pair_arguments,
    check_outputs,
    pair_from_args,
    parse_float,
    parse_tangential,
    parse_values,
    refuse_together,
)
from ._stdout import encodable_stdout


def register(sub) -> None:
    p = sub.add_parser(
        "oblique",
        help="oblique impacts: tangential restitution, rebound spin and angle against the impact angle",
        description="Rebound of a sphere hitting a flat obliquely at speed V: the seed's normal restitution, and "
        "the tangential outcome of the compliant model (Mindlin no-slip tangential spring with a Coulomb limit, "
        "along the seed's normal history) and of the rigid-body Coulomb model, for each impact angle. "
        "--alumina uses the published alumina case: the sphere of Kharaz et al. (2001) on their glass anvil "
        "(microimpact.oblique.alumina_pair).",
    )
    p.add_argument("velocity", metavar="V", nargs="?", help="resultant impact speed [m/s] (default 3.9 with --alumina)")
    add_pair_arguments(p)
    p.add_argument(
        "--alumina",
        action="store_true",
        help="the alumina sphere on the glass anvil (E, nu, rho, r, mu, V; glass E, nu)",
    )
    p.add_argument(
        "--angles",
        default="0:85:18",
        metavar="DEG",
        help="impact angles from the normal [deg]: list or start:stop:count (default 0:85:18)",
    )
    p.add_argument("--friction", metavar="MU", help="Coulomb friction coefficient (default 0.3; 0.092 with --alumina)")
    p.add_argument("--poisson", metavar="NU", help="Poisson's ratio for G* (default: from the pair's materials)")
    p.add_argument("--spin", default="0", metavar="RAD/S", help="incoming spin, positive adding to the slip")
    p.add_argument(
        "--tangential",
        default="both",
        metavar="LAWS",
        help="tangential model(s), comma-separated: mindlin, rigid, lammps_mindlin, lammps_mindlin_force, "
        "lammps_mindlin_rescale, lammps_mindlin_rescale_force, lammps_linear_history, liggghts_history, "
        "di_renzo_di_maio, mindlin_deresiewicz, stronge; 'both' = mindlin,rigid (default), 'all' = every one",
    )
    p.add_argument(
        "--tangential-stiffness",
        metavar="N/M",
        help="lammps_linear_history: constant tangential stiffness [N/m] (default 8 G* a_m of each impact)",
    )
    p.add_argument(
        "--work-of-adhesion",
        metavar="G",
        help="work of adhesion G [J/m^2]: the normal contact becomes the adhesive law --adhesion (default the "
        "whole adhesive elastic-plastic law of Thornton & Ning 1998, the wall interaction's), integrated with the tangential law; each impact is classified as bounce, stick, "
        "captured rolling or captured sliding (microimpact.oblique.adhesive)",
    )
    p.add_argument(
        "--adhesion",
        metavar="MODEL",
        help="the adhesive normal law for --work-of-adhesion (default the whole adhesive elastic-plastic law)",
    )
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.add_argument("--plot", metavar="FILE.png", help="also draw the three curves to this image")
    p.set_defaults(func=encodable_stdout(run))


def _rows(out):
    return {
        column("angle"): out.angle,
        "psi": out.normalized_angle,
        "e_n": out.normal_restitution,
        "e_t": out.tangential_restitution,
        "spin_rad_s": out.rebound_spin,
        "rebound_angle_deg": out.rebound_angle,
        "contact_rebound_angle_deg": out.contact_rebound_angle,
        "regime": out.regime,
    }


def _adhesive_rows(out):
    return {
        column("angle"): out.angle,
        "e_n": out.normal_restitution,
        "e_t": out.tangential_restitution,
        "v_t_m_s": out.tangential_velocity,
        "spin_rad_s": out.rebound_spin,
        "outcome": out.outcome,
    }


def _json_value(v):
    v = v.item() if hasattr(v, "item") else v
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def run(args) -> int:
    from .. import oblique as ob

    if args.alumina:
        # the published case fixes the pair: a pair option beside it would be ignored
        refuse_together(args, ("alumina",), tuple(PAIR_OPTIONS))
        pair = ob.alumina_pair()  # on glass: kappa from both materials
        nu = None
        V = ob.ALUMINA_CASE["velocity"]
        mu = ob.ALUMINA_CASE["friction"]
    else:
        pair = pair_from_args(args)
        nu, V, mu = None, None, 0.3
    if args.velocity is not None:
        V = parse_float(args.velocity, "velocity")
    if V is None:
        raise ValueError("give the impact speed V (or --alumina)")
    if args.friction is not None:
        mu = parse_float(args.friction, "friction")
    if args.poisson is not None:
        nu = parse_float(args.poisson, "poisson")
    if nu is None and (pair.particle is None or pair.surface is None):
        nu = 0.3  # the seed's value for both bodies
    angles = parse_values(args.angles, "angles")
    spin = parse_float(args.spin, "spin")
    models = parse_tangential(args.tangential, ob.TANGENTIAL_MODELS)
    check_outputs(figures=[args.plot])
    k_lin = None
    if args.tangential_stiffness is not None:
        if "lammps_linear_history" not in models:
            raise ValueError("--tangential-stiffness is used by --tangential lammps_linear_history only")
        k_lin = parse_float(args.tangential_stiffness, "tangential-stiffness")
    adhesive = {}
    if args.work_of_adhesion is not None or args.adhesion is not None:
        G = None if args.work_of_adhesion is None else parse_float(args.work_of_adhesion, "work-of-adhesion")
        adhesive = {"work_of_adhesion": G, "adhesion": args.adhesion}
        if args.plot:
            raise ValueError(
                "--plot draws the non-adhesive curves: use microimpact.figures.oblique_adhesive for a capture map"
            )
        bad = [m for m in models if m in ("mindlin_deresiewicz", "stronge")]
        if bad:
            raise ValueError(f"--work-of-adhesion: tangential {bad[0]} is not integrated with an adhesive normal law")
    results = {
        m: ob.oblique_impact(
            pair,
            V,
            angles,
            mu,
            poisson_ratio=nu,
            tangential=m,
            spin=spin,
            **({"tangential_stiffness": k_lin} if m == "lammps_linear_history" and k_lin is not None else {}),
            **adhesive,
        )
        for m in models
    }
    rows_of = {m: (_rows if isinstance(out, ob.ObliqueImpact) else _adhesive_rows) for m, out in results.items()}
    kappa = next((float(out.kappa) for out in results.values() if hasattr(out, "kappa")), None)
    if kappa is None:  # adhesive results carry no kappa: the pair's own
        kappa = ob.stiffness_ratio_of(pair, nu) if any(m != "rigid" for m in models) else math.nan
    if args.json:
        doc = {
            "velocity": V,
            "friction": mu,
            "kappa": kappa,
            "yield_velocity": float(pair.yield_velocity),
            "models": {
                m: {k: [_json_value(x) for x in np.ravel(v)] for k, v in rows_of[m](out).items()}
                for m, out in results.items()
            },
        }
        print(json.dumps(doc, indent=1))
    else:
        print(
            f"# oblique impacts at V = {V:g} m/s, mu = {mu:g}, kappa = 4G*/E* = {kappa:.4g}, "
            f"V_y = {float(pair.yield_velocity):.4g} m/s"
        )
        for m, out in results.items():
            print(f"# tangential model: {m}")
            rows = rows_of[m](out)
            width = [max(len(k), 11) for k in rows]
            print("  ".join(f"{k:>{w}s}" for k, w in zip(rows, width)))
            for i in range(out.angle.size):
                cells = []
                for v, w in zip(rows.values(), width):
                    x = v[i]
                    cells.append(f"{x:>{w}s}" if isinstance(x, str) else f"{float(x):>{w}.5g}")
                print("  ".join(cells))
    if args.plot:
        from ..figures.oblique import oblique_data, plot_oblique

        table = oblique_data(None if args.alumina else pair, velocity=V, friction=mu, poisson_ratio=nu, models=models)
        axes = plot_oblique(None if args.alumina else pair, table=table, measured=args.alumina)
        fig = axes[0].figure
        from ..io import save_figure

        save_figure(fig, args.plot, dpi=300)
        import matplotlib.pyplot as plt

        plt.close(fig)
        print(f"# plot in {args.plot}", file=sys.stderr)
    if any(bool(np.any(getattr(out, "large_strain", False))) for out in results.values()):
        print("warning: the contact radius exceeds 0.3 R*: outside the model's small-strain range", file=sys.stderr)
    return 0
