"""microimpact: elastic-plastic impact of micro-particles on surfaces.

The dynamic impact model of Aerosol Sci. Tech. 50(4):321-330 (2016): Hertz
loading to the limiting contact pressure, Thornton-Ning plastic loading and
elastic unloading with a flattened contact and a plastic displacement, with
closed forms for the restitution coefficient, energy loss, contact times and
time histories.

>>> import microimpact as mi
>>> pair = mi.ContactPair.sphere_on_flat(radius=2.45e-6, density=1350.0,
...                                      effective_modulus=1.31e9, limiting_pressure=156e6)
>>> out = pair.impact(50.0)
>>> round(float(out.rebound_velocity), 2)  # seed: 36.31 m/s
36.24
"""

from . import contact, coupling, deposition, dynamics, fitting, impact, materials, sweep
from .adhesion import adhesive_restitution, sticking_velocity, work_of_adhesion
from .dynamics import (
    ImpactHistory,
    contact_times,
    deresiewicz_contact_time,
    impact_history,
    integrate_impact,
    ning_loading_time,
)
from .fitting import FitResult, fit_restitution, load_restitution_csv
from .impact import (
    impact_outcome,
    restitution_coefficient,
    thornton_ning_restitution,
    yield_velocity,
    yield_velocity_sphere_on_flat,
)
from .materials import MATERIALS, Material, effective_mass, effective_modulus, effective_radius, get_material
from .pair import ContactPair, ImpactResult, LargeStrainWarning
from .wall import WallInteraction, wall_interaction

__version__ = "0.1.0"

__all__ = [
    "ContactPair",
    "ImpactResult",
    "LargeStrainWarning",
    "Material",
    "MATERIALS",
    "get_material",
    "effective_modulus",
    "effective_radius",
    "effective_mass",
    "yield_velocity",
    "yield_velocity_sphere_on_flat",
    "impact_outcome",
    "restitution_coefficient",
    "thornton_ning_restitution",
    "contact_times",
    "deresiewicz_contact_time",
    "ning_loading_time",
    "ImpactHistory",
    "impact_history",
    "integrate_impact",
    "FitResult",
    "fit_restitution",
    "load_restitution_csv",
    "WallInteraction",
    "wall_interaction",
    "sticking_velocity",
    "adhesive_restitution",
    "work_of_adhesion",
    "contact",
    "coupling",
    "deposition",
    "impact",
    "dynamics",
    "materials",
    "fitting",
    "sweep",
    "__version__",
]
