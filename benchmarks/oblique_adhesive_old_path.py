"""The error of wall_interaction's adhesive tangential approximation against the integrated oblique impact.

``wall_interaction`` scales the non-adhesive tangential table by the adhesive normal impulse; this
script compares it with :func:`microimpact.oblique.adhesive.adhesive_oblique_impact` (normal and
tangential integrated together under the same adhesive law) on a grid of speed and angle, and prints
the largest differences (the numbers of ``docs/laws/oblique_adhesive.rst``).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

import microimpact as mi
from microimpact.core.models import whole_law
from microimpact.oblique import adhesive as ad
from microimpact.wall import wall_interaction

R, RHO, E, NU, G, MU = 5e-6, 2500.0, 5e9, 0.25, 0.1, 0.3
KAPPA = 2 * (1 - NU) / (2 - NU)
SPEEDS = np.array([0.12, 0.2, 0.5, 1.0, 3.0])
ANGLES = np.array([10.0, 30.0, 50.0, 70.0, 80.0])


def main():
    warnings.simplefilter("ignore")
    law = whole_law()
    A, S = np.meshgrid(ANGLES, SPEEDS)
    th = np.radians(A.ravel())
    vel = np.column_stack([S.ravel() * np.sin(th), np.zeros(th.size), -S.ravel() * np.cos(th)])
    for p_y in (math.inf, 5e7):
        pair = mi.ContactPair.sphere_on_flat(radius=R, density=RHO, effective_modulus=E, limiting_pressure=p_y)
        old = wall_interaction(
            vel, [0, 0, 1], 2 * R, RHO, effective_modulus=E, limiting_pressure=p_y, work_of_adhesion=G,
            friction=MU, tangential="mindlin", adhesion=law, poisson_ratio=NU,
        )  # fmt: skip
        for coulomb in ad.COULOMB_LIMITS:
            new = ad.adhesive_oblique_impact(
                pair, S.ravel(), A.ravel(), MU, model=law, params=(G,), tangential="mindlin", kappa=KAPPA,
                steps=2000, coulomb=coulomb,
            )  # fmt: skip
            ok = ~new.captured & ~old.stuck
            dv = np.abs(old.velocity[:, 0] - new.tangential_velocity) / S.ravel()
            dw = np.abs(-old.spin[:, 1] - new.rebound_spin) * R / S.ravel()
            print(f"p_y = {p_y:g} Pa, coulomb = {coulomb}: {ok.sum()} bouncing, {int((new.captured != old.stuck).sum())} "
                  f"capture disagreements; max |dv_t'|/V {dv[ok].max():.3f} (mean {dv[ok].mean():.3f}), "
                  f"max |d(R omega')|/V {dw[ok].max():.3f}")  # fmt: skip
            for V in SPEEDS:
                sel = ok & (S.ravel() == V)
                if sel.any():
                    print(f"    V = {V:g} m/s: max |dv_t'|/V {dv[sel].max():.3f}")
            cap = new.captured & old.stuck
            if cap.any():
                print(f"    captured: old v_t' {np.unique(old.velocity[cap, 0])}, integrated "
                      f"{new.tangential_velocity[cap].min():.3f}-{new.tangential_velocity[cap].max():.3f} m/s")  # fmt: skip


if __name__ == "__main__":
    main()
