"""``microimpact bench``: run the benchmark suite (``benchmarks/``, pytest-benchmark) and print its table.

The suite lives in the source tree's ``benchmarks/`` directory (see its ``conftest.py`` for what
each benchmark measures); this command is its front end. It runs the suite in a subprocess
(``python -m pytest benchmarks --size MODE --ratios-json FILE``), then prints the ratio table and
keeps the JSON. It needs pytest and pytest-benchmark (``pip install 'microimpact[bench]'``) and a
source checkout (the suite is not installed with the wheel): it looks in ``./benchmarks`` and
beside the package's source tree, or takes ``--suite DIR``.
"""

from __future__ import annotations

import importlib
import importlib.util
import json
import os
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from .._optional import MissingExtraError
from ._stdout import encodable_stdout

__all__ = ["BENCHMARKS", "FILES", "find_suite", "machine_info", "format_table", "register", "run"]

#: The suite's benchmarks, in the order of their numbers (``--only``).
BENCHMARKS = [
    "outcome_vs_ode",
    "restitution_vs_copy",
    "impact_latency",
    "wall_vs_copy",
    "memory",
    "paper",
    "outcome_vs_copy",
    "threads_1e3",
    "startup",
    "c_wall",
    "warm_start",
    "fit_models",
    "csv_sweep",
    "small_arrays",
]
#: The file of the suite that holds each.
FILES = {
    "outcome_vs_ode": "test_outcome_vs_ode.py",
    "restitution_vs_copy": "test_restitution.py",
    "impact_latency": "test_latency.py",
    "wall_vs_copy": "test_wall.py",
    "memory": "test_memory.py",
    "paper": "test_paper.py",
    "outcome_vs_copy": "test_outcome_array.py",
    "threads_1e3": "test_outcome_array.py",
    "startup": "test_startup.py",
    "c_wall": "test_c_wall.py",
    "warm_start": "test_warm_start.py",
    "fit_models": "test_fit_models.py",
    "csv_sweep": "test_csv_sweep.py",
    "small_arrays": "test_small_arrays.py",
}


def _is_suite(path: Path) -> bool:
    return (path / "conftest.py").is_file() and all((path / f).is_file() for f in FILES.values())


def find_suite(suite=None) -> Path:
    """The benchmark suite's directory.

    Parameters
    ----------
    suite : str or Path, optional
        Where it is; default ``./benchmarks``, else the ``benchmarks/`` beside the package's
        ``src/`` tree (an editable or in-tree install).

    Returns
    -------
    Path
        The directory.

    Raises
    ------
    ValueError
        If no suite is found there.
    """
    if suite is not None:
        path = Path(suite)
        if not _is_suite(path):
            raise ValueError(f"--suite must be the benchmarks/ directory of a microimpact checkout, got {suite!r}")
        return path
    here = Path(__file__).resolve()
    for path in (Path.cwd() / "benchmarks", here.parents[3] / "benchmarks"):
        if _is_suite(path):
            return path
    raise ValueError(
        "the benchmark suite is not installed with the package: run from a source checkout "
        "(its benchmarks/ directory) or pass --suite DIR"
    )


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def machine_info() -> dict:
    """Platform, CPU, cores and library versions of this run.

    Returns
    -------
    dict
        ``platform``, ``cpu``, ``cores``, ``usable_cores``, ``python``, ``numpy``, ``scipy``,
        ``microimpact``, and the versions of numba, dask and xarray where installed.
    """
    import scipy

    from .._version import __version__

    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        usable = os.cpu_count()
    info = {
        "platform": platform.platform(),
        "cpu": _cpu_model(),
        "cores": os.cpu_count(),
        "usable_cores": usable,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "microimpact": __version__,
    }
    for mod in ("numba", "dask", "xarray", "pytest_benchmark"):
        if importlib.util.find_spec(mod) is not None:
            try:
                info[mod] = importlib.import_module(mod).__version__
            except Exception:  # pragma: no cover - a broken optional install
                info[mod] = "broken"
    return info


def format_table(report: dict) -> str:
    """The suite's report as a plain-text (also Markdown) table, with the machine above it.

    Parameters
    ----------
    report : dict
        As the suite writes it with ``--ratios-json``: ``mode``, ``date``, ``machine``, ``results``.

    Returns
    -------
    str
        The table.
    """
    m = report["machine"]
    versions = ", ".join(f"{k} {m[k]}" for k in ("numpy", "scipy", "numba", "dask") if k in m)
    lines = [
        f"machine: {m['cpu']}, {m['cores']} cores ({m['usable_cores']} usable), {m['platform']}",
        f"python {m['python']}, {versions}; mode: {report['mode']}; {report['date']}",
        "",
        "| # | benchmark | measured | target | met |",
        "|---|---|---|---|---|",
    ]
    for r in report["results"]:
        met = {True: "yes", False: "NO", None: "-"}[r["met"]]
        lines.append(f"| {r['number']} | **{r['title']}** | {r['headline']} | {r['target']} | {met} |")
        lines += [f"|  | {label} | {value} |  |  |" for label, value in r["rows"]]
        lines += [f"|  | note: {note} |  |  |  |" for note in r.get("notes", [])]
    return "\n".join(lines)


def _parse_only(text):
    if not text:
        return list(range(1, len(BENCHMARKS) + 1))
    from ._common import parse_names

    try:
        only = [int(x) for x in parse_names(text, "--only")]
    except ValueError:
        raise ValueError(f"--only must be comma-separated numbers 1-{len(BENCHMARKS)}, got {text!r}") from None
    bad = [i for i in only if not 1 <= i <= len(BENCHMARKS)]
    if bad or not only:
        raise ValueError(f"--only must list benchmark numbers 1-{len(BENCHMARKS)}, got {text!r}")
    return sorted(set(only))


def register(sub) -> None:
    p = sub.add_parser(
        "bench",
        help="run the benchmark suite and print its table (needs the bench extra and a checkout)",
        description="Run the benchmark suite in benchmarks/ (pytest-benchmark): closed form vs ODE, restitution vs "
        "memory copy, one impact vs plain Python, wall interaction vs copy, memory peaks, paper end to end. "
        "Prints the ratio table and writes JSON.",
    )
    size = p.add_mutually_exclusive_group()
    size.add_argument("--quick", action="store_true", help="sizes 100x smaller (about a minute)")
    size.add_argument("--tiny", action="store_true", help="smallest sizes, no paper run (a smoke test)")
    p.add_argument("--only", default=None, metavar="N,N", help="comma-separated benchmark numbers (1-14); default all")
    p.add_argument(
        "--json",
        default="microimpact-bench.json",
        metavar="FILE",
        help="where to write the JSON report (default microimpact-bench.json; '-' for none)",
    )
    p.add_argument("--suite", default=None, metavar="DIR", help="the suite's directory (default ./benchmarks)")
    p.set_defaults(func=encodable_stdout(run))


def run(args) -> int:
    from ..io import check_output_path, write_json

    mode = "tiny" if args.tiny else "quick" if args.quick else "full"
    only = _parse_only(args.only)
    if args.json and args.json != "-":
        check_output_path(args.json)  # a folder, device, FIFO or socket is refused before the suite runs
    suite = find_suite(args.suite)
    for mod in ("pytest", "pytest_benchmark"):
        if importlib.util.find_spec(mod) is None:
            raise MissingExtraError(f"{mod} is needed to run the benchmarks: pip install 'microimpact[bench]'")
    with tempfile.TemporaryDirectory() as tmp:
        report_path = Path(tmp) / "ratios.json"
        files = dict.fromkeys(str(suite / FILES[BENCHMARKS[i - 1]]) for i in only)  # each file once
        cmd = [sys.executable, "-m", "pytest", *files]
        cmd += ["-q", "-p", "no:cacheprovider", "--rootdir", str(suite), "-c", os.devnull]
        cmd += ["--size", mode, "--ratios-json", str(report_path), "--benchmark-disable-gc", "--benchmark-sort=name"]
        cmd += ["--benchmark-storage", "file://" + str(Path(tmp) / "storage")]  # no .benchmarks/ in the cwd
        print(f"running the benchmark suite in {suite} ({mode} sizes) ...", file=sys.stderr, flush=True)
        # the suite is its own pytest run: options meant for the caller's pytest (PYTEST_ADDOPTS, e.g.
        # --cov, which would time the benchmarks under a tracer and leave .coverage in the cwd) are not
        # passed on
        env = {k: v for k, v in os.environ.items() if k != "PYTEST_ADDOPTS"}
        proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
        if proc.returncode != 0 or not report_path.is_file():
            print(proc.stdout[-6000:], file=sys.stderr)
            print(proc.stderr[-2000:], file=sys.stderr)
            print(f"bench: the suite failed (pytest exit status {proc.returncode})", file=sys.stderr)
            return 1
        report = json.loads(report_path.read_text())
    print(format_table(report))
    if args.json and args.json != "-":
        write_json(report, args.json)
        print(f"\nJSON written to {args.json}")
    return 0
