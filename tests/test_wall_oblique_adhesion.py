"""wall_interaction with adhesion and a compliant tangential law: each adhesive impact is the integrated
one of :func:`microimpact.oblique.adhesive.adhesive_oblique_impact` (normal and tangential together, the
adhesive Coulomb limit), not the non-adhesive table scaled by the adhesive normal impulse.

* in the plane of the impact each particle is the adhesive module's impact, bit for bit, and in 3-D
  (any normal, a velocity and spin across the slip) the same impact rotated, the cross parts untouched;
* without adhesion the path is today's, bit for bit, and vanishing adhesion approaches it;
* energy is never created; capture is the normal law's (its sticking speed, head on and oblique);
* a captured particle keeps the motion the integration gives (rolling on the wall), not zero;
* what cannot be integrated (laws the integration does not run) is refused; the additive rule, which has
  no force history, gets the whole law in its place with a DeprecationWarning.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import microimpact as mi
from microimpact.adhesion import WHOLE_LAW
from microimpact.core.tangential import stiffness_ratio_same_poisson
from microimpact.core.wall import sphere_mass
from microimpact.impact import elastic_max_approach
from microimpact.oblique import adhesive as ad
from microimpact.wall import OUTCOMES, wall_interaction

R, RHO, E, NU, G, MU = 5e-6, 2500.0, 5e9, 0.3, 0.1, 0.3
KAPPA = stiffness_ratio_same_poisson(NU)  # as wall_interaction computes it from poisson_ratio
M = sphere_mass(R, RHO)
#: (speed [m/s], angle [deg], spin omega_y [rad/s], p_y [Pa]) in the x-z plane, wall normal +z:
#: bounces at small and grazing angles, with top and back spin (the slip reversed), captured rolling.
PLANE = (
    (0.5, 10.0, 0.0, math.inf),
    (0.5, 80.0, 0.0, math.inf),
    (0.3, 30.0, 2e4, math.inf),
    (0.3, 30.0, -8e4, math.inf),  # back spin: the contact point slips backwards
    (0.05, 60.0, 0.0, math.inf),  # captured
    (1.0, 45.0, 0.0, 5e7),
    (0.3, 70.0, 0.0, 5e7),  # captured after yield
)


def _vectors(speed, angle, spin):
    th = np.radians(angle)
    vel = np.column_stack([speed * np.sin(th), 0 * th, -speed * np.cos(th)])
    w = np.column_stack([0 * th, spin, 0 * th])
    return vel, w


def _wall(vel, w, p_y, G=G, normal=(0.0, 0.0, 1.0), tangential="mindlin", friction=MU):
    return wall_interaction(
        vel, normal, 2 * R, RHO, effective_modulus=E, limiting_pressure=p_y, work_of_adhesion=G, friction=friction,
        spin=w, tangential=tangential, adhesion=WHOLE_LAW, poisson_ratio=NU,
    )  # fmt: skip


def _pair(p_y):
    return mi.ContactPair.sphere_on_flat(R, mass=M, effective_modulus=E, limiting_pressure=p_y)


def _module(vel, w, p_y, tangential="mindlin", **kw):
    """The adhesive module called as wall_interaction calls it for particles in the x-z plane (v_x > 0)."""
    V = -vel[:, 2]
    vx = np.abs(vel[:, 0])
    return ad.adhesive_oblique_impact(
        _pair(p_y), np.hypot(V, vx), np.degrees(np.arctan2(vx, V)), MU, model=WHOLE_LAW, params=(G,),
        tangential=tangential, spin=-w[:, 1], kappa=KAPPA, **kw,
    )  # fmt: skip


@pytest.fixture(scope="module")
def plane():
    out = []
    for p_y in (math.inf, 5e7):
        rows = [c for c in PLANE if c[3] == p_y]
        vel, w = _vectors(*(np.array([c[k] for c in rows]) for k in range(3)))
        out.append((p_y, vel, w, _wall(vel, w, p_y), _module(vel, w, p_y)))
    return out


def test_each_particle_is_the_adhesive_module_s_impact(plane):
    seen = set()
    for _, vel, _, wall, ref in plane:
        assert np.array_equal(wall.velocity[:, 0], ref.tangential_velocity)
        assert np.array_equal(-wall.spin[:, 1], ref.rebound_spin)
        assert np.array_equal(wall.restitution, ref.normal_restitution)
        assert np.array_equal(wall.velocity[:, 2], ref.normal_restitution * -vel[:, 2])
        assert np.all(wall.velocity[:, 1] == 0.0) and np.all(wall.spin[:, [0, 2]] == 0.0)
        assert np.array_equal(wall.stuck, ref.captured) and np.array_equal(wall.outcome, ref.outcome)
        assert np.array_equal(wall.rolling, ~ref.captured & ref.held)
        assert not wall.outside_table.any()
        seen |= set(ref.outcome)
    assert {"bounce", "captured rolling"} <= seen
    assert set(OUTCOMES) == set(ad.OUTCOMES) and OUTCOMES == ad.OUTCOMES


def test_in_3d_the_same_impact_rotated_with_the_cross_motion_kept(plane):
    """Any wall normal; a velocity across the slip with the spin that cancels its slip: the impact along
    the slip is the plane one, the cross velocity and its spin pass unchanged (the force stays along
    the slip of a sphere whose arm is r)."""
    rng = np.random.default_rng(5)
    for p_y, vel, w, flat, _ in plane:
        n = vel.shape[0]
        cross = rng.uniform(-0.3, 0.3, n)
        vel3 = vel + np.column_stack([0 * cross, cross, 0 * cross])
        w3 = w + np.column_stack([-cross / R, 0 * cross, 0 * cross])  # r n x omega cancels v_y: slip along x
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        rot = _wall(vel3 @ q.T, w3 @ q.T, p_y, normal=q[:, 2])
        v_back, w_back = rot.velocity @ q, rot.spin @ q
        scale = np.linalg.norm(vel, axis=1)
        expect_v = flat.velocity + np.column_stack([0 * cross, cross, 0 * cross])
        expect_w = flat.spin + np.column_stack([-cross / R, 0 * cross, 0 * cross])
        assert np.max(np.abs(v_back - expect_v) / scale[:, None]) < 1e-9
        assert np.max(np.abs(w_back - expect_w) * R / scale[:, None]) < 1e-9
        assert np.array_equal(rot.outcome, flat.outcome)


def test_without_adhesion_today_s_path_and_vanishing_adhesion_approaches_it():
    speed, angle, spin = np.array([0.5, 0.5, 1.0, 3.0]), np.array([10.0, 45.0, 30.0, 70.0]), np.array([0, -2e4, 3e4, 0])
    vel, w = _vectors(speed, angle, spin)
    none = _wall(vel, w, math.inf, G=0.0)
    mixed = _wall(vel, w, math.inf, G=np.array([0.0, G, 0.0, G]))
    for name in ("velocity", "spin", "restitution", "rolling", "stuck"):
        assert np.array_equal(getattr(mixed, name)[[0, 2]], getattr(none, name)[[0, 2]]), name
    assert none.outcome.tolist() == ["bounce"] * 4
    tiny = _wall(vel, w, math.inf, G=1e-9)
    # the table's error, 3e-3 of mu J_n (J_n/m <= 2 V), bounds the difference
    bound = 3e-3 * MU * 2.0 * speed
    assert np.all(np.abs(tiny.velocity[:, 0] - none.velocity[:, 0]) < bound)
    assert np.all(np.abs(tiny.spin[:, 1] - none.spin[:, 1]) * R < 2.5 * bound)
    np.testing.assert_allclose(tiny.restitution, none.restitution, rtol=1e-6)
    assert np.array_equal(tiny.rolling, none.rolling)
    assert np.max(np.abs(mixed.velocity[1] - none.velocity[1])) > 1e-2 * speed[1]  # adhesion does act


@pytest.mark.parametrize("p_y", [math.inf, 5e7])
def test_energy_is_never_created(p_y):
    rng = np.random.default_rng(9)
    n = 8
    vel = rng.normal(size=(n, 3)) * rng.uniform(0.05, 1.5, (n, 1))
    normal = rng.normal(size=(n, 3))
    vel -= np.maximum(np.sum(vel * normal, 1), 0.0)[:, None] * 2 * normal / np.sum(normal**2, 1)[:, None]
    w = rng.normal(size=(n, 3)) * 3e4
    out = _wall(vel, w, p_y, normal=normal)
    assert out.approaching.all()

    def energy(v, om):
        return np.sum(v**2, 1) + 0.4 * R**2 * np.sum(om**2, 1)

    assert np.all(energy(out.velocity, out.spin) <= energy(vel, w) * (1 + 1e-9))


@pytest.mark.parametrize("p_y", [math.inf, 5e7])
def test_capture_is_the_normal_law_s(p_y):
    """Head on and at 60 degrees, the particle is captured just below the law's sticking speed (what the
    wall reports) and bounces just above; head on its restitution is the law's, bit for bit."""
    Vc = float(_wall(np.array([[0.0, 0.0, -1.0]]), None, p_y).sticking_velocity[0])
    assert Vc == pytest.approx(_pair(p_y).sticking_velocity(model=WHOLE_LAW, work_of_adhesion=G), rel=1e-12)
    f = np.array([1 - 2e-3, 1 + 2e-3])
    head, _ = _vectors(f * Vc, np.zeros(2), np.zeros(2))
    out = _wall(head, None, p_y)
    assert out.stuck.tolist() == [True, False] and out.outcome.tolist() == ["stick", "bounce"]
    law = _pair(p_y).impact(f * Vc, model=WHOLE_LAW, warn=False, work_of_adhesion=G)
    assert np.array_equal(out.restitution, law.restitution)
    oblique, _ = _vectors(f * Vc / math.cos(math.radians(60.0)), np.full(2, 60.0), np.zeros(2))
    assert _wall(oblique, None, p_y).stuck.tolist() == [True, False]


def test_a_captured_particle_keeps_rolling_on_the_wall():
    vel, w = _vectors(np.array([0.05]), np.array([60.0]), np.array([0.0]))
    out = _wall(vel, w, math.inf)
    assert out.stuck[0] and out.outcome[0] == "captured rolling" and out.regime[0] == "stuck"
    vt = vel[0, 0]
    assert out.velocity[0, 2] == 0.0 and out.velocity[0, 0] == pytest.approx(5.0 / 7.0 * vt, rel=1e-9)
    assert out.velocity[0, 0] - R * out.spin[0, 1] == pytest.approx(0.0, abs=1e-9 * vt)  # no slip: rolling
    assert out.deposited_fraction == 1.0
    rigid = wall_interaction(
        vel, [0, 0, 1], 2 * R, RHO, effective_modulus=E, limiting_pressure=math.inf, work_of_adhesion=G,
        friction=MU, adhesion=WHOLE_LAW,
    )  # fmt: skip
    assert rigid.stuck[0] and np.all(rigid.velocity == 0.0) and rigid.outcome[0] == "stick"  # unchanged


@pytest.mark.parametrize("law", ["lammps_linear_history", "liggghts_history"])
def test_other_laws_are_the_module_s_impact(law):
    vel, w = _vectors(np.array([0.5, 0.05]), np.array([40.0, 60.0]), np.array([1e4, 0.0]))
    wall = _wall(vel, w, math.inf, tangential=law)
    for k in range(2):
        kw = {}
        if law == "lammps_linear_history":  # each impact's 8 G* a_m, a_m of the elastic impact at V_n
            V = -vel[k, 2]
            kw["tangential_stiffness"] = 2.0 * KAPPA * E * math.sqrt(R * float(elastic_max_approach(V, E, R, M)))
        ref = _module(vel[k : k + 1], w[k : k + 1], math.inf, tangential=law, **kw)
        assert wall.velocity[k, 0] == ref.tangential_velocity[0] and -wall.spin[k, 1] == ref.rebound_spin[0]
        assert wall.outcome[k] == ref.outcome[0]
    assert wall.stuck.tolist() == [False, True]


def test_what_cannot_be_integrated_is_refused_and_the_additive_rule_is_deprecated_there():
    vel, w = _vectors(np.array([0.5]), np.array([40.0]), np.array([0.0]))
    kw = dict(effective_modulus=E, limiting_pressure=1e8, friction=MU, poisson_ratio=NU)
    with pytest.warns(DeprecationWarning, match=r"adhesion='additive'.*no force history.*" + WHOLE_LAW):
        old = wall_interaction(vel, [0, 0, 1], 2 * R, RHO, work_of_adhesion=G, tangential="mindlin", **kw)
    whole = wall_interaction(
        vel, [0, 0, 1], 2 * R, RHO, work_of_adhesion=G, tangential="mindlin", adhesion=WHOLE_LAW, **kw
    )
    assert old.adhesion == WHOLE_LAW and old.outcome[0] == whole.outcome[0]
    assert np.array_equal(old.velocity, whole.velocity) and np.array_equal(old.spin, whole.spin)
    for law in ("stronge", "mindlin_deresiewicz"):
        with pytest.raises(ValueError, match=f"tangential='{law}' with adhesion \\(work_of_adhesion = "):
            wall_interaction(vel, [0, 0, 1], 2 * R, RHO, work_of_adhesion=G, tangential=law, adhesion=WHOLE_LAW, **kw)
    # still accepted: the rigid impulse with the additive rule, and no adhesion
    assert wall_interaction(vel, [0, 0, 1], 2 * R, RHO, work_of_adhesion=G, **kw).outcome[0] == "bounce"
    out = wall_interaction(vel, [0, 0, 1], 2 * R, RHO, work_of_adhesion=0.0, tangential="mindlin", **kw)
    assert out.outcome[0] == "bounce"
