"""The ways to build a :class:`~microimpact.pair.ContactPair`: a sphere on a flat from effective
values, a sphere of one material on a flat of another, two free spheres, and the seed paper's cases.

Each function takes the class (``cls``), as the classmethods of :class:`~microimpact.pair.ContactPair`
that call it pass it, so a subclass builds its own kind; the checks and the defaults are written here once.
"""

from __future__ import annotations

from .._validation import check_positive
from ..core.wall import sphere_mass as _sphere_mass
from ..materials import PAPER_CASES, effective_modulus, get_material, sphere_mass
from ..materials import limiting_pressure as _k_times_yield

__all__ = ["limiting_pressure_of", "sphere_on_flat", "from_materials", "two_spheres", "paper_case"]


def limiting_pressure_of(limiting_pressure, k, yield_strength, particle=None, surface=None):
    """``p_y`` [Pa] as given, or ``k Y`` with ``Y`` given or the softer material's (it yields first)."""
    if limiting_pressure is not None:
        if yield_strength is not None or k is not None:
            raise ValueError("limiting_pressure was given together with k/yield_strength; give one or the other")
        return limiting_pressure
    if k is not None:
        check_positive("k", k, scalar=True)
    if yield_strength is None:
        known = [m.yield_strength for m in (particle, surface) if m is not None and m.yield_strength]
        if not known:
            raise ValueError(
                "limiting_pressure is needed: give limiting_pressure=..., or yield_strength=... "
                "(p_y = k * Y), or a material with a yield strength"
            )
        yield_strength = min(known)  # the softer body yields first
    return _k_times_yield(yield_strength, k)


def sphere_on_flat(cls, radius, density, effective_modulus, limiting_pressure, mass, yield_strength, k, label):
    """:meth:`ContactPair.sphere_on_flat <microimpact.pair.ContactPair.sphere_on_flat>`."""
    if effective_modulus is None:
        raise ValueError("effective_modulus is needed for sphere_on_flat (or use from_materials)")
    radius = check_positive("radius", radius, scalar=True)
    if (density is None) == (mass is None):
        raise ValueError("give exactly one of density or mass")
    if density is not None:
        m = float(sphere_mass(radius, density))
    else:
        m = check_positive("mass", mass, scalar=True)
        density = m / _sphere_mass(radius, 1.0)
    p_y = limiting_pressure_of(limiting_pressure, k, yield_strength)
    return cls(effective_modulus, radius, m, p_y, density=density, label=label)


def from_materials(cls, particle, surface, radius, limiting_pressure, k, yield_strength, label):
    """:meth:`ContactPair.from_materials <microimpact.pair.ContactPair.from_materials>`."""
    p, s = get_material(particle), get_material(surface)
    E = float(effective_modulus(p.youngs_modulus, p.poisson_ratio, s.youngs_modulus, s.poisson_ratio))
    radius = check_positive("radius", radius, scalar=True)
    m = float(sphere_mass(radius, p.density))
    p_y = limiting_pressure_of(limiting_pressure, k, yield_strength, p, s)
    return cls(E, radius, m, p_y, density=p.density, label=label or f"{p.name} on {s.name}", particle=p, surface=s)


def two_spheres(cls, material1, material2, radius1, radius2, limiting_pressure, k, yield_strength, label):
    """:meth:`ContactPair.two_spheres <microimpact.pair.ContactPair.two_spheres>`."""
    p, s = get_material(material1), get_material(material2)
    E = float(effective_modulus(p.youngs_modulus, p.poisson_ratio, s.youngs_modulus, s.poisson_ratio))
    r1 = check_positive("radius1", radius1, scalar=True)
    r2 = check_positive("radius2", radius2, scalar=True)
    m1, m2 = float(sphere_mass(r1, p.density)), float(sphere_mass(r2, s.density))
    p_y = limiting_pressure_of(limiting_pressure, k, yield_strength, p, s)
    return cls(
        E,
        1.0 / (1.0 / r1 + 1.0 / r2),
        1.0 / (1.0 / m1 + 1.0 / m2),
        p_y,
        label=label or f"{p.name} sphere on {s.name} sphere",
        particle=p,
        surface=s,
    )


def paper_case(cls, name):
    """:meth:`ContactPair.paper_case <microimpact.pair.ContactPair.paper_case>`."""
    key = str(name).lower()
    if key not in PAPER_CASES:
        raise ValueError(f"case must be one of {', '.join(PAPER_CASES)}, got {name!r}")
    c = PAPER_CASES[key]
    return cls.sphere_on_flat(
        c["radius"], c["density"], c["effective_modulus"], c["limiting_pressure"], label=c["label"]
    )
