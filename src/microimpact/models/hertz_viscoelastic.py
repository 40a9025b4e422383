"""Face of :mod:`microimpact.core.models.hertz_viscoelastic`: calibration, LAMMPS lines, style."""

from __future__ import annotations

import math

import numpy as np

from ..core import hertz
from ..core.models import hertz_viscoelastic as law
from ._base import LAMMPS_TANGENTIAL, limit_force_option, run

__all__ = ["STYLE", "calibrate", "lammps"]

#: Matplotlib keywords of the model's line in comparison figures (Okabe-Ito colours).
STYLE = {"color": "#0072B2", "linestyle": "-."}


def calibrate(pair_values, velocity, target_restitution, target_contact_time, *, limit_force=None):
    """Dissipative constant and force convention giving the target ``e``.

    Returns ``(A, limit_force)``: at one speed the root of ``e(kappa)`` (``kappa = A/T``), over several
    the least-squares ``A`` (bounded search in ``ln A`` around the single-speed value at the median
    speed). Hertz's stiffness is fixed, so the contact time is not matched."""
    limit = limit_force_option(limit_force, law)
    return (_dissipative_constant(velocity, target_restitution, limit, pair_values), limit)


def _dissipative_constant(V, e_t, limit, pv):
    from scipy.optimize import brentq, minimize_scalar

    E, R, m, p_y = pv
    rho = 4.0 / 3.0 * E * math.sqrt(R)

    def T(v):
        return (m / (rho * math.sqrt(v))) ** 0.4

    if V.size == 1:
        e0 = float(e_t[0])
        if e0 == 1.0:
            return 0.0

        def f(kappa):
            return law.scaled_restitution(kappa, limit == 1.0, 0.5) - e0

        hi = 1.0
        while f(hi) > 0.0:
            hi *= 2.0
            if hi > 1e6:
                raise ValueError(f"target_restitution {e0!r} cannot be reached by the viscoelastic law")
        kappa = brentq(f, 0.0, hi, xtol=1e-16, rtol=1e-15, maxiter=500)
        return kappa * hertz.dem_time_scale(float(V[0]), E, R, m)

    model = law  # the module has the contract's outcome: run() needs only .outcome

    def cost(logA):
        e, _ = run(model, V, pv, (math.exp(logA), limit))
        return float(np.sum((e - e_t) ** 2))

    # start from the single-speed value at the middle speed
    mid = float(np.median(V))
    A0 = _dissipative_constant(np.array([mid]), np.array([float(np.interp(mid, V, e_t))]), limit, pv)
    g = math.log(A0) if A0 > 0.0 else 0.0
    r = minimize_scalar(cost, bounds=(g - 5.0, g + 5.0), method="bounded", options={"xatol": 1e-10})
    return math.exp(r.x)


def lammps(cal):
    """LAMMPS ``pair_coeff`` arguments: ``hertz`` with damping ``viscoelastic``, ``eta_n0 = 4 E* A/(3 m*)``."""
    p = cal.as_dict()
    A = p["dissipative_constant"]
    k_n = 4.0 / 3.0 * cal.effective_modulus
    eta0 = 4.0 * cal.effective_modulus * A / (3.0 * cal.effective_mass)
    lim = " limit_damping" if p["limit_force"] == 1.0 else ""
    coeff = f"hertz {k_n:.12g} {eta0:.12g} {LAMMPS_TANGENTIAL} damping viscoelastic{lim}"
    return coeff, f"# eta_n0 = 4 E* A / (3 m*) for m* = {cal.effective_mass:.12g} kg (one particle size only)"
