"""The paper's figures: each ``*_data`` function returns exactly what the public API gives,
and each plot function draws on a given Axes with labelled axes in units."""

import math

import numpy as np
import pytest

import microimpact as mi
from microimpact.figures import paper as fp

plt = pytest.importorskip("matplotlib.pyplot")

SILICON = mi.ContactPair.paper_case("silicon")


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _rows(table, key, value):
    return np.asarray(table[key]) == value


# ----------------------------------------------------------------------------- data == public API
def test_restitution_data_equals_pair_impact():
    V = np.array([1.0, 5.0, 7.0, 10.0, 50.0, 120.0])
    measured = {"silicon": ([20.0, 40.0], [0.9, 0.8])}
    t = fp.restitution_data(velocity=V, data=measured)
    for name in ("silicon", "mica"):
        m = _rows(t, "series", name) & _rows(t, "kind", "model")
        pair = mi.ContactPair.paper_case(name)
        np.testing.assert_array_equal(t["velocity_m_s"][m], V)
        np.testing.assert_array_equal(t["restitution"][m], pair.impact(V, warn=False).restitution)
        assert np.all(t["yield_velocity_m_s"][m] == pair.yield_velocity)
    meas = _rows(t, "kind", "measured")
    np.testing.assert_array_equal(t["velocity_m_s"][meas], [20.0, 40.0])
    np.testing.assert_array_equal(t["restitution"][meas], [0.9, 0.8])


def test_restitution_data_default_grid_contains_yield_point():
    t = fp.restitution_data()
    for name in ("silicon", "mica"):
        m = _rows(t, "series", name)
        Vy = mi.ContactPair.paper_case(name).yield_velocity
        assert Vy in t["velocity_m_s"][m]
        assert t["velocity_m_s"][m].max() == 120.0
        # e = 1 up to V_y, < 1 above (eq. 27)
        e, V = t["restitution"][m], t["velocity_m_s"][m]
        assert np.all(e[V <= Vy] == 1.0) and np.all(e[V > Vy] < 1.0)


def test_restitution_data_rejects_mismatched_measurements():
    with pytest.raises(ValueError, match="silicon"):
        fp.restitution_data(data={"silicon": ([1.0, 2.0], [0.9])})


@pytest.mark.parametrize(
    "parameter, values, change",
    [
        ("limiting_pressure", [50e6, 250e6], lambda v: SILICON.replace(limiting_pressure=v)),
        ("density", [1350.0, 5350.0], lambda v: mi.ContactPair.sphere_on_flat(2.45e-6, v, 1.31e9, 156e6)),
        # independent E* of the seed's Fig. 4: E2 = 150 GPa, nu = 0.3 both
        (
            "particle_modulus",
            [1.2e9, 21.2e9],
            lambda v: SILICON.replace(effective_modulus=1.0 / (0.91 / v + 0.91 / 150e9)),
        ),
    ],
)
def test_energy_loss_data_equals_pair_impact(parameter, values, change):
    V = np.array([0.0, 3.0, 30.0, 80.0, 120.0])
    t = fp.energy_loss_data(parameter, values, velocity=V)
    col = fp.ENERGY_LOSS_PARAMETERS[parameter][0]
    for v in values:
        m = _rows(t, col, v)
        out = change(v).impact(V, warn=False)
        np.testing.assert_allclose(t["energy_loss"][m], out.energy_loss, rtol=1e-13, atol=0)
        np.testing.assert_allclose(t["restitution"][m], out.restitution, rtol=1e-13)
        np.testing.assert_array_equal(t["large_strain"][m], out.large_strain.astype(int))
        np.testing.assert_allclose(t["yield_velocity_m_s"][m], out.yield_velocity, rtol=1e-13)


def test_energy_loss_data_trends_of_the_paper():
    # Figs. 3-5 (Sec. 3.2): more loss for lower p_y, higher E1, higher density, at every plastic speed
    V = np.array([60.0, 120.0])
    for parameter, values, sign in (
        ("limiting_pressure", [50e6, 150e6, 250e6], -1),
        ("particle_modulus", [1.2e9, 11.2e9, 21.2e9], 1),
        ("density", [1350.0, 3350.0, 5350.0], 1),
    ):
        t = fp.energy_loss_data(parameter, values, velocity=V)
        loss = np.asarray(t["energy_loss"]).reshape(len(values), V.size)
        assert np.all(sign * np.diff(loss, axis=0) > 0), parameter


def test_energy_loss_data_rejects_unknown_parameter():
    with pytest.raises(ValueError, match="parameter"):
        fp.energy_loss_data("poisson", [0.3])


def test_force_displacement_data_equals_force_law():
    t = fp.force_displacement_data((30.0, 70.0), n=51)
    for V in (30.0, 70.0):
        out = SILICON.impact(V, warn=False)
        load = _rows(t, "velocity_m_s", V) & _rows(t, "branch", "loading")
        unload = _rows(t, "velocity_m_s", V) & _rows(t, "branch", "unloading")
        a_l, a_u = t["approach_m"][load], t["approach_m"][unload]
        np.testing.assert_array_equal(t["force_N"][load], SILICON.force(a_l))
        np.testing.assert_array_equal(t["force_N"][unload], SILICON.force(a_u, max_approach=out.max_approach))
        # branches from 0 to alpha* and back to alpha_p, yield point included
        assert a_l[0] == 0.0 and a_l[-1] == out.max_approach and SILICON.yield_approach in a_l
        assert a_u[0] == out.max_approach and a_u[-1] == out.plastic_approach
        # independent: the branches meet at P* and unloading ends at zero force
        np.testing.assert_allclose(t["force_N"][load][-1], out.max_force, rtol=1e-12)
        np.testing.assert_allclose(t["force_N"][unload][0], out.max_force, rtol=1e-12)
        assert abs(t["force_N"][unload][-1]) < 1e-12 * out.max_force
        # the stated plastic approach is the API's
        assert np.all(t["plastic_approach_m"][load] == out.plastic_approach)


def test_approach_data_equals_pair_impact():
    V = np.array([2.0, 10.0, 50.0, 120.0])
    t = fp.approach_data(velocity=V)
    out = SILICON.impact(V, warn=False)
    np.testing.assert_array_equal(t["max_approach_m"], out.max_approach)
    np.testing.assert_array_equal(t["plastic_approach_m"], out.plastic_approach)
    np.testing.assert_allclose(t["plastic_ratio"], out.plastic_approach / out.max_approach, rtol=1e-15)
    assert t["plastic_ratio"][0] == 0.0  # elastic impact below V_y


def test_contact_time_data_equals_pair_impact():
    V = np.array([2.0, 7.6, 50.0, 120.0])
    t = fp.contact_time_data(velocity=V)
    out = SILICON.impact(V, warn=False)
    for name in ("elastic_stage_time", "plastic_stage_time", "loading_time", "unloading_time", "contact_time"):
        np.testing.assert_array_equal(t[name + "_s"], getattr(out, name))
    np.testing.assert_array_equal(t["deresiewicz_time_s"], SILICON.deresiewicz_contact_time(V))
    assert np.all(t["ning_loading_time_s"] == SILICON.ning_loading_time())
    # independent: t_L tends to eq. 31 from above
    assert np.all(t["loading_time_s"][1:] > t["ning_loading_time_s"][1:])


def test_force_time_data_equals_history():
    t = fp.force_time_data(70.0, n=201)
    ep = SILICON.history(70.0, n=201)
    el = SILICON.elastic_equivalent().history(70.0, n=201)
    m = _rows(t, "series", "elastic-plastic")
    np.testing.assert_array_equal(t["time_s"][m], ep.time)
    np.testing.assert_array_equal(t["force_N"][m], ep.force)
    m = _rows(t, "series", "elastic")
    np.testing.assert_array_equal(t["force_N"][m], el.force)
    m = _rows(t, "series", "hertz")
    loading = (ep.stage == 1) | (ep.stage == 2)
    np.testing.assert_array_equal(t["time_s"][m], ep.time[loading])
    np.testing.assert_allclose(
        t["force_N"][m],
        4 / 3 * SILICON.effective_modulus * math.sqrt(SILICON.effective_radius) * ep.approach[loading] ** 1.5,
        rtol=1e-13,
    )
    # the seed's Fig. 7: elastic-plastic lasts longer than the equivalent elastic impact, with a lower peak
    assert ep.time[-1] > el.time[-1] and ep.force.max() < el.force.max()


def test_dynamics_data_equals_history():
    t = fp.dynamics_data(50.0, n=301)
    h = SILICON.history(50.0, n=301)
    for col, attr in (
        ("time_s", "time"),
        ("approach_velocity_m_s", "approach_velocity"),
        ("force_N", "force"),
        ("approach_m", "approach"),
        ("stage", "stage"),
    ):
        np.testing.assert_array_equal(t[col], getattr(h, attr))
    assert t["approach_velocity_m_s"][0] == 50.0
    np.testing.assert_allclose(
        t["approach_velocity_m_s"][-1], -SILICON.impact(50.0, warn=False).rebound_velocity, rtol=1e-9
    )


def test_large_strain_velocity_is_where_a_over_R_is_0_3():
    for name in ("silicon", "mica"):
        pair = mi.ContactPair.paper_case(name)
        V = fp.large_strain_velocity(pair)
        a = pair.impact([V * (1 - 1e-6), V * (1 + 1e-6)], warn=False)
        assert list(a.large_strain) == [False, True]
        np.testing.assert_allclose(
            float(pair.impact(V, warn=False).max_contact_radius) / pair.effective_radius, 0.3, rtol=1e-9
        )
    assert fp.large_strain_velocity(SILICON.elastic_equivalent().replace(effective_modulus=1e30)) == math.inf


def test_every_data_column_is_documented():
    tables = [
        fp.restitution_data(velocity=[10.0], data={"x": ([1.0], [1.0])}),
        fp.energy_loss_data("particle_modulus", [1e9], velocity=[10.0]),
        fp.force_displacement_data((30.0,), n=3),
        fp.approach_data(velocity=[10.0]),
        fp.contact_time_data(velocity=[10.0]),
        fp.force_time_data(70.0, n=11),
        fp.dynamics_data(50.0, n=11),
    ]
    for t in tables:
        lengths = {len(np.atleast_1d(v)) for v in t.values()}
        assert len(lengths) == 1  # columns of one table
        for k in t:
            assert k in fp.COLUMNS, k


# ----------------------------------------------------------------------------- plot functions
V_SHORT = np.linspace(1.0, 120.0, 40)

PLOTS = [
    ("restitution", lambda ax: fp.plot_restitution(ax=ax, velocity=V_SHORT), "m/s", "–"),
    (
        "energy_loss",
        lambda ax: fp.plot_energy_loss("limiting_pressure", [100e6, 200e6], ax=ax, velocity=V_SHORT),
        "m/s",
        "–",
    ),
    ("force_displacement", lambda ax: fp.plot_force_displacement((30.0, 50.0), ax=ax), "nm", "µN"),
    ("force_time", lambda ax: fp.plot_force_time(70.0, ax=ax), "ns", "µN"),
    ("approach", lambda ax: fp.plot_approach(ax=ax, velocity=V_SHORT), "m/s", "nm"),
    ("contact_times", lambda ax: fp.plot_contact_times(ax=ax, velocity=V_SHORT), "m/s", "ns"),
]


@pytest.mark.parametrize("name, draw, xunit, yunit", PLOTS, ids=[p[0] for p in PLOTS])
def test_plot_uses_given_axes_with_units(name, draw, xunit, yunit):
    fig, ax = plt.subplots()
    out = draw(ax)
    assert out is ax
    assert f"({xunit})" in ax.get_xlabel()
    assert f"({yunit})" in ax.get_ylabel()
    assert ax.get_legend() is not None and len(ax.get_legend().get_texts()) >= 2
    assert sum(len(a.get_lines()) for a in ax.figure.axes) >= 2


def test_plot_creates_axes_when_none_given():
    ax = fp.plot_energy_loss("density", [1350.0, 5350.0], velocity=V_SHORT)
    assert ax.figure is not None
    w, h = ax.figure.get_size_inches()
    assert (w, h) == pytest.approx((3.5, 2.8))


def test_plot_draws_the_table_it_is_given():
    t = fp.approach_data(velocity=[10.0, 20.0, 30.0])
    ax = fp.plot_approach(table=t)
    x, y = ax.get_lines()[0].get_data()
    np.testing.assert_array_equal(x, t["velocity_m_s"])
    np.testing.assert_allclose(y, t["max_approach_m"] * 1e9)  # plotted in nm
    assert "(–)" in ax.right_ax.get_ylabel()


def test_plot_dynamics_three_panels():
    fig, axes = plt.subplots(3, 1)
    out = fp.plot_dynamics(50.0, ax=axes)
    assert list(out) == list(axes)
    assert "(m/s)" in axes[0].get_ylabel() and "(µN)" in axes[1].get_ylabel() and "(nm)" in axes[2].get_ylabel()
    assert "(ns)" in axes[2].get_xlabel()
    with pytest.raises(ValueError, match="three"):
        fp.plot_dynamics(50.0, ax=[axes[0]])


def test_plot_restitution_overlays_measurements():
    fig, ax = plt.subplots()
    fp.plot_restitution(ax=ax, velocity=V_SHORT, data={"silicon": ([20.0, 40.0], [0.9, 0.8])})
    measured = [ln for ln in ax.get_lines() if ln.get_linestyle() in ("None", "none", "") and len(ln.get_xdata()) == 2]
    assert len(measured) == 1
    np.testing.assert_array_equal(measured[0].get_ydata(), [0.9, 0.8])
    assert any("measured" in t.get_text() for t in ax.get_legend().get_texts())
