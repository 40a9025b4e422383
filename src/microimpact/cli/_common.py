"""Arguments shared by the commands: how to name a contact pair and a set of speeds, and the
checks every command makes on its options and output paths before it computes anything."""

from __future__ import annotations

import argparse
import math
import os
import sys

import numpy as np

from .._validation import check_pair_scales, check_positive, first_duplicate, parse_number
from ..io import check_figure_path, check_input_file, check_memory, check_output_path
from ..materials import DEFAULT_K, PAPER_CASES, limiting_pressure, list_materials, sphere_mass
from ..pair import ContactPair

__all__ = [
    "add_pair_arguments",
    "pair_from_args",
    "check_pair_options",
    "parse_values",
    "parse_float",
    "parse_names",
    "refuse_together",
    "check_outputs",
    "check_distinct_paths",
    "check_input_file",
    "show_progress",
    "add_model_arguments",
    "parse_models",
    "parse_model_params",
    "parse_tangential",
    "DeferredHelp",
]


class DeferredHelp(str):
    """An option's help text whose ``%(name)s`` fields are read from their source only when the help
    is printed: argparse formats a help text with ``%`` then, and only then (as ``--version`` reads the
    version only when asked). ``values``: name -> function returning the text. So that building a
    command's parser does not import what only its help names (every model, to list the adhesion rules).
    """

    def __new__(cls, text: str, **values):
        self = super().__new__(cls, text)
        self._values = values
        return self

    def __mod__(self, params):
        return str(self) % {**params, **{name: value() for name, value in self._values.items()}}


#: Options of :func:`add_pair_arguments`: dest -> option as typed.
PAIR_OPTIONS = {
    "case": "--case",
    "particle": "--particle",
    "surface": "--surface",
    "radius": "--radius",
    "diameter": "--diameter",
    "density": "--density",
    "effective_modulus": "--effective-modulus",
    "limiting_pressure": "--limiting-pressure",
    "yield_strength": "--yield-strength",
    "k": "--k",
}


def show_progress(args=None) -> bool:
    """True when a progress bar should be drawn: stderr is a terminal and neither --quiet nor --no-progress."""
    if args is not None and (getattr(args, "quiet", False) or getattr(args, "no_progress", False)):
        return False
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


def parse_float(text: str, name: str = "value") -> float:
    """A float from the command line (a decimal number: ``1_0`` is refused), or a ValueError naming ``name``."""
    return parse_number(text, name)


def number(text: str) -> float:
    """argparse ``type=`` of a numeric option: a decimal number (argparse names the option on failure)."""
    return parse_number(text)


def parse_values(texts, name: str = "velocity", *, bytes_per_value: float = 8.0, unique: bool = False) -> np.ndarray:
    """Numbers and ranges: ``50``, ``30,50,70``, ``1:120:500`` (start:stop:count, inclusive).

    ``bytes_per_value`` is the memory the command needs per value; the total is
    checked against :func:`microimpact.io.memory_budget` before any array is made.
    ``unique=True`` refuses a value given twice (naming it).
    """
    parts = []
    total = 0
    for text in texts if isinstance(texts, (list, tuple)) else [texts]:
        for part in str(text).split(","):
            part = part.strip()
            if not part:
                raise ValueError(f"{name} has an empty value in {str(text)!r} (values are separated by one comma)")
            if ":" in part:
                bits = part.split(":")
                if len(bits) != 3:
                    raise ValueError(f"{name} range must be start:stop:count, got {part!r}")
                start, stop = parse_float(bits[0], name), parse_float(bits[1], name)
                try:
                    count = int(bits[2])
                except ValueError:
                    raise ValueError(f"{name} range count must be an integer, got {bits[2]!r}") from None
                if count < 1:
                    raise ValueError(f"{name} range count must be >= 1, got {count}")
                if not (math.isfinite(start) and math.isfinite(stop)):
                    raise ValueError(f"{name} range ends must be finite, got {part!r}")
                parts.append((start, stop, count))
                total += count
            else:
                parts.append(parse_float(part, name))
                total += 1
    if not parts:
        raise ValueError(f"{name}: no values given")
    check_memory(total * bytes_per_value, f"{name} with {total} values", "give fewer values")
    out = np.empty(total)
    i = 0
    for p in parts:
        if isinstance(p, tuple):
            out[i : i + p[2]] = np.linspace(*p)
            i += p[2]
        else:
            out[i] = p
            i += 1
    if unique and out.size > 1:
        dup = first_duplicate(out)
        if dup is not None:
            raise ValueError(f"{name} has the value {dup:g} more than once (a sweep's values must be distinct)")
    return out


def parse_names(text, name: str) -> list[str]:
    """The items of a comma list (``lammps,liggghts``), stripped; a ValueError naming ``name`` when the
    list or one of its items is empty (``lammps,``, ``,x``, ``a,,b``): a stray comma is a typo, not a
    request for fewer items."""
    items = [t.strip() for t in str(text).split(",")]
    if not any(items):
        raise ValueError(f"{name}: nothing named in {str(text)!r}")
    if not all(items):
        raise ValueError(f"{name} has an empty item in {str(text)!r} (items are separated by one comma)")
    return items


def refuse_together(args, *groups) -> None:
    """Raise a ValueError naming both options when options of two ``groups`` are both given.

    Each group is ``(dest, ...)``; option names are taken from :data:`PAIR_OPTIONS`
    or spelled from the dest.
    """
    given = [[d for d in g if getattr(args, d, None) not in (None, False)] for g in groups]
    for i in range(len(given)):
        for j in range(i + 1, len(given)):
            if given[i] and given[j]:
                a, b = (PAIR_OPTIONS.get(x, "--" + x.replace("_", "-")) for x in (given[i][0], given[j][0]))
                raise ValueError(f"{a} and {b} cannot be used together ({b} would be ignored)")


def check_outputs(files=(), figures=(), directories=()) -> None:
    """Check output paths before computing: parents exist and are directories; nothing is created."""
    for path in files:
        if path is not None and str(path) != "-":
            check_output_path(path)
    for path in figures:
        if path is not None:
            check_figure_path(path)
    for path in directories:
        if path is not None:
            check_output_path(path, directory=True)


def _same_file(a: str, b: str, real_a: str, real_b: str) -> bool:
    """True when ``a`` and ``b`` name one file: the same path once links are resolved, or (both
    existing) the same device and inode, which also catches hard links and bind mounts."""
    if real_a == real_b:
        return True
    try:
        return os.path.samefile(a, b)
    except OSError:  # one of them does not exist yet: only the resolved paths can tell
        return False


def _inside(real_path: str, real_dir: str) -> bool:
    try:
        return os.path.commonpath([real_path, real_dir]) == real_dir
    except ValueError:  # different drives
        return False


def check_distinct_paths(inputs=(), outputs=(), directories=()) -> None:
    """Refuse a run whose output would overwrite one of its inputs or another of its outputs.

    Each argument is a sequence of ``(option, path)``; ``None`` and ``"-"`` (stdout) paths are
    skipped. ``outputs`` are files the run writes, ``directories`` output folders it replaces.
    Paths are compared after resolving symbolic links (:func:`os.path.realpath`) and, where both
    exist, by :func:`os.path.samefile`, so that a link or a second name of an input is caught
    too; an input inside an output folder is refused as well. Called before anything is
    computed or written; the ValueError names both options and paths (the CLI prints it on
    one line, exit 2).
    """

    def norm(items):
        return [
            (opt, os.fspath(p), os.path.realpath(os.fspath(p))) for opt, p in items if p is not None and str(p) != "-"
        ]

    ins, outs, dirs = norm(inputs), norm(outputs), norm(directories)
    for i, (o_opt, o_path, o_real) in enumerate(outs):
        for i_opt, i_path, i_real in ins:
            if _same_file(o_path, i_path, o_real, i_real):
                raise ValueError(
                    f"{o_opt} {o_path!r} is the input {i_opt} {i_path!r}: the run would overwrite what it reads"
                )
        for p_opt, p_path, p_real in outs[:i]:
            if _same_file(o_path, p_path, o_real, p_real):
                raise ValueError(
                    f"{o_opt} {o_path!r} and {p_opt} {p_path!r} name the same file: one output would overwrite the other"
                )
        for d_opt, d_path, d_real in dirs:
            if _inside(o_real, d_real):
                raise ValueError(
                    f"{o_opt} {o_path!r} lies inside the output folder {d_opt} {d_path!r}, which the run replaces"
                )
    for d_opt, d_path, d_real in dirs:
        for i_opt, i_path, i_real in ins:
            if _inside(i_real, d_real) or _same_file(d_path, i_path, d_real, i_real):
                raise ValueError(
                    f"the input {i_opt} {i_path!r} lies inside the output folder {d_opt} {d_path!r}, which the run "
                    "replaces: the run would overwrite or delete what it reads"
                )
    for j, (d_opt, d_path, d_real) in enumerate(dirs):
        for e_opt, e_path, e_real in dirs[:j]:
            if _inside(d_real, e_real) or _inside(e_real, d_real):
                raise ValueError(f"the output folders {e_opt} {e_path!r} and {d_opt} {d_path!r} overlap")


def add_pair_arguments(parser: argparse.ArgumentParser) -> None:
    """Options naming a contact pair: a paper case, two materials, or effective values."""
    g = parser.add_argument_group(
        "contact pair",
        "Either --case, or --particle/--surface with --diameter or --radius, or effective values "
        "(--effective-modulus, --density, --radius/--diameter, --limiting-pressure). "
        "Default: the seed's NH4Fl-on-silicon case. --yield-strength and --k give p_y = k Y "
        "(with a paper case alone, --k multiplies the case's yield strength).",
    )
    g.add_argument("--case", choices=sorted(PAPER_CASES), help="one of the seed paper's cases")
    g.add_argument("--particle", metavar="MATERIAL", help=f"particle material ({', '.join(list_materials())})")
    g.add_argument("--surface", metavar="MATERIAL", help="surface material (flat)")
    g.add_argument("--radius", type=number, metavar="M", help="particle radius [m]")
    g.add_argument("--diameter", type=number, metavar="M", help="particle diameter [m]")
    g.add_argument("--density", type=number, metavar="KG/M3", help="particle density [kg/m^3]")
    g.add_argument("--effective-modulus", type=number, metavar="PA", help="effective modulus E* [Pa]")
    g.add_argument("--limiting-pressure", type=number, metavar="PA", help="limiting contact pressure p_y [Pa]")
    g.add_argument("--yield-strength", type=number, metavar="PA", help="yield strength Y [Pa]; p_y = k Y")
    g.add_argument("--k", type=number, help=f"p_y / Y (default {DEFAULT_K}, the middle of the seed's 2.1-2.3)")


def check_pair_options(args) -> None:
    """Check the pair options alone, before anything is computed or written.

    Every number must be positive and finite (``--limiting-pressure inf``: an
    elastic pair); options that would be ignored or that conflict are refused,
    naming both.
    """
    for dest in ("radius", "diameter", "density", "effective_modulus", "yield_strength", "k"):
        value = getattr(args, dest, None)
        if value is not None:
            check_positive(PAIR_OPTIONS[dest], value)
    if getattr(args, "limiting_pressure", None) is not None:
        check_positive("--limiting-pressure", args.limiting_pressure, allow_inf=True)
    refuse_together(args, ("radius",), ("diameter",))
    refuse_together(args, ("case",), ("particle", "surface", "effective_modulus"))
    refuse_together(args, ("particle", "surface"), ("effective_modulus", "density"))
    refuse_together(args, ("limiting_pressure",), ("yield_strength", "k"))
    if (args.particle or args.surface) and not (args.particle and args.surface):
        raise ValueError("give both --particle and --surface")
    if args.effective_modulus is not None and args.k is not None and args.yield_strength is None:
        raise ValueError("--k needs --yield-strength with --effective-modulus (p_y = k Y); or give --limiting-pressure")


def _radius(args):
    if args.radius is not None and args.diameter is not None:
        raise ValueError("give --radius or --diameter, not both")
    if args.diameter is not None:
        return args.diameter / 2.0
    return args.radius


def _size_option(args) -> str:
    return "--diameter" if args.diameter is not None else "--radius"


def _check_mass(radius, density, option, value):
    """Refuse, naming the command-line option, a size or density whose particle mass 4/3 pi R^3 rho
    leaves the normal floats; :func:`~microimpact.materials.sphere_mass` refuses it naming its own
    parameters (radius, density), which the user did not type."""
    unit = "kg/m^3" if option == "--density" else "m"
    try:
        sphere_mass(radius, density)
    except ValueError as exc:
        raise ValueError(f"{option} {value:g} {unit} is outside what double precision can model: {exc}") from None


def pair_from_args(args) -> ContactPair:
    """Build the :class:`ContactPair` the options describe (after :func:`check_pair_options`); a pair
    whose yield velocity double precision cannot hold (``--effective-modulus 1e308``) is refused,
    naming the input (:func:`microimpact._validation.check_pair_scales`)."""
    pair = _pair_from_args(args)
    check_pair_scales(pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure)
    return pair


def _pair_from_args(args) -> ContactPair:
    check_pair_options(args)
    radius = _radius(args)
    size_value = args.diameter if args.diameter is not None else args.radius
    if args.particle or args.surface:
        if radius is None:
            raise ValueError("--radius or --diameter is needed with --particle/--surface")
        from ..materials import get_material

        _check_mass(radius, get_material(args.particle).density, _size_option(args), size_value)
        return ContactPair.from_materials(
            args.particle,
            args.surface,
            radius,
            limiting_pressure=args.limiting_pressure,
            k=args.k,
            yield_strength=args.yield_strength,
        )
    if args.effective_modulus is not None:
        if radius is None or args.density is None:
            raise ValueError("--effective-modulus needs --radius (or --diameter) and --density")
        if args.limiting_pressure is None and args.yield_strength is None:
            raise ValueError("--effective-modulus needs --limiting-pressure or --yield-strength")
        _check_mass(radius, args.density, _size_option(args), size_value)
        return ContactPair.sphere_on_flat(
            radius,
            args.density,
            args.effective_modulus,
            args.limiting_pressure,
            yield_strength=args.yield_strength,
            k=args.k,
        )
    case = args.case or "silicon"
    pair = ContactPair.paper_case(case)
    changed = []
    # Single overrides on top of a paper case.
    if radius is not None or args.density is not None:
        rho = pair.density if args.density is None else args.density
        r = pair.effective_radius if radius is None else radius
        if radius is not None:
            _check_mass(r, rho, _size_option(args), size_value)
        else:
            _check_mass(r, rho, "--density", args.density)
        pair = pair.resized(radius=radius, density=args.density)
        if radius is not None:
            changed.append(f"R = {radius:.6g} m")
        if args.density is not None:
            changed.append(f"density {args.density:.6g} kg/m^3")
    changes = {}
    if args.limiting_pressure is not None:
        changes["limiting_pressure"] = args.limiting_pressure
        changed.append(f"p_y = {args.limiting_pressure:.6g} Pa")
    elif args.yield_strength is not None or args.k is not None:
        Y = args.yield_strength if args.yield_strength is not None else PAPER_CASES[case]["yield_strength"]
        k = args.k if args.k is not None else DEFAULT_K
        changes["limiting_pressure"] = limiting_pressure(Y, k)
        changed.append(f"p_y = {k:g} x {Y:.6g} Pa")
    if changed:
        changes["label"] = f"{pair.label}, with {', '.join(changed)}"
    return pair.replace(**changes) if changes else pair


def add_model_arguments(parser: argparse.ArgumentParser, *, many: bool = True, default: str | None = None) -> None:
    """``--model NAME[,NAME...]`` and ``--param MODEL:NAME=VALUE`` (repeatable)."""
    from ..models import DEFAULT, available

    g = parser.add_argument_group("impact models", f"Models: {', '.join(available())}.")
    g.add_argument(
        "--model",
        metavar="NAME[,NAME...]" if many else "NAME",
        default=default,
        help=("impact model(s), comma-separated" if many else "impact model")
        + f" (default: {default or 'the seed, ' + DEFAULT})",
    )
    g.add_argument(
        "--param",
        action="append",
        default=[],
        metavar="MODEL:NAME=VALUE",
        help="a model parameter, e.g. MODEL:restitution=0.7 (`microimpact impact --model list 1` lists each "
        "model's; repeat for more; MODEL: may be left out when one model is named)",
    )


def parse_models(text) -> list[str] | None:
    """The names of ``--model a,b`` (checked), or None when the option was not given."""
    if text is None:
        return None
    from ..models import get

    names = parse_names(text, "--model")
    for n in names:
        try:
            get(n)
        except ValueError as exc:
            raise ValueError(f"--model: {exc}") from None
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ValueError(f"--model names {dup[0]!r} more than once")
    return names


def parse_model_params(texts, names) -> dict:
    """``{model: {parameter: value}}`` from ``--param MODEL:NAME=VALUE`` options, for the models ``names``."""
    from ..models import parameters

    out: dict = {}
    for text in texts or []:
        head, eq, value = str(text).partition("=")
        if not eq:
            raise ValueError(f"--param must be MODEL:NAME=VALUE, got {text!r}")
        model, colon, name = head.strip().rpartition(":")
        if not colon:
            if len(names) != 1:
                raise ValueError(f"--param {text!r} must name its model (MODEL:NAME=VALUE) when several are compared")
            model = names[0]
        model, name = model.strip(), name.strip()
        if model not in names:
            raise ValueError(
                f"--param {text!r} names the model {model!r}, which is not among --model {','.join(names)}"
            )
        known = parameters(model)
        if name not in known:
            raise ValueError(
                f"--param {text!r}: model {model!r} has no parameter {name!r}; its parameters: {', '.join(known) or 'none'}"
            )
        if name in out.get(model, {}):
            raise ValueError(f"--param {model}:{name} is given more than once")
        out.setdefault(model, {})[name] = parse_float(value.strip(), f"--param {model}:{name}")
    return out


def parse_tangential(text, known):
    """The tangential models named by ``--tangential`` (checked, in order, without repeats): a comma
    list of ``known``, ``both`` (mindlin, rigid) or ``all``."""
    if text == "both":
        return ["mindlin", "rigid"]
    if text == "all":
        return list(known)
    if not str(text).strip():
        raise ValueError(f"tangential must name at least one model, got {text!r}")
    names = parse_names(text, "--tangential")
    for n in names:
        if n not in known:
            raise ValueError(f"tangential must be among {', '.join(known)} (or both, all), got {n!r}")
    return list(dict.fromkeys(names))
