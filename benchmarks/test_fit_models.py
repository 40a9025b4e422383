"""12. A fit of each model against a fit of the seed, on the same data (``fit --models`` ranking).

Each model is fitted to the example data (``examples/synthetic_silicon.csv``, the seed's silicon
case) with :func:`microimpact.fitting.fit_restitution`, its free parameter as listed below (``p_y``
where the model depends on it), and timed against the seed's fit of ``p_y`` in the same run. Two
variants per model, side by side: as the library runs it (``e`` alone, through the model's
``restitution_only`` hook where it has one, once per distinct group where it declares
``restitution_group``; compiled loops where its declared cost class says its Python loop would cost
the fit more than the array layer's budget), and ``e`` taken from the full outcome at every point (18 fields, contact-time
quadratures included: the cost a fit would have without those hooks). Target: any model's fit at most
5x the seed's.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

KEY = "fit_models"
DATA = Path(__file__).resolve().parent.parent / "examples" / "synthetic_silicon.csv"

#: model: (free parameters, fixed model parameters) -- p_y free wherever the model depends on it.
MODELS = {
    "liggghts_thornton_ning": (("limiting_pressure",), {}),
    "thornton_ning_1998_adhesive_plastic": (("limiting_pressure",), {"work_of_adhesion": 0.001}),
    "jackson_green_brake": (("yield_strength",), {"yield_strength": 50e6}),
    "kogut_etsion_ekk": (("yield_strength",), {"yield_strength": 50e6}),
    "hertz_tsuji": (("damping_ratio",), {"damping_ratio": 0.3}),
    "hertz_viscoelastic": (("dissipative_constant",), {"dissipative_constant": 1e-9}),
    "jkr_elastic_adhesive": (("surface_energy",), {"surface_energy": 0.01}),
    "thornton_ning_1998_elastic_adhesive": (("work_of_adhesion",), {"work_of_adhesion": 0.001}),
    "linear_spring_dashpot": (("restitution",), {"stiffness": 100.0, "restitution": 0.7}),
    "luding_hysteretic": (("unloading_stiffness",), {"loading_stiffness": 100.0, "unloading_stiffness": 200.0}),
    "luding_adhesive": (
        ("unloading_stiffness",),
        {"loading_stiffness": 100.0, "unloading_stiffness": 200.0, "adhesion_stiffness": 10.0, "plasticity_depth": 0.5},
    ),
}
#: The models of a smoke run (``--size tiny``).
TINY = ("liggghts_thornton_ning", "thornton_ning_1998_adhesive_plastic")
SEED = "thornton_ning_2016"
BEFORE = " (e through the full outcome)"


@pytest.fixture(scope="module")
def data():
    import microimpact as mi
    from microimpact.io import load_restitution_csv

    return load_restitution_csv(DATA), mi.ContactPair.paper_case("silicon")


def _fit(data, model, free=("limiting_pressure",), model_params=None):
    from microimpact.fitting import fit_restitution

    d, pair = data

    def run():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # large-strain and fit warnings: the timing is the subject
            return fit_restitution(
                d.velocity, d.restitution, pair, sigma=d.sigma, model=model, params=free, model_params=model_params
            )

    return run


def test_seed(timed, data):
    fit = timed(KEY, SEED, _fit(data, SEED), rounds=7)
    assert 140e6 < fit.params["limiting_pressure"] < 180e6  # the data's p_y (156 MPa) within the noise


_FITTED: dict = {}


@pytest.mark.parametrize("before", [False, True], ids=["e alone", "full outcome"])
@pytest.mark.parametrize("model", list(MODELS))
def test_model(timed, data, model, before, size, monkeypatch):
    if not size["paper"] and model not in TINY:  # size["paper"] is False only in tiny mode
        pytest.skip("smoke run: two models")
    from microimpact import fitting
    from microimpact.impact import outcome_arrays

    free, params = MODELS[model]
    if before:
        monkeypatch.setattr(
            fitting._models,
            "restitution_arrays",
            lambda mod, V, E, R, m, p_y, p: outcome_arrays(mod, V, E, R, m, p_y, p)["restitution"],
        )
        monkeypatch.setattr(fitting._models, "_group_hooks", lambda mod: None)  # e once per point, not per group
    fit = timed(KEY, model + (BEFORE if before else ""), _fit(data, model, free, params), rounds=3)
    other = _FITTED.setdefault(model, {}).setdefault(not before, None)
    _FITTED[model][before] = fit
    if other is not None:  # the same fit either way: e alone is the outcome's field bit for bit
        for name in free:
            assert fit.params[name] == other.params[name], name
