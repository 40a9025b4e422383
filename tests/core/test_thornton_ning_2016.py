"""The seed's model file (core.models.thornton_ning_2016) against 50-digit mpmath evaluations of the
same equations, where double precision is hardest: next to V_y (alpha_p -> 0 as (v - 1)^2, the stage
times with a square-root kink) and far above it (alpha* - alpha_p -> small against alpha*)."""

import math

import numpy as np
import pytest

from microimpact.core.models import thornton_ning_2016 as seed
from microimpact.core.quantities import OUTCOME_FIELDS

mp = pytest.importorskip("mpmath")

# the seed's silicon case (THEORY.md section 5)
E, R, RHO, P_Y = 1.31e9, 2.45e-6, 1350.0, 156e6
M = 4.0 / 3.0 * math.pi * R**3 * RHO


def _exact(V):
    """Outcome and times at ``V`` from eqs. 5-33 in 50-digit arithmetic (given the double V_y)."""
    a_y, P_y, Vy = seed.yield_point(E, R, M, P_Y)
    with mp.workdps(50):
        V_, a_y_, Vy_ = mp.mpf(V), mp.mpf(a_y), mp.mpf(Vy)
        v = V_ / Vy_
        q = mp.sqrt((24 - 4 / v**2) / 5)
        A = (1 + v * q) / 3
        Ph = v * q / 2
        e = q / 2 / A ** mp.mpf("0.25")
        ap = a_y_ * (A - Ph / mp.sqrt(A))
        recovery = a_y_ * Ph / mp.sqrt(A)
        B = mp.beta(mp.mpf(2) / 5, mp.mpf(1) / 2)
        tU = mp.mpf(2) / 5 * B * recovery / (e * V_)
        u = (Vy_ / V_) ** 2
        alpha_m = a_y_ * u ** (-mp.mpf(2) / 5)
        t1 = mp.mpf(2) / 5 * alpha_m / V_ * mp.betainc(mp.mpf(2) / 5, mp.mpf(1) / 2, 0, u)
        omega = mp.sqrt(mp.pi * mp.mpf(P_Y) * mp.mpf(R) / mp.mpf(M))
        t2 = mp.atan2(mp.sqrt(V_**2 - Vy_**2), 2 * omega * a_y_ / 3) / omega
        return {
            "restitution": e,
            "plastic_approach": ap,
            "max_approach": a_y_ * A,
            "unloading_time": tU,
            "elastic_stage_time": t1,
            "plastic_stage_time": t2,
        }


def _ours(V):
    return dict(zip(OUTCOME_FIELDS, seed.outcome(V, E, R, M, P_Y, ())))


VY = seed.yield_point(E, R, M, P_Y)[2]
SPEEDS = [VY * (1.0 + d) for d in (1e-12, 1e-9, 1e-6, 1e-3, 0.1)] + [VY * f for f in (2.0, 10.0, 1e3, 1e6, 1e9, 1e12)]


@pytest.mark.parametrize("V", SPEEDS)
def test_outcome_and_times_against_mpmath(V):
    ours, exact = _ours(V), _exact(V)
    for name, value in exact.items():
        assert ours[name] == pytest.approx(float(value), rel=4e-15, abs=0.0), name


def test_plastic_approach_near_yield_keeps_its_digits():
    """alpha_p ~ (v - 1)^2: at v = 1 + 1e-6 the direct A - P^/A^(1/2) keeps 12 digits fewer."""
    V = VY * (1.0 + 1e-6)
    v = V / VY
    A, Phat = seed.plastic_stage(v, v - 1.0)[:2]
    direct = A - Phat / math.sqrt(A)
    exact = float(_exact(V)["plastic_approach"]) / seed.yield_point(E, R, M, P_Y)[0]
    assert seed.plastic_stage(v, (V - VY) / VY)[2] == pytest.approx(exact, rel=1e-14)
    assert abs(direct - exact) > 1e-6 * exact  # the cancellation the identity avoids is real


def test_restitution_paths_agree_bitwise():
    """pair.restitution's function and the outcome's restitution are the same operations."""
    rng = np.random.default_rng(4)
    for V in list(VY * rng.uniform(0.0, 50.0, 500)) + SPEEDS:
        assert seed.restitution_at(V, VY) == _ours(V)["restitution"]


def test_restitution_limits():
    assert seed.restitution(1.0) == 1.0
    assert seed.restitution(1.0 + 1e-6) < 1.0
    assert seed.restitution(math.inf) == 0.0
    assert seed.restitution_at(0.0, VY) == 1.0
    assert seed.restitution_at(1e300, math.inf) == 1.0


def test_unloading_time_vanishes_only_in_the_limit():
    """Where V/V_y overflows the limit t_U -> 0 is returned; just below it t_U is finite and positive."""
    Vy = 1e-10
    a = _ours_at(1e290, Vy)  # V/V_y = 1e300, still a float
    assert a > 0.0 and math.isfinite(a)
    assert _ours_at(math.inf, Vy) == 0.0


def _ours_at(V, Vy):
    """t_U for a pair whose yield velocity is ``Vy`` (``p_y`` from eq. 28 solved for it)."""
    p_y = (Vy**2 * 40.0 / math.pi**4 * E**4 * RHO) ** 0.2
    return dict(zip(OUTCOME_FIELDS, seed.outcome(V, E, R, M, p_y, ())))["unloading_time"]


def test_limiting_pressure_for_yield_velocity_inverts_eq_28():
    """The p_y that moves V_y to a target gives that V_y through yield_point (eq. 28), the pair kept;
    and ContactPair.vary(yield_velocity=...) lands on it."""
    from microimpact import ContactPair

    Vy0 = seed.yield_point(E, R, M, P_Y)[2]
    for target in (0.01, 1.0, Vy0, 37.0, 900.0):
        p = seed.limiting_pressure_for_yield_velocity(target, P_Y, Vy0)
        assert seed.yield_point(E, R, M, p)[2] == pytest.approx(target, rel=1e-14)
    pair = ContactPair.paper_case("silicon")
    assert pair.vary(yield_velocity=3.0).yield_velocity == pytest.approx(3.0, rel=1e-14)


def test_particle_modulus_inverts_effective_modulus():
    from microimpact.core import hertz

    for E1, nu1, E2, nu2 in ((1.2e9, 0.3, 163e9, 0.22), (70e9, 0.33, 70e9, 0.33), (5e6, 0.49, 2e11, 0.0)):
        Es = hertz.effective_modulus(E1, nu1, E2, nu2)
        assert hertz.particle_modulus(Es, nu1, E2, nu2) == pytest.approx(E1, rel=1e-12)
    assert math.isnan(hertz.particle_modulus(200e9, 0.3, 100e9, 0.3))  # stiffer than the surface: none
