"""The one table of quantities: name, unit, description and seed equation of every result and input.

Every place that labels a number reads it from here: :class:`~microimpact.pair.ImpactResult`'s
documentation, the CLI's table and JSON units, CSV headers, a sweep's attributes, history columns
and the figures' data columns. Units are UDUNITS strings (``"1"`` for dimensionless), as CF
conventions for NetCDF expect.
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = ["Quantity", "QUANTITIES", "OUTCOME_FIELDS", "FLAG_FIELDS", "HISTORY_FIELDS", "table", "label"]


class Quantity(NamedTuple):
    """One quantity: its name, unit, a short description and the seed's equation (``""`` if none)."""

    name: str
    unit: str
    description: str
    equation: str = ""


def _q(name, unit, description, equation=""):
    return name, Quantity(name, unit, description, equation)


#: Every quantity microimpact reports or takes, by name.
QUANTITIES: dict[str, Quantity] = dict(
    [
        # outcome of one impact
        _q("velocity", "m/s", "impact speed V"),
        _q("yield_velocity", "m/s", "yield velocity V_y, 1/2 m* V_y^2 = 2/5 P_y alpha_y", "28"),
        _q("normalized_velocity", "1", "V / V_y"),
        _q("elastic", "1", "True where V <= V_y (purely elastic impact)"),
        _q("restitution", "1", "coefficient of restitution e", "27"),
        _q("rebound_velocity", "m/s", "rebound speed V_r = e V"),
        _q("max_approach", "m", "maximum approach alpha*", "22"),
        _q("plastic_approach", "m", "plastic (unrecoverable) approach alpha_p", "11"),
        _q("max_force", "N", "maximum contact force P*", "14"),
        _q("unloading_radius", "m", "curvature radius of the flattened contact R_p", "9"),
        _q("energy_loss", "1", "fraction of kinetic energy lost, 1 - e^2", "29"),
        _q("max_contact_radius", "m", "contact radius at maximum approach a* = (R* alpha*)^(1/2)", "3"),
        _q("large_strain", "1", "True where a*/R* > 0.3 (outside the small-strain range)"),
        _q("elastic_stage_time", "s", "stage 1 (Hertz loading) duration t1", "20"),
        _q("plastic_stage_time", "s", "stage 2 (plastic loading) duration t2", "23"),
        _q("loading_time", "s", "loading time t_L = t1 + t2", "32"),
        _q("unloading_time", "s", "unloading time t_U", "26"),
        _q("contact_time", "s", "contact time t_c = t_L + t_U", "33"),
        # a pair's inputs and effective values
        _q("limiting_pressure", "Pa", "limiting contact pressure p_y", "6"),
        _q("yield_strength", "Pa", "yield strength Y of the softer body (p_y = k Y)"),
        _q("k", "1", "ratio k = p_y / Y"),
        _q("particle_modulus", "Pa", "Young's modulus of the particle E1"),
        _q("surface_modulus", "Pa", "Young's modulus of the surface E2"),
        _q("particle_poisson", "1", "Poisson ratio of the particle nu1"),
        _q("surface_poisson", "1", "Poisson ratio of the surface nu2"),
        _q("density", "kg/m^3", "particle density rho"),
        _q("radius", "m", "particle radius R (sphere on a flat: R* = R)"),
        _q("diameter", "m", "particle diameter d = 2 R"),
        _q("effective_modulus", "Pa", "effective modulus E* = 1/((1-nu1^2)/E1 + (1-nu2^2)/E2)"),
        _q("effective_radius", "m", "effective radius R*"),
        _q("effective_mass", "kg", "effective mass m*"),
        # one impact against time
        _q("time", "s", "time since first contact t"),
        _q("approach", "m", "approach alpha (negative: a gap, no contact)"),
        _q("approach_velocity", "m/s", "approach velocity dalpha/dt (positive while approaching)", "17"),
        _q("force", "N", "contact force P", "2, 8, 10"),
        _q("stage", "1", "0 no contact, 1 Hertz loading, 2 plastic loading, 3 elastic unloading"),
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
