"""Sweeps (:mod:`microimpact.sweep`) and the ``microimpact sweep`` command.

A sweep must equal the pointwise results of :meth:`ContactPair.impact`; the
lazy (dask) path must equal the eager one bit for bit and stay lazy until
computed; files written by the CLI must read back equal to the API.
"""

import importlib
import pickle
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

xr = pytest.importorskip("xarray")
da = pytest.importorskip("dask.array")
pd = pytest.importorskip("pandas")

import microimpact as mi  # noqa: E402
from microimpact._optional import MissingExtraError  # noqa: E402
from microimpact.cli import main  # noqa: E402
from microimpact.materials import effective_modulus  # noqa: E402
from microimpact.sweep import SWEEP_VARIABLES, sweep, sweep_to_csv, sweep_to_netcdf  # noqa: E402

# the module itself (robust if the package ever exports the function ``sweep`` under the same name)
msweep = importlib.import_module("microimpact.sweep")

# speeds on both sides of V_y (7.52 m/s for silicon), the paper's 30/50/70, 0 and the top of its range
V = np.array([0.0, 2.0, 7.5, 7.6, 30.0, 50.0, 70.0, 120.0])
SILICON = mi.ContactPair.paper_case("silicon")
IMPACT_FIELDS = [f for f in mi.pair.RESULT_FIELDS if f != "velocity"] + ["yield_velocity"]


def assert_pointwise(ds, pair, **sel):
    """Every field of ``pair.impact(V)`` equals the sweep at ``sel``.

    Same formulas, same inputs; numpy's vectorized ``pow`` on arrays may differ from its scalar
    ``pow`` in the last bit, hence 1e-14 rather than exact equality (infinities must match).
    """
    ref = pair.impact(ds.velocity.values, warn=False)
    point = ds.sel(**sel)
    for name in IMPACT_FIELDS:
        got = point[name].broadcast_like(point.restitution).values
        want = np.broadcast_to(getattr(ref, name), got.shape)
        if got.dtype == bool:
            np.testing.assert_array_equal(got, want, err_msg=name)
        else:
            np.testing.assert_allclose(got, want, rtol=1e-14, atol=0, err_msg=name)
    np.testing.assert_allclose(point.effective_modulus.values, pair.effective_modulus, rtol=1e-15)
    np.testing.assert_allclose(point.effective_mass.values, pair.effective_mass, rtol=1e-15)


# --------------------------------------------------------------------------- pointwise equality
def test_velocity_by_limiting_pressure_is_pointwise():
    p_y = np.array([50e6, 100e6, 150e6, 200e6, 250e6])  # the seed's Fig. 3
    ds = sweep(V, limiting_pressure=p_y)
    assert dict(ds.sizes) == {"velocity": V.size, "limiting_pressure": p_y.size}
    for p in p_y:
        assert_pointwise(ds, SILICON.replace(limiting_pressure=p), limiting_pressure=p)
    assert ds.yield_velocity.dims == ("limiting_pressure",)


def test_velocity_by_particle_modulus_follows_fig4_definition():
    # Fig. 4: E1 = 1.2 ... 21.2 GPa on a surface of E2 = 150 GPa, nu = 0.3 for both
    E1 = np.array([1.2e9, 6.2e9, 11.2e9, 16.2e9, 21.2e9])
    ds = sweep(V, particle_modulus=E1)
    assert "150" in ds.attrs["material_defaults"]
    for e1 in E1:
        Estar = float(effective_modulus(e1, 0.3, 150e9, 0.3))
        pair = mi.ContactPair.sphere_on_flat(2.45e-6, 1350.0, Estar, 156e6)
        assert_pointwise(ds, pair, particle_modulus=e1)
    # a stiffer particle: higher E*, lower V_y (eq. 28: V_y ~ E*^-2), lower e at 50 m/s
    assert np.all(np.diff(ds.yield_velocity.values) < 0)
    assert np.all(np.diff(ds.restitution.sel(velocity=50.0).values) < 0)


def test_derived_particle_modulus_reproduces_base_pair():
    # A material input given as a scalar switches E* to the material form; with the defaults it is
    # the base pair's E* again (E1 = 1.2017 GPa for the silicon case, the paper's 1.2 GPa).
    ds = sweep(V, surface_modulus=150e9)
    assert float(ds.effective_modulus) == pytest.approx(SILICON.effective_modulus, rel=1e-12)
    assert "E1 = 1.2016" in ds.attrs["material_defaults"]
    ref = SILICON.impact(V, warn=False)
    np.testing.assert_allclose(ds.restitution.values, ref.restitution, rtol=1e-12)


def test_density_and_radius_are_pointwise():
    rho = np.array([1350.0, 2350.0, 3350.0, 4350.0, 5350.0])  # Fig. 5
    R = np.array([0.5e-6, 2.45e-6, 10e-6])
    ds = sweep(V, density=rho, radius=R)
    assert ds.effective_mass.dims == ("density", "radius")
    assert ds.effective_radius.dims == ("radius",)
    for r in R:
        for d in rho:
            pair = mi.ContactPair.sphere_on_flat(r, d, 1.31e9, 156e6)
            assert_pointwise(ds, pair, density=d, radius=r)
    # eq. 28: for a sphere on a flat V_y does not depend on the radius
    vy = ds.yield_velocity.values
    np.testing.assert_allclose(vy, np.broadcast_to(vy[:, :1], vy.shape), rtol=1e-13)
    np.testing.assert_allclose(vy[:, 0], mi.yield_velocity_sphere_on_flat(156e6, 1.31e9, rho), rtol=1e-13)


def test_material_base_pair_and_poisson_sweep():
    base = mi.ContactPair.from_materials("nh4fl", "silicon", radius=2.45e-6, limiting_pressure=156e6)
    nu2 = np.array([0.1, 0.22, 0.4])
    ds = sweep(V, surface_poisson=nu2, surface_modulus=61e9, base=base)
    assert "nh4fl" in ds.attrs["material_defaults"]
    for nu in nu2:
        Estar = float(effective_modulus(1.2e9, 0.3, 61e9, nu))
        assert_pointwise(ds, base.replace(effective_modulus=Estar), surface_poisson=nu)
    assert float(ds.surface_modulus) == 61e9 and "surface_modulus" not in ds.dims


def test_effective_modulus_and_scalar_overrides():
    Es = np.array([0.5e9, 1.31e9, 5e9])
    ds = sweep(V, effective_modulus=Es, limiting_pressure=100e6, base="mica")
    assert ds.limiting_pressure.ndim == 0 and float(ds.limiting_pressure) == 100e6
    mica = mi.ContactPair.paper_case("mica")
    for E in Es:
        assert_pointwise(ds, mica.replace(effective_modulus=E, limiting_pressure=100e6), effective_modulus=E)


def test_paper_rebound_velocity_through_a_sweep():
    ds = sweep(np.array([50.0]))
    # seed Sec. 3.2: rebound at 50 m/s is 36.31 m/s (its inputs rounded; within 1 %)
    assert float(ds.rebound_velocity.sel(velocity=50.0)) == pytest.approx(36.31, rel=0.01)
    assert float(ds.yield_velocity) == pytest.approx(7.59, rel=0.01)


def test_scalar_velocity_gives_no_dimension():
    ds = sweep(50.0)
    assert ds.restitution.ndim == 0
    assert float(ds.restitution) == float(SILICON.impact(50.0, warn=False).restitution)


# --------------------------------------------------------------------------- attrs
def test_units_in_attrs():
    ds = sweep(
        V,
        limiting_pressure=np.array([1e8, 2e8]),
        density=np.array([1e3, 2e3]),
        radius=np.array([1e-6, 2e-6]),
        particle_poisson=np.array([0.2, 0.3]),
    )
    for name in ds.variables:
        assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, name
    expect = {
        "velocity": "m/s",
        "limiting_pressure": "Pa",
        "density": "kg/m^3",
        "radius": "m",
        "particle_poisson": "1",
        "restitution": "1",
        "max_force": "N",
        "contact_time": "s",
        "max_approach": "m",
        "yield_velocity": "m/s",
        "effective_mass": "kg",
        "effective_modulus": "Pa",
    }
    for name, unit in expect.items():
        assert ds[name].attrs["units"] == unit, name
    assert set(ds.data_vars) == set(SWEEP_VARIABLES)
    assert ds.elastic.dtype == bool and ds.large_strain.dtype == bool


# --------------------------------------------------------------------------- dask
BIG = dict(
    limiting_pressure=np.linspace(50e6, 250e6, 4),
    particle_modulus=np.array([1.2e9, 6.2e9, 21.2e9]),
    density=np.array([1350.0, 5350.0]),
    radius=np.array([1e-6, 2.45e-6, 4e-6, 9e-6, 2e-5]),
)
VV = np.concatenate([[0.0], np.linspace(1.0, 120.0, 37)])


@pytest.mark.parametrize("chunks", [5, {"velocity": 7, "radius": 2}, "auto", {"limiting_pressure": 1}])
def test_dask_equals_eager_exactly(chunks):
    eager = sweep(VV, **BIG)
    lazy = sweep(VV, chunks=chunks, **BIG)
    computed = lazy.compute()
    for name in eager.data_vars:
        assert computed[name].dims == eager[name].dims
        assert computed[name].dtype == eager[name].dtype, name
        np.testing.assert_array_equal(computed[name].values, eager[name].values, err_msg=name)
    xr.testing.assert_identical(computed, eager)


@settings(max_examples=10, deadline=None)
@given(cv=st.integers(1, 40), cp=st.integers(1, 4))
def test_dask_equals_eager_any_blocks(cv, cp):
    kw = dict(limiting_pressure=BIG["limiting_pressure"])
    eager = sweep(VV, **kw)
    lazy = sweep(VV, chunks={"velocity": cv, "limiting_pressure": cp}, **kw)
    assert lazy.restitution.data.chunks[0][0] == min(cv, VV.size)
    xr.testing.assert_identical(lazy.compute(), eager)


def test_lazy_until_computed(monkeypatch):
    calls = []
    original = msweep._evaluate

    def counting(group, p, spec):
        calls.append(group)
        return original(group, p, spec)

    monkeypatch.setattr(msweep, "_evaluate", counting)
    ds = sweep(VV, limiting_pressure=BIG["limiting_pressure"], radius=BIG["radius"], chunks=10)
    assert "impact" not in calls and "yield_velocity" not in calls  # nothing swept evaluated yet
    for name in ("restitution", "contact_time", "elastic", "yield_velocity", "effective_mass"):
        assert isinstance(ds[name].data, da.Array), name
    assert ds.restitution.data.numblocks == (4, 1, 1)
    total = float(ds.restitution.sum())  # a reduction computes block by block
    assert calls.count("impact") == 4  # once per block, not once per variable
    assert total == pytest.approx(
        float(sweep(VV, limiting_pressure=BIG["limiting_pressure"], radius=BIG["radius"]).restitution.sum()), rel=1e-14
    )


def test_graph_pickles_for_a_cluster():
    # a dask.distributed scheduler ships tasks by pickling them: the graph must survive
    # plain pickle (module-level kernel, no closures) and compute to the same values
    from dask.threaded import get

    ds = sweep(VV, limiting_pressure=BIG["limiting_pressure"], chunks=9)
    arr = ds.max_force.data
    graph = pickle.loads(pickle.dumps(dict(arr.__dask_graph__())))
    blocks = get(graph, arr.__dask_keys__())
    np.testing.assert_array_equal(
        da.core.concatenate3(blocks), sweep(VV, **{"limiting_pressure": BIG["limiting_pressure"]}).max_force
    )


def test_progress_bar(capsys):
    ds = sweep(VV, limiting_pressure=BIG["limiting_pressure"], progress=True)
    err = capsys.readouterr().err
    assert "100% Completed" in err
    assert not ds.chunks  # computed, in memory
    xr.testing.assert_identical(ds, sweep(VV, limiting_pressure=BIG["limiting_pressure"]))
    with pytest.warns(UserWarning, match="computed by the caller"):
        sweep(VV, chunks=10, progress=True)


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(velocity=np.array([10.0, -1.0])), "velocity"),
        (dict(velocity=V, limiting_pressure=np.array([1e8, -5e7])), "limiting_pressure"),
        (dict(velocity=V, density=np.array([0.0, 1e3])), "density"),
        (dict(velocity=V, radius=np.array([np.nan, 1e-6])), "radius"),
        (dict(velocity=V, particle_modulus=np.array([-1e9, 1e9])), "particle_modulus"),
        (dict(velocity=V, surface_poisson=np.array([0.3, 0.6])), "surface_poisson"),
        (dict(velocity=V, radius=np.ones((2, 2)) * 1e-6), "radius"),
        (dict(velocity=V, density=np.array([])), "density"),
        (dict(velocity=V, chunks={"temperature": 3}), "temperature"),
        (dict(velocity=V, chunks=0), "chunks"),
        (dict(velocity=V, chunks="big"), "chunks"),
        (dict(velocity=V, effective_modulus=1e9, particle_modulus=np.array([1e9, 2e9])), "effective_modulus"),
        (dict(velocity=V, base="granite"), "case"),
        (dict(velocity=V, effective_modulus=np.array([1e9, np.inf])), "effective_modulus"),
    ],
)
def test_bad_input_names_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=name):
        sweep(**kwargs)


def test_two_sphere_base_needs_density_for_radius_sweeps():
    pair = mi.ContactPair.two_spheres("glass", "glass", 1e-6, 2e-6, limiting_pressure=1e9)
    with pytest.raises(ValueError, match="density"):
        sweep(V, radius=np.array([1e-6, 2e-6]), base=pair)
    # without radius/density the two-sphere R*, m* are used as they are
    ds = sweep(V, limiting_pressure=np.array([1e9, 2e9]), base=pair)
    assert_pointwise(ds, pair.replace(limiting_pressure=2e9), limiting_pressure=2e9)


# --------------------------------------------------------------------------- writers and CLI
def test_netcdf_round_trip_both_engines(tmp_path):
    netCDF4 = pytest.importorskip("netCDF4")
    ds = sweep(VV, density=BIG["density"], radius=BIG["radius"], chunks=11)
    eager = sweep(VV, density=BIG["density"], radius=BIG["radius"])
    for engine in ("netcdf4", "scipy"):
        path = sweep_to_netcdf(ds, tmp_path / f"s_{engine}.nc", engine=engine)
        with xr.open_dataset(path, engine=engine) as back:
            for name in eager.variables:
                np.testing.assert_array_equal(back[name].values, eager[name].values, err_msg=name)
                assert back[name].attrs["units"] == eager[name].attrs["units"]
            assert back.elastic.dtype == bool
    with netCDF4.Dataset(tmp_path / "s_netcdf4.nc") as raw:  # stored as int8, as NetCDF needs
        assert raw["elastic"].dtype == np.int8 and raw["large_strain"].dtype == np.int8


def read_csv_sweep(path):
    df = pd.read_csv(path)
    units = {c.split(" [")[0]: c.split(" [")[1].rstrip("]") for c in df.columns}
    df.columns = [c.split(" [")[0] for c in df.columns]
    return df, units


def test_csv_long_format_equals_api(tmp_path):
    eager = sweep(VV, limiting_pressure=BIG["limiting_pressure"], density=BIG["density"])
    lazy = sweep(VV, limiting_pressure=BIG["limiting_pressure"], density=BIG["density"], chunks=6)
    for ds, name in ((eager, "eager.csv"), (lazy, "lazy.csv")):
        df, units = read_csv_sweep(sweep_to_csv(ds, tmp_path / name, rows_per_block=5))
        assert len(df) == VV.size * 4 * 2
        assert list(df.columns[:3]) == ["velocity", "limiting_pressure", "density"]
        assert units["velocity"] == "m/s" and units["max_force"] == "N"
        flat = eager.to_dataframe(dim_order=["velocity", "limiting_pressure", "density"]).reset_index()
        for col in df.columns:
            np.testing.assert_array_equal(df[col].to_numpy(), flat[col].to_numpy().astype(df[col].dtype), err_msg=col)


def test_cli_netcdf_equals_api(tmp_path, capsys):
    out = tmp_path / "fig3.nc"
    rc = main(
        ["sweep", "--velocity", "1:120:60", "--limiting-pressure", "50e6:250e6:5", "--out", str(out), "--chunks", "25"]
    )
    cap = capsys.readouterr()
    assert rc == 0, cap.err
    # stderr is not a terminal here: no progress bar, only the one-line summary
    assert "100% Completed" not in cap.err and "300 points" in cap.err
    ref = sweep(np.linspace(1, 120, 60), limiting_pressure=np.linspace(50e6, 250e6, 5))
    with xr.open_dataset(out) as back:
        xr.testing.assert_equal(back.load(), ref)  # values, dims, coords (attrs checked below)
        assert back.velocity.attrs["units"] == "m/s"
    n_large = int(ref.large_strain.sum())
    assert f"{n_large} of 300 points" in cap.err


def test_cli_csv_equals_api(tmp_path, capsys):
    out = tmp_path / "fig4.csv"
    rc = main(
        [
            "sweep",
            "--velocity",
            "10,50,100",
            "--particle-modulus",
            "1.2e9:21.2e9:5",
            "--density",
            "2000",
            "--out",
            str(out),
            "--no-progress",
        ]
    )
    assert rc == 0
    df, units = read_csv_sweep(out)
    ref = sweep(np.array([10.0, 50.0, 100.0]), particle_modulus=np.linspace(1.2e9, 21.2e9, 5), density=2000.0)
    assert "density" not in df.columns  # one value: an override, not a dimension
    np.testing.assert_array_equal(df["restitution"], ref.restitution.values.ravel())
    np.testing.assert_array_equal(df["contact_time"], ref.contact_time.values.ravel())
    np.testing.assert_array_equal(df["elastic"], ref.elastic.values.ravel().astype(int))
    assert units["particle_modulus"] == "Pa"


def test_cli_materials_base(tmp_path, capsys):
    out = tmp_path / "steel.csv"
    rc = main(
        [
            "sweep",
            "--velocity",
            "5:50:4",
            "--particle",
            "steel",
            "--surface",
            "copper",
            "--radius",
            "1e-6,5e-6",
            "--out",
            str(out),
            "--no-progress",
        ]
    )
    assert rc == 0, capsys.readouterr().err
    df, _ = read_csv_sweep(out)
    pair = mi.ContactPair.from_materials("steel", "copper", radius=5e-6)  # p_y = 2.2 * 70 MPa (copper)
    ref = pair.impact(np.linspace(5, 50, 4), warn=False)
    np.testing.assert_array_equal(df[df.radius == 5e-6]["restitution"], ref.restitution)


@pytest.mark.parametrize(
    "argv, text",
    [
        (["--velocity", "-1:120:5"], "velocity"),
        (["--velocity", "1:120:5", "--limiting-pressure", "-5e6,5e6"], "limiting_pressure"),
        (["--velocity", "1:120:x"], "--velocity"),
        (["--velocity", "1:120:5", "--chunks", "0"], "--chunks"),
        (["--velocity", "1:120:5", "--particle", "steel"], "--surface"),
    ],
)
def test_cli_bad_input_exit_2(tmp_path, capsys, argv, text):
    rc = main(["sweep", *argv, "--out", str(tmp_path / "x.nc")])
    err = capsys.readouterr().err
    assert rc == 2 and text in err and len(err.strip().splitlines()) == 1
    rc = main(["sweep", "--velocity", "1", "--out", str(tmp_path / "x.txt")])
    assert rc == 2 and ".csv" in capsys.readouterr().err


# --------------------------------------------------------------------------- optional extras
def test_missing_xarray_names_the_extra(monkeypatch, tmp_path, capsys):
    monkeypatch.setitem(sys.modules, "xarray", None)  # makes `import xarray` fail
    with pytest.raises(MissingExtraError, match=r"microimpact\[sweep\]"):
        sweep(V)
    rc = main(["sweep", "--velocity", "1:10:3", "--out", str(tmp_path / "x.nc")])
    assert rc == 2 and "microimpact[sweep]" in capsys.readouterr().err


def test_missing_dask_only_matters_for_lazy(monkeypatch):
    monkeypatch.setitem(sys.modules, "dask.array", None)
    eager = sweep(V, limiting_pressure=np.array([1e8, 2e8]))  # works without dask
    assert eager.restitution.shape == (V.size, 2)
    with pytest.raises(MissingExtraError, match=r"microimpact\[sweep\]"):
        sweep(V, limiting_pressure=np.array([1e8, 2e8]), chunks=2)


def test_core_import_needs_no_extras():
    code = (
        "import sys\n"
        "for m in ('xarray', 'dask', 'dask.array', 'netCDF4', 'pandas'): sys.modules[m] = None\n"
        "import microimpact, microimpact.sweep, microimpact.cli.sweep\n"
        "print(microimpact.ContactPair.paper_case().impact(50.0).restitution)\n"
    )
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    assert float(res.stdout) == pytest.approx(0.7248, abs=1e-4)


def test_small_cli_sweep_equals_a_chunked_one_and_a_later_lazy_sweep_still_works(tmp_path):
    """A sweep of one block (computed eagerly, in numpy) writes the same file as a chunked sweep, bit
    for bit, and a lazy sweep afterwards in the same process is lazy and right."""
    code = f"""
import sys
from microimpact.cli import main
assert main(["sweep", "--velocity", "1:120:30", "--density", "1000,2000", "--no-progress",
             "--out", r"{tmp_path / "eager.nc"}"]) == 0
assert main(["sweep", "--velocity", "1:120:30", "--density", "1000,2000", "--chunks", "7", "--no-progress",
             "--out", r"{tmp_path / "lazy.nc"}"]) == 0
import dask.array as da, numpy as np, xarray as xr
from microimpact.sweep import sweep
import microimpact as mi
lazy = sweep(velocity=np.linspace(1, 120, 30), density=[1000.0, 2000.0], base=mi.ContactPair.paper_case("silicon"),
             chunks=7)
assert isinstance(lazy["restitution"].data, da.Array)
with xr.open_dataset(r"{tmp_path / "eager.nc"}") as a, xr.open_dataset(r"{tmp_path / "lazy.nc"}") as b:
    xr.testing.assert_identical(a, b)
    for v in a.data_vars:
        assert a[v].values.tobytes() == b[v].values.tobytes(), v
    np.testing.assert_array_equal(lazy["restitution"].values, a["restitution"].values)
print("ok")
"""
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr[-3000:]
    assert res.stdout.strip().endswith("ok")


def _csv_threads_end(timeout=10.0):
    """Wait until no thread of the CSV writer is left; True if none is."""
    import threading
    import time

    t0 = time.monotonic()
    while any(t.name.startswith("microimpact-csv") for t in threading.enumerate()):
        if time.monotonic() - t0 > timeout:
            return False
        time.sleep(0.01)
    return True


def _csv_pieces(rng):
    """Pieces as a sweep yields them: numeric columns of several lengths (none, one row, a few
    formatting calls), a text column (a model dimension), and None after each block."""
    pieces = []
    for n in (0, 1, 7, 3 * 5 + 2, 40):
        x = rng.integers(0, 2**64 - 1, n, dtype=np.uint64, endpoint=True).view(np.float64)
        pieces.append([np.linspace(1.0, 2.0, n), x, rng.random(n) < 0.5, rng.integers(-9, 9, n)])
        pieces.append(None)
    pieces.append([np.array(["hertz", "seed", "jg"]), np.array([1.5, np.nan, -np.inf])])
    pieces.append(None)
    return pieces


@pytest.mark.parametrize("window", [1, 2, 4])
def test_csv_writer_threads_write_what_one_thread_writes(monkeypatch, window):
    """The overlapped writer (a producer, two formatting threads, the writing thread) writes the
    same bytes, in the same order, as formatting each piece in one thread; steps once per block;
    and leaves no thread behind. Small pieces and a small window make every stage wait on the others."""
    import io

    monkeypatch.setattr(msweep, "_CSV_FORMAT_ROWS", 5)
    monkeypatch.setattr(msweep, "_CSV_WINDOW", window)
    pieces = _csv_pieces(np.random.default_rng(window))
    serial = io.BytesIO()
    for cols in pieces:
        if cols is not None:
            msweep._write_rows(serial, cols)
    steps = []
    threaded = io.BytesIO()
    msweep._write_pieces(threaded, iter(pieces), lambda: steps.append(threaded.tell()))
    assert threaded.getvalue() == serial.getvalue()
    assert len(steps) == pieces.count(None) and steps == sorted(steps) and steps[-1] == len(serial.getvalue())
    assert _csv_threads_end()


class _FailingFile:
    """A binary file whose ``fail_at``-th write raises ENOSPC."""

    def __init__(self, fail_at):
        self.writes = 0
        self.fail_at = fail_at

    def write(self, data):
        self.writes += 1
        if self.writes == self.fail_at:
            raise OSError(28, "No space left on device")
        return len(data)


def _endless_pieces(made):
    rng = np.random.default_rng(3)
    while True:
        made.append(1)
        yield [rng.random(12), rng.random(12)]
        yield None


@pytest.mark.parametrize("where", ["producer", "write", "interrupt"])
def test_csv_writer_raises_what_any_stage_raises_and_stops_the_others(monkeypatch, where):
    """An error while producing (a block that fails to compute), while writing (a full disk) or an
    interrupt in the writing thread is raised by the writer, and every stage stops: an endless
    source of pieces is not drained, and no thread is left."""
    monkeypatch.setattr(msweep, "_CSV_FORMAT_ROWS", 4)
    monkeypatch.setattr(msweep, "_CSV_WINDOW", 2)
    made = []
    pieces = _endless_pieces(made)
    fh, step = _FailingFile(fail_at=0), lambda: None
    if where == "producer":

        def failing():
            yield from [[np.arange(9.0)], None, [np.arange(3.0)]]
            raise ValueError("block 2 failed")

        pieces, expected = failing(), ValueError
    elif where == "write":
        fh, expected = _FailingFile(fail_at=5), OSError
    else:
        calls = []

        def step():
            calls.append(1)
            if len(calls) == 3:
                raise KeyboardInterrupt

        expected = KeyboardInterrupt
    with pytest.raises(expected):
        msweep._write_pieces(fh, pieces, step)
    assert _csv_threads_end()
    assert len(made) < 20  # the producer stopped within a few pieces of the window


def test_csv_writer_asks_the_kernel_to_write_back_what_it_wrote(tmp_path, monkeypatch):
    """Every _CSV_WRITEBACK_BYTES the bytes written since the last request, and only those, are
    handed to posix_fadvise (DONTNEED starts their writeback); the file is what one thread writes."""
    import io
    import os

    if not hasattr(os, "posix_fadvise"):
        pytest.skip("no posix_fadvise on this system")
    asked = []
    real = os.posix_fadvise
    monkeypatch.setattr(
        os, "posix_fadvise", lambda fd, off, n, advice: (asked.append((off, n, advice)), real(fd, off, n, advice))
    )
    monkeypatch.setattr(msweep, "_CSV_FORMAT_ROWS", 64)
    monkeypatch.setattr(msweep, "_CSV_WRITEBACK_BYTES", 4096)
    rng = np.random.default_rng(7)
    pieces = [[rng.random(500), rng.random(500)], None, [rng.random(300), rng.random(300)], None]
    path = tmp_path / "w.csv"
    with open(path, "wb") as fh:
        fh.write(b"a,b\n")
        msweep._write_pieces(fh, iter(pieces), lambda: None)
    serial = io.BytesIO(b"a,b\n")
    serial.seek(0, 2)
    for cols in pieces[::2]:
        msweep._write_rows(serial, cols)
    assert path.read_bytes() == serial.getvalue()
    assert asked and all(a == os.POSIX_FADV_DONTNEED for *_, a in asked)
    assert asked[0][0] == 4 and all(o + n == o2 for (o, n, _), (o2, *_) in zip(asked, asked[1:]))
    assert all(n >= 4096 for _, n, _ in asked) and len(serial.getvalue()) - sum(asked[-1][:2]) < 4096


def test_csv_rows_read_back_bit_for_bit_nan_inf_and_flags_spelled_as_before(tmp_path):
    """The CSV writer's numbers read back bit for bit with Python's float() (random bit patterns,
    subnormals, the extremes, signed zeros), NaN as ``nan``, infinities as ``inf``/``-inf``,
    booleans 0/1; and more rows than one formatting call takes."""
    import io

    rng = np.random.default_rng(25)
    x = rng.integers(0, 2**64 - 1, 70_000, dtype=np.uint64, endpoint=True).view(np.float64)
    x[:8] = [0.0, -0.0, 5e-324, -5e-324, 1.7976931348623157e308, 2.2250738585072014e-308, 1e-5, 1e16]
    flags = rng.random(x.size) < 0.5
    ints = rng.integers(-(2**40), 2**40, x.size)
    buf = io.BytesIO()
    msweep._write_rows(buf, [x, flags, ints])
    lines = buf.getvalue().decode("ascii").split("\n")
    assert lines[-1] == "" and len(lines) == x.size + 1 > msweep._CSV_FORMAT_ROWS
    cells = [line.split(",") for line in lines[:-1]]
    back = np.array([float(c[0]) for c in cells])
    finite = np.isfinite(x)
    assert back[finite].tobytes() == x[finite].tobytes()
    for c, v in zip(cells, x):
        if np.isnan(v):
            assert c[0] == "nan"
        elif np.isinf(v):
            assert c[0] == ("inf" if v > 0 else "-inf")
    assert [c[1] for c in cells] == ["1" if f else "0" for f in flags]
    assert [int(c[2]) for c in cells] == ints.tolist()
