"""13. A sweep written to CSV against the same sweep written to NetCDF (dask chunks chosen
automatically, each file through a temporary file beside its target), in the same process,
interleaved (NetCDF, CSV, NetCDF, CSV), best of each."""

import time

import numpy as np
import pytest

KEY = "csv_sweep"


def test_csv_against_netcdf(record, size, pair, tmp_path):
    pytest.importorskip("netCDF4")
    pytest.importorskip("polars")
    from microimpact.sweep import sweep, sweep_to_csv, sweep_to_netcdf

    n = size["sweep"]
    density = np.linspace(1000.0, 3000.0, 1000 if n >= 10**5 else 10)
    velocity = np.linspace(1.0, 120.0, n // density.size)
    ds = sweep(velocity, density=density, base=pair, chunks="auto")
    best = {}
    for _ in range(2 if n < 10**7 else 1):
        for label, write, name in (("NetCDF", sweep_to_netcdf, "s.nc"), ("CSV", sweep_to_csv, "s.csv")):
            t0 = time.perf_counter()
            write(ds, tmp_path / name)
            best[label] = min(best.get(label, float("inf")), time.perf_counter() - t0)
    for label, seconds in best.items():
        record.time(KEY, label, seconds)
    record.metric(KEY, "points", velocity.size * density.size)
    record.metric(KEY, "csv_bytes", (tmp_path / "s.csv").stat().st_size)
    with open(tmp_path / "s.csv") as fh:  # the last row reads back bit for bit
        *_, last = fh
    cells = [float(c) for c in last.split(",")]
    assert cells[0] == velocity[-1] and cells[1] == density[-1]
    assert cells[2] == float(ds["restitution"].isel(velocity=-1, density=-1))
