"""Fault corpus: writing under the process's file-size limit (``ulimit -f``, RLIMIT_FSIZE).

The system refuses a write past the limit: with SIGXFSZ ignored (Python ignores it at start-up, and
the child here ignores it explicitly) the write fails with EFBIG. The NetCDF library turned that into
``RuntimeError: NetCDF: HDF error`` and a traceback, and with a chunked sweep a second traceback at
exit (the file left open). Every writing command must end with one line on stderr naming the user's
file, exit 2, and leave nothing behind: no temporary file, an earlier output byte for byte.
"""

from __future__ import annotations

import signal
import subprocess
import sys

import pytest

from .test_faults import _env, assert_one_line, no_temp_files

resource = pytest.importorskip("resource")

#: The limit: far below every output written here, above the few bytes a run may write first.
LIMIT = 64 * 1024


def _limited(nbytes):
    def set_limit():  # in the child, before exec: it alone runs under the limit
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (nbytes, nbytes))

    return set_limit


def run_limited(argv, cwd, nbytes=LIMIT, timeout=300):
    """``python -m microimpact ARGV`` (or ``python -c CODE``) under a file-size limit of ``nbytes``."""
    cmd = [sys.executable, *argv] if argv[0] == "-c" else [sys.executable, "-m", "microimpact", *argv]
    proc = subprocess.run(
        cmd, cwd=cwd, env=_env(), capture_output=True, text=True, timeout=timeout, preexec_fn=_limited(nbytes)
    )
    return proc.returncode, proc.stdout, proc.stderr


@pytest.fixture(scope="module", autouse=True)
def warm_cache(tmp_path_factory):
    """The compiled loops on disk first: a cold cache cannot be written under the limit either, and says
    so in a warning line of its own (the computation still runs), which is not what these tests check."""
    cwd = tmp_path_factory.mktemp("warm")
    for argv in (
        ["sweep", "--velocity", "1:120:20000", "--out", "w.nc", "-q"],  # sizes that take the compiled loops
        ["sweep", "--velocity", "1:120:40000", "--chunks", "5000", "--out", "w.csv", "-q"],
        ["sweep", "--velocity", "1:120:200", "--density", "1000:3000:100", "--chunks", "50", "--out", "g.nc", "-q"],
        ["export", "--out", "out"],
    ):
        subprocess.run([sys.executable, "-m", "microimpact", *argv], cwd=cwd, env=_env(), capture_output=True)


def listing(folder):
    return sorted((p.relative_to(folder).as_posix(), p.read_bytes()) for p in folder.rglob("*") if p.is_file())


@pytest.mark.parametrize(
    "argv",
    [
        ["--velocity", "1:120:20000"],  # computed at once, written by xarray in one go
        ["--velocity", "1:120:40000", "--chunks", "5000"],  # lazy: written block by block
        ["--velocity", "1:120:200", "--density", "1000:3000:100", "--chunks", "50"],  # two dimensions, lazy
    ],
    ids=["eager", "chunked", "grid"],
)
def test_netcdf_sweep_over_the_file_size_limit(tmp_path, argv):
    (tmp_path / "s.nc").write_bytes(b"an earlier output\n")
    before = listing(tmp_path)
    rc, out, err = run_limited(["sweep", *argv, "--out", "s.nc", "-q"], tmp_path)
    assert_one_line(rc, err, "s.nc", "file too large", "ulimit -f")
    assert ".tmp" not in err and "Exception ignored" not in err
    assert listing(tmp_path) == before and no_temp_files(tmp_path) == []


def test_csv_sweep_over_the_file_size_limit(tmp_path):
    (tmp_path / "s.csv").write_text("an earlier output\n")
    before = listing(tmp_path)
    rc, out, err = run_limited(
        ["sweep", "--velocity", "1:120:40000", "--chunks", "5000", "--out", "s.csv", "-q"], tmp_path
    )
    assert_one_line(rc, err, "s.csv", "file too large")
    assert listing(tmp_path) == before and no_temp_files(tmp_path) == []


@pytest.mark.parametrize("command", ["export", "paper"])
def test_output_folder_over_the_file_size_limit(tmp_path, command):
    """The folder's files are written into a staging folder first: the error names the file in the
    user's folder (``out/NAME``), not the staging path, and the folder does not appear."""
    rc, out, err = run_limited([command, "--out", "out"], tmp_path, nbytes=2048)
    assert_one_line(rc, err, "file too large", "out/")
    assert ".tmp" not in err and ".microimpact-staging" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_export_into_an_earlier_output_over_the_limit(tmp_path):
    """Into an earlier output folder (staged inside it): the earlier files stay, byte for byte."""
    rc, out, err = run_limited(["export", "--out", "out"], tmp_path, nbytes=1 << 30)
    assert rc == 0, err
    before = listing(tmp_path)
    rc, out, err = run_limited(["export", "--out", "out", "--diameter", "3e-6"], tmp_path, nbytes=2048)
    assert_one_line(rc, err, "file too large", "out/")
    assert ".microimpact-staging" not in err
    assert listing(tmp_path) == before


LIBRARY = r"""
import errno, os, sys
import numpy as np
from microimpact.sweep import sweep, sweep_to_netcdf
ds = sweep(np.linspace(1.0, 120.0, 20_000), chunks=5_000)
for engine in sys.argv[1:]:
    target = f"s-{engine}.nc"
    try:
        sweep_to_netcdf(ds, target, engine=engine)
    except OSError as exc:
        assert exc.errno == errno.EFBIG and exc.filename == target, (engine, exc.errno, exc.filename, exc)
        print(engine, "EFBIG", exc.filename)
    else:
        raise SystemExit(f"{engine}: no error")
print(sorted(os.listdir(".")))
"""


def test_library_netcdf_writer_raises_efbig_naming_the_file(tmp_path):
    """The API's error is an OSError (EFBIG, naming the target) for either NetCDF engine."""
    engines = ["netcdf4", "scipy"]
    pytest.importorskip("netCDF4")
    pytest.importorskip("scipy.io")
    rc, out, err = run_limited(["-c", LIBRARY, *engines], tmp_path)
    assert rc == 0, err
    assert [f"{e} EFBIG s-{e}.nc" for e in engines] == out.splitlines()[:-1]
    assert out.splitlines()[-1] == "[]"
    assert "Exception ignored" not in err
