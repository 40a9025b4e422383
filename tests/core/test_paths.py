"""Every execution path of the core on the same cases: the scalar Python core, the array paths
(Python loop, compiled serial loop, compiled multi-threaded loop) and the exported C.

The array paths run the very same scalar functions, so they must agree bitwise. The C export is
the one permitted second copy of the restitution, the yield and sticking velocities and the wall
interaction (core.wall); it does the same operations in the same order, so it agrees bitwise too.
"""

from __future__ import annotations

import ctypes
import math
import shutil
import subprocess

import numpy as np
import pytest

import microimpact as mi
from microimpact import engine
from microimpact.cexport import generate_c_source
from microimpact.core.models import thornton_ning_2016 as seed
from microimpact.core.quantities import OUTCOME_FIELDS

PAIR = mi.ContactPair.paper_case("silicon")
ARGS = (PAIR.effective_modulus, PAIR.effective_radius, PAIR.effective_mass, PAIR.limiting_pressure)
VY = PAIR.yield_velocity


def _edge_speeds(Vy):
    """Elastic, at V_y, one ulp either side, just above, far above, huge, V = 0."""
    return np.array(
        [
            0.0,
            5e-324,
            1e-300,
            1e-6,
            0.5 * Vy,
            np.nextafter(Vy, 0.0),
            Vy,
            np.nextafter(Vy, np.inf),
            Vy * (1 + 1e-12),
            Vy * (1 + 1e-6),
            1.5 * Vy,
            50.0,
            1e3,
            1e6,
            1e12,
            1e200,
            1.7e308,
        ]
    )


def _random_cases(n=3000, seed_=7):
    rng = np.random.default_rng(seed_)
    E = 10 ** rng.uniform(8, 11.7, n)
    R = 10 ** rng.uniform(-8, -3, n)
    m = 4 / 3 * np.pi * R**3 * 10 ** rng.uniform(2.7, 4.3, n)
    p = 10 ** rng.uniform(6, 10, n)
    p[::11] = np.inf  # p_y = inf: every impact elastic
    Vy = np.array([seed.yield_point(*x)[2] for x in zip(E, R, m, p)])
    V = np.where(rng.uniform(size=n) < 0.5, Vy * 10 ** rng.uniform(-3, 3, n), 10 ** rng.uniform(-3, 5, n))
    V[np.isinf(V)] = 10.0
    return V, E, R, m, p


def _all_paths(fn, *arrays_, nout, params=None):
    """``fn`` over the inputs by each path: scalar calls, Python loop, compiled serial and parallel."""
    n = arrays_[0].size
    scalar = np.array([fn(*(float(a[i]) for a in arrays_), *(() if params is None else (params,))) for i in range(n)])
    scalar = scalar.reshape(n, nout).T if nout > 1 else scalar.reshape(1, n)
    py = engine.evaluate(fn, *arrays_, nout=nout, params=params, backend="python")
    serial = engine.evaluate(fn, *arrays_, nout=nout, params=params, backend="numba")  # n < PARALLEL_MIN
    old = engine.PARALLEL_MIN
    try:
        engine.PARALLEL_MIN = 1
        parallel = engine.evaluate(fn, *arrays_, nout=nout, params=params, backend="numba")
    finally:
        engine.PARALLEL_MIN = old
    return {"scalar": scalar, "python loop": py, "compiled serial": serial, "compiled parallel": parallel}


@pytest.mark.parametrize("cases", ["edge", "random"])
def test_outcome_bitwise_equal_on_every_path(cases):
    if cases == "edge":
        V = _edge_speeds(VY)
        E, R, m, p = (np.full(V.size, x) for x in ARGS)
    else:
        V, E, R, m, p = _random_cases()
    paths = _all_paths(seed.outcome, V, E, R, m, p, nout=len(OUTCOME_FIELDS), params=())
    ref = paths.pop("scalar")
    assert np.all(np.isfinite(ref[OUTCOME_FIELDS.index("restitution")]))
    for name, got in paths.items():
        for k, field in enumerate(OUTCOME_FIELDS):
            same = (got[k] == ref[k]) | (np.isnan(got[k]) & np.isnan(ref[k]))
            assert same.all(), f"{name}: {field} differs at V = {V[~same][:3]}"


def test_pair_impact_scalar_bitwise_equal_to_array_path():
    """``pair.impact(50.0)`` (the scalar core) equals ``pair.impact([50.0])`` (compiled or loop) bit for bit."""
    one = PAIR.impact(50.0, warn=False)
    many = PAIR.impact(np.array([50.0, 50.0]), warn=False)
    for field in OUTCOME_FIELDS:
        assert np.asarray(getattr(many, field))[0] == getattr(one, field), field


# ------------------------------------------------------------------------------ the C export
def _compile_c(tmp_path):
    cc = next((shutil.which(c) for c in ("cc", "gcc", "clang") if shutil.which(c)), None)
    if cc is None:
        pytest.skip("no C compiler on this machine")
    src = tmp_path / "mi.c"
    src.write_text(generate_c_source(PAIR))
    lib = tmp_path / "libmi.so"
    subprocess.run([cc, "-std=c99", "-O2", "-shared", "-fPIC", "-o", str(lib), str(src), "-lm"], check=True)
    so = ctypes.CDLL(str(lib))
    for name, nargs in (("microimpact_restitution", 2), ("microimpact_yield_velocity", 4)):
        getattr(so, name).restype = ctypes.c_double
        getattr(so, name).argtypes = [ctypes.c_double] * nargs
    return so


def test_c_export_matches_the_core_on_edge_and_random_cases(tmp_path):
    so = _compile_c(tmp_path)
    V, E, R, m, p = _random_cases(1000)
    Vy = np.array([seed.yield_point(*x)[2] for x in zip(E, R, m, p)])
    c_vy = np.array([so.microimpact_yield_velocity(pi, Ei, Ri, mi_) for pi, Ei, Ri, mi_ in zip(p, E, R, m)])
    np.testing.assert_array_equal(c_vy, Vy)  # same operations in the same order: same bits
    speeds = np.concatenate([_edge_speeds(VY) / VY * v for v in (VY,)] + [V])
    vys = np.concatenate([np.full(_edge_speeds(VY).size, VY), Vy])
    core = engine.evaluate(seed.restitution_at, speeds, vys)[0]
    c_e = np.array([so.microimpact_restitution(a, b) for a, b in zip(speeds, vys)])
    np.testing.assert_array_equal(c_e, core)  # the same operations in the same order
    assert c_e[0] == 1.0 and core[-1] <= 1.0


def test_every_path_refuses_nothing_silently_for_infinite_p_y():
    """``p_y = inf``: V_y = inf, every impact elastic, on every path."""
    V = np.array([0.0, 1.0, 1e6])
    paths = _all_paths(seed.outcome, V, *(np.full(3, x) for x in (*ARGS[:3], math.inf)), nout=18, params=())
    for got in paths.values():
        assert np.all(got[OUTCOME_FIELDS.index("elastic")] == 1.0)
        assert np.all(got[OUTCOME_FIELDS.index("restitution")] == 1.0)


class _Params(ctypes.Structure):
    _fields_ = [(k, ctypes.c_double) for k in ("E", "p_y", "G", "mu")]


@pytest.mark.parametrize("G, mu", [(0.0, 0.0), (0.0, 0.3), (0.05, 0.3), (2.0, 1.0)])
def test_c_wall_function_matches_the_core_bitwise(tmp_path, G, mu):
    """microimpact_wall_interaction (C) against core.wall.wall_impact (Python) on random particles:
    bouncing, rolling and sliding, sticking (G > 0), moving away, with spin; every output bit for bit."""
    from microimpact.core import wall

    so = _compile_c(tmp_path)
    fn = so.microimpact_wall_interaction
    vec = ctypes.c_double * 3
    fn.restype = ctypes.c_int
    E, p_y = PAIR.effective_modulus, PAIR.limiting_pressure
    params = _Params(E, p_y, G, mu)
    rng = np.random.default_rng(21)
    seen = set()
    for _ in range(400):
        v = rng.normal(0.0, 5.0, 3)
        v[2] = -rng.uniform(-5.0, 60.0)  # mostly towards the wall (normal ~ +z), some away
        n = np.array([0.0, 0.0, 1.0]) + rng.normal(0.0, 0.2, 3)
        w = rng.normal(0.0, 1e5, 3)
        d, rho = rng.uniform(0.5e-6, 20e-6), rng.uniform(500.0, 3000.0)
        vo, wo, e = vec(), vec(), ctypes.c_double()
        code = fn(
            vec(*v),
            vec(*n),
            vec(*w),
            ctypes.c_double(d),
            ctypes.c_double(rho),
            ctypes.byref(params),
            vo,
            wo,
            ctypes.byref(e),
        )
        ref = dict(zip(wall.WALL_FIELDS, wall.wall_impact(*v, *n, *w, d, rho, E, p_y, G, mu, math.nan, math.nan)))
        assert list(vo) == [ref["vx"], ref["vy"], ref["vz"]]
        assert list(wo) == [ref["wx"], ref["wy"], ref["wz"]]
        assert e.value == ref["restitution"]
        want = {wall.NONE: -1, wall.STUCK: 1}.get(ref["regime"], 0)
        assert code == want
        seen.add(ref["regime"])
    assert wall.NONE in seen  # moving away met
    if mu < 1.0:
        assert wall.SLIDING in seen
    if mu > 0.0:
        assert wall.ROLLING in seen
    if G > 1.0:
        assert wall.STUCK in seen


def test_c_wall_skips_the_root_of_e_squared_only_where_it_is_e():
    """Without adhesion the C wall function returns e_p for the core's sqrt(max(e_p^2 - 0, 0)): the same
    bits because sqrt(RN(x^2)) = x unless x^2 is subnormal, and the seed's e_p is 0 or far above that
    at every speed ratio up to the largest double (e_p ~ v^(-1/4) >= 1e-78)."""
    v = np.concatenate([np.geomspace(1.0, 1.7e308, 200_000), [np.nextafter(1.0, 2.0), 1.7976931348623157e308]])
    e = np.array([seed.restitution_at(x, 1.0) for x in v.tolist()])
    assert e[e > 0.0].min() > 1e-78  # 0 only where v q overflows
    assert np.array_equal(np.sqrt(np.maximum(e * e, 0.0)), e)


def test_small_arrays_stay_in_python_only_while_that_is_cheap():
    """In a new process a small array of the seed's outcome runs in Python (numba not even imported);
    the same size of a model that integrates its equation of motion (~1 ms per element) is compiled,
    and gives the numbers of the Python loop bit for bit."""
    import subprocess
    import sys

    code = """
import sys, numpy as np, microimpact as mi
pair = mi.ContactPair.paper_case("silicon")
V = np.linspace(1.0, 100.0, 1000)
from microimpact import engine
pair.impact(V, warn=False)
print("numba" in sys.modules or bool(engine._LOOPS))
a = pair.impact(V[:400], model="hertz_viscoelastic", dissipative_constant=1e-9, warn=False).restitution
print(bool(engine._LOOPS))  # compiled (or loaded from numba's cache)
from microimpact.core.models import hertz_viscoelastic as hv
E, R, m, p = (np.float64(x) for x in pair._args)
b = engine.evaluate(hv.outcome, V[:400], E, R, m, p, nout=18, params=(1e-9, 1.0), backend="python")[4]
print(bool(np.array_equal(a, b)))
"""
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout.split()
    assert out == ["False", "True", "True"]


def test_many_small_calls_go_compiled_once_python_has_cost_enough():
    """Small calls stay in Python only until the Python loops over the function have together cost
    PYTHON_BUDGET in this process: then the compiled loop runs, with the numbers of the Python loop
    bit for bit. The budget is set to about six calls' estimated cost (the one element timed on the
    first call, times 500), so the count does not depend on how fast the machine is (a fixed 0.02 s
    was spent in two calls under coverage on a slow host)."""
    import subprocess
    import sys

    code = """
import sys, numpy as np
from microimpact import engine
from microimpact.core.models import thornton_ning_2016 as seed
engine.PYTHON_BUDGET = float("inf")  # the first call stays in Python, and times one element
V = np.linspace(1.0, 100.0, 500)
first = engine.evaluate(seed.restitution_at, V, 0.37)
engine.PYTHON_BUDGET = 5.5 * engine._PY_COST[seed.restitution_at] * V.size
print("numba" in sys.modules or bool(engine._LOOPS))
calls = 1
while not engine._LOOPS and calls < 10000:
    assert engine.evaluate(seed.restitution_at, V, 0.37).tobytes() == first.tobytes()
    calls += 1
print(bool(engine._LOOPS), calls == 6)
print(engine.evaluate(seed.restitution_at, V, 0.37).tobytes() == first.tobytes())
"""
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout.split()
    assert out == ["False", "True", "True", "True"]


# ------------------------------------------------------------------- integer powers are products
def test_no_integer_power_or_pow_square_root_in_a_jitable_function():
    """``x**5`` is libm's ``pow(x, 5.0)`` in Python but ``(x^2)^2 x`` compiled (numba expands integer
    powers by squaring): the two differ in the last bit for about half the ``x``, and an integration
    carries that on (1e-8 in a universal table of core.tangential). Every integer power in the core's
    scalar functions is written as products, and every square root as ``math.sqrt`` (a compiler makes
    ``x ** 0.5`` a correctly rounded square root, libm's pow is not always one); this scan keeps it so."""
    import ast
    import importlib
    import inspect
    import pkgutil
    import textwrap

    import microimpact.core
    from microimpact.core import _jit

    for info in pkgutil.walk_packages(microimpact.core.__path__, "microimpact.core."):
        importlib.import_module(info.name)  # every module of the core: every jitable function registered
    found = []
    for fn in list(_jit.JITABLE):
        tree = ast.parse(textwrap.dedent(inspect.getsource(fn)))
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.BinOp)
                and isinstance(node.op, ast.Pow)
                and isinstance(node.right, ast.Constant)
                and (type(node.right.value) is int or node.right.value in (0.5, 2.0, 3.0, 4.0, 5.0))
            ):
                found.append(f"{fn.__module__}.{fn.__qualname__}: {ast.unparse(node)}")
    assert len(_jit.JITABLE) > 100
    assert not found, found


def _random_pair_arrays(n, rng):
    E = 10 ** rng.uniform(8, 11.7, n)
    R = 10 ** rng.uniform(-8, -3, n)
    m = 4 / 3 * np.pi * R**3 * 10 ** rng.uniform(2.7, 4.3, n)
    return E, R, m


def _powers_cases():
    """Functions whose integer powers became products, with random arguments in their domains."""
    from microimpact.core import tangential as tg
    from microimpact.core.models import _jkr, hertz_tsuji, luding_hysteretic
    from microimpact.core.models import dmt_elastic_adhesive as dmt
    from microimpact.core.models import thornton_ning_1998_elastic_adhesive as tn98

    rng = np.random.default_rng(11)
    n = 400
    E, R, m = _random_pair_arrays(n, rng)
    u = rng.uniform(0.0, 1.0, n)
    G = 10 ** rng.uniform(-3, 0.5, n)
    s = 10 ** rng.uniform(-7, -4, n)
    K = 10 ** rng.uniform(-16, -8, n)
    k = 10 ** rng.uniform(2, 6, n)
    Fc = np.where(u < 0.2, 0.0, 10 ** rng.uniform(-9, -5, n))
    return {
        "core.tangential.integrate_tangential": (
            tg.integrate_tangential,
            (rng.uniform(-4, 4, 48), rng.uniform(0.6, 1.2, 48), 10 ** rng.uniform(-2, 0.5, 48), np.full(48, 40.0)),
            2,
        ),
        "seed.yield_velocity_sphere_on_flat": (
            seed.yield_velocity_sphere_on_flat,
            (10 ** rng.uniform(6, 10, n), E, m / R**3),
            1,
        ),
        "thornton_ning_1998.sticking_work": (tn98.sticking_work, (E, R, G), 1),
        "dmt.max_approach_root": (dmt.max_approach_root, (K, k, Fc), 1),
        "hertz_tsuji.alpha_tsuji": (hertz_tsuji.alpha_tsuji, (u,), 1),
        "_jkr.b_of_alpha": (_jkr.b_of_alpha, (rng.uniform(-1e-9, 1e-6, n), E, R, s), 1),
        "luding.loading_stiffness_for": (
            luding_hysteretic.loading_stiffness_for,
            (u, 10 ** rng.uniform(-9, -5, n), m),
            1,
        ),
        "luding.characteristic_velocity": (luding_hysteretic.characteristic_velocity, (k, E, R, m), 1),
    }


@pytest.mark.parametrize("name", sorted(_powers_cases()))
def test_functions_with_powers_bitwise_equal_on_every_path(name):
    fn, args, nout = _powers_cases()[name]
    paths = _all_paths(fn, *args, nout=nout)
    ref = paths.pop("scalar")
    assert np.isfinite(ref).mean() > 0.9, name
    for path, got in paths.items():
        same = (got == ref) | (np.isnan(got) & np.isnan(ref))
        assert same.all(), f"{name}, {path}: differs at {np.argwhere(~same)[:3].ravel()}"
