"""``microimpact export --adhesion``: the exported tables and C file follow the chosen adhesion rule
and agree with :func:`microimpact.wall.wall_interaction` of the same rule (issue 21)."""

from __future__ import annotations

import contextlib
import io
import shutil
import subprocess

import numpy as np
import pytest
from test_coupling import _compiler, build_driver

import microimpact as mi
from microimpact.adhesion import WHOLE_LAW, whole_law_restitution
from microimpact.cexport import generate_c_source, restitution_table, write_tables
from microimpact.cli import main
from microimpact.core.models import dmt_elastic_adhesive as dmt
from microimpact.wall import wall_interaction

SILICON = mi.ContactPair.paper_case("silicon")
G = 1.0
DIAMETERS = (0.1e-6, 0.3e-6, 2e-6)  # V_s/V_y from about 7 (beyond the seed's yield by far) to 0.6


def _head_on(pair, d, V, adhesion):
    """wall_interaction of head-on impacts at speeds V of the pair's particle resized to d."""
    return wall_interaction(
        np.column_stack([np.zeros_like(V), np.zeros_like(V), -V]),
        [0.0, 0.0, 1.0],
        d,
        pair.density,
        effective_modulus=pair.effective_modulus,
        limiting_pressure=pair.limiting_pressure,
        work_of_adhesion=G,
        adhesion=adhesion,
    )


def _columns(path):
    """The project's CSV layout: header ``name [unit]``, ``#`` comments, rows; columns by name."""
    lines = path.read_text().splitlines()
    names = [h.rsplit(" [", 1)[0] for h in lines[0].split(",")]
    rows = [[float(x) for x in line.split(",")] for line in lines[1:] if line and not line.startswith("#")]
    return dict(zip(names, np.array(rows).T))


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    out = tmp_path_factory.mktemp("export_adhesion") / "cfd"
    args = ["export", "--out", str(out), "--case", "silicon", "--work-of-adhesion", str(G)]
    args += ["--diameters", ",".join(repr(d) for d in DIAMETERS), "--velocities", "0:600:241"]
    args += ["--vs-over-vy", "0,0.5,2,8,20"]
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main([*args, "--adhesion", WHOLE_LAW]) == 0
    assert "adhesion " + WHOLE_LAW in buf.getvalue()
    return out


def test_size_tables_are_the_wall_interaction(exported):
    """Each per-size table is what wall_interaction(adhesion=the whole law) gives head-on: e to 1e-14,
    the same stuck and outside-table flags; and it is not the additive rule (which captures slower)."""
    V = np.linspace(0.0, 600.0, 241)
    for d in DIAMETERS:
        cols = _columns(exported / f"restitution_d{d * 1e6:g}um.csv")
        assert np.array_equal(cols["normal speed"], V)
        ref = _head_on(SILICON, d, V[1:], WHOLE_LAW)
        e = cols["restitution e"]
        assert e[0] == 0.0 and cols["stuck"][0] == 1  # V = 0: stuck (V_s > 0)
        assert np.max(np.abs(e[1:] - ref.restitution)) < 1e-14
        assert np.array_equal(cols["stuck"][1:] == 1, ref.stuck)
        assert np.array_equal(cols["outside table"][1:] == 1, ref.outside_table)
        add = _head_on(SILICON, d, V[1:], "additive")
        # the whole law captures faster particles where V_s/V_y is not small (and the same ones where it is)
        more = np.count_nonzero(ref.stuck) - np.count_nonzero(add.stuck)
        assert more > 10 if d < 1e-6 else more >= 0
        # the law's own capture speed is in the comments, and the table's stick boundary is next to it
        text = (exported / f"restitution_d{d * 1e6:g}um.csv").read_text()
        Vc = float(text.split("its capture velocity ")[1].split()[0])
        assert Vc == pytest.approx(SILICON.sticking_velocity(d, work_of_adhesion=G), rel=1e-9)
        bounce = V[1:][~ref.stuck]
        assert bounce.min() >= Vc * (1.0 - 1.5e-3)
        assert np.all(ref.stuck[V[1:] <= Vc * (1.0 - 1.5e-3)])


def test_universal_table_is_the_whole_law(exported):
    cols = _columns(exported / "restitution_vs_v_over_vy.csv")
    x = cols["V/V_y"]
    for s in (0.0, 0.5, 2.0, 8.0, 20.0):
        key = f"e at V_s/V_y={s:g}"
        want, outside = whole_law_restitution(x, 1.0, s)
        assert np.array_equal(cols[key], want), key
        assert outside.any() == (s > 10.0)
    assert np.array_equal(cols["e at V_s/V_y=0"], restitution_table(x, [0.0])[:, 0])  # no adhesion: the seed's
    assert np.max(np.abs(cols["e at V_s/V_y=2"] - restitution_table(x, [2.0])[:, 0])) > 0.1  # not additive
    text = (exported / "restitution_vs_v_over_vy.csv").read_text()
    assert "columns V_s/V_y = 20" in text  # the column beyond the table is flagged


def test_exported_c_is_the_wall_interaction(exported, tmp_path):
    """The C file written by the command is generate_c_source(adhesion=the whole law) of the pair, and,
    compiled with the system's cc, gives the per-size tables' e and stuck flags (1e-12)."""
    src = (exported / "microimpact_wall.c").read_text()
    assert src == generate_c_source(SILICON, work_of_adhesion=G, adhesion=WHOLE_LAW)
    cc = _compiler()
    if cc is None:
        pytest.skip("no C compiler on this machine")
    shutil.copy(exported / "microimpact_wall.c", tmp_path / "microimpact_wall.c")
    exe = build_driver(cc, tmp_path)
    V = np.linspace(0.0, 600.0, 241)[1:]
    rows = []
    for d in DIAMETERS:
        for v in V:
            rows.append([0.0, 0.0, -v, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, d, SILICON.density])
            rows[-1] += [SILICON.effective_modulus, SILICON.limiting_pressure, G, 0.0]
    text = "\n".join(" ".join(repr(float(x)) for x in row) for row in rows)
    res = subprocess.run([str(exe)], input=text + "\n", capture_output=True, text=True, check=True)
    got = np.array([[float(x) for x in line.split()] for line in res.stdout.splitlines()])
    for k, d in enumerate(DIAMETERS):
        cols = _columns(exported / f"restitution_d{d * 1e6:g}um.csv")
        part = got[k * V.size : (k + 1) * V.size]
        assert np.array_equal(part[:, 0] == 1, cols["stuck"][1:] == 1)
        assert np.max(np.abs(part[:, 7] - cols["restitution e"][1:])) < 1e-12


def test_additive_stays_the_default_byte_for_byte(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    base = ["export", "--case", "mica", "--work-of-adhesion", "0.3", "--diameters", "1e-6,5e-6"]
    assert main([*base, "--out", str(a)]) == 0
    assert main([*base, "--out", str(b), "--adhesion", "additive"]) == 0
    names = sorted(p.name for p in a.iterdir())
    assert names == sorted(p.name for p in b.iterdir())
    for name in names:
        assert (a / name).read_bytes() == (b / name).read_bytes(), name
    assert "tn98" not in (a / "microimpact_wall.c").read_text()
    assert "outside table" not in (a / "restitution_d1um.csv").read_text()


def test_bad_adhesion_is_one_line_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "cfd"
    assert main(["export", "--out", str(out), "--work-of-adhesion", "0.1"]) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    capsys.readouterr()
    for bad, why in (("whole", None), (dmt.NAME, "e = 1 at every speed"), ("", None), ("Additive", None)):
        rc = main(["export", "--out", str(out), "--adhesion", bad, "--work-of-adhesion", "0.2"])
        err = capsys.readouterr().err
        assert rc == 2 and err.count("\n") == 1 and "--adhesion" in err and repr(bad) in err, err
        assert "'additive', '" + WHOLE_LAW + "'" in err
        if why:
            assert why in err
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert main(["export", "--out", str(tmp_path / "new"), "--adhesion", "whole"]) == 2
    assert not (tmp_path / "new").exists()


def test_band_export_with_the_whole_law(tmp_path, capsys):
    """--fit with --adhesion: every end's C file and tables use the whole law."""
    V = np.array([5.0, 10.0, 20.0, 40.0, 80.0])
    data = tmp_path / "data.csv"
    e = SILICON.restitution(V) + [0.0, 0.01, -0.01, 0.005, -0.005]
    data.write_text("velocity,restitution\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(V, e)))
    out = tmp_path / "band"
    args = ["export", "--out", str(out), "--fit", str(data), "--work-of-adhesion", "0.5", "--adhesion", WHOLE_LAW]
    assert main(args) == 0
    capsys.readouterr()
    for end in ("estimate", "lower", "upper"):
        assert "microimpact_tn98_correction" in (out / f"microimpact_wall_{end}.c").read_text()
        assert "outside table" in (out / f"restitution_d4.9um_{end}.csv").read_text()
    assert WHOLE_LAW in (out / "README.txt").read_text()


def test_python_api_refuses_dmt_with_its_reason(tmp_path):
    for call in (
        lambda: wall_interaction(
            [0, 0, -1.0], [0, 0, 1], 1e-6, 1000.0, effective_modulus=1e9, limiting_pressure=1e8, adhesion=dmt.NAME
        ),
        lambda: generate_c_source(SILICON, adhesion=dmt.NAME),
        lambda: write_tables(tmp_path / "t", SILICON, adhesion=dmt.NAME),
        lambda: restitution_table([1.0], [0.5], adhesion=dmt.NAME),
    ):
        with pytest.raises(ValueError, match=r"adhesion must be one of .*e = 1 at every speed"):
            call()
    assert not (tmp_path / "t").exists()


def test_help_names_the_rules_and_the_fits_choices(capsys):
    """The help texts read their names only when printed (issue 25): they still list them all."""
    from microimpact import fitting

    assert main(["export", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())  # argparse wraps the help to the terminal
    assert "additive or " + WHOLE_LAW in text
    assert ", ".join(fitting.LOSSES) in text and ", ".join(fitting.INTERVALS) in text


def test_bad_loss_or_interval_is_one_line_and_writes_nothing(tmp_path, capsys):
    data = tmp_path / "e.csv"
    data.write_text("velocity,restitution\n20,0.8\n40,0.7\n60,0.6\n")
    out = tmp_path / "cfd"
    for option, bad in (("--loss", "l2"), ("--interval", "wilson"), ("--loss", "")):
        assert main(["export", "--out", str(out), "--fit", str(data), option, bad]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and option in err and repr(bad) in err, err
        assert "linear, soft_l1" in err or "auto, wald, profile" in err, err
    assert not out.exists()


def test_a_default_export_loads_no_model_it_does_not_run(tmp_path):
    """``export`` without adhesion imports neither the fit nor a model that ``import microimpact`` does
    not already load (every model was read to list the adhesion rules in the help: 10 ms of 140)."""
    import sys

    code = (
        "import sys, microimpact\n"
        "before = set(sys.modules)\n"
        "from microimpact.cli import main\n"
        f"assert main(['export', '--no-c', '--out', {str(tmp_path / 'cfd')!r}]) == 0\n"
        "new = sorted(m for m in set(sys.modules) - before if m.startswith('microimpact.'))\n"
        "print(','.join(m for m in new if m.startswith(('microimpact.fitting', 'microimpact.core.models.'))))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.splitlines()[-1] == "", out
