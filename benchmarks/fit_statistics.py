"""Coverage, bias and model-ranking frequencies of ``microimpact.fitting`` over many seeded draws.

``python benchmarks/fit_statistics.py [DRAWS]`` (default 1000 draws for coverage, DRAWS/10 for
ranking). The test suite checks the same quantities with fewer draws and binomial bounds; this
script gives the numbers quoted in the docs. Data: the seed's e(V) for the mica case plus seeded
Gaussian noise 0.02, never clipped; 16 speeds from 0.8 to 12 V_y (about 1.6 values above 1 per
set), or 8 speeds from 0.5 to 6 V_y with only 5 above V_y (the profile interval's case).
Ranking: data from the seed and from a power law ``e = (V/V_y)^-0.5`` (the stand-in zoo model of
``tests/test_fitting_models.py``), ranked among the seed, the power law (p_y and exponent free) and
a constant ``e = e0``, at three noise levels. Nothing is written; the table is printed.
"""

from __future__ import annotations

import pathlib
import sys
import warnings

import numpy as np

import microimpact as mi
from microimpact.fitting import LOSSES, SEED_MODEL, FitWarning, fit_restitution

MICA = mi.ContactPair.paper_case("mica")


def coverage(kind, draws, V, **kw):
    truth = MICA.limiting_pressure
    hits, est = 0, []
    for s in range(draws):
        e = MICA.restitution(V) + np.random.default_rng(900_000 + s).normal(0.0, 0.02, V.size)
        fit = fit_restitution(V, e, MICA.replace(limiting_pressure=truth * 0.5), **kw)
        lo, hi = fit.conf_int["limiting_pressure"]
        hits += lo <= truth <= hi
        est.append(fit.params["limiting_pressure"])
    est = np.asarray(est) / truth - 1
    c = hits / draws
    print(
        f"{kind:34s} {fit.interval:8s} coverage {c:.3f} +- {np.sqrt(c * (1 - c) / draws):.3f}   "
        f"bias {100 * est.mean():+.3f} % +- {100 * est.std(ddof=1) / np.sqrt(draws):.3f} %",
        flush=True,
    )


def ranking(draws):
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests"))
    import test_fitting_models as t  # the stand-in zoo models

    from microimpact.core import models as zoo

    real_available, real_get = zoo.available, zoo.get
    zoo.available = lambda: [*real_available(), *t.FAKE]
    zoo.get = lambda name=zoo.DEFAULT: t.FAKE[name] if name in t.FAKE else real_get(name)
    for truth in (SEED_MODEL, "power_law"):
        for noise in (0.01, 0.02, 0.05):
            counts = t.rank_first_counts(truth, noise, seed0=700_000, draws=draws)
            print(
                f"data from {truth:18s} noise {noise:.2f}: ranked first "
                + ", ".join(f"{k} {v}/{draws}" for k, v in counts.items()),
                flush=True,
            )
    zoo.available, zoo.get = real_available, real_get


def main() -> int:
    draws = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
    near = MICA.yield_velocity * np.geomspace(0.8, 12.0, 16)
    few = MICA.yield_velocity * np.array([0.5, 0.7, 0.9, 1.1, 1.5, 2.2, 3.5, 6.0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FitWarning)
        coverage("least squares (residual scale)", draws, near)
        coverage("least squares (absolute sigma)", draws, near, sigma=0.02)
        for loss in LOSSES[1:]:
            coverage(loss, draws, near, loss=loss)
        for loss in ("linear", "soft_l1"):
            coverage(f"{loss}, 5 points above V_y", draws, few, loss=loss)
            coverage(f"{loss}, 5 points above V_y (Wald)", draws, few, loss=loss, interval="wald")
        ranking(max(draws // 10, 10))
    return 0


if __name__ == "__main__":
    sys.exit(main())
