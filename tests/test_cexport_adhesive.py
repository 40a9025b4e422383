"""The C wall function's adhesive oblique impact against :func:`microimpact.wall.wall_interaction`.

With adhesion and a compliant tangential law the Python path integrates each impact
(:func:`microimpact.oblique.adhesive.adhesive_oblique_impact`); the generated C performs the same
operations in the same order, so the outgoing velocity, spin, restitution and capture decision are
compared bit for bit (or within 1e-15 relative, where a C library rounds a ``cos`` differently).
"""

from __future__ import annotations

import subprocess
import time

import numpy as np
import pytest
from test_coupling import DRIVER, _compiler

from microimpact import oblique
from microimpact.adhesion import WHOLE_LAW
from microimpact.cexport import generate_c_source, write_c_source
from microimpact.oblique.adhesive import ADHESIVE_LAWS
from microimpact.wall import wall_interaction

NU = 0.3
#: The compliant laws the adhesive integration runs, each exported and compared.
LAWS = tuple(law for law in ADHESIVE_LAWS if law != "rigid")
#: Particles per law (the Python path integrates each: about 10 ms a particle once compiled).
PER_LAW = 6
REL = 1e-15


@pytest.fixture(scope="module")
def programs(tmp_path_factory):
    """One compiled driver per law. The universal table baked in serves the non-adhesive particles only,
    none here: every law gets Mindlin's, built coarse (a full one takes seconds per law in a new cache)."""
    cc = _compiler()
    if cc is None:
        pytest.skip("no C compiler on this machine")
    full = oblique.universal_table
    out = {}
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(oblique, "universal_table", lambda k, law="mindlin": full(k, dpsi=0.5, n_x=3, steps=20))
        for law in LAWS:
            tmp = tmp_path_factory.mktemp(f"cexport_adhesive_{law}")
            write_c_source(
                tmp,
                effective_modulus=1.31e9,
                limiting_pressure=156e6,
                work_of_adhesion=0.1,
                friction=0.3,
                tangential=law,
                poisson_ratio=NU,
                adhesion=WHOLE_LAW,
            )
            (tmp / "driver.c").write_text(DRIVER)
            exe = tmp / "driver"
            flags = ["-std=c99", "-O2", "-ffp-contract=off", "-Wall", "-Werror", "-pedantic"]
            res = subprocess.run(
                [cc, *flags, "-o", str(exe), str(tmp / "driver.c"), "-lm"], capture_output=True, text=True
            )
            assert res.returncode == 0, res.stderr
            out[law] = exe
    return out


def _cases(rng, n):
    """``n`` adhesive particles hitting walls of random orientation at 5-80 degrees, half of them spinning,
    at 0.3-3 times the whole law's capture speed (bounce and capture both met), one with back spin
    ``R omega = 5/2 v_t`` (it comes to rest: "stick"), one slippery (captured sliding), one elastic."""
    d = 10 ** rng.uniform(-6, -5, n)
    rho = rng.uniform(1000, 3000, n)
    E = 10 ** rng.uniform(9, 10.5, n)
    py = 10 ** rng.uniform(7.5, 9, n)
    py[-1] = np.inf
    G = 10 ** rng.uniform(-2, -0.3, n)
    mu = rng.uniform(0.1, 0.6, n)
    mu[2] = 0.01
    nrm = rng.normal(size=(n, 3)) * rng.uniform(0.5, 3.0, (n, 1))  # any length: normalised by both
    u = nrm / np.linalg.norm(nrm, axis=1)[:, None]
    along = np.cross(u, rng.normal(size=(n, 3)))
    along /= np.linalg.norm(along, axis=1)[:, None]
    zero = np.zeros((n, 3))
    Vc = wall_interaction(
        -u, u, d, rho, effective_modulus=E, limiting_pressure=py, work_of_adhesion=G, friction=mu,
        spin=zero, tangential="rigid", adhesion=WHOLE_LAW,
    ).sticking_velocity  # fmt: skip
    Vn = Vc * rng.uniform(0.3, 3.0, n)
    Vn[1:3] = 0.5 * Vc[1:3]
    theta = np.radians(rng.uniform(5.0, 80.0, n))
    theta[2] = np.radians(75.0)
    vt = Vn * np.tan(theta)
    v = -Vn[:, None] * u + vt[:, None] * along
    w = rng.normal(size=(n, 3)) * (vt / (0.5 * d))[:, None]
    w[::2] = 0.0
    w[1] = 2.5 / (0.5 * d[1]) * vt[1] * np.cross(along[1], u[1])  # r n x omega = 5/2 v_t: rolls to rest
    return v, nrm, w, d, rho, E, py, G, mu


def _run(exe, rows):
    lines = "\n".join(" ".join(repr(float(x)) if np.isfinite(x) else "inf" for x in row) for row in rows)
    res = subprocess.run([str(exe)], input=lines + "\n", capture_output=True, text=True, check=True)
    return np.array([[float(x) for x in line.split()] for line in res.stdout.splitlines()])


def test_adhesive_c_equals_python(programs):
    """Every accepted law: the C function's capture decision is wall_interaction's, and its velocity,
    spin and restitution are the same bits (at most 1e-15 relative apart)."""
    rng = np.random.default_rng(43)
    outcomes = set()
    report = []
    start = time.perf_counter()
    for law, exe in programs.items():
        v, n, w, d, rho, E, py, G, mu = _cases(rng, PER_LAW)
        got = _run(exe, np.column_stack([v, n, w, d, rho, E, py, G, mu]))
        assert got.shape == (PER_LAW, 8)
        ref = wall_interaction(
            v, n, d, rho, effective_modulus=E, limiting_pressure=py, work_of_adhesion=G, friction=mu,
            spin=w, tangential=law, poisson_ratio=NU, adhesion=WHOLE_LAW,
        )  # fmt: skip
        outcomes |= set(ref.outcome)
        assert np.array_equal(got[:, 0].astype(int), ref.stuck.astype(int)), law  # 1 captured, 0 bounced
        vscale = np.linalg.norm(v, axis=1)[:, None]
        wscale = np.maximum(np.linalg.norm(w, axis=1), np.linalg.norm(v, axis=1) / (0.5 * d))[:, None]
        err = (
            np.max(np.abs(got[:, 1:4] - ref.velocity) / vscale),
            np.max(np.abs(got[:, 4:7] - ref.spin) / wscale),
            np.max(np.abs(got[:, 7] - ref.restitution)),
        )
        same = all(np.array_equal(a, b) for a, b in ((got[:, 1:4], ref.velocity), (got[:, 4:7], ref.spin)))
        same = same and np.array_equal(got[:, 7], ref.restitution)
        report.append(f"{law}: " + ("bitwise equal" if same else f"max relative difference {max(err):.1e}"))
        assert max(err) <= REL, (law, err)
        # a captured particle keeps its motion along the wall: no normal part, e = 0
        cap = ref.stuck
        u = n / np.linalg.norm(n, axis=1)[:, None]
        assert np.all(got[cap, 7] == 0.0)
        assert np.all(np.abs(np.sum(got[cap, 1:4] * u[cap], axis=1)) <= 1e-12 * vscale[cap, 0])
        assert np.all(got[~cap, 7] > 0.0)
    print("; ".join(report), f"({time.perf_counter() - start:.1f} s)")
    assert outcomes == {"bounce", "stick", "captured rolling", "captured sliding"}, outcomes


def test_adhesive_source_per_law(monkeypatch):
    """The law's constants are baked in from core.tangential_laws; the -3 refusal is gone for the laws the
    integration runs and kept (with the ValueError) for the others."""
    from microimpact.core import tangential_laws as tl

    full = oblique.universal_table
    monkeypatch.setattr(oblique, "universal_table", lambda k, law="mindlin": full(k, dpsi=0.5, n_x=3, steps=20))

    pair_kw = {"effective_modulus": 1.31e9, "limiting_pressure": 156e6, "friction": 0.3, "poisson_ratio": NU}
    # G > 0 baked in with the additive rule (the default): the whole law is integrated, and said so, as
    # wall_interaction says it
    with pytest.warns(DeprecationWarning, match="the whole law it approximates is integrated instead"):
        src = generate_c_source(tangential="lammps_linear_history", work_of_adhesion=0.1, **pair_kw)
    consts = ", ".join(repr(float(c)) for c in tl.law_parameters(tl.law_code("lammps_linear_history")))
    assert f"microimpact_adh_law[6] = {{{consts}, 0.0}};" in src
    assert "return -3;" not in src and "microimpact__adhesive_wall(v_in, n, w, vn, r, m" in src
    src = generate_c_source(tangential="liggghts_history", **pair_kw)
    assert src.count("microimpact_adh_law[6] = {1.0, 1.0, 1.0, 0.0, 0.5, 1.0};") == 1  # arm r - delta/2, mu |F|
    for law in ("stronge", "mindlin_deresiewicz"):
        assert law not in LAWS
        with pytest.raises(ValueError, match=f"tangential='{law}' with adhesion .* integrated with 'mindlin'"):
            generate_c_source(tangential=law, work_of_adhesion=0.1, **pair_kw)
    src = generate_c_source(tangential="stronge", **pair_kw)  # an adhesive struct: -3, outputs = inputs
    assert "return -3;" in src and "microimpact__adhesive_wall" not in src


def test_cli_exports_adhesion_with_a_compliant_law(tmp_path, monkeypatch):
    """``microimpact export`` writes the C file of a compliant law with adhesion (it refused it before)."""
    from microimpact.cli import main

    full = oblique.universal_table
    monkeypatch.setattr(oblique, "universal_table", lambda k, law="mindlin": full(k, dpsi=0.5, n_x=3, steps=20))
    args = ["export", "--out", str(tmp_path), "--radius", "5e-6", "--density", "2500", "--effective-modulus", "5e9"]
    args += ["--limiting-pressure", "1e8", "--poisson-ratio", "0.3", "--friction", "0.3"]
    with pytest.warns(DeprecationWarning, match="additive"):  # --adhesion's default, as wall_interaction's
        assert main([*args, "--work-of-adhesion", "0.1", "--tangential", "lammps_mindlin"]) == 0
    src = (tmp_path / "microimpact_wall.c").read_text()
    assert "microimpact__adhesive_wall" in src and "return -3;" not in src
