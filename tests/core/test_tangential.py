"""Tangential compliance along the seed's closed-form normal history (microimpact.core.tangential)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microimpact.core import tangential as tg
from microimpact.dynamics import BETA_25_12, contact_times
from microimpact.impact import elastic_max_approach, normalized_restitution
from microimpact.oblique import integrate_oblique_ode

settings.register_profile("oblique-ci", derandomize=True, deadline=None, max_examples=60)
CI = settings.get_profile("oblique-ci")

KAPPA = 2 * (1 - 0.23) / (2 - 0.23)  # alumina on a rigid flat


@pytest.mark.parametrize("x", [2.0, 1.0, 0.5, 0.1, 0.01])
def test_history_constants_give_the_seeds_restitution(x):
    hc = tg.history_constants(x)
    e = 1.0 if x >= 1 else float(normalized_restitution(1.0 / x))
    assert hc[13] == pytest.approx(e, rel=1e-12)


@pytest.mark.parametrize("x", [2.0, 0.5, 0.05])
def test_stage_points_integrate_to_the_seeds_contact_time_and_impulse(x):
    # Midpoint sums of dtau/dv and P dtau/dv over the stages: contact time and normal impulse.
    hc = tg.history_constants(x)
    n = 4000
    tc = imp = 0.0
    for stage in (1, 3) if x >= 1 else (1, 2, 3):
        for i in range(n):
            d = tg.stage_point(stage, (i + 0.5) / n, hc)
            tc += d[0] / n
            imp += d[0] * d[3] / n
    # Dimensional check against dynamics.contact_times for a pair with V_y = x V.
    V, E, R, m = 10.0, 1e9, 1e-6, 1e-14
    alpha_m = float(elastic_max_approach(V, E, R, m))
    # p_y such that V_y = x V: V_y ~ p_y^(5/2) at fixed E, R, m (THEORY.md section 3).
    from microimpact.impact import yield_velocity

    p1 = 1e8
    p_y = p1 * (min(x, 1e6) * V / float(yield_velocity(p1, E, R, m))) ** 0.4
    t = contact_times(V, E, R, m, p_y)
    assert tc * alpha_m / V == pytest.approx(float(t["contact_time"]), rel=1e-6)
    assert imp == pytest.approx(1.0 + hc[13], rel=1e-6)
    if x >= 1:
        assert tc == pytest.approx(0.8 * BETA_25_12, rel=1e-6)


CASES = [(x, psi) for x in (2.0, 0.5, 0.05) for psi in (0.3, 0.9, 1.2, 2.0, 3.5, 6.0)]


@pytest.mark.parametrize(("x", "psi"), CASES)
def test_closed_history_integration_equals_the_3dof_ode(x, psi):
    u0 = psi / KAPPA
    ode = integrate_oblique_ode(u0, KAPPA, x)
    ur, regime = tg.integrate_tangential(u0, KAPPA, x, 1600)
    assert ur == pytest.approx(ode["u_r"], abs=1e-8)
    assert regime == ode["regime"]
    assert ode["e"] == pytest.approx(tg.history_constants(x)[13], abs=1e-10)
    # The ODE's separate translational and rotational parts: r omega changes 5/2 times v_t.
    assert ode["r_omega"] == pytest.approx(2.5 * (ode["v_t"] - u0), abs=1e-10)


def test_fixed_step_error_at_the_default_steps():
    worst = 0.0
    for x, psi in CASES:
        a = tg.integrate_tangential(psi / KAPPA, KAPPA, x, 400)[0]
        b = tg.integrate_tangential(psi / KAPPA, KAPPA, x, 3200)[0]
        worst = max(worst, abs(a - b))
    assert worst < 1e-7  # in units of mu V_n


@pytest.mark.parametrize("x", [2.0, 0.3])
def test_large_angle_slides_throughout_with_the_coulomb_impulse(x):
    u0 = 20.0 / KAPPA
    ur, regime = tg.integrate_tangential(u0, KAPPA, x, 200)
    assert regime == tg.REGIME_SLIDING
    assert ur == pytest.approx(
        u0 - tg.SLIP_FACTOR * (1.0 + tg.history_constants(x)[13]), abs=1e-7
    )  # RK4 quadrature of P


@pytest.mark.parametrize("u0", [0.5, 2.0, 5.0])
def test_infinitely_stiff_contact_is_the_rigid_model(u0):
    rigid = tg.rigid_impulse(u0, 2.0)[0]
    errs = []
    for kappa in (1e2, 1e4):
        o = integrate_oblique_ode(u0, kappa, 1.0, rtol=1e-10, atol=1e-12)
        errs.append(abs((o["u_r"] - u0) / tg.SLIP_FACTOR - rigid))
    assert errs[1] < 1e-4
    assert errs[1] < errs[0] / 10  # converges as kappa grows


def test_zero_slip_gives_no_tangential_force():
    assert tg.integrate_tangential(0.0, KAPPA, 0.5, 100) == (0.0, tg.REGIME_STICKING)


def test_stiffness_ratio_of_one_material_on_a_rigid_flat():
    E, nu = 2e11, 0.28
    G = tg.effective_shear_modulus(E, nu, math.inf, 0.3)
    Es = E / (1 - nu**2)
    assert tg.stiffness_ratio(G, Es) == pytest.approx(2 * (1 - nu) / (2 - nu), rel=1e-14)


@CI
@given(
    vt=st.floats(-5.0, 5.0),
    rw=st.floats(-5.0, 5.0),
    kappa=st.floats(0.5, 1.3),
    x=st.floats(0.01, 2.0),
)
def test_energy_is_never_created(vt, rw, kappa, x):
    # Translational + rotational kinetic energy of the tangential motion, in m (mu V)^2 units
    # (stored spring energy is zero once the contact has opened).
    u0 = vt + rw
    ur, _ = tg.integrate_tangential(u0, kappa, x, 200)
    J = (ur - u0) / tg.SLIP_FACTOR
    before = 0.5 * vt**2 + 0.2 * rw**2
    after = 0.5 * (vt + J) ** 2 + 0.2 * (rw + 2.5 * J) ** 2
    assert after <= before * (1 + 1e-9) + 1e-12


@CI
@given(psi=st.floats(0.0, 12.0), x=st.floats(0.01, 2.0))
def test_slip_never_grows(psi, x):
    # The effective tangential energy 1/2 (2m/7) u^2 cannot grow: |u_r| <= |u0|.
    u0 = psi / KAPPA
    ur, _ = tg.integrate_tangential(u0, KAPPA, x, 200)
    assert abs(ur) <= abs(u0) + 1e-9
    assert np.isfinite(ur)


@settings(CI, max_examples=25)
@given(psi=st.floats(0.05, 10.0), x=st.floats(0.02, 2.0), kappa=st.floats(0.6, 1.2))
def test_energy_with_the_stored_part_never_increases_along_the_impact(psi, x, kappa):
    # Translational + rotational + stored (T^2 / 2 k_t) energy along the 3-DOF ODE's path.
    out = integrate_oblique_ode(psi / kappa, kappa, x, rtol=1e-10, atol=1e-12, record=True)
    E = out["energy"]
    assert E[0] == pytest.approx(0.5 * (psi / kappa) ** 2)
    assert np.all(np.diff(E) <= 1e-9 * E[0])
