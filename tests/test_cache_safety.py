"""Only the current user's own cache files are used: tables and calibrations.

A stored table becomes the numbers of a result and a calibration its parameters; a checksum proves a
file whole, not whose it is. So a file is read only when the cache folder and the file are the
user's own and writable by no one else, and the file is a regular one (``microimpact.engine.cache``).
Each case below puts one such file in the way: the computation still gives the numbers of a healthy
cache, with exactly one CacheWarning naming what was passed over. (The compiled loops' cases, which
need fresh processes, are in ``tests/cli/test_faults_cache.py``.)
"""

from __future__ import annotations

import os
import warnings

import numpy as np
import pytest

import microimpact as mi
from microimpact import _calibration_cache, oblique
from microimpact.calibrate import calibrate
from microimpact.engine import CacheWarning
from microimpact.engine import cache as ecache

OTHER_UID = 12345
SMALL = dict(n_x=3, steps=20)  # a small table: a fraction of a second to build


@pytest.fixture
def cache_in(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv("MICROIMPACT_CACHE_DIR", str(folder))
    return folder


def _table(kappa=0.8):
    oblique._table.cache_clear()
    return oblique.universal_table(kappa, **SMALL)


def _cache_warnings(caught):
    return [w for w in caught if issubclass(w.category, CacheWarning)]


def _needs_root():
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        pytest.skip("needs root, to give a file to another user")


def _with_warnings(fn):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = fn()
    return out, _cache_warnings(caught)


# ----------------------------------------------------------------------------- tables
def test_a_healthy_table_is_read_back_without_a_word(cache_in, monkeypatch):
    built = _table()
    calls = []
    monkeypatch.setattr(oblique, "universal_curve", lambda *a, **k: calls.append(1))
    read, said = _with_warnings(_table)
    assert not calls and not said and np.array_equal(read.values, built.values)


@pytest.mark.parametrize("mode", [0o777, 0o770, 0o702])
def test_a_cache_folder_others_can_write_is_not_used(cache_in, mode):
    built = _table()  # healthy: stored
    (path,) = (cache_in / "tables").glob("*.npy")
    cache_in.chmod(mode)
    again, said = _with_warnings(_table)
    assert np.array_equal(again.values, built.values)  # computed again: the same numbers
    assert len(said) == 1 and str(cache_in) in str(said[0].message) and "written by others" in str(said[0].message)
    assert ecache.load_array("universal_table", path.stem.removeprefix("universal_table_")) is None


def test_a_table_of_another_user_is_not_used(cache_in, monkeypatch):
    _needs_root()
    built = _table()
    (path,) = (cache_in / "tables").glob("*.npy")
    os.chown(path, OTHER_UID, OTHER_UID)
    calls = []
    real = oblique.universal_curve
    monkeypatch.setattr(oblique, "universal_curve", lambda *a, **k: calls.append(1) or real(*a, **k))
    again, said = _with_warnings(_table)
    assert calls and np.array_equal(again.values, built.values)  # not read: computed, the same numbers
    assert len(said) == 1 and path.name in str(said[0].message) and "another user" in str(said[0].message)


def test_a_fifo_or_link_where_a_table_should_be_is_not_used(cache_in, tmp_path):
    built = _table()
    (path,) = (cache_in / "tables").glob("*.npy")
    elsewhere = tmp_path / "elsewhere.npy"
    os.replace(path, elsewhere)
    path.symlink_to(elsewhere)  # a whole, valid table: but behind a link
    key = path.stem.removeprefix("universal_table_")
    got, said = _with_warnings(lambda: ecache.load_array("universal_table", key))
    assert got is None and len(said) == 1 and "no regular file" in str(said[0].message)
    path.unlink()
    os.mkfifo(path)
    ecache._WARNED.clear()
    got, said = _with_warnings(lambda: ecache.load_array("universal_table", key))  # does not wait on the FIFO
    assert got is None and len(said) == 1 and "no regular file" in str(said[0].message)
    again, _ = _with_warnings(_table)
    assert np.array_equal(again.values, built.values)


def test_a_table_writable_by_others_is_not_used(cache_in):
    a = np.linspace(0.0, 1.0, 5)
    assert ecache.store_array("t", "k", a)
    path = cache_in / "tables" / "t_k.npy"
    assert np.array_equal(ecache.load_array("t", "k"), a)
    path.chmod(0o666)
    got, said = _with_warnings(lambda: ecache.load_array("t", "k"))
    assert got is None and len(said) == 1 and "written by others" in str(said[0].message)


def test_nothing_is_written_into_a_folder_others_can_write(cache_in):
    (cache_in / "tables").mkdir(parents=True, mode=0o700)
    (cache_in / "tables").chmod(0o777)
    stored, said = _with_warnings(lambda: ecache.store_array("t", "k", np.zeros(3)))
    assert stored is False and len(said) == 1
    assert list((cache_in / "tables").iterdir()) == []


def test_the_folders_it_makes_are_its_owners_alone(cache_in):
    assert ecache.store_array("t", "k", np.zeros(3))
    for p in (cache_in, cache_in / "tables", cache_in / "tables" / "t_k.npy"):
        assert p.stat().st_mode & 0o077 == 0, p


# ----------------------------------------------------------------------------- calibrations
PAIR = mi.ContactPair.paper_case("silicon")


def _calibrate():
    return calibrate(PAIR, "linear_spring_dashpot", [10.0, 50.0])


def test_a_calibration_of_another_user_is_not_used(cache_in):
    _needs_root()
    first = _calibrate()
    (entry,) = (cache_in / "calibrations").glob("*.json")
    os.chown(entry, OTHER_UID, OTHER_UID)
    again, said = _with_warnings(_calibrate)
    assert again.params == first.params and np.array_equal(again.restitution, first.restitution)
    assert len(said) == 1 and entry.name in str(said[0].message)


def test_a_calibration_folder_others_can_write_is_not_used(cache_in):
    first = _calibrate()
    (cache_in / "calibrations").chmod(0o777)
    again, said = _with_warnings(_calibrate)
    assert again.params == first.params
    assert len(said) == 1 and "calibrations" in str(said[0].message)


def test_a_stored_warning_is_shown_without_control_characters(cache_in):
    text = "e(V) \x1b[31mis not\x1b[0m monotonic\r\x07 \u202eevil\nsecond line\tend"
    assert _calibration_cache.store("a" * 32, (1.0,), [0.5], [1e-9], text)
    params, e, t, shown = _calibration_cache.load("a" * 32, 1, 1)
    assert params == (1.0,) and e.tolist() == [0.5]
    assert shown == "e(V) [31mis not[0m monotonic evil\nsecond line\tend"
    assert _calibration_cache.printable("plain text, 5 % off") == "plain text, 5 % off"
