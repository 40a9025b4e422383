"""The benchmark suite of microimpact (pytest-benchmark): ratios taken in one run, and memory peaks.

Run it with ``microimpact bench`` (a front end that prints the table) or directly::

    python -m pytest benchmarks --size quick --ratios-json bench.json

Each benchmark file times a subject and its baseline as separate pytest-benchmark tests of one
group (best round kept: ``stats.min``). At the end of the session the ratios the project tracks
are formed from those best times and printed as one table, and written as JSON with
``--ratios-json``:

1. ``outcome_vs_ode``: outcome and contact times in closed form against Newton's equation
   integrated by an ODE solver (the seed's route), and their largest relative difference;
2. ``restitution_vs_copy``: restitution alone against copying the array (memory bandwidth);
3. ``impact_latency``: ``pair.impact(50.0)`` and ``pair.restitution(50.0)`` against plain-Python
   functions computing the same (``benchmarks/_reference.py``, and the physics core's scalar
   ``outcome`` where it exists);
4. ``wall_vs_copy``: the wall interaction against copying its inputs;
5. ``memory``: peaks of traced allocations (:mod:`tracemalloc`) per point of an array call and of
   an eager against a chunked sweep;
6. ``paper``: ``microimpact paper`` end to end (not in ``tiny`` mode);
7. ``outcome_vs_copy``: the full outcome with times for many speeds against copying them;
8. ``threads_1e3``: the compiled loop on 1e3 speeds, as the library runs it against threads forced;
9. ``startup``: small commands against the import each cannot avoid (numpy, xarray, numba), first array call;
10. ``c_wall``: the exported C wall function per call in a C loop, against the loop only copying.
11. ``warm_start``: what needs the oblique universal table, in a new process with the cache warm,
    against ``python -c "import numpy"`` run in turn with it.
12. ``fit_models``: a fit of each model against the seed's fit on the same data, as the library
    runs it (``e`` alone) and with ``e`` from the full outcome at every point.
13. ``csv_sweep``: a sweep written to CSV against the same sweep written to NetCDF.
14. ``small_arrays``: what an array call on 1e3 speeds adds to its compiled loop.

No benchmark asserts a timing; accuracies (closed form against ODE, every path against the
reference restitution) are asserted.
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

import pytest

#: Problem sizes of each mode (``--size``).
SIZES = {
    "full": dict(outcome=10**6, ode=50, restitution=10**7, wall=10**6, memory=10**6, sweep=10**7, paper=True),
    "quick": dict(outcome=10**4, ode=10, restitution=10**5, wall=10**4, memory=10**5, sweep=10**5, paper=True),
    "tiny": dict(outcome=2000, ode=2, restitution=20000, wall=1000, memory=10**4, sweep=2000, paper=False),
}

#: Targets the project tracks, as `microimpact bench` reports them (the README states the speed goals).
TARGETS = {
    "outcome_vs_ode": "closed form >= 1e4x faster than the ODE, max rel. difference < 1e-8",
    "restitution_vs_copy": "<= 2x the time of copying the array (numba; <= 5x without)",
    "impact_latency": "pair.impact(50.0), its large-strain warning included, and pair.restitution(50.0) <= 2x "
    "plain-Python closed forms returning the same numbers",
    "wall_vs_copy": "wall interaction <= 15x copying its inputs",
    "memory": "chunked sweep peak < 500 MB at 1e7 points",
    "paper": "microimpact paper end to end < 20 s and <= 10x python -c 'import matplotlib.pyplot'",
    "outcome_vs_copy": "full outcome with times <= 100x copying the speeds (1e7)",
    "threads_1e3": "1e3 speeds: the default never slower than the serial loop (threads only where they pay)",
    "startup": "impact 50, history 50 and export <= 2x python -c 'import numpy'; small sweep and compare "
    "<= 2x 'import xarray'; first compiled call (1e6, whole process) <= 2.5x 'import numba'; "
    "first array call of 1e3 speeds <= 50 ms",
    "c_wall": "the exported C wall function no slower than its form of 2026-11-24 beside it "
    "(44 ns per call where the goal was set)",
    "warm_start": "oblique --alumina, a first compliant wall_interaction, export --tangential mindlin: "
    "each <= 0.3 s in a new process with the cache warm (on a host where import numpy takes 0.15 s: "
    "where it takes longer, <= 2x import numpy beside it)",
    "fit_models": "any model's fit <= 5x the seed's on the same data (ranking computes only e)",
    "csv_sweep": "a sweep (1e7 points at full size) to CSV <= 3x the same sweep to NetCDF",
    "small_arrays": "1e3 speeds: pair.restitution(V) adds <= 10 us to its compiled loop (pair.impact reported)",
}

TITLES = {
    "outcome_vs_ode": "outcome + contact times, closed form vs ODE",
    "restitution_vs_copy": "restitution alone vs copying the array",
    "impact_latency": "one impact through the object API vs plain Python",
    "wall_vs_copy": "wall interaction vs copying its inputs",
    "memory": "memory peaks (tracemalloc)",
    "paper": "microimpact paper, end to end",
    "outcome_vs_copy": "full outcome and contact times vs copying the speeds",
    "threads_1e3": "compiled loop on 1e3 speeds: serial vs threads",
    "startup": "start-up of a new process",
    "c_wall": "the exported C wall function, in a C loop",
    "warm_start": "warm start of what needs the oblique universal table",
    "fit_models": "a fit of each model vs a fit of the seed (fit --models ranking)",
    "csv_sweep": "a sweep to CSV vs the same sweep to NetCDF",
    "small_arrays": "fixed cost of an array call on 1e3 speeds",
}

ORDER = list(TARGETS)

PAPER_PAIR = dict(radius=2.45e-6, density=1350.0, effective_modulus=1.31e9, limiting_pressure=156e6)


@pytest.hookimpl(tryfirst=True)
def pytest_cmdline_main(config):
    """One process: the test suite's ``-n auto`` (``addopts`` in ``pyproject.toml``) does not apply here.

    Under pytest-xdist, pytest-benchmark disables itself, and the ratios are measured side by side in
    one process anyway. This runs before xdist's own hook (a conftest's ``tryfirst`` comes first).
    """
    if getattr(config.option, "numprocesses", None):
        config.option.numprocesses = 0


def pytest_addoption(parser):
    group = parser.getgroup("microimpact benchmarks")
    group.addoption("--size", choices=sorted(SIZES), default="quick", help="problem sizes (default quick)")
    group.addoption("--ratios-json", default=None, metavar="FILE", help="write the ratio table as JSON")


class Record:
    """Best times [s] and metrics of one session, grouped by benchmark key."""

    def __init__(self, mode):
        self.mode = mode
        self.times: dict[str, dict[str, float]] = {}
        self.metrics: dict[str, dict] = {}
        self.notes: dict[str, list[str]] = {}

    def time(self, key, variant, seconds):
        self.times.setdefault(key, {})[variant] = float(seconds)

    def metric(self, key, name, value):
        self.metrics.setdefault(key, {})[name] = value

    def note(self, key, text):
        self.notes.setdefault(key, []).append(text)


def pytest_configure(config):
    config._microimpact_record = Record(config.getoption("--size"))


#: Memory touched once before a full run [bytes] (see :func:`_touch_memory`).
PRETOUCH = 4 * 2**30


@pytest.fixture(scope="session", autouse=True)
def _touch_memory(request):
    """Touch up to 4 GB once before a full run, then free it.

    On a virtual machine the first write to memory the guest has never used is a page fault in the
    host too: measured here, filling a fresh 88 MB result took 200 ms instead of 6 ms, at random,
    depending on whether the kernel handed out pages used before. The copies a subject is compared
    with write into arrays allocated once, so that artefact fell on the subject alone (the wall
    interaction read 9x or 45x its copy from one run to the next). Touched once, the pages stay
    backed, and every variant pays the same ordinary cost for a new array.
    """
    if request.config.getoption("--size") != "full":
        return
    import numpy as np

    try:
        free = os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        free = 0
    size = min(PRETOUCH, free // 4)
    if size > 0:
        t0 = time.perf_counter()
        block = np.ones(size // 8)
        del block
        request.config._microimpact_record.note(
            "memory", f"{size / 2**30:.2g} GB of memory touched once before the run ({time.perf_counter() - t0:.1f} s)"
        )


@pytest.fixture(scope="session")
def record(request) -> Record:
    return request.config._microimpact_record


@pytest.fixture(scope="session")
def size(request) -> dict:
    return SIZES[request.config.getoption("--size")]


@pytest.fixture(scope="session")
def pair():
    from microimpact import ContactPair

    return ContactPair.sphere_on_flat(**PAPER_PAIR, label="NH4Fl on silicon (seed Sec. 3)")


@pytest.fixture
def timed(benchmark, record):
    """``timed(key, variant, fn, rounds=, iterations=)``: time ``fn`` with pytest-benchmark, keep its best.

    The best round, per call (pytest-benchmark divides each round by ``iterations``), is
    recorded under ``key``/``variant``. With ``--benchmark-disable``
    the same rounds are timed here with :func:`time.perf_counter` instead.
    """

    def run(key, variant, fn, *, rounds=5, iterations=1, warmup_rounds=1):
        benchmark.group = key
        benchmark.name = variant
        result = benchmark.pedantic(fn, rounds=rounds, iterations=iterations, warmup_rounds=warmup_rounds)
        stats = getattr(getattr(benchmark, "stats", None), "stats", None)
        if stats is not None:
            best = stats.min
        else:  # --benchmark-disable: pytest-benchmark ran fn once and kept no statistics
            best = math.inf
            for _ in range(rounds):
                t0 = time.perf_counter()
                for _ in range(iterations):
                    fn()
                best = min(best, (time.perf_counter() - t0) / iterations)
        record.time(key, variant, best)
        return result

    return run


# ----------------------------------------------------------------------------- the table


def _fmt_t(seconds):
    if seconds is None or not math.isfinite(seconds):
        return "n/a"
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("us", 1e-6), ("ns", 1e-9)):
        if seconds >= scale:
            return f"{seconds / scale:.3g} {unit}"
    return f"{seconds / 1e-9:.3g} ns"


def _entry(key, rec: Record) -> dict | None:
    t = rec.times.get(key, {})
    m = dict(rec.metrics.get(key, {}))
    if not t and not m:
        return None
    rows, headline, met = [], "", None
    if key == "outcome_vs_ode" and {"closed_per_impact", "ode_per_impact"} <= set(t):
        ratio = t["ode_per_impact"] / t["closed_per_impact"]
        worst = m.get("max_rel_diff", math.nan)
        m["speed_ratio"] = ratio
        met = bool(ratio >= 1e4 and worst < 1e-8)
        headline = f"{ratio:.2g}x faster, max rel. diff. {worst:.1g}"
        rows = [
            (f"closed form, per impact ({m.get('n', '?'):.0e} speeds)", _fmt_t(t["closed_per_impact"])),
            (f"ODE (DOP853, rtol 1e-12), per impact ({m.get('n_ode', '?')} speeds)", _fmt_t(t["ode_per_impact"])),
            ("speed ratio", f"{ratio:.3g}"),
            (f"max rel. difference ({m.get('worst_quantity', '?')})", f"{worst:.2g}"),
        ]
    elif key in ("restitution_vs_copy", "wall_vs_copy") and "copy" in t:
        copy = t["copy"]
        rows.append(("copy (np.copyto into preallocated arrays)", _fmt_t(copy)))
        ratios = {}
        for variant, s in t.items():
            if variant == "copy":
                continue
            ratios[variant] = s / copy
            rows.append((variant, f"{_fmt_t(s)} = {s / copy:.3g}x copy"))
        m["ratios"] = ratios
        if key == "restitution_vs_copy" and ratios:
            best = min(ratios, key=ratios.get)
            m["best"] = best
            met = bool(ratios[best] <= 2.0) if rec.mode == "full" else None  # the target is set at 1e7
            headline = f"{ratios[best]:.2g}x copy ({best})"
        elif ratios:
            (variant, r), *_ = ratios.items()
            headline = f"{r:.3g}x copy"
            met = bool(r <= 15.0) if rec.mode == "full" else None
    elif key == "impact_latency" and "pair.impact(50.0)" in t:
        api = t["pair.impact(50.0)"]
        headline = f"{_fmt_t(api)}"
        if "outcome_reference (plain Python)" in t:
            quiet = t.get("pair.impact(50.0, warn=False)", api)
            r = quiet / t["outcome_reference (plain Python)"]
            read = t.get("pair.impact(50.0, warn=False), every field read", quiet)
            r_read = read / t["outcome_reference (plain Python)"]
            r_warn = api / t["outcome_reference (plain Python)"]
            # the warning included (a filter hides it); reading the fields back is reported apart
            met = bool(r_warn <= 2.0)
            if {"pair.restitution(50.0)", "restitution_reference (plain Python)"} <= set(t):
                r_e = t["pair.restitution(50.0)"] / t["restitution_reference (plain Python)"]
                met = met and bool(r_e <= 2.0)
            headline = (
                f"{_fmt_t(api)} = {r_warn:.2g}x plain Python with the warning ({r:.2g}x without; "
                f"{r_read:.2g}x with all 18 fields then read back)"
            )
        for variant, s in t.items():
            rows.append((variant, _fmt_t(s)))
        ratios = {}
        if "core outcome (plain Python)" in t:
            ratios["pair.impact / core outcome"] = api / t["core outcome (plain Python)"]
        if {"pair.restitution(50.0)", "restitution_reference (plain Python)"} <= set(t):
            ratios["pair.restitution / plain-Python e"] = (
                t["pair.restitution(50.0)"] / t["restitution_reference (plain Python)"]
            )
        if "outcome_reference (plain Python)" in t:
            ratios["pair.impact / plain-Python outcome"] = api / t["outcome_reference (plain Python)"]
            if "pair.impact(50.0, warn=False)" in t:
                ratios["pair.impact(warn=False) / plain-Python outcome"] = (
                    t["pair.impact(50.0, warn=False)"] / t["outcome_reference (plain Python)"]
                )
            read = t.get("pair.impact(50.0, warn=False), every field read")
            if read is not None:
                ratios["pair.impact(warn=False), every field read / plain-Python outcome"] = (
                    read / t["outcome_reference (plain Python)"]
                )
        for name, r in ratios.items():
            rows.append((name, f"{r:.3g}x"))
        m["ratios"] = ratios
    elif key == "outcome_vs_copy" and {"copy", "pair.impact (18 fields)"} <= set(t):
        r = t["pair.impact (18 fields)"] / t["copy"]
        met = bool(r <= 100.0) if rec.mode == "full" else None
        headline = f"{r:.3g}x copy"
        rows = [
            ("copy", _fmt_t(t["copy"])),
            ("pair.impact (18 fields)", f"{_fmt_t(t['pair.impact (18 fields)'])} = {r:.3g}x copy"),
        ]
    elif key == "threads_1e3" and {"default", "serial forced"} <= set(t):
        r = t["default"] / t["serial forced"]
        met = bool(r <= 1.1)
        headline = f"the default takes {r:.3g}x the serial loop"
        if "threads forced" in t:
            headline += f" (threads forced: {t['threads forced'] / t['serial forced']:.3g}x)"
        rows = [(k, _fmt_t(s)) for k, s in t.items()]
    elif key == "startup" and t:
        from test_startup import GOALS

        rows = [(k, _fmt_t(s)) for k, s in t.items()]
        parts, oks = [], []
        for name, (base, goal) in GOALS.items():
            b = t.get(f"python -c '{base}'")
            if name in t and b:
                r = m.get(f"ratio: {name}", t[name] / b)
                oks.append(r <= goal)
                rows.append((f"{name} / {base}", f"{r:.3g}x (goal <= {goal:g}x)"))
                parts.append(f"{name.split(' (')[0].removeprefix('microimpact ')} {r:.2g}x")
        first = t.get("first array call, 1e+03 speeds")
        if first is not None:
            parts.append(f"first call (1e3) {_fmt_t(first)}")
            oks.append(first <= 0.05)
        met = all(oks) if oks else None
        headline = ", ".join(parts)
    elif key == "memory":
        mb = 1024.0**2
        for name, value in m.items():
            if name.endswith("_peak_bytes"):
                rows.append((f"{name.removesuffix('_peak_bytes')}: peak", f"{value / mb:.3g} MB"))
            elif name.endswith("_peak_per_point"):
                rows.append((f"{name.removesuffix('_peak_per_point')}: peak per point", f"{value:.3g} B"))
        if "sweep_chunked_peak_bytes" in m:
            headline = f"chunked sweep peak {m['sweep_chunked_peak_bytes'] / mb:.0f} MB"
            if "sweep_eager_peak_bytes" in m:
                headline += f" (eager {m['sweep_eager_peak_bytes'] / mb:.0f} MB)"
            met = bool(m["sweep_chunked_peak_bytes"] < 500 * mb) if rec.mode == "full" else None
    elif key == "c_wall" and any("rigid" in k for k in t):
        call_name = next(k for k in t if "rigid" in k)
        call = t[call_name]
        then = next((s for k, s in t.items() if "2026-11-24" in k), None)
        # the goal is a throughput figure: the rigid call must not be slower than its reference form
        # (44 ns where the goal was set); side by side, a slower host slows both forms alike
        met = bool(call <= then) if then else bool(call <= 55e-9)
        headline = f"{call * 1e9:.3g} ns per call (rigid)"
        rows = [(k, _fmt_t(s)) for k, s in t.items()]
        if then:
            headline += f", {call / then:.3g}x its form of 2026-11-24 ({then * 1e9:.3g} ns beside it)"
            rows.append(("ratio (rigid / its form of 2026-11-24)", f"{call / then:.3g}x"))
        copy = t.get("the same loop copying inputs to outputs")
        if copy:
            headline += f", {call / copy:.3g}x the loop copying its data"
            rows.append(("ratio (rigid / copy)", f"{call / copy:.3g}x"))
        compliant = next((s for k, s in t.items() if "mindlin" in k), None)
        if compliant:
            headline += f"; compliant {compliant * 1e9:.3g} ns"
        additive = t.get("adhesion G = 0.1 J/m^2: additive rule")
        whole = t.get("adhesion G = 0.1 J/m^2: whole law's table")
        if additive and whole:
            headline += f"; whole adhesive law {whole / additive:.3g}x the additive rule"
            rows.append(("ratio (whole law's table / additive rule)", f"{whole / additive:.3g}x"))
    elif key == "warm_start" and len(t) > 1:
        base = t.get("python -c 'import numpy'")
        subjects = {k: s for k, s in t.items() if k != "python -c 'import numpy'"}
        for k, s in t.items():
            rows.append((k, _fmt_t(s) + (f" = {s / base:.3g}x import numpy" if base and k in subjects else "")))
        slowest = max(subjects, key=subjects.get)
        # The goal's 0.3 s is twice a new process's import numpy on this host when it is quiet (148-152
        # ms measured). Load slows both alike, so on a slower host the goal is that ratio, timed in turn.
        met = bool(subjects[slowest] <= 0.3 or (base and subjects[slowest] <= 2.0 * base))
        headline = f"slowest {_fmt_t(subjects[slowest])} ({slowest})"
        if base:
            headline += f" = {subjects[slowest] / base:.3g}x import numpy ({_fmt_t(base)})"
    elif key == "fit_models" and "thornton_ning_2016" in t and len(t) > 1:
        from test_fit_models import BEFORE

        seed = t["thornton_ning_2016"]
        rows.append(("seed (thornton_ning_2016), p_y free", _fmt_t(seed)))
        ratios, before = {}, {}
        for variant, s in t.items():
            if variant == "thornton_ning_2016" or variant.endswith(BEFORE):
                continue
            ratios[variant] = s / seed
            b = t.get(variant + BEFORE)
            if b is not None:
                before[variant] = b / seed
            was = f" (before: {before[variant]:.3g}x)" if variant in before else ""
            rows.append((variant, f"{_fmt_t(s)} = {s / seed:.3g}x the seed{was}"))
        m["ratios"] = ratios
        m["ratios_before"] = before
        if ratios:
            worst = max(ratios, key=ratios.get)
            over = sorted(k for k, r in ratios.items() if r > 5.0)
            met = not over
            headline = f"worst {ratios[worst]:.3g}x the seed ({worst})"
            if "liggghts_thornton_ning" in ratios:
                was = before.get("liggghts_thornton_ning")
                headline += f"; LIGGGHTS law {ratios['liggghts_thornton_ning']:.3g}x" + (
                    f" (was {was:.3g}x)" if was else ""
                )
            if over:
                headline += f"; {len(over)} over 5x"
    elif key == "csv_sweep" and {"CSV", "NetCDF"} <= set(t):
        r = t["CSV"] / t["NetCDF"]
        met = bool(r <= 3.0) if rec.mode == "full" else None  # the goal is set at 1e7 points
        headline = f"{r:.3g}x NetCDF ({m.get('points', 0):.0e} points)"
        rows = [("NetCDF", _fmt_t(t["NetCDF"])), ("CSV", f"{_fmt_t(t['CSV'])} = {r:.3g}x NetCDF")]
    elif key == "small_arrays" and t:
        fixed = {}
        for call, loop in (
            ("pair.restitution(V)", "restitution loop alone"),
            ("pair.impact(V, warn=False)", "outcome loop alone"),
        ):
            if {call, loop} <= set(t):
                fixed[call] = t[call] - t[loop]
                rows.append((call, f"{_fmt_t(t[call])} = loop {_fmt_t(t[loop])} + {_fmt_t(fixed[call])}"))
        if "restitution loop the library runs" in t:
            rows.append(("restitution loop the library runs, alone", _fmt_t(t["restitution loop the library runs"])))
        m["fixed_s"] = fixed
        if "pair.restitution(V)" in fixed:
            met = bool(fixed["pair.restitution(V)"] <= 10e-6)
        headline = ", ".join(f"{k.split('(')[0]} +{_fmt_t(v)}" for k, v in fixed.items())
    elif key == "paper" and "end to end" in t:
        s = t["end to end"]
        met = bool(s < 20.0)
        headline = _fmt_t(s)
        rows = [("wall-clock time, subprocess", _fmt_t(s))]
        mpl = t.get("python -c 'import matplotlib.pyplot'")
        if mpl:
            met = met and bool(s / mpl <= 10.0)
            headline += f" = {s / mpl:.3g}x import matplotlib.pyplot"
            rows += [("python -c 'import matplotlib.pyplot'", _fmt_t(mpl)), ("ratio", f"{s / mpl:.3g}x")]
            one = t.get("end to end, one process")
            if one:
                rows += [("one process (--workers 1)", f"{_fmt_t(one)} = {one / mpl:.3g}x")]
        if m.get("load average (1 min)"):
            lo, hi = m["load average (1 min)"]
            rows += [("1-minute load average during the runs", f"{lo:.2f}-{hi:.2f}")]
    if not headline:
        headline = "incomplete: " + ", ".join(sorted(t)) if t else "no timings"
    return {
        "key": key,
        "number": ORDER.index(key) + 1,
        "title": TITLES[key],
        "target": TARGETS[key],
        "headline": headline,
        "met": met,
        "times_s": t,
        "metrics": m,
        "rows": rows,
        "notes": rec.notes.get(key, []),
    }


def build_report(rec: Record) -> dict:
    """The session's results as a JSON-able dict: machine, mode and one entry per benchmark."""
    from microimpact.cli.bench import machine_info

    results = [e for e in (_entry(k, rec) for k in ORDER) if e is not None]
    return {"mode": rec.mode, "date": time.strftime("%Y-%m-%d"), "machine": machine_info(), "results": results}


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    from microimpact.cli.bench import format_table

    rec = config._microimpact_record
    report = build_report(rec)
    terminalreporter.section("microimpact: ratios")
    terminalreporter.write_line(format_table(report))
    path = config.getoption("--ratios-json")
    if path:
        path = Path(path)
        tmp = path.with_name(path.name + f".tmp{os.getpid()}")
        tmp.write_text(json.dumps(report, indent=2, default=float))
        tmp.replace(path)
