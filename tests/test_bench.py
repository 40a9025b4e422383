"""The benchmark suite runs and reports sane numbers (no timed assertions: timings are reported, not tested)."""

import json
import math
import pathlib
import subprocess
import sys
import warnings

import numpy as np
import pytest

from microimpact.cli import bench, main
from microimpact.pair import ContactPair, LargeStrainWarning

ROOT = pathlib.Path(__file__).resolve().parents[1]


def numbers(obj):
    """Every int/float inside a JSON structure."""
    if isinstance(obj, bool):
        return []
    if isinstance(obj, (int, float)):
        return [obj]
    if isinstance(obj, dict):
        return [x for v in obj.values() for x in numbers(v)]
    if isinstance(obj, list):
        return [x for v in obj for x in numbers(v)]
    return []


@pytest.fixture(scope="module")
def tiny_report(tmp_path_factory):
    path = tmp_path_factory.mktemp("bench") / "bench.json"
    rc = main(["bench", "--tiny", "--json", str(path)])
    assert rc == 0
    return json.loads(path.read_text())


def test_bench_command_writes_report(tiny_report, capsys):
    r = tiny_report
    assert r["mode"] == "tiny"
    for key in ("platform", "cpu", "cores", "numpy", "scipy", "backend"):
        assert key in r["machine"]
    assert [x["key"] for x in r["results"]] == bench.BENCHMARKS
    assert [x["number"] for x in r["results"]] == [1, 2, 3, 4, 5, 6]
    for x in r["results"]:
        assert set(x) >= {"key", "title", "target", "status", "met", "metrics", "rows", "headline"}
        assert not x["status"].startswith("error"), x["status"]
        assert all(math.isfinite(v) and v >= 0 for v in numbers(x["metrics"])), x["metrics"]
    assert r["results"][5]["status"] == "skipped"  # tiny mode never runs the paper


def test_bench_figures_are_consistent(tiny_report):
    res = {x["key"]: x for x in tiny_report["results"]}
    m = res["restitution_vs_copy"]["metrics"]
    # every backend computes the same restitution as the reference function
    assert "numpy" in m["backends"]
    for b in m["backends"].values():
        assert b["max_rel_diff"] < 1e-14
        assert b["ratio"] == pytest.approx(b["time_s"] / m["copy_s"])
    m = res["impact_latency"]["metrics"]
    assert m["scalar_vs_array_max_rel_diff"] < 1e-13
    m = res["outcome_vs_ode"]["metrics"]
    if res["outcome_vs_ode"]["status"] == "ok":  # closed form and ODE agree (issue 3's 1e-8)
        assert m["max_rel_diff"] < 1e-8
        assert m["speed_ratio"] == pytest.approx(m["ode_time_per_impact_s"] / m["closed_time_per_impact_s"])
    if res["sweep_memory"]["status"] == "ok":  # eager and dask give the same means
        assert res["sweep_memory"]["metrics"]["mean_rel_diff"] < 1e-12


def test_table_lists_every_benchmark(tiny_report):
    text = bench.format_table(tiny_report)
    assert "| # | benchmark | measured | target | met |" in text
    for x in tiny_report["results"]:
        assert x["title"] in text and x["target"] in text
    assert tiny_report["machine"]["cpu"] in text


def test_script_entry_point(tmp_path):
    out = tmp_path / "r.json"
    proc = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "run.py"), "--tiny", "--only", "2,3", "--json", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    report = json.loads(out.read_text())
    assert [x["number"] for x in report["results"]] == [2, 3]
    assert "restitution alone" in proc.stdout


@pytest.mark.parametrize("only", ["0", "7", "1,x"])
def test_bad_only(only, capsys):
    assert main(["bench", "--tiny", "--only", only, "--json", "-"]) == 2
    assert "only" in capsys.readouterr().err


def test_missing_module_is_reported_not_raised(monkeypatch):
    monkeypatch.setattr(bench, "_module_has", lambda module, name: None)
    r = bench.bench_wall(100)
    assert r["status"] == "not available yet" and r["met"] is None
    r = bench.bench_sweep(100)
    assert r["status"] == "not available yet"
    r = bench.bench_outcome_vs_ode(100, 2)
    assert r["status"] == "not available yet" and r["metrics"]["closed_time_per_impact_s"] > 0


def test_rel_diff():
    assert bench._rel_diff([1.0, 2.0, np.inf], [1.0, 2.0 * (1 + 1e-9), np.inf]) == pytest.approx(1e-9, rel=1e-6)
    assert bench._rel_diff([0.0], [0.0]) == 0.0


@pytest.mark.parametrize("V", [0.0, 5.0, 7.6, 30.0, 50.0, math.inf])
def test_scalar_wrapper_equals_pair_impact(V):
    # what ContactPair.impact will do for one float, once wired to impact_scalar
    pair = ContactPair.paper_case("silicon")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = pair.impact(V)
    b = bench.impact_via_scalar(pair, V, warn=False)
    for k, x in a.to_dict().items():
        y = getattr(b, k)
        assert type(y) is type(x), k  # numpy scalars, as the array path gives
        assert y == x or (np.isnan(x) and np.isnan(y)) or abs(y - x) <= 1e-13 * abs(x), (k, x, y)


def test_scalar_wrapper_warns_like_pair_impact():
    pair = ContactPair.paper_case("silicon")
    with pytest.warns(LargeStrainWarning, match="V = 50 m/s"):
        bench.impact_via_scalar(pair, 50.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        bench.impact_via_scalar(pair, 20.0)  # small strain: silent
