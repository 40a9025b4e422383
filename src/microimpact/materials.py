"""Named materials with cited sources, and the effective properties of a contact pair.

The effective ("mechanical") parameters of the seed paper (Aerosol Sci. Tech.
50(4):321-330, 2016, Section 2.1, after eq. 2):

* ``E* = 1 / ((1 - nu1**2)/E1 + (1 - nu2**2)/E2)``
* ``R* = 1 / (1/R1 + 1/R2)`` (a flat surface has ``R2 = inf``)
* ``m* = 1 / (1/m1 + 1/m2)`` (a flat, fixed surface has ``m2 = inf``)

Values in :data:`MATERIALS` are room-temperature handbook values; each entry
names its source. They are starting points: the limiting contact pressure in
particular is a property of the *pair* and is best fitted to rebound data
(:mod:`microimpact.fitting`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ._validation import TINY_NORMAL as _TINY
from ._validation import check_not_subnormal, check_poisson, check_positive
from .core import hertz as _hertz
from .core.constants import DEFAULT_K

__all__ = [
    "Material",
    "MATERIALS",
    "DEFAULT_K",
    "PAPER_CASES",
    "get_material",
    "list_materials",
    "effective_modulus",
    "effective_radius",
    "effective_mass",
    "sphere_mass",
    "limiting_pressure",
]


@dataclass(frozen=True)
class Material:
    """An isotropic, linear-elastic, perfectly plastic material.

    Parameters
    ----------
    name : str
        Registry key (lower case).
    youngs_modulus : float
        Young's modulus ``E`` [Pa].
    poisson_ratio : float
        Poisson's ratio ``nu``, in (-1, 0.5].
    density : float
        Mass density [kg/m^3].
    yield_strength : float or None
        Uniaxial yield strength ``Y`` [Pa], if meaningful (None for brittle solids).
    source : str
        Where the values come from.
    description : str
        Free text.
    """

    name: str
    youngs_modulus: float
    poisson_ratio: float
    density: float
    yield_strength: float | None = None
    source: str = ""
    description: str = field(default="", compare=False)

    def __post_init__(self):
        check_positive(f"{self.name}.youngs_modulus", self.youngs_modulus)
        check_poisson(f"{self.name}.poisson_ratio", self.poisson_ratio)
        check_positive(f"{self.name}.density", self.density)
        if self.yield_strength is not None:
            check_positive(f"{self.name}.yield_strength", self.yield_strength)

    @property
    def plane_strain_compliance(self) -> float:
        """``(1 - nu^2) / E`` [1/Pa], this body's share of ``1/E*``."""
        return _hertz.compliance(self.youngs_modulus, self.poisson_ratio)


_W90 = "Wall, John, Wang & Goren (1990), Aerosol Sci. Technol. 12:926-946, as used in the seed paper, Section 3.1"

#: Named materials (key -> :class:`Material`), each with the source of its values.
#: ``"aluminum"`` is an alias of ``"aluminium"``. See :func:`list_materials`.
MATERIALS: dict[str, Material] = {
    m.name: m
    for m in [
        Material(
            "nh4fl",
            1.2e9,
            0.3,
            1350.0,
            74e6,
            source=(
                "ammonium fluorescein particles of " + _W90 + "; density 1350 kg/m^3 from the seed; "
                "E = 1.2 GPa, nu = 0.3 as in the literature that uses this case; Y = 74 MPa is the "
                "seed's yield limit for the silicon pair (the mica pair has 68 MPa)"
            ),
            description="ammonium fluorescein (NH4Fl), the seed paper's particle",
        ),
        Material(
            "silicon",
            163e9,
            0.22,
            2329.0,
            None,
            source=(
                "Hopcroft, Nix & Kenny (2010), J. Microelectromech. Syst. 19:229, 'What is the "
                "Young's modulus of silicon?' (polycrystalline/isotropic average); density from "
                "CRC Handbook of Chemistry and Physics. With nh4fl gives E* = 1.309 GPa (seed: 1.31)"
            ),
            description="single-crystal silicon wafer (isotropic average)",
        ),
        Material(
            "mica",
            61e9,
            0.25,
            2830.0,
            None,
            source=(
                "muscovite: stiffness normal to the cleavage plane C33 = 61 GPa, McNeil & "
                "Grimsditch (1993), J. Phys.: Condens. Matter 5:1681; nu = 0.25 assumed; density "
                "CRC Handbook. With nh4fl gives E* = 1.293 GPa (seed: 1.30)"
            ),
            description="muscovite mica, loaded normal to the cleavage plane",
        ),
        Material(
            "glass",
            70e9,
            0.22,
            2500.0,
            None,
            source="soda-lime glass, Ashby & Jones, Engineering Materials 1 (4th ed., 2012), Table 3.1",
            description="soda-lime glass (brittle: no yield strength)",
        ),
        Material(
            "fused_silica",
            72.7e9,
            0.16,
            2200.0,
            None,
            source="Corning 7980 fused silica product data; also CRC Handbook",
            description="amorphous SiO2",
        ),
        Material(
            "quartz",
            95.6e9,
            0.08,
            2650.0,
            None,
            source="alpha-quartz, Voigt-Reuss-Hill average of single-crystal constants, "
            "Heyliger, Ledbetter & Kim (2003), J. Acoust. Soc. Am. 114:644",
            description="crystalline alpha-quartz (isotropic average)",
        ),
        Material(
            "steel",
            210e9,
            0.29,
            7850.0,
            250e6,
            source="structural carbon steel (S250/ASTM A36 class): Ashby & Jones (2012) Table 3.1, "
            "Y = 250 MPa minimum yield of A36",
            description="mild/structural carbon steel",
        ),
        Material(
            "stainless_steel",
            193e9,
            0.29,
            8000.0,
            215e6,
            source="AISI 304, annealed: ASM Handbook Vol. 1 (1990) property tables",
            description="AISI 304 stainless steel, annealed",
        ),
        Material(
            "aluminium",
            70e9,
            0.33,
            2700.0,
            276e6,
            source="6061-T6 aluminium alloy: ASM Handbook Vol. 2 (1990); E, nu from Ashby & Jones (2012)",
            description="6061-T6 aluminium alloy",
        ),
        Material(
            "copper",
            117e9,
            0.34,
            8960.0,
            70e6,
            source="annealed OFHC copper: ASM Handbook Vol. 2 (1990); used by Rogers & Reed (1984) "
            "for copper micro-particles",
            description="annealed copper",
        ),
        Material(
            "fly_ash",
            70e9,
            0.2,
            2300.0,
            None,
            source="glassy aluminosilicate fly ash: density 2000-2600 kg/m^3 (ASTM C618 class F "
            "ashes); stiffness taken as that of aluminosilicate glass (Ashby & Jones 2012). "
            "Representative only: measure or fit for your ash",
            description="coal fly ash sphere (representative values)",
        ),
    ]
}
MATERIALS["aluminum"] = MATERIALS["aluminium"]  # US spelling, same entry


def list_materials() -> list[str]:
    """Names of the registered materials, sorted (aliases left out).

    Returns
    -------
    list of str
        Keys of :data:`MATERIALS` that name their own entry.

    Examples
    --------
    >>> "silicon" in list_materials(), "aluminum" in list_materials()
    (True, False)
    """
    return sorted(k for k, m in MATERIALS.items() if k == m.name)


def get_material(name) -> Material:
    """Look up a material by name (case-insensitive); a :class:`Material` passes through.

    Hyphens and spaces in ``name`` are read as underscores (``"fused silica"``).

    Parameters
    ----------
    name : str or Material
        Registry key of :data:`MATERIALS` (``"silicon"``, ``"NH4Fl"``, ...) or a
        :class:`Material`, returned as is.

    Returns
    -------
    Material
        The registered material.

    Raises
    ------
    ValueError
        If ``name`` is not a registered material; the message lists the names.

    Examples
    --------
    >>> get_material("Silicon").youngs_modulus
    163000000000.0
    """
    if isinstance(name, Material):
        return name
    key = str(name).strip().lower().replace("-", "_").replace(" ", "_")
    try:
        return MATERIALS[key]
    except KeyError:
        raise ValueError(f"material must be one of {', '.join(list_materials())}, got {name!r}") from None


def effective_modulus(E1, nu1, E2, nu2):
    """Effective ("mechanical") modulus ``E*`` of two elastic bodies [Pa].

    ``E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)`` (seed, definition after eq. 2).
    ``E2 = inf`` is a rigid surface.

    Parameters
    ----------
    E1, E2 : array_like
        Young's moduli [Pa], positive (``E2`` may be ``inf``).
    nu1, nu2 : array_like
        Poisson ratios in (-1, 0.5].

    Returns
    -------
    ndarray
        Effective modulus ``E*`` [Pa].

    Raises
    ------
    ValueError
        If a modulus is not positive or a Poisson ratio is outside (-1, 0.5].

    Examples
    --------
    >>> round(float(effective_modulus(1.2e9, 0.3, 163e9, 0.22)) / 1e9, 3)
    1.309
    """
    E1 = check_positive("E1", E1)
    E2 = check_not_subnormal("E2", check_positive("E2", E2, allow_inf=True))  # (1 - nu2^2)/E2 overflows
    nu1 = check_poisson("nu1", nu1)
    nu2 = check_poisson("nu2", nu2)
    return _hertz.effective_modulus(E1, nu1, E2, nu2)


def effective_radius(R1, R2=math.inf):
    """Effective radius ``R* = 1 / (1/R1 + 1/R2)`` [m] (seed, definition after eq. 2).

    A flat has ``R2 = inf``, so ``R* = R1``.

    Parameters
    ----------
    R1 : array_like
        Radius of the first body [m], positive.
    R2 : array_like, optional
        Radius of the second body [m], positive; ``inf`` (default) for a flat.

    Returns
    -------
    ndarray
        Effective radius ``R*`` [m].

    Raises
    ------
    ValueError
        If a radius is not positive.

    Examples
    --------
    >>> float(effective_radius(2.45e-6))
    2.45e-06
    >>> float(effective_radius(2e-6, 2e-6))  # two equal spheres: R/2
    1e-06
    """
    R1 = check_not_subnormal("R1", check_positive("R1", R1, allow_inf=True))  # 1/R overflows
    R2 = check_not_subnormal("R2", check_positive("R2", R2, allow_inf=True))
    return 1.0 / (1.0 / R1 + 1.0 / R2)


def effective_mass(m1, m2=math.inf):
    """Effective mass ``m* = 1 / (1/m1 + 1/m2)`` [kg] (seed, definition after eq. 2).

    A fixed wall has ``m2 = inf``, so ``m* = m1``.

    Parameters
    ----------
    m1 : array_like
        Mass of the first body [kg], positive.
    m2 : array_like, optional
        Mass of the second body [kg], positive; ``inf`` (default) for a fixed wall.

    Returns
    -------
    ndarray
        Effective mass ``m*`` [kg].

    Raises
    ------
    ValueError
        If a mass is not positive.

    Examples
    --------
    >>> round(float(effective_mass(3e-15, 3e-15)) * 1e15, 12)  # two equal particles: m/2, in 1e-15 kg
    1.5
    """
    m1 = check_not_subnormal("m1", check_positive("m1", m1, allow_inf=True))  # 1/m overflows
    m2 = check_not_subnormal("m2", check_positive("m2", m2, allow_inf=True))
    return 1.0 / (1.0 / m1 + 1.0 / m2)


def sphere_mass(radius, density):
    """Mass of a solid sphere, ``m = 4/3 pi R^3 rho`` [kg].

    Parameters
    ----------
    radius : array_like
        Sphere radius ``R`` [m], positive.
    density : array_like
        Mass density ``rho`` [kg/m^3], positive.

    Returns
    -------
    ndarray
        Mass ``m`` [kg].

    Raises
    ------
    ValueError
        If ``radius`` or ``density`` is not positive.

    Examples
    --------
    >>> round(float(sphere_mass(2.45e-6, 1350.0)) * 1e14, 4)  # 4.9 um NH4Fl particle, 1e-14 kg
    8.3161
    """
    radius = check_positive("radius", radius)
    density = check_positive("density", density)
    from .core.wall import sphere_mass as _mass
    from .engine import evaluate

    m = evaluate(_mass, radius, density)[0]
    _check_mass(m, radius, density)
    return m


def _check_mass(m, radius, density) -> None:
    """Refuse, naming ``radius`` and ``density``, a mass that left the normal floats: a radius and a
    density each in range can give an overflowing or a subnormal (or zero) product, whose reciprocal
    (every law divides by the mass) overflows."""
    arr = np.asarray(m, dtype=float)
    ok = np.isfinite(arr) & (arr >= _TINY)
    if ok.all():
        return
    i = np.unravel_index(int(np.argmin(ok)), arr.shape) if arr.ndim else ()
    r = float(np.broadcast_to(radius, arr.shape)[i])
    d = float(np.broadcast_to(density, arr.shape)[i])
    raise ValueError(
        f"radius {r!r} and density {d!r} give the sphere mass {float(arr[i])!r}, which is no normal float "
        f"(between {_TINY!r} and {float(np.finfo(float).max)!r} kg): give a radius and density in range"
    )


def limiting_pressure(yield_strength, k=None) -> float:
    """Limiting contact pressure ``p_y = k Y`` [Pa] (seed, Section 3.1, after Hardy et al. 1971).

    Parameters
    ----------
    yield_strength : float
        Yield strength ``Y`` [Pa] of the softer body, positive and finite.
    k : float, optional
        ``p_y / Y`` [-], positive; default :data:`DEFAULT_K` (the seed takes 2.1-2.3).

    Returns
    -------
    float
        ``p_y`` [Pa].

    Raises
    ------
    ValueError
        Naming ``k`` or ``yield_strength`` when it is not a positive finite number.

    Examples
    --------
    >>> round(limiting_pressure(74e6, 2.11) / 1e6, 2)  # the seed's silicon case: 156 MPa
    156.14
    """
    k = DEFAULT_K if k is None else check_positive("k", k, scalar=True)
    return k * check_positive("yield_strength", yield_strength, scalar=True)


#: The seed paper's two validation cases (Section 3.1): ammonium fluorescein
#: particles of 4.9 um diameter on silicon and on mica, as effective values. The
#: quoted yield velocities are the paper's; eq. 28 with these (rounded) inputs
#: gives 7.52 and 7.89 m/s (:func:`~microimpact.impact.yield_velocity_sphere_on_flat`).
PAPER_CASES: dict[str, dict] = {
    "silicon": {
        "radius": 2.45e-6,
        "density": 1350.0,
        "effective_modulus": 1.31e9,
        "limiting_pressure": 156e6,
        "yield_strength": 74e6,
        "quoted_yield_velocity": 7.59,
        "label": "NH4Fl on silicon (seed, Sec. 3.1)",
    },
    "mica": {
        "radius": 2.45e-6,
        "density": 1350.0,
        "effective_modulus": 1.30e9,
        "limiting_pressure": 158e6,
        "yield_strength": 68e6,
        "quoted_yield_velocity": 7.92,
        "label": "NH4Fl on mica (seed, Sec. 3.1)",
    },
}
