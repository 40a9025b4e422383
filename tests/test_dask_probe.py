"""xarray's probe for dask arrays skipped while none can exist (microimpact._optional.without_dask_probe).

Building a Dataset of numpy data makes xarray import dask.array to ask whether the data are dask
arrays (half a second). Before that module is imported no object can be one, so the command
line's small sweep and the comparison skip the question: the Dataset is the one built with dask
imported, and a later lazy computation imports dask as before.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

pytest.importorskip("xarray")
pytest.importorskip("dask")

_CODE = """
import sys
import xarray as xr
import microimpact as mi
from microimpact._optional import without_dask_probe
ds = mi.compare_models("silicon", [10.0, 50.0], ["thornton_ning_2016", "hertz_viscoelastic"])
from microimpact.sweep import sweep
with without_dask_probe():  # as the command line's small sweep does, written to NetCDF too
    small = sweep([5.0, 50.0])
    small.to_netcdf(sys.argv[1])
assert "dask.array" not in sys.modules, "a numpy-only comparison imported dask.array"
assert "dask" not in sys.modules, "a numpy-only comparison imported dask (xarray's collection check)"
from xarray.namedarray import utils
assert utils.is_dask_collection.__module__.startswith("xarray"), "the collection check was not given back"
import dask.array as da
with without_dask_probe():  # dask imported: a dask collection is seen as one
    assert utils.is_dask_collection(da.zeros(3))
with without_dask_probe():  # dask.array imported: the probe answers as usual
    assert xr.Variable("x", da.zeros(3)).chunks == ((3,),)
again = mi.compare_models("silicon", [10.0, 50.0], ["thornton_ning_2016", "hertz_viscoelastic"])
xr.testing.assert_identical(ds, again)
xr.testing.assert_identical(small, sweep([5.0, 50.0]))
with xr.open_dataset(sys.argv[1]) as back:
    xr.testing.assert_identical(back.load(), small)
from xarray.backends import locks, writers
assert locks.get_dask_scheduler is writers.get_dask_scheduler, "the scheduler check was not given back"
assert writers.get_dask_scheduler() == "threaded"  # dask imported: its answer as before
lazy = sweep([5.0, 50.0], chunks=1)
assert isinstance(lazy.restitution.data, da.Array)
print("ok")
"""


def test_numpy_datasets_built_without_dask_array_and_identical(tmp_path):
    pytest.importorskip("netCDF4")
    nc = str(tmp_path / "small.nc")
    out = subprocess.run([sys.executable, "-c", _CODE, nc], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"
