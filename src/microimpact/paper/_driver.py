"""The figures of the seed's Section 3, their data and the report, written in one go (:func:`reproduce`)."""

from __future__ import annotations

import os
import sys
import threading
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..figures import paper as figs
from ..io import write_table
from . import _draw, _worker
from ._claims import PAPER_QUOTES, PAPER_STATEMENTS, check_statements, compare_with_paper
from ._report import report_blocks, to_html, to_markdown
from ._setup import (
    DEFAULT_OUT_DIR,
    FIG3_PRESSURES,
    FIG4_MODULI,
    FIG4_SURFACE,
    FIG5_DENSITIES,
    FIG6_VELOCITIES,
    FIG7_VELOCITY,
    FIG10_VELOCITY,
    FIGURES,
    SEED,
    TOLERANCE,
)

__all__ = ["PaperReport", "reproduce", "load_measurements"]

_SOURCE = f"seed: {SEED}"  # the provenance line of every CSV file


def load_measurements(path):
    """Measured impact speeds and restitution coefficients from a CSV file.

    Uses :func:`microimpact.io.load_restitution_csv` (columns ``velocity``,
    ``restitution``; errors name the file and line); an uncertainty column is
    ignored here.

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file.

    Returns
    -------
    velocity : ndarray
        Impact speeds ``V`` [m/s].
    restitution : ndarray
        Coefficients of restitution ``e`` [-].

    Raises
    ------
    ValueError
        If the file is malformed (the message gives the line number).
    """
    from ..io import load_restitution_csv

    data = load_restitution_csv(path)
    return np.asarray(data[0], float), np.asarray(data[1], float)


# ----------------------------------------------------------------------------- figures
# Each figure's table (from the public API; it is also the figure's CSV) and its drawing from that
# table alone, so that a second process can draw it from the table (._worker).
_TABLES = {
    "fig02": lambda data: figs.restitution_data(data=data),
    "fig03": lambda data: figs.energy_loss_data("limiting_pressure", FIG3_PRESSURES),
    "fig04": lambda data: figs.energy_loss_data("particle_modulus", FIG4_MODULI, **FIG4_SURFACE),
    "fig05": lambda data: figs.energy_loss_data("density", FIG5_DENSITIES),
    "fig06": lambda data: figs.force_displacement_data(FIG6_VELOCITIES),
    "fig07": lambda data: figs.force_time_data(FIG7_VELOCITY),
    "fig08": lambda data: figs.approach_data(),
    "fig09": lambda data: figs.contact_time_data(),
    "fig10": lambda data: figs.dynamics_data(FIG10_VELOCITY),
}
assert list(_TABLES) == [f[0] for f in FIGURES]

_FORMATS = ("png", "pdf", "svg", "eps")


@dataclass
class PaperReport:
    """What :func:`reproduce` wrote, and the comparison it made.

    Attributes
    ----------
    out_dir : Path
        Directory the files were written to.
    figures : dict of str -> list of Path
        Image files of each figure (``fig02`` ... ``fig10``).
    tables : dict of str -> Path
        The CSV behind each figure.
    markdown, html, comparison_csv : Path
        ``report.md``, ``report.html`` (self-contained), ``comparison.csv``.
    comparison : list of dict
        :func:`compare_with_paper` rows.
    statements : list of dict
        :func:`check_statements` rows.
    elapsed : float
        Wall time [s].
    """

    out_dir: Path
    figures: dict = field(default_factory=dict)
    tables: dict = field(default_factory=dict)
    markdown: Path | None = None
    html: Path | None = None
    comparison_csv: Path | None = None
    comparison: list = field(default_factory=list)
    statements: list = field(default_factory=list)
    elapsed: float = 0.0

    @property
    def all_agree_or_explained(self) -> bool:
        """True when every quoted number agrees within the tolerance or carries an explanation."""
        return all(r["agrees"] or r["note"] for r in self.comparison)

    def summary(self) -> str:
        """A few lines for the terminal."""
        n_ok = sum(r["agrees"] for r in self.comparison)
        n_expl = sum((not r["agrees"]) and bool(r["note"]) for r in self.comparison)
        n_st = sum(r["holds"] for r in self.statements)
        return (
            f"wrote {len(self.figures)} figures, {len(self.tables)} tables and the report to {self.out_dir}\n"
            f"  paper numbers: {n_ok} of {len(self.comparison)} within {TOLERANCE:.0%}, "
            f"{n_expl} explained in the report\n"
            f"  paper statements: {n_st} of {len(self.statements)} hold\n"
            f"  report: {self.html}\n"
            f"  time: {self.elapsed:.1f} s"
        )


def _progress_fn(progress):
    """One line per figure to ``progress`` where it is a callable, else nowhere (the bar shows it)."""
    return progress if callable(progress) else (lambda msg: None)


def _normalize_data(data):
    out = {}
    for name, value in (data or {}).items():
        if isinstance(value, (str, os.PathLike)):
            out[str(name)] = load_measurements(value)
        else:
            V, e = value
            out[str(name)] = (np.asarray(V, float), np.asarray(e, float))
    return out


def _processes(workers) -> int:
    """How many processes draw the figures: ``workers``, or by default 2 when this process may run
    on more than one core (its CPU affinity) and a whole core is idle, else 1.

    A second process is a new interpreter (:mod:`._worker`): its imports cost about a CPU-second,
    which a machine with no idle core pays in time, so the 1-minute load average must leave a
    whole core idle (at most the cores less one); and ``sys.executable`` must be a Python (not a
    bundled application). Wherever a worker would run the calling script's own code again as it
    starts (:func:`._worker.can_start`), 1."""
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1):
        raise ValueError(f"workers must be a whole number >= 1, got {workers!r}")
    if not _worker.can_start():
        return 1
    if workers is None:
        try:
            cores = len(os.sched_getaffinity(0))
        except (AttributeError, OSError):  # not Linux
            cores = os.cpu_count() or 1
        try:
            load = os.getloadavg()[0]
        except (AttributeError, OSError):  # Windows
            load = 0.0
        if cores <= 1 or getattr(sys, "frozen", False):  # a bundled application: no Python to start
            return 1
        return 2 if load <= cores - 1 else 1
    return min(int(workers), len(FIGURES))


def _rc_snapshot() -> dict:
    """The current rcParams, for a worker to draw with the caller's settings (its backend aside)."""
    import matplotlib as mpl

    return {k: v for k, v in mpl.rcParams.copy().items() if k != "backend"}


def reproduce(out_dir=DEFAULT_OUT_DIR, data=None, formats=("png", "pdf"), progress=True, workers=None) -> PaperReport:
    """Regenerate Section 3 of the seed paper: Figures 2-10, their data, and a report.

    Parameters
    ----------
    out_dir : str or Path
        Output directory (created if needed); default ``microimpact-paper``.
    data : dict of str -> path or (velocity, restitution), optional
        Measured restitution data to overlay on Fig. 2, e.g.
        ``{"silicon": "wall1990_silicon.csv"}`` (CSV columns ``velocity`` [m/s],
        ``restitution`` [-]). The paper's Wall et al. (1990) points are not shipped.
    formats : sequence of str
        Image formats among ``png``, ``pdf``, ``svg``, ``eps`` (the HTML report always embeds PNG).
    progress : bool or callable
        ``True``: a progress bar on stderr (:func:`microimpact.io.progress_bar`); a callable
        receives one line per figure (``"[3/9] fig04 ... done (0.41 s)"``); ``False``: quiet.
    workers : int, optional
        Processes drawing the figures (this one included). Default: 2 when this process may run
        on more than one core and a whole core is idle (1-minute load average at most the cores
        less one), else 1. The files are the same bytes whatever the number.

    Notes
    -----
    With more than one worker, the other processes (new Python interpreters, started at once)
    draw figures from their tables while this one draws others; they write no file (this
    process writes every file, in the order of the figures), they draw with this process's
    rcParams and in the package's style, and a figure they cannot draw is drawn here. They do
    not see fonts added at run time (``matplotlib.font_manager.fontManager.addfont``): use
    ``workers=1`` for such figures. An interrupt ends them with this call. A new interpreter
    first runs the calling script's top level again (:mod:`multiprocessing`'s ``spawn``), so
    from a script whose top level does more than define and import (no
    ``if __name__ == "__main__":`` guard) the figures are drawn in this process alone.

    The output folder owns only what it wrote (:func:`microimpact.io.owned_directory`):
    its files are staged and committed only when all are complete; an existing
    ``out_dir`` is written into only when a manifest of an earlier run lists every
    file in it unchanged, and a data file inside it is refused.

    Returns
    -------
    PaperReport
    """
    t0 = time.perf_counter()
    if isinstance(formats, str):
        formats = [f for f in formats.split(",") if f.strip()]
    formats = [str(f).strip().lower().lstrip(".") for f in formats]
    bad = [f for f in formats if f not in _FORMATS]
    if bad or not formats:
        raise ValueError(f"formats must be among {', '.join(_FORMATS)}, got {', '.join(formats) or 'none'}")
    n_proc = _processes(workers)
    inputs = [v for v in (data or {}).values() if isinstance(v, (str, os.PathLike))]
    data = _normalize_data(data)
    emit = _progress_fn(progress)
    from ..io import check_output_path

    out = Path(out_dir)
    check_output_path(out, directory=True)
    # The other processes start now: their imports overlap this one's work.
    pool = _worker.Pool(n_proc - 1) if n_proc > 1 else None
    try:
        return _reproduce(PaperReport(out_dir=out), t0, data, formats, inputs, pool, progress, emit)
    finally:
        if pool is not None:
            pool.stop()


def _reproduce(report, t0, data, formats, inputs, pool, progress, emit) -> PaperReport:
    """:func:`reproduce` once its inputs are checked and its workers started (``pool``, or None)."""
    from ..io import atomic_write, owned_directory, progress_bar

    out = report.out_dir
    pngs = {}
    n = len(FIGURES)
    bar = progress_bar(n + 1, "paper", unit="step", disable=progress is not True)
    # Staged, then committed with a manifest of what was written (microimpact.io.owned_directory).
    with bar, owned_directory(out, "paper", inputs=inputs) as tmp:
        # Every table first (each is its figure's CSV): the figures are then drawn from them, here
        # from the first on and by the workers from the last on, until the two meet.
        tables, seconds = [], []
        for stem, title, _caption in FIGURES:
            t1 = time.perf_counter()
            bar.set_description(f"paper {stem}")
            table = _TABLES[stem](data)
            write_table(
                tmp / f"{stem}.csv", table, title=f"Fig. {int(stem[3:])}: {title}", columns=figs.COLUMNS, source=_SOURCE
            )
            report.tables[stem] = out / f"{stem}.csv"
            tables.append((stem, table))
            seconds.append(time.perf_counter() - t1)
        # The comparison too, while a worker is still starting: at the end it would run alone.
        t1 = time.perf_counter()
        report.comparison = compare_with_paper()
        report.statements = check_statements()
        compared = time.perf_counter() - t1
        jobs = {"lo": 0, "hi": n - 1}  # next figure drawn here / by a worker (._worker.Feeder)
        lock = threading.Lock()
        taken = {}
        answers = {}
        rc = _rc_snapshot() if pool else None
        feeders = (
            [_worker.Feeder(pool.executor, r, jobs, lock, taken, tables, formats, rc) for r in pool.ready]
            if pool
            else []
        )
        written = 0

        def write_ready():
            nonlocal written
            while written < n and written in answers:
                stem, title, _caption = FIGURES[written]
                images, said, spent = answers.pop(written)
                for message, category, filename, lineno in said:
                    warnings.warn_explicit(message, category, filename, lineno)
                pngs[stem] = images["png"]
                files = []
                for fmt in formats:
                    with atomic_write(tmp / f"{stem}.{fmt}", "wb") as fh:
                        fh.write(images[fmt])
                    files.append(out / f"{stem}.{fmt}")
                report.figures[stem] = files
                bar.update(1)
                emit(f"[{written + 1}/{n}] {stem} {title} ... done ({seconds[written] + spent:.2f} s)")
                written += 1

        def draw_here(i):
            t1 = time.perf_counter()
            images = _draw.draw_figure(*tables[i], formats)
            answers[i] = (images, [], time.perf_counter() - t1)

        try:
            while True:
                with lock:
                    if jobs["lo"] > jobs["hi"]:
                        break
                    i = jobs["lo"]
                    jobs["lo"] += 1
                bar.set_description(f"paper {tables[i][0]}")
                draw_here(i)
                write_ready()
        finally:
            for f in feeders:  # no new job for a worker, whatever ends the loop
                f.stop = True
        for i in sorted(taken):  # what the workers took: their answer, or drawn here
            # (exception() rather than result(): what a worker raised, whatever its kind, is its failure;
            # an interrupt of this process while it waits still propagates)
            if taken[i].exception() is None:
                answers[i] = taken[i].result()
            else:  # the worker failed this figure: it is drawn here, where its error shows
                draw_here(i)
            write_ready()
        write_ready()
        if written != n:  # pragma: no cover - every figure is drawn here or by a worker
            raise RuntimeError(f"paper: {n - written} figures were not drawn")
        t1 = time.perf_counter() - compared
        head = f"[report] comparing {len(PAPER_QUOTES)} quoted numbers and {len(PAPER_STATEMENTS)} statements ..."
        bar.set_description("paper report")
        write_table(
            tmp / "comparison.csv",
            {
                k: np.array([r[k] for r in report.comparison], dtype=object)
                for k in (
                    "name",
                    "quantity",
                    "where",
                    "unit",
                    "quoted",
                    "computed",
                    "relative_difference",
                    "agrees",
                    "note",
                )
            },
            title="The seed's quoted numbers (Section 3) against the model now",
            source=_SOURCE,
            columns={
                "name": ("", "identifier"),
                "quantity": ("", "what is compared"),
                "where": ("", "place in the paper"),
                "unit": ("", "unit of quoted and computed"),
                "quoted": ("unit", "value printed in the paper"),
                "computed": ("unit", "value computed now"),
                "relative_difference": ("1", "(computed - quoted) / quoted"),
                "agrees": ("1", f"1 if |relative_difference| <= {TOLERANCE}"),
                "note": ("", "explanation"),
            },
        )
        report.comparison_csv = out / "comparison.csv"
        report.elapsed = time.perf_counter() - t0
        report.markdown = out / "report.md"
        report.html = out / "report.html"
        blocks = report_blocks(report, data, formats)
        with atomic_write(tmp / "report.md") as fh:
            fh.write(to_markdown(blocks, report))
        with atomic_write(tmp / "report.html") as fh:
            fh.write(to_html(blocks, pngs))
        bar.update(1)
    report.elapsed = time.perf_counter() - t0
    tail = f" done ({time.perf_counter() - t1:.2f} s)"
    emit(head + tail)
    return report
