"""An interrupt a library swallowed stops a command before its outputs appear.

Python prints and drops an exception raised inside a ``__del__`` or a weakref callback, so the
command line's interrupt can be lost in the middle of drawing a figure; the command would then
finish its outputs and report the interrupt only after. :func:`microimpact.io.commit_check` puts the
command's check just before each output takes its place: an output is committed, or it is not there.
"""

from __future__ import annotations

import gc
import signal

import pytest

from microimpact.cli import _interrupt
from microimpact.io import MANIFEST, atomic_write, commit_check, owned_directory


class Stop(KeyboardInterrupt):
    pass


def _stop():
    raise Stop


def test_a_file_is_not_replaced_when_the_check_raises(tmp_path):
    target = tmp_path / "out.csv"
    target.write_text("earlier\n")
    with pytest.raises(Stop), commit_check(_stop), atomic_write(target) as fh:
        fh.write("new\n")
    assert target.read_text() == "earlier\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.csv"]  # no temporary file left


@pytest.mark.parametrize("earlier", [False, True], ids=["new-folder", "earlier-output"])
def test_a_folder_is_not_committed_when_the_check_raises(tmp_path, earlier):
    out = tmp_path / "out"
    if earlier:
        with owned_directory(out, "test") as stage:
            (stage / "a.txt").write_text("earlier\n")
    before = sorted(p.name for p in out.iterdir()) if earlier else None
    with pytest.raises(Stop), commit_check(_stop), owned_directory(out, "test") as stage:
        (stage / "a.txt").write_text("new\n")
        (stage / "b.txt").write_text("new\n")
    if earlier:
        assert sorted(p.name for p in out.iterdir()) == before == sorted(["a.txt", MANIFEST])
        assert (out / "a.txt").read_text() == "earlier\n"
    else:
        assert list(tmp_path.iterdir()) == []


def test_without_a_check_outputs_are_committed(tmp_path):
    target = tmp_path / "out.csv"
    with commit_check(lambda: None), atomic_write(target) as fh:
        fh.write("new\n")
    assert target.read_text() == "new\n"
    with atomic_write(target) as fh:  # outside the block: no check
        fh.write("again\n")
    assert target.read_text() == "again\n"


@pytest.mark.needs_sigint
def test_an_interrupt_swallowed_in_a_finalizer_stops_the_commit(tmp_path):
    """The signal's exception raised inside ``__del__`` is dropped by Python; the pending interrupt
    still stops the output (the command line's own check, as :func:`microimpact.cli.main` sets it)."""

    class Finalized:
        def __del__(self):
            signal.raise_signal(signal.SIGINT)  # the handler raises here, where Python cannot propagate it

    target = tmp_path / "out.csv"
    _interrupt.install()
    try:
        with pytest.raises(_interrupt.Interrupted), commit_check(_interrupt.check), atomic_write(target) as fh:
            fh.write("new\n")
            obj = Finalized()
            del obj
            gc.collect()
            fh.write("more\n")  # the command went on: its exception was swallowed
    finally:
        _interrupt.restore()
    assert not target.exists()
    assert list(tmp_path.iterdir()) == []
