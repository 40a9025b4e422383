"""Face of :mod:`microimpact.core.models.hertz_tsuji`: calibration, DEM input lines, style."""

from __future__ import annotations

import math

from ..core import hertz
from ..core.models import hertz_tsuji as law
from ._base import I_RESTITUTION, LAMMPS_TANGENTIAL, limit_force_option

__all__ = ["STYLE", "calibrate", "lammps", "liggghts"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#D55E00", "linestyle": "--"}


def calibrate(pair_values, velocity, target_restitution, target_contact_time, *, limit_force=None):
    """Damping ratio and force convention giving the mean target ``e``.

    Returns ``(alpha_T, limit_force)`` (``e`` is constant in speed; Hertz's stiffness is fixed by
    ``E*`` and ``R*``, so the contact time is not matched): the root of ``e(alpha_T)``
    below LAMMPS' critical damping ``alpha_T = 5^(1/2)``."""
    from scipy.optimize import brentq

    limit = limit_force_option(limit_force, law)
    E, R, m, p_y = pair_values
    e_t = float(target_restitution.mean())

    def f(a):
        return law.outcome(1.0, E, R, m, p_y, (a, limit))[I_RESTITUTION] - e_t

    if e_t == 1.0:
        return (0.0, limit)
    hi = math.sqrt(5.0) * (1.0 - 1e-9)  # critical damping of coeff_restitution's formula
    if f(hi) > 0.0:
        e_min = f(hi) + e_t
        raise ValueError(f"target_restitution {e_t!r} is below what this law can give ({e_min:.6g})")
    return (brentq(f, 0.0, hi, xtol=1e-16, rtol=1e-15, maxiter=500), limit)


def lammps(cal, damping="coeff_restitution", tsuji_sqrt2=False):
    """LAMMPS ``pair_coeff`` arguments: ``hertz`` with damping ``coeff_restitution`` (or ``tsuji``) at the ``e_n`` that gives ``alpha_T``."""
    p = cal.as_dict()
    k_n = 4.0 / 3.0 * cal.effective_modulus
    lim = " limit_damping" if p["limit_force"] == 1.0 else ""
    if damping == "tsuji":
        e_n = _tsuji_input(p["damping_ratio"], tsuji_sqrt2)
        coeff = f"hertz {k_n:.12g} {e_n:.12g} {LAMMPS_TANGENTIAL} damping tsuji{lim}"
        return coeff, "# damping tsuji: eta_n = alpha_T (m* k_nd)^(1/2), alpha_T = Marshall's polynomial of e_n" + (
            " times 2^(1/2) (LAMMPS development source after July 2026)"
            if tsuji_sqrt2
            else " (LAMMPS 22 Jul 2025 and earlier)"
        )
    e_n = law.code_restitution(p["damping_ratio"])
    coeff = f"hertz {k_n:.12g} {e_n:.12g} {LAMMPS_TANGENTIAL} damping coeff_restitution{lim}"
    return coeff, "# coeff_restitution with hertz: eta_n = alpha_T (m* k_nd)^(1/2), k_nd = 4/3 E* a"


def _tsuji_input(alpha, sqrt2):
    """The ``e_n`` LAMMPS' ``damping tsuji`` turns into ``alpha`` (Marshall's polynomial decreases on [0, 1])."""
    from scipy.optimize import brentq

    lo, hi = law.alpha_tsuji(1.0, sqrt2), law.alpha_tsuji(0.0, sqrt2)
    if not lo <= alpha <= hi:
        raise ValueError(
            f"damping tsuji cannot give damping_ratio {alpha!r}: its e_n in [0, 1] covers {lo:.6g} to {hi:.6g}; "
            "use damping='coeff_restitution'"
        )
    return brentq(lambda x: law.alpha_tsuji(x, sqrt2) - alpha, 0.0, 1.0, xtol=1e-15, rtol=1e-15, maxiter=500)


def liggghts(cal, poisson, wall):
    """``gran model hertz`` with ``coefficientRestitution`` the ``e_n`` that gives ``alpha_T``
    (``youngsModulus = 2 (1 - nu^2) E*`` so that ``Y* = E*``); LIGGGHTS needs ``e_n > 0.05``."""
    p = cal.as_dict()
    e_n = law.code_restitution(p["damping_ratio"])
    if not e_n > 0.05:
        raise ValueError(f"LIGGGHTS requires coefficientRestitution > 0.05; this law needs {e_n!r}")
    lim = "on" if p["limit_force"] == 1.0 else "off"
    Y = hertz.equal_bodies_modulus(cal.effective_modulus, poisson)
    return [
        f"pair_style gran model hertz tangential no_history limitForce {lim}",
        "pair_coeff * *",
        f"fix m1 all property/global youngsModulus peratomtype {Y:.12g}",
        f"fix m2 all property/global poissonsRatio peratomtype {poisson:.12g}",
        f"fix m3 all property/global coefficientRestitution peratomtypepair 1 {e_n:.12g}",
        "fix m4 all property/global coefficientFriction peratomtypepair 1 0.0",
        f"fix wall all wall/gran model hertz tangential no_history primitive type 1 {wall} limitForce {lim}",
    ]
