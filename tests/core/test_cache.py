"""The on-disk cache (microimpact.core.cache) and the universal table kept in it.

The cache is an optimisation: a stored table is bitwise the one computed, and a missing, corrupt,
unreadable or unwritable cache falls back to computing. Processes started together compute a table
once (a file lock); a lock that cannot be had costs only the wait.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from microimpact import oblique as ob
from microimpact.core import cache

SMALL = dict(n_x=3, steps=20)  # a small table: a fraction of a second to build


@pytest.fixture
def cache_in(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv("MICROIMPACT_CACHE_DIR", str(folder))
    return folder


def _count_builds(monkeypatch):
    calls = []
    real = ob.universal_curve

    def counting(*a, **k):
        calls.append(1)
        return real(*a, **k)

    monkeypatch.setattr(ob, "universal_curve", counting)
    return calls


def _fresh(kappa):
    ob._table.cache_clear()
    return ob.universal_table(kappa, **SMALL)


def test_array_round_trip_and_corruption(cache_in):
    a = np.random.default_rng(1).random((3, 7))
    assert cache.store_array("t", "k", a)
    b = cache.load_array("t", "k")
    assert b.dtype == np.float64 and np.array_equal(a, b)
    path = cache_in / "tables" / "t_k.npy"
    data = bytearray(path.read_bytes())
    data[-1] ^= 1  # one flipped bit in the numbers
    path.write_bytes(bytes(data))
    assert cache.load_array("t", "k") is None
    path.write_bytes(bytes(data[:40]))  # truncated
    assert cache.load_array("t", "k") is None
    path.write_bytes(b"")
    assert cache.load_array("t", "k") is None
    assert cache.load_array("t", "absent") is None


def test_table_read_back_bitwise_and_not_recomputed(cache_in, monkeypatch):
    built = _fresh(0.8)
    assert list((cache_in / "tables").glob("universal_table_*.npy"))
    calls = _count_builds(monkeypatch)
    read = _fresh(0.8)
    assert not calls  # read from disk
    assert np.array_equal(built.values, read.values) and np.array_equal(built.psi, read.psi)
    assert not read.values.flags.writeable
    other = _fresh(0.9)  # another kappa: another entry
    assert calls and not np.array_equal(other.values, read.values)


def test_mindlin_deresiewicz_table_read_back(cache_in, monkeypatch):
    """Mindlin-Deresiewicz never slides throughout (its table ends within 3e-3 of 1, not at 1): its
    stored table is read back too, not refused by the end-of-grid check and rebuilt in every process."""
    ob._table.cache_clear()
    built = ob.universal_table(0.8, law="mindlin_deresiewicz", n_x=3, steps=100)
    assert not np.all(built.values[:, -1] == 1.0)  # the case: short of 1 at the grid's end
    calls = _count_builds(monkeypatch)
    ob._table.cache_clear()
    read = ob.universal_table(0.8, law="mindlin_deresiewicz", n_x=3, steps=100)
    assert not calls  # read from disk
    assert np.array_equal(built.values, read.values)


def test_corrupt_table_is_recomputed_and_healed(cache_in, monkeypatch):
    built = _fresh(0.8)
    (path,) = (cache_in / "tables").glob("universal_table_*.npy")
    data = bytearray(path.read_bytes())
    data[-3] ^= 0x40
    path.write_bytes(bytes(data))
    calls = _count_builds(monkeypatch)
    again = _fresh(0.8)
    assert calls  # not trusted: recomputed
    assert np.array_equal(built.values, again.values)
    healed = cache.load_array("universal_table", path.stem.removeprefix("universal_table_"))
    assert healed is not None and np.array_equal(healed, built.values)  # written again


def test_unwritable_cache_computes(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("a regular file where the cache folder's parent should be")
    folder = blocker / "cache"  # cannot be created, not even by root
    monkeypatch.setenv("MICROIMPACT_CACHE_DIR", str(folder))
    with cache.locked(folder, "x") as held:
        assert held is False
    assert cache.store_array("t", "k", np.zeros(2)) is False
    table = _fresh(0.8)
    assert np.all(table.values[:, -1] == 1.0)
    assert blocker.read_text().startswith("a regular file")


def test_lock_excludes_and_gives_up(tmp_path):
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "import fcntl, os, sys, time\n"
            f"fd = os.open({str(tmp_path / 'x.lock')!r}, os.O_RDWR | os.O_CREAT)\n"
            "fcntl.flock(fd, fcntl.LOCK_EX)\nprint('held', flush=True)\ntime.sleep(30)\n",
        ],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert holder.stdout.readline().strip() == "held"
        t0 = time.monotonic()
        with cache.locked(tmp_path, "x", timeout=0.3) as held:
            assert held is False  # another process holds it: the block runs anyway, after the wait
        assert time.monotonic() - t0 >= 0.3
    finally:
        holder.kill()
        holder.wait()
        holder.stdout.close()
    with cache.locked(tmp_path, "x", timeout=5) as held:
        assert held is True


_RACER = """
import sys
from microimpact import oblique as ob
calls = []
real = ob.universal_curve
def counting(*a, **k):
    calls.append(1)
    return real(*a, **k)
ob.universal_curve = counting
t = ob.universal_table(0.77, n_x=3, steps=20)
print(len(calls), float(t.values.sum()).hex())
"""


def test_processes_started_together_build_once(cache_in):
    src = str(Path(ob.__file__).resolve().parents[1])
    env = dict(os.environ, PYTHONPATH=src + os.pathsep + os.environ.get("PYTHONPATH", ""))
    procs = [
        subprocess.Popen([sys.executable, "-c", _RACER], stdout=subprocess.PIPE, text=True, env=env) for _ in range(3)
    ]
    outs = [p.communicate(timeout=300)[0].split() for p in procs]
    assert all(p.returncode == 0 for p in procs)
    builders = [int(o[0]) > 0 for o in outs]
    assert sum(builders) == 1, outs  # one built the table, the others waited and read it
    assert len({o[1] for o in outs}) == 1  # the same numbers everywhere


def test_core_hash_is_sha256_of_the_sources_in_path_order():
    """core_hash walks the folder without pathlib and hashes without OpenSSL: the files, their order
    and the digest are still those of ``sorted(Path.rglob("*.py"))`` through hashlib."""
    import hashlib

    core = Path(cache.__file__).resolve().parent
    h = hashlib.sha256()
    for path in sorted(core.rglob("*.py")):
        h.update(path.relative_to(core).as_posix().encode())
        h.update(path.read_bytes())
    assert cache.core_hash() == h.hexdigest()
    data = np.random.default_rng(2).bytes(100_000)
    assert cache.sha256(data).digest() == hashlib.sha256(data).digest()


_WARM_WALL = """
import functools, sys
import numpy as np
from microimpact import oblique
from microimpact.wall import wall_interaction

oblique.universal_table = functools.partial(oblique.universal_table, n_x=3, steps=20)  # a small table
wall_interaction(np.array([[3.0, -10.0, 0.0]]), np.array([0.0, 1.0, 0.0]), 5e-6, 1350.0, effective_modulus=1.31e9,
                 limiting_pressure=156e6, friction=0.3, tangential="mindlin", poisson_ratio=0.3)
print(",".join(m for m in ("pathlib", "_hashlib", "numpy.ma") if m in sys.modules))
"""


def test_a_warm_table_is_read_without_pathlib_openssl_or_numpy_ma(cache_in):
    """A script's first compliant wall interaction on a warm cache (row 11 of the benchmarks) loads
    none of pathlib, OpenSSL's hashlib and numpy.ma: 25-40 ms together of a new process."""
    from microimpact.core.tangential import stiffness_ratio_same_poisson

    _fresh(stiffness_ratio_same_poisson(0.3))  # the script's table, stored in the cache folder
    src = str(Path(ob.__file__).resolve().parents[1])
    env = dict(os.environ, PYTHONPATH=src + os.pathsep + os.environ.get("PYTHONPATH", ""))
    out = subprocess.run([sys.executable, "-c", _WARM_WALL], capture_output=True, text=True, env=env, check=True)
    assert out.stdout.strip() == ""


# ------------------------------------------------------------------ temporary names without tempfile
@pytest.mark.parametrize("kind", ["file", "folder"])
def test_temporary_names_are_new_private_and_never_reused(tmp_path, monkeypatch, kind):
    """``cache.mkstemp`` / ``cache.mkdtemp`` keep :mod:`tempfile`'s contract: created exclusively
    (a taken name, even a dangling link, is skipped, never opened or followed), owner only, in the
    folder asked, ``prefix<random>suffix``; when every try is taken, FileExistsError naming the folder."""
    make = cache.mkstemp if kind == "file" else cache.mkdtemp
    monkeypatch.setattr(os, "umask", os.umask)  # unchanged: the modes below are before the umask
    draws = iter([b"\x00" * 6, b"\x00" * 6, b"\x01" * 6])
    monkeypatch.setattr(os, "urandom", lambda n: next(draws))
    taken = tmp_path / ".out.000000000000.tmp"
    taken.symlink_to(tmp_path / "elsewhere")  # a dangling link on the first name drawn
    got = make(tmp_path, ".out.", ".tmp")
    path = got[1] if kind == "file" else got
    if kind == "file":
        os.write(got[0], b"x")
        os.close(got[0])
    assert path == str(tmp_path / ".out.010101010101.tmp")
    assert not (tmp_path / "elsewhere").exists() and taken.is_symlink()
    mode = os.stat(path).st_mode & 0o777
    assert mode == (0o600 if kind == "file" else 0o700) & ~_umask()
    monkeypatch.setattr(os, "urandom", lambda n: b"\x01" * n)  # every name drawn is taken now
    with pytest.raises(FileExistsError) as err:
        make(tmp_path, ".out.", ".tmp")
    assert err.value.filename == str(tmp_path)


def _umask():
    old = os.umask(0)
    os.umask(old)
    return old
