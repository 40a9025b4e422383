"""Face of :mod:`microimpact.core.models.linear_spring_dashpot`: calibration, DEM input lines, style."""

from __future__ import annotations

from ..core.models import linear_spring_dashpot as law
from ._base import I_CONTACT_TIME, I_RESTITUTION, LAMMPS_TANGENTIAL, limit_force_option

__all__ = ["STYLE", "calibrate", "lammps", "liggghts"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#56B4E9", "linestyle": (0, (5, 1.5, 1, 1.5, 1, 1.5))}


def calibrate(pair_values, velocity, target_restitution, target_contact_time, *, limit_force=None):
    """Stiffness, restitution and force convention matching the mean target ``e`` and contact time.

    Returns ``(k, e_n, limit_force)`` (``e`` does not depend on the speed). ``limit_force`` 0 (default): ``e_n = e``; 1: ``e_n`` solved so that the
    clipped law gives ``e``. The contact time scales as ``k^(-1/2)`` at fixed ``e_n``."""
    from scipy.optimize import brentq

    limit = limit_force_option(limit_force, law)
    E, R, m, p_y = pair_values
    e_t = float(target_restitution.mean())
    t_t = float(target_contact_time.mean())
    if limit == 1.0:
        # e(e_n) with the force clipped: increasing in e_n, from its value at e_n -> 0 to 1
        def f(en):
            return law.outcome(1.0, E, R, m, p_y, (1.0, en, 1.0))[I_RESTITUTION] - e_t

        lo = 1e-300
        if f(lo) > 0.0:
            e_min = f(lo) + e_t
            raise ValueError(
                f"target_restitution {e_t!r} is below what the clipped linear law can give ({e_min:.6g}); use limit_force=0"
            )
        e_n = 1.0 if e_t == 1.0 else brentq(f, lo, 1.0, xtol=1e-300, rtol=1e-15, maxiter=500)
    else:
        e_n = e_t
    t1 = law.outcome(1.0, E, R, m, p_y, (1.0, e_n, limit))[I_CONTACT_TIME]
    return ((t1 / t_t) ** 2, e_n, limit)


def lammps(cal):
    """LAMMPS ``pair_coeff`` arguments: ``hooke`` with damping ``coeff_restitution``.

    As in LAMMPS ``doc/src/pair_granular.rst``, with the legacy ``pair_style gran/hooke`` line (``gamma_n = eta/m*``) as a comment."""
    p = cal.as_dict()
    k, e = p["stiffness"], p["restitution"]
    lim = " limit_damping" if p["limit_force"] == 1.0 else ""
    coeff = f"hooke {k:.12g} {e:.12g} {LAMMPS_TANGENTIAL} damping coeff_restitution{lim}"
    gamma_n = law.damping_coefficient(k, e, cal.effective_mass) / cal.effective_mass
    return coeff, f"# legacy equivalent: pair_style gran/hooke {k:.12g} NULL {gamma_n:.12g} 0.0 0.0 0{lim}"


def liggghts(cal, poisson, wall):
    """``gran model hooke/stiffness`` with ``kn`` and ``gamman = eta/m*``
    (``src/normal_model_hooke_stiffness.h``; ``limitForce`` for the clipped convention)."""
    p = cal.as_dict()
    k, e = p["stiffness"], p["restitution"]
    lim = "on" if p["limit_force"] == 1.0 else "off"
    gamma_n = law.damping_coefficient(k, e, cal.effective_mass) / cal.effective_mass
    return [
        f"pair_style gran model hooke/stiffness tangential no_history limitForce {lim}",
        "pair_coeff * *",
        f"fix m1 all property/global kn peratomtypepair 1 {k:.12g}",
        f"fix m2 all property/global kt peratomtypepair 1 {2.0 / 7.0 * k:.12g}",
        f"fix m3 all property/global gamman peratomtypepair 1 {gamma_n:.12g}",
        "fix m4 all property/global gammat peratomtypepair 1 0.0",
        "fix m5 all property/global coefficientFriction peratomtypepair 1 0.0",
        f"fix wall all wall/gran model hooke/stiffness tangential no_history primitive type 1 {wall} limitForce {lim}",
    ]
