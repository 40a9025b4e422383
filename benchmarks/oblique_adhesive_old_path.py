"""The error of wall_interaction's former adhesive tangential approximation against its integrated path.

Until the adhesive integration replaced it, ``wall_interaction(..., tangential="mindlin", adhesion=<the
whole law>, work_of_adhesion=G)`` took the tangential impulse of the non-adhesive universal table,
``J_t = F(psi, V_y/V) mu J_n`` with ``psi = kappa |u_t| / (mu V)``, scaled by the adhesive normal impulse
``J_n = m (1 + e) V`` (``e`` and the capture from the whole law's table), and stopped a captured particle
dead. This script rebuilds that approximation from the public pieces (the universal table, and the
rigid path's normal outcome, which is the same) and compares it with ``wall_interaction`` now, which
integrates each adhesive impact (:func:`microimpact.oblique.adhesive.adhesive_oblique_impact`), on a
grid of speed and angle (with and without spin), and times the integrated path per particle: the numbers
of ``docs/laws/oblique_adhesive.rst``.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np

from microimpact.adhesion import WHOLE_LAW
from microimpact.core.tangential import stiffness_ratio_same_poisson
from microimpact.oblique import universal_table
from microimpact.wall import wall_interaction

R, RHO, E, NU, G, MU = 5e-6, 2500.0, 5e9, 0.25, 0.1, 0.3
KAPPA = stiffness_ratio_same_poisson(NU)
SPEEDS = np.array([0.12, 0.2, 0.5, 1.0, 3.0])
ANGLES = np.array([10.0, 30.0, 50.0, 70.0, 80.0])


def old_path(vel, spin_y, p_y):
    """The former approximation for particles in the x-z plane (wall normal +z, spin about y, v_x > 0
    and a slip along +x): ``(v_x', R omega_y', stuck)``."""
    kw = dict(effective_modulus=E, limiting_pressure=p_y, work_of_adhesion=G, friction=MU, adhesion=WHOLE_LAW)
    spin = np.column_stack([0 * spin_y, spin_y, 0 * spin_y])
    normal = wall_interaction(vel, [0, 0, 1], 2 * R, RHO, spin=spin, **kw)  # the rigid path: the same e, capture
    V, e, Vy = normal.normal_speed, normal.restitution, normal.yield_velocity
    slip = vel[:, 0] - R * spin_y  # u_t = v_t + r n x omega, along x
    F = universal_table(KAPPA)(KAPPA * slip / (MU * V), np.minimum(Vy / V, 1.0))
    J = F * MU * (1.0 + e) * V  # |J_t| / m against the slip
    v = np.where(normal.stuck, 0.0, vel[:, 0] - J)
    w = np.where(normal.stuck, 0.0, R * spin_y + 2.5 * J)  # R omega_y: omega' = omega - 5/(2 m r) n x J_t
    return v, w, normal.stuck


def main():
    warnings.simplefilter("ignore")
    A, S = np.meshgrid(ANGLES, SPEEDS)
    speed, angle = S.ravel(), A.ravel()
    th = np.radians(angle)
    vel = np.column_stack([speed * np.sin(th), 0 * th, -speed * np.cos(th)])
    for p_y in (math.inf, 5e7):
        for label, spin_y in (("no spin", 0.0 * speed), ("back spin R omega = -v_t/2", 0.5 * vel[:, 0] / R)):
            v_old, w_old, stuck_old = old_path(vel, spin_y, p_y)
            spin = np.column_stack([0 * spin_y, spin_y, 0 * spin_y])
            t0 = time.perf_counter()
            new = wall_interaction(
                vel, [0, 0, 1], 2 * R, RHO, effective_modulus=E, limiting_pressure=p_y, work_of_adhesion=G,
                friction=MU, spin=spin, tangential="mindlin", adhesion=WHOLE_LAW, poisson_ratio=NU,
            )  # fmt: skip
            cost = (time.perf_counter() - t0) / speed.size * 1e3
            ok = ~new.stuck & ~stuck_old
            dv = np.abs(v_old - new.velocity[:, 0]) / speed
            dw = np.abs(w_old - R * new.spin[:, 1]) / speed
            print(
                f"p_y = {p_y:g} Pa, {label}: {ok.sum()} of {speed.size} bounce, "
                f"{int((new.stuck != stuck_old).sum())} capture disagreements; max |dv_t'|/V {dv[ok].max():.3f} "
                f"(mean {dv[ok].mean():.3f}), max |d(R omega')|/V {dw[ok].max():.3f}; {cost:.1f} ms a particle"
            )
            for V in SPEEDS:
                sel = ok & (speed == V)
                if sel.any():
                    print(f"    V = {V:g} m/s: max |dv_t'|/V {dv[sel].max():.3f}")
            cap = new.stuck
            if cap.any():
                print(
                    f"    captured ({cap.sum()}): old v_t' {np.unique(v_old[stuck_old])}, integrated "
                    f"{new.velocity[cap, 0].min():.3f} to {new.velocity[cap, 0].max():.3f} m/s "
                    f"({', '.join(sorted(set(new.outcome[cap])))})"
                )


if __name__ == "__main__":
    main()
