"""Fault corpus, part 3: text and numbers from strangers.

Each case failed on the code before its check:

1. user text entering a LAMMPS or LIGGGHTS deck (a wall style, a parameter name) was pasted into
   it, so a line break added a command (``shell`` runs any program) and ``&``, ``$``, ``#`` and
   quotes changed what the code's parser read (LAMMPS manual, "Parsing rules");
2. an output could be one of the run's inputs or another of its outputs (``fit --plot`` wrote its
   image over the data it read, by name, through a symbolic link or a hard link);
3. empty items of comma lists, an empty material name, ``stick --particle`` without ``--diameter``,
   a finished write reported as an error when stdout cannot encode a path, repeated sweep values, a
   C trigraph out of a label, a path of the machine in the sources;
4. subnormal and extreme numbers that divided by zero inside a model instead of being named, or
   named a derived quantity (the mass) instead of the inputs, or made a search run without end.
"""

from __future__ import annotations

import dataclasses
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import microimpact as mi
from microimpact import dem
from microimpact._validation import check_pair, check_velocity
from microimpact.calibrate import calibrate
from microimpact.cexport import generate_c_source

from .test_faults import ROOT, _env, assert_one_line, run

DATA = "velocity,restitution\n5,1.0\n20,0.86\n50,0.72\n80,0.64\n"
PAIR = mi.ContactPair.paper_case("silicon")


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "data.csv").write_text(DATA)
    return tmp_path


def listing(folder):
    return sorted(p.name for p in folder.iterdir())


# ----------------------------------------------------------------------------- 1. DEM decks take words only
@pytest.fixture(scope="module")
def cal():
    return calibrate(PAIR, "linear_spring_dashpot", 50.0)


def _hostile(target):
    """Walls that, pasted into a deck, run ``touch target`` or change what the parser reads."""
    return [
        f"zplane 0.0 NULL\nshell touch {target}",
        f"zplane 0.0 NULL\r\nshell touch {target}",
        f"zplane 0.0\x0bshell touch {target}",
        "zplane 0.0 NULL &",
        "zplane ${x} NULL",
        "zplane $x NULL",
        "zplane $(1+1) NULL",
        "zplane 0.0 NULL # comment",
        'zplane "0.0" NULL',
        "zplane '0.0' NULL",
        'zplane """0.0""" NULL',
        "zplane 0.0 NULL;shell",
        "",
        "   ",
        "zplane 0.0 é",
    ]


@pytest.mark.parametrize("i", range(len(_hostile("FILE"))))
def test_hostile_walls_are_refused_by_every_printer(cal, tmp_path, i):
    wall = _hostile(tmp_path / "FILE")[i]
    calls = [
        lambda: cal.lammps(wall=wall),
        lambda: cal.liggghts(wall=wall),
        lambda: dem.deck(cal, "lammps", 50.0, wall=wall),
        lambda: dem.deck(cal, "liggghts", 50.0, wall=wall, geometry="sphere"),
        lambda: dem.lines(cal, "lammps", wall=wall),
    ]
    for call in calls:
        with pytest.raises(ValueError, match="wall") as info:
            call()
        assert repr(wall) in str(info.value)
    assert not (tmp_path / "FILE").exists()


@pytest.mark.parametrize("wall", [3, None, b"zplane 0.0"])
def test_a_wall_that_is_not_text_is_named(cal, wall):
    with pytest.raises(ValueError, match="wall"):
        cal.lammps(wall=wall)


@pytest.mark.parametrize(
    "wall", ["zplane 0.0 NULL", "zplane -1e-3 NULL", "zcylinder 1e-3", "region box_2", "zplane v_z NULL"]
)
def test_words_of_the_wall_grammar_pass(cal, wall):
    from microimpact._validation import check_dem_words

    assert check_dem_words("wall", wall) == wall
    assert f"{wall}\n" in cal.lammps(wall=wall) + "\n"


@pytest.mark.parametrize("where", ["model", "names"])
def test_a_hand_built_calibration_cannot_smuggle_a_line(cal, tmp_path, where):
    bad = f"limit_force\nshell touch {tmp_path / 'FILE'}"
    if where == "model":
        hand = dataclasses.replace(cal, model=bad)
    else:
        hand = dataclasses.replace(cal, names=cal.names + (bad,), params=cal.params + (0.0,))
    for call in (hand.lammps, hand.liggghts, lambda: dem.deck(hand, "lammps", 50.0)):
        with pytest.raises(ValueError, match=where if where == "names" else "model"):
            call()


@pytest.mark.parametrize("record", ["a b.txt", "x\nshell y", "r$x.txt", "..", "é.txt", "a/b.txt", ""])
def test_record_names_are_plain_ascii_file_names(cal, record):
    with pytest.raises(ValueError, match="record"):
        dem.deck(cal, "lammps", 50.0, record=record)


@pytest.mark.parametrize("poisson", ["0.3", "0.3\nshell x", 0.7, float("nan"), True])
def test_liggghts_poisson_is_a_number_in_range(cal, poisson):
    with pytest.raises(ValueError, match="poisson"):
        cal.liggghts(poisson=poisson)


@pytest.mark.parametrize("code", dem.CODES)
def test_a_legitimate_deck_still_runs_and_runs_nothing_else(cal, tmp_path, code):
    """The printed lines pass the new checks unchanged and run in the code; the hostile deck is never
    written, so its ``shell touch`` leaves no file."""
    exe = dem.find_code(code)
    if exe is None:
        pytest.skip(f"{code} is not installed (CI installs it)")
    target = tmp_path / "FILE"
    with pytest.raises(ValueError, match="wall"):
        dem.deck(cal, code, 50.0, wall=f"zplane 0.0{' NULL' if code == 'lammps' else ''}\nshell touch {target}")
    d = dem.deck(cal, code, 50.0, steps_per_contact=200)
    assert "shell" not in d.text and "$x" not in d.text
    res = dem.run(d, exe, keep=tmp_path / "run")
    assert abs(res["restitution"] / res["predicted_restitution"] - 1.0) < 1.0 / 200
    assert not target.exists()
    assert sorted(os.listdir(tmp_path)) == ["run"]


# ----------------------------------------------------------------------------- 2. no output is an input or another output
def _same_file(work, kind):
    """``(input name, output name)`` naming one file in ``work`` in the way ``kind`` says."""
    if kind == "name":
        (work / "data.png").write_text(DATA)
        return "data.png", "data.png"
    if kind == "symlink-input":
        (work / "data.png").write_text(DATA)
        os.symlink("data.png", work / "link.csv")
        return "link.csv", "data.png"
    if kind == "symlink-output":
        os.symlink("data.csv", work / "plot.png")
        return "data.csv", "plot.png"
    if kind == "hard-link":
        os.link(work / "data.csv", work / "hard.png")
        return "data.csv", "hard.png"
    raise AssertionError(kind)


@pytest.mark.parametrize("kind", ["name", "symlink-input", "symlink-output", "hard-link"])
@pytest.mark.parametrize("option", ["--plot", "--fig2"])
def test_fit_never_writes_over_its_data(work, capsys, kind, option):
    data, image = _same_file(work, kind)
    before = listing(work)
    rc, out, err = run(["fit", data, option, image], capsys)
    assert_one_line(rc, err, option, image, data)
    assert listing(work) == before
    assert (work / data).read_text() == DATA


def test_fit_outputs_are_distinct(work, capsys):
    rc, out, err = run(["fit", "data.csv", "--plot", "a.png", "--fig2", "./a.png"], capsys)
    assert_one_line(rc, err, "--plot", "--fig2", "a.png")
    assert listing(work) == ["data.csv"]


@pytest.mark.parametrize(
    "argv, first, second",
    [
        (["history", "50", "--out", "h.csv", "--plot", "h.png"], "--out", "--plot"),
        (["stick", "-G", "0.1", "--out", "h.csv", "--plot", "h.png"], "--out", "--plot"),
        (["compare", "10,50", "--out", "h.csv", "--plot", "h.png"], "--out", "--plot"),
    ],
    ids=["history", "stick", "compare"],
)
def test_two_outputs_of_one_run_through_a_link(work, capsys, argv, first, second):
    (work / "h.csv").write_text("old\n")
    os.symlink("h.csv", work / "h.png")
    rc, out, err = run(argv, capsys)
    assert_one_line(rc, err, first, second)
    assert (work / "h.csv").read_text() == "old\n"
    assert listing(work) == ["data.csv", "h.csv", "h.png"]


def test_export_fit_input_inside_the_output_folder_through_a_link(work, capsys):
    (work / "real").mkdir()
    (work / "real" / "m.csv").write_text(DATA)
    os.symlink("real", work / "out")
    rc, out, err = run(["export", "--out", "out", "--fit", "real/m.csv"], capsys)
    assert_one_line(rc, err, "--fit", "m.csv", "--out")
    assert listing(work / "real") == ["m.csv"] and (work / "real" / "m.csv").read_text() == DATA


def test_paper_data_inside_the_output_folder(work, capsys):
    rc, out, err = run(["paper", "--out", ".", "--quiet", "--data", "silicon=data.csv"], capsys)
    assert_one_line(rc, err, "--data silicon", "data.csv", "--out")
    assert listing(work) == ["data.csv"] and (work / "data.csv").read_text() == DATA


# ----------------------------------------------------------------------------- 3. leftovers
@pytest.mark.parametrize(
    "argv, word",
    [
        (["stick", "-G", "0.1", "--law", "additive,"], "--law"),
        (["stick", "-G", "0.1", "--law", ",additive"], "--law"),
        (["stick", "-G", "0.1", "--law", "additive,,additive"], "--law"),
        (["export", "--out", "e", "--dem", "lammps,"], "--dem"),
        (["export", "--out", "e", "--dem", ",liggghts"], "--dem"),
        (["export", "--out", "e", "--dem", ","], "--dem"),
        (["compare", "10,50", "--model", "thornton_ning_2016,"], "--model"),
        (["fit", "data.csv", "--free", "limiting_pressure,"], "--free"),
        (["paper", "--out", "p", "--formats", "png,"], "--formats"),
    ],
    ids=lambda x: " ".join(x) if isinstance(x, list) else x,
)
def test_empty_items_of_comma_lists(work, capsys, argv, word):
    rc, out, err = run(argv, capsys)
    assert_one_line(rc, err, word)
    assert listing(work) == ["data.csv"]


@pytest.mark.parametrize("name", ["", " "])
def test_an_empty_material_name_is_an_error_not_the_list(capsys, name):
    rc, out, err = run(["materials", name], capsys)
    assert_one_line(rc, err, "material", "empty")
    assert out == ""


def test_stick_with_materials_is_sized_by_its_diameters(capsys):
    argv = ["stick", "-G", "0.1", "--particle", "nh4fl", "--surface", "silicon", "1e-6,2e-6", "--json"]
    rc, out, err = run(argv, capsys)
    assert rc == 0, err
    rc2, out2, err2 = run(argv + ["--diameter", "5e-6"], capsys)
    assert rc2 == 0, err2
    import json

    a, b = json.loads(out), json.loads(out2)
    assert a["diameter"] == [1e-6, 2e-6]
    assert a["laws"] == b["laws"]  # the sizing diameter changes nothing: every size is resized


@pytest.mark.parametrize(
    "argv, written",
    [
        (["history", "50", "--out", "hé.csv"], "hé.csv"),
        (["stick", "-G", "0.1", "--out", "sé.csv"], "sé.csv"),
        (["fit", "dé.csv"], None),
        (["sweep", "--velocity", "10,20", "--out", "wé.csv", "-q"], "wé.csv"),
    ],
    ids=lambda x: " ".join(x) if isinstance(x, list) else str(x),
)
def test_an_ascii_stdout_does_not_turn_a_finished_write_into_an_error(tmp_path, argv, written):
    (tmp_path / "dé.csv").write_text(DATA)
    env = _env(PYTHONIOENCODING="ascii", LANG="C", LC_ALL="C")
    proc = subprocess.run(
        [sys.executable, "-m", "microimpact", *argv], cwd=tmp_path, env=env, capture_output=True, timeout=300
    )
    assert proc.returncode == 0, proc.stderr.decode(errors="replace")
    assert b"Traceback" not in proc.stderr and b"error" not in proc.stderr
    if written is not None:
        assert (tmp_path / written).stat().st_size > 0
        assert written.encode("ascii", "backslashreplace") in proc.stdout


@pytest.mark.parametrize(
    "kw", [{"velocity": [10.0, 10.0]}, {"velocity": [10.0, 20.0, 10.0]}, {"velocity": 10.0, "radius": [1e-6, 1e-6]}]
)
def test_a_sweep_refuses_repeated_values(kw):
    from microimpact.sweep import sweep

    name = next(k for k, v in kw.items() if np.ndim(v))
    with pytest.raises(ValueError, match=f"{name} has the value .* more than once"):
        sweep(**kw)
    assert sweep(**{k: (v[:1] + [v[0] * 2] if np.ndim(v) else v) for k, v in kw.items()}).sizes[name] == 2


TRIGRAPH = re.compile(r"\?\?[=/'()!<>-]")


@pytest.mark.parametrize("label", ["a ??/ b", "??=define X", "é?/", "*??/", "x ???/ y", "??" * 5 + "/"])
def test_no_trigraph_reaches_the_c_source(label):
    text = generate_c_source(PAIR.replace(label=label))
    assert not TRIGRAPH.search(text), [text[m.start() - 10 : m.end() + 10] for m in TRIGRAPH.finditer(text)]
    assert "??" not in text


def test_no_path_of_this_machine_in_sources_or_docs():
    pattern = re.compile(r"(?<![\w.])/(?:home|root|work|tmp|Users)/\w")
    found = []
    paths = [ROOT / "README.md", *sorted((ROOT / "src").rglob("*.py")), *sorted((ROOT / "docs").rglob("*"))]
    for path in paths:
        if not path.is_file() or path.suffix in (".png", ".pdf", ".svg", ".ico", ".nc"):
            continue
        try:
            text = path.read_text()
        except UnicodeDecodeError:
            continue
        found += [f"{path.relative_to(ROOT)}: {m.group(0)}" for m in pattern.finditer(text)]
    assert found == []


# ----------------------------------------------------------------------------- 4. subnormal and extreme numbers
@pytest.mark.parametrize(
    "args, name",
    [
        ((5e-324, 2.45e-6, 8.3e-14, 1.56e8), "effective_modulus"),
        ((1.31e9, 1e-320, 8.3e-14, 1.56e8), "effective_radius"),
        ((1.31e9, 2.45e-6, 5e-324, 1.56e8), "effective_mass"),
        ((1e308, 2.45e-6, 8.3e-14, 1.56e8), "effective_modulus"),
        ((1.31e9, 1e-300, 8.3e-14, 1.56e8), "effective_radius"),
    ],
)
def test_pairs_double_precision_cannot_hold_are_named(args, name):
    with pytest.raises(ValueError, match=name):
        check_pair(*args)
    with pytest.raises(ValueError, match=name):
        mi.impact_outcome(10.0, *args)


def test_extreme_but_representable_pairs_keep_their_results():
    """``V_y = inf`` (the pair never yields at a finite speed) and ``p_y = inf`` are the elastic limit."""
    for args in [
        (1.31e9, 2.45e-6, 8.3e-14, 1e308),
        (1.31e9, 2.45e-6, 8.3e-14, np.inf),
        (1.31e9, 1e300, 8.3e-14, 1.56e8),
    ]:
        check_pair(*args)
        assert float(mi.impact_outcome(10.0, *args)["restitution"]) == 1.0
    E, R, m, p = (PAIR.effective_modulus, PAIR.effective_radius, PAIR.effective_mass, PAIR.limiting_pressure)
    assert mi.impact_outcome(50.0, E, R, m, p)["restitution"] == PAIR.impact(50.0, warn=False).restitution


@pytest.mark.parametrize("backend", ["python", "numba"])
def test_a_speed_far_below_a_models_scaling_is_computed(monkeypatch, backend):
    """The seed's e(V) holds down to the subnormal 5e-324 (e = 1, kept in the reference outputs), and so
    does hertz_tsuji's, whose Hertz time scale underflows long before (it divided by zero there, then
    was refused): its e is the same at every speed, its contact time scales as V^(-1/5), in both loops."""
    monkeypatch.setenv("MICROIMPACT_BACKEND", backend)
    ref = PAIR.impact(np.array([1.0]), model="hertz_tsuji", damping_ratio=0.3)
    for V in (5e-324, 1e-300):
        out = PAIR.impact(np.array([V, 1.0]), model="hertz_tsuji", damping_ratio=0.3)
        assert out.restitution == pytest.approx(ref.restitution[0], rel=1e-14)
        assert out.contact_time[0] == pytest.approx(ref.contact_time[0] * V ** (-0.2), rel=1e-12)
    assert PAIR.dem_time_step(5e-324, model="hertz_tsuji", damping_ratio=0.3) == pytest.approx(
        PAIR.dem_time_step(1.0, model="hertz_tsuji", damping_ratio=0.3) * 5e-324 ** (-0.2), rel=1e-12
    )
    assert PAIR.dem_time_step(5e-324) > 0.0
    assert check_velocity("velocity", np.array([0.0, 5e-324, 1.0])).size == 3


@pytest.mark.parametrize(
    "argv, word",
    [
        (["stick", "-G", "0.1", "1e-320"], "diameter"),
        (["stick", "-G", "0.1", "1e-200"], "diameter"),
        (
            [
                "impact",
                "10",
                "--effective-modulus",
                "1e308",
                "--radius",
                "1e-6",
                "--density",
                "1000",
                "--limiting-pressure",
                "1e8",
            ],
            "effective_modulus",
        ),
        (["impact", "10", "--radius", "1e-320"], "radius"),
        # a radius and a density each in range whose sphere mass is not (named effective_mass before)
        (["impact", "10", "--radius", "1e300"], "radius"),
        (["impact", "10", "--radius", "1e-6", "--density", "1e-300"], "density"),
        # a subnormal surface energy: the pull-off search never ended
        (["impact", "10", "--model", "jkr_elastic_adhesive", "--param", "surface_energy=1e-320"], "surface_energy"),
        # a speed whose V^2 underflows: the closed-form history divided by its zero time scale
        (["history", "1e-200"], "velocity"),
    ],
    ids=lambda x: " ".join(x) if isinstance(x, list) else x,
)
def test_cli_names_what_double_precision_cannot_hold(capsys, monkeypatch, argv, word):
    monkeypatch.setenv("MICROIMPACT_BACKEND", "python")  # the loop that divided by zero
    rc, out, err = run(argv, capsys)
    assert_one_line(rc, err, word)
