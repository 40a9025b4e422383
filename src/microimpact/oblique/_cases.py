"""The published alumina case of the oblique impact: its pair and its measurements."""

from __future__ import annotations

import math

import numpy as np

#: Chung & Ooi's (2011) Test 4, Kharaz, Gorham & Salman's (2001) experiment: 5 mm alumina
#: sphere at 3.9 m/s on the thick glass anvil of the experiment (:func:`alumina_pair`; the flat
#: is rigid in Chung & Ooi's benchmark: ``alumina_pair("rigid")``). The sphere's values.
ALUMINA_CASE = {
    "youngs_modulus": 3.8e11,
    "poisson_ratio": 0.23,
    "density": 4000.0,
    "radius": 2.5e-3,
    "friction": 0.092,
    "velocity": 3.9,
}


def alumina_pair(wall="glass"):
    """:class:`~microimpact.pair.ContactPair` of :data:`ALUMINA_CASE` (elastic: ``p_y = inf``).

    ``wall="glass"`` (default): the glass anvil of Kharaz, Gorham & Salman's (2001) experiment, as
    the named material ``"glass"`` (soda-lime glass, E = 70 GPa, nu = 0.22, Ashby & Jones 2012; the
    anvil's own grade is not in the sources read here): ``E* = 62.2 GPa``, a Hertz contact time of
    12.9 us at 3.9 m/s head on, and ``kappa = 4 G*/E* = 0.875`` from both materials' shear moduli
    (the pair carries both materials, so :func:`oblique_impact` needs no ``poisson_ratio``).
    ``wall="rigid"``: the rigid flat of Chung & Ooi's (2011) benchmark, ``E* = E/(1 - nu^2)`` (6.1 us;
    ``kappa`` from ``poisson_ratio=0.23``: 0.870). The default was ``"rigid"`` before 2026-11: the
    case the measured points belong to is the glass one.
    """
    from ..materials import Material
    from ..pair import ContactPair

    c = ALUMINA_CASE
    if wall == "rigid":
        return ContactPair.sphere_on_flat(
            radius=c["radius"],
            density=c["density"],
            effective_modulus=c["youngs_modulus"] / (1.0 - c["poisson_ratio"] ** 2),
            limiting_pressure=math.inf,
            label="alumina on a rigid flat (Chung & Ooi 2011, Test 4)",
        )
    if wall != "glass":
        raise ValueError(f"wall must be 'glass' or 'rigid', got {wall!r}")
    alumina = Material(
        "alumina",
        c["youngs_modulus"],
        c["poisson_ratio"],
        c["density"],
        source="Chung & Ooi (2011), Test 4; Kharaz, Gorham & Salman (2001)",
        description="alumina sphere of the oblique-impact experiment",
    )
    return ContactPair.from_materials(
        alumina,
        "glass",
        c["radius"],
        limiting_pressure=math.inf,
        label="alumina on glass (Kharaz, Gorham & Salman 2001)",
    )


def measured_alumina(source="experiment", quantity="et"):
    """Published points of the alumina case, read off figures (``data/oblique_alumina.csv``).

    Parameters
    ----------
    source : {"experiment", "dem"}
        Kharaz et al. (2001) measurements, or Chung & Ooi's (2011) DEM verification result,
        both as plotted by Chung & Ooi (2011) (digitised; precision in the file header).
    quantity : {"et", "spin", "angle"}
        Tangential restitution of the centre [-], rebound spin [rad/s] (negative: opposing
        the incident slip) or contact-point rebound angle [deg].

    Returns
    -------
    angle, value : ndarray
        Impact angle from the normal [deg] and the quantity.
    """
    from importlib import resources

    if source not in ("experiment", "dem"):
        raise ValueError(f"source must be 'experiment' or 'dem', got {source!r}")
    if quantity not in ("et", "spin", "angle"):
        raise ValueError(f"quantity must be 'et', 'spin' or 'angle', got {quantity!r}")
    text = resources.files("microimpact").joinpath("data/oblique_alumina.csv").read_text(encoding="utf-8")
    rows = [ln.split(",") for ln in text.splitlines() if ln and not ln.startswith("#")][1:]
    sel = [(float(a), float(v)) for s, q, a, v in rows if s == source and q == quantity]
    arr = np.array(sel, dtype=float)
    return arr[:, 0], arr[:, 1]
