"""Materials, effective values, the force laws and the ContactPair object layer."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import microimpact as mi
from microimpact import contact, materials


# --------------------------------------------------------------------------- materials
@pytest.mark.parametrize("name", materials.list_materials())
def test_every_material_is_valid_and_cited(name):
    m = mi.get_material(name)
    assert m.name == name
    assert len(m.source) > 20  # a real citation, not a placeholder
    assert 0 < m.youngs_modulus < 1e12 and -1 < m.poisson_ratio <= 0.5 and 500 < m.density < 25000


def test_required_materials_present():
    for name in [
        "nh4fl",
        "silicon",
        "mica",
        "glass",
        "steel",
        "aluminium",
        "copper",
        "fused_silica",
        "quartz",
        "fly_ash",
    ]:
        assert name in mi.MATERIALS


def test_material_lookup_is_forgiving_but_strict():
    assert mi.get_material("Fused Silica") is mi.MATERIALS["fused_silica"]
    assert mi.get_material("aluminum") is mi.MATERIALS["aluminium"]
    with pytest.raises(ValueError, match="unobtainium"):
        mi.get_material("unobtainium")


def test_paper_materials_reproduce_paper_effective_moduli():
    # seed Sec. 3.1: E* = 1.31 GPa (silicon), 1.30 GPa (mica)
    si = mi.ContactPair.from_materials("nh4fl", "silicon", radius=2.45e-6, limiting_pressure=156e6)
    mica = mi.ContactPair.from_materials("nh4fl", "mica", radius=2.45e-6, limiting_pressure=158e6)
    assert si.effective_modulus == pytest.approx(1.31e9, rel=0.01)
    assert mica.effective_modulus == pytest.approx(1.30e9, rel=0.01)


def test_effective_values():
    assert float(mi.effective_modulus(1e9, 0.0, np.inf, 0.3)) == pytest.approx(1e9)
    # two identical bodies: E* = E / (2 (1 - nu^2))
    assert float(mi.effective_modulus(2e9, 0.3, 2e9, 0.3)) == pytest.approx(2e9 / (2 * 0.91))
    assert float(mi.effective_radius(1.0)) == 1.0
    assert float(mi.effective_radius(1.0, 1.0)) == 0.5
    assert float(mi.effective_mass(2.0, 2.0)) == 1.0
    assert float(materials.sphere_mass(1.0, 3.0 / (4.0 * math.pi))) == pytest.approx(1.0)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: mi.effective_modulus(-1e9, 0.3, 1e9, 0.3), "E1"),
        (lambda: mi.effective_modulus(0.0, 0.3, 1e9, 0.3), "E1"),
        (lambda: mi.effective_modulus(np.nan, 0.3, 1e9, 0.3), "E1"),
        (lambda: mi.effective_modulus(1e9, 0.6, 1e9, 0.3), "nu1"),
        (lambda: mi.effective_modulus(1e9, 0.3, 1e9, -1.0), "nu2"),
        (lambda: mi.effective_modulus(1e9, 0.3, 1e9, np.nan), "nu2"),
        (lambda: mi.Material("x", 1e9, 0.7, 1000.0), "poisson"),
        (lambda: mi.ContactPair.sphere_on_flat(-1e-6, 1000.0, 1e9, 1e8), "radius"),
        (lambda: mi.ContactPair.sphere_on_flat(1e-6, 0.0, 1e9, 1e8), "density"),
        (lambda: mi.ContactPair.sphere_on_flat(1e-6, 1000.0, np.inf, 1e8), "effective_modulus"),
        (lambda: mi.ContactPair.sphere_on_flat(1e-6, 1000.0, 1e9, -5.0), "limiting_pressure"),
        (lambda: mi.ContactPair.sphere_on_flat(1e-6, 1000.0, 1e9, np.nan), "limiting_pressure"),
        (lambda: mi.ContactPair(1e9, 1e-6, 0.0, 1e8), "effective_mass"),
        (lambda: mi.yield_velocity_sphere_on_flat(1e8, 1e9, -3.0), "density"),
    ],
)
def test_bad_input_names_the_parameter_and_value(call, name):
    with pytest.raises(ValueError) as info:
        call()
    msg = str(info.value)
    assert name in msg
    assert any(ch.isdigit() for ch in msg) or "nan" in msg or "inf" in msg


def test_boundary_poisson_ratios_accepted():
    assert np.isfinite(mi.effective_modulus(1e9, 0.5, 1e9, -0.999))


# --------------------------------------------------------------------------- force laws
E, R, PY = 1.31e9, 2.45e-6, 156e6


def test_yield_point_definition():
    a_y = float(contact.yield_approach(PY, E, R))
    # the Hertz central pressure reaches p_y exactly at alpha_y (eqs. 1, 4, 5)
    assert float(contact.hertz_central_pressure(a_y, E, R)) == pytest.approx(PY, rel=1e-14)
    assert float(contact.yield_force(PY, E, R)) == pytest.approx(float(contact.hertz_force(a_y, E, R)), rel=1e-14)
    # the seed's identity pi p_y R* alpha_y = 3/2 P_y (THEORY.md §2)
    assert math.pi * PY * R * a_y == pytest.approx(1.5 * float(contact.yield_force(PY, E, R)), rel=1e-14)


def test_loading_force_continuous_at_yield_and_normalised_forms():
    a_y = float(contact.yield_approach(PY, E, R))
    P_y = float(contact.yield_force(PY, E, R))
    a = a_y * np.array([0.0, 0.3, 1 - 1e-12, 1.0, 1 + 1e-12, 2.0, 10.0])
    P = contact.loading_force(a, E, R, PY)
    np.testing.assert_allclose(P / P_y, contact.normalized_loading_force(a / a_y), rtol=1e-12, atol=1e-300)
    assert P[2] == pytest.approx(P[4], rel=1e-10)
    # stage 2 slope is pi p_y R*
    assert (P[6] - P[5]) / (a[6] - a[5]) == pytest.approx(math.pi * PY * R, rel=1e-12)


@settings(max_examples=100, deadline=None)
@given(st.floats(min_value=1.0, max_value=1e3), st.floats(min_value=0.0, max_value=1.0))
def test_normalised_unloading_matches_dimensional(A, frac):
    a_y = float(contact.yield_approach(PY, E, R))
    P_y = float(contact.yield_force(PY, E, R))
    alpha_max = A * a_y
    alpha = alpha_max * frac
    dimensional = float(contact.contact_force(alpha, E, R, PY, max_approach=alpha_max))
    normalised = float(contact.normalized_unloading_force(alpha / a_y, A)) * P_y
    assert dimensional == pytest.approx(normalised, rel=1e-9, abs=1e-15 * P_y)


def test_unloading_radius_and_plastic_approach():
    a_y = float(contact.yield_approach(PY, E, R))
    a_max = 5 * a_y
    P_max = float(contact.loading_force(a_max, E, R, PY))
    F_e = float(contact.hertz_force(a_max, E, R))
    assert float(contact.unloading_radius(a_max, P_max, E, R)) == pytest.approx(R * F_e / P_max)  # eq. 9
    assert float(contact.plastic_approach(a_max, P_max, E, R)) == pytest.approx(a_max * (1 - P_max / F_e))  # eq. 11
    # elastic: no flattening
    assert float(contact.unloading_radius(a_y / 2, contact.hertz_force(a_y / 2, E, R), E, R)) == pytest.approx(R)


def test_negative_approach_rejected():
    with pytest.raises(ValueError, match="alpha"):
        contact.hertz_force(-1e-9, E, R)


# --------------------------------------------------------------------------- ContactPair
def test_constructors_agree():
    a = mi.ContactPair.sphere_on_flat(radius=2.45e-6, density=1350.0, effective_modulus=1.31e9, limiting_pressure=156e6)
    b = mi.ContactPair.paper_case("silicon")
    c = mi.ContactPair.sphere_on_flat(
        2.45e-6, mass=a.effective_mass, effective_modulus=1.31e9, yield_strength=74e6, k=156 / 74
    )
    d = mi.ContactPair(1.31e9, 2.45e-6, a.effective_mass, 156e6)
    for p in (b, c, d):
        assert p.yield_velocity == pytest.approx(a.yield_velocity, rel=1e-12)


def test_limiting_pressure_from_k_and_yield_strength():
    pair = mi.ContactPair.from_materials("nh4fl", "silicon", radius=2e-6)
    assert pair.limiting_pressure == pytest.approx(materials.DEFAULT_K * 74e6)
    pair = mi.ContactPair.from_materials("copper", "steel", radius=2e-6, k=2.1)
    assert pair.limiting_pressure == pytest.approx(2.1 * 70e6)  # the softer (copper) yields
    with pytest.raises(ValueError, match="limiting_pressure"):
        mi.ContactPair.from_materials("glass", "silicon", radius=2e-6)  # no yield strength known
    with pytest.raises(ValueError, match="limiting_pressure"):
        mi.ContactPair.sphere_on_flat(1e-6, 1000.0, 1e9, 1e8, yield_strength=1e7)


def test_two_spheres_reduce_to_effective_values():
    pair = mi.ContactPair.two_spheres("steel", "steel", 1e-6, 1e-6, limiting_pressure=1e9)
    m = materials.sphere_mass(1e-6, 7850.0)
    assert pair.effective_radius == pytest.approx(0.5e-6)
    assert pair.effective_mass == pytest.approx(m / 2)
    # the general energy form of V_y with m* agrees with eq. 28's structure scaled by the mass ratio
    flat = mi.ContactPair.from_materials("steel", "steel", radius=0.5e-6, limiting_pressure=1e9)
    # same E*, R*; m* of the pair is (1e-6)^3 rho (4/3 pi)/2 vs (0.5e-6)^3 rho (4/3 pi): ratio 4
    assert pair.yield_velocity == pytest.approx(flat.yield_velocity / 2.0, rel=1e-12)


def test_sphere_on_sphere_large_target_tends_to_flat():
    flat = mi.ContactPair.from_materials("nh4fl", "silicon", radius=2.45e-6, limiting_pressure=156e6)
    big = mi.ContactPair.two_spheres("nh4fl", "silicon", 2.45e-6, 1.0, limiting_pressure=156e6)
    out_f, out_b = flat.impact(40.0, warn=False), big.impact(40.0, warn=False)
    assert out_b.restitution == pytest.approx(out_f.restitution, rel=1e-5)


def test_pair_force_delegates():
    pair = mi.ContactPair.paper_case("silicon")
    out = pair.impact(50.0, warn=False)
    assert float(pair.force(out.max_approach)) == pytest.approx(float(out.max_force), rel=1e-12)
    assert float(pair.force(out.plastic_approach, max_approach=out.max_approach)) == pytest.approx(
        0.0, abs=1e-12 * float(out.max_force)
    )


def test_result_to_dict_round_trip():
    out = mi.ContactPair.paper_case("silicon").impact([10.0, 20.0])
    d = out.to_dict()
    assert set(d) >= {
        "restitution",
        "rebound_velocity",
        "max_approach",
        "plastic_approach",
        "max_force",
        "unloading_radius",
        "energy_loss",
        "elastic_stage_time",
        "plastic_stage_time",
        "loading_time",
        "unloading_time",
        "contact_time",
    }
    assert len(out) == 2


def test_pair_restitution_fast_path_equals_full_result():
    pair = mi.ContactPair.paper_case("mica")
    V = np.concatenate([[0.0, pair.yield_velocity, 1e300], np.logspace(-2, 4, 500)])
    fast = pair.restitution(V)
    full = pair.impact(V, warn=False).restitution
    np.testing.assert_allclose(fast, full, rtol=1e-14, atol=0)
    assert float(pair.restitution(50.0)) == pytest.approx(
        float(full[V == 50.0][0]) if (V == 50.0).any() else float(pair.impact(50.0, warn=False).restitution), rel=1e-14
    )


def test_result_and_pair_show_their_values_with_units():
    """repr and the notebook table: every field, its unit, a single value or the range, flags counted."""
    pair = mi.ContactPair.paper_case("silicon")
    one = pair.impact(50.0, warn=False)
    text = repr(one)
    assert text.startswith("ImpactResult(1 impact: velocity = 50 m/s, restitution = 0.724814,")
    assert "contact_time = 2.47611e-08 s" in text
    many = pair.impact([5.0, 50.0, 100.0], warn=False)
    e = many.restitution
    assert f"3 impacts: velocity = 5 .. 100 m/s, restitution = {e.min():.6g} .. 1," in repr(many)
    table = many._repr_html_()
    from microimpact.core.quantities import OUTCOME_FIELDS

    for name in OUTCOME_FIELDS:
        assert f"<code>{name}</code>" in table
    assert "<td>2 of 3</td>" in table  # large_strain: 50 and 100 m/s
    assert "<td>1 of 3</td>" in table  # elastic: 5 m/s
    empty = pair.impact(np.array([]), warn=False)
    assert "(empty)" in empty._repr_html_()
    card = pair._repr_html_()
    assert "V_y" in card and f"{pair.yield_velocity:.6g}" in card and "kg/m^3" in card
    elastic = pair.elastic_equivalent()
    assert "V_y" not in elastic._repr_html_()  # p_y = inf: no yield point to show


def test_one_impact_fields_are_the_array_paths_numpy_scalars_whatever_is_read_first():
    """pair.impact(float) keeps the core's tuple until a field is read; every field, read first or
    later, is then the numpy scalar (flags numpy booleans) the array path gives, bit for bit."""
    import copy
    import pickle

    from microimpact.core.quantities import FLAG_FIELDS, OUTCOME_FIELDS

    pair = mi.ContactPair.paper_case("silicon")
    for V in (0.5 * pair.yield_velocity, 50.0):
        many = pair.impact(np.array([V]), warn=False)
        for first in OUTCOME_FIELDS:
            one = pair.impact(V, warn=False)
            kept = pickle.loads(pickle.dumps(one)), copy.copy(one)  # before any field is read
            for res in (one, *kept):
                getattr(res, first)
                for name in OUTCOME_FIELDS:
                    x = getattr(res, name)
                    assert type(x) is (np.bool_ if name in FLAG_FIELDS else np.float64), name
                    assert x.tobytes() == np.asarray(getattr(many, name))[0].tobytes(), name
    assert not hasattr(mi.ImpactResult, "velocity")  # a field, no class attribute
    with pytest.raises(AttributeError, match="no_such_field"):
        pair.impact(50.0, warn=False).no_such_field


def test_large_strain_warning_under_each_first_filter():
    """The warning is skipped only where the first filter ignores it whatever its text: an "error"
    first, a message pattern, or an ignore of another category still see it."""
    import warnings

    pair = mi.ContactPair.paper_case("silicon")  # 50 m/s is flagged large_strain
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pair.impact(50.0)  # nothing, no error
        warnings.simplefilter("error", mi.LargeStrainWarning)
        with pytest.raises(mi.LargeStrainWarning, match="from V = 50 m/s"):
            pair.impact(50.0)
    for ignore in (
        dict(category=DeprecationWarning),
        dict(category=mi.LargeStrainWarning, message="no such text"),
        dict(category=mi.LargeStrainWarning, module="no_such_module"),
    ):
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            warnings.filterwarnings("ignore", **ignore)
            pair.impact(50.0)
        assert [w.category for w in seen] == [mi.LargeStrainWarning], ignore
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        warnings.filterwarnings("ignore", category=mi.LargeStrainWarning)
        assert pair.impact(50.0).large_strain
    assert seen == []
