"""A pair's inputs and how varying one moves the effective values: the one way microimpact varies
a pair (:meth:`ContactPair.vary <microimpact.pair.ContactPair.vary>` for one pair,
:meth:`ContactPair.effective_values <microimpact.pair.ContactPair.effective_values>` over arrays;
sweeps, fits and figures go through them)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from .. import impact
from .._validation import check_poisson, check_positive
from ..core import hertz as _hertz
from ..core.models import thornton_ning_2016 as _seed
from ..materials import effective_modulus, sphere_mass

__all__ = [
    "DEFAULT_POISSON",
    "DEFAULT_SURFACE_MODULUS",
    "PAIR_INPUTS",
    "material_inputs",
    "effective_values",
    "vary",
    "yield_strength_of",
]

#: Poisson ratio of both bodies when a pair has no materials (the seed's Fig. 4 takes 0.3).
DEFAULT_POISSON = 0.3
#: Surface Young's modulus [Pa] when a pair has no materials (the seed's Fig. 4: 150 GPa).
DEFAULT_SURFACE_MODULUS = 150e9

#: The inputs of a pair that :meth:`ContactPair.vary` and :meth:`ContactPair.effective_values` take.
PAIR_INPUTS = (
    "limiting_pressure",
    "yield_strength",
    "k",
    "yield_velocity",
    "effective_modulus",
    "particle_modulus",
    "particle_poisson",
    "surface_modulus",
    "surface_poisson",
    "radius",
    "diameter",
    "density",
    "effective_radius",
    "effective_mass",
)
_MATERIAL_INPUTS = ("particle_modulus", "particle_poisson", "surface_modulus", "surface_poisson")
# Names that set the same value: any of the first tuple with any of the second is refused.
_EXCLUSIVE = (
    (("limiting_pressure",), ("yield_strength", "k", "yield_velocity")),
    (("yield_velocity",), ("yield_strength", "k")),
    (("effective_modulus",), _MATERIAL_INPUTS),
    (("radius", "diameter", "density"), ("effective_radius", "effective_mass")),
)
_CHECKS = {
    "limiting_pressure": lambda n, x: check_positive(n, x, allow_inf=True),
    "particle_poisson": lambda n, x: check_poisson(n, x),
    "surface_poisson": lambda n, x: check_poisson(n, x),
}


def material_inputs(pair) -> tuple[dict, str]:
    """:meth:`ContactPair.material_inputs <microimpact.pair.ContactPair.material_inputs>`."""
    if pair.particle is not None and pair.surface is not None:
        p, s = pair.particle, pair.surface
        return (
            {
                "particle_modulus": p.youngs_modulus,
                "particle_poisson": p.poisson_ratio,
                "surface_modulus": s.youngs_modulus,
                "surface_poisson": s.poisson_ratio,
            },
            f"from the base pair's materials ({p.name}, {s.name})",
        )
    nu, E2 = DEFAULT_POISSON, DEFAULT_SURFACE_MODULUS
    E1 = _hertz.particle_modulus(pair.effective_modulus, nu, E2, nu)
    return (
        {"particle_modulus": E1, "particle_poisson": nu, "surface_modulus": E2, "surface_poisson": nu},
        f"the base pair has effective values only: nu1 = nu2 = {nu}, E2 = {E2 / 1e9:g} GPa (as the seed's "
        f"Fig. 4) and E1 = {E1:.6g} Pa so that E* equals the base pair's {pair.effective_modulus:.6g} Pa",
    )


def effective_values(pair, inputs: dict):
    """:meth:`ContactPair.effective_values <microimpact.pair.ContactPair.effective_values>`, ``inputs`` by name."""
    unknown = sorted(set(inputs) - set(PAIR_INPUTS))
    if unknown:
        raise ValueError(f"cannot vary {unknown[0]!r}; a pair's inputs: {', '.join(PAIR_INPUTS)}")
    for group in _EXCLUSIVE:
        given = [n for n in group[0] if n in inputs]
        other = [n for n in group[1] if n in inputs]
        if given and other:
            raise ValueError(f"{given[0]} was given together with {other[0]}: they set the same value")
    if "diameter" in inputs and "radius" in inputs:
        raise ValueError("diameter was given together with radius: they set the same value")
    v = {k: _CHECKS.get(k, check_positive)(k, x) for k, x in inputs.items()}
    if "diameter" in v:
        v["radius"] = 0.5 * v.pop("diameter")
    # E*
    material = [k for k in _MATERIAL_INPUTS if k in v]
    if "effective_modulus" in v:
        E = v["effective_modulus"]
    elif material:
        defaults, _ = pair.material_inputs()
        mat = {k: v.get(k, defaults[k]) for k in _MATERIAL_INPUTS}
        for k, x in mat.items():
            if k not in v and not math.isfinite(x):
                raise ValueError(
                    f"{k} is needed: this pair's E* = {pair.effective_modulus:g} Pa is too stiff to come "
                    f"from a surface of E2 = {DEFAULT_SURFACE_MODULUS:g} Pa"
                )
        E = effective_modulus(
            mat["particle_modulus"], mat["particle_poisson"], mat["surface_modulus"], mat["surface_poisson"]
        )
    else:
        E = np.float64(pair.effective_modulus)
    # R*, m*
    if "radius" in v or "density" in v:
        if "density" not in v and pair.density is None:
            raise ValueError(
                "density is needed: a radius or density change treats the particle as a sphere on a flat, "
                "and this pair has no density (a two-sphere pair?)"
            )
        R = v.get("radius", np.float64(pair.effective_radius))
        m = sphere_mass(R, v.get("density", pair.density))
    else:
        R = v.get("effective_radius", np.float64(pair.effective_radius))
        m = v.get("effective_mass", np.float64(pair.effective_mass))
    # p_y
    if "limiting_pressure" in v:
        p_y = v["limiting_pressure"]
    elif "k" in v or "yield_strength" in v:
        Y = v["yield_strength"] if "yield_strength" in v else yield_strength_of(pair)
        k = v["k"] if "k" in v else pair.limiting_pressure / Y
        p_y = k * Y
    elif "yield_velocity" in v:
        if not math.isfinite(pair.limiting_pressure):
            raise ValueError("yield_velocity can be set only on a pair with a finite limiting_pressure")
        Vy0 = impact.yield_velocity(pair.limiting_pressure, E, R, m)
        p_y = _seed.limiting_pressure_for_yield_velocity(v["yield_velocity"], pair.limiting_pressure, Vy0)
    else:
        p_y = np.float64(pair.limiting_pressure)
    return E, R, m, p_y


def vary(pair, inputs: dict):
    """:meth:`ContactPair.vary <microimpact.pair.ContactPair.vary>`, ``inputs`` by name."""
    for k, x in inputs.items():
        if np.ndim(x) != 0:
            raise ValueError(f"{k} must be a single value to vary a pair, got shape {np.shape(x)}")
    E, R, m, p_y = (float(x) for x in effective_values(pair, inputs))
    rho = inputs.get("density", pair.density)
    if ("radius" in inputs or "diameter" in inputs or "density" in inputs) and rho is not None:
        rho = float(rho)
    elif "effective_radius" in inputs or "effective_mass" in inputs:
        rho = None
    changed_material = any(k in inputs for k in (*_MATERIAL_INPUTS, "effective_modulus"))
    return replace(
        pair,
        effective_modulus=E,
        effective_radius=R,
        effective_mass=m,
        limiting_pressure=p_y,
        density=rho,
        particle=None if changed_material else pair.particle,
        surface=None if changed_material else pair.surface,
    )


def yield_strength_of(pair) -> float:
    """``Y`` [Pa] of the softer of the pair's materials (it yields first); refused without one."""
    known = [x.yield_strength for x in (pair.particle, pair.surface) if x is not None and x.yield_strength]
    if not known:
        raise ValueError(
            "yield_strength is needed: this pair has no material with a yield strength (give yield_strength=...)"
        )
    return min(known)
