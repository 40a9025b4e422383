"""The command's entry points and its error paths: ``python -m microimpact``, usage errors, broken pipes.

Also the argument checks of :func:`microimpact.sweep.sweep` that no other test reaches (a bad
base pair, bad chunk specifications): each raises ValueError naming the parameter and the value.
"""

import runpy
import signal
import subprocess
import sys
import warnings

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


def test_a_command_gives_back_the_hooks_it_set(capsys):
    # the command line silences the interrupt's tracebacks while a command runs, and only then
    def now():
        return (
            sys.excepthook,
            sys.unraisablehook,
            signal.getsignal(signal.SIGINT),
            signal.getsignal(signal.SIGTERM),
            warnings.formatwarning,
            warnings.showwarning,
            list(warnings.filters),
        )

    hooks = now()
    assert main(["impact", "50"]) == 0
    assert now() == hooks
    capsys.readouterr()


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


def test_a_deprecation_reaches_the_command_line(tmp_path):
    # Python's default filters hide a DeprecationWarning raised outside __main__: the command shows
    # microimpact's own, once, on one line (here the additive rule with a compliant tangential law)
    argv = ["export", "--out", "out", "--work-of-adhesion", "0.1", "--tangential", "mindlin"]
    argv += ["--poisson-ratio", "0.3", "--friction", "0.3", "--velocities", "1,10"]
    proc = subprocess.run(
        [sys.executable, "-m", "microimpact", *argv], cwd=tmp_path, capture_output=True, text=True, timeout=120
    )
    assert proc.returncode == 0, proc.stderr
    lines = proc.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("warning: adhesion='additive'"), proc.stderr
    assert "adhesion='thornton_ning_1998_adhesive_plastic'" in lines[0]


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


# ----------------------------------------------------------------------------- values with a minus sign
NEGATIVE_TOKENS = ["-1e-3", "-.5", "-5", "-5:5:11", "-1,2", "-2.5E+3"]


@pytest.mark.parametrize("token", NEGATIVE_TOKENS)
def test_parse_negative_values_of_options(token):
    """A number, range or list with a minus sign after an option is the option's value: alone, among
    the values of a many-valued option, after ``=``, and after an abbreviated option."""
    parser = cli.build_parser()
    for argv, values in [
        (["--velocity", token], [token]),
        (["--velocity", "1", token, "3:4:2"], ["1", token, "3:4:2"]),
        ([f"--velocity={token}"], [token]),
        (["--vel", token], [token]),
    ]:
        args = parser.parse_args(["sweep", *argv, "--out", "s.nc"])
        assert args.velocity == values and args.out == "s.nc", argv
    if ":" not in token and "," not in token:  # a typed option gets the number
        args = parser.parse_args(["impact", "50", "--radius", token, "--rad", token, "--json"])
        assert args.radius == float(token) and args.json and args.velocities == ["50"]


@pytest.mark.parametrize("token", NEGATIVE_TOKENS)
def test_parse_negative_values_as_positionals(token):
    parser = cli.build_parser()
    assert parser.parse_args(["impact", token]).velocities == [token]
    assert parser.parse_args(["impact", "30", token, "70", "--json"]).velocities == ["30", token, "70"]
    assert parser.parse_args(["impact", "--json", "--", token]).velocities == [token]
    assert parser.parse_args(["history", token]).velocity == token


@pytest.mark.parametrize(
    "argv, message",
    [
        (["impact", "-5:5:11"], "velocity must be non-negative and not NaN, got -5.0"),
        (["impact", "30", "-.5"], "velocity must be non-negative and not NaN, got -0.5"),
        (["sweep", "--velocity", "-5:5:11", "--out", "s.nc"], "velocity must be non-negative and not NaN, got -5.0"),
        (["sweep", "--velocity", "1", "-1e-3", "--out", "s.nc"], "got -0.001"),
        (["impact", "50", "--radius", "-1e-3"], "--radius must be positive and finite, got -0.001"),
    ],
)
def test_negative_values_reach_the_parameters_own_check(argv, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "argv, message",
    [
        (["paper", "--workers", "-1.5"], "argument --workers: invalid int value: '-1.5'"),
        (["history", "50", "-5"], "unrecognized arguments: -5"),
        (["-5:5:11"], "argument COMMAND: invalid choice: '-5:5:11'"),
        (["impact", "50", "--radius", "-x"], "argument --radius: expected one argument"),
    ],
)
def test_parse_errors_quote_a_negative_value_as_given(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and "\0" not in err and "\\x00" not in err, err
