"""Every public number is unchanged (issue 11): the public API against stored reference outputs.

``tests/reference/reference_outputs.npz`` holds the inputs and outputs of a
grid of calls to the public API (pairs, impacts by the scalar and the array
path, the module functions, force laws, histories, sweeps, fits, wall
interactions, adhesion), written by ``tests/reference/make_reference.py``
before the physics core was redesigned. Each test replays one group of calls
with the stored inputs and compares with ``rtol = 1e-13, atol = 0`` (bools,
ints and strings exactly; NaN equals NaN; shapes must match).

Two exceptions, each explained where it is used:

* Fits go through :func:`scipy.optimize.least_squares`, whose stopping point
  moves with the last bits of the model: looser tolerances.
* Near the yield point the closed forms are ill-conditioned (``1 - e^2``,
  ``alpha* - alpha_p`` and the stage-1 time at ``V -> V_y``): there the
  scalar path (``pair.impact(float)``) and the array path
  (``pair.impact(array)``, ``impact_outcome``, ``contact_times``) of today's
  code already differ by more than 1e-13. An entry of those grids passes if it
  matches either path's stored value.

If a change of the physics is intended, rerun ``make_reference.py`` in the same
commit and say why.

Changes so far: issue 20 replaced the sticking constant 14.18 (Thornton & Ning's
printed rounding) by the derived 14.18439 (twice the JKR separation work, the
value the elastic-adhesive model already used): the stored
``constants/STICKING_CONSTANT``, ``adhesion/sticking_velocity`` and the wall
interaction's adhesive outputs (``wall/*_velocity``, ``*_spin``,
``*_restitution``, ``*_sticking_velocity``; V_s 1.5485e-4 larger) were recomputed
with the stored inputs; nothing else was rewritten.
"""

from __future__ import annotations

import importlib.util
import warnings
from pathlib import Path

import numpy as np
import pytest

REFERENCE_DIR = Path(__file__).resolve().parent / "reference"
RTOL = 1e-13

_spec = importlib.util.spec_from_file_location("_microimpact_make_reference", REFERENCE_DIR / "make_reference.py")
ref = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ref)

INPUTS, OUTPUTS = ref.load_reference()

# Infinite impact speeds were allowed when the file was written (e = 0, V_r = inf); issue 12 made
# them an error (V_r = e V cannot hold), so they are replayed as 1e300 and their entries are not
# compared. tests/cli/test_faults.py and tests/test_impact.py check that inf is refused.
INF_SPEEDS = ~np.isfinite(INPUTS["speeds"])
INPUTS["speeds"] = np.where(INF_SPEEDS, 1e300, INPUTS["speeds"])
_INF_2D = INF_SPEEDS[0].reshape(-1, 4)[:, ::-1]
_INF_KEEP = INF_SPEEDS[:, ~np.any(INPUTS["speeds"] == 5e-324, axis=0)]  # thornton_ning_restitution's columns
_INF_V = ~np.isfinite(INPUTS["v_normalized"])
INPUTS["v_normalized"] = np.where(_INF_V, 1e300, INPUTS["v_normalized"])


def _skip_mask(shape):
    """Entries of a speeds-shaped output that belong to an infinite speed (not compared)."""
    if shape == INF_SPEEDS.shape:
        return INF_SPEEDS
    if shape == _INF_2D.shape:
        return _INF_2D
    if shape == _INF_V.shape:
        return _INF_V
    if shape == _INF_KEEP.shape:
        return _INF_KEEP
    return None


def _close(actual, expected, rtol, atol=0.0):
    """Elementwise: equal (bools, ints, strings) or within ``atol + rtol |expected|`` (floats, NaN == NaN)."""
    if expected.dtype.kind in "biuUS":
        return np.asarray(actual == expected)
    return np.isclose(actual, expected, rtol=rtol, atol=atol, equal_nan=True)


def assert_same(name, actual, expected, rtol=RTOL, atol=0.0, alternative=None):
    """``actual`` equals the stored ``expected`` (or, entry by entry, the stored ``alternative``)."""
    actual = np.asarray(actual)
    assert actual.shape == expected.shape, f"{name}: shape {actual.shape}, stored {expected.shape}"
    kind = "iu" if expected.dtype.kind in "iu" else expected.dtype.kind
    assert actual.dtype.kind in kind, f"{name}: dtype {actual.dtype}, stored {expected.dtype}"
    ok = _close(actual, expected, rtol, atol)
    if alternative is not None:
        ok = ok | _close(actual, alternative, rtol, atol)
    skip = _skip_mask(actual.shape)
    if skip is not None:
        ok = ok | skip
    if np.all(ok):
        return
    bad = ~np.asarray(ok, dtype=bool).reshape(actual.shape)
    where = np.argwhere(bad)[:5].tolist() if actual.ndim else "scalar"
    if expected.dtype.kind in "biuUS":
        np.testing.assert_array_equal(actual[bad], expected[bad], err_msg=f"{name} at {where}")
    if np.ndim(rtol):  # a tolerance per entry: report the worst offenders by hand
        r = np.broadcast_to(rtol, actual.shape)[bad]
        a, e = actual[bad], expected[bad]
        raise AssertionError(
            f"{name} at {where}: actual {a[:5]}, stored {e[:5]}, allowed rtol {r[:5]}, "
            f"relative difference {(np.abs(a - e) / np.abs(e))[:5]}"
        )
    np.testing.assert_allclose(
        actual[bad] if actual.ndim else actual,
        expected[bad] if actual.ndim else expected,
        rtol=rtol,
        atol=atol,
        equal_nan=True,
        err_msg=f"{name} at {where}",
    )
    raise AssertionError(f"{name} differs at {where}")  # pragma: no cover (assert_allclose raised)


def _replay(group):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # LargeStrainWarning is a UserWarning
        new = ref.GROUPS[group](INPUTS)
    stored = OUTPUTS[group]
    assert sorted(new) == sorted(stored), f"{group}: outputs {sorted(set(new) ^ set(stored))} added or missing"
    return new, stored


# ------------------------------------------------------------------ groups compared at 1e-13
@pytest.mark.parametrize(
    "group", ["constants", "pairs", "contact", "materials", "history", "sweep", "wall", "adhesion"]
)
def test_group_unchanged(group):
    new, stored = _replay(group)
    for name in sorted(stored):
        # An unloading force evaluated where alpha - alpha_p is itself a rounding residue (alpha
        # within a few ulp of alpha_p): only its absolute size, tiny against the array's largest
        # force, is meaningful. Moved by the core redesign from ~1e-33 N to ~1e-32 N (P* ~ 1e-6 N).
        atol = 1e-13 * float(np.nanmax(np.abs(stored[name]))) if name in _CANCELLING.get(group, ()) else 0.0
        # The approach velocity V (1 - u)^(1/2) near the maximum approach, where 1 - u is small and
        # the last bits of B(2/5, 1/2) (now correctly rounded; scipy's was one ulp low) are amplified:
        # moved by up to 2e-13 relative at 3 of 2,000 history points.
        rtol = 1e-12 if group == "history" and name.endswith("approach_velocity") else RTOL
        assert_same(f"{group}/{name}", new[name], stored[name], rtol=rtol, atol=atol)


_CANCELLING = {"contact": ("contact_force_unloading",)}


# ------------------------------------------------------------------ impacts: pairs x speeds grids
# Near V = V_y (and at V/V_y ~ 1e10) a value can hang on the last bit of V_y or on a
# cancellation: there today's scalar path (pair.impact(float), math module) and array
# path (numpy) differ by up to ~1e-3 relative in plastic_approach, ~1e-8 in
# elastic_stage_time, and flip `elastic` at V = V_y +- 1 ulp. A redesign that merges the
# two paths onto one core can match only one of them there, so an entry of these grids
# passes if it matches the stored value of either path at 1e-13. Elsewhere (every other
# entry: the paths agree to 1e-13) this is the plain comparison.
_FUNCTION_TWINS = {
    **{f"impact_outcome_{f}": f for f in ref.RESULT_FIELDS},
    **{f"contact_times_{f}": f for f in ref.RESULT_FIELDS},
    "restitution_coefficient": "restitution",
    "energy_loss_fraction": "energy_loss",
    "elastic_stage_time": "elastic_stage_time",
    "plastic_stage_time": "plastic_stage_time",
    "unloading_time": "unloading_time",
}


def _twin(group, name):
    """The stored value of the same quantity on the same grid by today's other path, or None."""
    scalar, array = OUTPUTS["impact_scalar"], OUTPUTS["impact_array"]
    if group == "impact_scalar":
        return array[name]
    if group == "impact_array":
        if name.startswith("2d_"):  # pairs[0] at its speeds, reshaped as the call did
            return scalar[name[3:]][0].reshape(-1, 4)[:, ::-1]
        return scalar.get(name)  # the 0-d call has no twin
    return scalar.get(_FUNCTION_TWINS.get(name, ""))


# Moved on purpose (issue 11, second session), each measured against 50-digit mpmath:
# * The yield point: alpha^(3/2) is now alpha alpha^(1/2) (a square root instead of pow), which
#   moves V_y by up to an ulp. Near V_y the outcome is ill-conditioned in V_y: t2 grows as
#   (V^2 - V_y^2)^(1/2), alpha_p as A - P^/A^(1/2) -> 0, so one ulp of V_y moves them by about
#   eps/(2 (V/V_y - 1)) relative. Each entry is compared at 1e-13 + 2e-15/|V/V_y - 1|, and the
#   `elastic` flag may flip where V is within 1e-15 relative of V_y (the grid has such points).
# * plastic_approach near V_y: alpha_p/alpha_y = A - P^/A^(1/2) cancelled (both terms -> 1, the
#   difference -> 0 as (v - 1)^2); the stored values are off by up to 8e-4 relative at
#   V/V_y = 1 + 1e-6. It is now computed without cancellation (plastic_stage's docstring), within
#   4e-15 of mpmath (tests/core/test_thornton_ning_2016.py). Compared at 1e-13 + 1e-15/(V/V_y - 1)^2.
# * unloading_time (and contact_time = t_L + t_U) at V/V_y > 1e4: t_U was computed from
#   alpha* - alpha_p, which cancels as the impact becomes ever more plastic; the stored values
#   carry up to 1e-9 relative error there. It is now alpha_y P^/A^(1/2) (no cancellation,
#   within 4e-15 of mpmath: tests/core/test_thornton_ning_2016.py). Compared there at 1e-8.
# * energy_loss = 1 - e^2 just above V_y, where e = 1 - a few ulp: the restitution now takes two
#   divisions instead of four and its last bit moved, so 1 - e^2 moves by up to 4.5e-16 absolute
#   (the stored array value was -4.4e-16, now 0). Compared with atol 1e-15.
# * Where alpha_y underflows (pairs with V_y ~ 1e290 m/s, say) the stored t_U cancelled to exactly
#   0 and is now a correct 1e-68 s or so: times are also compared with atol 1e-40 s.
_CANCELLED_TIMES = ("unloading_time", "contact_time")


def _normalized_speed(name, stored):
    """The stored V/V_y on the same grid as ``name``, or None."""
    return _same_grid(name, "normalized_velocity", stored)


def _same_grid(name, field, stored):
    """The stored ``field`` on the same grid as ``name`` (same prefix first), or None."""
    prefix = next((p for p in ("2d_", "0d_") if name.startswith(p)), "")
    for key in (prefix + field, "impact_outcome_" + field, "contact_times_" + field):
        if key in stored and stored[key].shape == stored[name].shape:
            return stored[key]
    return None


@pytest.mark.parametrize("group", ["impact_scalar", "impact_array", "impact_functions"])
def test_impact_grid_unchanged(group):
    new, stored = _replay(group)
    for name in sorted(stored):
        twin = _twin(group, name)
        if twin is not None and twin.shape != stored[name].shape:
            twin = None
        expected, got = stored[name], np.asarray(new[name])
        v = _normalized_speed(name, stored)
        rtol, atol = RTOL, 0.0
        if v is not None and expected.dtype.kind == "f":
            with np.errstate(divide="ignore", invalid="ignore"):
                rtol = RTOL + np.nan_to_num(2e-15 / np.abs(v - 1.0), nan=0.0, posinf=1.0)
            if name.endswith("plastic_approach"):  # the stored value lost (v - 1)^-2 ulps to cancellation
                with np.errstate(divide="ignore", invalid="ignore"):
                    rtol = rtol + np.nan_to_num(1e-15 / (v - 1.0) ** 2, nan=0.0, posinf=1.0)
            if name.endswith(_CANCELLED_TIMES) and "hertz" not in name and "deresiewicz" not in name:
                rtol = np.where(v > 1e4, np.maximum(rtol, 1e-8), rtol)
        if v is not None and expected.dtype.kind == "b":
            at_yield = np.abs(v - 1.0) < 1e-15
            expected = np.where(at_yield, got, expected)  # may flip with the last bit of V_y
            if twin is not None:
                twin = np.where(at_yield, got, twin)
        if name.endswith("_time") or name.endswith("_times"):
            atol = 1e-40
            scale = _same_grid(name, "contact_time", stored)
            if v is not None and scale is not None:  # t2 ~ (V - V_y)^(1/2): ulps of V_y -> 1e-8 of t_c
                atol = np.where(np.abs(v - 1.0) < 1e-12, 1e-7 * scale, atol)
        if name.endswith("plastic_approach"):  # the stored value's absolute error: a few ulps of alpha*
            scale = _same_grid(name, "max_approach", stored)
            if name.startswith("normalized_"):
                scale = np.ones(stored[name].shape)  # alpha*/alpha_y ~ 1 where it cancels
            atol = 0.0 if scale is None else 1e-15 * np.where(np.isfinite(scale), scale, 0.0)
        if "energy_loss" in name:
            atol = 1e-15
        assert_same(f"{group}/{name}", got, expected, rtol=rtol, atol=atol, alternative=twin)


def test_scalar_path_returns_numpy_scalars():
    pair = ref.build_pairs(INPUTS)[0]
    res = pair.impact(5.0)  # elastic, small strain: no warning
    for f in ref.RESULT_FIELDS:
        assert np.ndim(getattr(res, f)) == 0, f


# ------------------------------------------------------------------ fits
# least_squares stops at xtol = ftol = gtol = 1e-12 after a trajectory that depends on
# the last bits of the model: perturbing the data by 1-2 ulp moved the fitted p_y,
# V_y and their confidence intervals by up to 8e-10 relative, the covariances and
# standard errors (3-point Jacobian at the stopping point) by up to 2e-9, the
# prediction and band by 2e-10. Hence 1e-8 for everything the solution feeds.
# Residuals (data minus model, down to 0 at the elastic points) are compared with an
# absolute tolerance of 1e-8 instead. Counts, flags and the quantile (a function of
# the dof only) stay exact; chi2 and rss get 1e-8 too.
FIT_RTOL = 1e-8
FIT_RESIDUAL_ATOL = 1e-8


def test_fit_unchanged():
    new, stored = _replay("fit")
    for name in sorted(stored):
        if name.startswith("soft_l1_"):
            # Moved on purpose (issue 14): the soft_l1 fit's default scale is now set for 95 %
            # Gaussian efficiency and its intervals come from a sandwich covariance with the raw
            # Jacobian; the standard error was 33 % too wide. Its estimate stays within 1e-3.
            if name in ("soft_l1_param", "soft_l1_pair_limiting_pressure", "soft_l1_predict"):
                assert_same(f"fit/{name}", new[name], stored[name], rtol=1e-3)
            continue
        if name.endswith("_quantile"):
            assert_same(f"fit/{name}", new[name], stored[name])
        elif name.endswith("_residuals"):
            assert_same(f"fit/{name}", new[name], stored[name], rtol=0.0, atol=FIT_RESIDUAL_ATOL)
        else:
            assert_same(f"fit/{name}", new[name], stored[name], rtol=FIT_RTOL)


# ------------------------------------------------------------------ the file itself
def test_reference_covers_the_edge_speeds():
    """The grid holds the speeds the issue asks for (so a regenerated file cannot silently drop them)."""
    V = INPUTS["speeds"]
    Vy = OUTPUTS["pairs"]["yield_velocity"]
    finite = np.isfinite(Vy)
    assert finite.sum() >= 25 and (~finite).sum() >= 5
    for x in (0.0, 5e-324, 1e-12, 1e8):
        assert np.all(np.any(V == x, axis=1)), x
    assert np.all(np.any(INF_SPEEDS, axis=1))
    assert np.all(np.any(V[finite] == Vy[finite, None], axis=1))
    assert np.all(np.any(V[finite] == (Vy * (1 + 1e-12))[finite, None], axis=1))
    assert np.all(np.any((V < Vy[:, None]) & (V > Vy[:, None] * (1 - 1e-11)), axis=1)[finite])
    assert OUTPUTS["impact_scalar"]["elastic"].any() and not OUTPUTS["impact_scalar"]["elastic"].all()
    assert OUTPUTS["impact_scalar"]["large_strain"].any()
