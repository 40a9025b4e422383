"""The one table of quantities: name, unit, description and seed equation of every result field."""

from __future__ import annotations

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
