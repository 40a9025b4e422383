"""The OpenFOAM reader refuses, with a one-line ValueError naming file and line, the records it would misread.

Each case is a record that today's reader would turn into wrong numbers without a word (a column
taking another's data, an id overflowing int64, a NaN weight, an impact fraction above one) or
that it should not read at all (the working folder for an empty path, a FIFO that blocks, a device
or a file larger than the bound).
"""

from __future__ import annotations

import os
import sys
import threading

import numpy as np
import pytest

from microimpact import openfoam

sys.path.insert(0, os.path.dirname(__file__))
from test_openfoam import HEAD, _row  # noqa: E402

sys.path.pop(0)


def _write(path, rows, head=HEAD):
    path.write_text(head + "\n" + "\n".join(rows) + "\n")
    return path


def _good(t=1e-4, orig=0, n=1.0):
    return _row(t, (1e-4, 0, 0), (0.5, 0.0, -3.0), 4e-6, orig=orig, n=n)


def test_a_column_named_twice_is_refused(tmp_path):
    """Two ``d`` columns: the table kept the last, so every diameter read was dTarget's value."""
    f = _write(tmp_path / "plate.post", [_good()], head=HEAD.replace(" dTarget ", " d "))
    with pytest.raises(ValueError, match=r"plate\.post, line 1: column 'd' named twice"):
        openfoam.read_patch_hits(f)


@pytest.mark.parametrize("token", ["1e30", "-1e30", "9223372036854775808", "2.5", "nan", "inf"])
def test_an_id_that_is_no_int64_label_is_refused(tmp_path, token):
    f = _write(tmp_path / "plate.post", [_good(orig=1), _good(orig=2).replace(" 0.79 0 2 1 ", f" 0.79 0 {token} 1 ")])
    with pytest.raises(ValueError, match=rf"line 3: origId {token!r} is (not an integer label|outside the int64)"):
        openfoam.read_patch_hits(f)


def test_large_ids_are_read_exactly(tmp_path):
    big = 2**62 + 1  # a float would round it
    f = _write(tmp_path / "plate.post", [_good().replace(" 0.79 0 0 1 ", f" 0.79 0 {big} 1 "), _good(orig=7)])
    hits = openfoam.read_patch_hits(f)
    assert hits.orig_id.dtype == np.int64 and sorted(hits.orig_id.tolist()) == [7, big]


@pytest.mark.parametrize("token", ["nan", "inf", "-1.0"])
def test_a_particle_count_that_is_not_a_count_is_refused(tmp_path, token):
    f = _write(tmp_path / "plate.post", [_good(), _good(orig=1).replace(" -1 1.0 ", f" -1 {token} ")])
    with pytest.raises(ValueError, match=rf"line 3: nParticle {token!r}"):
        openfoam.read_patch_hits(f)


def test_fractional_particle_counts_still_read(tmp_path):
    """OpenFOAM sizes parcels by mass by default, so nParticle is fractional in valid records."""
    f = _write(tmp_path / "plate.post", [_good(n=2.75)])
    assert openfoam.read_patch_hits(f).n_particle.tolist() == [2.75]


def test_an_impact_fraction_above_one_is_refused(tmp_path):
    pytest.importorskip("xarray")
    f = _write(tmp_path / "plate.post", [_good(orig=k) for k in range(5)])
    hits = openfoam.read_patch_hits(f)
    dec = openfoam.decide(hits)
    ok = openfoam.deposition_report(hits, dec, {4e-6: 5})
    assert float(ok["impact_fraction"][0]) == 1.0
    with pytest.raises(ValueError, match=r"impact fraction 5\.0 > 1"):
        openfoam.deposition_report(hits, dec, {4e-6: 1})
    with pytest.raises(ValueError, match="positive and finite"):
        openfoam.deposition_report(hits, dec, {4e-6: float("inf")})


def test_an_empty_path_is_refused_not_the_working_folder(tmp_path, monkeypatch):
    _write(tmp_path / "plate.post", [_good()])
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match="^path must name"):
        openfoam.read_patch_hits("")


def test_a_directory_named_like_a_record_is_refused(tmp_path):
    (tmp_path / "odd.post").mkdir()
    with pytest.raises(ValueError, match=r"odd\.post: not a regular file"):
        openfoam.read_patch_hits(tmp_path)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_a_fifo_named_like_a_record_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "plate.post"
    os.mkfifo(fifo)
    out = {}

    def read():
        try:
            openfoam.read_patch_hits(tmp_path)
        except Exception as exc:  # noqa: BLE001 - the test inspects what came out
            out["exc"] = exc

    th = threading.Thread(target=read, daemon=True)
    th.start()
    th.join(10.0)
    blocked = th.is_alive()
    if blocked:  # release the reader: a writer that opens and closes gives it end-of-file
        os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
        th.join(10.0)
    assert not blocked, "the reader blocked on a FIFO"
    assert isinstance(out.get("exc"), ValueError) and "not a regular file" in str(out["exc"])


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero here")
def test_a_device_is_refused(tmp_path):
    with pytest.raises(ValueError, match="not a regular file"):
        openfoam.read_patch_hits("/dev/zero")
    (tmp_path / "zero.post").symlink_to("/dev/zero")
    with pytest.raises(ValueError, match=r"zero\.post: not a regular file"):
        openfoam.read_patch_hits(tmp_path)


def test_a_record_beyond_the_bound_is_refused(tmp_path, monkeypatch):
    f = _write(tmp_path / "plate.post", [_good()])
    size = f.stat().st_size
    monkeypatch.setattr(openfoam, "MAX_RECORD_BYTES", size)
    assert len(openfoam.read_patch_hits(f)) == 1
    monkeypatch.setattr(openfoam, "MAX_RECORD_BYTES", size - 1)
    with pytest.raises(ValueError, match=rf"plate\.post: {size} bytes, more than the {size - 1}"):
        openfoam.read_patch_hits(f)
