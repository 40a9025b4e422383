"""A model is two files: a throw-away model written here, as a user would, in a temporary package
(its physics and its face), works everywhere a model name is taken once its package is registered,
with no file of microimpact edited.

The law is the linear hysteretic spring (Walton & Braun 1986; :mod:`microimpact.core.models.luding_hysteretic`
without adhesion and with a fixed unloading stiffness): loading ``P = k alpha``, unloading
``P = (k/e^2)(alpha - alpha_p)``. Its outcome is harmonic motion in closed form (a quarter period
``pi/2 (m*/k)^(1/2)`` each way, rebound speed ``e V``), which the integration of the force law that
``history(method="ode")`` runs checks independently.
"""

from __future__ import annotations

import math
import textwrap
import uuid

import numpy as np
import pytest

import microimpact as mi
from microimpact import models

NAME = "throwaway_hysteretic_spring"

CORE = '''
"""Linear hysteretic spring, a throw-away model of tests/test_new_model.py."""

import math

from microimpact.core.models import Parameter, checks, dem_outcome, in_bounds, jitable, nan_outcome

NAME = "throwaway_hysteretic_spring"
TITLE = "Linear hysteretic spring (Walton & Braun 1986), a test's throw-away model"
LABEL = "throw-away spring"
PARAMETERS = (
    Parameter.of("restitution", "e in (0, 1]", low=0.0, high=1.0, low_open=True),  # unit: its row's
    Parameter("stiffness", "N/m", "loading stiffness k > 0", default=1000.0, low=0.0, low_open=True),
)
BOUNDS, validate = checks(NAME, PARAMETERS)


@jitable
def outcome(V, E, R, m, p_y, params):
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    e = params[0]
    k = params[1]
    w = math.sqrt(k / m)
    amax = V / w
    tL = 0.5 * math.pi / w
    return dem_outcome(V, e, amax, amax * (1.0 - e * e), k * amax, R, tL, e * tL)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    e = params[0]
    k = params[1]
    if alpha >= alpha_max:
        return k * alpha if alpha > 0.0 else 0.0
    return k / (e * e) * (alpha - alpha_max * (1.0 - e * e))


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    p = signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)
    return p if p > 0.0 else 0.0


@jitable
def ends_at_zero_force(params):
    return True
'''

FACE = '''
"""Face of the throw-away spring: its plot style."""

STYLE = {"color": "#F0E442", "linestyle": (0, (2, 2)), "linewidth": 2.5}
'''


@pytest.fixture
def new_model(tmp_path, monkeypatch):
    """The two files in a fresh package (a unique name: nothing cached from another test), registered."""
    package = f"zoo_{uuid.uuid4().hex[:8]}"
    root = tmp_path / package
    (root / "faces").mkdir(parents=True)
    (root / "__init__.py").write_text("")
    (root / "faces" / "__init__.py").write_text("")
    (root / f"{NAME}.py").write_text(textwrap.dedent(CORE))
    (root / "faces" / f"{NAME}.py").write_text(textwrap.dedent(FACE))
    monkeypatch.syspath_prepend(str(tmp_path))
    models.register_path(package)
    yield package
    models.unregister_path(package)


PAIR = mi.ContactPair.paper_case("silicon")
E_TRUE = 0.6


def test_it_is_a_model(new_model):
    assert NAME in models.available() and models.get(NAME).LABEL == "throw-away spring"
    assert models.parameters(NAME)["stiffness"] == ("N/m", "loading stiffness k > 0", 1000.0)
    with pytest.raises(ValueError, match=r"restitution must lie in \(0, 1\], got 1.5"):
        PAIR.impact(1.0, model=NAME, restitution=1.5)
    models.unregister_path(new_model)
    assert NAME not in models.available()
    models.register_path(new_model)


def test_impact_against_its_own_force_law(new_model):
    """pair.impact (the closed form, through the compiled array path) against history(method="ode")."""
    m = PAIR.effective_mass
    V = np.array([0.5, 2.0, 8.0])
    r = PAIR.impact(V, model=NAME, restitution=E_TRUE)
    tL = 0.5 * math.pi * math.sqrt(m / 1000.0)
    np.testing.assert_allclose(r.restitution, E_TRUE, rtol=1e-15)
    np.testing.assert_allclose(r.contact_time, tL * (1.0 + E_TRUE), rtol=1e-14)
    for v in V:
        h = PAIR.history(float(v), model=NAME, method="ode", restitution=E_TRUE)
        one = PAIR.impact(float(v), model=NAME, restitution=E_TRUE)
        assert h.rebound_velocity == pytest.approx(float(one.rebound_velocity), rel=1e-8)
        assert h.contact_time == pytest.approx(float(one.contact_time), rel=1e-8)
        assert h.max_approach == pytest.approx(float(one.max_approach), rel=1e-8)
        assert set(np.unique(h.stage)) <= set(mi.dynamics.stage_names(NAME))


def test_sweep_and_compare(new_model):
    from microimpact.sweep import sweep

    ds = sweep(
        np.array([1.0, 10.0]), base=PAIR, model=[models.DEFAULT, NAME], model_params={NAME: {"restitution": E_TRUE}}
    )
    np.testing.assert_array_equal(ds.restitution.sel(model=NAME).values, [E_TRUE, E_TRUE])
    seed = PAIR.impact(np.array([1.0, 10.0])).restitution
    np.testing.assert_array_equal(ds.restitution.sel(model=models.DEFAULT).values, seed)

    from microimpact.compare import compare_models

    c = compare_models(PAIR, [1.0, 10.0], models=[models.DEFAULT, NAME], params={NAME: {"restitution": E_TRUE}})
    np.testing.assert_array_equal(c.restitution.sel(model=NAME).values, [E_TRUE, E_TRUE])


def test_its_label_and_style_in_a_figure(new_model):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from microimpact.compare import compare_models
    from microimpact.figures.compare import plot_comparison

    c = compare_models(
        PAIR, np.geomspace(1.0, 100.0, 20), models=[models.DEFAULT, NAME], params={NAME: {"restitution": E_TRUE}}
    )
    ax = plot_comparison(c)
    axes = ax if isinstance(ax, np.ndarray) else np.atleast_1d(ax)
    lines = [ln for a in np.ravel(axes) for ln in a.get_lines() if ln.get_label() == "throw-away spring"]
    assert lines, "the model's LABEL is not a line of the figure"
    assert lines[0].get_color() == "#F0E442" and lines[0].get_linewidth() == 2.5
    plt.close("all")


def test_fit_and_calibration(new_model):
    """fit_restitution gives back e from the model's own data; the default calibration finds the e
    of the seed at the calibration speed (the law's e is constant)."""
    from microimpact.calibrate import calibrate
    from microimpact.fitting import fit_restitution

    V = np.geomspace(1.0, 50.0, 12)
    e = np.asarray(PAIR.impact(V, model=NAME, warn=False, restitution=E_TRUE).restitution)
    fit = fit_restitution(V, e, PAIR, model=NAME, params=("restitution",), model_params={"restitution": 0.9})
    assert fit.params["restitution"] == pytest.approx(E_TRUE, rel=1e-8)

    cal = calibrate(PAIR, NAME, 30.0)
    assert cal.as_dict()["restitution"] == pytest.approx(float(PAIR.impact(30.0, warn=False).restitution), rel=1e-8)
