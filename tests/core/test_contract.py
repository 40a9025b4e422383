"""The model contract of :mod:`microimpact.core.models`: one parameter spec, two checks generated
from it that agree; defaults for what a model does not declare; one packing function."""

from __future__ import annotations

import math
import types
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microimpact.core import models
from microimpact.core.quantities import OUTCOME_FIELDS
from microimpact.engine import evaluate

WITH_PARAMETERS = [n for n in models.available() if models.get(n).PARAMETERS]
values = st.one_of(
    st.sampled_from([0.0, 1.0, 2.0, -1.0, 0.5, 1e3, math.inf, -math.inf, math.nan]),
    st.floats(allow_nan=True, allow_infinity=True),
)


def test_every_model_file_is_written_to_the_spec():
    """Every model with parameters declares them as :class:`~microimpact.core.models.Parameter` and
    takes its two checks from :func:`~microimpact.core.models.checks` (no 3-tuples with ``DEFAULTS``
    beside them, no hand-written second copy of the bounds)."""
    old = [
        n
        for n in WITH_PARAMETERS
        if "BOUNDS" not in vars(models.get(n).module)
        or "DEFAULTS" in vars(models.get(n).module)
        or not all(isinstance(p, models.Parameter) for p in vars(models.get(n).module)["PARAMETERS"])
    ]
    assert not old, f"model files not written to the spec: {', '.join(old)}"


@pytest.mark.parametrize("name", WITH_PARAMETERS)
@settings(max_examples=300, derandomize=True, deadline=None)
@given(data=st.data())
def test_the_compiled_check_and_validate_agree(name, data):
    """``in_bounds(params, BOUNDS)`` (what ``outcome`` runs) accepts exactly what ``validate`` accepts."""
    mod = models.get(name)
    params = tuple(data.draw(values) for _ in mod.PARAMETERS)
    try:
        mod.validate(params)
        accepted = True
    except ValueError as exc:
        accepted = False
        assert str(exc).split()[0] in {p.name for p in mod.PARAMETERS}  # names the parameter
    assert models.in_bounds(params, mod.BOUNDS) is accepted
    if not accepted:
        assert all(math.isnan(x) for x in mod.outcome(1.0, 1e9, 1e-6, 1e-14, 1e8, params)[1:])


@pytest.mark.parametrize("name", WITH_PARAMETERS)
def test_the_compiled_check_compiled_agrees(name):
    """The same check inside numba's compiled loop: invalid parameters give NaN rows, as in Python."""
    mod = models.get(name)
    good = tuple(
        p.default if not math.isnan(p.default) else 0.5 * (p.low + p.high) if p.high < math.inf else 10.0 * (i + 1)
        for i, p in enumerate(mod.PARAMETERS)
    )
    mod.validate(good)
    bad = (-1.0,) + good[1:]
    V = np.array([0.5, 1.0])
    for params in (good, bad):
        compiled = evaluate(
            mod.outcome,
            V,
            np.array(1e9),
            np.array(1e-6),
            np.array(1e-14),
            np.array(1e8),
            nout=len(OUTCOME_FIELDS),
            params=params,
            backend="numba",
        )
        plain = evaluate(
            mod.outcome,
            V,
            np.array(1e9),
            np.array(1e-6),
            np.array(1e-14),
            np.array(1e8),
            nout=len(OUTCOME_FIELDS),
            params=params,
            backend="python",
        )
        np.testing.assert_array_equal(np.isnan(compiled), np.isnan(plain))
        np.testing.assert_allclose(compiled, plain, rtol=1e-14)


def test_a_bare_model_gets_the_defaults():
    def outcome(V, E, R, m, p_y, params):
        return models.pack(V, 1.0, V, 1.0, 1.0, V, 0.0, 0.0, 0.0, R, 0.0, R, 0.0, 0.0, 1.0, 2.0)

    bare = models.declare(types.SimpleNamespace(NAME="bare", TITLE="a law", outcome=outcome, force=lambda *a: 0.0))
    assert bare.PARAMETERS == () and bare.DEFAULTS == () and bare.STICKS is False
    assert bare.STAGES == models.GENERIC_STAGES and bare.LABEL == "bare"
    assert bare.signed_force is bare.force and bare.ends_at_zero_force is None and bare.separation_approach is None
    assert bare.validate(()) == ()
    with pytest.raises(ValueError, match="model 'bare' takes no parameters"):
        bare.validate((1.0,))
    out = dict(zip(OUTCOME_FIELDS, bare.outcome(3.0, 1.0, 2.0, 1.0, 1.0, ())))
    assert out["energy_loss"] == 0.0 and out["contact_time"] == 3.0 and out["large_strain"] == 0.0
    with pytest.raises(ValueError, match="does not define force"):
        models.declare(types.SimpleNamespace(NAME="x", TITLE="t", outcome=outcome))
    assert bare.WALL_ADHESION is False and bare.WALL_REFUSAL is None
    assert bare.COST == bare.OUTCOME_COST == "cheap"


def test_cost_classes_are_declared():
    """``COST`` and ``OUTCOME_COST`` take a class of :data:`COST_CLASSES`; the outcome's defaults to
    ``e``'s; anything else is refused with the model's name."""

    def make(**kw):
        return models.declare(types.SimpleNamespace(NAME="c", TITLE="t", outcome=None, force=None, **kw))

    assert make(COST="slow").OUTCOME_COST == "slow"
    both = make(OUTCOME_COST="slow")
    assert (both.COST, both.OUTCOME_COST) == ("cheap", "slow")
    with pytest.raises(ValueError, match="model 'c': COST must be one of cheap, slow, got 'fast'"):
        make(COST="fast")
    with pytest.raises(ValueError, match="model 'c': OUTCOME_COST must be one of cheap, slow, got 1"):
        make(OUTCOME_COST=1)
    # a law whose e integrates its equation of motion declares it; a closed form does not
    assert models.get("hertz_viscoelastic").COST == "slow" and models.get(models.DEFAULT).COST == "cheap"
    assert models.COST_CLASSES["slow"] > 10 * models.COST_CLASSES["cheap"]


def test_old_style_parameters_are_still_read():
    """A model file written before the spec (3-tuples, DEFAULTS beside them) keeps working."""
    old = models.declare(
        types.SimpleNamespace(
            NAME="old",
            TITLE="t",
            PARAMETERS=(("k", "N/m", "stiffness"),),
            DEFAULTS=(2.0,),
            outcome=None,
            force=None,
        )
    )
    assert old.PARAMETERS == (models.Parameter("k", "N/m", "stiffness", 2.0),) and old.DEFAULTS == (2.0,)
    assert models.parameters("linear_spring_dashpot")["limit_force"][2] == 0.0


def test_parameter_messages():
    p = models.Parameter("x", "1", "d", low=0.0, high=1.0, high_open=True)
    with pytest.raises(ValueError, match=r"x must lie in \[0, 1\), got 1.0"):
        p.check(1.0, {})
    q = models.Parameter("y", "1", "d", low=2.0)
    with pytest.raises(ValueError, match="y must be finite and >= 2.0, got 1.0"):
        q.check(1.0, {})


def test_seed_stage_models_is_deprecated():
    import microimpact.dynamics as dyn

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        names = dyn.SEED_STAGE_MODELS
    assert "stage_names" in str(caught[0].message) and caught[0].category is DeprecationWarning
    assert models.DEFAULT in names
    assert dyn.stage_names()[2].startswith("plastic loading")
    assert dyn.stage_names("linear_spring_dashpot") == {0: dyn.STAGE_NAMES[0], 1: "loading", 3: "unloading"}


def test_the_whole_law_is_found_by_its_declaration():
    """The whole adhesive law (the default of ``pair.sticking_velocity``, the law of the stick/bounce
    maps) is the one model declaring ``WALL_ADHESION``, and its ``yield_velocity_of`` hook is its
    outcome's ``yield_velocity`` field (the same bits with adhesion)."""
    from microimpact import ContactPair

    declaring = [n for n in models.available() if models.get(n).WALL_ADHESION]
    assert declaring == [models.whole_law()] == ["thornton_ning_1998_adhesive_plastic"]
    law = models.get(models.whole_law())
    E, R, m, p_y = 1.31e9, 2.45e-6, 4.0 / 3.0 * math.pi * 2.45e-6**3 * 1350.0, 156e6
    for G in (0.01, 0.5, 5.0):
        assert law.yield_velocity_of(E, R, m, p_y, (G,)) == law.outcome(3.0, E, R, m, p_y, (G,))[1]
    assert law.yield_velocity_of(E, R, m, p_y, (0.5,)) < law.yield_velocity_of(E, R, m, p_y, (0.01,))
    pair = ContactPair.paper_case("silicon")
    assert pair.sticking_velocity(work_of_adhesion=0.3) == pair.sticking_velocity(
        model=models.whole_law(), work_of_adhesion=0.3
    )
    assert pair.sticking_velocity(work_of_adhesion=0.3) != pair.sticking_velocity(
        model="thornton_ning_1998_elastic_adhesive", work_of_adhesion=0.3
    )
    assert models.get(models.DEFAULT).yield_velocity_of is None  # a hook, None where not declared


def test_no_model_file_writes_the_outcome_tuple():
    """The 18-field outcome is written once, in :func:`~microimpact.core.models.pack` (and the NaN one
    in ``nan_outcome``): no model file, nor a helper shared by model files, builds it itself."""
    import ast
    from pathlib import Path

    folder = Path(models.__file__).parent
    n = len(OUTCOME_FIELDS)
    found = []
    for path in sorted(folder.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.FunctionDef) and path.name == "_common.py" and node.name in ("pack", "nan_outcome"):
                continue
            for t in ast.walk(node) if isinstance(node, ast.FunctionDef) else ():
                if isinstance(t, ast.Tuple) and len(t.elts) == n:
                    found.append(f"{path.name}:{t.lineno} ({node.name})")
    assert not found, "outcome tuples written outside pack: " + ", ".join(sorted(set(found)))


def test_pack_beyond_flags_large_strain_and_is_pack_otherwise():
    from microimpact.core.models._common import pack_beyond

    args = (3.0, 2.0, 1.5, 0.0, 0.8, 2.4, 1e-7, 2e-8, 1e-3, 3e-6)
    tail = (1e-8, 2e-8, 3e-8, 4e-8)
    small = models.pack(*args, 1e-7, 1e-6, *tail)  # a/R = 0.1: within the small-strain range
    assert small[OUTCOME_FIELDS.index("large_strain")] == 0.0
    assert pack_beyond(*args, 1e-7, 1e-6, 0.0, *tail) == small
    flagged = pack_beyond(*args, 1e-7, 1e-6, 1.0, *tail)
    i = OUTCOME_FIELDS.index("large_strain")
    assert flagged[i] == 1.0 and flagged[:i] + flagged[i + 1 :] == small[:i] + small[i + 1 :]
    large = models.pack(*args, 5e-7, 1e-6, *tail)  # a/R = 0.5
    assert pack_beyond(*args, 5e-7, 1e-6, 0.0, *tail) == large == pack_beyond(*args, 5e-7, 1e-6, 1.0, *tail)


#: Model files released with a module-level ``DEFAULTS`` (the contract before the parameter spec).
RELEASED_DEFAULTS = (
    "hertz_tsuji",
    "hertz_viscoelastic",
    "jkr_elastic_adhesive",
    "liggghts_thornton_ning",
    "linear_spring_dashpot",
    "luding_adhesive",
    "luding_hysteretic",
    "thornton_ning_1998_elastic_adhesive",
    "thornton_ning_2016",
)


@pytest.mark.parametrize("name", RELEASED_DEFAULTS)
def test_released_defaults_still_read_with_a_warning(name):
    import importlib

    module = importlib.import_module(f"microimpact.core.models.{name}")
    with pytest.warns(DeprecationWarning, match=rf"{name}\.DEFAULTS is deprecated; use microimpact\.models\.get"):
        defaults = module.DEFAULTS
    assert defaults == models.get(name).DEFAULTS == tuple(p.default for p in models.get(name).PARAMETERS)
    with pytest.raises(AttributeError, match="no attribute 'NO_SUCH_NAME'"):
        module.NO_SUCH_NAME  # noqa: B018
    assert not hasattr(module, "NO_SUCH_NAME")


def test_the_seeds_released_signed_force_warns():
    from microimpact.core.models import thornton_ning_2016 as seed

    with pytest.warns(DeprecationWarning, match=r"thornton_ning_2016\.signed_force is deprecated"):
        fn = seed.signed_force
    assert fn is seed.force is models.get(models.DEFAULT).signed_force
