"""Helpers shared by the model files (private: not a model, so not listed by ``available()``).

Everything here is plain Python over floats in numba's subset, marked ``@jitable`` like the
model functions that call it.
"""

from __future__ import annotations

import math

from .._jit import jitable
from ..constants import LARGE_STRAIN_RATIO  # noqa: F401  (re-exported for the model files)

__all__ = ["LARGE_STRAIN_RATIO", "pack", "pack_beyond", "nan_outcome", "dem_outcome", "in_bounds"]


@jitable
def pack(
    V,
    Vy,
    v,
    elastic,
    e,
    rebound,
    max_approach,
    plastic_approach,
    max_force,
    unloading_radius,
    contact_radius,
    R,
    t1,
    t2,
    tL,
    tU,
):
    """One outcome tuple in :data:`~microimpact.core.quantities.OUTCOME_FIELDS` order: the one place
    every model's :func:`outcome` returns through.

    Derived here, so that every model computes them the same way: ``energy_loss = 1 - e^2`` (seed
    eq. 29), ``large_strain`` (``contact_radius / R* >``
    :data:`~microimpact.core.constants.LARGE_STRAIN_RATIO`, as 1.0/0.0) and ``contact_time = t_L + t_U``.
    """
    large = 1.0 if contact_radius / R > LARGE_STRAIN_RATIO else 0.0
    return (
        V,
        Vy,
        v,
        elastic,
        e,
        rebound,
        max_approach,
        plastic_approach,
        max_force,
        unloading_radius,
        1.0 - e * e,
        contact_radius,
        large,
        t1,
        t2,
        tL,
        tU,
        tL + tU,
    )


@jitable
def pack_beyond(
    V,
    Vy,
    v,
    elastic,
    e,
    rebound,
    max_approach,
    plastic_approach,
    max_force,
    unloading_radius,
    contact_radius,
    R,
    beyond,
    t1,
    t2,
    tL,
    tU,
):
    """:func:`pack`, for a law whose stated range ends before the small-strain limit too: ``beyond``
    1.0 sets ``large_strain`` (the impact is outside that range) whatever ``contact_radius / R``
    gives; 0.0 leaves :func:`pack`'s flag. The tuple is :func:`pack`'s."""
    out = pack(
        V, Vy, v, elastic, e, rebound, max_approach, plastic_approach, max_force, unloading_radius, contact_radius, R,
        t1, t2, tL, tU,
    )  # fmt: skip
    if beyond == 1.0 and out[12] == 0.0:
        return out[:12] + (1.0,) + out[13:]
    return out


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
    a_c = math.sqrt(R * max_approach)  # Hertz geometry (seed eq. 3), for comparison
    return pack(
        V, n, n, 1.0 if e == 1.0 else 0.0, e, e * V, max_approach, plastic_approach, max_force, n, a_c, R, n, n, tL, tU
    )


@jitable
def in_bounds(params, bounds):
    """The compiled check of a model's ``params`` against its ``BOUNDS`` (made by
    :func:`microimpact.core.models.checks` from ``PARAMETERS``): right length, each value in its
    interval and no subnormal where it refuses one, flags 0 or 1. False rather than an exception, so that ``outcome`` returns NaN."""
    if len(params) != len(bounds):
        return False
    for i in range(len(bounds)):
        b = bounds[i]
        x = params[i]
        if b[5] == 1.0:
            if not (x == 0.0 or x == 1.0):
                return False
            continue
        lo = b[0] if b[4] < 0.0 else params[int(b[4])]
        if not (x > lo if b[2] == 1.0 else x >= lo):
            return False
        if not (x < b[1] if (b[3] == 1.0 or b[1] == math.inf) else x <= b[1]):
            return False
        if b[6] == 1.0 and x != 0.0 and abs(x) < 2.2250738585072014e-308:  # Parameter.refuses_subnormal
            return False
    return True
