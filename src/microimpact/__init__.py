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

import importlib as _importlib

from . import materials, models
from ._version import __version__
from .core.models import available as _available  # noqa: F401  (the registry loads with the package)
from .materials import MATERIALS, Material, effective_mass, effective_modulus, effective_radius, get_material
from .models import OutsideValidityWarning
from .pair import AdhesionRangeWarning, ContactPair, ImpactResult, LargeStrainWarning

# Everything else loads on first use (PEP 562), so that ``import microimpact`` and one impact on
# the command line import neither scipy, nor xarray, nor matplotlib, nor the deposition example.
_LAZY = {
    "yield_velocity": "impact",
    "yield_velocity_sphere_on_flat": "impact",
    "impact_outcome": "impact",
    "restitution_coefficient": "impact",
    "thornton_ning_restitution": "impact",
    "contact_times": "dynamics",
    "deresiewicz_contact_time": "dynamics",
    "ning_loading_time": "dynamics",
    "ImpactHistory": "dynamics",
    "impact_history": "dynamics",
    "integrate_impact": "dynamics",
    "integrate_model": "dynamics",
    "compare_models": "compare",
    "FitResult": "fitting",
    "fit_restitution": "fitting",
    "load_restitution_csv": "io",
    "WallInteraction": "wall",
    "wall_interaction": "wall",
    "sticking_velocity": "adhesion",
    "adhesive_restitution": "adhesion",
    "work_of_adhesion": "adhesion",
}
_SUBMODULES = {
    "contact",
    "coupling",
    "deposition",
    "impact",
    "dynamics",
    "fitting",
    "sweep",
    "adhesion",
    "wall",
    "cexport",
    "compare",
    "paper",
    "figures",
    "core",
}


def __getattr__(name):
    if name in _LAZY:
        value = getattr(_importlib.import_module(f".{_LAZY[name]}", __name__), name)
    elif name in _SUBMODULES:
        value = _importlib.import_module(f".{name}", __name__)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY) | _SUBMODULES)


__all__ = [
    "ContactPair",
    "ImpactResult",
    "LargeStrainWarning",
    "OutsideValidityWarning",
    "AdhesionRangeWarning",
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
    "integrate_model",
    "compare_models",
    "FitResult",
    "fit_restitution",
    "load_restitution_csv",
    "WallInteraction",
    "wall_interaction",
    "sticking_velocity",
    "adhesive_restitution",
    "work_of_adhesion",
    "contact",
    "deposition",
    "impact",
    "dynamics",
    "materials",
    "fitting",
    "sweep",
    "compare",
    "models",
    "__version__",
]
