"""Write, mesh and run the OpenFOAM case of an impinging stagnation-point flow with particles.

``python case.py CASE_DIR [--jet-speed 10] [--height 1e-3] [--diameters 1.5e-6,...] [--particles 20]
[--gas-density 1.2] [--run]``

The gas: the inviscid axisymmetric stagnation-point flow onto a plate at ``z = 0``,
``u = (a x/2, a y/2, -a z)`` with ``a = U/H`` (the flow of :mod:`microimpact.deposition`), set on a
``blockMesh`` box ``[-1.5 H, 1.5 H]^2 x [0, 1.2 H]`` by ``setExprFields`` / ``setExprBoundaryFields``
(cells and boundary faces: the linear field is interpolated exactly). OpenFOAM's
``icoUncoupledKinematicParcelFoam`` tracks the particles through it (Putnam's ``sphereDrag``, no
gravity, one-way); each particle starts at ``z = H`` on the x axis at equal-area radii
``r_i = R_jet ((i + 1/2)/P)^(1/2)``, ``R_jet = H/2``, with the gas velocity there (one
``manualInjection`` per size and radius). Every hit on the plate is recorded by the
``patchPostProcessing`` cloud function and the particle leaves (``escape``): the first impact is
exact, what happens after it is for microimpact to decide (``microimpact.openfoam``).

``--run`` runs ``blockMesh``, ``setExprFields``, ``setExprBoundaryFields`` and the solver (each
logged to ``log.<name>`` in the case); the OpenFOAM executables must be on the PATH (Debian's
``apt-get install openfoam``; or source OpenFOAM's ``etc/bashrc``).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

HEADER = """FoamFile
{{
    version     2.0;
    format      ascii;
    class       {cls};
    location    "{loc}";
    object      {obj};
}}
"""

DEFAULTS = dict(
    jet_speed=10.0,  # m/s
    height=1e-3,  # m
    diameters=(
        1.5e-6,
        2e-6,
        2.4e-6,
        2.6e-6,
        2.8e-6,
        3e-6,
        3.25e-6,
        3.5e-6,
        3.75e-6,
        4e-6,
        4.5e-6,
        5e-6,
        6e-6,
        7e-6,
        8.5e-6,
        10e-6,
    ),  # m
    particles=20,
    particle_density=1350.0,  # kg/m^3 (NH4Fl, as microimpact.deposition's default)
    gas_density=1.2,  # kg/m^3
    gas_viscosity=1.81e-5,  # Pa s
    cells=(30, 30, 24),
)


def _file(path, cls, obj, body):
    path.parent.mkdir(parents=True, exist_ok=True)
    loc = path.parent.name
    path.write_text(HEADER.format(cls=cls, loc=loc, obj=obj) + body + "\n")


def write_case(case, p):
    """Write every file of the case into the new directory ``case`` for the parameters ``p``."""
    case = Path(case)
    case.mkdir(parents=True, exist_ok=False)
    H, U = p["height"], p["jet_speed"]
    a = U / H
    L, Z = 1.5 * H, 1.2 * H
    nx, ny, nz = p["cells"]
    _file(
        case / "system" / "blockMeshDict",
        "dictionary",
        "blockMeshDict",
        f"""convertToMeters 1;
vertices ( ({-L!r} {-L!r} 0) ({L!r} {-L!r} 0) ({L!r} {L!r} 0) ({-L!r} {L!r} 0)
           ({-L!r} {-L!r} {Z!r}) ({L!r} {-L!r} {Z!r}) ({L!r} {L!r} {Z!r}) ({-L!r} {L!r} {Z!r}) );
blocks ( hex (0 1 2 3 4 5 6 7) ({nx} {ny} {nz}) simpleGrading (1 1 1) );
edges ();
boundary
(
    plate {{ type wall; faces ( (0 3 2 1) ); }}
    top {{ type patch; faces ( (4 5 6 7) ); }}
    sides {{ type patch; faces ( (0 1 5 4) (1 2 6 5) (2 3 7 6) (3 0 4 7) ); }}
);
mergePatchPairs ();""",
    )
    end = 20.0 / a
    dt = 0.01 / a
    _file(
        case / "system" / "controlDict",
        "dictionary",
        "controlDict",
        f"""application icoUncoupledKinematicParcelFoam;
startFrom startTime; startTime 0; stopAt endTime; endTime {end!r}; deltaT {dt!r};
writeControl runTime; writeInterval {end!r}; purgeWrite 0; writeFormat ascii; writePrecision 12;
writeCompression off; timeFormat general; timePrecision 8; runTimeModifiable no;""",
    )
    _file(
        case / "system" / "fvSchemes",
        "dictionary",
        "fvSchemes",
        """ddtSchemes { default none; }
gradSchemes { default none; }
divSchemes { default none; }
laplacianSchemes { default none; }
interpolationSchemes { default linear; }
snGradSchemes { default none; }""",
    )
    _file(case / "system" / "fvSolution", "dictionary", "fvSolution", "solvers {}")
    expr = f"vector({a / 2!r}*pos().x(), {a / 2!r}*pos().y(), {-a!r}*pos().z())"
    _file(
        case / "system" / "setExprFieldsDict",
        "dictionary",
        "setExprFieldsDict",
        f"""expressions
(
    U {{ field U; dimensions [0 1 -1 0 0 0 0]; expression #{{ {expr} #}}; }}
);""",
    )
    patches = "\n".join(
        f"        {{ patch {name}; target value; expression #{{ {expr} #}}; }}"
        for name in ("plate", "top", "sides")
    )
    _file(
        case / "system" / "setExprBoundaryFieldsDict",
        "dictionary",
        "setExprBoundaryFieldsDict",
        f"flow\n{{\n    field U;\n    expressions\n    (\n{patches}\n    );\n}}",
    )
    bf = "\n".join(
        f"    {n} {{ type fixedValue; value uniform (0 0 0); }}"
        for n in ("plate", "top", "sides")
    )
    _file(
        case / "0" / "U",
        "volVectorField",
        "U",
        f"dimensions [0 1 -1 0 0 0 0];\ninternalField uniform (0 0 0);\nboundaryField\n{{\n{bf}\n}}",
    )
    _file(
        case / "constant" / "g",
        "uniformDimensionedVectorField",
        "g",
        "dimensions [0 1 -2 0 0 0 0];\nvalue (0 0 0);",
    )
    _file(
        case / "constant" / "transportProperties",
        "dictionary",
        "transportProperties",
        f"rhoInf {p['gas_density']!r};\ntransportModel Newtonian;\nnu {p['gas_viscosity'] / p['gas_density']!r};",
    )
    _file(
        case / "constant" / "turbulenceProperties",
        "dictionary",
        "turbulenceProperties",
        "simulationType laminar;",
    )
    # one injector per size and start radius: each starts with the gas velocity at its position
    P = int(p["particles"])
    R_jet = 0.5 * H
    radii = [R_jet * math.sqrt((i + 0.5) / P) for i in range(P)]
    injectors = []
    for i, r in enumerate(radii):
        (case / "constant" / f"positions_{i}").write_text(
            HEADER.format(cls="vectorField", loc="constant", obj=f"positions_{i}")
            + f"(\n({r!r} 0 {H!r})\n)\n"
        )
    for j, d in enumerate(p["diameters"]):
        for i, r in enumerate(radii):
            injectors.append(
                f"""        d{j}_r{i}
        {{
            type manualInjection; massTotal {p["particle_density"] * math.pi / 6 * d**3!r}; parcelBasisType fixed;
            nParticle 1; SOI 0; positionsFile "positions_{i}"; U0 ({a / 2 * r!r} 0 {-a * H!r});
            sizeDistribution {{ type fixedValue; fixedValueDistribution {{ value {d!r}; }} }}
        }}"""
            )
    _file(
        case / "constant" / "kinematicCloudProperties",
        "dictionary",
        "kinematicCloudProperties",
        f"""solution
{{
    active true; coupled false; transient yes; cellValueSourceCorrection off; maxCo 0.1;
    sourceTerms {{ schemes {{ }} }}
    interpolationSchemes {{ rho cell; U cellPoint; mu cell; }}
    integrationSchemes {{ U analytical; }}
}}
constantProperties {{ rho0 {p["particle_density"]!r}; youngsModulus 1e9; poissonsRatio 0.3; }}
subModels
{{
    particleForces {{ sphereDrag; }}
    injectionModels
    {{
{chr(10).join(injectors)}
    }}
    dispersionModel none;
    patchInteractionModel localInteraction;
    localInteractionCoeffs {{ patches ( plate {{ type escape; }} top {{ type escape; }} sides {{ type escape; }} ); }}
    surfaceFilmModel none;
    stochasticCollisionModel none;
    collisionModel none;
}}
cloudFunctions
{{
    patchPostProcessing1 {{ type patchPostProcessing; maxStoredParcels 1000000; patches ( plate ); }}
}}""",
    )
    (case / "case.json").write_text(
        json.dumps(
            {
                **{k: (list(v) if isinstance(v, tuple) else v) for k, v in p.items()},
                "strain_rate": a,
                "jet_radius": R_jet,
                "plate_radius": L,
                "start_radii": radii,
                "injected_per_diameter": P,
            },
            indent=1,
        )
    )
    return case


#: Where OpenFOAM's environment script may be (Debian's package, OpenCFD's packages); $FOAM_BASHRC first.
BASHRCS = (
    "/usr/share/openfoam/etc/bashrc",
    "/usr/lib/openfoam/openfoam1912/etc/bashrc",
    "/usr/lib/openfoam/openfoam/etc/bashrc",
)


def foam_bashrc():
    """OpenFOAM's ``etc/bashrc`` to source before running its tools (None: the environment is set already)."""
    if os.environ.get("WM_PROJECT_DIR"):
        return None
    for cand in (os.environ.get("FOAM_BASHRC"), *BASHRCS):
        if cand and Path(cand).is_file():
            return cand
    return None


def run_case(case):
    """Run the OpenFOAM steps in ``case``; returns ``{step: seconds}``."""
    case = Path(case)
    times = {}
    bashrc = foam_bashrc()
    for step in (
        ["blockMesh"],
        ["setExprFields"],
        ["setExprBoundaryFields"],
        ["icoUncoupledKinematicParcelFoam"],
    ):
        exe = shutil.which(step[0])
        if exe is None:
            raise RuntimeError(
                f"{step[0]} is not on the PATH: install OpenFOAM (apt-get install openfoam)"
            )
        cmd = [exe, "-case", str(case)]
        if (
            bashrc is not None
        ):  # as the Debian package documents: source the environment first
            cmd = [
                "bash",
                "-c",
                f'. "{bashrc}" >/dev/null 2>&1; exec "$@"',
                "foam",
                *cmd,
            ]
        t = time.perf_counter()
        with open(case / f"log.{step[0]}", "w") as log:
            proc = subprocess.run(
                cmd, stdout=log, stderr=subprocess.STDOUT, env={**os.environ}
            )
        times[step[0]] = time.perf_counter() - t
        if proc.returncode != 0:
            tail = (case / f"log.{step[0]}").read_text().strip().splitlines()[-8:]
            raise RuntimeError(
                f"{step[0]} failed ({proc.returncode}):\n" + "\n".join(tail)
            )
    return times


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("case", help="case directory to create (must not exist)")
    ap.add_argument("--jet-speed", type=float, default=DEFAULTS["jet_speed"])
    ap.add_argument("--height", type=float, default=DEFAULTS["height"])
    ap.add_argument(
        "--diameters", default=",".join(repr(d) for d in DEFAULTS["diameters"])
    )
    ap.add_argument("--particles", type=int, default=DEFAULTS["particles"])
    ap.add_argument("--gas-density", type=float, default=DEFAULTS["gas_density"])
    ap.add_argument("--run", action="store_true", help="also mesh and run it")
    args = ap.parse_args(argv)
    p = dict(DEFAULTS)
    p.update(
        jet_speed=args.jet_speed,
        height=args.height,
        diameters=tuple(float(x) for x in args.diameters.split(",")),
        particles=args.particles,
        gas_density=args.gas_density,
    )
    case = write_case(args.case, p)
    print(f"wrote {case}")
    if args.run:
        for step, s in run_case(case).items():
            print(f"{step}: {s:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
