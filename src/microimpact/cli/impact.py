"""``microimpact impact``: the outcome of impacts at given speeds, as a table or JSON."""

from __future__ import annotations

import dataclasses
import math
import sys
import warnings

import numpy as np

from .. import models, quantities
from .._validation import check_velocity
from ..io import write_json
from ..pair import RESULT_FIELDS, ImpactResult, LargeStrainWarning
from ._common import add_pair_arguments, pair_from_args, parse_values
from ._stdout import encodable_stdout

#: Memory per speed [bytes]: 18 result arrays with their temporaries, and the JSON or table text.
BYTES_PER_SPEED = 2000

#: Result fields the table leaves out (the pair's V_y is printed above it; the flags mark rows).
HIDDEN = ("yield_velocity", "normalized_velocity", "elastic", "max_contact_radius", "large_strain")

#: The table's columns: (attribute, header, scale to the shown unit, format), from the quantities table,
#: in the order of :class:`~microimpact.pair.ImpactResult`'s fields.
COLUMNS = [
    (n, quantities.header(n), quantities.QUANTITIES[n].scale, quantities.QUANTITIES[n].fmt)
    for n in (f.name for f in dataclasses.fields(ImpactResult))
    if n not in HIDDEN
]


def register(sub) -> None:
    p = sub.add_parser(
        "impact",
        help="restitution, energy loss, approaches, force and contact times at given speeds",
        description="Outcome of normal impacts at the given speeds (closed form). "
        "Speeds: numbers, comma lists or ranges start:stop:count, in m/s.",
    )
    p.add_argument("velocities", nargs="+", metavar="V", help="impact speed(s) [m/s], e.g. 30 50 70 or 1:120:12")
    add_pair_arguments(p)
    p.add_argument(
        "--model",
        default=None,
        metavar="NAME",
        help=f"impact model (default {models.DEFAULT}); `microimpact impact --model list 1` lists them",
    )
    p.add_argument(
        "--param",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="a parameter of the model (repeat for several); fields a model does not define print as nan",
    )
    p.add_argument("--json", action="store_true", help="print JSON (SI units) instead of a table")
    p.set_defaults(func=encodable_stdout(run))


def parse_params(items) -> dict:
    """``["name=value", ...]`` as ``{name: float}``; ValueError naming ``--param`` and the item."""
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise ValueError(f"--param must be NAME=VALUE, got {item!r}")
        if name in out:
            raise ValueError(f"--param {name} was given twice")
        try:
            out[name] = float(value)
        except ValueError:
            raise ValueError(f"--param {name} must be a number, got {value!r}") from None
    return out


def _fmt(value, scale, fmt):
    x = float(value) * scale
    if math.isinf(x):
        return "inf"
    return fmt.format(x)


def format_table(result) -> str:
    """The result as an aligned text table; rows outside small strain end with ``*``."""
    V = np.atleast_1d(result.velocity)
    cols = {name: np.atleast_1d(getattr(result, name)) for name, *_ in COLUMNS}
    flags = np.atleast_1d(result.large_strain)
    rows = [[h for _, h, _, _ in COLUMNS]]
    for i in range(V.size):
        row = [_fmt(cols[name][i], scale, fmt) for name, _, scale, fmt in COLUMNS]
        row[-1] += " *" if flags[i] else ""
        rows.append(row)
    widths = [max(len(r[j]) for r in rows) for j in range(len(COLUMNS))]
    lines = ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def run(args) -> int:
    if args.model == "list":
        for name in models.available():
            print(f"{name}: {models.get(name).TITLE}")
            for pname, (unit, desc, default) in models.parameters(name).items():
                shown = quantities.unit_text(unit)
                print(f"    {pname} [{shown}]: {desc}" + ("" if math.isnan(default) else f" (default {default:g})"))
        return 0
    name = models.DEFAULT if args.model is None else args.model  # omitted: the default, no "model:" line
    module = models.get(name)  # ValueError naming the models when unknown
    params = parse_params(args.param)
    models.resolve_params(module, params)  # every input checked before anything is computed
    V = parse_values(args.velocities, "velocity", bytes_per_value=BYTES_PER_SPEED)
    check_velocity("velocity", V)
    pair = pair_from_args(args)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", LargeStrainWarning)
        result = pair.impact(V, model=name, **params)
    flagged = np.atleast_1d(result.large_strain)
    if args.json:
        data = {k: np.atleast_1d(v).tolist() for k, v in result.to_dict().items()}
        doc = {
            "pair": {
                "label": pair.label,
                "effective_modulus": pair.effective_modulus,
                "effective_radius": pair.effective_radius,
                "effective_mass": pair.effective_mass,
                "limiting_pressure": pair.limiting_pressure,
                "density": pair.density,
                "yield_velocity": pair.yield_velocity,
            },
            "model": {"name": name, "params": params},
            "units": {k: u for k, (u, _) in RESULT_FIELDS.items()},
            "results": data,
        }
        write_json(doc)  # NaN/inf -> null: always valid JSON
    else:
        print(pair.describe())
        if args.model is not None:
            print(f"model: {name}" + "".join(f", {k} = {v:g}" for k, v in params.items()))
        print()
        print(format_table(result))
    if flagged.any():
        print(
            f"warning: {int(flagged.sum())} of {flagged.size} impacts (marked *) reach a contact radius "
            "above 0.3 R*: outside the model's small-strain range",
            file=sys.stderr,
        )
    return 0
