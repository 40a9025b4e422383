"""A pair and adhesion: whether it lies in the limit (JKR or DMT) its adhesive model is written for,
by Tabor's parameter, and the speed at and below which its particle sticks."""

from __future__ import annotations

import math

import numpy as np

from .._validation import check_nonnegative, check_positive
from ..core import adhesion as _adhesion
from ..core import models
from ..core.models import thornton_ning_2016 as _seed

__all__ = ["tabor_check", "range_warning_text", "adhesion_range", "sticking_velocity"]


def tabor_check(mod, limit, p, z0, effective_modulus, effective_radius):
    """``(mu, outside)``: Tabor's parameter of the pair with ``mod``'s work of adhesion at ``p``, and
    whether it lies outside ``limit`` (never for a work of adhesion of zero)."""
    G = float(mod.work_of_adhesion(p))
    mu = _adhesion.tabor_parameter(effective_modulus, effective_radius, G, z0) if G > 0.0 else 0.0
    outside = mu < _adhesion.TABOR_JKR if limit == "JKR" else mu > _adhesion.TABOR_DMT
    return mu, bool(outside and G > 0.0)


def range_warning_text(name, limit, mu):
    """The warning of a pair outside its adhesive model's limit."""
    if limit == "JKR":
        where = f"below {_adhesion.TABOR_JKR:g}: the JKR limit of {name} does not hold"
        if mu < _adhesion.TABOR_DMT:
            where += " (the DMT limit does: small, stiff particles)"
    else:
        where = f"above {_adhesion.TABOR_DMT:g}: the DMT limit of {name} does not hold"
        if mu > _adhesion.TABOR_JKR:
            where += " (the JKR limit does)"
    return f"Tabor parameter {mu:.3g} (z0 = 0.3 nm) {where}; results flagged in .outside_adhesion_range"


def adhesion_range(pair, model, equilibrium_separation, params) -> dict:
    """:meth:`ContactPair.adhesion_range <microimpact.pair.ContactPair.adhesion_range>`."""
    mod = models.get(model)
    limit = mod.ADHESION_LIMIT
    if limit is None:
        raise ValueError(f"model {model!r} has no adhesion limit (it is not a JKR or DMT adhesive law)")
    p = models.resolve_params(mod, params)
    z0 = _adhesion.EQUILIBRIUM_SEPARATION if equilibrium_separation is None else equilibrium_separation
    z0 = float(check_positive("equilibrium_separation", z0, scalar=True))
    if not math.isfinite(z0):
        raise ValueError(f"equilibrium_separation must be positive and finite, got {equilibrium_separation!r}")
    mu, outside = tabor_check(mod, limit, p, z0, pair.effective_modulus, pair.effective_radius)
    return {
        "tabor_parameter": mu,
        "limit": limit,
        "inside": not outside,
        "work_of_adhesion": float(mod.work_of_adhesion(p)),
        "equilibrium_separation": z0,
    }


def _values(pair):
    return (pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure)


def sticking_velocity(pair, diameter, model, params):
    """:meth:`ContactPair.sticking_velocity <microimpact.pair.ContactPair.sticking_velocity>`."""
    if model is None:
        model = models.whole_law()
    if model == "additive":
        unknown = sorted(set(params) - {"work_of_adhesion"})
        if unknown or "work_of_adhesion" not in params:
            raise ValueError(
                "the additive rule takes one parameter, work_of_adhesion"
                + (f"; got {unknown[0]!r}" if unknown else " (no default)")
            )
        G = params["work_of_adhesion"]
        G = float(check_nonnegative("work_of_adhesion", G))

        def one(pair):
            E, R, m, p_y = _values(pair)
            return _adhesion.capture_velocity(
                _seed.yield_point(E, R, m, p_y)[2], _adhesion.sticking_velocity(G, E, R, m)
            )

    else:
        mod = models.get(model)
        fn = mod.sticking_velocity
        if fn is None:
            names = [n for n in models.available() if models.get(n).sticking_velocity is not None]
            raise ValueError(
                f"model {model!r} has no sticking velocity; models that have one: {', '.join(names)}, additive"
            )
        p = models.resolve_params(mod, params)

        def one(pair):
            return fn(*_values(pair), p)

    if diameter is None:
        return float(one(pair))
    d = check_positive("diameter", diameter)
    if pair.density is None:
        raise ValueError("diameters need a pair with a particle density (a sphere on a flat)")
    out = np.array([one(pair.resized(radius=0.5 * x)) for x in d.ravel()]).reshape(d.shape)
    return float(out) if np.ndim(diameter) == 0 else out
