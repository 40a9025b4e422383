"""microimpact.figures.oblique: the plotted numbers are those of the data twins, which are the
application's (oblique_impact, universal_curve); the published alumina points are drawn."""

import numpy as np
import pytest

from microimpact import oblique as ob
from microimpact.figures import oblique as fo

plt = pytest.importorskip("matplotlib.pyplot")

ANGLES = [5.0, 20.0, 45.0, 80.0]


def test_oblique_data_is_oblique_impact():
    data = fo.oblique_data(angle=ANGLES)
    case = ob.ALUMINA_CASE
    for model in ("mindlin", "rigid"):
        sel = data["model"] == model
        ref = ob.oblique_impact(
            ob.alumina_pair(), case["velocity"], ANGLES, case["friction"],
            tangential=model, method="table",
        )  # fmt: skip
        np.testing.assert_array_equal(data["angle"][sel], ANGLES)
        for k in ("tangential_restitution", "rebound_spin", "contact_rebound_angle", "impulse_ratio"):
            np.testing.assert_array_equal(data[k][sel], getattr(ref, k))
    # at grazing incidence both models slide: the same impulse
    far = data["angle"] == 80.0
    assert np.all(data["impulse_ratio"][far] == 1.0)


def test_plot_oblique_draws_the_data_and_the_published_points():
    data = fo.oblique_data(angle=ANGLES)
    axes = fo.plot_oblique(table=data)
    assert len(axes) == 3
    for ax, key in zip(axes, ("tangential_restitution", "rebound_spin", "contact_rebound_angle")):
        lines = ax.get_lines()
        mindlin = lines[0]
        np.testing.assert_array_equal(mindlin.get_xdata(), ANGLES)
        np.testing.assert_allclose(mindlin.get_ydata(), data[key][data["model"] == "mindlin"])
        markers = [ln for ln in lines if ln.get_linestyle() == "None"]
        assert len(markers) == 2  # measured and DEM points
    a, v = ob.measured_alumina("experiment", "et")
    np.testing.assert_allclose(axes[0].get_lines()[2].get_xdata(), a)
    assert "impact angle" in axes[-1].get_xlabel()
    plt.close(axes[0].figure)


def test_universal_data_limits_and_plot():
    psi = np.array([0.0, 0.5, 2.0, 30.0])
    data = fo.universal_data(0.85, x=(1.0, 0.1), psi=psi)
    for model in ("mindlin", "rigid"):
        sel = (data["model"] == model) & (data["x"] == 1.0)
        F = data["impulse_ratio"][sel]
        assert F[0] == 0.0 and F[-1] == pytest.approx(1.0, abs=1e-9)  # no slip: no impulse; far: Coulomb
        assert np.all(np.diff(F) >= 0.0)
    sel = (data["model"] == "mindlin") & (data["x"] == 0.1)
    F, _, _ = ob.universal_curve(psi, 0.85, 0.1)
    np.testing.assert_array_equal(data["impulse_ratio"][sel], F)
    ax = fo.plot_universal(0.85, table=data)
    assert len(ax.get_lines()) == 3 + 1  # two compliant curves, the rigid one, the zero line
    np.testing.assert_array_equal(ax.get_lines()[0].get_xdata(), psi)
    plt.close(ax.figure)


@pytest.mark.parametrize(
    "models, ncol", [(("mindlin", "rigid"), 2), (("mindlin", "mindlin_deresiewicz", "di_renzo_di_maio"), 1)]
)
def test_the_legend_fits_the_figure(models, ncol):
    # two columns where they fit the 3.5 in figure; a long label (Mindlin-Deresiewicz's) takes one column, not the
    # page's edge (its two columns ran 0.4 in past the right edge, cutting "Kharaz et al. 2001")
    axes = fo.plot_oblique(models=models, angle=[5.0, 30.0, 60.0])
    fig = axes[0].figure
    try:
        fig.canvas.draw()  # laid out as when saved
        (leg,) = fig.legends
        box = leg.get_window_extent(fig.canvas.get_renderer())
        assert leg._ncols == ncol
        assert box.x0 >= 0.0 and box.x1 <= fig.bbox.width
    finally:
        plt.close(fig)
