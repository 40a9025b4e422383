"""``microimpact cache``: show or empty the compiled-kernel cache (an optimisation: never needed)."""

from __future__ import annotations

from ._stdout import encodable_stdout


def register(sub) -> None:
    p = sub.add_parser(
        "cache",
        help="show (--info) or empty (--clear) the cache of compiled loops, tables and calibrations",
        description="The array computations compile their loops with numba once and keep the machine code in "
        "a cache folder (MICROIMPACT_CACHE_DIR, else $XDG_CACHE_HOME/microimpact or ~/.cache/microimpact), so "
        "that a new process loads instead of compiling. The cache is an optimisation: when it cannot be read or "
        "written (a read-only home, a full disk) the loops are compiled in memory, and a corrupt entry is "
        "deleted and rebuilt, each with a one-line warning naming the folder. The same folder keeps the tables "
        "of the oblique and adhesive laws (tables/) and compare's calibrations (calibrations/). --clear deletes "
        "only the files microimpact can prove it made there (generated loop files by their first line and "
        "numba's entries for them, tables and calibrations by their checksums), nothing else in the folder.",
    )
    g = p.add_mutually_exclusive_group()
    g.add_argument("--info", action="store_true", help="print the folder, its files and their size (default)")
    g.add_argument("--clear", action="store_true", help="delete the cache's own files")
    p.set_defaults(func=encodable_stdout(run))


def run(args) -> int:
    from ..cache import cache_info, clear_cache

    if args.clear:
        n = clear_cache()
        print(f"deleted {n} cache file{'s' if n != 1 else ''} from {cache_info()['folder']}")
        return 0
    info = cache_info()
    print(f"folder:   {info['folder']}")
    print(f"files:    {info['files']} ({info['bytes'] / 1e6:.3g} MB)")
    print(f"writable: {'yes' if info['writable'] else 'no (loops are compiled in memory)'}")
    return 0
