"""Tests of the coupling to flow codes: wall interaction, adhesion, tables, C export, export CLI."""

from __future__ import annotations

import csv
import math
import shutil
import subprocess
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.optimize import brentq

import microimpact as mi
from microimpact import adhesion, wall
from microimpact.adhesion import adhesive_restitution, sticking_velocity, work_of_adhesion
from microimpact.cexport import generate_c_source, restitution_table, write_c_source, write_tables
from microimpact.cli import main
from microimpact.impact import thornton_ning_restitution
from microimpact.pair import LargeStrainWarning
from microimpact.wall import wall_interaction

SILICON = dict(effective_modulus=1.31e9, limiting_pressure=156e6)


def _sphere_mass(d, rho):
    r = 0.5 * d
    return 4.0 / 3.0 * np.pi * r**3 * rho


def _kinetic_energy(v, w, d, rho):
    m = _sphere_mass(d, rho)
    inertia = 0.4 * m * (0.5 * d) ** 2
    return 0.5 * m * np.sum(v * v, axis=-1) + 0.5 * inertia * np.sum(w * w, axis=-1)


# ----------------------------------------------------------------------------- adhesion
def test_sticking_constant_is_the_jkr_separation_work():
    """14.1844 = 2 x the JKR work to separate from zero approach (independent integration)."""
    E = R = w = 1.0  # JKR with work of adhesion w: pull-off force 1.5 pi w R
    P = lambda a: 4 * E * a**3 / (3 * R) - np.sqrt(8 * np.pi * w * E * a**3)  # noqa: E731
    delta = lambda a: a**2 / R - np.sqrt(2 * np.pi * w * a / E)  # noqa: E731
    ddelta = lambda a: 2 * a / R - 0.5 * np.sqrt(2 * np.pi * w / (E * a))  # noqa: E731
    a0 = (2 * np.pi * w * R**2 / E) ** (1 / 3)  # contact radius at delta = 0
    af = brentq(ddelta, 1e-9, a0)  # separation (displacement control): minimum of delta
    assert delta(a0) == pytest.approx(0.0, abs=1e-12)
    # pull-off force of this JKR curve is 1.5 pi w R: the convention of the docstring
    a_min = brentq(lambda a: 4 * E * a**2 / R - 1.5 * np.sqrt(8 * np.pi * w * E * a), 1e-9, a0)
    assert -P(a_min) == pytest.approx(1.5 * np.pi * w * R, rel=1e-12)
    work = quad(lambda a: -P(a) * ddelta(a), af, a0, epsabs=0, epsrel=1e-13)[0]
    # the derived constant (Thornton & Ning print it rounded, 14.18): the integral to quad's accuracy
    assert 2 * work == pytest.approx(adhesion.STICKING_CONSTANT, rel=1e-12)
    assert round(adhesion.STICKING_CONSTANT, 2) == 14.18
    # sticking_velocity: 1/2 m V_s^2 = 7.0922 (G^5 R^4/E^2)^(1/3), scaled to a real particle
    G, Es, Rs = 0.2, 2.0e9, 1.5e-6
    m = _sphere_mass(2 * Rs, 2000.0)
    Vs = sticking_velocity(G, Es, Rs, m)
    assert 0.5 * m * Vs**2 == pytest.approx(work * (G**5 * Rs**4 / Es**2) ** (1 / 3), rel=1e-12)


def test_work_of_adhesion_convention():
    assert work_of_adhesion(0.05) == pytest.approx(0.1)  # identical surfaces: 2 gamma
    assert work_of_adhesion(0.04, 0.09) == pytest.approx(2 * 0.06)  # geometric mean
    with pytest.raises(ValueError, match="surface_energy_2"):
        work_of_adhesion(0.04, -1.0)


def test_adhesive_restitution_closed_form_and_limits():
    V = np.array([0.0, 0.5, 2.0, 7.0, 20.0, 80.0])
    Vy, Vs = 7.5, 1.0
    ep = thornton_ning_restitution(V, Vy)
    e = adhesive_restitution(V, Vy, Vs)
    expect = np.where(ep * V <= Vs, 0.0, np.sqrt(np.clip(ep**2 - (Vs / np.where(V > 0, V, 1)) ** 2, 0, None)))
    np.testing.assert_allclose(e, expect, rtol=1e-13, atol=0)
    # G = 0: the seed's model unchanged, nothing sticks, even at V = 0
    np.testing.assert_allclose(adhesive_restitution(V, Vy, 0.0), ep, rtol=1e-13)
    assert np.all(adhesive_restitution(V, Vy, 0.0) > 0)
    with pytest.raises(ValueError, match="sticking_velocity"):
        adhesive_restitution(1.0, 1.0, -1.0)
    with pytest.raises(ValueError, match="velocity"):
        adhesive_restitution(np.inf, 1.0, 1.0)


def test_restitution_table_scales():
    v = np.linspace(0.0, 30.0, 61)
    s = np.array([0.0, 0.1, 1.0])
    tab = restitution_table(v, s)
    assert tab.shape == (61, 3)
    np.testing.assert_allclose(tab[:, 0], thornton_ning_restitution(v, 1.0), rtol=1e-13)
    # scaled table equals a dimensional pair: V_y = 7.52..., V_s = 0.1 V_y
    pair = mi.ContactPair.paper_case()
    Vy = pair.yield_velocity
    np.testing.assert_allclose(adhesive_restitution(v * Vy, Vy, 0.1 * Vy), tab[:, 1], rtol=1e-12)
    assert np.all(np.diff(tab, axis=1) <= 1e-15)  # more adhesion, less rebound


# ----------------------------------------------------------------------------- wall interaction
@pytest.mark.parametrize(
    "particle,surface,py",
    [("nh4fl", "silicon", 156e6), ("nh4fl", "mica", 158e6), ("copper", "steel", 154e6), ("glass", "aluminium", 6e8)],
)
def test_normal_impact_reproduces_pair_impact_exactly(particle, surface, py):
    d = 4.9e-6
    pair = mi.ContactPair.from_materials(particle, surface, radius=d / 2, limiting_pressure=py)
    V = np.array([0.1, 1.0, pair.yield_velocity, 10.0, 30.0, 50.0, 70.0, 120.0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", LargeStrainWarning)
        ref = pair.impact(V)
    n = np.array([0.0, 0.0, 1.0])
    out = wall_interaction(-V[:, None] * n, n, d, material=particle, wall=surface, limiting_pressure=py)
    assert np.array_equal(out.restitution, ref.restitution)
    assert np.array_equal(out.velocity[:, 2], ref.rebound_velocity)
    assert np.all(out.velocity[:, :2] == 0.0)
    assert not out.stuck.any() and out.approaching.all()
    assert out.spin is None  # no spin given, no friction
    assert np.allclose(out.yield_velocity, pair.yield_velocity, rtol=1e-15)


def test_normal_impact_along_any_normal():
    rng = np.random.default_rng(1)
    n = rng.normal(size=(50, 3))
    n_unit = n / np.linalg.norm(n, axis=1)[:, None]
    V = rng.uniform(0.1, 100.0, 50)
    out = wall_interaction(-V[:, None] * n_unit, n, 3e-6, 1350.0, **SILICON)
    ref = mi.ContactPair.sphere_on_flat(1.5e-6, 1350.0, **SILICON).restitution(V)
    np.testing.assert_allclose(out.restitution, ref, rtol=1e-13)
    np.testing.assert_allclose(out.velocity, (ref * V)[:, None] * n_unit, rtol=1e-12, atol=1e-12)


def test_mu_zero_keeps_tangential_velocity_and_spin():
    rng = np.random.default_rng(2)
    v = rng.normal(size=(100, 3)) * 20.0
    v[:, 2] = -np.abs(v[:, 2]) - 0.1
    w = rng.normal(size=(100, 3)) * 1e6
    out = wall_interaction(v, [0, 0, 1], 2e-6, 2500.0, **SILICON, friction=0.0, spin=w)
    assert np.array_equal(out.velocity[:, :2], v[:, :2])
    assert np.array_equal(out.spin, w)


def test_rolling_gives_five_sevenths():
    v = np.array([[4.0, -3.0, -20.0], [1.0, 0.0, -5.0]])
    out = wall_interaction(v, [0, 0, 1], 5e-6, 1350.0, **SILICON, friction=10.0)
    assert out.rolling.all() and list(out.regime) == ["rolling", "rolling"]
    np.testing.assert_allclose(out.velocity[:, :2], 5.0 / 7.0 * v[:, :2], rtol=1e-14)
    # the sphere leaves rolling: contact-point slip v_t + r n x omega is zero
    r = 2.5e-6
    slip = out.velocity[:, :2] + r * np.cross([0, 0, 1], out.spin)[:, :2]
    np.testing.assert_allclose(slip, 0.0, atol=1e-12)
    # omega = n x v_t / r: rolling without slipping on the wall
    np.testing.assert_allclose(out.spin, np.cross([0, 0, 1], out.velocity) / r, rtol=1e-13)


def test_sliding_takes_the_coulomb_impulse():
    mu = 0.1
    v = np.array([[30.0, 0.0, -10.0]])  # steep slip: beyond the Coulomb limit
    out = wall_interaction(v, [0, 0, 1], 5e-6, 1350.0, **SILICON, friction=mu)
    assert out.regime[0] == "sliding"
    e = out.restitution[0]
    assert out.velocity[0, 0] == pytest.approx(30.0 - mu * (1 + e) * 10.0, rel=1e-14)
    # a spinning particle whose contact point does not slip keeps its tangential velocity
    r = 2.5e-6
    w = np.array([[0.0, 30.0 / r, 0.0]])  # rolling already: v_t + r n x w = 0
    out2 = wall_interaction(v, [0, 0, 1], 5e-6, 1350.0, **SILICON, friction=mu, spin=w)
    np.testing.assert_allclose(out2.velocity[0, :2], v[0, :2], rtol=1e-14)
    np.testing.assert_allclose(out2.spin, w, rtol=1e-14)


def test_away_moving_particles_pass_unchanged():
    v = np.array([[1.0, 2.0, 3.0], [5.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
    w = np.ones((3, 3))
    out = wall_interaction(v, [0, 0, 1], 1e-6, 1000.0, **SILICON, friction=0.5, work_of_adhesion=1.0, spin=w)
    assert list(out.approaching) == [False, False, True]
    assert np.array_equal(out.velocity[:2], v[:2]) and np.array_equal(out.spin[:2], w[:2])
    assert list(out.regime) == ["none", "none", "stuck"]
    assert np.array_equal(out.restitution[:2], [1.0, 1.0])


def test_slower_than_sticking_velocity_sticks():
    d, rho, G = 1e-6, 1350.0, 0.1
    m = _sphere_mass(d, rho)
    Vs = float(sticking_velocity(G, SILICON["effective_modulus"], d / 2, m))
    assert 0.5 < Vs < 7.5  # below V_y: e_p = 1, so the threshold is V_s itself
    V = np.array([0.2, 0.99, 1.01, 3.0]) * Vs
    w = np.full((4, 3), 1e5)
    out = wall_interaction(
        np.column_stack([V, 0 * V, -V]), [0, 0, 1], d, rho, **SILICON, work_of_adhesion=G, friction=0.3, spin=w
    )
    assert list(out.stuck) == [True, True, False, False]
    assert np.all(out.velocity[:2] == 0.0) and np.all(out.spin[:2] == 0.0)
    np.testing.assert_allclose(out.restitution[2:], np.sqrt(1 - (Vs / V[2:]) ** 2), rtol=1e-12)
    assert out.deposited_fraction == 0.5


def test_g_zero_never_sticks():
    rng = np.random.default_rng(3)
    V = np.concatenate([[0.0, 1e-9], rng.uniform(0.0, 200.0, 1000)])
    out = wall_interaction(
        np.column_stack([0 * V, 0 * V, -V]),
        [0, 0, 1],
        rng.uniform(1e-7, 1e-4, V.size),
        material="nh4fl",
        wall="silicon",
        limiting_pressure=156e6,
    )
    assert not out.stuck.any()


def test_per_particle_materials_match_pairs():
    mats = np.array(["nh4fl", "copper", "glass", "copper"])
    V = np.array([20.0, 20.0, 20.0, 60.0])
    out = wall_interaction(
        np.column_stack([0 * V, 0 * V, -V]),
        [0, 0, 1],
        2e-6,
        material=mats,
        wall="steel",
        limiting_pressure=[160e6, 160e6, 500e6, 160e6],
    )
    for i, (m, py) in enumerate(zip(mats, [160e6, 160e6, 500e6, 160e6])):
        pair = mi.ContactPair.from_materials(m, "steel", 1e-6, limiting_pressure=py)
        assert out.restitution[i] == pytest.approx(float(pair.restitution(V[i])), rel=1e-14)
    # default p_y = k Y with the smaller yield strength (copper 70 MPa < steel 250 MPa)
    out2 = wall_interaction([0, 0, -20.0], [0, 0, 1], 2e-6, material="copper", wall="steel")
    pair = mi.ContactPair.from_materials("copper", "steel", 1e-6)
    assert pair.limiting_pressure == pytest.approx(2.2 * 70e6)
    assert out2.restitution == pytest.approx(float(pair.restitution(20.0)), rel=1e-14)
    assert out2.velocity.shape == (3,)


def test_bad_input_names_the_parameter():
    n = [0, 0, 1]
    for kwargs, name in [
        (dict(velocity=[[1, 2]], normal=n, diameter=1e-6, density=1e3), "velocity"),
        (dict(velocity=[0, 0, np.nan], normal=n, diameter=1e-6, density=1e3), "velocity"),
        (dict(velocity=[0, 0, -1], normal=[0, 0, 0], diameter=1e-6, density=1e3), "normal"),
        (dict(velocity=[0, 0, -1], normal=n, diameter=-1e-6, density=1e3), "diameter"),
        (dict(velocity=[0, 0, -1], normal=n, diameter=1e-6, density=0.0), "density"),
        (dict(velocity=[0, 0, -1], normal=n, diameter=1e-6, density=1e3, friction=-0.1), "friction"),
        (dict(velocity=[0, 0, -1], normal=n, diameter=1e-6, density=1e3, work_of_adhesion=-1), "work_of_adhesion"),
        (dict(velocity=[[0, 0, -1]] * 2, normal=n, diameter=[1e-6] * 3, density=1e3), "diameter"),
        (dict(velocity=[0, 0, -1], normal=n, diameter=1e-6, density=1e3, limiting_pressure=-5.0), "limiting_pressure"),
    ]:
        kwargs.setdefault("effective_modulus", 1e9)
        kwargs.setdefault("limiting_pressure", 1e8)
        with pytest.raises(ValueError, match=name):
            wall_interaction(**kwargs)
    with pytest.raises(ValueError, match="limiting_pressure"):
        wall_interaction([0, 0, -1], n, 1e-6, material="glass", wall="silicon")  # no yield strength known
    with pytest.raises(ValueError, match="material"):
        wall_interaction([0, 0, -1], n, 1e-6, material="unobtainium")


vec = st.tuples(*[st.floats(-100.0, 100.0)] * 3)


@settings(max_examples=100, deadline=None)
@given(
    v=vec,
    n=st.tuples(*[st.floats(-1.0, 1.0)] * 3).filter(lambda x: sum(c * c for c in x) > 1e-4),
    w=st.tuples(*[st.floats(-1e7, 1e7)] * 3),
    d=st.floats(1e-7, 1e-4),
    mat=st.sampled_from(["nh4fl", "copper", "glass", "steel", "fly_ash", "aluminium"]),
    wall=st.sampled_from(["silicon", "mica", "steel", "quartz", "glass"]),
    py=st.floats(1e7, 3e9),
    mu=st.floats(0.0, 2.0),
    G=st.sampled_from([0.0, 0.01, 0.1, 1.0]),
)
def test_energy_never_increases(v, n, w, d, mat, wall, py, mu, G):
    v, w = np.array([v]), np.array([w])
    out = wall_interaction(
        v, n, d, material=mat, wall=wall, limiting_pressure=py, friction=mu, work_of_adhesion=G, spin=w
    )
    rho = mi.get_material(mat).density
    before = _kinetic_energy(v, w, d, rho)
    after = _kinetic_energy(out.velocity, out.spin, d, rho)
    assert after <= before * (1 + 1e-12) + 1e-300
    assert 0.0 <= out.restitution <= 1.0
    if G == 0.0:
        assert not out.stuck.any()
    # normal component never reverses toward the wall
    nu = np.asarray(n) / np.linalg.norm(n)
    if out.approaching.all() and not out.stuck.any():
        assert out.velocity @ nu >= 0.0


# ----------------------------------------------------------------------------- C export
DRIVER = r"""
#include <stdio.h>
#include "microimpact_wall.c"
int main(void)
{
    double v[3], n[3], w[3], d, rho, vo[3], wo[3], e;
    microimpact_wall_params p;
    while (scanf("%lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf",
                 &v[0], &v[1], &v[2], &n[0], &n[1], &n[2], &w[0], &w[1], &w[2], &d, &rho,
                 &p.effective_modulus, &p.limiting_pressure, &p.work_of_adhesion, &p.friction) == 15) {
        int s = microimpact_wall_interaction(v, n, w, d, rho, &p, vo, wo, &e);
        printf("%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", s, vo[0], vo[1], vo[2], wo[0], wo[1], wo[2], e);
    }
    return 0;
}
"""


def _compiler():
    for name in ("cc", "gcc", "clang"):
        path = shutil.which(name)
        if path:
            return path
    return None


def build_driver(cc, tmp):
    """Compile DRIVER against the ``microimpact_wall.c`` written in ``tmp``; the executable's path."""
    (tmp / "driver.c").write_text(DRIVER)
    exe = tmp / "driver"
    res = subprocess.run(
        [cc, "-std=c99", "-O2", "-Wall", "-Werror", "-pedantic", "-o", str(exe), str(tmp / "driver.c"), "-lm"],
        capture_output=True,
        text=True,
        cwd=tmp,
    )
    assert res.returncode == 0, res.stderr
    return exe


@pytest.fixture(scope="module")
def c_program(tmp_path_factory):
    cc = _compiler()
    if cc is None:
        pytest.skip("no C compiler on this machine")
    tmp = tmp_path_factory.mktemp("cexport")
    src = write_c_source(tmp, effective_modulus=1.31e9, limiting_pressure=156e6, work_of_adhesion=0.1, friction=0.3)
    assert src.name == "microimpact_wall.c"
    return build_driver(cc, tmp)


def _random_cases(rng, N):
    v = rng.normal(size=(N, 3)) * 10 ** rng.uniform(-2, 2, (N, 1))
    n = rng.normal(size=(N, 3)) * rng.uniform(0.1, 10.0, (N, 1))
    w = rng.normal(size=(N, 3)) * 10 ** rng.uniform(0, 7, (N, 1))
    d = 10 ** rng.uniform(-7, -4, N)
    rho = rng.uniform(500, 9000, N)
    E = 10 ** rng.uniform(8, 11.5, N)
    py = 10 ** rng.uniform(7, 9.5, N)
    py[rng.random(N) < 0.05] = np.inf
    G = np.where(rng.random(N) < 0.3, 0.0, 10 ** rng.uniform(-3, 0.5, N))
    mu = np.where(rng.random(N) < 0.2, 0.0, rng.uniform(0, 1.0, N))
    return v, n, w, d, rho, E, py, G, mu


def test_c_source_agrees_with_python(c_program):
    rng = np.random.default_rng(2024)
    N = 3000
    v, n, w, d, rho, E, py, G, mu = _random_cases(rng, N)
    lines = "\n".join(
        " ".join(repr(float(x)) if np.isfinite(x) else "inf" for x in row)
        for row in np.column_stack([v, n, w, d, rho, E, py, G, mu])
    )
    res = subprocess.run([str(c_program)], input=lines + "\n", capture_output=True, text=True, check=True)
    got = np.array([[float(x) for x in line.split()] for line in res.stdout.splitlines()])
    assert got.shape == (N, 8)
    py_out = wall_interaction(
        v, n, d, rho, effective_modulus=E, limiting_pressure=py, work_of_adhesion=G, friction=mu, spin=w
    )
    flag = got[:, 0].astype(int)
    expect_flag = np.where(~py_out.approaching, -1, np.where(py_out.stuck, 1, 0))
    assert np.array_equal(flag, expect_flag)
    # every regime is exercised
    assert {"none", "stuck", "rolling", "sliding"} <= set(py_out.regime)
    vscale = np.maximum(np.linalg.norm(v, axis=1), 1e-300)[:, None]
    wscale = np.maximum(np.linalg.norm(w, axis=1), np.linalg.norm(v, axis=1) / (0.5 * d))[:, None]
    err_v = np.max(np.abs(got[:, 1:4] - py_out.velocity) / vscale)
    err_w = np.max(np.abs(got[:, 4:7] - py_out.spin) / wscale)
    err_e = np.max(np.abs(got[:, 7] - py_out.restitution))
    assert err_v < 1e-12 and err_w < 1e-12 and err_e < 1e-12, (err_v, err_w, err_e)


def test_c_source_bakes_the_pair_in():
    pair = mi.ContactPair.paper_case("mica")
    src = generate_c_source(pair, work_of_adhesion=0.05, friction=0.25)
    assert f"{pair.effective_modulus!r}, {pair.limiting_pressure!r}, 0.05, 0.25" in src
    assert "int microimpact_wall_interaction(const double v_in[3]" in src
    assert "DEFINE_DPM_BC" in src and "PatchInteractionModel" in src
    assert "INFINITY" in generate_c_source(effective_modulus=1e9, limiting_pressure=np.inf)
    with pytest.raises(ValueError, match="effective_modulus"):
        generate_c_source(limiting_pressure=1e8)
    with pytest.raises(ValueError, match="friction"):
        generate_c_source(pair, friction=-1.0)


# ----------------------------------------------------------------------------- tables and CLI
def _read_csv(path):
    with open(path, newline="") as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].startswith("#")]
    return rows[0], np.array(rows[1:], dtype=float)


def test_write_tables_equal_the_api(tmp_path):
    pair = mi.ContactPair.paper_case()
    V = np.linspace(0.05, 100.0, 77)
    files = write_tables(tmp_path, pair, [1e-6, 4.9e-6], V, work_of_adhesion=0.2, vs_over_vy_values=[0, 0.3])
    names = sorted(p.name for p in files)
    assert names == ["restitution_d1um.csv", "restitution_d4.9um.csv", "restitution_vs_v_over_vy.csv"]
    header, data = _read_csv(tmp_path / "restitution_vs_v_over_vy.csv")
    assert header[0] == "V/V_y [1]" and header[2] == "e at V_s/V_y=0.3 [1]"
    assert np.array_equal(data[:, 1:], restitution_table(data[:, 0], [0, 0.3]))
    for d in (1e-6, 4.9e-6):
        header, data = _read_csv(tmp_path / f"restitution_d{d * 1e6:g}um.csv")
        assert header == ["normal speed [m/s]", "restitution e [1]", "stuck [1]"]
        first = (tmp_path / f"restitution_d{d * 1e6:g}um.csv").read_text().splitlines()[0]
        assert first == ",".join(header)  # the project's CSV layout: header first, then # lines
        assert np.array_equal(data[:, 0], V)
        out = wall_interaction(
            np.column_stack([0 * V, 0 * V, -V]), [0, 0, 1], d, pair.density, **SILICON, work_of_adhesion=0.2
        )
        assert np.array_equal(data[:, 1], out.restitution)
        assert np.array_equal(data[:, 2].astype(bool), out.stuck)
        assert out.stuck.any() and not out.stuck.all()


def test_cli_export(tmp_path, capsys):
    out = tmp_path / "exp"
    rc = main(
        [
            "export",
            "--out",
            str(out),
            "--surface-energy",
            "0.05",
            "--friction",
            "0.3",
            "--diameters",
            "1e-6,5e-6",
            "--velocities",
            "0.1:50:11",
            "--vs-over-vy",
            "0,0.5",
        ]
    )
    assert rc == 0
    text = capsys.readouterr().out
    assert "work of adhesion G = 0.1 J/m^2" in text  # 2 gamma
    assert {p.name for p in out.iterdir()} == {
        "restitution_vs_v_over_vy.csv",
        "restitution_d1um.csv",
        "restitution_d5um.csv",
        "microimpact_wall.c",
        ".microimpact-manifest.json",  # what the export wrote, so that a later run may replace it
    }
    pair = mi.ContactPair.paper_case()
    V = np.linspace(0.1, 50, 11)
    _, data = _read_csv(out / "restitution_d5um.csv")
    m = _sphere_mass(5e-6, 1350.0)
    G = float(work_of_adhesion(0.05))
    assert G == pytest.approx(0.1, rel=1e-15)
    Vs = sticking_velocity(G, pair.effective_modulus, 2.5e-6, m)
    Vy = pair.replace(effective_radius=2.5e-6, effective_mass=m).yield_velocity
    np.testing.assert_array_equal(data[:, 1], adhesive_restitution(V, Vy, Vs))
    src = (out / "microimpact_wall.c").read_text()
    assert src == generate_c_source(pair, work_of_adhesion=G, friction=0.3)
    # bad input: one line on stderr, exit 2
    rc = main(["export", "--out", str(out), "--friction", "abc"])
    assert rc == 2 and "friction" in capsys.readouterr().err
    rc = main(["export", "--out", str(out), "--work-of-adhesion", "-1"])
    assert rc == 2 and "--work-of-adhesion" in capsys.readouterr().err


def test_throughput_shape_million():
    """The wall interaction handles 10^6 particles in one call (no timing asserted)."""
    rng = np.random.default_rng(0)
    N = 200_000
    v = rng.normal(size=(N, 3)) * 20
    out = wall_interaction(
        v, [0, 0, 1], rng.uniform(1e-7, 1e-5, N), 1350.0, **SILICON, friction=0.3, work_of_adhesion=0.05
    )
    assert out.velocity.shape == (N, 3) and out.spin.shape == (N, 3)
    assert math.isclose(out.approaching.mean(), 0.5, abs_tol=0.01)


@pytest.mark.parametrize("normal", [[0.0, 0.0, 0.0], [[0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]])
def test_zero_normal_is_refused_whether_one_or_one_per_particle(normal):
    """One zero normal among many is found by the core (NaN) and refused like a single one."""
    v = [[0.0, 0.0, -5.0], [1.0, 0.0, -5.0], [-5.0, 0.0, 0.0]]
    with pytest.raises(ValueError, match="normal must not be a zero vector"):
        wall.wall_interaction(v, normal, 5e-6, 1350.0, effective_modulus=1.31e9, limiting_pressure=156e6)


def test_wall_reads_strided_columns_and_leaves_inputs_alone():
    """Velocities given as a view with strides (a column block of a wider table) give the same
    numbers as a contiguous copy, and no input array is written to."""
    rng = np.random.default_rng(8)
    table = rng.normal(0.0, 5.0, (200, 7))
    table[:, 3] = -rng.uniform(1.0, 80.0, 200)
    v = table[:, 1:4]  # strided rows
    d = rng.uniform(1e-6, 1e-5, 200)
    before = table.copy(), d.copy()
    kw = dict(effective_modulus=1.31e9, limiting_pressure=156e6, friction=0.3)
    a = wall.wall_interaction(v, [0.0, 0.0, 1.0], d, 1350.0, **kw)
    b = wall.wall_interaction(np.ascontiguousarray(v), [0.0, 0.0, 1.0], d.copy(), 1350.0, **kw)
    np.testing.assert_array_equal(a.velocity, b.velocity)
    np.testing.assert_array_equal(a.spin, b.spin)
    np.testing.assert_array_equal(a.restitution, b.restitution)
    np.testing.assert_array_equal(table, before[0])
    np.testing.assert_array_equal(d, before[1])


def test_the_old_coupling_module_warns_and_names_the_new_home():
    """microimpact.coupling (the re-exports of before the split) works one more release, with a warning."""
    from microimpact import cexport, coupling

    for name, home in coupling.MOVED.items():
        with pytest.warns(DeprecationWarning, match=f"microimpact.{home}.{name}"):
            value = getattr(coupling, name)
        assert value is getattr({"adhesion": adhesion, "wall": wall, "cexport": cexport}[home], name)
    with pytest.raises(AttributeError):
        coupling.no_such_name  # noqa: B018
