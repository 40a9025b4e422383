"""Tests of microimpact.deposition: the stagnation-point-flow deposition example."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from scipy.optimize import brentq

from microimpact.adhesion import sticking_velocity
from microimpact.deposition import (
    CRITICAL_STOKES_NUMBER,
    cunningham_correction,
    flight_to_wall,
    flight_to_wall_ode,
    plot_deposition,
    relaxation_time,
    simulate_deposition,
    stokes_number,
)
from microimpact.impact import thornton_ning_restitution

PAIR = dict(material="nh4fl", wall="silicon", limiting_pressure=156e6)
RHO = 1350.0


def test_cunningham_limits_and_value():
    # continuum limit: no slip; free-molecular limit: 1 + Kn (1.257 + 0.4)
    assert cunningham_correction(1e-3) == pytest.approx(1.0, abs=2e-4)
    kn = 2 * 68e-9 / 1e-11
    assert cunningham_correction(1e-11) == pytest.approx(1 + kn * 1.657, rel=1e-4)
    # hand computation at d = 1 um, lambda = 68 nm: Kn = 0.136
    assert cunningham_correction(1e-6) == pytest.approx(1 + 0.136 * (1.257 + 0.4 * np.exp(-1.1 / 0.136)), rel=1e-12)
    # tau = rho d^2 Cc / (18 mu)
    assert relaxation_time(2e-6, 1000.0) == pytest.approx(1000 * 4e-12 * cunningham_correction(2e-6) / (18 * 1.81e-5))
    with pytest.raises(ValueError, match="diameter"):
        cunningham_correction(0.0)


@pytest.mark.parametrize("seed", range(6))
def test_closed_form_flight_equals_ode(seed):
    rng = np.random.default_rng(seed)
    a = 10 ** rng.uniform(2, 5)
    stk = 10 ** rng.uniform(np.log10(0.3), 1.5)
    tau = stk / a
    H = 1e-3
    x0 = rng.uniform(0, 0.5e-3)
    # release with the gas velocity, and a start on the wall after a bounce
    for z0, u0, w0 in [(H, 0.5 * a * x0, -a * H), (0.0, rng.uniform(-1, 1) * a * H, rng.uniform(0.1, 1) * a * H)]:
        cf = flight_to_wall(x0, z0, u0, w0, a, tau)
        ode = flight_to_wall_ode(x0, z0, u0, w0, a, tau)
        assert np.isfinite(cf["time"]) and np.isfinite(ode["time"])
        assert cf["time"] == pytest.approx(ode["time"], rel=1e-8)
        assert cf["w"] == pytest.approx(ode["w"], rel=1e-7)
        assert cf["u"] == pytest.approx(ode["u"], rel=1e-7, abs=1e-9 * a * H)
        assert cf["x"] == pytest.approx(ode["x"], rel=1e-7, abs=1e-12)
        assert cf["w"] < 0  # arrives moving toward the wall


@pytest.mark.parametrize("stk,hits", [(0.2, False), (0.249, False), (0.26, True), (0.4, True)])
def test_critical_stokes_number(stk, hits):
    """Released with the gas velocity, a particle reaches the plate only if a tau > 1/4."""
    a, H = 1e4, 1e-3
    cf = flight_to_wall(1e-4, H, 0.5 * a * 1e-4, -a * H, a, stk / a)
    ode = flight_to_wall_ode(1e-4, H, 0.5 * a * 1e-4, -a * H, a, stk / a)
    assert np.isfinite(cf["time"]) == hits
    assert np.isfinite(ode["time"]) == hits


def test_impaction_cut_on_at_critical_stokes():
    U, H = 10.0, 1e-3
    d_c = brentq(lambda d: stokes_number(d, RHO, U / H) - CRITICAL_STOKES_NUMBER, 1e-7, 1e-4)
    res = simulate_deposition(
        [0.5 * d_c, 0.99 * d_c, 1.5 * d_c, 3 * d_c],
        U,
        height=H,
        n_particles=20,
        work_of_adhesion=5.0,
        max_impacts=1,
        **PAIR,
    )
    assert list(res.impacted_fraction[0, :2]) == [0.0, 0.0]  # small particles follow the streamlines
    assert np.all(res.impacted_fraction[0, 2:] > 0.5)
    assert np.all(res.stokes_number[0, :2] < 0.25) and np.all(res.stokes_number[0, 2:] > 0.25)


def test_more_bounce_at_higher_jet_speed_with_weak_adhesion():
    """Weak adhesion: faster jets hit harder and bounce more, so fewer particles deposit."""
    d, G = 5e-6, 0.5
    speeds = np.geomspace(2.5, 40.0, 9)
    kw = dict(n_particles=30, work_of_adhesion=G, friction=0.3, **PAIR)
    res = simulate_deposition(d, speeds, max_impacts=1, plate_radius=np.inf, **kw)
    frac = res.deposited_fraction[:, 0]
    assert np.all(res.stokes_number[:, 0] > CRITICAL_STOKES_NUMBER)  # all reach the plate by inertia
    assert np.all(res.impacted_fraction == 1.0)
    V1 = res.first_impact_speed[:, 0]
    assert np.all(np.diff(V1) > 0)  # faster jet, harder impact
    assert np.all(np.diff(frac) <= 0.0)
    assert frac[0] == 1.0 and frac[-1] == 0.0
    # the first impact decides: stick exactly where e_p(V1) V1 <= V_s (Thornton & Ning), V_s from the closed form
    m = 4 / 3 * np.pi * (d / 2) ** 3 * RHO
    E = 1.0 / ((1 - 0.3**2) / 1.2e9 + (1 - 0.22**2) / 163e9)  # nh4fl on silicon
    Vs = float(sticking_velocity(G, E, d / 2, m))
    assert res.sticking_velocity[0] == pytest.approx(Vs, rel=1e-12)
    ep = thornton_ning_restitution(V1, res.yield_velocity[0])
    np.testing.assert_array_equal(frac == 1.0, ep * V1 <= Vs)
    # with re-impacts tracked (finite plate) deposition can only grow
    one = simulate_deposition(d, speeds, max_impacts=1, **kw)
    many = simulate_deposition(d, speeds, max_impacts=20, **kw)
    assert np.all(many.deposited_fraction >= one.deposited_fraction)
    assert np.any(many.deposited_fraction > one.deposited_fraction)
    assert np.all(many.mean_impacts >= one.mean_impacts)


def test_no_adhesion_nothing_deposits_and_ode_path_agrees():
    d = np.array([1e-6, 4e-6, 10e-6])
    res0 = simulate_deposition(d, 5.0, n_particles=10, work_of_adhesion=0.0, friction=0.3, **PAIR)
    assert np.all(res0.deposited_fraction == 0.0)
    assert np.all(res0.impacted_fraction[0, 1:] > 0)
    kw = dict(n_particles=6, work_of_adhesion=0.3, friction=0.3, max_impacts=3, **PAIR)
    a = simulate_deposition(d, 5.0, **kw)
    o = simulate_deposition(d, 5.0, method="ode", **kw)
    np.testing.assert_array_equal(a.deposited_fraction, o.deposited_fraction)
    np.testing.assert_array_equal(a.impacted_fraction, o.impacted_fraction)
    np.testing.assert_allclose(a.first_impact_speed, o.first_impact_speed, rtol=1e-6)


def test_plot_and_bad_input(tmp_path):
    res = simulate_deposition(np.geomspace(1e-6, 2e-5, 8), [2.0, 10.0], n_particles=8, work_of_adhesion=0.3, **PAIR)
    ax = plot_deposition(res)
    assert "diameter" in ax.get_xlabel() and "[" in ax.get_ylabel()
    assert len(ax.get_legend().get_texts()) == 4
    np.testing.assert_allclose(ax.lines[0].get_ydata(), res.deposited_fraction[0])
    ax2 = plot_deposition(res, x="stokes", show_impacted=False)
    assert "Stokes" in ax2.get_xlabel()
    ax.figure.savefig(tmp_path / "dep.png")
    rows = res.to_rows()
    assert len(rows) == 16 and rows[0]["jet_speed [m/s]"] == 2.0
    with pytest.raises(ValueError, match="x must"):
        plot_deposition(res, x="time")
    with pytest.raises(ValueError, match="diameters"):
        simulate_deposition([-1e-6], 1.0, **PAIR)
    with pytest.raises(ValueError, match="jet_speeds"):
        simulate_deposition([1e-6], 0.0, **PAIR)
    with pytest.raises(ValueError, match="method"):
        simulate_deposition([1e-6], 1.0, method="euler", **PAIR)
    with pytest.raises(ValueError, match="max_impacts"):
        simulate_deposition([1e-6], 1.0, max_impacts=0, **PAIR)
