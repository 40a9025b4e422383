"""The compiled loops' machine code kept for a new process (microimpact.core._native).

The kept loop is the same ``@jitable`` function compiled by the same numba: its numbers must be
bitwise those of the scalar core and of numba's own loops, serial and split over threads. A call
it cannot take goes to numba's loop; a missing or corrupt entry only means numba's route (and the
entry is written again); a new process with a sound entry computes without importing numba (nor
scipy, which numba's start-up imports); processes started together on an empty cache write it once.
"""

from __future__ import annotations

import ctypes
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("numba")

from microimpact.core import _native, arrays  # noqa: E402
from microimpact.core.models import hertz_viscoelastic as visco  # noqa: E402
from microimpact.core.models import thornton_ning_2016 as seed  # noqa: E402
from microimpact.core.quantities import OUTCOME_FIELDS  # noqa: E402

from .test_paths import ARGS, VY, _edge_speeds, _random_cases  # noqa: E402

NOUT = len(OUTCOME_FIELDS)


def _same(a, b):
    return np.array_equal(np.asarray(a).view(np.int64), np.asarray(b).view(np.int64))


def _loops(tmp_path, fn, kinds, nout, nparams):
    """``(serial, threaded, fallback calls)`` of an entry built in ``tmp_path`` and loaded back."""
    path = tmp_path / "entry.bin"
    assert _native.build(fn, kinds, nout, nparams, path)
    assert _native.sound(path)
    used = []

    def fallback():
        used.append(1)
        serial, parallel = arrays._numba_loops(fn, kinds, nout, nparams is not None)
        return (lambda n, *r: serial(n, *r), lambda n, *r: parallel(n, *r))

    serial, threaded = _native.load(path, kinds, nout, fallback)
    assert isinstance(serial, _native.NativeLoop)
    return serial, threaded, used


def _scalar(fn, columns, params):
    n = columns[0].size
    rows = [fn(*(float(c[i]) for c in columns), *(() if params is None else (params,))) for i in range(n)]
    out = np.array(rows, dtype=np.float64)
    return out.reshape(n, -1).T


@pytest.mark.parametrize("cases", ["edge", "random"])
def test_kept_loop_is_bitwise_the_core_serial_and_threaded(tmp_path, cases):
    if cases == "edge":
        V = _edge_speeds(VY)
        E, R, m, p = (np.full(V.size, x) for x in ARGS)
    else:
        V, E, R, m, p = _random_cases()
    serial, threaded, used = _loops(tmp_path, seed.outcome, "aaaaa", NOUT, 0)
    want = _scalar(seed.outcome, (V, E, R, m, p), ())
    numba_serial, _ = arrays._numba_loops(seed.outcome, "aaaaa", NOUT, True)
    by_numba = np.empty((NOUT, V.size))
    numba_serial(V.size, V, E, R, m, p, (), by_numba)
    for loop in (serial, threaded):
        out = np.full((NOUT, V.size), -1.0)
        loop(V.size, V, E, R, m, p, (), out)
        assert _same(out, want) and _same(out, by_numba)
    assert not used  # every call taken by the kept loop


def test_kept_loop_with_parameters_and_scalars(tmp_path):
    """A model with parameters (a loop of its own, called, not inlined), scalar arguments, an output
    with any strides (a table's transpose), split over threads: still the core's numbers."""
    V = np.linspace(0.5, 90.0, 3000)
    params = (2e-6, 1.0)
    serial, threaded, used = _loops(tmp_path, visco.outcome, "assss", NOUT, len(params))
    want = _scalar(visco.outcome, [V] + [np.full(V.size, x) for x in ARGS], params)
    for loop in (serial, threaded):
        table = np.full((V.size, NOUT), -1.0)
        loop(V.size, V, *ARGS, params, table.T)
        assert _same(table.T, want)
    assert not used


def test_calls_the_kept_loop_cannot_take_go_to_numba(tmp_path):
    V = np.linspace(0.5, 90.0, 3000)
    params = (2e-6, 1.0)
    serial, threaded, used = _loops(tmp_path, visco.outcome, "assss", NOUT, len(params))
    want = _scalar(visco.outcome, [V] + [np.full(V.size, x) for x in ARGS], params)
    wide = np.repeat(V, 2)[::2]  # a strided column: taken, read in place
    out = np.empty((NOUT, V.size))
    threaded(V.size, wide, *ARGS, params, out)
    assert not used and _same(out, want)
    frozen = V.copy()
    frozen.setflags(write=False)  # read-only: its address from numpy's interface, not a writable view
    for loop in (serial, threaded):
        out = np.empty((NOUT, V.size))
        loop(V.size, frozen, *ARGS, params, out)
        assert not used and _same(out, want)
    raw = np.zeros(V.nbytes + 1, dtype=np.uint8)
    odd = raw[1:].view(np.float64)  # an unaligned column: numba's loop
    odd[:] = V
    assert not odd.flags.aligned
    out = np.empty((NOUT, V.size))
    serial(V.size, odd, *ARGS, params, out)
    assert len(used) == 1 and _same(out, want)


def test_the_lane_checks_what_evaluate_leaves_to_it(tmp_path):
    """A lane (evaluate's usual call, its result allocated inside) checks only the first array and
    the parameters: a strided or read-only column is taken in place; an unaligned one, parameters
    of another count or type go to numba's loop; every answer is the core's."""
    V = np.linspace(0.5, 90.0, 1500)
    params = (2e-6, 1.0)
    serial, _, used = _loops(tmp_path, visco.outcome, "assss", NOUT, len(params))
    run = serial.lane(NOUT)
    want = _scalar(visco.outcome, [V] + [np.full(V.size, x) for x in ARGS], params)
    frozen = V.copy()
    frozen.setflags(write=False)
    for column in (V, np.repeat(V, 2)[::2], frozen, V[::-1].copy()[::-1]):
        out = run(V.size, (column, *ARGS), params)
        assert out.shape == (NOUT, V.size) and not used and _same(out, want)
    raw = np.zeros(V.nbytes + 1, dtype=np.uint8)
    odd = raw[1:].view(np.float64)
    odd[:] = V
    assert len(used) == 0 and _same(run(V.size, (odd, *ARGS), params), want) and len(used) == 1
    for wrong in ((2e-6,), (2e-6, 1)):
        with pytest.raises(Exception):  # numba's loop refuses them as it always did
            run(V.size, (V, *ARGS), wrong)
    assert serial.lane(NOUT) is not None and _loops(tmp_path, visco.outcome, "aaaaa", NOUT, 2)[0].lane(NOUT) is None


def test_the_loop_writes_its_status_slot_on_every_call(tmp_path, monkeypatch):
    """numba's convention writes the return value into the first status slot even when the call
    succeeds: the slots a call passes must outlive it (a freed pair was overwritten), which the
    module's one shared pair does (the ufunc's inner loop passes slots on its own stack, which
    outlive its call too)."""
    monkeypatch.setattr(_native, "_ufunc_api", lambda: None)  # the ctypes lane, as without the ufunc
    serial, _, used = _loops(tmp_path, seed.restitution_at, "as", 1, None)
    V = np.linspace(0.5, 90.0, 100)

    def general():
        out = np.empty((1, V.size))
        serial(V.size, V, VY, (), out)
        return out

    lane = serial.lane(1)
    for call in (general, lambda: lane(V.size, (V, VY), ())):
        _native._SCRATCH_SLOTS[0] = 0x5A5A
        out = call()
        assert _native._SCRATCH_SLOTS[0] is None  # NULL written, into memory the module owns
        assert _same(out[0], [seed.restitution_at(float(v), VY) for v in V])
    assert not used


@pytest.fixture
def ufunc_at_once(monkeypatch):
    """Lanes make their loop's ufunc at their first call, not after UFUNC_AFTER calls through ctypes."""
    monkeypatch.setattr(_native, "UFUNC_AFTER", 0)


def _ufunc_lane(tmp_path, fn, kinds, nparams):
    serial, _, used = _loops(tmp_path, fn, kinds, 1, nparams)
    run = serial.lane(1)
    assert serial._s.ufunc is None  # not made before the lane's calls ask for it
    V = np.linspace(0.5, 90.0, 8)
    run(V.size, (V, *((VY,) if kinds == "as" else ARGS)), (2e-6, 1.0)[: nparams or 0])
    assert serial._s.ufunc, "the lane of a one-result loop makes its ufunc where numpy's C API is found"
    return serial, run, used


@pytest.mark.parametrize("cases", ["edge", "random"])
def test_the_ufunc_lane_is_bitwise_the_core(tmp_path, cases, ufunc_at_once):
    """A one-result loop's lane calls the kept loop as a numpy ufunc: the core's numbers bit for bit,
    for the seed's restitution (no parameters) and a model's (parameters gathered into the C array
    the loop takes), for any float64 column (strided, reversed, read-only, unaligned: numpy copies
    that one to an aligned buffer first), with no call going to numba's loop."""
    V = _edge_speeds(VY) if cases == "edge" else _random_cases()[0]
    seed_loop, run, used = _ufunc_lane(tmp_path / "seed", seed.restitution_at, "as", None)
    want = _scalar(seed.restitution_at, (V, np.full(V.size, VY)), None)
    raw = np.zeros(V.nbytes + 1, dtype=np.uint8)
    odd = raw[1:].view(np.float64)
    odd[:] = V
    frozen = V.copy()
    frozen.setflags(write=False)
    wide = np.repeat(V, 2)[::2]
    for column, expect in ((V, want), (wide, want), (V[::-1], want[:, ::-1]), (frozen, want), (odd, want)):
        out = run(column.size, (column, VY), ())
        assert out.shape == (1, V.size) and out.flags.c_contiguous and _same(out, expect)
    assert _same(run(V.size, (V, np.float64(VY)), ()), want)
    params = (2e-6, 1.0)
    (tmp_path / "visco").mkdir()
    visco_loop, run, used_visco = _ufunc_lane(tmp_path / "visco", visco.restitution_only, "assss", len(params))
    want = _scalar(visco.restitution_only, [V] + [np.full(V.size, x) for x in ARGS], params)
    assert _same(run(V.size, (V, *ARGS), params), want)
    assert not used and not used_visco
    # every call computed by the ufunc itself: none refused (then the general route would have given
    # the same bits), for either loop
    assert seed_loop._s.ufunc[1].value == 0 and visco_loop._s.ufunc[1].value == 0


def test_the_ufunc_lane_reports_no_floating_point_status(tmp_path, ufunc_at_once):
    """numpy reads the floating-point status after a ufunc's loop and warns (or raises) on what it
    finds; the seed's restitution overflows in a branch it does not take at large speeds. No path
    of the package reports it (numba's loops and ctypes' call do not): neither does the ufunc."""
    serial, run, used = _ufunc_lane(tmp_path, seed.restitution_at, "as", None)
    V = np.array([0.0, 5e-324, 1e-300, VY * (1 - 1e-12), VY, VY * (1 + 1e-12), 1e3, 1e150, 1e300, 1.7e308])
    with np.errstate(all="raise"):
        out = run(V.size, (V, VY), ())
    assert _same(out[0], [seed.restitution_at(float(v), VY) for v in V]) and not used
    assert serial._s.ufunc[1].value == 0  # computed by the ufunc, not refused to the general route
    with np.errstate(all="raise"):
        assert np.sqrt(np.array([4.0]))[0] == 2.0  # numpy's own status is left clean


def test_a_call_the_ufunc_refuses_goes_to_numba(tmp_path, ufunc_at_once):
    """The ufunc takes its scalars as numpy's broadcast scalars (step 0): an array in their place is
    refused (counted, nothing computed), as is an error status from the loop; the lane then takes
    numba's loop, which computes the same or raises as it always did. Parameters of another count
    or type go to numba's loop too; an error status sends the call to the general route (the loop
    through ctypes, whose own error status hands it to numba's loop, which raises)."""
    serial, run, used = _ufunc_lane(tmp_path, visco.restitution_only, "assss", 2)
    ufunc, refused = serial._s.ufunc
    V = np.linspace(0.5, 90.0, 100)
    before = refused.value
    ufunc(V, np.full(V.size, ARGS[0]), *ARGS[1:], 2e-6, 1.0)
    assert refused.value == before + 1
    for wrong in ((2e-6,), (2e-6, 1)):
        with pytest.raises(Exception):  # numba's loop refuses them as it always did
            run(V.size, (V, *ARGS), wrong)
    assert len(used) == 1

    import llvmlite.binding as ll

    # a loop that reports an error on every call: the ufunc counts it, the lane asks numba's loop
    args = ", ".join(["ptr", "ptr", "i64", "ptr", "i64", "double", "ptr", "ptr", "i64", "i64"])
    engine = ll.create_mcjit_compiler(
        ll.parse_assembly(f"define i32 @fails({args}) {{\n  ret i32 1\n}}\n"),
        ll.Target.from_triple(ll.get_process_triple()).create_target_machine(jit=True),
    )
    engine.finalize_object()
    failing = ctypes.CFUNCTYPE(ctypes.c_int32)(engine.get_function_address("fails"))
    made = _native._ufunc(failing, "as", 0, "fails")
    assert made is not None
    ufunc, refused = made
    ufunc(V, VY)
    assert refused.value == 1
    serial, _, used = _loops(tmp_path, seed.restitution_at, "as", 1, None)
    serial._s.ufunc = made
    out = serial.lane(1)(V.size, (V, VY), ())  # refused twice: the general call (ctypes) computes it
    assert refused.value == 3 and not used
    assert _same(out[0], [seed.restitution_at(float(v), VY) for v in V])


def test_without_numpys_c_api_the_lane_calls_through_ctypes(tmp_path, monkeypatch, ufunc_at_once):
    monkeypatch.setattr(_native, "_ufunc_api", lambda: None)
    serial, _, used = _loops(tmp_path, seed.restitution_at, "as", 1, None)
    V = np.linspace(0.5, 90.0, 100)
    run = serial.lane(1)
    for _ in range(2):
        out = run(V.size, (V, VY), ())
        assert serial._s.ufunc == () and not used
        assert _same(out[0], [seed.restitution_at(float(v), VY) for v in V])


def test_a_lane_makes_its_ufunc_only_after_many_calls(tmp_path, monkeypatch):
    """Making the ufunc compiles its inner loop (milliseconds): a lane's first UFUNC_AFTER calls go
    through ctypes, so a command or a short script never pays for it; the next makes it, and every
    call gives the core's numbers."""
    assert _native.UFUNC_AFTER >= 100
    monkeypatch.setattr(_native, "UFUNC_AFTER", 3)
    made = []
    real = _native._ufunc
    monkeypatch.setattr(_native, "_ufunc", lambda *a: made.append(1) or real(*a))
    serial, _, used = _loops(tmp_path, seed.restitution_at, "as", 1, None)
    V = np.linspace(0.5, 90.0, 100)
    want = [seed.restitution_at(float(v), VY) for v in V]
    run = serial.lane(1)
    for k in range(6):
        assert _same(run(V.size, (V, VY), ())[0], want)
        assert len(made) == (k >= 3) and (serial._s.ufunc is None) == (k < 3)
    assert serial.lane(1)(V.size, (V, VY), ()) is not None and len(made) == 1  # a new lane: the ufunc made
    assert not used


def test_an_entry_that_is_not_sound_is_not_loaded(tmp_path):
    path = tmp_path / "entry.bin"
    assert _native.build(seed.outcome, "assss", NOUT, 0, path)
    good = path.read_bytes()
    for bad in (good[:-1] + bytes([good[-1] ^ 1]), good[:50], b"", b"\x7fELF" + good[4:]):
        path.write_bytes(bad)
        assert not _native.sound(path)
        assert _native.load(path, "assss", NOUT, lambda: None) is None
    path.write_bytes(good)
    assert _native.load(path, "aaaaa", NOUT, lambda: None) is None  # another loop's signature
    assert _native.load(path, "assss", NOUT, lambda: None) is not None


_RUN = r"""
import sys, hashlib, numpy as np, microimpact as mi
from microimpact.core import _native
built = []
real = _native._compile
_native._compile = lambda *a: built.append(1) or real(*a)
pair = mi.ContactPair.paper_case("silicon")
r = pair.impact(np.linspace(1.0, 120.0, 200_000), warn=False)
digest = hashlib.sha256(b"".join(np.ascontiguousarray(getattr(r, f)).tobytes() for f in ("restitution", "contact_time")))
print(digest.hexdigest(), len(built), int("numba" in sys.modules), int("scipy" in sys.modules))
"""


def _runs(cache, k=1):
    env = dict(os.environ, MICROIMPACT_CACHE_DIR=str(cache))
    env.pop("MICROIMPACT_BACKEND", None)
    src = str(Path(arrays.__file__).resolve().parents[2])
    env["PYTHONPATH"] = src + os.pathsep + env.get("PYTHONPATH", "")
    procs = [
        subprocess.Popen(
            [sys.executable, "-c", _RUN], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env
        )
        for _ in range(k)
    ]
    outs = []
    for p in procs:
        out, err = p.communicate(timeout=600)
        assert p.returncode == 0, err
        assert "kernel cache" not in err, err
        outs.append(out.split())
    return outs


def test_a_new_process_computes_without_numba_and_heals_a_corrupt_entry(tmp_path):
    cache = tmp_path / "cache"
    [first] = _runs(cache)
    assert first[1:] == ["1", "1", "1"]  # numba's route, the machine code kept
    entries = list((cache / "kernels" / "native").glob("*.bin"))
    assert len(entries) == 1
    [warm] = _runs(cache)
    assert warm == [first[0], "0", "0", "0"]  # the same numbers; neither numba nor scipy imported
    data = bytearray(entries[0].read_bytes())
    data[len(data) // 2] ^= 0x10
    entries[0].write_bytes(bytes(data))
    [healing] = _runs(cache)
    assert healing == [first[0], "1", "1", "1"]  # numba's route again, the entry written anew
    assert _native.sound(entries[0])
    [healed] = _runs(cache)
    assert healed == [first[0], "0", "0", "0"]


def test_processes_started_together_on_an_empty_cache_keep_it_once(tmp_path):
    outs = _runs(tmp_path / "cache", k=3)
    assert len({o[0] for o in outs}) == 1  # the same numbers everywhere
    assert sum(int(o[1]) for o in outs) == 1, outs  # one wrote the machine code, the others waited


def test_numba_works_after_a_kept_loop_was_loaded(tmp_path):
    """Loading an entry gives numba's helper names (used only by the wrapper it never calls) a
    placeholder when numba is not loaded; numba's own start-up then sets the real ones."""
    path = tmp_path / "entry.bin"
    assert _native.build(seed.outcome, "assss", NOUT, 0, path)
    code = f"""
import numpy as np
from microimpact.core import _native
from microimpact.core.models.thornton_ning_2016 import outcome
import sys
serial, _ = _native.load(__import__("pathlib").Path({str(path)!r}), "assss", {NOUT}, None)
assert "numba" not in sys.modules
import numba

@numba.njit
def f(n):
    a = np.arange(n) * 1.0  # allocates and frees (numba's runtime)
    if n > 3:
        raise ValueError("n is", n)  # numba's exception helpers
    return a.sum()

print(f(3))
try:
    f(5)
except ValueError as e:
    print(e)
"""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(Path(arrays.__file__).resolve().parents[2]) + os.pathsep + env.get("PYTHONPATH", "")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split("\n")[:2] == ["3.0", "('n is', 5)"]


def test_a_signal_during_the_join_waits_for_every_worker_then_raises():
    """A threaded native call never returns (nor raises) while a worker still runs its machine code:
    Ctrl-C raised inside ``join`` used to leave daemon workers running into the interpreter's exit
    (a segmentation fault instead of exit 130 in about 1 of 40 interrupted ``impact`` commands)."""
    import threading

    from microimpact.core import _native

    release = threading.Event()
    done = []

    def work(k):
        release.wait(5)
        done.append(k)

    workers = [threading.Thread(target=work, args=(k,), daemon=True) for k in range(3)]
    for w in workers:
        w.start()
    unstarted = threading.Thread(target=work, args=(99,))  # the signal came before it was started
    interrupts = iter([KeyboardInterrupt("first"), KeyboardInterrupt("second")])
    real_join = threading.Thread.join

    def join(self, timeout=None):
        exc = next(interrupts, None)
        if exc is not None:  # as a signal handler raising inside join
            release.set()
            raise exc
        return real_join(self, timeout)

    threading.Thread.join = join
    try:
        with pytest.raises(KeyboardInterrupt, match="first"):
            _native._join_all([*workers, unstarted])
    finally:
        threading.Thread.join = real_join
    assert sorted(done) == [0, 1, 2] and not any(w.is_alive() for w in workers)
