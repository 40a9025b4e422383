"""Fault corpus, part 4: the compiled-loop cache never breaks a computation.

Each case runs an array computation through the compiled loops (``impact 1:120:100000``, or a cheap
loop that compiles in a second) in a fresh process with the cache in trouble: read-only, full, a
damaged numba index, or files that another user could have written (a folder writable by others, an
entry of another owner, a FIFO where an entry should be). Each time the numbers come out the same
(checked against a run with a healthy cache), with one :class:`~microimpact.engine.CacheWarning`
naming the folder; a damaged entry is rebuilt by the next process.

Running as root, file modes do not make a folder read-only: that case runs its process without root's
override of file modes (``capsh``; skipped where that cannot be done). Another user's file is made
with ``os.chown`` (as root; skipped otherwise).
"""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
import sys

import pytest

from .test_faults import _env

pytest.importorskip("numba")

#: A user id no file of this machine belongs to (the "other user" of the cases below).
OTHER_UID = 12345

DRIVER = r"""
import errno, os, sys
from microimpact.engine import loops

mode = sys.argv[1]
if mode == "full-kernels":  # the loop file cannot be written
    def full(path, text):
        raise OSError(errno.ENOSPC, "No space left on device", str(path))
    loops.write_atomic = full
if sys.argv[2:] == ["api"]:  # a cheap loop (compiles in a second): sphere masses of 5000 radii
    import numpy as np
    from microimpact.engine import evaluate
    from microimpact.core.wall import sphere_mass
    out = evaluate(sphere_mass, np.linspace(1e-6, 1e-5, 5000), np.array(1350.0), backend="numba")
    print(out.tobytes().hex()[:64], float(out.sum()).hex())
    raise SystemExit(0)
from microimpact.cli import main
raise SystemExit(main(sys.argv[2:]))
"""
ARGV = ["api"]


def _run(mode, cache, argv=ARGV, prefix=()):
    return subprocess.run(
        [*prefix, sys.executable, "-c", DRIVER, mode, *argv],
        capture_output=True,
        text=True,
        env=_env(MICROIMPACT_CACHE_DIR=str(cache), MICROIMPACT_BACKEND="numba"),
        timeout=600,
    )


def _warnings(err):
    """The cache's warnings: as Python shows them, or as the command does (``warning: ...``)."""
    return [ln for ln in err.splitlines() if "CacheWarning: cache " in ln or ln.startswith("warning: cache ")]


@pytest.fixture(scope="module")
def healthy(tmp_path_factory):
    cache = tmp_path_factory.mktemp("cache")
    proc = _run("healthy", cache)
    assert proc.returncode == 0 and _warnings(proc.stderr) == [], proc.stderr
    assert list(cache.rglob("*.nbi"))  # numba's index: the loop was cached
    return cache, proc.stdout


def _copy(warm, tmp_path):
    cache = tmp_path / "cache"
    shutil.copytree(warm, cache)
    return cache


def _one_warning(proc, want, cache, *words):
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    assert proc.stdout == want  # the same numbers
    lines = _warnings(proc.stderr)
    assert len(lines) == 1 and str(cache) in lines[0], proc.stderr  # one line, naming the folder
    for word in words:
        assert word in lines[0], lines[0]


# ----------------------------------------------------------------------------- cannot be written
#: Runs a command as root without the capabilities that let root write what its modes refuse.
NO_OVERRIDE = ("capsh", "--drop=cap_dac_override,cap_dac_read_search", "--", "-c", 'exec "$0" "$@"')


def test_a_read_only_warm_cache_under_the_impact_command(tmp_path):
    """A warm cache its owner cannot write: modes without write permission, and a process that
    respects them (root, run without its override of file modes)."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0 or shutil.which("capsh") is None:
        pytest.skip("needs root and capsh, to run a process that file modes bind")
    cache = tmp_path / "cache"
    argv = ["impact", "1:120:100000"]  # 10^5 impacts: the compiled loops
    want = _run("healthy", cache, argv)
    assert want.returncode == 0 and _warnings(want.stderr) == [], want.stderr
    assert list(cache.rglob("*.nbi"))
    for p in [cache, *cache.rglob("*")]:
        p.chmod(stat.S_IMODE(p.stat().st_mode) & ~0o222)
    try:
        proc = _run("healthy", cache, argv, prefix=NO_OVERRIDE)
    finally:
        for p in [cache, *cache.rglob("*")]:
            p.chmod(stat.S_IMODE(p.stat().st_mode) | 0o200)
    _one_warning(proc, want.stdout, cache, "read-only")


def test_a_loop_file_that_cannot_be_written_compiles_in_memory(healthy, tmp_path):
    _, want = healthy
    cache = tmp_path / "cache"
    proc = _run("full-kernels", cache)
    _one_warning(proc, want, cache, "No space left")


# ----------------------------------------------------------------------------- damaged
@pytest.mark.parametrize("damage", ["truncate", "garbage", "empty"])
def test_a_corrupt_index_is_rebuilt(healthy, tmp_path, damage):
    warm, want = healthy
    cache = _copy(warm, tmp_path)
    indexes = sorted(cache.rglob("*.nbi"))
    assert indexes
    for p in indexes:
        data = p.read_bytes()
        p.write_bytes({"truncate": data[:10], "garbage": b"\x80\x04not a pickle" * 7, "empty": b""}[damage])
    proc = _run("healthy", cache)
    _one_warning(proc, want, cache, "corrupt")
    again = _run("healthy", cache)  # healed: the rebuilt entry loads without a word
    assert again.returncode == 0 and again.stdout == want and _warnings(again.stderr) == [], again.stderr


# ----------------------------------------------------------------------------- whose files
def test_a_folder_others_can_write_is_not_used(healthy, tmp_path):
    warm, want = healthy
    cache = _copy(warm, tmp_path)
    (cache / "kernels").chmod(0o777)
    before = {p: p.stat().st_mtime_ns for p in cache.rglob("*") if p.is_file()}
    proc = _run("healthy", cache)
    _one_warning(proc, want, cache, "can be written by others", "kernels")
    assert {p: p.stat().st_mtime_ns for p in cache.rglob("*") if p.is_file()} == before  # nothing written there


def test_a_group_writable_cache_folder_is_not_used(healthy, tmp_path):
    warm, want = healthy
    cache = _copy(warm, tmp_path)
    cache.chmod(0o770)
    proc = _run("healthy", cache)
    _one_warning(proc, want, cache, "can be written by others")


@pytest.mark.parametrize("which", ["index", "loop file"])
def test_an_entry_of_another_user_is_not_used(healthy, tmp_path, which):
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        pytest.skip("needs root, to give a file to another user")
    warm, want = healthy
    cache = _copy(warm, tmp_path)
    (entry,) = sorted(cache.rglob("*.nbi")) if which == "index" else sorted((cache / "kernels").glob("*.py"))
    os.chown(entry, OTHER_UID, OTHER_UID)
    proc = _run("healthy", cache)
    _one_warning(proc, want, cache, "another user", entry.name)


def test_a_fifo_where_an_index_should_be_is_not_used(healthy, tmp_path):
    warm, want = healthy
    cache = _copy(warm, tmp_path)
    (entry,) = sorted(cache.rglob("*.nbi"))
    entry.unlink()
    os.mkfifo(entry)
    proc = _run("healthy", cache)  # no hang on the FIFO: it is never opened
    _one_warning(proc, want, cache, "no regular file", entry.name)


# ----------------------------------------------------------------------------- what is the cache's
def test_cache_info_and_clear_touch_only_the_caches_files(healthy, tmp_path):
    warm, _ = healthy
    cache = _copy(warm, tmp_path)
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
from microimpact.engine import cache
cache.store_array("demo_table", "k" * 16, np.linspace(0.0, 1.0, 7))
with cache.locked(cache.cache_dir() / "tables", "demo_table_" + "k" * 16):
    pass
mi.compare_models("silicon", [10.0, 50.0], ["hertz_viscoelastic"])  # stores one calibration
"""


def test_clear_deletes_the_tables_and_calibrations_it_can_prove_it_wrote(healthy, tmp_path):
    """``cache --clear`` also empties tables/ and calibrations/, by what each file proves (its format
    line and checksum), never by its name: a user's file, a look-alike and a damaged entry stay."""
    warm, _ = healthy
    cache = _copy(warm, tmp_path)
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
