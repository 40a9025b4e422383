"""Reference outputs of microimpact's public API on a fixed grid (issue 11: "every public number is unchanged").

Run from the repository root (``PYTHONPATH=src``) to (re)write
``tests/reference/reference_outputs.npz``::

    python tests/reference/make_reference.py

Only do that on purpose: the file records what the code computed when it was
written, and ``tests/test_reference_outputs.py`` checks that the code still
computes the same numbers (relative 1e-13). Rewriting it after a change of the
physics hides the change.

The file holds two kinds of arrays:

* ``in/<name>``: the inputs (seeded random pairs, speeds, vectors, data sets),
  so that the test replays exactly the same calls without a random generator;
* ``out/<group>/<name>``: what each call returned.

Each group is one function ``group_<name>(inp)`` below, taking the dict of
inputs and returning a dict of arrays; the test imports this file and calls the
same functions. They use only public names of :mod:`microimpact`.
"""

from __future__ import annotations

import dataclasses
import math
import os
import sys
import warnings
from pathlib import Path

import numpy as np

import microimpact as mi
from microimpact import adhesion, contact, dynamics, impact, materials
from microimpact.cexport import restitution_table
from microimpact.fitting import fit_restitution
from microimpact.sweep import SWEEP_VARIABLES as SWEEP_VARIABLE_UNITS
from microimpact.sweep import sweep
from microimpact.wall import wall_interaction

HERE = Path(__file__).resolve().parent
REFERENCE_FILE = HERE / "reference_outputs.npz"
SEED = 20261123
N_RANDOM_PAIRS = 30

#: Fields of an ImpactResult, in the dataclass order.
RESULT_FIELDS = tuple(f.name for f in dataclasses.fields(mi.ImpactResult))
HISTORY_ARRAYS = tuple(dynamics.HISTORY_COLUMNS)
HISTORY_SCALARS = tuple(dynamics.HISTORY_SCALARS)
WALL_FIELDS = (
    "velocity",
    "spin",
    "stuck",
    "restitution",
    "normal_speed",
    "approaching",
    "rolling",
    "yield_velocity",
    "sticking_velocity",
    "regime",
    "deposited_fraction",
)
SWEEP_VARIABLES = tuple(SWEEP_VARIABLE_UNITS)

# Speeds tied to the yield velocity (set per pair); a pair with p_y = inf has
# V_y = inf and gets ELASTIC_ONLY_SPEEDS in these slots instead.
N_YIELD_SPEEDS = 9
ELASTIC_ONLY_SPEEDS = (0.5, 1.0, 2.0, 3.0, 5.0, 7.0, 11.0, 13.0, 17.0)
FIXED_SPEEDS = np.concatenate([[0.0, 5e-324, 1e-300, 1e-12], np.geomspace(1e-3, 1e4, 29), [1e8, math.inf]])


# ============================================================================ inputs
def _yield_speeds(Vy: float) -> list[float]:
    """The speeds around the yield point: V_y exactly, one ulp and 1e-12 either side, and above."""
    if not math.isfinite(Vy):
        return list(ELASTIC_ONLY_SPEEDS)
    return [
        Vy * (1.0 - 1e-12),
        math.nextafter(Vy, 0.0),
        Vy,
        math.nextafter(Vy, math.inf),
        Vy * (1.0 + 1e-12),
        Vy * (1.0 + 1e-6),
        Vy * (1.0 + 1e-3),
        1.5 * Vy,
        100.0 * Vy,
    ]


def make_inputs() -> dict[str, np.ndarray]:
    """All inputs of the reference calls, from one seeded generator."""
    rng = np.random.default_rng(SEED)
    inp: dict[str, np.ndarray] = {}
    n = N_RANDOM_PAIRS
    # Random sphere-on-flat pairs over wide ranges (log-uniform); every sixth elastic (p_y = inf).
    inp["random_radius"] = 10.0 ** rng.uniform(-8.0, -3.0, n)
    inp["random_density"] = 10.0 ** rng.uniform(math.log10(500.0), math.log10(20000.0), n)
    inp["random_modulus"] = 10.0 ** rng.uniform(8.0, math.log10(5e11), n)
    py = 10.0 ** rng.uniform(6.0, 10.0, n)
    py[::6] = math.inf
    inp["random_pressure"] = py

    pairs = build_pairs(inp)
    speeds = [np.array(_yield_speeds(p.yield_velocity) + list(FIXED_SPEEDS)) for p in pairs]
    inp["speeds"] = np.stack(speeds)  # (n_pairs, n_speeds)

    # Approaches for the force laws, relative to R* (the pair's own scale).
    inp["approach_over_radius"] = np.concatenate([[0.0, 1e-300], np.geomspace(1e-12, 0.5, 23)])
    # Normalized speeds v = V/V_y and approaches for the normalized laws.
    inp["v_normalized"] = np.concatenate(
        [[0.0, 0.5, 1.0, 1.0 + 1e-12, 1.0 + 1e-6, 1.5], np.geomspace(2.0, 1e8, 20), [math.inf]]
    )
    inp["alpha_hat"] = np.concatenate([[0.0, 1e-12, 0.3, 1.0, 1.0 + 1e-12], np.geomspace(1.5, 1e4, 12)])
    inp["max_alpha_hat"] = np.array([1.0, 1.0 + 1e-9, 2.0, 10.0, 1e3, 1e5])
    inp["beta_u"] = np.concatenate([[0.0, 1e-300, 1e-12], np.linspace(0.05, 0.95, 19), [1.0 - 1e-12, 1.0]])

    # Material combinations for materials.effective_* .
    m = 16
    inp["mat_E1"] = 10.0 ** rng.uniform(8.0, 12.0, m)
    inp["mat_nu1"] = rng.uniform(-0.9, 0.5, m)
    inp["mat_E2"] = 10.0 ** rng.uniform(8.0, 12.0, m)
    inp["mat_nu2"] = rng.uniform(-0.9, 0.5, m)
    inp["mat_R1"] = 10.0 ** rng.uniform(-8.0, -3.0, m)
    inp["mat_R2"] = np.where(np.arange(m) % 4 == 0, math.inf, 10.0 ** rng.uniform(-8.0, -3.0, m))
    inp["mat_m1"] = 10.0 ** rng.uniform(-20.0, -5.0, m)
    inp["mat_m2"] = np.where(np.arange(m) % 4 == 1, math.inf, 10.0 ** rng.uniform(-20.0, -5.0, m))

    # Histories: (pair index, speed) pairs; closed form on a uniform grid and at given times.
    inp["history_pair"] = np.array([0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 10, 20, 25])
    # Elastic, just plastic, plastic, fast. Not V = V_y itself: there the stage boundaries (and
    # so the grid's length) hang on the last bit of V_y; the impact grids cover that point.
    hv = [1.0, 10.0, 50.0, 1e3]
    for i in inp["history_pair"][4:]:
        Vy = pairs[i].yield_velocity
        hv.append(3.0 * Vy if math.isfinite(Vy) else 2.0)
    inp["history_velocity"] = np.array(hv)
    inp["history_times_fraction"] = np.array([-0.5, -1e-12, 0.0, 1e-9, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0, 1.0 + 1e-12, 2.0])

    # Sweep grid.
    inp["sweep_velocity"] = np.array([0.0, 1.0, 7.5, 30.0, 50.0, 200.0, 1e3])
    inp["sweep_pressure"] = np.array([50e6, 156e6, 1e9, math.inf])
    inp["sweep_radius"] = np.array([1e-7, 2.45e-6, 1e-4])
    inp["sweep_particle_modulus"] = np.array([0.5e9, 5e9, 200e9])
    inp["sweep_surface_poisson"] = np.array([0.0, 0.3, 0.49])

    # Synthetic restitution data for the fits: the silicon case plus seeded noise.
    V = np.geomspace(2.0, 300.0, 25)
    e_true = mi.ContactPair.paper_case("silicon").restitution(V)
    sigma = np.full(V.size, 0.01)
    e = np.minimum(e_true + sigma * rng.standard_normal(V.size), 1.0)
    e[[5, 17]] += 0.06  # two outliers for the robust loss
    inp["fit_velocity"] = V
    inp["fit_restitution"] = np.minimum(e, 1.0)
    inp["fit_sigma"] = sigma
    inp["fit_band_velocity"] = np.concatenate([[0.0, 1.0], np.geomspace(5.0, 500.0, 15)])

    # Wall interaction: random particles, normals, adhesion, friction, spin.
    w = 64
    vel = 30.0 * rng.standard_normal((w, 3))
    vel[0] = [0.0, 0.0, -5.0]  # head on, no tangential slip
    vel[1] = [0.0, 0.0, 5.0]  # leaving the wall
    vel[2] = [3.0, 0.0, -50.0]  # the docstring example
    nrm = rng.standard_normal((w, 3))
    nrm[:3] = [0.0, 0.0, 1.0]
    inp["wall_velocity"] = vel
    inp["wall_normal"] = nrm * 10.0 ** rng.uniform(-1.0, 1.0, (w, 1))  # not unit: normalised inside
    inp["wall_diameter"] = 10.0 ** rng.uniform(-7.0, -4.0, w)
    inp["wall_density"] = 10.0 ** rng.uniform(math.log10(500.0), math.log10(20000.0), w)
    inp["wall_modulus"] = 10.0 ** rng.uniform(8.0, 11.0, w)
    wp = 10.0 ** rng.uniform(7.0, 10.0, w)
    wp[::7] = math.inf
    inp["wall_pressure"] = wp
    G = 10.0 ** rng.uniform(-3.0, 0.0, w)
    G[::5] = 0.0
    inp["wall_adhesion"] = G
    mu = rng.uniform(0.0, 0.8, w)
    mu[::4] = 0.0
    inp["wall_friction"] = mu
    inp["wall_spin"] = 10.0 ** rng.uniform(2.0, 6.0, (w, 1)) * rng.standard_normal((w, 3))
    names = np.array(["nh4fl", "copper", "steel", "aluminium", "stainless_steel"])
    inp["wall_material"] = names[rng.integers(0, names.size, w)]

    # Adhesion helpers and the lookup table.
    inp["adh_velocity"] = np.concatenate([[0.0, 1e-12, 0.1, 0.5, 1.0], np.geomspace(2.0, 1e4, 15)])
    inp["adh_yield_velocity"] = np.array([1e-3, 0.5, 7.52, 100.0, math.inf])
    inp["adh_sticking_velocity"] = np.array([0.0, 1e-6, 0.3, 1.0, 10.0])
    inp["adh_gamma1"] = np.array([0.0, 0.01, 0.05, 0.5])
    inp["adh_gamma2"] = np.array([0.02, 0.0, 0.1, 0.5])
    inp["table_v_over_vy"] = np.concatenate([np.linspace(0.0, 2.0, 41)[:-1], np.geomspace(2.0, 100.0, 30)])
    inp["table_vs_over_vy"] = np.array([0.0, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0])
    return inp


def build_pairs(inp) -> list:
    """The pairs of the grid: the paper's cases, constructor variants, then the random pairs."""
    pairs = [
        mi.ContactPair.paper_case("silicon"),
        mi.ContactPair.paper_case("mica"),
        mi.ContactPair.from_materials("nh4fl", "silicon", radius=2.45e-6, limiting_pressure=156e6),
        mi.ContactPair.from_materials("copper", "steel", radius=1e-5),  # p_y = k Y from the materials
        mi.ContactPair.two_spheres("aluminium", "copper", 1e-5, 3e-5, k=2.1),
        mi.ContactPair.sphere_on_flat(5e-7, mass=1e-15, effective_modulus=70e9, yield_strength=100e6),
        mi.ContactPair.paper_case("silicon").elastic_equivalent(),
        mi.ContactPair.paper_case("mica").resized(radius=1e-6, density=2000.0),
    ]
    for R, rho, E, py in zip(
        inp["random_radius"], inp["random_density"], inp["random_modulus"], inp["random_pressure"], strict=True
    ):
        pairs.append(mi.ContactPair.sphere_on_flat(float(R), float(rho), float(E), float(py)))
    return pairs


# ============================================================================ groups of calls
def _stack(rows):
    return np.array(rows)


def _pair_columns(pairs):
    E = np.array([p.effective_modulus for p in pairs])[:, None]
    R = np.array([p.effective_radius for p in pairs])[:, None]
    m = np.array([p.effective_mass for p in pairs])[:, None]
    py = np.array([p.limiting_pressure for p in pairs])[:, None]
    return E, R, m, py


def group_constants(inp):
    return {
        "LARGE_STRAIN_RATIO": np.float64(impact.LARGE_STRAIN_RATIO),
        "BETA_25_12": np.float64(dynamics.BETA_25_12),
        "HERTZ_TIME_CONSTANT": np.float64(dynamics.HERTZ_TIME_CONSTANT),
        "STICKING_CONSTANT": np.float64(adhesion.STICKING_CONSTANT),
        "DEFAULT_K": np.float64(materials.DEFAULT_K),
    }


def group_pairs(inp):
    """Effective values and yield point of every pair (constructors and properties)."""
    pairs = build_pairs(inp)
    out = {}
    for name in ("effective_modulus", "effective_radius", "effective_mass", "limiting_pressure"):
        out[name] = np.array([getattr(p, name) for p in pairs])
    out["density"] = np.array([math.nan if p.density is None else p.density for p in pairs])
    for name in ("yield_velocity", "yield_approach", "yield_force", "yield_contact_radius"):
        out[name] = np.array([getattr(p, name) for p in pairs])
    out["ning_loading_time"] = np.array([p.ning_loading_time() for p in pairs])
    out["deresiewicz_contact_time"] = np.stack(
        [np.asarray(p.deresiewicz_contact_time(v), dtype=float) for p, v in zip(pairs, inp["speeds"], strict=True)]
    )
    return out


def group_impact_scalar(inp):
    """``pair.impact(float)``: one call per pair and speed (the scalar path)."""
    pairs = build_pairs(inp)
    rows = {f: [] for f in RESULT_FIELDS}
    rest = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mi.LargeStrainWarning)
        for p, speeds in zip(pairs, inp["speeds"], strict=True):
            res = [p.impact(float(V)) for V in speeds]
            for f in RESULT_FIELDS:
                rows[f].append([getattr(r, f)[()] for r in res])
            rest.append([p.restitution(float(V)) for V in speeds])
    out = {f: _stack(rows[f]) for f in RESULT_FIELDS}
    out["pair_restitution"] = np.array(rest, dtype=float)
    return out


def group_impact_array(inp):
    """``pair.impact(array)``: one call per pair over all its speeds (the array path), and 2-D / 0-d calls."""
    pairs = build_pairs(inp)
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mi.LargeStrainWarning)
        res = [p.impact(speeds) for p, speeds in zip(pairs, inp["speeds"], strict=True)]
        two_d = pairs[0].impact(inp["speeds"][0].reshape(-1, 4)[:, ::-1])
        zero_d = pairs[0].impact(np.array(50.0))
    for f in RESULT_FIELDS:
        out[f] = np.stack([np.asarray(getattr(r, f)) for r in res])
        out["2d_" + f] = np.asarray(getattr(two_d, f))
        out["0d_" + f] = np.asarray(getattr(zero_d, f))
    out["pair_restitution"] = np.stack(
        [np.asarray(p.restitution(s), dtype=float) for p, s in zip(pairs, inp["speeds"], strict=True)]
    )
    return out


def group_impact_functions(inp):
    """Module functions of :mod:`microimpact.impact` and :mod:`microimpact.dynamics`, broadcast over pairs x speeds."""
    pairs = build_pairs(inp)
    E, R, m, py = _pair_columns(pairs)
    V = inp["speeds"]
    out = {}
    outcome = impact.impact_outcome(V, E, R, m, py)
    for k, v in outcome.items():
        out["impact_outcome_" + k] = np.asarray(v)
    for k, v in dynamics.contact_times(V, E, R, m, py).items():
        out["contact_times_" + k] = np.asarray(v)
    Vy = impact.yield_velocity(py, E, R, m)
    out["yield_velocity"] = np.asarray(Vy)
    dens = inp["random_density"]
    out["yield_velocity_sphere_on_flat"] = np.asarray(
        impact.yield_velocity_sphere_on_flat(inp["random_pressure"], inp["random_modulus"], dens)
    )
    out["restitution_coefficient"] = np.asarray(impact.restitution_coefficient(V, Vy))
    # The denormal speed 5e-324 is left out here: V_y / V overflows (a RuntimeWarning, e = 1 still).
    keep = ~np.any(V == 5e-324, axis=0)
    out["thornton_ning_restitution"] = np.asarray(impact.thornton_ning_restitution(V[:, keep], Vy))
    out["energy_loss_fraction"] = np.asarray(impact.energy_loss_fraction(out["restitution_coefficient"]))
    out["elastic_max_approach"] = np.asarray(impact.elastic_max_approach(V, E, R, m))
    v = inp["v_normalized"]
    for name in (
        "normalized_max_approach",
        "normalized_max_force",
        "normalized_plastic_approach",
        "normalized_unloading_radius",
        "normalized_restitution",
    ):
        out[name] = np.asarray(getattr(impact, name)(v))
    out["hertz_contact_time"] = np.asarray(dynamics.hertz_contact_time(V, E, R, m))
    out["deresiewicz_contact_time"] = np.asarray(dynamics.deresiewicz_contact_time(V, E, R, m))
    out["ning_loading_time"] = np.asarray(dynamics.ning_loading_time(py, R, m))
    out["plastic_frequency"] = np.asarray(dynamics.plastic_frequency(py, R, m))
    for name in ("elastic_stage_time", "plastic_stage_time", "unloading_time"):
        out[name] = np.asarray(getattr(dynamics, name)(V, E, R, m, py))
    out["incomplete_beta"] = np.asarray(dynamics.incomplete_beta(inp["beta_u"]))
    return out


def group_contact(inp):
    """The force laws of :mod:`microimpact.contact` over approaches scaled by each pair's R*."""
    pairs = build_pairs(inp)
    E, R, m, py = _pair_columns(pairs)
    a = inp["approach_over_radius"][None, :] * R
    out = {
        "hertz_force": contact.hertz_force(a, E, R),
        "hertz_contact_radius": contact.hertz_contact_radius(a, R),
        "hertz_central_pressure": contact.hertz_central_pressure(a, E, R),
        "yield_contact_radius": contact.yield_contact_radius(py, E, R),
        "yield_approach": contact.yield_approach(py, E, R),
        "yield_force": contact.yield_force(py, E, R),
        "loading_force": contact.loading_force(a, E, R, py),
        "contact_force_loading": contact.contact_force(a, E, R, py),
        "equivalent_elastic_force": contact.equivalent_elastic_force(a, E, R),
    }
    finite = np.isfinite(py[:, 0])
    out["plastic_loading_force"] = contact.plastic_loading_force(a[finite], E[finite], R[finite], py[finite])
    # Unloading from the maximum approach of an impact at 3 V_y (or 10 m/s when elastic).
    Vy = np.array([p.yield_velocity for p in pairs])[:, None]
    V = np.where(np.isfinite(Vy), 3.0 * Vy, 10.0)
    o = impact.impact_outcome(V, E, R, m, py)
    a_star, P_star = o["max_approach"], o["max_force"]
    out["unloading_radius"] = contact.unloading_radius(a_star, P_star, E, R)
    out["plastic_approach"] = contact.plastic_approach(a_star, P_star, E, R)
    frac = np.linspace(0.0, 1.0, 11)[None, :]
    a_p = o["plastic_approach"]
    a_u = a_p + frac * (a_star - a_p)
    out["unloading_force"] = contact.unloading_force(a_u, a_p, out["unloading_radius"], E)
    out["contact_force_unloading"] = contact.contact_force(a_u, E, R, py, max_approach=a_star)
    out["normalized_loading_force"] = contact.normalized_loading_force(inp["alpha_hat"])
    ah = inp["alpha_hat"][:, None]
    mah = inp["max_alpha_hat"][None, :]
    out["normalized_unloading_force"] = contact.normalized_unloading_force(np.minimum(ah, mah), mah)
    return {k: np.asarray(v) for k, v in out.items()}


def group_materials(inp):
    """Effective values of :mod:`microimpact.materials` (and ``mi.effective_*``)."""
    return {
        "effective_modulus": np.asarray(
            mi.effective_modulus(inp["mat_E1"], inp["mat_nu1"], inp["mat_E2"], inp["mat_nu2"])
        ),
        "effective_radius": np.asarray(mi.effective_radius(inp["mat_R1"], inp["mat_R2"])),
        "effective_mass": np.asarray(mi.effective_mass(inp["mat_m1"], inp["mat_m2"])),
        "sphere_mass": np.asarray(materials.sphere_mass(inp["random_radius"], inp["random_density"])),
    }


def group_history(inp):
    """``pair.history(V)`` (closed form) on its default grid and at given times, and ``dynamics.impact_history``."""
    pairs = build_pairs(inp)
    out = {}
    for j, (i, V) in enumerate(zip(inp["history_pair"], inp["history_velocity"], strict=True)):
        p = pairs[int(i)]
        h = p.history(float(V), n=101)
        t_c = h.contact_time
        ht = p.history(float(V), times=inp["history_times_fraction"] * t_c)
        d = dynamics.impact_history(
            float(V), p.effective_modulus, p.effective_radius, p.effective_mass, p.limiting_pressure, n=33
        )
        for name in HISTORY_ARRAYS:
            out[f"{j}_grid_{name}"] = np.asarray(getattr(h, name))
            out[f"{j}_times_{name}"] = np.asarray(getattr(ht, name))
            out[f"{j}_function_{name}"] = np.asarray(d[name])
        out[f"{j}_hertz_force_along"] = np.asarray(dynamics.hertz_force_along(h))
        for name in HISTORY_SCALARS:
            out[f"{j}_scalar_{name}"] = np.float64(getattr(h, name))
            out[f"{j}_function_scalar_{name}"] = np.float64(d[name])
    return out


def group_sweep(inp):
    """Two small sweeps: speed x p_y x radius, and speed x particle modulus x surface Poisson ratio."""
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mi.LargeStrainWarning)
        ds1 = sweep(inp["sweep_velocity"], limiting_pressure=inp["sweep_pressure"], radius=inp["sweep_radius"])
        ds2 = sweep(
            inp["sweep_velocity"],
            particle_modulus=inp["sweep_particle_modulus"],
            surface_poisson=inp["sweep_surface_poisson"],
            base="mica",
        )
    for tag, ds in (("a", ds1), ("b", ds2)):
        for name in SWEEP_VARIABLES:
            if name in ds.data_vars:
                out[f"{tag}_{name}"] = np.asarray(ds[name].values)
        for name in ds.coords:
            out[f"{tag}_coord_{name}"] = np.asarray(ds[name].values)
    return out


def group_fit(inp):
    """``fit_restitution`` on the seeded synthetic data: least squares, with sigma, robust, and in V_y."""
    base = mi.ContactPair.paper_case("silicon").replace(limiting_pressure=100e6)
    V, e, s = inp["fit_velocity"], inp["fit_restitution"], inp["fit_sigma"]
    fits = {
        "ls": fit_restitution(V, e, base),
        "sigma": fit_restitution(V, e, base, sigma=s, confidence=0.9),
        "soft_l1": fit_restitution(V, e, base, loss="soft_l1"),
        "vy": fit_restitution(V, e, base, params=("yield_velocity",)),
        "modulus": fit_restitution(V, e, base, params="effective_modulus"),
    }
    out = {}
    Vb = inp["fit_band_velocity"]
    for tag, f in fits.items():
        (name,) = f.params
        out[f"{tag}_param"] = np.float64(f.params[name])
        out[f"{tag}_stderr"] = np.float64(f.stderr[name])
        out[f"{tag}_conf_int"] = np.array(f.conf_int[name])
        out[f"{tag}_covariance"] = np.asarray(f.covariance)
        out[f"{tag}_log_covariance"] = np.asarray(f.log_covariance)
        out[f"{tag}_yield_velocity"] = np.float64(f.yield_velocity)
        out[f"{tag}_yield_velocity_stderr"] = np.float64(f.yield_velocity_stderr)
        out[f"{tag}_yield_velocity_conf_int"] = np.array(f.yield_velocity_conf_int)
        out[f"{tag}_residuals"] = np.asarray(f.residuals)
        out[f"{tag}_chi2"] = np.float64(f.chi2)
        out[f"{tag}_rss"] = np.float64(f.rss)
        out[f"{tag}_reduced_chi2"] = np.float64(f.reduced_chi2)
        out[f"{tag}_quantile"] = np.float64(f.quantile)
        out[f"{tag}_f_scale"] = np.float64(f.f_scale)
        out[f"{tag}_dof"] = np.int64(f.dof)
        out[f"{tag}_n_points"] = np.int64(f.n_points)
        out[f"{tag}_n_elastic"] = np.int64(f.n_elastic)
        out[f"{tag}_success"] = np.bool_(f.success)
        out[f"{tag}_predict"] = np.asarray(f.predict(Vb))
        lo, hi = f.confidence_band(Vb)
        out[f"{tag}_band_lo"] = np.asarray(lo)
        out[f"{tag}_band_hi"] = np.asarray(hi)
        lo, hi = f.confidence_band(Vb, confidence=0.5)
        out[f"{tag}_band50_lo"] = np.asarray(lo)
        out[f"{tag}_band50_hi"] = np.asarray(hi)
        for k in ("effective_modulus", "effective_radius", "effective_mass", "limiting_pressure"):
            out[f"{tag}_pair_{k}"] = np.float64(getattr(f.pair, k))
    return out


def _wall_outputs(res, prefix):
    out = {}
    for name in WALL_FIELDS:
        value = getattr(res, name)
        if value is None:
            continue
        out[prefix + name] = np.asarray(value)
    return out


def group_wall(inp):
    """``wall_interaction`` on seeded random vectors: effective values, materials, one particle."""
    out = {}
    kw = {
        "effective_modulus": inp["wall_modulus"],
        "limiting_pressure": inp["wall_pressure"],
        "work_of_adhesion": inp["wall_adhesion"],
        "friction": inp["wall_friction"],
    }
    v, n, d, rho = inp["wall_velocity"], inp["wall_normal"], inp["wall_diameter"], inp["wall_density"]
    out.update(_wall_outputs(wall_interaction(v, n, d, rho, **kw), "eff_"))
    out.update(_wall_outputs(wall_interaction(v, n, d, rho, spin=inp["wall_spin"], **kw), "spin_"))
    out.update(_wall_outputs(wall_interaction(v, n[0], d, rho, effective_modulus=3e9, limiting_pressure=1e8), "plain_"))
    out.update(
        _wall_outputs(
            wall_interaction(v, n, d, material="nh4fl", wall="silicon", work_of_adhesion=0.05, friction=0.3), "nh4fl_"
        )
    )
    out.update(
        _wall_outputs(
            wall_interaction(v, n, d, material=list(inp["wall_material"]), wall="steel", friction=0.2, k=2.1),
            "mixed_",
        )
    )
    out.update(
        _wall_outputs(
            wall_interaction(
                v[2], n[2], 4.9e-6, 1350.0, effective_modulus=1.31e9, limiting_pressure=156e6, friction=0.3
            ),
            "single_",
        )
    )
    return out


def group_adhesion(inp):
    """``sticking_velocity``, ``work_of_adhesion``, ``adhesive_restitution`` and ``restitution_table``."""
    pairs = build_pairs(inp)
    E, R, m, _ = _pair_columns(pairs)
    G = np.concatenate([[0.0], np.geomspace(1e-3, 1.0, 5)])[None, :]
    V = inp["adh_velocity"][:, None, None]
    Vy = inp["adh_yield_velocity"][None, :, None]
    Vs = inp["adh_sticking_velocity"][None, None, :]
    return {
        "sticking_velocity": np.asarray(mi.sticking_velocity(G, E, R, m)),
        "work_of_adhesion_pair": np.asarray(mi.work_of_adhesion(inp["adh_gamma1"], inp["adh_gamma2"])),
        "work_of_adhesion_same": np.asarray(mi.work_of_adhesion(inp["adh_gamma1"])),
        "adhesive_restitution": np.asarray(mi.adhesive_restitution(V, Vy, Vs)),
        "restitution_table": np.asarray(restitution_table(inp["table_v_over_vy"], inp["table_vs_over_vy"])),
    }


GROUPS = {
    "constants": group_constants,
    "pairs": group_pairs,
    "impact_scalar": group_impact_scalar,
    "impact_array": group_impact_array,
    "impact_functions": group_impact_functions,
    "contact": group_contact,
    "materials": group_materials,
    "history": group_history,
    "sweep": group_sweep,
    "fit": group_fit,
    "wall": group_wall,
    "adhesion": group_adhesion,
}


# ============================================================================ file
def load_reference(path=REFERENCE_FILE):
    """``(inputs, outputs)``: ``inputs[name]`` and ``outputs[group][name]`` as arrays."""
    with np.load(path, allow_pickle=False) as z:
        data = {k: z[k] for k in z.files}
    inputs = {k[3:]: v for k, v in data.items() if k.startswith("in/")}
    outputs: dict[str, dict[str, np.ndarray]] = {}
    for k, v in data.items():
        if k.startswith("out/"):
            group, name = k[4:].split("/", 1)
            outputs.setdefault(group, {})[name] = v
    return inputs, outputs


def main(path=REFERENCE_FILE) -> None:
    inp = make_inputs()
    data = {f"in/{k}": np.asarray(v) for k, v in inp.items()}
    for group, fn in GROUPS.items():
        for k, v in fn(inp).items():
            data[f"out/{group}/{k}"] = np.asarray(v)
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp.npz")  # np.savez_compressed appends .npz to other names
    np.savez_compressed(tmp, **data)
    os.replace(tmp, path)
    n_out = sum(1 for k in data if k.startswith("out/"))
    print(f"wrote {path.name}: {len(data) - n_out} inputs, {n_out} outputs, {path.stat().st_size / 1e6:.2f} MB")


if __name__ == "__main__":
    main(*sys.argv[1:])
