"""The alumina case on the glass anvil of the experiment (Kharaz, Gorham & Salman 2001), wherever the
project builds it: the pair, the CLI, the figures' data and the stored DEM runs."""

from __future__ import annotations

import importlib.util
import json
import math
from pathlib import Path

import numpy as np
import pytest

from microimpact import oblique as ob
from microimpact.materials import get_material

ROOT = Path(__file__).resolve().parents[1]


def _glass_constants():
    """E* and G* of alumina on glass from the two materials (Hertz; Mindlin's G*)."""
    c, g = ob.ALUMINA_CASE, get_material("glass")
    E = 1.0 / ((1 - c["poisson_ratio"] ** 2) / c["youngs_modulus"] + (1 - g.poisson_ratio**2) / g.youngs_modulus)
    G1 = c["youngs_modulus"] / (2 * (1 + c["poisson_ratio"]))
    G2 = g.youngs_modulus / (2 * (1 + g.poisson_ratio))
    return E, 1.0 / ((2 - c["poisson_ratio"]) / G1 + (2 - g.poisson_ratio) / G2)


def test_the_alumina_case_is_on_glass():
    """Hertz: t_c ~ E*^(-2/5) at fixed mass, radius and speed; glass (70 GPa, 0.22) gives E* = 62.2 GPa
    and 12.9 us against the rigid flat's 401 GPa and 6.1 us; kappa = 4 G*/E* = 0.875 from both
    materials' shear moduli (0.870 from alumina's nu alone on the rigid flat)."""
    V = ob.ALUMINA_CASE["velocity"]
    glass, rigid = ob.alumina_pair(), ob.alumina_pair("rigid")
    E, G = _glass_constants()
    assert glass.effective_modulus == pytest.approx(E, rel=1e-14)
    assert ob.stiffness_ratio_of(glass) == pytest.approx(4 * G / E, rel=1e-14)
    assert round(ob.stiffness_ratio_of(glass), 3) == 0.875
    assert glass.particle.youngs_modulus == ob.ALUMINA_CASE["youngs_modulus"] and glass.surface.name == "glass"
    t_r, t_g = (float(p.impact(V).contact_time) for p in (rigid, glass))
    assert t_g / t_r == pytest.approx((rigid.effective_modulus / glass.effective_modulus) ** 0.4, rel=1e-9)
    assert round(t_r * 1e6, 1) == 6.1 and round(t_g * 1e6, 1) == 12.9
    with pytest.raises(ValueError, match="wall"):
        ob.alumina_pair("steel")


def test_the_cli_and_the_figures_build_the_glass_case(capsys):
    from microimpact.cli import main
    from microimpact.figures import oblique as fo

    kappa = ob.stiffness_ratio_of(ob.alumina_pair())
    assert main(["oblique", "--alumina", "--angles", "10", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["kappa"] == pytest.approx(kappa, rel=1e-14)
    data = fo.oblique_data(angle=[10.0], models=["mindlin"])
    ref = ob.oblique_impact(ob.alumina_pair(), 3.9, [10.0], 0.092, effective_shear_modulus=_glass_constants()[1])
    assert data["rebound_spin"][0] == pytest.approx(float(ref.rebound_spin[0]), rel=1e-12)


def test_the_stored_dem_runs_are_on_glass():
    """Each stored run's step is t_H(V_n)/N of the glass pair: the runs were made with its E*."""
    spec = importlib.util.spec_from_file_location("dem_oblique_runs", ROOT / "benchmarks" / "dem_oblique_runs.py")
    dem = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(dem)
    rows = dem.read_csv(dem.DEFAULT_OUT)
    text = dem.DEFAULT_OUT.read_text()
    assert "on a glass flat (E = 70000000000.0 Pa, nu = 0.22)" in text
    glass = ob.alumina_pair()
    assert len(rows) == 2 * len(dem.ANGLES) * len(dem.LAWS)
    for r in rows:
        Vn = 3.9 * math.cos(math.radians(r["angle_deg"]))
        t_h = float(glass.impact(Vn).contact_time)
        n = t_h / r["timestep_s"]
        assert min(abs(n - 20000), abs(n - 40000)) < 1e-6 * n


def test_glass_moves_the_tangential_rebound_within_the_reading_precision():
    """e_t depends on kappa = 4 G*/E*, angle and friction only: the glass anvil's kappa (0.875) against
    the rigid flat's (0.870) moves e_t by at most 3.2e-3, below the +-0.01 reading precision of the
    digitised points."""
    c = ob.ALUMINA_CASE
    ang = np.array([5.0, 10.0, 20.0, 30.0, 45.0, 60.0, 80.0])
    glass = ob.oblique_impact(ob.alumina_pair(), c["velocity"], ang, c["friction"])
    rigid = ob.oblique_impact(ob.alumina_pair("rigid"), c["velocity"], ang, c["friction"], poisson_ratio=0.23)
    d = np.abs(glass.tangential_restitution - rigid.tangential_restitution)
    assert d.max() < 4e-3 and d.max() > 1e-4
