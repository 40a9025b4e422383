"""What every part of the paper's reproduction shares: the seed, its two cases and the figures' inputs."""

from __future__ import annotations

from ..materials import PAPER_CASES
from ..pair import ContactPair

#: Where ``microimpact paper`` writes when no directory is given (relative to the working directory).
DEFAULT_OUT_DIR = "microimpact-paper"
#: Relative difference up to which a computed value "agrees" with the paper's.
TOLERANCE = 0.01

#: The seed paper, as the report and the CSV files name it.
SEED = (
    "Dynamic impact model of plastic deformation between micro-particles and flat surfaces "
    "without adhesion, Aerosol Science and Technology 50(4):321-330 (2016)"
)

# Parameters of the paper's figures (the paper's Section 3).
FIG3_PRESSURES = (50e6, 100e6, 150e6, 200e6, 250e6)  # p_y [Pa]
FIG4_MODULI = (1.2e9, 6.2e9, 11.2e9, 16.2e9, 21.2e9)  # particle E1 [Pa]
FIG4_SURFACE = {"surface_modulus": 150e9, "particle_poisson": 0.3, "surface_poisson": 0.3}
FIG5_DENSITIES = (1350.0, 2350.0, 3350.0, 4350.0, 5350.0)  # [kg/m^3]
FIG6_VELOCITIES = (30.0, 50.0, 70.0)  # [m/s]
FIG7_VELOCITY = 70.0
FIG10_VELOCITY = 50.0
FIG9_MAX_VELOCITY = 120.0  # top of the paper's speed range [m/s]


def silicon():
    return ContactPair.paper_case("silicon")


def mica():
    return ContactPair.paper_case("mica")


def case(name, key):
    return PAPER_CASES[name][key]


#: The figures :func:`~microimpact.paper.reproduce` makes: ``(stem, title, caption)``; stems are the file names.
FIGURES: list[tuple[str, str, str]] = [
    (
        "fig02",
        "restitution vs impact velocity",
        "Coefficient of restitution against impact speed (eq. 27) for NH4Fl particles (d = 4.9 um) on silicon "
        "and mica.",
    ),
    (
        "fig03",
        "energy loss vs limiting contact pressure",
        "Fraction of kinetic energy lost (eq. 29) for p_y = 50-250 MPa, silicon case otherwise.",
    ),
    (
        "fig04",
        "energy loss vs particle modulus",
        "Fraction of energy lost for particle moduli E1 = 1.2-21.2 GPa on a surface of E2 = 150 GPa (nu = 0.3 both).",
    ),
    (
        "fig05",
        "energy loss vs particle density",
        "Fraction of energy lost for particle densities 1350-5350 kg/m^3, silicon case otherwise.",
    ),
    (
        "fig06",
        "force vs approach at 30, 50, 70 m/s",
        "Contact force against approach: loading (Hertz then plastic, eqs. 2, 8) and elastic unloading (eq. 10); "
        "triangles mark the plastic approaches (eq. 11).",
    ),
    (
        "fig07",
        "force vs time at 70 m/s, elastic-plastic vs elastic",
        "Contact force against time at 70 m/s: the elastic-plastic impact, the equivalent elastic impact "
        "(p_y = inf) and the Hertz force at the elastic-plastic approach during loading.",
    ),
    (
        "fig08",
        "maximum approach and plastic share vs impact velocity",
        "Maximum approach alpha* (eq. 22) and the plastic share alpha_p/alpha* against impact speed.",
    ),
    (
        "fig09",
        "contact times vs impact velocity",
        "Stage times t1, t2, loading t_L, unloading t_U and contact time t_c (closed form), with Deresiewicz's "
        "elastic contact time (eq. 30) and Ning's loading time (eq. 31).",
    ),
    (
        "fig10",
        "velocity, force and approach vs time at 50 m/s",
        "Approach velocity, contact force and approach against time for one impact at 50 m/s (closed-form history).",
    ),
]
