"""Arguments shared by the commands: how to name a contact pair and a set of speeds."""

from __future__ import annotations

import argparse

import numpy as np

from ..materials import PAPER_CASES, list_materials
from ..pair import ContactPair

__all__ = ["add_pair_arguments", "pair_from_args", "parse_values", "parse_float"]


def parse_float(text: str, name: str = "value") -> float:
    """A float from the command line, or a ValueError naming ``name``."""
    try:
        return float(text)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {text!r}") from None


def parse_values(texts, name: str = "velocity") -> np.ndarray:
    """Numbers and ranges: ``50``, ``30,50,70``, ``1:120:500`` (start:stop:count, inclusive)."""
    out = []
    for text in texts if isinstance(texts, (list, tuple)) else [texts]:
        for part in str(text).split(","):
            part = part.strip()
            if not part:
                continue
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
                out.extend(np.linspace(start, stop, count))
            else:
                out.append(parse_float(part, name))
    if not out:
        raise ValueError(f"{name}: no values given")
    return np.asarray(out, dtype=float)


def add_pair_arguments(parser: argparse.ArgumentParser) -> None:
    """Options naming a contact pair: a paper case, two materials, or effective values."""
    g = parser.add_argument_group(
        "contact pair",
        "Either --case, or --particle/--surface with --diameter or --radius, or effective values "
        "(--effective-modulus, --density, --radius/--diameter, --limiting-pressure). "
        "Default: the seed's NH4Fl-on-silicon case.",
    )
    g.add_argument("--case", choices=sorted(PAPER_CASES), help="one of the seed paper's cases")
    g.add_argument("--particle", metavar="MATERIAL", help=f"particle material ({', '.join(list_materials())})")
    g.add_argument("--surface", metavar="MATERIAL", help="surface material (flat)")
    g.add_argument("--radius", type=float, metavar="M", help="particle radius [m]")
    g.add_argument("--diameter", type=float, metavar="M", help="particle diameter [m]")
    g.add_argument("--density", type=float, metavar="KG/M3", help="particle density [kg/m^3]")
    g.add_argument("--effective-modulus", type=float, metavar="PA", help="effective modulus E* [Pa]")
    g.add_argument("--limiting-pressure", type=float, metavar="PA", help="limiting contact pressure p_y [Pa]")
    g.add_argument("--yield-strength", type=float, metavar="PA", help="yield strength Y [Pa]; p_y = k Y")
    g.add_argument("--k", type=float, help="p_y / Y (default 2.2, the middle of the seed's 2.1-2.3)")


def _radius(args):
    if args.radius is not None and args.diameter is not None:
        raise ValueError("give --radius or --diameter, not both")
    if args.diameter is not None:
        return args.diameter / 2.0
    return args.radius


def pair_from_args(args) -> ContactPair:
    """Build the :class:`ContactPair` the options describe."""
    radius = _radius(args)
    if args.particle or args.surface:
        if not (args.particle and args.surface):
            raise ValueError("give both --particle and --surface")
        if radius is None:
            raise ValueError("--radius or --diameter is needed with --particle/--surface")
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
        return ContactPair.sphere_on_flat(
            radius,
            args.density,
            args.effective_modulus,
            args.limiting_pressure,
            yield_strength=args.yield_strength,
            k=args.k,
        )
    pair = ContactPair.paper_case(args.case or "silicon")
    # Single overrides on top of a paper case.
    if radius is not None or args.density is not None:
        pair = pair.resized(radius=radius, density=args.density)
    changes = {}
    if args.limiting_pressure is not None:
        changes["limiting_pressure"] = args.limiting_pressure
    elif args.yield_strength is not None:
        changes["limiting_pressure"] = (args.k or 2.2) * args.yield_strength
    return pair.replace(**changes) if changes else pair
