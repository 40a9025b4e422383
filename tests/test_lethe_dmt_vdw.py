"""Lethe's DMT law with non-contact van der Waals attraction (``"lethe_dmt_vdw"``), at a wall.

Lethe is not installed here: the model is held to an independent integration of its own force law
(scipy's DOP853 in contact, quadrature of the force outside it), to the closed forms where they
exist (the approach work, ``e = 1`` without damping), and to the energy balance of capture."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad, solve_ivp

import microimpact as mi
from microimpact.core.models import lethe_dmt_vdw as law
from microimpact.models import lethe_dmt_vdw as face

E_STAR, R, RHO = 1.31e9, 2.45e-6, 1350.0
M = 4.0 / 3.0 * math.pi * R**3 * RHO
I_E = 4


def field_work(R, m, params):
    """Work [J] of the attraction from the cut-off to contact, by quadrature of the force law."""

    def f(a):
        return -law.signed_force(a, 0.0, 0.0, E_STAR, R, m, 0.0, params)

    d0, ds = law.constant_zone_edge(R, params), law.cut_off(R, params)
    return quad(f, ds, d0, epsabs=0.0, epsrel=1e-13)[0] + quad(f, d0, 0.0, epsabs=0.0, epsrel=1e-13)[0]


def reference_e(V, E, R, m, params):
    """e by scipy: the field's work by quadrature, the contact by DOP853 from touch-down to exit."""
    W2 = 2.0 * field_work(R, m, params) / m
    vc = math.sqrt(V * V + W2)
    T = (m / (E * math.sqrt(R) * math.sqrt(vc))) ** 0.4
    L = vc * T

    def rhs(t, y):
        a = y[0] * L
        P = law.signed_force(a, y[1] * vc, a, E, R, m, 0.0, params) if a > 0.0 else -law.pull_off_force(R, params)
        return [y[1], -P * T / (m * vc)]

    def top(t, y):
        return y[1]

    top.terminal, top.direction = True, -1

    def leave(t, y):
        return y[0]

    leave.terminal, leave.direction = True, -1

    def turn(t, y):  # the speed back to zero inside the contact: the attraction holds the particle
        return y[1]

    turn.terminal, turn.direction = True, 1
    opts = dict(method="DOP853", rtol=1e-12, atol=1e-15)
    s1 = solve_ivp(rhs, (0.0, 50.0), [0.0, 1.0], events=[top], **opts)
    sol = solve_ivp(rhs, (s1.t[-1], s1.t[-1] + 50.0), [s1.y_events[0][0][0], 0.0], events=[leave, turn], **opts)
    if sol.status != 1 or len(sol.t_events[1]):
        return 0.0
    v_out = -sol.y_events[0][0][1] * vc
    return math.sqrt(max(v_out * v_out - W2, 0.0)) / V


@settings(max_examples=10, deadline=None)
@given(
    V=st.floats(0.05, 30.0),
    e_n=st.floats(0.2, 0.95),
    gamma=st.floats(0.01, 0.5),
    A=st.floats(1e-20, 1e-18),
    C=st.floats(0.02, 1.0),
    R=st.floats(2e-7, 2e-5),
)
def test_outcome_equals_independent_integration(V, e_n, gamma, A, C, R):
    params = (e_n, gamma, A, C)
    m = 4.0 / 3.0 * math.pi * R**3 * RHO
    e = law.outcome(V, E_STAR, R, m, 0.0, params)[I_E]
    assert e == pytest.approx(reference_e(V, E_STAR, R, m, params), abs=1e-8)
    assert 0.0 <= e <= 1.0


def test_closed_forms():
    """The approach work W = F_po |delta_0| (2 - C^(1/2)) equals the quadrature of the force; the
    field is continuous at delta_0; without damping every force is conservative: e = 1, no capture."""
    params = (1.0, 0.1, 1e-19, 0.1)
    assert law.approach_work(R, params) == pytest.approx(field_work(R, M, params), rel=1e-12)
    d0 = law.constant_zone_edge(R, params)
    f_in = law.signed_force(d0 * (1 - 1e-12), 0.0, 0.0, E_STAR, R, M, 0.0, params)
    f_out = law.signed_force(d0 * (1 + 1e-12), 0.0, 0.0, E_STAR, R, M, 0.0, params)
    assert f_in == pytest.approx(f_out, rel=1e-10) and f_in == pytest.approx(-law.pull_off_force(R, params))
    assert law.cut_off(R, params) == pytest.approx(d0 / math.sqrt(0.1), rel=1e-15)
    for V in (0.01, 1.0, 30.0):
        assert law.outcome(V, E_STAR, R, M, 0.0, params)[I_E] == pytest.approx(1.0, abs=1e-9)
    assert law.sticking_velocity(E_STAR, R, M, 0.0, params) == 0.0


def test_capture_velocity_is_the_energy_balance_with_the_field():
    """V_s: captured just below, escapes just above; at V_s the exit speed just pays the field's work
    (the attraction before contact is in the balance: without it the capture speed is another)."""
    params = (0.5, 0.1, 1e-19, 0.1)
    Vs = law.sticking_velocity(E_STAR, R, M, 0.0, params)
    assert law.outcome(Vs * (1 - 1e-6), E_STAR, R, M, 0.0, params)[I_E] == 0.0
    assert law.outcome(Vs * (1 + 1e-6), E_STAR, R, M, 0.0, params)[I_E] > 0.0
    assert abs(law.escape_margin(Vs, E_STAR, R, M, params)) < 1e-6 * Vs * Vs
    assert reference_e(Vs * (1 - 1e-5), E_STAR, R, M, params) == 0.0
    assert reference_e(Vs * (1 + 1e-5), E_STAR, R, M, params) > 0.0
    # the field's work decides it: at V_s the particle leaves the contact (not held) with the speed
    # (2W/m)^(1/2) > 0 that the field takes back; a contact-only balance would call that a bounce
    W2 = 2.0 * law.approach_work(R, params) / M
    v_out, held, *_ = law.contact_exit(math.sqrt(Vs * Vs + W2), E_STAR, R, M, params)
    assert held == 0.0 and v_out == pytest.approx(math.sqrt(W2), rel=1e-6)


def test_stronger_cohesion_captures_faster_particles():
    lo = law.sticking_velocity(E_STAR, R, M, 0.0, (0.5, 0.05, 1e-19, 0.1))
    hi = law.sticking_velocity(E_STAR, R, M, 0.0, (0.5, 0.2, 1e-19, 0.1))
    assert 0.0 < lo < hi


@pytest.mark.filterwarnings("ignore::microimpact.AdhesionRangeWarning")
def test_generic_machinery_and_face():
    assert "lethe_dmt_vdw" in mi.models.available()
    pair = mi.ContactPair(E_STAR, R, M, 156e6)
    kw = dict(restitution=0.5, effective_surface_energy=0.1, hamaker_constant=1e-19, cut_off_threshold=0.1)
    res = pair.impact(5.0, model="lethe_dmt_vdw", **kw)
    assert float(res.restitution) == pytest.approx(law.outcome(5.0, E_STAR, R, M, 0.0, tuple(kw.values()))[I_E])
    p = face.params_for_work_of_adhesion(0.3, (E_STAR, R, M, 156e6), tuple(kw.values()))
    assert p[1] == 0.3 and law.work_of_adhesion(p) == 0.3

    class Cal:
        effective_modulus = E_STAR

        @staticmethod
        def as_dict():
            return kw

    lines = face.lethe(Cal)
    assert "  set DMT cut-off threshold = 0.1" in lines
    assert f"    set surface energy particles = {0.05:.12g}" in lines  # gamma_e = 2 gamma for one material
    E = float([ln for ln in lines if "young modulus wall" in ln][0].split("=")[1])
    assert E / (2.0 * (1.0 - 0.3**2)) == pytest.approx(E_STAR, rel=1e-12)
