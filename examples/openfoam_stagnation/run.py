"""OpenFOAM tracks the particles, microimpact decides at the wall: deposition on an impinging-jet plate.

``python run.py [OUTDIR] [--gas-density RHO] [--work-of-adhesion G] [--particles P] [--keep]``

1. ``case.py`` writes the case (a stagnation-point flow ``u = (a x/2, a y/2, -a z)`` on a blockMesh
   box, particles released at ``z = H`` with the gas velocity) and runs ``blockMesh``,
   ``setExprFields``, ``setExprBoundaryFields`` and ``icoUncoupledKinematicParcelFoam``, whose
   ``patchPostProcessing`` records every hit on the plate.
2. :func:`microimpact.openfoam.read_patch_hits` reads the hits, :func:`microimpact.openfoam.decide`
   decides bounce or stick for each (the seed's model with Thornton & Ning's adhesion, NH4Fl on
   silicon), :func:`microimpact.openfoam.deposition_report` counts per size.
3. The same flow in :func:`microimpact.deposition.simulate_deposition` (closed-form flights with
   Stokes drag, first impact decides, Cunningham's correction off as in OpenFOAM's drag) gives the
   estimate at the same Stokes numbers; the table shows both and their difference.

Writes ``OUTDIR/deposition.csv`` (the table), ``OUTDIR/deposition.nc`` (the report, NetCDF),
``OUTDIR/deposition.png`` (the figure) and ``OUTDIR/timings.json``; the case stays in
``OUTDIR/case`` with ``--keep``.
"""

from __future__ import annotations

import argparse
import csv
import json
import shutil
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import case as of_case  # noqa: E402

import microimpact.deposition as dep  # noqa: E402
from microimpact import openfoam  # noqa: E402


def estimate(p, work_of_adhesion):
    """``simulate_deposition`` for the case's flow, first impact only, Stokes drag without slip correction."""
    res = dep.simulate_deposition(
        np.asarray(p["diameters"]),
        p["jet_speed"],
        height=p["height"],
        jet_radius=0.5 * p["height"],
        plate_radius=1.5 * p["height"],
        n_particles=p["particles"],
        density=p["particle_density"],
        material="nh4fl",
        wall="silicon",
        work_of_adhesion=work_of_adhesion,
        max_impacts=1,
        viscosity=p["gas_viscosity"],
        mean_free_path=1e-30,  # C_c = 1: OpenFOAM's drag has no slip correction
    )
    return res


def run(
    outdir,
    *,
    gas_density=1.2,
    work_of_adhesion=1.0,
    particles=20,
    diameters=None,
    keep=False,
):
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    casedir = out / "case"
    if casedir.exists():
        shutil.rmtree(casedir)
    p = dict(of_case.DEFAULTS, gas_density=gas_density, particles=particles)
    if diameters is not None:
        p["diameters"] = tuple(float(d) for d in diameters)
    t0 = time.perf_counter()
    of_case.write_case(casedir, p)
    timings = of_case.run_case(casedir)
    t1 = time.perf_counter()
    hits = openfoam.read_patch_hits(casedir / "postProcessing")
    decision = openfoam.decide(
        hits,
        (0.0, 0.0, 1.0),
        material="nh4fl",
        wall="silicon",
        work_of_adhesion=work_of_adhesion,
    )
    injected = {float(d): float(particles) for d in p["diameters"]}
    ds = openfoam.deposition_report(hits, decision, injected)
    ref = estimate(p, work_of_adhesion)
    ds["estimate_deposition_fraction"] = (
        "diameter",
        ref.deposited_fraction[0],
        {"units": "1", "long_name": "simulate_deposition, first impact"},
    )
    ds["estimate_impact_fraction"] = (
        "diameter",
        ref.impacted_fraction[0],
        {"units": "1", "long_name": "simulate_deposition, impacted"},
    )
    ds["estimate_impact_speed"] = (
        "diameter",
        ref.first_impact_speed[0],
        {"units": "m/s", "long_name": "simulate_deposition, first impact speed"},
    )
    ds["stokes_number"] = (
        "diameter",
        ref.stokes_number[0],
        {"units": "1", "long_name": "a tau, tau = rho d^2/(18 mu)"},
    )
    ds.attrs.update(
        gas_density=gas_density,
        work_of_adhesion=work_of_adhesion,
        jet_speed=p["jet_speed"],
        height=p["height"],
        openfoam="OpenFOAM ESI v1912 icoUncoupledKinematicParcelFoam (sphereDrag), patchPostProcessing",
    )
    t2 = time.perf_counter()
    from microimpact.sweep import sweep_to_netcdf

    sweep_to_netcdf(ds, out / "deposition.nc")
    with open(out / "deposition.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(
            [
                "diameter [m]",
                "stokes_number [-]",
                "impacted OpenFOAM [-]",
                "impacted estimate [-]",
                "deposited OpenFOAM+microimpact [-]",
                "deposited estimate [-]",
                "difference [-]",
                "mean impact speed OpenFOAM [m/s]",
                "impact speed estimate [m/s]",
            ]
        )
        for k, d in enumerate(ds["diameter"].values):
            a, b = (
                float(ds["deposition_fraction"][k]),
                float(ds["estimate_deposition_fraction"][k]),
            )
            w.writerow(
                [
                    repr(float(d)),
                    f"{float(ds['stokes_number'][k]):.4f}",
                    f"{float(ds['impact_fraction'][k]):.3f}",
                    f"{float(ds['estimate_impact_fraction'][k]):.3f}",
                    f"{a:.3f}",
                    f"{b:.3f}",
                    f"{a - b:+.3f}",
                    f"{float(ds['mean_impact_speed'][k]):.4f}",
                    f"{float(ds['estimate_impact_speed'][k]):.4f}",
                ]
            )
    import matplotlib

    matplotlib.use("Agg")
    axes = openfoam.plot_report(
        ds,
        reference=(
            ds["diameter"].values,
            ds["estimate_deposition_fraction"].values,
            "stagnation-flow estimate (microimpact.deposition)",
        ),
    )
    axes[0].figure.savefig(out / "deposition.png", dpi=150)
    timings.update(total_openfoam=t1 - t0, microimpact=t2 - t1)
    (out / "timings.json").write_text(json.dumps(timings, indent=1))
    if not keep:
        shutil.rmtree(casedir)
    return ds, timings


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("outdir", nargs="?", default="openfoam_deposition")
    ap.add_argument(
        "--gas-density",
        type=float,
        default=1.2,
        help="gas density [kg/m^3] (default 1.2, air)",
    )
    ap.add_argument(
        "--work-of-adhesion", type=float, default=1.0, help="G [J/m^2] (default 1.0)"
    )
    ap.add_argument(
        "--particles", type=int, default=20, help="particles per size (default 20)"
    )
    ap.add_argument("--keep", action="store_true", help="keep the OpenFOAM case")
    args = ap.parse_args(argv)
    ds, timings = run(
        args.outdir,
        gas_density=args.gas_density,
        work_of_adhesion=args.work_of_adhesion,
        particles=args.particles,
        keep=args.keep,
    )
    print(Path(args.outdir, "deposition.csv").read_text())
    print("timings [s]: " + ", ".join(f"{k} {v:.2f}" for k, v in timings.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
