"""microimpact.figures.capture_size: the outcome map of oblique adhesive impacts over diameter and angle.

The claim of the figure: a particle is captured exactly where the normal law captures the normal
component of its speed, ``V cos(theta) <= V_s(d)``, so at 0 degrees the outcome steps at the diameter
where the whole law's capture velocity equals the speed. Checked against the capture velocity of the
pair (``pair.sticking_velocity``, a root found here), and the outcome against the public oblique path
(``oblique_impact(work_of_adhesion=...)``, at its own default step count).
"""

import math
import warnings

import numpy as np
import pytest
from scipy.optimize import brentq

import microimpact as mi
from microimpact import oblique as ob
from microimpact.figures import capture_size as fc
from microimpact.oblique import adhesive as ad

plt = pytest.importorskip("matplotlib.pyplot")

V, G, MU = 1.0, 0.1, 0.3
ANGLES = np.array([0.0, 30.0, 60.0, 80.0])


@pytest.fixture(scope="module")
def pair():
    return mi.ContactPair.from_materials("nh4fl", "silicon", radius=2.45e-6, limiting_pressure=156e6)


@pytest.fixture(scope="module")
def d_c(pair):
    """The head-on capture diameter from the pair's own capture velocity, found here."""
    return math.exp(brentq(lambda x: pair.sticking_velocity(math.exp(x), work_of_adhesion=G) - V, math.log(0.1e-6),
                           math.log(100e-6), xtol=1e-12))  # fmt: skip


@pytest.fixture(scope="module")
def data(pair, d_c):
    d = np.sort(np.concatenate([np.geomspace(0.3e-6, 30e-6, 7), d_c * np.array([0.98, 1.02])]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fc.capture_size_data(pair, V, G, MU, diameter=d, angle=ANGLES)


def test_head_on_the_outcome_steps_at_the_capture_diameter(data, d_c):
    assert data["capture_diameter"] == pytest.approx(d_c, rel=1e-8)
    head_on = np.array(ad.OUTCOMES)[data["outcome"][0]]
    small = data["diameter"] < d_c
    assert set(head_on[small]) == {"stick"} and set(head_on[~small]) == {"bounce"}
    # the steps straddle d_c within 2 %
    assert head_on[data["diameter"] == d_c * 0.98] == "stick" and head_on[data["diameter"] == d_c * 1.02] == "bounce"


def test_captured_exactly_where_the_normal_speed_is_below_V_s(pair, data):
    vs = np.asarray(pair.sticking_velocity(data["diameter"], work_of_adhesion=G))
    np.testing.assert_allclose(data["capture_velocity"], vs, rtol=1e-10)
    captured = data["outcome"] != ad.OUTCOMES.index("bounce")
    expected = V * np.cos(np.radians(data["angle"]))[:, None] <= vs[None, :]
    np.testing.assert_array_equal(captured, expected)
    # an oblique captured particle keeps moving along the wall: never "stick" away from 0 deg
    assert not np.any(data["outcome"][1:] == ad.OUTCOMES.index("stick"))
    # the boundary curve: arccos(V_s/V), from 0 deg at d_c
    fine = data["boundary_diameter"]
    vs_fine = np.asarray(pair.sticking_velocity(fine[1:], work_of_adhesion=G))
    np.testing.assert_allclose(np.cos(np.radians(data["boundary_angle"][1:])), vs_fine / V, rtol=1e-9)
    assert data["boundary_angle"][0] == 0.0 and fine[0] == pytest.approx(data["capture_diameter"])


def test_outcome_is_the_public_oblique_path(pair, data):
    for j in (0, 4, 8):
        d = data["diameter"][j]
        out = ob.oblique_impact(pair.resized(radius=d / 2), V, ANGLES, MU, work_of_adhesion=G)
        assert [ad.OUTCOMES[k] for k in data["outcome"][:, j]] == list(out.outcome), d


def test_plot_marks_the_boundary_and_the_capture_diameter(data):
    ax = fc.plot_capture_size(data=data)
    try:
        assert ax.get_xscale() == "log"
        boundary = [ln for ln in ax.get_lines() if ln.get_label().startswith("capture boundary")]
        (line,) = boundary
        np.testing.assert_allclose(line.get_xdata(), data["boundary_diameter"] * 1e6)
        (mark,) = [ln for ln in ax.get_lines() if ln.get_label().startswith("head-on")]
        assert mark.get_xdata()[0] == pytest.approx(data["capture_diameter"] * 1e6) and mark.get_ydata()[0] == 0.0
        assert "Particle diameter" in ax.get_xlabel() and "angle" in ax.get_ylabel()
        labels = [t.get_text() for t in ax.figure.legends[0].get_texts()]
        assert "bounce" in labels and "captured rolling" in labels
    finally:
        plt.close(ax.figure)
