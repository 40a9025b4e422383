"""``microimpact materials``: list the named materials and their sources."""

from __future__ import annotations

from ..materials import get_material, list_materials
from ..quantities import header
from ._stdout import encodable_stdout


def register(sub) -> None:
    p = sub.add_parser("materials", help="list the named materials with their sources")
    p.add_argument("name", nargs="?", help="show one material in full")
    p.set_defaults(func=encodable_stdout(run))


def run(args) -> int:
    if args.name is not None:  # '' names no material: an error, not the list (which is the no-argument call)
        if not args.name.strip():
            raise ValueError(f"the material name is empty ({args.name!r}); give a name, or none to list them all")
        m = get_material(args.name)
        print(f"{m.name}: {m.description}")
        print(
            f"  E = {m.youngs_modulus:.4g} Pa, nu = {m.poisson_ratio}, rho = {m.density:g} kg/m^3, "
            f"Y = {m.yield_strength if m.yield_strength is not None else 'n/a'} Pa"
        )
        print(f"  source: {m.source}")
        return 0
    print(f"{'name':16s} {'E [GPa]':>8s} {'nu':>5s} {'rho [kg/m3]':>11s} {header('yield_strength'):>8s}  description")
    for name in list_materials():
        m = get_material(name)
        y = f"{m.yield_strength / 1e6:.0f}" if m.yield_strength else "-"
        print(
            f"{m.name:16s} {m.youngs_modulus / 1e9:8.1f} {m.poisson_ratio:5.2f} {m.density:11.0f} {y:>8s}  "
            f"{m.description}"
        )
    return 0
