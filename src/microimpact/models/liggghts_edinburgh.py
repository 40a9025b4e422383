"""Face of :mod:`microimpact.core.models.liggghts_edinburgh`: calibration, LIGGGHTS lines, style.

The LIGGGHTS lines set the code's own inputs to the model's parameters one for one (the property
names are those of ``src/global_properties.cpp`` at commit ``84ba3d76``): ``UnloadingStiffness``,
``overlapExponent``, ``adhesionExponent``, ``coefficientRestitution``, ``surfaceEnergy``,
``coefficientAdhesionStiffness``, ``pullOffForce``, and the model's switches ``fixKc`` and
``limitForce``; ``youngsModulus = 2 (1 - nu^2) E*`` so that particle and wall, one material, mix to
``Yeff = E*``.
"""

from __future__ import annotations

import math

import numpy as np

from ..core import hertz
from ..core.models import get as _get
from ..core.models import liggghts_edinburgh as law

__all__ = ["STYLE", "calibrate", "liggghts", "params_for_work_of_adhesion"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#D55E00", "linestyle": (0, (5, 1, 1, 1, 1, 1))}


def calibrate(pair_values, velocity, target_restitution, target_contact_time, **options):
    """The ``unloading_ratio`` ``k2/k1`` that gives the target ``e`` (the mean of the targets, at the
    mean speed), the other parameters at ``options`` (their names, else the defaults: no damping, no
    adhesion, ``n = x = 3/2``). The contact time is not matched: ``k1`` is ``E*``'s (``4/3 E* R*^(1/2)``).
    ValueError where the target cannot be reached (an ``e`` that the other inputs already take away, or
    a captured particle)."""
    from scipy.optimize import brentq

    spec = _get(law.NAME)
    names = [p.name for p in spec.PARAMETERS]
    unknown = sorted(set(options) - set(names) - {"unloading_ratio"})
    if unknown:
        raise ValueError(f"model {law.NAME!r} has no parameter {unknown[0]!r}")
    if "unloading_ratio" in options:
        raise ValueError("unloading_ratio is what the calibration finds; do not give it")
    E, R, m, p_y = pair_values
    V = float(np.mean(velocity))
    e_t = float(np.mean(target_restitution))
    values = dict(zip(names, spec.DEFAULTS))
    values.update({k: float(v) for k, v in options.items()})

    def params_of(log_r):
        values["unloading_ratio"] = 1.0 + math.exp(log_r)
        return spec.validate(tuple(values.values()))

    def miss(log_r):
        return law.outcome(V, E, R, m, p_y, params_of(log_r))[4] - e_t

    elastic = params_of(-math.inf)  # k2 = k1: no plastic loss
    if abs(law.outcome(V, E, R, m, p_y, elastic)[4] - e_t) <= 1e-12:
        return elastic
    lo, hi = -30.0, 30.0
    f_lo, f_hi = miss(lo), miss(hi)
    if not (f_lo >= 0.0 >= f_hi):
        raise ValueError(
            f"target_restitution {e_t!r} is out of reach of {law.NAME!r} at {V!r} m/s with these inputs "
            f"(e runs from {f_lo + e_t:.6g} to {f_hi + e_t:.6g} as unloading_ratio grows)"
        )
    r = brentq(miss, lo, hi, xtol=1e-14, rtol=1e-14)
    return params_of(r)


def liggghts(cal, poisson, wall):
    """``gran model edinburgh`` with the model's inputs (module docstring); ``tangential no_history``."""
    p = cal.as_dict()
    lim = "on" if p["limit_force"] == 1.0 else "off"
    fix = "on" if p["fix_kc"] == 1.0 else "off"
    Y = hertz.equal_bodies_modulus(cal.effective_modulus, poisson)
    opts = f"limitForce {lim} fixKc {fix}"
    return [
        f"pair_style gran model edinburgh tangential no_history {opts}",
        "pair_coeff * *",
        f"fix m1 all property/global youngsModulus peratomtype {Y:.15g}",
        f"fix m2 all property/global poissonsRatio peratomtype {poisson:.15g}",
        f"fix m3 all property/global coefficientRestitution peratomtypepair 1 {p['coefficient_restitution']:.15g}",
        "fix m4 all property/global coefficientFriction peratomtypepair 1 0.0",
        f"fix m5 all property/global UnloadingStiffness peratomtypepair 1 {p['unloading_ratio']:.15g}",
        f"fix m6 all property/global overlapExponent scalar {p['overlap_exponent']:.15g}",
        f"fix m7 all property/global adhesionExponent scalar {p['adhesion_exponent']:.15g}",
        f"fix m8 all property/global surfaceEnergy peratomtypepair 1 {p['work_of_adhesion']:.15g}",
        f"fix m9 all property/global coefficientAdhesionStiffness peratomtypepair 1 "
        f"{p['adhesion_stiffness_ratio']:.15g}",
        f"fix m10 all property/global pullOffForce peratomtypepair 1 {p['pull_off_force']:.15g}",
        f"fix wall all wall/gran model edinburgh tangential no_history primitive type 1 {wall} {opts}",
    ]


def params_for_work_of_adhesion(work_of_adhesion, pair_values, params):
    """``params`` with the code's ``surfaceEnergy`` set to the work of adhesion ``G`` [J/m^2] and
    ``fix_kc = 0``: the code's pull-off ``f_min = 1.5 pi Gamma a`` is the JKR pull-off ``3/2 pi G R`` with
    the plastic contact radius ``a`` for ``R``, so its ``Gamma`` is ``G`` (not the surface energy ``G/2``
    of one surface). On a wall (``two_spheres = 0``) the code takes ``a = 0``: ``G`` has no effect there."""
    G = float(work_of_adhesion)
    if not (G >= 0.0 and math.isfinite(G)):
        raise ValueError(f"work_of_adhesion must be non-negative and finite, got {work_of_adhesion!r}")
    spec = _get(law.NAME)
    values = dict(zip((p.name for p in spec.PARAMETERS), params))
    values["work_of_adhesion"] = G
    values["fix_kc"] = 0.0
    return spec.validate(tuple(values.values()))
