"""The models a fit evaluates: the registry's and the rules of :data:`microimpact.adhesion.FIT_RULES`, one
function for ``e(V)`` (:func:`restitution_of`), the engine chosen by the model's declared cost class, and the map
from the free parameters to a pair and a model's parameters (:class:`FitModel`).
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np

from .. import quantities
from ..adhesion import FIT_RULES
from ..core.models import DEFAULT as _DEFAULT_MODEL
from ..impact import outcome_arrays, restitution_arrays
from ..materials import DEFAULT_K, sphere_mass
from ..pair import ContactPair

# Public as microimpact.fitting.SEED_MODEL, documented there.
SEED_MODEL = _DEFAULT_MODEL

# Public as microimpact.fitting.FREE_PARAMETERS, documented there.
FREE_PARAMETERS: dict[str, dict] = {
    name: {
        "exponent": exponent,
        "si": quantities.QUANTITIES[name].unit,
        "unit": "" if quantities.QUANTITIES[name].shown_unit == "1" else quantities.QUANTITIES[name].shown_unit,
        "scale": quantities.QUANTITIES[name].scale,
        "symbol": quantities.QUANTITIES[name].symbol,
        "tex": quantities.QUANTITIES[name].tex,
    }
    for name, exponent in (
        ("limiting_pressure", 2.5),
        ("k", 2.5),
        ("effective_modulus", -2.0),
        ("density", -0.5),
        ("yield_velocity", 1.0),
    )
}

#: About how many times a fit evaluates its model (start grid, steps, Jacobians, band): see
#: :func:`_compile_if_costly`.
_FIT_CALLS = 50


# --------------------------------------------------------------------------- models
def _zoo():
    from ..core import models  # imported here: keeps `import microimpact` fast

    return models


def _arrays():
    from .. import engine  # imported here: keeps `import microimpact` fast

    return engine


def available_models() -> list[str]:
    """Names accepted as ``model=``: the models of :func:`microimpact.models.available`, the seed first."""
    return list(dict.fromkeys((SEED_MODEL, *_zoo().available())))  # the default first, each name once


_MODULES: dict = {}


def _rules() -> dict:
    """The rules for ``e`` taken beside the models (:data:`microimpact.adhesion.FIT_RULES`), by name."""
    return {rule.NAME: rule for rule in FIT_RULES}


def model_module(name):
    """The :class:`~microimpact.core.models.Model` declaration of ``name`` (ValueError naming it if
    unknown); a rule's of :data:`microimpact.adhesion.FIT_RULES` for its name."""
    rule = _rules().get(name) if isinstance(name, str) else None
    if rule is not None:
        return rule
    if not isinstance(name, str):
        raise ValueError(f"model must be a model's name (one of {', '.join(available_models())}), got {name!r}")
    zoo = _zoo()
    key = (name, zoo.get)  # the registry's function in the key: a replaced registry is looked up anew
    if key not in _MODULES:
        if name not in available_models():
            raise ValueError(f"model must be one of {', '.join(available_models())}; got {name!r}")
        _MODULES[key] = zoo.get(name)
    return _MODULES[key]


def fast_restitution(name):
    """The face's ``e(V, V_y)`` (``restitution_of_yield_velocity``) of a model whose declared group is
    ``V/V_y``, else None (:func:`microimpact.models.face`)."""
    if name in _rules():
        return None
    from ..models import face

    return face(name).restitution_of_yield_velocity


def model_sticks(name) -> bool:
    return model_module(name).STICKS


def _outcome_of(model_name, pair, params, V, fields=("restitution", "rebound_velocity", "contact_time")):
    """Outcome ``fields`` of model ``model_name`` for ``pair`` and model ``params`` at speeds ``V`` [m/s].

    The model's scalar ``outcome(V, E, R, m, p_y, params)`` over the array
    (:func:`microimpact.impact.outcome_arrays`: compiled loops for a ``@jitable`` outcome); the
    restitution alone of a model whose face gives ``e(V, V_y)`` (the seed's eq. 27) from that, else
    by the model's ``restitution_only`` hook where it has one (:func:`microimpact.impact.restitution_arrays`).
    """
    V = np.asarray(V, dtype=float)
    rule = _rules().get(model_name)
    if rule is not None:  # e alone: a rule has no contact times
        e = rule.restitution_of_pair(pair, params, V)
        out = {"restitution": e, "rebound_velocity": e * V, "contact_time": np.full(V.shape, math.nan)}
        return {f: out[f] for f in fields}
    fast = fast_restitution(model_name)
    if fields == ("restitution",) and fast is not None:
        return {"restitution": fast(V, pair.yield_velocity)}
    module = model_module(model_name)
    E, R, m, p_y = (
        np.asarray(float(x))
        for x in (pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure)
    )
    params = tuple(float(x) for x in params)
    if fields == ("restitution",):  # what fitting and ranking compare: e alone (the model's hook)
        return {"restitution": restitution_of_values(module, V.ravel(), E, R, m, p_y, params).reshape(V.shape)}
    _compile_if_costly(module, V.size, outcome=True)
    out = outcome_arrays(module, V.ravel(), E, R, m, p_y, params)
    return {f: np.asarray(out[f], dtype=float).reshape(V.shape) for f in fields}


def restitution_of_values(module, V, E, R, m, p_y, params):
    """``e`` [-] of a registry model at the speeds ``V`` [m/s] (1-D) for the pair's values ``E*`` [Pa],
    ``R*`` [m], ``m*`` [kg], ``p_y`` [Pa] (floats, or arrays like ``V``): once per distinct group where
    the model declares one, else its ``restitution_only`` hook, else its outcome's field; compiled
    where its declared cost says so (:func:`_compile_if_costly`)."""
    if _group_hooks(module) is not None and np.all(V > 0):
        return _restitution_by_group(module, V, E, R, m, p_y, params)
    _compile_if_costly(module, V.size, outcome=module.restitution_only is None)
    return np.asarray(restitution_arrays(module, V, E, R, m, p_y, params))


def _group_hooks(module):
    """``(restitution_group, restitution_of_group)`` of a model that declares its group (the model
    contract, :mod:`microimpact.core.models`), else None."""
    if module.restitution_group is None or module.restitution_of_group is None:
        return None
    return module.restitution_group, module.restitution_of_group


def _restitution_by_group(module, V, E, R, m, p_y, params):
    """``e`` at speeds ``V > 0``, evaluated once per distinct group ``g`` of the model (bit for bit the
    outcome's field: the model computes its outcome's ``e`` from the same ``g``)."""
    group, of_group = _group_hooks(module)
    arrays = _arrays()
    g = arrays.evaluate(group, V.ravel(), E, R, m, p_y, params=params)[0]
    distinct, where = np.unique(g, return_inverse=True)
    _compile_if_costly(module, distinct.size, outcome=False)
    return arrays.evaluate(of_group, distinct, params=params)[0][where.ravel()].reshape(V.shape)


def _compile_if_costly(module, n, outcome):
    """Import numba (from then on the array layer runs compiled loops:
    :func:`microimpact.engine.backend_for`; bit for bit the same numbers) where a fit's
    :data:`_FIT_CALLS` evaluations of ``n`` points in Python loops would exceed the array layer's
    budget for one call (:data:`microimpact.engine.PYTHON_BUDGET`), at the nominal time per
    point of the model's declared cost class (:data:`microimpact.core.models.COST_CLASSES`: its
    ``OUTCOME_COST`` for the whole outcome, else its ``COST``). Deterministic: no timing decides. A
    model that integrates its equation of motion for ``e`` costs ~0.5-2 ms a point in Python,
    ~10-50 us compiled."""
    if "numba" in sys.modules or os.environ.get("MICROIMPACT_BACKEND"):
        return
    cost = _zoo().COST_CLASSES[module.OUTCOME_COST if outcome else module.COST]
    if cost * n * _FIT_CALLS > _arrays().PYTHON_BUDGET:
        import numba  # noqa: F401  (the array layer compiles its loops once numba is imported)


def restitution_of(model_name, pair, params, V):
    """Restitution ``e(V)`` [-] of model ``model_name`` with ``pair`` and model ``params``: the one
    function through which fitting and ranking evaluate every model."""
    return _outcome_of(model_name, pair, params, V, fields=("restitution",))["restitution"]


def parse_params(params, allow_empty=False):
    if isinstance(params, str):
        params = [p.strip() for p in params.split(",") if p.strip()]
    params = tuple(params)
    if not params and not allow_empty:
        raise ValueError("params: give at least one free parameter")
    for p in params:
        if not isinstance(p, str):
            raise ValueError(f"params: names of parameters, got {p!r}")
    if len(set(params)) != len(params):
        raise ValueError(f"params: each parameter once, got {params!r}")
    pair_level = [p for p in params if p in FREE_PARAMETERS]
    if len(pair_level) > 1:
        raise ValueError(
            f"params {', '.join(pair_level)}: restitution data determine only one parameter of the pair. The "
            "model's e depends on V only through V/V_y, and V_y on p_y^(5/2) E*^(-2) m*^(-1/2) (seed eqs. 27-28), "
            "so these parameters are not separately identifiable whatever the speed range; "
            "fix all but one (e.g. params=('limiting_pressure',))"
        )
    return params


def real_number(name, value):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    return float(value)


class _YieldOnly:
    """Stands for a pair where only ``yield_velocity`` [m/s] is read (the seed's e(V), eq. 27)."""

    __slots__ = ("yield_velocity",)

    def __init__(self, yield_velocity):
        self.yield_velocity = yield_velocity


class FitModel:
    """Maps the free parameters ``u`` (logs) to a pair and model parameters, and those to ``e(V)``.

    At most one pair parameter (by ``pair.replace``) and any of the model's own
    ``PARAMETERS``; ``theta_j = ref_j exp(u_j)``.
    """

    def __init__(self, pair: ContactPair, names, *, model=SEED_MODEL, model_params=None, yield_strength=None):
        if not isinstance(pair, ContactPair):
            raise ValueError(f"pair must be a ContactPair, got {type(pair).__name__}")
        module = model_module(model)
        self.model = model
        self.pair = pair
        spec = tuple(module.PARAMETERS)
        self.own = tuple(p[0] for p in spec)
        self.own_units = {p[0]: p[1] for p in spec}
        values = dict(zip(self.own, (float(d) for d in module.DEFAULTS)))
        for k, v in (model_params or {}).items():
            if k not in self.own:
                have = ", ".join(self.own) or "none"
                raise ValueError(f"model_params: model {model} has no parameter {k!r} (its parameters: {have})")
            values[k] = real_number(f"model_params[{k!r}]", v)
        unknown = [n for n in names if n not in FREE_PARAMETERS and n not in self.own]
        if unknown:
            allowed = ", ".join([*FREE_PARAMETERS, *self.own])
            raise ValueError(f"params must be among {allowed} for model {model}, got {unknown[0]!r}")
        pair_names = [n for n in names if n in FREE_PARAMETERS]
        self.own_free = tuple(n for n in names if n in self.own)
        self.names = tuple(pair_names) + self.own_free
        for n in self.own:
            v = values[n]
            if n in self.own_free and not (math.isfinite(v) and v > 0):
                raise ValueError(
                    f"model parameter {n} is fitted in ln and needs a positive start value: "
                    f"give model_params={{{n!r}: ...}}, got {v!r}"
                )
            if not math.isfinite(v):
                raise ValueError(f"model {model} needs a value of its parameter {n}: give model_params={{{n!r}: ...}}")
        self.values = values
        self.name = pair_names[0] if pair_names else None
        self.yield_strength = None
        finite_py = math.isfinite(pair.limiting_pressure)
        self.ref = None
        if self.name is not None:
            self._init_pair_parameter(pair, self.name, yield_strength, finite_py)
        self.refs = np.array(([self.ref] if self.name else []) + [values[n] for n in self.own_free], dtype=float)
        # e from the pair's four values alone (values_at): a registry model without the face's e(V, V_y)
        self._by_values = self.name is not None and model not in _rules() and fast_restitution(model) is None

    def _init_pair_parameter(self, pair, name, yield_strength, finite_py):
        self.exponent = FREE_PARAMETERS[name]["exponent"]
        if not finite_py and name in ("effective_modulus", "density"):
            raise ValueError(f"pair has limiting_pressure = inf (never yields): give it a finite p_y to fit {name}")
        if name == "k":
            Y = yield_strength
            if Y is None:
                known = [m.yield_strength for m in (pair.particle, pair.surface) if m is not None and m.yield_strength]
                Y = min(known) if known else None
            if Y is None:
                raise ValueError(
                    "yield_strength is needed to fit k = p_y / Y: give yield_strength=... or a pair "
                    "built from materials with a yield strength"
                )
            Y = real_number("yield_strength", Y)
            if not (math.isfinite(Y) and Y > 0):
                raise ValueError(f"yield_strength must be positive and finite, got {Y!r}")
            self.yield_strength = Y
            self.ref = pair.limiting_pressure / Y if finite_py else DEFAULT_K
        elif name == "limiting_pressure":
            self.ref = pair.limiting_pressure if finite_py else 1e8
        elif name == "effective_modulus":
            self.ref = pair.effective_modulus
        elif name == "density":
            rho = pair.density
            if rho is None or not math.isclose(
                pair.effective_mass, float(sphere_mass(pair.effective_radius, rho)), rel_tol=1e-9
            ):
                raise ValueError(
                    "density can be fitted only for a sphere on a flat with a known radius and density "
                    "(ContactPair.sphere_on_flat or from_materials)"
                )
            self.ref = rho
        elif name == "yield_velocity":
            # V_y ~ p_y^(5/2) at fixed E*, m*: vary p_y from this base pair.
            self.base = pair if finite_py else pair.replace(limiting_pressure=1e8)
            self.ref = self.base.yield_velocity
        # Every pair parameter enters V_y as a power law; a pair with p_y = inf has no
        # finite V_y, so the reference pair takes a nominal finite p_y there.
        self.ref_pair = self.pair_at(0.0) if not finite_py else pair
        self.ref_vy = self.ref_pair.yield_velocity

    def _inputs_at(self, u):
        """``(pair, inputs)``: the pair to vary and the inputs that set the free pair parameter to
        ``ref * exp(u)`` (one rule for :meth:`pair_at` and :meth:`values_at`)."""
        theta = float(self.ref * math.exp(float(u)))
        if self.name == "k":
            return self.pair, {"limiting_pressure": theta * self.yield_strength}
        if self.name == "yield_velocity":
            return self.base, {"yield_velocity": theta}
        return self.pair, {self.name: theta}

    def pair_at(self, u) -> ContactPair:
        """The pair with the free pair parameter at ``ref * exp(u)`` (via :meth:`ContactPair.vary`)."""
        pair, inputs = self._inputs_at(u)
        return pair.vary(**inputs)

    def values_at(self, u):
        """``(E*, R*, m*, p_y)`` [Pa, m, kg, Pa] of :meth:`pair_at` without building the pair: the same
        :meth:`ContactPair.effective_values <microimpact.pair.ContactPair.effective_values>` call
        that :meth:`ContactPair.vary <microimpact.pair.ContactPair.vary>` makes, so the same floats
        (a fit's evaluations and its start's grid need only these; a pair costs its validation)."""
        pair, inputs = self._inputs_at(u)
        return tuple(float(x) for x in pair.effective_values(**inputs))

    def _own_params(self, u):
        vals = dict(self.values)
        i = 0 if self.name is None else 1
        for j, n in enumerate(self.own_free):
            vals[n] = float(self.refs[i + j] * math.exp(float(u[i + j])))
        return tuple(vals[n] for n in self.own)

    def split(self, u):
        """``(pair, params)`` at ``u``: the pair and the model's parameter tuple."""
        u = np.atleast_1d(np.asarray(u, dtype=float))
        pair = self.pair if self.name is None else self.pair_at(u[0])
        return pair, self._own_params(u)

    def theta(self, u):
        """Free parameters in their own units at ``u``."""
        return self.refs * np.exp(np.asarray(u, dtype=float))

    def restitution(self, u, V):
        """Model ``e(V)`` at ``u`` (via :func:`restitution_of`).

        The seed's ``e(V)`` reads only ``pair.yield_velocity``, which is the power law
        ``V_y,ref exp(c u)`` of the free pair parameter (eq. 28); the optimiser's many
        evaluations get it from :class:`_YieldOnly` instead of building a
        :class:`ContactPair` each time (0.3 ms of validation per pair).
        """
        if self.name is not None and not self.own and fast_restitution(self.model) is not None:
            u0 = float(np.atleast_1d(u)[0])
            return restitution_of(self.model, _YieldOnly(self.ref_vy * math.exp(self.exponent * u0)), (), V)
        if self._by_values:
            u = np.atleast_1d(np.asarray(u, dtype=float))
            V = np.asarray(V, dtype=float)
            values = self.values_at(u[0])
            e = restitution_of_values(model_module(self.model), V.ravel(), *values, self._own_params(u))
            return e.reshape(V.shape)
        pair, params = self.split(u)
        return restitution_of(self.model, pair, params, V)

    def restitution_rows(self, us, V):
        """``e(V)`` [-] at each row ``u`` of ``us`` (a 2-D array: one row per point of the start's
        grid), bit for bit :meth:`restitution` at each: in one array call where only the pair's
        values change from row to row (:meth:`values_at`)."""
        us = np.asarray(us, dtype=float)
        V = np.asarray(V, dtype=float).ravel()
        if not self._by_values or not np.all(us[:, 1:] == us[:1, 1:]):
            return np.array([self.restitution(u, V) for u in us])
        values = np.repeat(np.array([self.values_at(u[0]) for u in us]), V.size, axis=0)
        e = restitution_of_values(model_module(self.model), np.tile(V, len(us)), *values.T, self._own_params(us[0]))
        return e.reshape(len(us), V.size)

    def outcome(self, u, V, fields=("restitution", "rebound_velocity", "contact_time")):
        pair, params = self.split(u)
        return _outcome_of(self.model, pair, params, V, fields)

    def u_of_yield_velocity(self, vy):
        """Inverse of the power law ``V_y = V_y,ref exp(c u)`` (start values)."""
        return np.log(np.asarray(vy) / self.ref_vy) / self.exponent

    def unit(self, name):
        return FREE_PARAMETERS[name]["si"] if name in FREE_PARAMETERS else self.own_units.get(name, "")
