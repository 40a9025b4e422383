"""Fault corpus, part 4 (issue 24): the compiled-kernel cache never breaks a computation.

Each case ran an array computation through the compiled loops (``impact 1:120:100000``, or a cheap
loop that compiles in a second) in a fresh process with the cache in trouble; on the code before, each failed: a read-only cache with a warm
cache made numba raise ``RuntimeError: cannot cache function``, a truncated index gave a
permanent ``UnpicklingError``/``EOFError`` naming no folder, a full file system ``No space left
on device`` naming nothing. Now the numbers come out the same (checked against a run with a
healthy cache), with one warning naming the folder, and a corrupt entry is rebuilt.

Both routes of the compiled loops are tried: ``native`` (the machine code core._native keeps, what
a new process runs) and ``numba`` (numba's own loops and cache: calls the kept code cannot take, a
cache from an older version).

Running as root, file modes do not make a folder read-only, so the read-only and full cases make
numba's writability probe and writes fail the way the kernel reports them (EROFS, ENOSPC).
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from .test_faults import _env

pytest.importorskip("numba")

DRIVER = r"""
import errno, os, sys
import numba.core.caching as c
import microimpact.core.arrays as a
import microimpact.core.cache as k
from microimpact.core import _native

if os.environ["ROUTE"] == "numba":  # numba's own loops and cache, not the machine code core._native keeps
    _native.entry_path = lambda *args: None
mode = sys.argv[1]
def fail(code, text):
    def f(self, *args, **kw):
        raise OSError(code, text, str(getattr(self, "_index_path", "") or self.get_cache_path()))
    return f
if mode == "read-only":  # numba's probe of every cache folder fails; our files cannot be written
    c._CacheLocator.ensure_cache_path = fail(errno.EROFS, "Read-only file system")
    k.write_atomic = lambda path, data: (_ for _ in ()).throw(OSError(errno.EROFS, "Read-only file system", str(path)))
elif mode == "full-native":  # the kept machine code cannot be written
    k.write_atomic = lambda path, data: (_ for _ in ()).throw(OSError(errno.ENOSPC, "No space left on device", str(path)))
elif mode == "full-kernels":  # the loop file cannot be written
    a._write_atomic = lambda path, text: (_ for _ in ()).throw(OSError(errno.ENOSPC, "No space left on device", str(path)))
elif mode == "full-numba":  # the loop file is there, numba's entry cannot be saved
    c.IndexDataCacheFile._save_index = fail(errno.ENOSPC, "No space left on device")
if sys.argv[2:] == ["api"]:  # a cheap loop (compiles in a second): sphere masses of 5000 radii
    import numpy as np
    from microimpact.core.wall import sphere_mass
    out = a.evaluate(sphere_mass, np.linspace(1e-6, 1e-5, 5000), np.array(1350.0), backend="numba")
    print(out.tobytes().hex()[:64], float(out.sum()).hex())
    raise SystemExit(0)
from microimpact.cli import main
raise SystemExit(main(sys.argv[2:]))
"""
ARGV = ["api"]


def _run(mode, cache, argv=ARGV, route="numba"):
    return subprocess.run(
        [sys.executable, "-c", DRIVER, mode, *argv],
        capture_output=True,
        text=True,
        env=_env(MICROIMPACT_CACHE_DIR=str(cache), MICROIMPACT_BACKEND="numba", ROUTE=route),
        timeout=600,
    )


def _warnings(err):
    return [ln for ln in err.splitlines() if "kernel cache " in ln]


@pytest.fixture(scope="module")
def healthy(tmp_path_factory):
    cache = tmp_path_factory.mktemp("cache")
    proc = _run("healthy", cache)
    assert proc.returncode == 0 and _warnings(proc.stderr) == [], proc.stderr
    return cache, proc.stdout


@pytest.mark.parametrize("route", ["native", "numba"])
def test_a_read_only_warm_cache_under_the_impact_command(tmp_path, route):
    """``native``: the machine code kept by core._native (what a new process runs); ``numba``:
    numba's own loops and cache (calls the kept code cannot take, a cache of an older version)."""
    cache = tmp_path / "cache"
    argv = ["impact", "1:120:100000"]  # 10^5 impacts: the compiled loops
    want = _run("healthy", cache, argv, route)
    assert want.returncode == 0 and _warnings(want.stderr) == [], want.stderr
    proc = _run("read-only", cache, argv, route)
    assert proc.returncode == 0 and proc.stdout == want.stdout, proc.stderr
    lines = _warnings(proc.stderr)
    if route == "native":  # the kept machine code is only read: nothing to write, nothing to say
        assert lines == [], proc.stderr
    else:
        assert len(lines) == 1 and str(cache) in lines[0] and "cannot cache" in lines[0], proc.stderr


@pytest.mark.parametrize("mode", ["read-only", "full-native"])
def test_machine_code_that_cannot_be_kept_runs_from_memory(healthy, tmp_path, mode):
    _, want = healthy  # numba's loops: the same numbers
    cache = tmp_path / "cache"
    proc = _run(mode, cache, route="native")
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    assert proc.stdout == want
    lines = _warnings(proc.stderr)
    assert len(lines) == 1 and str(cache) in lines[0], proc.stderr
    assert ("Read-only" if mode == "read-only" else "No space left") in lines[0]
    assert not list(cache.rglob("*.bin"))


@pytest.mark.parametrize("mode", ["read-only", "full-kernels", "full-numba"])
def test_an_unwritable_cache_compiles_in_memory(healthy, tmp_path, mode):
    warm, want = healthy
    cache = warm if mode == "read-only" else tmp_path / "cache"  # read-only: with the warm cache
    proc = _run(mode, cache)
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr
    assert proc.stdout == want  # the same numbers
    lines = _warnings(proc.stderr)
    assert len(lines) == 1 and str(cache) in lines[0], proc.stderr  # one line, naming the folder
    assert ("cannot cache" if mode == "read-only" else "No space left") in lines[0]


@pytest.mark.parametrize("damage", ["truncate", "garbage", "empty"])
def test_a_corrupt_index_is_rebuilt(healthy, tmp_path, damage):
    import shutil

    warm, want = healthy
    cache = tmp_path / "cache"
    shutil.copytree(warm, cache)
    indexes = sorted(cache.rglob("*.nbi"))
    assert indexes
    for p in indexes:
        data = p.read_bytes()
        p.write_bytes({"truncate": data[:10], "garbage": b"\x80\x04not a pickle" * 7, "empty": b""}[damage])
    proc = _run("healthy", cache)
    assert proc.returncode == 0 and proc.stdout == want, proc.stderr
    lines = _warnings(proc.stderr)
    assert len(lines) == 1 and "corrupt" in lines[0] and str(cache) in lines[0], proc.stderr
    again = _run("healthy", cache)  # healed: the rebuilt entry loads without a word
    assert again.returncode == 0 and again.stdout == want and _warnings(again.stderr) == [], again.stderr


def test_cache_info_and_clear_touch_only_the_caches_files(healthy, tmp_path):
    import shutil

    warm, _ = healthy
    cache = tmp_path / "cache"
    shutil.copytree(warm, cache)
    mine = cache / "kernels" / "notes.py"
    mine.write_text("# a user's file that happens to sit in the folder\n")
    (cache / "kernels" / "__pycache__" / "other.nbi").write_bytes(b"not ours")
    info = _run("healthy", cache, ["cache", "--info"])
    assert info.returncode == 0 and str(cache) in info.stdout, info.stderr
    n_before = int(info.stdout.split("files:")[1].split()[0])
    assert n_before >= 3
    clear = _run("healthy", cache, ["cache", "--clear"])
    assert clear.returncode == 0 and f"deleted {n_before} cache files" in clear.stdout, clear.stdout
    assert mine.read_text().startswith("# a user's file")
    assert (cache / "kernels" / "__pycache__" / "other.nbi").read_bytes() == b"not ours"
    assert sorted(p.name for p in cache.rglob("*") if p.is_file()) == ["notes.py", "other.nbi"]
    info = _run("healthy", cache, ["cache", "--info"])
    assert "files:    0" in info.stdout


_TABLES_AND_CALIBRATIONS = r"""
import numpy as np
import microimpact as mi
from microimpact.core import cache
cache.store_array("demo_table", "k" * 16, np.linspace(0.0, 1.0, 7))
with cache.locked(cache.cache_dir() / "tables", "demo_table_" + "k" * 16):
    pass
mi.compare_models("silicon", [10.0, 50.0], ["hertz_viscoelastic"])  # stores one calibration
"""


def test_clear_deletes_the_tables_and_calibrations_it_can_prove_it_wrote(healthy, tmp_path):
    """``cache --clear`` also empties tables/ and calibrations/, by what each file proves (its format
    line and checksum), never by its name: a user's file, a look-alike and a damaged entry stay."""
    import shutil

    warm, _ = healthy
    cache = tmp_path / "cache"
    shutil.copytree(warm, cache)
    proc = subprocess.run(
        [sys.executable, "-c", _TABLES_AND_CALIBRATIONS],
        capture_output=True,
        text=True,
        env=_env(MICROIMPACT_CACHE_DIR=str(cache)),
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    tables, calibrations = cache / "tables", cache / "calibrations"
    ours = sorted(p.name for p in tables.iterdir()) + sorted(p.name for p in calibrations.iterdir())
    assert len(ours) == 3 and any(n.endswith(".lock") for n in ours), ours
    stored = next(tables.glob("*.npy"))
    kept = {
        tables / "notes.npy": b"a user's file named like a table",
        tables / "damaged_0123.npy": stored.read_bytes()[:-8],  # a damaged entry proves nothing
        tables / "other.lock": b"",  # a lock named after no table of ours
        calibrations / "mine.json": b'{"format": "microimpact-calibration-1", "key": "mine"}',
    }
    entry = next(calibrations.glob("*.json"))
    kept[calibrations / ("f" * 32 + ".json")] = entry.read_bytes()  # a copy under another key's name
    for path, data in kept.items():
        path.write_bytes(data)
    files = [p for p in cache.rglob("*") if p.is_file()]
    info = _run("healthy", cache, ["cache", "--info"])
    assert f"files:    {len(files) - len(kept)} " in info.stdout, info.stdout  # every file but the kept ones
    clear = _run("healthy", cache, ["cache", "--clear"])
    assert clear.returncode == 0 and f"deleted {len(files) - len(kept)} cache files" in clear.stdout, clear.stdout
    for path, data in kept.items():
        assert path.read_bytes() == data, path
    assert sorted(p for p in cache.rglob("*") if p.is_file()) == sorted(kept)
