"""The command's entry points and its error paths: ``python -m microimpact``, usage errors, broken pipes.

Also the argument checks of :func:`microimpact.sweep.sweep` that no other test reaches (a bad
base pair, bad chunk specifications): each raises ValueError naming the parameter and the value.
"""

import runpy
import signal
import sys

import numpy as np
import pytest

from microimpact import cli
from microimpact.cli import main


def test_python_dash_m_runs_the_command(monkeypatch, capsys):
    import microimpact

    monkeypatch.setattr(sys, "argv", ["microimpact", "--version"])
    handlers = {sig: signal.getsignal(sig) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        with pytest.raises(SystemExit) as exc:
            runpy.run_module("microimpact", run_name="__main__")
        # the entry point leaves the exiting process deaf to SIGINT/SIGTERM (cli.console_main)
        assert all(signal.getsignal(sig) == signal.SIG_IGN for sig in handlers)
    finally:
        for sig, handler in handlers.items():
            signal.signal(sig, handler)
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"microimpact {microimpact.__version__}"


def test_no_command_prints_help_and_exits_2(capsys):
    assert main([]) == 2
    assert "COMMAND" in capsys.readouterr().out


def test_usage_error_is_one_line_pointing_to_help(capsys):
    assert main(["impact", "--no-such-option"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].endswith("(see microimpact impact --help)")


def test_warnings_are_one_short_line():
    text = cli._short_warning("outside the small-strain range", UserWarning, "f.py", 1)
    assert text == "warning: outside the small-strain range\n"


def test_broken_pipe_is_a_quiet_success(monkeypatch):
    def func(args):
        raise BrokenPipeError

    parser = cli.build_parser()
    monkeypatch.setattr(cli, "build_parser", lambda **kw: parser)
    parser._subparsers._group_actions[0].choices["materials"].set_defaults(func=func)
    assert main(["materials"]) == 0


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(base=3), "base must be a ContactPair or a paper case name, got 3"),
        (dict(chunks=1.5), "chunks must be an int, a dict or 'auto', got 1.5"),
        (dict(chunks={"velocity": (1, 1)}), r"chunks for velocity must be positive and sum to 3, got \(1, 1\)"),
        (dict(chunks={"velocity": "a"}), "chunks for velocity must be a positive integer, got 'a'"),
        (dict(chunks={"velocity": 0}), "chunks for velocity must be a positive integer, got 0"),
    ],
)
def test_sweep_argument_errors_name_the_parameter(kwargs, match):
    pytest.importorskip("xarray")
    from microimpact.sweep import sweep

    with pytest.raises(ValueError, match=match):
        sweep(np.array([10.0, 20.0, 30.0]), **kwargs)
