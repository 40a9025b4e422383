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


@pytest.mark.parametrize("group", ["impact_scalar", "impact_array", "impact_functions"])
def test_impact_grid_unchanged(group):
    new, stored = _replay(group)
    for name in sorted(stored):
        twin = _twin(group, name)
        if twin is not None and twin.shape != stored[name].shape:
            twin = None
        assert_same(f"{group}/{name}", new[name], stored[name], alternative=twin)


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
