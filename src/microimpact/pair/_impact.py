"""A pair's impacts, by model: the outcome (:meth:`ContactPair.impact
<microimpact.pair.ContactPair.impact>`, one speed through the model's scalar outcome, many through its
array path), the restitution alone (the seed's, the fastest path), the DEM time step that resolves the
contact, and the time history (closed form or integrated, :mod:`microimpact.dynamics`)."""

from __future__ import annotations

import math
import warnings

import numpy as np

from .._validation import check_velocity
from ..core import adhesion as _adhesion
from ..core import models
from ..core.constants import LARGE_STRAIN_RATIO
from ..core.models import thornton_ning_2016 as _seed
from ..engine import evaluate as _evaluate
from ..impact import outcome_arrays, restitution_coefficient
from ..models import OutsideValidityWarning, validity_codes, validity_text
from ._adhesion import range_warning_text, tabor_check
from ._result import FALSE, LARGE, TRUE, AdhesionRangeWarning, LargeStrainWarning, one_result, trusted_result

__all__ = [
    "impact",
    "restitution",
    "dem_time_step",
    "history",
    "ning_loading_time",
    "deresiewicz_contact_time",
    "scalar_or_array",
]


def _ignored(category) -> bool:
    """True when the first of :data:`warnings.filters` ignores every ``category`` warning.

    :func:`warnings.warn` then shows nothing, whatever the text or the caller; this test costs a
    tenth of it (its frame look-up, registry and filter walk, and formatting the text first), the
    warning of ``pair.impact(50.0)`` under ``warnings.simplefilter("ignore")``. Any other first
    filter (an ``"error"``, a message or module pattern) leaves the decision to ``warnings``.
    """
    filters = warnings.filters
    if not filters:
        return False
    action, message, cat, module, lineno = filters[0]
    return action == "ignore" and message is None and module is None and not lineno and issubclass(category, cat)


def scalar_or_array(x):
    """A 0-d result as a numpy scalar, any other as the array."""
    if type(x) is not np.ndarray:
        x = np.asarray(x)
    return x[()] if x.ndim == 0 else x


def impact(values, velocity, model, warn, params):
    """:meth:`ContactPair.impact <microimpact.pair.ContactPair.impact>` of the pair's effective values
    ``(E*, R*, m*, p_y)``. Its warnings name the caller of that method (``stacklevel=3``)."""
    mod = models.get(model)
    p = models.resolve_params(mod, params)
    if type(velocity) is float or type(velocity) is int:
        # One speed: the model's scalar outcome itself (microseconds; no numpy per field).
        V = float(velocity)
        if not 0.0 <= V < math.inf:
            check_velocity("velocity", V)
        out = mod.outcome(V, *values, p)
        res = one_result(out)
        flagged = out[LARGE] == 1.0
        vmin = V
    else:
        V = check_velocity("velocity", velocity)
        # the pair's floats as they are: numpy scalars would make a small array's Python loop
        # compute in numpy's scalar arithmetic, ~3x slower for a model that integrates
        out = outcome_arrays(mod, V, *values, p)
        # arrays of V's shape, or 0-d ones for a 0-d V (then numpy scalars, as for one speed)
        res = trusted_result(out if V.ndim else {k: v[()] for k, v in out.items()})
        flagged = res.any_large_strain
        vmin = None
    if warn and flagged and not _ignored(LargeStrainWarning):
        if vmin is None:
            vmin = np.min(np.asarray(res.velocity)[np.asarray(res.large_strain)])
        warnings.warn(
            f"contact radius exceeds {LARGE_STRAIN_RATIO} R* from V = {vmin:.4g} m/s: "
            "outside the small-strain range of the model (results flagged in .large_strain)",
            LargeStrainWarning,
            stacklevel=3,
        )
    limit = mod.ADHESION_LIMIT
    if limit is not None:
        mu, outside = tabor_check(mod, limit, p, _adhesion.EQUILIBRIUM_SEPARATION, values[0], values[1])
        res.__dict__["tabor_parameter"] = mu
        res.__dict__["outside_adhesion_range"] = TRUE if outside else FALSE
        if warn and outside and not _ignored(AdhesionRangeWarning):
            warnings.warn(range_warning_text(mod.NAME, limit, mu), AdhesionRangeWarning, stacklevel=3)
    if mod.outside_validity is not None:  # flagged where the published law cannot say what happens
        codes = validity_codes(mod, res.velocity, *values, p)
        res.__dict__["outside_validity"] = scalar_or_array(codes != 0.0)
        if warn and codes.any() and not _ignored(OutsideValidityWarning):
            text = validity_text(mod.NAME, res.velocity, codes)
            warnings.warn(text, OutsideValidityWarning, stacklevel=3)
    return res


def restitution(velocity, yield_velocity, out):
    """:meth:`ContactPair.restitution <microimpact.pair.ContactPair.restitution>` at the pair's ``V_y``."""
    if out is not None:
        return restitution_coefficient(velocity, yield_velocity, out=out)
    if type(velocity) is float or type(velocity) is int:  # one speed: the core's scalar function itself
        V = float(velocity)
        if not 0.0 <= V < math.inf:
            check_velocity("velocity", V)
        return np.float64(_seed.restitution_at(V, yield_velocity))
    # the pair's own V_y was checked with the pair: only the speeds are
    V = check_velocity("velocity", velocity)
    return scalar_or_array(_evaluate(_seed.restitution_at, V, yield_velocity)[0])


def dem_time_step(pair, velocity, model, steps_per_contact, params) -> float:
    """:meth:`ContactPair.dem_time_step <microimpact.pair.ContactPair.dem_time_step>`."""
    if isinstance(steps_per_contact, bool) or not isinstance(steps_per_contact, (int, float, np.integer, np.floating)):
        raise ValueError(f"steps_per_contact must be a number >= 1, got {steps_per_contact!r}")
    if not (steps_per_contact >= 1.0 and math.isfinite(steps_per_contact)):
        raise ValueError(f"steps_per_contact must be a finite number >= 1, got {steps_per_contact!r}")
    V = np.atleast_1d(check_velocity("velocity", velocity))
    if not np.all(V > 0.0):
        raise ValueError(f"velocity must be positive (no contact at 0), got {float(V[V <= 0.0][0])!r}")
    tc = np.asarray(pair.impact(V, model=model, warn=False, **params).contact_time, dtype=float)
    if not np.all(np.isfinite(tc) & (tc > 0.0)):
        bad = float(V.ravel()[~(np.isfinite(tc) & (tc > 0.0)).ravel()][0])
        raise ValueError(f"model {model!r} has no finite contact time at velocity {bad!r}: no step resolves it")
    return float(np.min(tc)) / float(steps_per_contact)


def history(values, velocity, n, times, method, model, params):
    """:meth:`ContactPair.history <microimpact.pair.ContactPair.history>` of the pair's effective
    values ``(E*, R*, m*, p_y)``."""
    mod = models.get(model)
    from .. import dynamics  # imported here: one impact (and the CLI) need no history machinery
    from ..models import face

    closed_form = face(mod.NAME).closed_form_history  # the face's declaration (None: integrated only)
    if method is None:
        method = "ode" if closed_form is None else "closed"
    if method not in ("closed", "ode"):
        raise ValueError(f"method must be 'closed' or 'ode', got {method!r}")
    if method == "closed" and closed_form is None:
        raise ValueError(
            f"model {mod.NAME!r} has no closed-form history (method 'closed'); use method='ode', "
            "the integration of its force law"
        )
    if method == "closed":
        data = {
            **closed_form(velocity, values, models.resolve_params(mod, params), n=n, times=times),
            "model": mod.NAME,
        }
    else:
        data = dynamics.integrate_model(mod.NAME, velocity, *values, params, n=n, times=times)
    return dynamics.ImpactHistory.from_dict(data, method=method)


def ning_loading_time(pair) -> float:
    """:meth:`ContactPair.ning_loading_time <microimpact.pair.ContactPair.ning_loading_time>`."""
    from .. import dynamics

    return float(dynamics.ning_loading_time(pair.limiting_pressure, pair.effective_radius, pair.effective_mass))


def deresiewicz_contact_time(pair, velocity):
    """:meth:`ContactPair.deresiewicz_contact_time <microimpact.pair.ContactPair.deresiewicz_contact_time>`."""
    from .. import dynamics

    return scalar_or_array(
        dynamics.deresiewicz_contact_time(velocity, pair.effective_modulus, pair.effective_radius, pair.effective_mass)
    )
