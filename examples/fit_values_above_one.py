"""Fit p_y to rebound data with values above 1 and an outlier, rank two parametrisations, carry the band.

Synthetic data (the seed's e(V) for the silicon case, p_y = 156 MPa, plus seeded Gaussian noise
0.02; they are *not* measurements): 24 speeds from 4 to 110 m/s, so the points near V_y = 7.5 m/s
scatter above 1, and one outlier (a particle that hit a dust grain). The script writes the data
as CSV, fits with least squares and with the robust ``soft_l1`` loss, prints both, ranks the seed's
two parametrisations against a fixed wrong p_y, and draws the fit and the ranking.

Run:  python examples/fit_values_above_one.py [OUTPUT_FOLDER]

Everything goes to OUTPUT_FOLDER (created) or, without it, to a new temporary folder whose name
is printed; nothing is written anywhere else.
"""

from __future__ import annotations

import os
import sys
import tempfile
import warnings

import numpy as np

import microimpact as mi
from microimpact.figures.fit import plot_fit, plot_models
from microimpact.fitting import (
    FitWarning,
    fit_restitution,
    rank_models,
)
from microimpact.io import load_restitution_csv


def write_atomically(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as fh:
        fh.write(text)
    os.replace(tmp, path)


def save_figure(fig, path):
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=150)
    os.replace(tmp, path)


def main(out_dir=None) -> int:
    out_dir = out_dir or tempfile.mkdtemp(prefix="microimpact-fit-")
    os.makedirs(out_dir, exist_ok=True)
    truth = mi.ContactPair.paper_case("silicon")
    rng = np.random.default_rng(2026)
    V = np.geomspace(4.0, 110.0, 24)
    e = truth.restitution(V) + rng.normal(0.0, 0.02, V.size)
    e[13] -= 0.3  # the outlier
    csv_path = os.path.join(out_dir, "synthetic_rebounds.csv")
    rows = "".join(f"{v:.3f},{x:.4f}\n" for v, x in zip(V, e))
    write_atomically(
        csv_path,
        "# synthetic: seed model, p_y = 156 MPa, noise 0.02, one outlier\nvelocity [m/s],e\n"
        + rows,
    )

    data = load_restitution_csv(csv_path)
    print(
        f"{int(np.sum(data.restitution > 1))} of {len(data.velocity)} measured values lie above 1"
    )
    start = truth.replace(
        limiting_pressure=80e6
    )  # the fit must not depend on the start
    with warnings.catch_warnings():
        warnings.simplefilter(
            "ignore", FitWarning
        )  # the outlier lies below the curve, this is for e > 1
        plain = fit_restitution(
            data.velocity, data.restitution, start, line_numbers=data.lines
        )
        robust = fit_restitution(
            data.velocity,
            data.restitution,
            start,
            loss="soft_l1",
            line_numbers=data.lines,
        )
    print("least squares:", repr(plain))
    print("soft_l1:      ", repr(robust))

    pred = robust.predict([20.0, 50.0, 100.0], band=True)
    for v, lo, mid, hi in zip(
        pred.velocity,
        pred.rebound_velocity_lo,
        pred.rebound_velocity,
        pred.rebound_velocity_hi,
    ):
        print(
            f"V = {v:5.1f} m/s: rebound speed {mid:.2f} m/s, 95 % band [{lo:.2f}, {hi:.2f}]"
        )

    ranking = rank_models(
        data.velocity,
        data.restitution,
        start,
        [
            "thornton_ning_2016",
            "thornton_ning_2016:effective_modulus",
            "thornton_ning_2016:none",
        ],
        loss="soft_l1",
    )
    print(ranking.table())

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ax, _ = plot_fit(robust, data.velocity, data.restitution)
    ax.set_title(
        "soft_l1 fit of synthetic data with values above 1 and an outlier",
        fontsize="medium",
    )
    save_figure(ax.figure, os.path.join(out_dir, "fit.png"))
    ax, _ = plot_models(ranking)
    save_figure(ax.figure, os.path.join(out_dir, "ranking.png"))
    plt.close("all")
    print(f"wrote synthetic_rebounds.csv, fit.png and ranking.png to {out_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else None))
