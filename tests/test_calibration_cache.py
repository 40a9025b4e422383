"""Calibrations kept on disk (microimpact._calibration_cache): an optimisation that changes no result.

A calibration read back is bitwise the one computed (parameters, ``e`` and contact time) and warns
as it did; an entry that is missing, corrupt, truncated, of another size or unreadable, and a cache
folder that cannot be written, all fall back to computing; other inputs or options are other
entries; writers racing on one entry leave one whole file.
"""

from __future__ import annotations

import hashlib
import json
import threading
import warnings

import numpy as np
import pytest

import microimpact as mi
from microimpact import _calibration_cache as cc
from microimpact import calibrate as cal_mod
from microimpact.calibrate import CalibrationWarning, calibrate
from microimpact.engine import CacheWarning


@pytest.fixture
def cache_in(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv("MICROIMPACT_CACHE_DIR", str(folder))
    return folder


@pytest.fixture(scope="module")
def pair():
    return mi.ContactPair.paper_case("silicon")


def _counting(monkeypatch):
    """Count the calibrations computed (each computed one checks its law's monotonicity once)."""
    calls = []
    real = cal_mod._monotonic_note

    def counting(*a, **k):
        calls.append(1)
        return real(*a, **k)

    monkeypatch.setattr(cal_mod, "_monotonic_note", counting)
    return calls


def _same(a, b):
    assert a.params == b.params and all(isinstance(p, float) for p in b.params)
    for f in ("velocity", "restitution", "contact_time", "target_restitution", "target_contact_time"):
        x, y = getattr(a, f), getattr(b, f)
        assert x.dtype == y.dtype == np.float64 and x.shape == y.shape
        assert x.tobytes() == y.tobytes(), f  # bit for bit


def _entries(folder):
    return sorted((folder / "calibrations").glob("*.json"))


def _uncached(pair, model, V, monkeypatch, tmp_path, **options):
    """The calibration computed where no cache can be written (the folder's parent is a regular file)."""
    blocker = tmp_path / "blocker"
    blocker.write_text("not a folder")
    with monkeypatch.context() as m:
        m.setenv("MICROIMPACT_CACHE_DIR", str(blocker / "cache"))
        return calibrate(pair, model, V, **options)


@pytest.mark.parametrize("model", ["linear_spring_dashpot", "hertz_viscoelastic"])
def test_read_back_bitwise_and_not_recomputed(cache_in, pair, monkeypatch, tmp_path, model):
    V = [30.0, 60.5]
    first = calibrate(pair, model, V)
    assert len(_entries(cache_in)) == 1
    calls = _counting(monkeypatch)
    again = calibrate(pair, model, V)
    assert not calls  # read from disk
    _same(first, again)
    _same(first, _uncached(pair, model, V, monkeypatch, tmp_path))  # and it is what an uncached run computes
    assert len(calls) == 1


def test_warning_given_again_from_the_cache(cache_in, pair, monkeypatch):
    with pytest.warns(CalibrationWarning, match="not monotonic") as first:
        a = calibrate(pair, "luding_hysteretic", 60.5, plasticity=True)
    calls = _counting(monkeypatch)
    with pytest.warns(CalibrationWarning, match="not monotonic") as again:
        b = calibrate(pair, "luding_hysteretic", 60.5, plasticity=True)
    assert not calls
    _same(a, b)
    assert [str(w.message) for w in first] == [str(w.message) for w in again]
    assert again[0].filename == __file__  # attributed to the caller, as when computed
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        calibrate(pair, "luding_hysteretic", 60.5)  # the constant-k2 spring: monotonic, no warning, cached or not
        calibrate(pair, "luding_hysteretic", 60.5)


def test_other_inputs_are_other_entries(cache_in, pair, monkeypatch):
    base = calibrate(pair, "linear_spring_dashpot", 50.0)
    calls = _counting(monkeypatch)
    other_v = calibrate(pair, "linear_spring_dashpot", np.nextafter(50.0, 60.0))  # one ulp away
    other_opt = calibrate(pair, "linear_spring_dashpot", 50.0, limit_force=1)
    other_target = calibrate(pair, "linear_spring_dashpot", 50.0, target_restitution=0.5)
    other_pair = calibrate(mi.ContactPair.paper_case("mica"), "linear_spring_dashpot", 50.0)
    assert len(calls) == 4 and len(_entries(cache_in)) == 5
    assert other_target.params != base.params and other_target.restitution[0] == pytest.approx(0.5, rel=1e-10)
    assert other_pair.params != base.params and other_opt.params != base.params
    assert other_v.velocity[0] != base.velocity[0]


@pytest.mark.parametrize(
    "damage",
    [
        lambda b: b[:-1] + bytes([b[-1] ^ 1]),  # one flipped bit
        lambda b: b[: len(b) // 2],  # truncated
        lambda b: b"",
        lambda b: b"\xff\xfe not json",
    ],
)
def test_damaged_entry_is_recomputed_and_healed(cache_in, pair, monkeypatch, damage):
    first = calibrate(pair, "linear_spring_dashpot", 50.0)
    (path,) = _entries(cache_in)
    path.write_bytes(damage(path.read_bytes()))
    calls = _counting(monkeypatch)
    again = calibrate(pair, "linear_spring_dashpot", 50.0)
    assert calls  # not trusted: computed
    _same(first, again)
    calls.clear()
    _same(first, calibrate(pair, "linear_spring_dashpot", 50.0))  # written again whole
    assert not calls


def test_entry_of_other_sizes_or_content_is_not_used(cache_in):
    """An entry whose checksum holds but whose content does not fit (another layout, sizes or key) is ignored."""
    name = "a" * 32
    path = cache_in / "calibrations" / f"{name}.json"
    assert cc.store(name, (1.0, 2.0, 0.0), [0.5, 0.25], [1e-7, 2e-7], None)
    params, e, t, note = cc.load(name, 3, 2)
    assert params == (1.0, 2.0, 0.0) and e.tolist() == [0.5, 0.25] and t.tolist() == [1e-7, 2e-7] and note is None
    assert cc.load(name, 2, 2) is None and cc.load(name, 3, 3) is None
    good = json.loads(path.read_bytes().partition(b"\n")[2])
    for change in ({"format": "other"}, {"key": "0" * 32}, {"warning": 3}, {"params": ["x", "y", "z"]}, {"params": 1}):
        raw = json.dumps({**good, **change}).encode()
        path.write_bytes(hashlib.sha256(raw).hexdigest().encode() + b"\n" + raw)
        assert cc.load(name, 3, 2) is None, change


def test_unwritable_or_unreadable_cache_computes(tmp_path, pair, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("a regular file where the cache folder's parent should be")
    monkeypatch.setenv("MICROIMPACT_CACHE_DIR", str(blocker / "cache"))
    calls = _counting(monkeypatch)
    a = calibrate(pair, "linear_spring_dashpot", 50.0)
    b = calibrate(pair, "linear_spring_dashpot", 50.0)
    assert len(calls) == 2  # nothing kept, nothing raised
    _same(a, b)
    assert blocker.read_text().startswith("a regular file")
    # an entry that is a folder (cannot be read as a file) is computed past as well
    folder = tmp_path / "c2"
    monkeypatch.setenv("MICROIMPACT_CACHE_DIR", str(folder))
    name = cc.key(
        mi.models.face("linear_spring_dashpot"),
        cal_mod._pair_values(pair),
        a.velocity,
        a.target_restitution,
        a.target_contact_time,
        {},
    )
    (folder / "calibrations" / f"{name}.json").mkdir(parents=True)
    with pytest.warns(CacheWarning, match=r"is no regular file \(a folder\)") as said:
        _same(a, calibrate(pair, "linear_spring_dashpot", 50.0))
    assert len(said) == 1 and len(calls) == 3


def test_options_that_cannot_be_named_are_not_cached(cache_in):
    face = mi.models.face("linear_spring_dashpot")
    args = (face, (1e9, 1e-6, 1e-12, 1e8), np.array([50.0]), np.array([0.7]), np.array([1e-7]))
    assert cc.key(*args, {"limit_force": object()}) is None
    assert cc.load(None, 3, 1) is None and cc.store(None, (1.0,), [1.0], [1.0], None) is False
    assert cc.key(*args, {"limit_force": 1}) != cc.key(*args, {"limit_force": 1.0})  # int and float: other entries


def test_writers_racing_on_one_entry_leave_one_whole_file(cache_in):
    name = "f" * 32
    stop = threading.Event()
    errors = []

    def write(seed):
        rng = np.random.default_rng(seed)
        while not stop.is_set():
            e = rng.random(50)
            if not cc.store(name, (1.0, 2.0), e, e, None):
                errors.append("store failed")

    # one whole entry before the race: the reader's 300 loads could otherwise all come before any
    # writer thread first ran (seen == 0 on CI once), which says nothing about the race itself
    assert cc.store(name, (1.0, 2.0), np.zeros(50), np.zeros(50), None)
    threads = [threading.Thread(target=write, args=(s,)) for s in range(4)]
    for t in threads:
        t.start()
    try:
        seen = 0
        for _ in range(300):
            got = cc.load(name, 2, 50)
            if got is not None:
                seen += 1
                assert np.array_equal(got[1], got[2])  # one writer's whole entry, never a mix
    finally:
        stop.set()
        for t in threads:
            t.join()
    assert not errors and seen > 0
    assert [p.name for p in (cache_in / "calibrations").iterdir()] == [f"{name}.json"]  # no temporary left


def test_a_model_from_outside_is_keyed_by_its_file(tmp_path):
    import dataclasses
    import types

    face = mi.models.face("linear_spring_dashpot")
    args = ((1e9, 1e-6, 1e-12, 1e8), np.array([50.0]), np.array([0.7]), np.array([1e-7]), {})
    source = tmp_path / "my_law.py"
    source.write_text("# a law added with register_path\n")
    outside = types.ModuleType("my_law")
    outside.__file__ = str(source)
    added = dataclasses.replace(face, model=dataclasses.replace(face.model, module=outside))
    first = cc.key(added, *args)
    assert first is not None and first != cc.key(face, *args)
    source.write_text("# a law added with register_path, edited\n")
    assert cc.key(added, *args) != first  # an edited law is calibrated again
    in_memory = dataclasses.replace(face, model=dataclasses.replace(face.model, module=types.ModuleType("in_memory")))
    assert cc.key(in_memory, *args) is None  # no source to hash: never cached
