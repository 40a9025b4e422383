"""The array face of the core, generated: one line per wrapper instead of one hand-written function.

:func:`array_function` turns a scalar ``@jitable`` core function into the public array function
of :mod:`microimpact.contact` (and the like): the inputs checked (each ``ValueError`` names the
parameter and its value), broadcast and handed to :func:`microimpact.core.arrays.evaluate`, and a
numpydoc docstring whose parameters and return value come from
:data:`microimpact.core.quantities.QUANTITIES` (description and SI unit), so that a wrapper
repeats neither the formula nor the units. The function is generated as source with the real
parameter names (keywords work, :func:`inspect.signature` and the API pages show them), in the
namespace of the module that asks for it (its doctests run as that module's).
"""

from __future__ import annotations

import textwrap

import numpy as np

from ._validation import check_nonnegative, check_positive, check_velocity
from .core.arrays import evaluate
from .core.quantities import QUANTITIES

__all__ = ["array_function", "CHECKS"]


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


def _parameter_doc(param, check, note):
    q = QUANTITIES[_ALIASES.get(param, param)]
    unit = q.unit if q.unit not in ("", "1") else "-"
    words = q.description.split(",")[0].split(" (")[0].split(" = ")[0]  # "effective modulus E*"
    if q.symbol and words.endswith(" " + q.symbol):
        words = words[: -len(q.symbol)] + f"``{q.symbol}``"
    elif q.symbol:
        words += f" ``{q.symbol}``"
    text = f"{words} [{unit}], {CHECKS[check][1]}"
    return f"{param} : array_like\n    {text[0].upper()}{text[1:]}{'; ' + note if note else ''}."


def array_function(
    namespace, name, core_function, parameters, returns, summary, notes="", examples="", output=(0, 1), order=None
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

    Returns
    -------
    callable
        The function (also bound in ``namespace``).
    """
    params = [p if len(p) == 3 else (p[0], p[1], "") for p in parameters]
    args = ", ".join(p for p, _, _ in params)
    checks = "".join(f"    {p} = _checks[{c!r}][0]({p!r}, {p})\n" for p, c, _ in params)
    checked = ", ".join(order or [p for p, _, _ in params])
    index, count = output
    nout = f", nout={count}" if count != 1 else ""
    source = f"def {name}({args}):\n{checks}    return _evaluate(_core_{name}, {checked}{nout})[{index}]\n"
    namespace.setdefault("_evaluate", evaluate)
    namespace.setdefault("_checks", CHECKS)
    namespace[f"_core_{name}"] = core_function
    exec(compile(source, f"<microimpact array face: {name}>", "exec"), namespace)  # noqa: S102
    fn = namespace[name]
    quantity, words = returns
    q = QUANTITIES[quantity]
    unit = q.unit if q.unit not in ("", "1") else "-"
    doc = [summary.strip()]
    if notes:
        doc.append(textwrap.dedent(notes).strip())
    doc.append("Parameters\n----------\n" + "\n".join(_parameter_doc(p, c, n) for p, c, n in params))
    doc.append(f"Returns\n-------\nndarray\n    {words} [{unit}].")
    doc.append(
        "Raises\n------\nValueError\n    If an argument breaks its condition above (the message names it and its value)."
    )
    if examples:
        doc.append("Examples\n--------\n" + textwrap.dedent(examples).strip())
    doc.append(f"Generated from :func:`{core_function.__module__}.{core_function.__name__}`.")
    fn.__doc__ = "\n\n".join(doc) + "\n"
    return fn
