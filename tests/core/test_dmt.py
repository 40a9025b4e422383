"""The DMT elastic adhesive law (``dmt_elastic_adhesive``, LAMMPS ``pair_style granular`` ``dmt``) and
Tabor's parameter: the force as LAMMPS writes it, the energy balance, an independent quadrature of the
contact time, Hertz without adhesion, e = 1 (the law is conservative)."""

from __future__ import annotations

import math
import warnings

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import IntegrationWarning, quad

from microimpact.core import adhesion, models
from microimpact.core.models import _jkr
from microimpact.core.models import dmt_elastic_adhesive as dmt
from microimpact.core.quantities import OUTCOME_FIELDS

PROFILE = dict(derandomize=True, deadline=None)
E, R, RHO = 1.31e9, 2.45e-6, 1350.0
M = 4.0 / 3.0 * math.pi * R**3 * RHO


def _o(V, gamma, E=E, R=R, m=M):
    return dict(zip(OUTCOME_FIELDS, dmt.outcome(V, E, R, m, 1e8, (gamma,))))


def test_contract():
    assert dmt.NAME in models.available() and models.get(dmt.NAME).module is dmt
    assert models.get(dmt.NAME).ADHESION_LIMIT == "DMT" and models.get(dmt.NAME).LABEL == "DMT adhesive"
    assert dmt.STICKS is False
    with pytest.raises(ValueError, match="surface_energy must be non-negative and finite, got -0.1"):
        dmt.validate((-0.1,))
    out = dmt.outcome(1.0, E, R, M, 1e8, (math.nan,))
    assert out[0] == 1.0 and all(math.isnan(x) for x in out[1:])


@pytest.mark.parametrize("alpha", [0.0, 1e-12, 3e-9, 1e-7])
def test_force_is_lammps_dmt(alpha):
    """``Fne = k a delta - 4 pi gamma R``, ``k = 4/3 E``, ``a = (R delta)^(1/2)`` (LAMMPS'
    ``gran_normal_dmt_force``) in contact; nothing apart (no force beyond contact)."""
    gamma = 0.05
    a = math.sqrt(R * alpha)
    want = 4.0 / 3.0 * E * a * alpha - 4.0 * math.pi * gamma * R
    assert dmt.force(alpha, 0.0, alpha, E, R, M, 1e8, (gamma,)) == pytest.approx(want, rel=1e-15, abs=0)
    assert dmt.force(-1e-12, 0.0, alpha, E, R, M, 1e8, (gamma,)) == 0.0
    assert dmt.pulloff_force(R, gamma) == pytest.approx(2.0 * math.pi * (2.0 * gamma) * R, rel=1e-15)  # 2 pi G R


@pytest.mark.parametrize("V", [1e-3, 0.3, 3.0, 300.0])
def test_without_adhesion_is_hertz(V):
    out = dmt.outcome(V, E, R, M, 1e8, (0.0,))
    ref = _jkr.hertz_impact(V, E, R, M)
    for k, x, r in zip(OUTCOME_FIELDS, out, ref):
        if math.isnan(r):
            assert math.isnan(x), k
        else:
            assert x == pytest.approx(r, rel=1e-13, abs=0.0), k


@settings(max_examples=60, **PROFILE)
@given(
    logV=st.floats(-3.0, 2.5),
    logg=st.floats(-4.0, 0.5),
    logE=st.floats(8.0, 11.5),
    logR=st.floats(-8.0, -4.0),
)
def test_energy_balance_force_and_time(logV, logg, logE, logR):
    """e = 1; the maximum approach balances the impact energy (W(alpha_m) = m V^2/2 to 1e-12), the
    maximum force is the law's there, and the contact time is twice an independent quadrature
    (scipy's QUADPACK on d alpha / v(alpha)) to 1e-9."""
    V, gamma, Em, Rm = 10.0**logV, 10.0**logg, 10.0**logE, 10.0**logR
    m = 4.0 / 3.0 * math.pi * Rm**3 * 2500.0
    o = _o(V, gamma, Em, Rm, m)
    assert o["restitution"] == 1.0 and o["rebound_velocity"] == V and o["energy_loss"] == 0.0
    k = 4.0 / 3.0 * Em * math.sqrt(Rm)
    Fc = 4.0 * math.pi * gamma * Rm
    am = o["max_approach"]
    K = 0.5 * m * V * V

    def W(a):
        return 0.4 * k * a**2.5 - Fc * a

    assert W(am) == pytest.approx(K, rel=1e-12)
    assert o["max_force"] == pytest.approx(k * am**1.5 - Fc, rel=1e-12)

    # t = int_0^am da / v: v^2 = 2 (K - W(a))/m, with the turning point's square root taken out
    # by a = am (1 - s^2) (an independent route: QUADPACK in alpha, not Gauss-Legendre in b)
    def f(s):
        a = am * (1.0 - s * s)
        return (
            2.0 * am * s / math.sqrt(2.0 * (K - W(a)) / m)
            if s > 0.0
            else 2.0 * am / math.sqrt(2.0 * am * (k * am**1.5 - Fc) / m)
        )

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)  # QUADPACK's own 1e-13 goal; 1e-9 is asked
        t, err = quad(
            f,
            0.0,
            1.0,
            epsabs=0.0,
            epsrel=1e-13,
            limit=200,
            points=[math.sqrt(max(0.0, 1.0 - (K / Fc) / am))] if Fc > 0 and K / Fc < am else None,
        )
    assert o["loading_time"] == pytest.approx(t, rel=1e-9)
    assert o["contact_time"] == 2.0 * o["loading_time"] and o["unloading_time"] == o["loading_time"]
    assert o["plastic_approach"] == 0.0 and o["elastic"] == 1.0


def test_adhesion_deepens_and_lengthens_the_contact():
    a = [_o(1.0, g) for g in (0.0, 0.05, 0.5)]
    assert a[0]["max_approach"] < a[1]["max_approach"] < a[2]["max_approach"]
    assert a[0]["contact_time"] < a[1]["contact_time"] < a[2]["contact_time"]
    assert all(x["restitution"] == 1.0 for x in a)


def test_tabor_parameter():
    """mu = (R G^2 / (E^2 z0^3))^(1/3): a small stiff particle is DMT, a soft large one JKR."""
    mu = adhesion.tabor_parameter(1e11, 25e-9, 0.1, 0.3e-9)
    assert mu == pytest.approx((25e-9 * 0.01 / (1e22 * 2.7e-29)) ** (1.0 / 3.0), rel=1e-14)
    assert mu < adhesion.TABOR_DMT
    assert adhesion.tabor_parameter(E, R, 0.1, adhesion.EQUILIBRIUM_SEPARATION) > adhesion.TABOR_JKR
    # scaling: mu ~ R^(1/3) G^(2/3) E^(-2/3) z0^(-1)
    assert adhesion.tabor_parameter(E, 8 * R, 0.1, 0.3e-9) == pytest.approx(
        2.0 * adhesion.tabor_parameter(E, R, 0.1, 0.3e-9), rel=1e-14
    )
