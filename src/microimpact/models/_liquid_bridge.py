"""What the faces of LIGGGHTS' two capillary cohesion models share: their input lines."""

from __future__ import annotations

from ..core import hertz

__all__ = ["capillary_lines"]


def capillary_lines(cal, poisson, wall, style, extra=()):
    """``gran model hertz`` with ``cohesion STYLE`` on the pair and the primitive wall, and the
    properties the cohesion model reads (one atom type, the wall's type too)."""
    p = cal.as_dict()
    e_n = p["coefficient_restitution"]
    if not e_n > 0.05:
        raise ValueError(f"LIGGGHTS requires coefficientRestitution > 0.05; got coefficient_restitution {e_n!r}")
    lim = "on" if p["limit_force"] == 1.0 else "off"
    Y = hertz.equal_bodies_modulus(cal.effective_modulus, poisson)
    settings = " ".join(extra)
    return [
        f"pair_style gran model hertz tangential no_history cohesion {style} limitForce {lim} {settings}".rstrip(),
        "pair_coeff * *",
        f"fix m1 all property/global youngsModulus peratomtype {Y:.12g}",
        f"fix m2 all property/global poissonsRatio peratomtype {poisson:.12g}",
        f"fix m3 all property/global coefficientRestitution peratomtypepair 1 {e_n:.12g}",
        "fix m4 all property/global coefficientFriction peratomtypepair 1 0.0",
        f"fix m5 all property/global surfaceLiquidContentInitial scalar {p['liquid_content']:.12g}",
        f"fix m6 all property/global surfaceTension scalar {p['surface_tension']:.12g}",
        f"fix m7 all property/global fluidViscosity scalar {p['fluid_viscosity']:.12g}",
        f"fix m8 all property/global contactAngle peratomtype {p['contact_angle']:.12g}",
        f"fix m9 all property/global minSeparationDistanceRatio scalar {p['min_separation_ratio']:.12g}",
        f"fix m10 all property/global maxSeparationDistanceRatio scalar {p['max_separation_ratio']:.12g}",
        f"fix wall all wall/gran model hertz tangential no_history cohesion {style} primitive type 1 {wall} "
        f"limitForce {lim} {settings}".rstrip(),
    ]
