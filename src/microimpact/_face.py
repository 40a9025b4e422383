"""The array face of the core, generated: one line per wrapper instead of one hand-written function.

:func:`array_function` turns a scalar ``@jitable`` core function into the public array function
of :mod:`microimpact.contact` (and the like): the inputs checked (each ``ValueError`` names the
parameter and its value), broadcast and handed to :func:`microimpact.engine.evaluate`, and a
numpydoc docstring whose parameters and return value come from
:data:`microimpact.core.quantities.QUANTITIES` (description and SI unit), so that a wrapper
repeats neither the formula nor the units. The function is generated as source with the real
parameter names (keywords work, :func:`inspect.signature` and the API pages show them), in the
namespace of the module that asks for it (its doctests run as that module's).

A history on a time grid, the seed's closed form (its face's ``impact_history``) as every integrated
one (:func:`microimpact.dynamics.integrate_model`), shares the rest: the checked inputs of one impact
(:func:`scalar_pair`), the times (:func:`time_grid`), the stage codes (:func:`stage_of`) and the
free flight before and after the contact (:func:`free_flight`).
"""

from __future__ import annotations

import textwrap

import numpy as np

from ._validation import check_nonnegative, check_pair, check_positive, check_velocity, describe_value
from .core.quantities import DIMENSIONLESS_SHOWN, OUTCOME_FIELDS, QUANTITIES, unit_text
from .engine import evaluate

__all__ = [
    "array_function",
    "outcome_function",
    "outcome_arrays",
    "restitution_arrays",
    "CHECKS",
    "scalar_pair",
    "time_grid",
    "stage_of",
    "free_flight",
]


def _positive_or_inf(name, value):
    return check_positive(name, value, allow_inf=True)


def _any(name, value):
    return np.asarray(value, dtype=float)


#: What an input of the generated function must be: ``check -> (function(name, value), words)``.
CHECKS = {
    "nonnegative": (check_nonnegative, ">= 0"),
    "positive": (check_positive, "positive"),
    "positive_or_inf": (_positive_or_inf, "positive (``inf`` allowed)"),
    "velocity": (check_velocity, ">= 0 and finite"),
    "any": (_any, "any real number"),
}

#: Parameter names that are not quantity names.
_ALIASES = {
    "alpha": "approach",
    "alpha_hat": "normalized_approach",
    "max_alpha_hat": "normalized_approach",
    "v": "normalized_velocity",
}


def _unit(unit):
    """A parameter's unit as its docstring shows it (``[-]`` dimensionless); text has none of its own."""
    return unit_text(unit) or DIMENSIONLESS_SHOWN


def _parameter_doc(param, check, note, described=None, optional=False):
    """One parameter's numpydoc entry: words and unit from its quantity (or ``described``, a
    ``(words, unit)`` pair for a parameter that is not a quantity), its check and ``note``."""
    if described is not None:
        words, unit = described
        unit = _unit(unit)
    else:
        q = QUANTITIES[_ALIASES.get(param, param)]
        unit = _unit(q.unit)
        words = q.description.split(",")[0].split(" (")[0].split(" = ")[0]  # "effective modulus E*"
        if q.symbol and words.endswith(" " + q.symbol):
            words = words[: -len(q.symbol)] + f"``{q.symbol}``"
        elif q.symbol:
            words += f" ``{q.symbol}``"
    text = f"{words} [{unit}], {CHECKS[check][1]}"
    kind = "array_like, optional" if optional else "array_like"
    return f"{param} : {kind}\n    {text[0].upper()}{text[1:]}{'; ' + note if note else ''}."


def _docstring(summary, notes, parameters, returns, examples, source):
    """A numpydoc docstring of a generated function: summary, notes, parameters, one ndarray
    returned, the ValueError of a bad argument, examples and where it was generated from."""
    doc = [summary.strip()]
    if notes:
        doc.append(textwrap.dedent(notes).strip())
    doc.append("Parameters\n----------\n" + "\n".join(parameters))
    doc.append(f"Returns\n-------\nndarray\n    {returns}")
    doc.append(
        "Raises\n------\nValueError\n    If an argument breaks its condition above (the message names it and its value)."
    )
    if examples:
        doc.append("Examples\n--------\n" + textwrap.dedent(examples).strip())
    doc.append(source)
    return "\n\n".join(doc) + "\n"


def _out_of_range(name: str, inputs: dict):
    """Raise the ValueError of an array face whose formula divided by a zero that the inputs, each in
    its range, made by underflow (``E*^4`` of a tiny modulus, ``p_y^2`` of a subnormal pressure): no
    value is due there, and the message names every input with its value(s)."""
    arrays = {k: np.asarray(v) for k, v in inputs.items()}
    given = ", ".join(f"{k} {float(v)!r}" if v.ndim == 0 else f"{k} {describe_value(v)}" for k, v in arrays.items())
    raise ValueError(
        f"{name}: {given} leave the float range (a product of the inputs underflows to zero and the "
        "formula divides by it): give inputs in range"
    ) from None


def array_function(
    namespace,
    name,
    core_function,
    parameters,
    returns,
    summary,
    notes="",
    examples="",
    output=(0, 1),
    order=None,
    defaults=None,
    described=None,
):
    """Define ``name`` in ``namespace`` (a module's ``globals()``): ``core_function`` over arrays.

    Parameters
    ----------
    namespace : dict
        The module's globals; the function is defined there (``__module__`` is that module's).
    name : str
        The public name.
    core_function : callable
        The scalar ``@jitable`` function of :mod:`microimpact.core` it evaluates element by element
        (the output ``output`` names is returned).
    parameters : sequence of tuple
        ``(parameter, check)`` or ``(parameter, check, note)`` in the core function's order;
        ``parameter`` a quantity name (or ``alpha`` for the approach), ``check`` a key of
        :data:`CHECKS`, ``note`` a few words for its docstring.
    returns : tuple of str
        ``(quantity, words)``: what the function returns and a short description of it.
    summary : str
        The docstring's first paragraph (the formula and the seed equation).
    notes, examples : str, optional
        Further paragraphs of the docstring and its ``Examples`` section (doctests).
    output : tuple of int, optional
        ``(index, count)``: the core function returns ``count`` values, the array function the
        one at ``index`` (default: the only one).
    order : sequence of str, optional
        The parameters in the order the core function takes them, where it differs from the
        public signature's (each is checked in the signature's order first).
    defaults : dict, optional
        ``{parameter: value}``: the default values of the last parameters (keywords of the
        signature, as in a hand-written function).
    described : dict, optional
        ``{parameter: (words, unit)}`` for a parameter that is not a quantity of
        :data:`~microimpact.core.quantities.QUANTITIES` (a prefactor, say); the unit spelled as the
        table spells it (``"1"`` dimensionless).

    Returns
    -------
    callable
        The function (also bound in ``namespace``).
    """
    params = [p if len(p) == 3 else (p[0], p[1], "") for p in parameters]
    defaults = defaults or {}
    described = described or {}
    for p, value in defaults.items():
        namespace[f"_default_{name}_{p}"] = value
    args = ", ".join(p + (f"=_default_{name}_{p}" if p in defaults else "") for p, _, _ in params)
    checks = "".join(f"    {p} = _checks[{c!r}][0]({p!r}, {p})\n" for p, c, _ in params)
    checked = ", ".join(order or [p for p, _, _ in params])
    index, count = output
    nout = f", nout={count}" if count != 1 else ""
    given = ", ".join(f"{p!r}: {p}" for p, _, _ in params)
    source = (
        f"def {name}({args}):\n{checks}    try:\n"
        f"        return _evaluate(_core_{name}, {checked}{nout})[{index}]\n"
        f"    except ZeroDivisionError:\n        _out_of_range({name!r}, {{{given}}})\n"
    )
    namespace.setdefault("_evaluate", evaluate)
    namespace.setdefault("_out_of_range", _out_of_range)
    namespace.setdefault("_checks", CHECKS)
    namespace[f"_core_{name}"] = core_function
    exec(compile(source, f"<microimpact array face: {name}>", "exec"), namespace)  # noqa: S102
    fn = namespace[name]
    quantity, words = returns
    q = QUANTITIES[quantity]
    fn.__doc__ = _docstring(
        summary,
        notes,
        [_parameter_doc(p, c, n, described.get(p), p in defaults) for p, c, n in params],
        f"{words} [{_unit(q.unit)}].",
        examples,
        f"Generated from :func:`{core_function.__module__}.{core_function.__name__}`.",
    )
    return fn


#: The pair's inputs of a model's outcome, with their checks.
_PAIR = (
    ("velocity", "velocity"),
    ("effective_modulus", "positive"),
    ("effective_radius", "positive"),
    ("effective_mass", "positive"),
    ("limiting_pressure", "positive_or_inf", "``inf``: elastic impact"),
)


def outcome_function(namespace, name, model, summary, notes="", returns="", examples="", field=None):
    """Define ``name`` in ``namespace``: the field ``field`` (default ``name``) of ``model``'s outcome over arrays.

    ``name(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure)``
    checks its inputs, broadcasts them and returns ``outcome_arrays(model, ...)[field]``; the
    docstring's parameters and units come from :data:`~microimpact.core.quantities.QUANTITIES`,
    as for :func:`array_function`. ``model`` is a model module, ``returns`` the value's line of the
    docstring, with its unit (default: the quantity's description and unit).
    """

    field = field or name

    def fn(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure):
        V = check_velocity("velocity", velocity)
        E, R, m, p_y = check_pair(effective_modulus, effective_radius, effective_mass, limiting_pressure)
        return outcome_arrays(model, V, E, R, m, p_y, ())[field]

    fn.__name__ = fn.__qualname__ = name
    fn.__module__ = namespace["__name__"]
    q = QUANTITIES[field]
    fn.__doc__ = _docstring(
        summary,
        notes,
        [_parameter_doc(*p if len(p) == 3 else (*p, "")) for p in _PAIR],
        returns or f"{q.description} [{_unit(q.unit)}].",
        examples,
        f"The field ``{field}`` of :func:`{model.__name__}.outcome`.",
    )
    namespace[name] = fn
    return fn


def outcome_arrays(model, V, E, R, m, p_y, params) -> dict:
    """Every field of ``model``'s outcome over checked, broadcast float arrays, as a dict of ndarrays
    (``model`` a :class:`~microimpact.core.models.Model`, ``V`` [m/s], ``E`` [Pa], ``R`` [m], ``m``
    [kg], ``p_y`` [Pa], ``params`` its tuple; each field in the unit of
    :data:`~microimpact.core.quantities.QUANTITIES`).

    The array path of :meth:`microimpact.pair.ContactPair.impact`: one compiled (or, for small
    arrays, Python) loop over the model's scalar ``outcome``; flags become booleans.
    """
    try:
        values = evaluate(model.outcome, V, E, R, m, p_y, nout=len(OUTCOME_FIELDS), params=tuple(params))
    except (ZeroDivisionError, OverflowError):
        # a speed so small that a model's power of it underflows (the Hertz time scale's m V/T^2 at
        # V = 1e-300 m/s) divides by zero: named as bad input, not a crash inside the loop
        Vp = np.asarray(V, dtype=float)
        Vp = Vp[Vp > 0.0]
        low = float(Vp.min()) if Vp.size else 0.0
        raise ValueError(
            f"velocity {low!r} m/s (the smallest given): model {model.NAME!r} cannot be evaluated in double "
            "precision there (a quotient of its scaling underflows to 0)"
        ) from None
    out = dict(zip(OUTCOME_FIELDS, values))
    for name in ("elastic", "large_strain"):
        out[name] = out[name] == 1.0
    return out


def restitution_arrays(model, V, E, R, m, p_y, params) -> np.ndarray:
    """The field ``restitution`` of :func:`outcome_arrays` alone, bit for bit, as an ndarray [-].

    Through the model's ``restitution_only`` hook where it declares one (a compiled, or for small
    arrays Python, loop over that scalar function, as for the outcome), which skips what only
    the other fields need (a contact time's quadrature); else, where the model declares its
    group (``restitution_group``, ``restitution_of_group``) and every speed is finite and positive,
    ``e`` once per distinct group; else the outcome's field.
    """
    params = tuple(params)
    if model.restitution_only is not None:
        return evaluate(model.restitution_only, V, E, R, m, p_y, params=params)[0]
    speeds = np.asarray(V, dtype=float)
    if model.restitution_group is not None and speeds.size and np.all(np.isfinite(speeds) & (speeds > 0.0)):
        g = evaluate(model.restitution_group, V, E, R, m, p_y, params=params)[0]
        distinct, where = np.unique(g.ravel(), return_inverse=True)
        return evaluate(model.restitution_of_group, distinct, params=params)[0][where].reshape(g.shape)
    return outcome_arrays(model, V, E, R, m, p_y, params)["restitution"]


# ----------------------------------------------------------------------------- a history on a time grid
def scalar_pair(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure):
    """Check the inputs of one impact; return them as floats ``(V, E*, R*, m*, p_y)``."""
    out = []
    names = ("velocity", "effective_modulus", "effective_radius", "effective_mass", "limiting_pressure")
    for name, value in zip(names, (velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure)):
        if np.ndim(value) != 0:
            raise ValueError(f"{name} must be a single number for a history, got shape {np.shape(value)}")
        out.append(value)
    V = float(check_velocity("velocity", out[0]))
    if not (0.0 < V < np.inf):
        raise ValueError(f"velocity must be positive and finite for a history, got {V!r}")
    E, R, m, p_y = (float(x) for x in check_pair(*out[1:]))
    return V, E, R, m, p_y


def time_grid(n, times, boundaries, t_c):
    """The times of a history: ``times`` as given, or ``n`` uniform points on ``[0, t_c]`` plus the boundaries."""
    if times is not None:
        try:
            t = np.array(times, dtype=float, ndmin=1)
        except (TypeError, ValueError):
            raise ValueError(f"times must be an array of numbers, got {times!r}") from None
        if t.ndim != 1 or t.size == 0:
            raise ValueError(f"times must be a non-empty 1-d array, got shape {t.shape}")
        if not np.all(np.isfinite(t)):
            raise ValueError(f"times must be finite, got {float(t[~np.isfinite(t)][0])!r}")
        return t
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)) or n < 2:
        raise ValueError(f"n must be an integer >= 2, got {n!r}")
    t = np.linspace(0.0, t_c, int(n))
    t[-1] = t_c
    # np.union1d, written out: numpy's unique imports numpy.ma on its first call (18 ms of a 150 ms
    # history command). Finite values only here, so sorting and dropping repeats is the same.
    u = np.sort(np.concatenate((t, [b for b in boundaries if 0.0 < b < t_c])))
    return u[np.concatenate(([True], u[1:] != u[:-1]))]


def stage_of(t, t1, t_L, t_c):
    """Stage code at each time: 1 on ``[0, t1]``, 2 on ``(t1, t_L]``, 3 on ``(t_L, t_c]``, 0 outside."""
    stage = np.where(t <= t1, 1, np.where(t <= t_L, 2, 3))
    return np.where((t < 0.0) | (t > t_c), 0, stage).astype(np.int8)


def free_flight(t, V, t_c, a_p, V_r):
    """Approach and velocity outside the contact: ``V t`` before, ``alpha_p - V_r (t - t_c)`` after."""
    approach = np.where(t < 0.0, V * t, a_p - V_r * (t - t_c))
    velocity = np.where(t < 0.0, V, -V_r)
    return approach, velocity
