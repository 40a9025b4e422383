"""``microimpact paper``: regenerate the seed paper's Section 3 (Figures 2-10, their data, a report)."""

from __future__ import annotations

import sys

from ._common import check_input_file, check_outputs, show_progress


def register(sub) -> None:
    p = sub.add_parser(
        "paper",
        help="reproduce the seed paper's Figures 2-10 and compare with its quoted numbers",
        description="Write the seed paper's Figures 2-10 (PNG and a vector format), the CSV behind each, "
        "and a report (report.md, self-contained report.html) setting every number the paper quotes in "
        "Section 3 beside the value computed now.",
    )
    p.add_argument(
        "--out",
        default=None,
        metavar="DIR",
        help="output folder (default: ./microimpact-paper); it owns only what it wrote: an existing DIR may hold "
        "only the files an earlier run listed in its manifest (.microimpact-manifest.json), unchanged",
    )
    p.add_argument(
        "--data",
        action="append",
        default=[],
        metavar="NAME=FILE.csv",
        help="measured restitution to overlay on Fig. 2 (CSV columns velocity [m/s], restitution); "
        "repeatable, e.g. --data silicon=wall_si.csv",
    )
    p.add_argument(
        "--formats",
        default="png,pdf",
        metavar="LIST",
        help="image formats, comma separated, among png, pdf, svg, eps (default: png,pdf)",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        metavar="N",
        help="processes drawing the figures, this one included (default: 2 when it may run on more than one "
        "core and a core is idle, else 1); the files are the same bytes whatever N",
    )
    p.add_argument("--quiet", "-q", action="store_true", help="no progress bar and no summary")
    p.set_defaults(func=run)


def parse_data(items) -> dict:
    """``["silicon=FILE.csv", ...]`` -> ``{"silicon": "FILE.csv"}``; a ValueError names a malformed item."""
    out = {}
    for item in items:
        name, sep, path = str(item).partition("=")
        if not sep or not name.strip() or not path.strip():
            raise ValueError(f"--data must be NAME=FILE.csv, got {item!r}")
        out[name.strip()] = path.strip()
    return out


def run(args) -> int:
    from ..paper import DEFAULT_OUT_DIR, reproduce
    from ..paper._draw import defer_font_subsetting

    defer_font_subsetting()  # this process's own: fontTools.subset loads only if a font is subset

    out = args.out or DEFAULT_OUT_DIR
    check_outputs(directories=[out])
    data = parse_data(args.data)
    for name, path in data.items():
        check_input_file(path, f"--data {name}")
    report = reproduce(
        out,
        data=data,
        formats=[f for f in args.formats.split(",") if f.strip()],
        progress=show_progress(args),
        workers=args.workers,
    )
    if not args.quiet:
        print(report.summary(), file=sys.stderr)
    print(report.html)
    return 0
