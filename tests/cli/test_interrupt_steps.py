"""A signal during a step numba must finish (:mod:`microimpact._atomic`) is raised when the step ends.

Numba builds and loads compiled loops in Python, through llvmlite; a KeyboardInterrupt raised there by
the command line's handler left an LLVM object owned twice, whose release then aborted the process
("free(): double free detected", exit -6, in the interrupt soak) instead of the one line and 130.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys

import pytest

from microimpact import _atomic
from microimpact.cli import _interrupt


@pytest.fixture
def installed():
    _interrupt.install()
    try:
        yield
    finally:
        _interrupt.restore()


@pytest.mark.needs_sigint
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_inside_a_step_is_raised_when_the_step_ends(installed, sig):
    done = []
    with pytest.raises(_interrupt.Interrupted) as caught:
        with _atomic.step():
            with _atomic.step():  # nested: the outermost step's end raises it
                os.kill(os.getpid(), sig)
                done.append(sum(range(1000)))  # bytecodes after the signal: the handler has run, not raised
            done.append("inner left")
    assert done == [499500, "inner left"]
    assert caught.value.signum == int(sig) and _interrupt.pending() == int(sig)


@pytest.mark.needs_sigint
def test_outside_a_step_the_signal_is_raised_where_the_command_is(installed):
    with pytest.raises(_interrupt.Interrupted):
        os.kill(os.getpid(), signal.SIGINT)
        for _ in range(10**6):  # the handler runs between bytecodes
            pass
    assert not _atomic.busy()


def test_the_engine_compiles_and_loads_in_a_step():
    """Every first call of a compiled loop (where numba builds or loads it) runs inside a step: in a
    new process, where no loop is ready yet."""
    code = """
import numpy as np
import microimpact as mi
from microimpact import _atomic
from microimpact.engine import loops

seen = []
real = loops._Family.first_call


def spy(self, loop, args):
    seen.append(_atomic.busy())
    return real(self, loop, args)


loops._Family.first_call = spy
mi.ContactPair.paper_case("mica").impact(np.linspace(1.0, 2.0, 5000), warn=False)
print(len(seen), all(seen))
"""
    env = {**os.environ, "MICROIMPACT_BACKEND": "numba"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    n, every = out.stdout.split()
    assert int(n) > 0 and every == "True"


def test_no_handler_no_callback():
    """Without the command line's handler a step changes nothing: no callback, nothing raised."""
    assert not _atomic.busy()
    with _atomic.step():
        assert _atomic.busy()
    assert not _atomic.busy()


@pytest.mark.parametrize("sig", [pytest.param(signal.SIGINT, marks=pytest.mark.needs_sigint), signal.SIGTERM])
def test_a_signal_while_numba_initialises_its_dispatcher(tmp_path, sig):
    """numba's ``_dispatcher`` extension imports ``numba._devicearray`` in its initialisation and, when
    that import fails, prints the exception (C's ``PyErr_Print``, through :data:`sys.excepthook`) before
    raising an ImportError: a signal at that moment of the interrupt soak printed a traceback before the
    command's one line. The signal is sent from an audit hook at the import of ``numba._devicearray``."""
    driver = f"""
import os, signal, sys
def hook(event, args):
    handler = signal.getsignal({int(sig)})
    if event == "import" and args[0] == "numba._devicearray" and handler not in (signal.default_int_handler, signal.SIG_DFL, signal.SIG_IGN):
        os.kill(os.getpid(), {int(sig)})
sys.addaudithook(hook)
from microimpact.cli import console_main
# enough speeds for the compiled loop (numba is imported for it)
sys.argv = ["microimpact", "export", "--out", "out", "--velocities", "0.01:200:100000"]
sys.exit(console_main())
"""
    proc = subprocess.run([sys.executable, "-c", driver], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 128 + int(sig), proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "interrupted" in lines[0], proc.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("sig", [pytest.param(signal.SIGINT, marks=pytest.mark.needs_sigint), signal.SIGTERM])
def test_a_signal_while_xarray_creates_the_netcdf_file_waits_for_it(tmp_path, sig):
    """xarray takes its NetCDF file lock in Python while it creates the file: an interrupt raised
    between an acquire and the release left the lock held, and a sweep of the 1,000-run soak then
    waited for ever on it. The signal is sent as that call starts; it must be raised when the call
    has returned (the step), and the command end with one line and no file."""
    driver = f"""
import os, signal, sys
import xarray as xr
create = xr.Dataset.to_netcdf
def to_netcdf(self, *args, **kwargs):
    if kwargs.get("compute") is False:
        os.kill(os.getpid(), {int(sig)})
        delayed = create(self, *args, **kwargs)
        sys.stderr.write("created\\n")
        return delayed
    return create(self, *args, **kwargs)
xr.Dataset.to_netcdf = to_netcdf
from microimpact.cli import console_main
sys.argv = ["microimpact", "sweep", "--velocity", "1:120:2000", "--out", "out.nc", "--chunks", "200", "-q"]
sys.exit(console_main())
"""
    proc = subprocess.run([sys.executable, "-c", driver], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 128 + int(sig), proc.stderr
    lines = [ln for ln in proc.stderr.strip().splitlines() if not ln.startswith("warning:")]
    assert len(lines) == 2 and lines[0] == "created" and "interrupted" in lines[1], proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == []
