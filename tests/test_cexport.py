"""C export with the compliant tangential model (issue 16) and export of a fit's band (issue 14)."""

from __future__ import annotations

import csv
import dataclasses
import subprocess

import numpy as np
import pytest
from test_coupling import _compiler, _random_cases, build_driver

import microimpact as mi
from microimpact.adhesion import WHOLE_LAW
from microimpact.cexport import band_pairs, generate_c_source, write_band, write_c_source
from microimpact.cli import main
from microimpact.fitting import fit_restitution
from microimpact.oblique import universal_curve, universal_table
from microimpact.wall import wall_interaction

NU = 0.3
KAPPA = 2.0 * (1.0 - NU) / (2.0 - NU)
#: Stated error of the universal table against direct integration, in units of mu J_n
#: (:func:`microimpact.oblique.universal_table`).
TABLE_ERROR = 3e-3


@pytest.fixture(scope="module")
def mindlin_program(tmp_path_factory):
    cc = _compiler()
    if cc is None:
        pytest.skip("no C compiler on this machine")
    tmp = tmp_path_factory.mktemp("cexport_mindlin")
    write_c_source(
        tmp,
        effective_modulus=1.31e9,
        limiting_pressure=156e6,
        friction=0.3,
        tangential="mindlin",
        poisson_ratio=NU,
    )
    return build_driver(cc, tmp)


def _run(exe, rows):
    lines = "\n".join(" ".join(repr(float(x)) if np.isfinite(x) else "inf" for x in row) for row in rows)
    res = subprocess.run([str(exe)], input=lines + "\n", capture_output=True, text=True, check=True)
    return np.array([[float(x) for x in line.split()] for line in res.stdout.splitlines()])


def test_mindlin_c_equals_python_wall_interaction(mindlin_program):
    """Same table, same arithmetic: the C function equals wall_interaction(tangential='mindlin') to rounding
    without adhesion; with it (a struct whose work of adhesion is positive) it integrates the impact as
    Python does (tests/test_cexport_adhesive.py compares that bit for bit; here a few of these
    particles, among the others: no -3 any more)."""
    rng = np.random.default_rng(16)
    N = 3000
    v, n, w, d, rho, E, py, G, mu = _random_cases(rng, N)
    got = _run(mindlin_program, np.column_stack([v, n, w, d, rho, E, py, G, mu]))
    assert got.shape == (N, 8)
    adhesive = G > 0.0
    assert 0 < np.count_nonzero(adhesive) < N
    assert set(got[adhesive, 0].astype(int)) == {-1, 0, 1}
    some = np.flatnonzero(adhesive & (got[:, 0] >= 0))[:4]
    ref = wall_interaction(
        v[some], n[some], d[some], rho[some], effective_modulus=E[some], limiting_pressure=py[some],
        work_of_adhesion=G[some], friction=mu[some], spin=w[some], tangential="mindlin", poisson_ratio=NU,
        adhesion=WHOLE_LAW,
    )  # fmt: skip
    assert np.array_equal(got[some, 0], ref.stuck.astype(float))
    assert np.array_equal(got[some, 1:4], ref.velocity) and np.array_equal(got[some, 4:7], ref.spin)
    got, v, n, w, d, rho, E, py, G, mu = (x[~adhesive] for x in (got, v, n, w, d, rho, E, py, G, mu))
    ref = wall_interaction(
        v,
        n,
        d,
        rho,
        effective_modulus=E,
        limiting_pressure=py,
        work_of_adhesion=G,
        friction=mu,
        spin=w,
        tangential="mindlin",
        poisson_ratio=NU,
    )
    flag = got[:, 0].astype(int)
    assert np.array_equal(flag, np.where(~ref.approaching, -1, np.where(ref.stuck, 1, 0)))
    # stuck-at-some-time (F < 1), sliding throughout, not approaching
    assert {"none", "rolling", "sliding"} <= set(ref.regime)
    vscale = np.maximum(np.linalg.norm(v, axis=1), 1e-300)[:, None]
    wscale = np.maximum(np.linalg.norm(w, axis=1), np.linalg.norm(v, axis=1) / (0.5 * d))[:, None]
    err_v = np.max(np.abs(got[:, 1:4] - ref.velocity) / vscale)
    err_w = np.max(np.abs(got[:, 4:7] - ref.spin) / wscale)
    err_e = np.max(np.abs(got[:, 7] - ref.restitution))
    assert err_v < 1e-12 and err_w < 1e-12 and err_e < 1e-12, (err_v, err_w, err_e)
    # and it is not the rigid model
    rigid = wall_interaction(
        v, n, d, rho, effective_modulus=E, limiting_pressure=py, work_of_adhesion=G, friction=mu, spin=w
    )
    assert np.max(np.abs(got[:, 1:4] - rigid.velocity) / vscale) > 1e-2


def test_mindlin_c_impulse_within_the_table_error_of_direct_integration(mindlin_program):
    """|J_t| / (mu J_n) of the C function against the integration along the normal history."""
    rng = np.random.default_rng(7)
    N = 120
    V = rng.uniform(1.0, 60.0, N)  # V_y of these particles is 5-9 m/s: elastic and plastic impacts
    theta = rng.uniform(0.5, 80.0, N)
    v = np.column_stack([V * np.tan(np.radians(theta)), np.zeros(N), -V])
    d = rng.uniform(1e-6, 1e-5, N)
    rows = np.column_stack(
        [v, np.tile([0.0, 0.0, 1.0], (N, 1)), np.zeros((N, 3)), d, np.full(N, 1350.0)]
        + [np.full(N, x) for x in (1.31e9, 156e6, 0.0, 0.3)]
    )
    got = _run(mindlin_program, rows)
    e = got[:, 7]
    F_c = (v[:, 0] - got[:, 1]) / (0.3 * (1.0 + e) * V)
    Vy = wall_interaction(v, [0, 0, 1], d, 1350.0, effective_modulus=1.31e9, limiting_pressure=156e6).yield_velocity
    psi = KAPPA * v[:, 0] / (0.3 * V)
    F_direct = np.array([universal_curve(p, KAPPA, min(x, 1.0))[0][0] for p, x in zip(psi, Vy / V)])
    err = np.abs(F_c - F_direct)
    assert np.max(err) < TABLE_ERROR, np.max(err)
    print(f"largest |F_C - F_direct| = {np.max(err):.2e}, mean {np.mean(err):.1e}")
    assert np.any(F_direct < 0.9) and np.any(F_direct > 1.0 - 1e-6)  # micro-slip and sliding both met
    assert np.any(Vy / V < 1.0) and np.any(Vy / V > 1.0)


def test_rigid_source_unchanged_and_options_checked():
    pair = mi.ContactPair.paper_case("mica")
    rigid = generate_c_source(pair, work_of_adhesion=0.05, friction=0.25)
    assert generate_c_source(pair, work_of_adhesion=0.05, friction=0.25, tangential="rigid") == rigid
    assert "microimpact_oblique" not in rigid and "MICROIMPACT_KAPPA" not in rigid
    comp = generate_c_source(pair, friction=0.25, tangential="mindlin", poisson_ratio=NU)
    assert f"#define MICROIMPACT_KAPPA {KAPPA!r}" in comp
    assert "return -3;" not in comp and "return -3;" not in rigid  # adhesion is integrated (test_cexport_adhesive)
    assert "microimpact__adhesive_wall" in comp and "microimpact__adhesive_wall" not in rigid
    assert "double microimpact_oblique_impulse_ratio(double psi, double x)" in comp
    assert "stop <= limit" not in comp
    # the table baked in is the one of the pair's kappa
    t = universal_table(KAPPA)
    assert f"{t.values[10, 20]:.17g}" in comp
    # kappa from G*: 4 G*/E* (chosen equal to KAPPA to rounding: the cached table serves)
    gs = 0.25 * KAPPA * pair.effective_modulus
    comp_g = generate_c_source(pair, tangential="mindlin", effective_shear_modulus=gs)
    assert f"#define MICROIMPACT_KAPPA {4.0 * gs / pair.effective_modulus!r}" in comp_g
    # a comment cannot end the header comment
    assert "* / injected" in generate_c_source(pair, comment="*/ injected")
    with pytest.raises(ValueError, match="poisson_ratio"):
        generate_c_source(pair, poisson_ratio=NU)  # would be ignored by the rigid model
    with pytest.raises(ValueError, match="not both"):
        generate_c_source(pair, tangential="mindlin", poisson_ratio=NU, effective_shear_modulus=1e9)
    with pytest.raises(ValueError, match="materials"):
        generate_c_source(pair, tangential="mindlin")
    with pytest.raises(ValueError, match="poisson_ratio"):
        generate_c_source(pair, tangential="mindlin", poisson_ratio=0.7)
    with pytest.raises(ValueError, match="tangential"):
        generate_c_source(pair, tangential="coulomb")


@pytest.mark.parametrize("law", ["stronge", "mindlin_deresiewicz"])
def test_adhesion_with_a_law_not_integrated_is_not_exported(law, tmp_path, capsys):
    """wall_interaction integrates adhesive impacts of the other compliant laws only (and so does the C
    function: test_cexport_adhesive.py); with these the export refuses, in one line naming the options
    and why, and writes nothing."""
    pair = mi.ContactPair.paper_case("mica")
    refusal = rf"tangential='{law}' with adhesion \(work_of_adhesion = 0\.05 J/m\^2\): .* integrated with 'mindlin'"
    with pytest.raises(ValueError, match=refusal) as err:
        generate_c_source(pair, work_of_adhesion=0.05, friction=0.25, tangential=law, poisson_ratio=NU)
    assert "\n" not in str(err.value) and "C wall function" in str(err.value)
    with pytest.raises(ValueError, match=refusal):
        write_c_source(tmp_path / "c", pair, work_of_adhesion=0.05, tangential=law, poisson_ratio=NU)
    assert not (tmp_path / "c").exists()
    args = ["export", "--out", str(tmp_path / "cli"), "--radius", "5e-6", "--density", "2500"]
    args += ["--effective-modulus", "5e9", "--limiting-pressure", "1e8", "--poisson-ratio", "0.3"]
    assert main([*args, "--work-of-adhesion", "0.1", "--tangential", law]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--tangential" in err and "--work-of-adhesion" in err and "C" in err
    assert not (tmp_path / "cli").exists()


def test_mindlin_kappa_from_materials(monkeypatch):
    from microimpact import oblique

    full = oblique.universal_table
    # a coarse table: only the kappa it is asked for matters here (building the full one takes ~30 s)
    monkeypatch.setattr(oblique, "universal_table", lambda k: full(k, dpsi=0.5, n_x=3, steps=20))
    pair = mi.ContactPair.from_materials("fly_ash", "steel", 5e-6, limiting_pressure=4e8)
    src = generate_c_source(pair, friction=0.3, tangential="mindlin")
    kappa = oblique.stiffness_ratio_of(pair)
    assert f"#define MICROIMPACT_KAPPA {kappa!r}" in src
    assert f"#define MICROIMPACT_OBLIQUE_KAPPA {round(kappa, 12):.17g}" in src


# ----------------------------------------------------------------------------- band export
def _data(seed=3, n=15):
    pair = mi.ContactPair.paper_case("silicon")
    rng = np.random.default_rng(seed)
    V = np.geomspace(3.0, 100.0, n)
    e = pair.restitution(V) + rng.normal(0.0, 0.02, n)
    e[2] = 1.03  # a value above 1, as measured near V_y
    return pair, V, e


def _read_csv(path):
    with open(path, newline="") as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].startswith("#")]
    comments = [ln for ln in path.read_text().splitlines() if ln.startswith("#")]
    return rows[0], np.array(rows[1:], dtype=float), comments


@pytest.mark.parametrize("free", ["limiting_pressure", "density"])
def test_band_tables_equal_the_fits_band(tmp_path, free):
    pair, V, e = _data()
    fit = fit_restitution(V, e, pair, params=(free,), confidence=0.9)
    files = write_band(fit, tmp_path / "band", velocities=V, source="data.csv")
    names = {p.name for p in files}
    assert names == {
        "README.txt",
        "restitution_vs_v_over_vy.csv",
        *(f"restitution_d4.9um_{x}.csv" for x in ("estimate", "lower", "upper")),
        *(f"microimpact_wall_{x}.c" for x in ("estimate", "lower", "upper")),
    }
    assert {p.name for p in (tmp_path / "band").iterdir()} == names | {".microimpact-manifest.json"}  # its manifest
    band = fit.predict(V, band=True)
    for end, want in (("estimate", band.restitution), ("lower", band.restitution_lo), ("upper", band.restitution_hi)):
        _, data, comments = _read_csv(tmp_path / "band" / f"restitution_d4.9um_{end}.csv")
        np.testing.assert_array_equal(data[:, 0], V)
        np.testing.assert_allclose(data[:, 1], want, rtol=1e-13, atol=0)
        assert any(f"{end} end of the 90 % confidence band" in c or "best estimate" in c for c in comments)
        src = (tmp_path / "band" / f"microimpact_wall_{end}.c").read_text()
        assert "90 % confidence" in src
    assert np.any(band.restitution_hi > band.restitution_lo)
    # each end's C file carries that end's pair
    ends = {b["name"]: b for b in band_pairs(fit)}
    for end in ("lower", "upper"):
        p = ends[end]["pair"]
        assert (
            f"{p.effective_modulus!r}, {p.limiting_pressure!r}"
            in (tmp_path / "band" / f"microimpact_wall_{end}.c").read_text()
        )
    # which parameter end gives the lower e: p_y's lower end, density's upper end
    lo, hi = fit.conf_int[free]
    assert ends["lower"]["value"] == (lo if free == "limiting_pressure" else hi)
    readme = (tmp_path / "band" / "README.txt").read_text()
    assert "90 % confidence band" in readme and "data.csv" in readme


def test_band_refuses_before_writing(tmp_path):
    pair, V, e = _data()
    fit = fit_restitution(V, e, pair)
    out = tmp_path / "band"
    with pytest.raises(ValueError, match="diameter"):
        write_band(fit, out, diameters=[-1e-6])
    with pytest.raises(ValueError, match="poisson_ratio"):
        write_band(fit, out, tangential="mindlin")
    with pytest.raises(ValueError, match="work_of_adhesion"):
        write_band(fit, out, work_of_adhesion=-1.0)
    with pytest.raises(ValueError, match="FitResult"):
        write_band(pair, out)
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_band_refuses_other_models_and_open_intervals(tmp_path):
    pair, V, e = _data()
    fit = fit_restitution(V, e, pair)
    with pytest.raises(ValueError, match="seed"):
        band_pairs(dataclasses.replace(fit, model="hertz_tsuji"))
    # two points above V_y and a wide level: the profile interval is open above
    Vf = np.array([2.0, 3.0, 4.0, 5.0, 6.0, 9.0, 12.0])
    ef = pair.restitution(Vf) + np.array([0.01, -0.01, 0.0, 0.01, -0.01, 0.03, -0.03])
    fit = fit_restitution(Vf, ef, pair, interval="profile", confidence=0.999)
    lo, hi = fit.conf_int["limiting_pressure"]
    if np.isfinite(hi) and lo > 0:
        pytest.skip(f"this draw has a closed interval ({lo:g}, {hi:g})")
    with pytest.raises(ValueError, match="open"):
        write_band(fit, tmp_path / "band")
    assert list(tmp_path.iterdir()) == []


def test_cli_export_fit_and_mindlin(tmp_path, capsys):
    pair, V, e = _data()
    data = tmp_path / "data.csv"
    data.write_text("velocity,restitution\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(V, e)))
    out = tmp_path / "exp"
    args = ["export", "--out", str(out), "--fit", str(data), "--confidence", "0.9", "--velocities", "3:100:5"]
    rc = main([*args, "--tangential", "mindlin", "--poisson-ratio", "0.3", "--friction", "0.3"])
    assert rc == 0
    text = capsys.readouterr().out
    assert "90 % confidence interval" in text and "tangential mindlin" in text
    fit = fit_restitution(V, e, pair, confidence=0.9)
    ends = {b["name"]: b for b in band_pairs(fit)}
    for end in ("estimate", "lower", "upper"):
        src = (out / f"microimpact_wall_{end}.c").read_text()
        want = generate_c_source(
            ends[end]["pair"],
            friction=0.3,
            tangential="mindlin",
            poisson_ratio=0.3,
            comment=f"fit to data.csv: {ends[end]['text']}",
        )
        assert src == want
    # a plain export may replace the band's directory, and the other way round
    assert main(["export", "--out", str(out), "--tangential", "mindlin", "--poisson-ratio", "0.3"]) == 0
    assert (out / "microimpact_wall.c").read_text() == generate_c_source(
        mi.ContactPair.paper_case(), tangential="mindlin", poisson_ratio=0.3
    )
    capsys.readouterr()
    before = sorted(p.name for p in out.iterdir())
    bad = [
        (["--tangential", "mindlin"], "--poisson-ratio"),
        (["--poisson-ratio", "0.3"], "--tangential mindlin"),
        (["--tangential", "mindlin", "--poisson-ratio", "0.3", "--no-c"], "--no-c"),
        (["--tangential", "mindlin", "--poisson-ratio", "0.7"], "--poisson-ratio"),
        (["--tangential", "mindlin", "--shear-modulus", "-1"], "--shear-modulus"),
        (["--confidence", "0.9"], "--fit"),
        (["--free", "density"], "--fit"),
        (["--fit", str(data), "--confidence", "1.5"], "--confidence"),
        (["--fit", str(data), "--free", "limiting_pressure,density"], "--free"),
        (["--fit", str(tmp_path / "missing.csv")], "--fit"),
    ]
    for extra, name in bad:
        rc = main(["export", "--out", str(out), *extra])
        err = capsys.readouterr().err
        assert rc == 2 and name in err, (extra, err)
    assert main(["export", "--out", str(out), "--poisson-ratio", "0.3", "--shear-modulus", "1e9"]) == 2
    err = capsys.readouterr().err
    assert "--poisson-ratio" in err and "--shear-modulus" in err
    assert sorted(p.name for p in out.iterdir()) == before
