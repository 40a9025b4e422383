"""``microimpact bench`` runs the benchmark suite and prints its table (no timed assertions).

The suite itself (``benchmarks/``) asserts its accuracies; here the front end is checked: it
finds the suite, runs it (pytest-benchmark; skipped with the reason when that is missing),
turns its JSON into the table, and refuses bad options with status 2.
"""

import importlib.util
import json
import math
import os
import pathlib
import sys

import pytest

from microimpact.cli import bench, main

ROOT = pathlib.Path(__file__).resolve().parents[2]
SUITE = ROOT / "benchmarks"

needs_suite = pytest.mark.skipif(
    importlib.util.find_spec("pytest_benchmark") is None,
    reason="pytest-benchmark is not installed (pip install 'microimpact[bench]')",
)


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
    if importlib.util.find_spec("pytest_benchmark") is None:
        pytest.skip("pytest-benchmark is not installed (pip install 'microimpact[bench]')")
    cwd = tmp_path_factory.mktemp("bench")
    path = cwd / "bench.json"
    here = os.getcwd()
    os.chdir(cwd)  # the run leaves nothing in the working directory but the JSON
    try:
        rc = main(["bench", "--tiny", "--only", "1,2,4", "--suite", str(SUITE), "--json", str(path)])
    finally:
        os.chdir(here)
    assert rc == 0
    assert sorted(p.name for p in cwd.iterdir()) == ["bench.json"]  # no .benchmarks/ (pytest-benchmark's store)
    return json.loads(path.read_text())


@needs_suite
def test_bench_runs_the_suite(tiny_report):
    r = tiny_report
    assert r["mode"] == "tiny"
    for key in ("platform", "cpu", "cores", "numpy", "scipy"):
        assert key in r["machine"]
    assert [x["key"] for x in r["results"]] == ["outcome_vs_ode", "restitution_vs_copy", "wall_vs_copy"]
    assert [x["number"] for x in r["results"]] == [1, 2, 4]
    for x in r["results"]:
        assert not x["headline"].startswith(("incomplete", "no timings")), x
        assert all(math.isfinite(v) and v >= 0 for v in numbers(x["metrics"]) + numbers(x["times_s"])), x


@needs_suite
def test_bench_ratios_are_formed_from_the_timings(tiny_report):
    res = {x["key"]: x for x in tiny_report["results"]}
    t, m = res["outcome_vs_ode"]["times_s"], res["outcome_vs_ode"]["metrics"]
    assert m["speed_ratio"] == pytest.approx(t["ode_per_impact"] / t["closed_per_impact"])
    assert m["max_rel_diff"] < 1e-8  # closed form and ODE agree (issue 3's 1e-8)
    t, m = res["restitution_vs_copy"]["times_s"], res["restitution_vs_copy"]["metrics"]
    assert "pair.restitution" in m["ratios"] and "impact.restitution_coefficient" in m["ratios"]
    for variant, ratio in m["ratios"].items():
        assert ratio == pytest.approx(t[variant] / t["copy"])
    assert res["restitution_vs_copy"]["met"] is None  # the <= 5x target is judged at full size only


@needs_suite
def test_table_lists_every_benchmark(tiny_report, capsys):
    text = bench.format_table(tiny_report)
    assert "| # | benchmark | measured | target | met |" in text
    for x in tiny_report["results"]:
        assert x["title"] in text and x["target"] in text
    assert tiny_report["machine"]["cpu"] in text


def test_format_table_of_a_report():
    report = {
        "mode": "full",
        "date": "2026-01-01",
        "machine": {"cpu": "cpu X", "cores": 2, "usable_cores": 2, "platform": "p", "python": "3", "numpy": "2"},
        "results": [
            {
                "number": 3,
                "title": "latency",
                "headline": "12 us",
                "target": "< 20 us",
                "met": True,
                "rows": [("pair.impact(50.0)", "12 us")],
                "notes": ["core not there"],
            }
        ],
    }
    text = bench.format_table(report)
    assert "| 3 | **latency** | 12 us | < 20 us | yes |" in text
    assert "|  | pair.impact(50.0) | 12 us |  |  |" in text
    assert "note: core not there" in text
    assert text.splitlines()[0] == "machine: cpu X, 2 cores (2 usable), p"


@pytest.mark.parametrize("only", ["0", "15", "1,x", ","])  # 15: one past the last benchmark
def test_bad_only(only, capsys):
    assert main(["bench", "--tiny", "--only", only, "--json", "-"]) == 2
    assert "--only" in capsys.readouterr().err


def test_missing_suite_is_a_one_line_error(tmp_path, capsys, monkeypatch):
    assert main(["bench", "--suite", str(tmp_path), "--json", "-"]) == 2
    assert "--suite" in capsys.readouterr().err
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(bench, "__file__", str(tmp_path / "a" / "b" / "c" / "bench.py"))
    assert main(["bench", "--json", "-"]) == 2
    assert "source checkout" in capsys.readouterr().err


def test_missing_pytest_benchmark_names_the_extra(monkeypatch, capsys):
    real = importlib.util.find_spec
    monkeypatch.setattr(
        bench.importlib.util, "find_spec", lambda name, *a: None if name == "pytest_benchmark" else real(name, *a)
    )
    assert main(["bench", "--tiny", "--suite", str(SUITE), "--json", "-"]) == 2
    assert "microimpact[bench]" in capsys.readouterr().err


def test_find_suite_default_is_the_checkout(monkeypatch, tmp_path):
    monkeypatch.chdir(ROOT)
    assert bench.find_suite().resolve() == SUITE.resolve()
    in_tree = ROOT / "src" in pathlib.Path(bench.__file__).resolve().parents
    if in_tree:  # imported from the checkout's src/: found from anywhere
        monkeypatch.chdir(tmp_path)
        assert bench.find_suite() == SUITE.resolve()


def test_plain_python_reference_is_eq_27():
    sys.path.insert(0, str(SUITE))
    try:
        from _reference import restitution_reference
    finally:
        sys.path.remove(str(SUITE))
    from microimpact.impact import restitution_coefficient

    Vy = 7.52
    for V in (0.0, 5.0, 7.52, 7.6, 20.0, 50.0, 120.0, 1e4):
        assert restitution_reference(V, Vy) == pytest.approx(float(restitution_coefficient(V, Vy)), rel=1e-13)


def test_machine_info_names_the_machine():
    info = bench.machine_info()
    assert info["cores"] >= 1 and 1 <= info["usable_cores"] <= info["cores"]
    assert info["cpu"] and info["python"].count(".") == 2
    import numpy

    assert info["numpy"] == numpy.__version__


@needs_suite
def test_a_failing_suite_is_reported_with_status_1(tmp_path, capsys):
    # a suite whose benchmarks fail: the front end shows pytest's output and exits 1, printing no table
    (tmp_path / "conftest.py").write_text((SUITE / "conftest.py").read_text())
    for name in bench.FILES.values():
        (tmp_path / name).write_text("def test_broken():\n    assert False, 'broken on purpose'\n")
    assert main(["bench", "--tiny", "--only", "2", "--suite", str(tmp_path), "--json", "-"]) == 1
    err = capsys.readouterr().err
    assert "broken on purpose" in err and "the suite failed" in err
