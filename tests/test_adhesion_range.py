"""Tabor's parameter flags a pair outside the adhesion limit (JKR or DMT) its adhesive model is
written for, as large strain is flagged: an attribute of the result and a warning, never a refusal."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import microimpact as mi
from microimpact.core import adhesion
from microimpact.pair import AdhesionRangeWarning

SILICON = mi.ContactPair.paper_case("silicon")  # NH4Fl, 2.45 um: soft and large, JKR
# a 50 nm silica-like particle on a stiff wall: small and stiff, DMT for weak adhesion
SMALL = mi.ContactPair.sphere_on_flat(radius=25e-9, density=2200.0, effective_modulus=70e9, limiting_pressure=5e9)


def _impact(pair, V, **kw):
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        res = pair.impact(V, **kw)
    return res, [x for x in w if issubclass(x.category, AdhesionRangeWarning)]


def test_tabor_parameter_of_the_pair_and_model():
    r = SILICON.adhesion_range(model="thornton_ning_1998_elastic_adhesive", work_of_adhesion=0.1)
    want = adhesion.tabor_parameter(SILICON.effective_modulus, SILICON.effective_radius, 0.1, 0.3e-9)
    assert r["tabor_parameter"] == want and r["limit"] == "JKR" and r["inside"] and want > 5.0
    # LAMMPS' jkr and dmt take the surface energy: G = 2 gamma
    assert SILICON.adhesion_range(model="jkr_elastic_adhesive", surface_energy=0.05)["tabor_parameter"] == want
    assert SILICON.adhesion_range(model="dmt_elastic_adhesive", surface_energy=0.05)["inside"] is False
    r = SMALL.adhesion_range(model="dmt_elastic_adhesive", surface_energy=0.005, equilibrium_separation=0.4e-9)
    assert r["inside"] and r["tabor_parameter"] < 0.1
    with pytest.raises(ValueError, match="has no adhesion limit"):
        SILICON.adhesion_range(model="thornton_ning_2016")
    with pytest.raises(ValueError, match="equilibrium_separation must be positive"):
        SILICON.adhesion_range(model="dmt_elastic_adhesive", surface_energy=0.05, equilibrium_separation=-1.0)
    with pytest.raises(ValueError, match="surface_energy"):
        SILICON.adhesion_range(model="dmt_elastic_adhesive", surface_energy=-0.05)


@pytest.mark.parametrize("V", [10.0, np.array([1.0, 10.0, 100.0])])
def test_impact_flags_a_small_stiff_pair_with_a_jkr_law(V):
    res, w = _impact(SMALL, V, model="thornton_ning_1998_adhesive_plastic", work_of_adhesion=0.05)
    mu = SMALL.adhesion_range(model="thornton_ning_1998_adhesive_plastic", work_of_adhesion=0.05)["tabor_parameter"]
    assert res.tabor_parameter == mu and mu < 0.1
    assert bool(res.outside_adhesion_range) and len(w) == 1
    assert "below 5: the JKR limit of thornton_ning_1998_adhesive_plastic does not hold" in str(w[0].message)
    assert "the DMT limit does" in str(w[0].message)
    assert np.all(np.isfinite(res.restitution))  # flagged, not refused
    # the same pair with the DMT law is inside its range: no flag, no warning
    res, w = _impact(SMALL, V, model="dmt_elastic_adhesive", surface_energy=0.025)
    assert not res.outside_adhesion_range and not w


def test_impact_flags_a_soft_large_pair_with_the_dmt_law_and_not_with_jkr():
    res, w = _impact(SILICON, 10.0, model="dmt_elastic_adhesive", surface_energy=0.05)
    assert res.outside_adhesion_range and "the JKR limit does" in str(w[0].message)
    res, w = _impact(SILICON, 10.0, model="jkr_elastic_adhesive", surface_energy=0.05)
    assert not res.outside_adhesion_range and not w
    # no warning with warn=False; the flag stays
    res = SILICON.impact(10.0, model="dmt_elastic_adhesive", surface_energy=0.05, warn=False)
    assert res.outside_adhesion_range


def test_models_without_adhesion_are_not_flagged():
    res, w = _impact(SILICON, 10.0)
    assert math.isnan(res.tabor_parameter) and not res.outside_adhesion_range and not w
    res, w = _impact(SMALL, 10.0, model="thornton_ning_1998_adhesive_plastic", work_of_adhesion=0.0)
    assert not res.outside_adhesion_range and not w  # G = 0: no adhesion to have a limit
