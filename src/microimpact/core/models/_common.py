"""Helpers shared by the model files (private: not a model, so not listed by ``available()``).

Everything here is plain Python over floats in numba's subset, marked ``@jitable`` like the
model functions that call it.
"""

from __future__ import annotations

import math

from .._jit import jitable
from ..constants import LARGE_STRAIN_RATIO  # noqa: F401  (re-exported for the model files)

__all__ = ["LARGE_STRAIN_RATIO", "NAN", "pack", "nan_outcome", "dem_outcome"]

NAN = math.nan


@jitable
def pack(
    V,
    Vy,
    v,
    elastic,
    e,
    max_approach,
    plastic_approach,
    max_force,
    unloading_radius,
    R,
    t1,
    t2,
    tL,
    tU,
):
    """One outcome tuple in :data:`~microimpact.core.quantities.OUTCOME_FIELDS` order.

    ``rebound_velocity = e V``, ``energy_loss = 1 - e^2``, ``max_contact_radius = (R* alpha*)^(1/2)``
    (Hertz geometry, seed eq. 3), ``large_strain`` and ``contact_time = t_L + t_U`` are derived here,
    so every model computes them the same way.
    """
    a_max = math.sqrt(R * max_approach)
    large = 1.0 if a_max / R > LARGE_STRAIN_RATIO else 0.0
    return (
        V,
        Vy,
        v,
        elastic,
        e,
        e * V,
        max_approach,
        plastic_approach,
        max_force,
        unloading_radius,
        1.0 - e * e,
        a_max,
        large,
        t1,
        t2,
        tL,
        tU,
        tL + tU,
    )


@jitable
def nan_outcome(V):
    """The outcome of an impact a model cannot evaluate (invalid parameters): NaN but the speed."""
    n = math.nan
    return (V, n, n, n, n, n, n, n, n, n, n, n, n, n, n, n, n, n)


@jitable
def dem_outcome(V, e, max_approach, plastic_approach, max_force, R, tL, tU):
    """Outcome of a DEM contact law: no yield point, so ``yield_velocity``, ``normalized_velocity``,
    ``unloading_radius`` and the stage times of the seed (``t1``, ``t2``) are NaN; ``elastic`` is
    1.0 where no energy is lost (``e == 1``)."""
    n = math.nan
    return pack(V, n, n, 1.0 if e == 1.0 else 0.0, e, max_approach, plastic_approach, max_force, n, R, n, n, tL, tU)


def no_parameters(name, params):
    """``validate`` of a model with no parameters of its own: ``params`` must be empty."""
    if len(params):
        raise ValueError(f"model {name!r} takes no parameters, got {params!r}")
    return ()
