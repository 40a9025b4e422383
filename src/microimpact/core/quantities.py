"""The one table of quantities: name, unit, description and seed equation of every result and input.

Every place that labels a number reads it from here: :class:`~microimpact.pair.ImpactResult`'s
documentation, the CLI's table and JSON units, CSV headers, a sweep's attributes, history columns
and the figures' data columns. Units are UDUNITS strings (``"1"`` for dimensionless), as CF
conventions for NetCDF expect; text has ``""``. The display columns (symbol, display unit and
scale, format) label the CLI's table and the figures' axes, and the check column names what an
input must be. A new outcome field is one row here, and so is a model parameter that several
models share (a model's :class:`~microimpact.core.models.Parameter` takes its unit from its row).

Dimensionless is spelled one way in data, ``"1"`` (:data:`DIMENSIONLESS`), and one way where people
read it, ``"-"`` (``[-]``; :data:`DIMENSIONLESS_SHOWN`), the second derived from the first by
:func:`unit_text` (figures typeset it as a dash, :func:`tex_unit`).

Two spellings of a name, both derived here: the attribute name (``max_approach``) for attributes,
JSON keys, NetCDF variables and options, and the CSV column name with its SI unit as a suffix
(``max_approach_m``, :func:`column`) where a file carries no separate unit.
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = [
    "Quantity",
    "QUANTITIES",
    "OUTCOME_FIELDS",
    "FLAG_FIELDS",
    "HISTORY_FIELDS",
    "table",
    "label",
    "column",
    "columns",
    "header",
    "axis_label",
    "tex_unit",
    "unit_text",
    "DIMENSIONLESS",
    "DIMENSIONLESS_SHOWN",
]


class Quantity(NamedTuple):
    """One quantity: the row of every label, unit and display of one number.

    ``name`` is the attribute, column and option name (``max_approach``); ``unit`` the SI unit as
    a UDUNITS string (``"1"`` dimensionless, ``""`` for text); ``description`` a short phrase;
    ``equation`` the seed's equation number(s) (``""`` if none); ``symbol`` the plain-text symbol
    (``alpha*``) and ``tex`` the matplotlib one (``$\\alpha^*$``); ``display_unit`` the unit shown
    to people (``nm``; ``""``: the SI unit) and ``scale`` the factor from SI to it (``1e9``);
    ``fmt`` the format of one displayed value; ``check`` what an input of it must be
    (``"positive"``, ``"nonnegative"``, ``"poisson"``, ``"flag"``; ``""`` for outputs).
    """

    name: str
    unit: str
    description: str
    equation: str = ""
    symbol: str = ""
    tex: str = ""
    display_unit: str = ""
    scale: float = 1.0
    fmt: str = "{:.6g}"
    check: str = ""

    @property
    def shown_unit(self) -> str:
        """The unit shown to people: :attr:`display_unit`, else the SI :attr:`unit`."""
        return self.display_unit or self.unit


#: The table's spelling of a dimensionless unit: UDUNITS' ``"1"``, what files carry (CSV headers
#: ``e [1]``, NetCDF ``units``) and every unit field in code means by dimensionless.
DIMENSIONLESS = "1"
#: The spelling of a dimensionless unit shown to people (docstrings ``[-]``, lists, reports);
#: :func:`unit_text` is the one place that turns :data:`DIMENSIONLESS` into it.
DIMENSIONLESS_SHOWN = "-"


def unit_text(unit: str) -> str:
    """``unit`` as shown to people: :data:`DIMENSIONLESS_SHOWN` (``"-"``) for the table's dimensionless
    ``"1"``, every other unit as it is (text's ``""`` stays empty).

    >>> unit_text("1"), unit_text("m/s"), unit_text("")
    ('-', 'm/s', '')
    """
    return DIMENSIONLESS_SHOWN if unit == DIMENSIONLESS else unit


def _q(name, unit, description, equation="", symbol="", tex="", display="", scale=1.0, fmt="{:.6g}", check=""):
    return name, Quantity(name, unit, description, equation, symbol, tex, display, scale, fmt, check)


_NS = dict(display="ns", scale=1e9, fmt="{:.4f}")  # times shown in ns

#: Every quantity microimpact reports or takes, by name.
QUANTITIES: dict[str, Quantity] = dict(
    [
        # outcome of one impact
        _q("velocity", "m/s", "impact speed V", "", "V", "$V$", fmt="{:.4g}", check="nonnegative"),
        _q("yield_velocity", "m/s", "yield velocity V_y, 1/2 m* V_y^2 = 2/5 P_y alpha_y", "28", "V_y", "$V_y$"),
        _q("normalized_velocity", "1", "V / V_y", "", "V/V_y", "$V/V_y$"),
        _q("elastic", "1", "True where V <= V_y (purely elastic impact)", check="flag"),
        _q("restitution", "1", "coefficient of restitution e", "27", "e", "$e$", fmt="{:.5f}"),
        _q("rebound_velocity", "m/s", "rebound speed V_r = e V", "", "V_r", "$V_r$", fmt="{:.4g}"),
        _q("max_approach", "m", "maximum approach alpha*", "22", "alpha*", r"$\alpha^*$", "nm", 1e9, "{:.5g}"),
        _q(
            "plastic_approach",
            "m",
            "plastic (unrecoverable) approach alpha_p",
            "11",
            "alpha_p",
            r"$\alpha_p$",
            "nm",
            1e9,
            "{:.5g}",
        ),
        _q("max_force", "N", "maximum contact force P*", "14", "P*", "$P^*$", "uN", 1e6, "{:.5g}"),
        _q(
            "unloading_radius",
            "m",
            "curvature radius of the flattened contact R_p",
            "9",
            "R_p",
            "$R_p$",
            "um",
            1e6,
            "{:.4g}",
        ),
        _q("energy_loss", "1", "fraction of kinetic energy lost, 1 - e^2", "29", "1-e^2", "$1-e^2$", fmt="{:.4f}"),
        _q(
            "max_contact_radius",
            "m",
            "contact radius at maximum approach a* = (R* alpha*)^(1/2)",
            "3",
            "a*",
            "$a^*$",
            "um",
            1e6,
            "{:.4g}",
        ),
        _q("large_strain", "1", "True where a*/R* > 0.3 (outside the small-strain range)"),
        _q("elastic_stage_time", "s", "stage 1 (Hertz loading) duration t1", "20", "t1", "$t_1$", **_NS),
        _q("plastic_stage_time", "s", "stage 2 (plastic loading) duration t2", "23", "t2", "$t_2$", **_NS),
        _q("loading_time", "s", "loading time t_L = t1 + t2", "32", "t_L", "$t_L$", **_NS),
        _q("unloading_time", "s", "unloading time t_U", "26", "t_U", "$t_U$", **_NS),
        _q("contact_time", "s", "contact time t_c = t_L + t_U", "33", "t_c", "$t_c$", **_NS),
        # a pair's inputs and effective values
        _q(
            "limiting_pressure",
            "Pa",
            "limiting contact pressure p_y",
            "6",
            "p_y",
            "$p_y$",
            "MPa",
            1e-6,
            check="positive",
        ),
        _q(
            "yield_strength",
            "Pa",
            "yield strength Y of the softer body (p_y = k Y)",
            "",
            "Y",
            "$Y$",
            "MPa",
            1e-6,
            check="positive",
        ),
        _q("k", "1", "ratio k = p_y / Y", "", "k = p_y/Y", "$k = p_y/Y$", check="positive"),
        _q(
            "particle_modulus",
            "Pa",
            "Young's modulus of the particle E1",
            "",
            "E1",
            "$E_1$",
            "GPa",
            1e-9,
            check="positive",
        ),
        _q(
            "surface_modulus",
            "Pa",
            "Young's modulus of the surface E2",
            "",
            "E2",
            "$E_2$",
            "GPa",
            1e-9,
            check="positive",
        ),
        _q("particle_poisson", "1", "Poisson ratio of the particle nu1", "", "nu1", r"$\nu_1$", check="poisson"),
        _q("surface_poisson", "1", "Poisson ratio of the surface nu2", "", "nu2", r"$\nu_2$", check="poisson"),
        _q("density", "kg/m^3", "particle density rho", "", "rho", r"$\rho$", check="positive"),
        _q("radius", "m", "particle radius R (sphere on a flat: R* = R)", "", "R", "$R$", "um", 1e6, check="positive"),
        _q("diameter", "m", "particle diameter d = 2 R", "", "d", "$d$", "um", 1e6, check="positive"),
        _q(
            "effective_modulus",
            "Pa",
            "effective modulus E* = 1/((1-nu1^2)/E1 + (1-nu2^2)/E2)",
            "",
            "E*",
            "$E^*$",
            "GPa",
            1e-9,
            check="positive",
        ),
        _q("effective_radius", "m", "effective radius R*", "", "R*", "$R^*$", "um", 1e6, check="positive"),
        _q("effective_mass", "kg", "effective mass m*", "", "m*", "$m^*$", check="positive"),
        # the yield point of a pair (eqs. 5, 7, 28)
        _q("yield_approach", "m", "yield approach alpha_y", "5", "alpha_y", r"$\alpha_y$", "nm", 1e9, "{:.5g}"),
        _q("yield_force", "N", "yield force P_y", "7", "P_y", "$P_y$", "uN", 1e6, "{:.5g}"),
        # one impact against time
        _q("time", "s", "time since first contact t", "", "t", "$t$", **_NS),
        _q("approach", "m", "approach alpha (negative: a gap, no contact)", "", "alpha", r"$\alpha$", "nm", 1e9),
        _q(
            "approach_velocity",
            "m/s",
            "approach velocity dalpha/dt (positive while approaching)",
            "17",
            "dalpha/dt",
            r"$\dot\alpha$",
        ),
        _q("force", "N", "contact force P", "2, 8, 10", "P", "$P$", "uN", 1e6),
        _q("stage", "1", "0 no contact, 1 Hertz loading, 2 plastic loading, 3 elastic unloading"),
        # the seed's normalised contact (eqs. 12-15)
        _q(
            "normalized_approach", "1", "normalised approach alpha/alpha_y", "12", "alpha/alpha_y", r"$\alpha/\alpha_y$"
        ),
        _q("normalized_force", "1", "normalised force P/P_y", "13-15", "P/P_y", "$P/P_y$"),
        # derived quantities of the figures and reports
        _q("plastic_frequency", "rad/s", "angular frequency of the plastic stage omega", "18-23", "omega", r"$\omega$"),
        _q("plastic_ratio", "1", "plastic share alpha_p/alpha*", "", "alpha_p/alpha*", r"$\alpha_p/\alpha^*$"),
        _q("deresiewicz_time", "s", "Deresiewicz's elastic contact time", "30", "t_D", "$t_D$", **_NS),
        _q("ning_loading_time", "s", "Ning's high-speed loading time", "31", "t_N", "$t_N$", **_NS),
        _q("calibrated", "1", "1 where the model was calibrated to the reference, else 0", check="flag"),
        _q("angle", "deg", "impact angle from the wall normal (0: head-on)", "", "theta", r"$\theta$"),
        _q("stuck", "1", "1 where the particle sticks to the wall (e = 0), else 0", check="flag"),
        _q(
            "outside_table",
            "1",
            "1 where the whole adhesive law's table was left (its edge used), else 0",
            check="flag",
        ),
        # adhesion: stick or bounce (Thornton & Ning 1998)
        _q("work_of_adhesion", "J/m^2", "work of adhesion G", "", "G", "$G$", check="nonnegative"),
        _q(
            "surface_energy",
            "J/m^2",
            "surface energy gamma, LAMMPS' cohesion (work of adhesion G = 2 gamma)",
            "",
            "gamma",
            r"$\gamma$",
            check="nonnegative",
        ),
        _q(
            "capture_velocity", "m/s", "capture (sticking) velocity V_s: e = 0 at and below it", "", "V_s", "$V_s$"
        ),  # fmt: skip
        _q(
            "parting_diameter",
            "m",
            "largest diameter where the two laws' capture velocities part",
            "",
            "d_p",
            "$d_p$",
            "um",
            1e6,
        ),  # fmt: skip
        # parameters several impact models share (their Parameter specs read unit and meaning here)
        _q("poisson_ratio", "1", "Poisson ratio nu", "", "nu", r"$\nu$", check="poisson"),
        _q("loading_stiffness", "N/m", "stiffness of the loading branch k1", "", "k1", "$k_1$", check="positive"),
        _q("unloading_stiffness", "N/m", "stiffness of the unloading branch k2", "", "k2", "$k_2$", check="positive"),
        _q(
            "plasticity_depth",
            "1",
            "plastic flow depth phi_f (LIGGGHTS' phiF) of Luding's hysteretic spring",
            "",
            "phi_f",
            r"$\phi_f$",
            check="nonnegative",
        ),
        _q(
            "damping_ratio",
            "1",
            "damping coefficient alpha_T of Tsuji's dashpot",
            "",
            "alpha_T",
            r"$\alpha_T$",
            check="nonnegative",
        ),
        _q(
            "limit_force",
            "1",
            "1: force clipped at zero, contact ends when it vanishes; 0: ends at zero approach",
            check="flag",
        ),
        _q(
            "damping_model",
            "1",
            "damping keyword of LAMMPS' pair granular in [0, 2]: 0 viscoelastic, 1 tsuji, 2 coeff_restitution (floored)",
        ),
        _q(
            "viscoelastic_damping",
            "1/(m s)",
            "eta_n0 of LAMMPS' damping viscoelastic (eta_n = eta_n0 m* a)",
            "",
            "eta_n0",
            r"$\eta_{n0}$",
            check="nonnegative",
        ),
        _q(
            "normal_restitution",
            "1",
            "e_n, the restitution LAMMPS' damping tsuji or coeff_restitution is given",
            "",
            "e_n",
            "$e_n$",
            check="nonnegative",
        ),
        # text
        _q("model", "", "name of the impact model"),
        _q("series", "", "label of the curve"),
        _q("kind", "", "'model' (computed) or 'measured' (user data)"),
        _q("branch", "", "'loading' (eqs. 2, 8) or 'unloading' (eq. 10)"),
    ]
)

#: Fields of one impact's outcome, in the order every model's ``outcome`` returns them.
OUTCOME_FIELDS = (
    "velocity",
    "yield_velocity",
    "normalized_velocity",
    "elastic",
    "restitution",
    "rebound_velocity",
    "max_approach",
    "plastic_approach",
    "max_force",
    "unloading_radius",
    "energy_loss",
    "max_contact_radius",
    "large_strain",
    "elastic_stage_time",
    "plastic_stage_time",
    "loading_time",
    "unloading_time",
    "contact_time",
)

#: Outcome fields that are flags (models return 1.0/0.0; the object layer gives booleans).
FLAG_FIELDS = ("elastic", "large_strain")

#: Columns of an impact history.
HISTORY_FIELDS = ("time", "approach", "approach_velocity", "force", "stage")


def label(name: str) -> str:
    """The description of a quantity followed by its seed equation, for headers and attributes."""
    q = QUANTITIES[name]
    return f"{q.description} (eq. {q.equation})" if q.equation else q.description


def table(names) -> dict[str, tuple[str, str]]:
    """``{name: (unit, description with its equation)}`` for ``names`` (the form headers and attrs use)."""
    return {n: (QUANTITIES[n].unit, label(n)) for n in names}


def _suffix(unit: str) -> str:
    """``"m/s"`` -> ``"_m_s"``, ``"kg/m^3"`` -> ``"_kg_m3"``; ``""`` for ``"1"`` and text."""
    if unit in ("", DIMENSIONLESS):
        return ""
    return "_" + unit.replace("/", "_").replace("^", "").replace(" ", "_")


def column(name: str, display: bool = False) -> str:
    """The CSV column name of quantity ``name``: the name with its unit as a suffix (``force_N``).

    With ``display`` the suffix is the display unit (``contact_time_ns``).
    """
    q = QUANTITIES[name]
    return name + _suffix(q.shown_unit if display else q.unit)


def columns(names, display: bool = False) -> dict[str, tuple[str, str]]:
    """``{column name: (unit, description with its equation)}`` of :func:`column` for ``names``."""
    out = {}
    for n in names:
        q = QUANTITIES[n]
        out[column(n, display)] = (q.shown_unit if display else q.unit, label(n))
    return out


def header(name: str) -> str:
    """A short table heading: the symbol and the display unit, ``alpha* [nm]`` (no unit if dimensionless)."""
    q = QUANTITIES[name]
    unit = q.shown_unit
    return f"{q.symbol or name} [{unit}]" if unit not in ("", DIMENSIONLESS) else (q.symbol or name)


def axis_label(name: str, text: str = "") -> str:
    """A figure axis label: ``text`` (default the description), the TeX symbol, the display unit in brackets.

    ``Maximum approach, $\\alpha^*$ (nm)``; the unit's powers in TeX (``kg m$^{-3}$``), a dimensionless
    quantity ``(–)``, text none.
    """
    q = QUANTITIES[name]
    words = text or q.description.split(",")[0].split(" (")[0]
    if not text and q.symbol and words.endswith(" " + q.symbol):  # "impact speed V" -> "impact speed"
        words = words[: -len(q.symbol) - 1]
    unit = unit_text(q.shown_unit)
    tail = f" ({tex_unit(unit)})" if unit else ""
    sym = f", {q.tex}" if q.tex else ""
    return f"{words[0].upper()}{words[1:]}{sym}{tail}"


def tex_unit(unit: str) -> str:
    """A UDUNITS unit in matplotlib text: ``"kg/m^3"`` -> ``"kg m$^{-3}$"``, ``"uN"`` -> ``"µN"``; dimensionless
    (``"1"`` or its shown ``"-"``) the typeset dash ``"–"``."""
    if unit in (DIMENSIONLESS, DIMENSIONLESS_SHOWN):
        return "–"
    if unit.startswith("u"):
        unit = "µ" + unit[1:]
    if "/" in unit:
        num, den = unit.split("/", 1)
        base, _, power = den.partition("^")
        return f"{num} {base}$^{{-{power or 1}}}$" if power else f"{num}/{den}"
    return unit
