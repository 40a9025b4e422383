"""Face of :mod:`microimpact.core.models.liggghts_hertz_sjkr`: calibration, LIGGGHTS lines, the
work-of-adhesion map, style."""

from __future__ import annotations

import math

import numpy as np

from ..core import hertz
from ..core.models import liggghts_hertz_sjkr as law
from ._base import limit_force_option

__all__ = ["STYLE", "calibrate", "liggghts", "params_for_work_of_adhesion", "pulloff_force"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#0072B2", "linestyle": (0, (5, 1, 1, 1))}

#: Smallest ``coefficientRestitution`` LIGGGHTS accepts (its ``createCoeffRest`` check).
LIGGGHTS_MIN_RESTITUTION = 0.05


def _flag(name, value):
    if isinstance(value, bool) or value not in (0, 1):
        raise ValueError(f"{name} must be 0 or 1, got {value!r}")
    return float(value)


def calibrate(
    pair_values,
    velocity,
    target_restitution,
    target_contact_time,
    *,
    cohesion_energy_density=0.0,
    sjkr2=0,
    on_wall=1,
    limit_force=None,
):
    """``(e_n, k, sjkr2, on_wall, limit_force)`` whose mean ``e`` over the speeds ``velocity`` is
    the mean target ``e``: ``k`` (``cohesion_energy_density`` [J/m^3], 0 by default; see
    :func:`params_for_work_of_adhesion` for one from a work of adhesion) and the variant are given,
    ``e_n`` is the root of the mean ``e`` in ``(0.05, 1]`` (``e`` rises with ``e_n`` at every speed).
    Hertz's stiffness is fixed by ``E*`` and ``R*``: the contact time is not matched."""
    from scipy.optimize import brentq

    limit = limit_force_option(limit_force, law)
    k = float(cohesion_energy_density)
    if not (k >= 0.0 and math.isfinite(k)):
        raise ValueError(f"cohesion_energy_density must be non-negative and finite, got {cohesion_energy_density!r}")
    rest = (k, _flag("sjkr2", sjkr2), _flag("on_wall", on_wall), limit)
    E, R, m, p_y = pair_values
    V = np.atleast_1d(np.asarray(velocity, dtype=float))
    e_t = float(np.mean(target_restitution))

    def f(e_n):
        p = (e_n, *rest)
        return float(np.mean([law.restitution_only(float(v), E, R, m, p_y, p) for v in V])) - e_t

    lo = LIGGGHTS_MIN_RESTITUTION * (1.0 + 1e-9)
    if f(1.0) < 0.0:
        raise ValueError(f"target_restitution {e_t!r} is above what this law can give ({f(1.0) + e_t:.6g})")
    if f(lo) > 0.0:
        raise ValueError(f"target_restitution {e_t!r} is below what this law can give ({f(lo) + e_t:.6g})")
    return (brentq(f, lo, 1.0, xtol=1e-15, rtol=1e-15, maxiter=500), *rest)


def liggghts(cal, poisson, wall):
    """``gran model hertz`` with ``cohesion sjkr`` (or ``sjkr2``) for the pair and the primitive wall,
    ``coefficientRestitution`` ``e_n`` and ``cohesionEnergyDensity`` ``k``; ``youngsModulus = 2 (1 -
    nu^2) E*`` so that ``Y* = E*`` for one material on itself (particle and wall of type 1)."""
    p = cal.as_dict()
    e_n, k = p["restitution"], p["cohesion_energy_density"]
    if not e_n > LIGGGHTS_MIN_RESTITUTION:
        raise ValueError(f"LIGGGHTS requires coefficientRestitution > 0.05; this law has {e_n!r}")
    lim = "on" if p["limit_force"] == 1.0 else "off"
    coh = "sjkr2" if p["sjkr2"] == 1.0 else "sjkr"
    Y = hertz.equal_bodies_modulus(cal.effective_modulus, poisson)
    return [
        f"pair_style gran model hertz tangential no_history cohesion {coh} limitForce {lim}",
        "pair_coeff * *",
        f"fix m1 all property/global youngsModulus peratomtype {Y:.12g}",
        f"fix m2 all property/global poissonsRatio peratomtype {poisson:.12g}",
        f"fix m3 all property/global coefficientRestitution peratomtypepair 1 {e_n:.12g}",
        "fix m4 all property/global coefficientFriction peratomtypepair 1 0.0",
        f"fix m5 all property/global cohesionEnergyDensity peratomtypepair 1 {k:.12g}",
        f"fix wall all wall/gran model hertz tangential no_history cohesion {coh} primitive type 1 {wall} "
        f"limitForce {lim}",
    ]


def pulloff_force(E, R, params):
    """The largest tensile force [N] the resting contact holds, ``max_alpha (k A(alpha) - 4/3 E*
    R*^(1/2) alpha^(3/2))``: ``(pi c_1 k)^3 R*^2/(12 E*^2)`` at ``alpha = (pi c_1 k R*/(2 E* R*^(1/2)))^2``
    in the small-strain limit (``c_2`` dropped; derived in docs/laws/liggghts_hertz_sjkr.rst)."""
    c1 = law.area_coefficients(params)[0]
    return (math.pi * c1 * params[1]) ** 3 * R * R / (12.0 * E * E)


def params_for_work_of_adhesion(work_of_adhesion, pair_values, params):
    """``params`` with ``cohesionEnergyDensity`` set so that the contact's pull-off force
    (:func:`pulloff_force`) is JKR's ``3/2 pi G R*``: ``k = (18 G E*^2/(pi^2 c_1^3 R*))^(1/3)``
    (``(9 G E*^2/(4 pi^2 R*))^(1/3)`` with sjkr, or sjkr2 at a wall).

    LIGGGHTS' documentation calls ``k`` a "cohesion energy density in J/m3" and relates it to no
    surface energy: this map is derived here and approximate. It matches one number, the static
    pull-off force; the sjkr contact has no JKR neck, so its equilibrium overlap at zero load
    (``(pi c_1 k R*^(1/2)/(4/3 E*))^2``, 16/9 of the force maximum's) and the energy it takes to
    separate differ from JKR's, and ``k`` depends on ``E*`` and ``R*``: one value per pair (a
    polydisperse LIGGGHTS run with one ``k`` has one ``G`` per size only approximately).
    """
    G = float(work_of_adhesion)
    if not (G >= 0.0 and math.isfinite(G)):
        raise ValueError(f"work_of_adhesion must be non-negative and finite, got {work_of_adhesion!r}")
    E, R = pair_values[0], pair_values[1]
    c1 = law.area_coefficients(params)[0]
    k = (18.0 * G * E * E / (math.pi**2 * c1**3 * R)) ** (1.0 / 3.0)
    return (params[0], k, *tuple(params[2:]))
