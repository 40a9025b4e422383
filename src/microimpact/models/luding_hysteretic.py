"""Face of :mod:`microimpact.core.models.luding_hysteretic`: calibration, LIGGGHTS lines, style."""

from __future__ import annotations

import math

import numpy as np

from ..core import hertz
from ..core.models import luding_hysteretic as law
from ._base import run

__all__ = ["STYLE", "COMPARE_OPTIONS", "calibrate", "liggghts"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#CC79A7", "linestyle": (0, (8, 2))}
#: Compared with the seed as Luding's law (LIGGGHTS ``hooke/hysteresis``), whose ``e`` varies with speed.
COMPARE_OPTIONS = {"plasticity": True}


def calibrate(
    pair_values, velocity, target_restitution, target_contact_time, *, plasticity=False, unloading_ratio=None
):
    """Loading and unloading stiffness and plasticity depth giving the target ``e`` and contact time.

    Returns ``(k1, k2, phi_f)``. ``plasticity=False``: the constant-``k2`` spring, ``k1`` from the mean
    contact time (``t_c = pi (1 + e)/(2 omega_1)``) and ``k2 = k1/e^2``. ``plasticity=True``:
    Luding's ``k2(alpha_max)`` (LIGGGHTS ``hooke/hysteresis``) with ``k2 = unloading_ratio k1``
    (``> 1/e^2``, default ``2/e^2``) and the ``plasticity_depth`` that matches ``e`` (in closed form
    at one speed; least squares in ``ln phi_f`` over several)."""
    if not isinstance(plasticity, bool):
        raise ValueError(f"plasticity must be True or False, got {plasticity!r}")
    E, R, m, p_y = pair_values
    V, e_t, t_t = velocity, target_restitution, target_contact_time
    if not plasticity:
        if unloading_ratio is not None:
            raise ValueError(f"unloading_ratio applies to plasticity=True only, got {unloading_ratio!r}")
        e_mean = float(np.mean(e_t))
        k1 = law.loading_stiffness_for(e_mean, float(np.mean(t_t)), m)
        return (k1, k1 / (e_mean * e_mean), 0.0)
    e0 = float(e_t[0]) if V.size == 1 else float(np.mean(e_t))
    t0 = float(np.mean(t_t))
    ratio = unloading_ratio
    if ratio is None:
        ratio = 2.0 / (e0 * e0)
    if isinstance(ratio, bool) or not (ratio > 1.0 / (e0 * e0) and math.isfinite(ratio)):
        raise ValueError(f"unloading_ratio must be finite and > 1/e^2 = {1.0 / (e0 * e0):.6g}, got {ratio!r}")
    k1 = law.loading_stiffness_for(e0, t0, m)
    k2 = ratio * k1
    if V.size == 1:
        return (k1, k2, law.plasticity_depth_for(float(V[0]), e0, k1, k2, m, R))

    from scipy.optimize import minimize_scalar

    def cost(logphi):
        e, _ = run(law, V, pair_values, (k1, k2, math.exp(logphi)))
        return float(np.sum((e - e_t) ** 2))

    a1 = float(np.max(V)) * math.sqrt(m / k1)
    guess = math.log(a1 / (2.0 * R))  # phi_f of order alpha_max/(2 R*)
    r = minimize_scalar(cost, bounds=(guess - 20.0, guess + 20.0), method="bounded", options={"xatol": 1e-10})
    return (k1, k2, math.exp(r.x))


def liggghts(cal, poisson, wall):
    """LIGGGHTS lines of Luding's law: ``gran model hooke/hysteresis``.

    Needs ``plasticity_depth > 0``. Its ``k1`` comes from
    ``youngsModulus``/``poissonsRatio`` and ``characteristicVelocity``
    (``kn = 16/15 R^(1/2) Y* (15 m v_c^2/(16 R^(1/2) Y*))^(1/5)``, ``src/normal_model_hooke.h``),
    here ``youngsModulus = 2 (1 - nu^2) E*`` so that ``Y* = E*``, and ``v_c`` solved for ``k1``;
    ``coefficientRestitution 1`` (no viscous damping) and ``coefficientAdhesionStiffness 0``. The
    constant-``k2`` spring has no LIGGGHTS model: ValueError."""
    p = cal.as_dict()
    if not p["plasticity_depth"] > 0.0:
        raise ValueError(
            f"LIGGGHTS has no normal model for {cal.model!r} with these parameters "
            "(use plasticity_depth > 0: hooke/hysteresis)"
        )
    k1, k2, phi = p["loading_stiffness"], p["unloading_stiffness"], p["plasticity_depth"]
    E, R, m = cal.effective_modulus, cal.effective_radius, cal.effective_mass
    vc = law.characteristic_velocity(k1, E, R, m)
    Y = hertz.equal_bodies_modulus(E, poisson)
    return [
        "pair_style gran model hooke/hysteresis tangential no_history",
        "pair_coeff * *",
        f"fix m1 all property/global youngsModulus peratomtype {Y:.12g}",
        f"fix m2 all property/global poissonsRatio peratomtype {poisson:.12g}",
        "fix m3 all property/global coefficientRestitution peratomtypepair 1 1.0",
        "fix m4 all property/global coefficientFriction peratomtypepair 1 0.0",
        f"fix m5 all property/global characteristicVelocity scalar {vc:.12g}",
        f"fix m6 all property/global coefficientMaxElasticStiffness peratomtypepair 1 {k2 / k1:.12g}",
        "fix m7 all property/global coefficientAdhesionStiffness peratomtypepair 1 0.0",
        f"fix m8 all property/global coefficientPlasticityDepth peratomtypepair 1 {phi:.12g}",
        f"fix wall all wall/gran model hooke/hysteresis tangential no_history primitive type 1 {wall}",
    ]
