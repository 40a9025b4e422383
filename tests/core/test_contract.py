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


# ----------------------------------------------------------------------------- what is special is declared
GROUPED = [n for n in models.available() if models.get(n).restitution_group is not None]


def test_the_group_hooks_come_in_pairs_and_include_the_seed():
    """``restitution_group`` and ``restitution_of_group`` are one declaration (``e`` of one
    dimensionless group): a model declares both or neither; the seed declares its ``V/V_y``."""
    for name in models.available():
        mod = models.get(name)
        assert (mod.restitution_group is None) == (mod.restitution_of_group is None), name
    assert models.DEFAULT in GROUPED and "hertz_tsuji" in GROUPED


@pytest.mark.parametrize("name", GROUPED)
def test_e_of_the_group_is_the_outcomes_field_bit_for_bit(name):
    """``e`` at the group a model computes at each speed is its outcome's ``e``, the same bits (the
    seed's from below to far above ``V_y``, adhesive-free pairs with a finite and an infinite ``p_y``)."""
    mod = models.get(name)
    params = tuple(0.3 if math.isnan(d) else d for d in mod.DEFAULTS)
    if name == "hertz_viscoelastic":
        params = (3e-7, *params[1:])
    E, R, m = 1.31e9, 2.45e-6, 4.0 / 3.0 * math.pi * 2.45e-6**3 * 1350.0
    for p_y in (156e6, 1e8, math.inf):
        for V in (1e-3, 0.37, 1.0, 7.52, 30.0, 50.0, 120.0, 1e3):
            e = mod.outcome(V, E, R, m, p_y, params)[OUTCOME_FIELDS.index("restitution")]
            g = mod.restitution_group(V, E, R, m, p_y, params)
            assert mod.restitution_of_group(g, params) == e or (math.isnan(e) and math.isnan(g)), (name, V, p_y)


def test_the_seeds_yield_velocity_form_is_its_group():
    """The seed's face gives ``e`` of ``V`` and ``V_y`` alone (fitting's grid search over ``V_y``):
    the same bits as ``e`` of its declared group ``V/V_y``."""
    from microimpact.models import face

    seed = models.get(models.DEFAULT)
    V = np.concatenate([np.geomspace(1e-3, 1e3, 41), [7.52, 7.52 * (1 + 2**-52)]])
    E, R, m, p_y = 1.31e9, 2.45e-6, 4.0 / 3.0 * math.pi * 2.45e-6**3 * 1350.0, 156e6
    Vy = seed.module.yield_point(E, R, m, p_y)[2]
    by_group = np.array([seed.restitution_of_group(seed.restitution_group(v, E, R, m, p_y, ()), ()) for v in V])
    assert face(models.DEFAULT).restitution_of_yield_velocity(V, Vy).tobytes() == by_group.tobytes()


def test_what_is_special_about_a_model_is_declared():
    """The seed is found by its declarations, like any model: the closed-form history is the face's
    hook (``dynamics.CLOSED_FORM_HISTORY``, a released name, lists the models declaring it), the C
    export's law declares ``C_EXPORT`` (one model), and every model cites its source."""
    import microimpact.dynamics as dyn
    from microimpact.models import closed_form_histories, face

    assert dyn.CLOSED_FORM_HISTORY == closed_form_histories() == (models.DEFAULT,)
    assert all(face(n).closed_form_history is None for n in models.available()[1:])
    assert [n for n in models.available() if models.get(n).C_EXPORT] == [models.DEFAULT]
    for name in models.available():
        citation = models.get(name).CITATION
        assert isinstance(citation, str) and citation.strip(), name
    assert "50(4):321-330 (2016)" in models.get(models.DEFAULT).CITATION


def test_a_model_declaring_a_closed_form_history_is_taken_by_its_declaration(tmp_path, monkeypatch):
    """A model added with ``register_path`` whose face declares ``closed_form_history`` has its history
    taken from it (method ``"closed"`` by default, listed in ``CLOSED_FORM_HISTORY``): no room knows
    the seed's name. Its face here borrows the seed's closed form, so the numbers are the seed's."""
    import sys

    import microimpact.dynamics as dyn
    from microimpact import ContactPair

    pkg = tmp_path / "closedpkg"
    (pkg / "faces").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "faces" / "__init__.py").write_text("")
    (pkg / "closed_law.py").write_text(
        "from microimpact.core.models import get\n"
        "_seed = get()\n"
        "NAME = 'closed_law'\n"
        "TITLE = 'The seed under another name'\n"
        "outcome, force, STAGES = _seed.outcome, _seed.force, _seed.STAGES\n"
    )
    (pkg / "faces" / "closed_law.py").write_text(
        "from microimpact.models import face\n\n"
        "def closed_form_history(velocity, pair_values, params, n=1001, times=None):\n"
        "    return face().closed_form_history(velocity, pair_values, params, n=n, times=times)\n"
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    models.register_path("closedpkg")
    try:
        assert dyn.CLOSED_FORM_HISTORY == (models.DEFAULT, "closed_law")
        pair = ContactPair.paper_case("silicon")
        h = pair.history(50.0, n=11, model="closed_law")
        seed = pair.history(50.0, n=11)
        assert h.method == "closed" and h.model == "closed_law" and seed.model == models.DEFAULT
        assert h.force.tobytes() == seed.force.tobytes() and h.contact_time == seed.contact_time
    finally:
        models.unregister_path("closedpkg")
        for key in [k for k in sys.modules if k.startswith("closedpkg")]:
            del sys.modules[key]
    assert dyn.CLOSED_FORM_HISTORY == (models.DEFAULT,)
