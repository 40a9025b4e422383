"""Calibrate the DEM contact laws to the seed's model (or to any target ``e(V)``).

A DEM engineer whose code offers a linear spring-dashpot, Hertz with viscoelastic or Tsuji damping
or a linear hysteretic spring wants the inputs that make it bounce like the seed's elastic-plastic
model: :func:`calibrate` returns them for one law, :func:`calibrate_all` for every DEM law, and
:meth:`Calibration.lammps` / :meth:`Calibration.liggghts` write them as input-script lines.

This module is the generic driver: it checks the pair, the speeds and the targets, asks the
model's face (:func:`microimpact.models.face`) for the parameters and its input lines, and
evaluates the result. Each law's inverse lives in its face file
(``microimpact/models/NAME.py``); a model without one is calibrated by least squares of ``e``
over its parameters without a default (:func:`microimpact.models._base.calibrate`).

What is matched
---------------
* The restitution coefficient ``e`` at the calibration speed (to the last digits: the laws
  reproduce the target to 1e-10 and better), or, over several speeds, in the least-squares sense.
* The contact time where the law has a free stiffness (linear spring-dashpot: ``k``; hysteretic
  spring: ``k1``): the target's contact time at that speed (the mean over several speeds). Hertz's
  stiffness is fixed by ``E*`` and ``R*``, so the two Hertz laws match ``e`` only.

Targets of :func:`calibrate` default to the seed's model (``thornton_ning_2016``) for the pair; pass
``target_restitution`` (and ``target_contact_time``) as callables of the speed [m/s], or as
arrays of the calibration speeds' shape, to calibrate to measurements or another model.

Adhesive laws as the DEM codes run them
---------------------------------------
A DEM code's adhesive law (EEPA, a simplified JKR, LAMMPS' ``jkr``/``dmt`` with their damping, a
capillary bridge) has inputs of its own: a cohesion energy density, an adhesive stiffness, a
restitution coefficient that its damping turns into a dashpot. Which values make it capture and
rebound as the particle would? :func:`calibrate_adhesive` answers by least squares against a
reference law for the same pair and work of adhesion, by default Thornton & Ning's whole adhesive
elastic-plastic law (the model declaring ``WALL_ADHESION``, :func:`microimpact.core.models.whole_law`):

* the residuals are ``e(V) - e_ref(V)`` at each calibration speed and ``w log(V_s / V_s,ref)`` for
  the capture velocity (weight ``w``, ``capture_weight``), so the capture velocity and the rebound
  above it are matched together, in the least-squares sense where the law cannot match both;
* the free inputs are the law's adhesion input (the parameters its face's
  ``params_for_work_of_adhesion`` sets from the work of adhesion), any without a default, or those
  named in ``free``; each is searched within its bounds, starting from its physical value;
* the result is an :class:`AdhesiveCalibration` (a :class:`~microimpact.calibrate.Calibration`, so
  :meth:`~microimpact.calibrate.Calibration.lammps` and :meth:`~microimpact.calibrate.Calibration.liggghts`
  print the code's lines) with both capture velocities and the residual reported, never hidden.

The other way, from a code's inputs to what it will give, is the model itself:
:func:`code_prediction` returns the capture velocity and ``e(V)`` of given inputs.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from . import _calibration_cache
from . import models as _models
from ._validation import TINY_NORMAL, check_dem_lines, check_dem_words, check_nonnegative, check_poisson
from .core import models as _core
from .core.quantities import OUTCOME_FIELDS

__all__ = [
    "AdhesiveCalibration",
    "adhesion_inputs",
    "calibrate_adhesive",
    "code_prediction",
    "Calibration",
    "CalibrationError",
    "CalibrationWarning",
    "calibrate",
    "calibrate_all",
    "DEM_MODELS",
    "MISS_TOLERANCE",
]


#: The DEM laws: the models whose face has a calibration of its own (at import; models added later
#: with :func:`microimpact.models.register_path` are in :func:`microimpact.models.dem_models`).
DEM_MODELS = _models.dem_models()


_E = OUTCOME_FIELDS.index("restitution")
_TC = OUTCOME_FIELDS.index("contact_time")


def _pair_values(pair):
    try:
        return (
            float(pair.effective_modulus),
            float(pair.effective_radius),
            float(pair.effective_mass),
            float(pair.limiting_pressure),
        )
    except AttributeError:
        raise ValueError(f"pair must be a ContactPair (effective_modulus, ...), got {pair!r}") from None


def _speeds(velocity):
    if isinstance(velocity, bool):
        raise ValueError(f"velocity must be a number or an array of numbers, not a bool, got {velocity!r}")
    try:
        v = np.atleast_1d(np.asarray(velocity, dtype=float))
    except (TypeError, ValueError):
        raise ValueError(f"velocity must be a number or an array of numbers, got {velocity!r}") from None
    if v.ndim != 1 or v.size == 0:
        raise ValueError(f"velocity must be a number or a 1-D array, got shape {v.shape}")
    bad = ~((v > 0.0) & np.isfinite(v))
    if bad.any():
        raise ValueError(f"velocity must be positive and finite, got {float(v[bad][0])!r}")
    # e(V) is looked at a decade either side (the monotonicity note): both ends must be normal doubles
    lo, hi = 10.0 * TINY_NORMAL, np.finfo(float).max / 10.0
    bad = ~((v >= lo) & (v <= hi))
    if bad.any():
        raise ValueError(f"velocity must lie in [{lo!r}, {hi!r}] m/s, got {float(v[bad][0])!r}")
    return v


def _target(values, V, default, name):
    if values is None:
        return default
    out = np.asarray(values(V) if callable(values) else values, dtype=float)
    out = np.broadcast_to(out, V.shape).astype(float)
    return out


def _run(model, V, pv, params):
    from .models._base import run

    return run(_models.get(model), V, pv, params)


class CalibrationWarning(UserWarning):
    """The calibrated law matches the target at the calibration speeds but behaves unlike it elsewhere
    (its ``e(V)`` rises and falls between a tenth of the lowest and ten times the highest speed)."""


class CalibrationError(ValueError):
    """The calibrated law misses its target ``e``: the search ended where the law does not bounce like the
    target (at one speed: off by more than :data:`MISS_TOLERANCE`; at several: a worse least-squares
    fit than a constant ``e``). The message names the model, the target, the ``e`` reached and the
    parameters found. A ValueError, as every refused calibration is."""


#: Largest ``|e - e_target|`` [-] a calibration at one speed may leave: the DEM laws' inverses reach
#: 1e-10 and better, the least-squares default 1e-12 where it converges to the target at all.
MISS_TOLERANCE = 1e-6


def _check_reached(model, names, params, V, e_target, e_reached):
    """Raise :class:`CalibrationError` where the calibration missed its target (:class:`CalibrationError`).

    At several speeds a least-squares fit cannot reach every target; it must at least fit them no worse
    than the best constant ``e`` (their mean), which any law whose ``e`` can vary does, and a law whose
    ``e`` does not depend on the speed matches exactly (its least-squares ``e`` is that mean)."""
    miss = np.asarray(e_reached, dtype=float) - e_target
    if V.size == 1:
        bad = not (abs(float(miss[0])) <= MISS_TOLERANCE)
    else:
        rms = float(np.sqrt(np.mean(miss * miss))) if np.all(np.isfinite(miss)) else np.inf
        spread = float(np.sqrt(np.mean((e_target - np.mean(e_target)) ** 2)))
        bad = not (rms <= spread * (1.0 + 1e-6) + MISS_TOLERANCE)
    if bad:
        found = ", ".join(f"{n} = {p:.6g}" for n, p in zip(names, params))
        speeds = ", ".join(f"{v:.6g}" for v in V[:5]) + (", ..." if V.size > 5 else "")
        targets = ", ".join(f"{e:.6g}" for e in e_target[:5]) + (", ..." if V.size > 5 else "")
        reached = ", ".join(f"{e:.6g}" for e in np.asarray(e_reached, dtype=float)[:5]) + (
            ", ..." if V.size > 5 else ""
        )
        raise CalibrationError(
            f"the calibration of {model!r} at {speeds} m/s missed its target: target e = {targets}, reached "
            f"e = {reached} with {found}"
        )


def _monotonic_note(model, params, V, pv):
    """The text of the :class:`CalibrationWarning` to give when the law's ``e(V)`` is not monotonic from
    ``min(V)/10`` to ``10 max(V)``, or None."""
    grid = np.geomspace(float(np.min(V)) / 10.0, float(np.max(V)) * 10.0, 41)
    e, _ = _run(model, grid, pv, params)
    ok = np.isfinite(e)
    g, e = grid[ok], e[ok]
    d = np.diff(e)
    tol = 1e-9
    if (d > tol).any() and (d < -tol).any():
        sign = np.sign(d[np.abs(d) > tol])
        first = sign[0]
        k = int(np.flatnonzero(np.sign(d) == -first)[0])  # the first step the other way: e turns at g[k]
        way = ("falls", "rises") if first < 0 else ("rises", "falls")
        return (
            f"the calibrated {model} law's e(V) is not monotonic: it {way[0]} from {e[0]:.4g} at {g[0]:.4g} m/s "
            f"to {e[k]:.4g} at {g[k]:.4g} m/s, then {way[1]} ({e[-1]:.4g} at {g[-1]:.4g} m/s); it was calibrated "
            f"at {', '.join(f'{v:.4g}' for v in np.atleast_1d(V)[:5])} m/s and does not follow the target "
            "away from there"
        )
    return None


@dataclass(frozen=True)
class Calibration:
    """Inputs of one DEM contact law matched to a target ``e(V)`` (see :func:`calibrate`).

    Attributes
    ----------
    model : str
        Name of the law (a model of :mod:`microimpact.core.models`).
    params : tuple of float
        Its parameters, in the order of the model's ``PARAMETERS`` (units there).
    names : tuple of str
        The parameters' names.
    velocity : ndarray
        Calibration speed(s) [m/s].
    target_restitution, restitution : ndarray
        Target ``e`` and the calibrated law's ``e`` at ``velocity`` [-].
    target_contact_time, contact_time : ndarray
        Target contact time and the law's [s].
    effective_modulus, effective_radius, effective_mass : float
        ``E*`` [Pa], ``R*`` [m], ``m*`` [kg] of the pair the law was calibrated for.
    """

    model: str
    params: tuple
    names: tuple
    velocity: np.ndarray
    target_restitution: np.ndarray
    restitution: np.ndarray
    target_contact_time: np.ndarray
    contact_time: np.ndarray
    effective_modulus: float
    effective_radius: float
    effective_mass: float

    def as_dict(self) -> dict:
        """``{parameter name: value}``."""
        return dict(zip(self.names, self.params))

    @classmethod
    def of(cls, pair, model: str, params: dict, velocity=50.0) -> Calibration:
        """A :class:`Calibration` of given parameters (no fit): to print or run a law chosen by hand.

        ``params`` maps the law's parameter names to values (missing ones take the model's
        defaults; a missing one without a default is a ValueError naming it); ``velocity`` [m/s]
        is where ``restitution`` and ``contact_time`` are evaluated (targets: the seed's there).
        """
        printable = _models.dem_line_models()
        if model not in printable:
            raise ValueError(f"model must be one of {', '.join(printable)}; got {model!r}")
        mod = _models.get(model)
        names = tuple(p[0] for p in mod.PARAMETERS)
        values = _models.resolve_params(mod, dict(params))
        pv = _pair_values(pair)
        V = _speeds(velocity)
        e_c, t_c = _run(model, V, pv, values)
        seed_e, seed_t = _run(_models.DEFAULT, V, pv, ())
        return cls(
            model=model,
            params=values,
            names=names,
            velocity=V,
            target_restitution=seed_e,
            restitution=e_c,
            target_contact_time=seed_t,
            contact_time=t_c,
            effective_modulus=pv[0],
            effective_radius=pv[1],
            effective_mass=pv[2],
        )

    # ------------------------------------------------------------------ LAMMPS
    def lammps(
        self, wall: str = "zplane 0.0 NULL", damping: str = "coeff_restitution", tsuji_sqrt2: bool = False
    ) -> str:
        """LAMMPS input lines (``units si``) for this law: ``pair_style granular`` + ``pair_coeff`` and
        the matching ``fix wall/gran granular`` for a flat wall (``wall``: its wallstyle arguments).

        Syntax of ``doc/src/pair_granular.rst`` (normal models ``hooke``/``hertz``, damping
        ``coeff_restitution``/``viscoelastic``, ``tangential linear_nohistory`` with zero damping and
        friction, ``limit_damping``) and ``doc/src/fix_wall_gran.rst``; the normal model's arguments
        and a comment line come from the model's face (``lammps``). A law LAMMPS has no normal model
        for (the hysteretic spring): ValueError.

        ``damping="tsuji"`` (Marshall's polynomial; for the laws whose face takes it, Hertz with
        Tsuji's damping): the ``e_n`` printed is then the one whose ``alpha_T`` is the law's for the
        LAMMPS version: ``tsuji_sqrt2=False`` (default) for LAMMPS 22 Jul 2025 and earlier, ``True``
        for the development source that multiplies the polynomial by ``2^(1/2)``
        (:func:`microimpact.core.models.hertz_tsuji.alpha_tsuji`).

        ``wall`` is held to DEM input words (ASCII letters, digits, ``_ . + -`` and spaces): a line
        break, ``#``, ``&``, ``$`` or a quote would be a new command, a comment, a continuation, a
        substitution or quoting to LAMMPS's parser (ValueError naming ``wall``).
        """
        check_dem_words("wall", wall)
        head = self._head()
        if damping not in ("coeff_restitution", "tsuji"):
            raise ValueError(f"damping must be 'coeff_restitution' or 'tsuji', got {damping!r}")
        if not isinstance(tsuji_sqrt2, bool):
            raise ValueError(f"tsuji_sqrt2 must be True or False, got {tsuji_sqrt2!r}")
        face = _models.face(self.model)
        if damping == "coeff_restitution":
            coeff, legacy = face.lammps(self)
        else:
            import inspect

            takes = [n for n in DEM_MODELS if "damping" in inspect.signature(_models.face(n).lammps).parameters]
            if self.model not in takes:
                raise ValueError(
                    f"damping='tsuji' is for model {' or '.join(map(repr, takes))} only, not {self.model!r}"
                )
            coeff, legacy = face.lammps(self, damping=damping, tsuji_sqrt2=tsuji_sqrt2)
        lines = [
            head,
            "units si",
            "comm_modify vel yes",
            "pair_style granular",
            f"pair_coeff * * {coeff}",
            f"fix wall all wall/gran granular {coeff} {wall}",
            legacy,
        ]
        return "\n".join(check_dem_lines(lines, f"the face of {self.model!r} (lammps)"))

    # ---------------------------------------------------------------- LIGGGHTS
    def liggghts(self, poisson: float = 0.3, wall: str = "zplane 0.0") -> str:
        """LIGGGHTS-PUBLIC input lines (``units si``, one atom type for particle and wall).

        The lines after ``units si`` come from the model's face (``liggghts``): ``gran model
        hooke/stiffness`` for the linear spring-dashpot, ``hertz`` for Tsuji's damping,
        ``hooke/hysteresis`` for Luding's spring (``plasticity_depth > 0``), each documented
        there. A law LIGGGHTS has no normal model for (Hertz with Brilliantov's damping, the
        constant-``k2`` spring): ValueError. ``wall`` (the ``primitive`` wall's arguments) is held to
        DEM input words as in :meth:`lammps`; ``poisson`` lies in (-1, 0.5].
        """
        check_dem_words("wall", wall)
        poisson = check_poisson("poisson", poisson, scalar=True)
        head = self._head()
        lines = _models.face(self.model).liggghts(self, poisson, wall)
        return "\n".join(check_dem_lines([head, "units si", *lines], f"the face of {self.model!r} (liggghts)"))

    def _head(self) -> str:
        """The comment line naming the law and its parameters, once the names are checked to be
        identifiers: a name is printed into the deck, where a line break or a trailing ``&`` in it
        would start or swallow a command."""
        for what, name in (("model", self.model), *(("names", n) for n in self.names)):
            if not (isinstance(name, str) and name.isascii() and name.isidentifier()):
                raise ValueError(
                    f"Calibration.{what} must be an identifier (it is printed into a DEM deck), got {name!r}"
                )
        return f"# {self.model}: {', '.join(f'{n} = {v:.12g}' for n, v in zip(self.names, self.params))}"


def calibrate(
    pair,
    model: str,
    velocity,
    *,
    target_restitution=None,
    target_contact_time=None,
    **options,
) -> Calibration:
    """Inputs of the law ``model`` that reproduce a target ``e`` at ``velocity``.

    Parameters
    ----------
    pair : ContactPair
        The particle and surface (its ``E*``, ``R*``, ``m*``, ``p_y``).
    model : str
        The law to calibrate: a DEM law of :data:`DEM_MODELS` (``"linear_spring_dashpot"``,
        ``"hertz_viscoelastic"``, ``"hertz_tsuji"``, ``"luding_hysteretic"``), whose face has an
        inverse of its own, or any other model (least squares of ``e`` over its parameters
        without a default).
    velocity : float or array_like
        Calibration speed [m/s], or several: then ``e`` is matched in the least-squares sense
        (the mean target ``e`` for the laws whose ``e`` does not depend on the speed).
    target_restitution, target_contact_time : callable or array_like, optional
        Target ``e`` [-] and contact time [s] at ``velocity``; default: the seed's model.
    **options
        The law's own calibration options (its face's ``calibrate``):

        * ``limit_force`` ``{0, 1}`` (linear and Hertz laws): force-sign convention (see their
          model files); default the model's default (0 for the linear law, 1 for the Hertz laws).
        * ``plasticity`` (``luding_hysteretic``): False (default) calibrates the constant-``k2``
          spring; True Luding's ``k2(alpha_max)`` (LIGGGHTS ``hooke/hysteresis``), whose free
          ``plasticity_depth`` is then set to match ``e``.
        * ``unloading_ratio`` (``luding_hysteretic``, ``plasticity=True`` only): ``k2/k1``,
          > ``1/e^2`` (default ``2/e^2``).

    Returns
    -------
    Calibration

    Raises
    ------
    ValueError
        Unknown model, bad speed or option (named), or a target the law cannot reach.
    CalibrationError
        (a ValueError) The search ended without reaching the target: at one speed ``e`` off by more
        than :data:`MISS_TOLERANCE`, at several a fit worse than a constant ``e``; the message names the
        target, the ``e`` reached and the parameters.

    Warns
    -----
    CalibrationWarning
        When the calibrated law's ``e(V)`` is not monotonic between a tenth of the lowest and ten
        times the highest calibration speed: Luding's law with ``plasticity=True`` (LIGGGHTS'
        ``hooke/hysteresis`` runs show the same, it is the law's), whose ``e`` rises again once the
        largest overlap passes the plasticity depth, while the seed's keeps falling.

    Examples
    --------
    >>> import microimpact as mi
    >>> pair = mi.ContactPair.paper_case("silicon")
    >>> cal = calibrate(pair, "linear_spring_dashpot", 50.0)
    >>> round(cal.params[1], 4), round(float(cal.restitution[0]), 4)
    (0.7248, 0.7248)
    """
    face = _models.face(model)
    unknown = sorted(set(options) - set(face.options))
    if unknown:
        raise ValueError(
            f"model {model!r} takes no calibration option {unknown[0]!r}; its options: {', '.join(face.options) or 'none'}"
        )
    pv = _pair_values(pair)
    E, R, m, p_y = pv
    V = _speeds(velocity)
    seed_e = seed_t = None
    if target_restitution is None or target_contact_time is None:
        seed_e, seed_t = _run(_models.DEFAULT, V, pv, ())
    e_t = _target(target_restitution, V, seed_e, "target_restitution")
    t_t = _target(target_contact_time, V, seed_t, "target_contact_time")
    bad = ~((e_t > 0.0) & (e_t <= 1.0))
    if bad.any():
        raise ValueError(f"target_restitution must lie in (0, 1], got {float(e_t[bad][0])!r}")
    bad = ~((t_t > 0.0) & np.isfinite(t_t))
    if bad.any():
        raise ValueError(f"target_contact_time must be positive and finite, got {float(t_t[bad][0])!r}")
    # kept on disk by its inputs and the sources computing it (microimpact._calibration_cache)
    name = _calibration_cache.key(face, pv, V, e_t, t_t, options)
    found = _calibration_cache.load(name, len(face.model.PARAMETERS), V.size)
    if found is None:
        params = face.calibrate(pv, V, e_t, t_t, **options)
        e_c, t_c = _run(model, V, pv, params)
        note = _monotonic_note(model, params, V, pv)
        _calibration_cache.store(name, params, e_c, t_c, note)
    else:
        params, e_c, t_c, note = found
    _check_reached(model, tuple(p[0] for p in face.model.PARAMETERS), params, V, np.asarray(e_t, dtype=float), e_c)
    if note is not None:
        warnings.warn(note, CalibrationWarning, stacklevel=2)
    return Calibration(
        model=model,
        params=tuple(float(p) for p in params),
        names=tuple(p[0] for p in face.model.PARAMETERS),
        velocity=V,
        target_restitution=np.asarray(e_t, dtype=float),
        restitution=e_c,
        target_contact_time=np.asarray(t_t, dtype=float),
        contact_time=t_c,
        effective_modulus=E,
        effective_radius=R,
        effective_mass=m,
    )


def calibrate_all(pair, velocity, **options) -> dict:
    """:func:`calibrate` for every law of :data:`DEM_MODELS`: ``{name: Calibration}``.

    Each of ``options`` goes to the laws whose calibration takes it (``limit_force`` to the
    linear and Hertz laws, ``plasticity`` and ``unloading_ratio`` to the hysteretic spring); an
    option no law takes is refused.
    """
    names = _models.dem_models()
    takes = {name: set(_models.face(name).options) for name in names}
    unknown = sorted(set(options) - set().union(*takes.values()))
    if unknown:
        raise ValueError(f"no DEM law takes the calibration option {unknown[0]!r}")
    return {
        name: calibrate(pair, name, velocity, **{k: v for k, v in options.items() if k in takes[name]})
        for name in names
    }


# ----------------------------------------------------------------------------- adhesive laws
@dataclass(frozen=True)
class AdhesiveCalibration(Calibration):
    """An adhesive law's inputs matched to a reference law (:func:`calibrate_adhesive`).

    Beyond :class:`~microimpact.calibrate.Calibration`'s attributes (``target_restitution`` is the
    reference law's ``e``):

    Attributes
    ----------
    reference : str
        The reference law.
    work_of_adhesion : float
        ``G`` [J/m^2] of the reference.
    capture_velocity, target_capture_velocity : float
        The calibrated law's and the reference's capture velocity [m/s].
    free : tuple of str
        The inputs that were searched.
    residual : float
        Root mean square of the residuals at the solution (``e`` differences and the weighted log
        ratio of the capture velocities) [-]: 0 where the law reproduces the reference.
    """

    reference: str = ""
    work_of_adhesion: float = math.nan
    capture_velocity: float = math.nan
    target_capture_velocity: float = math.nan
    free: tuple = ()
    residual: float = math.nan


def adhesion_inputs(model: str, work_of_adhesion, pair_values, given=None) -> tuple:
    """The parameter tuple of ``model`` for the work of adhesion ``G`` [J/m^2] and ``pair_values =
    (E*, R*, m*, p_y)``: :func:`microimpact.models.adhesion_inputs`, except that an input named in
    ``given`` keeps its given value (a calibration's start)."""
    given = dict(given or {})
    names = [p.name for p in _core.get(model).PARAMETERS]
    mapped = _models.adhesion_inputs(model, work_of_adhesion, pair_values, given)
    return tuple(float(given[n]) if n in given else v for n, v in zip(names, mapped))


def _check_free(mod, free):
    names = [p.name for p in mod.PARAMETERS]
    for n in free:
        if n not in names:
            raise ValueError(f"free names {n!r}, which is not a parameter of {mod.NAME!r}: {', '.join(names)}")
    if len(set(free)) != len(free):
        raise ValueError(f"free names a parameter more than once: {free!r}")
    return tuple(free)


def calibrate_adhesive(
    pair,
    model: str,
    work_of_adhesion,
    velocity,
    *,
    reference: str | None = None,
    params=None,
    free=None,
    capture_weight: float = 1.0,
    reference_params=None,
) -> AdhesiveCalibration:
    """Inputs of the adhesive law ``model`` that give the reference law's capture velocity and ``e(V)``.

    Parameters
    ----------
    pair : ContactPair
        The particle and the surface (``E*``, ``R*``, ``m*``, ``p_y``).
    model : str
        A law that captures particles (``STICKS``, with a ``sticking_velocity``): the law as a DEM
        code computes it.
    work_of_adhesion : float
        ``G`` [J/m^2] of the interface: sets the reference law's adhesion, and the start of the
        calibrated law's adhesion input.
    velocity : float or array_like
        Speeds [m/s] at which ``e`` is matched (above the capture velocity, where ``e`` carries
        information; ``e = 0`` below it is matched through the capture velocity).
    reference : str, optional
        The law to reproduce (default Thornton & Ning's whole law); its adhesion is set from ``G``.
    params : dict, optional
        Values of the law's other inputs (``{name: value}``), held fixed unless named in ``free``,
        where they are the search's start.
    free : sequence of str, optional
        The inputs to search (default: the adhesion input and the inputs without a default).
    capture_weight : float
        Weight ``w`` of the capture velocity's residual ``w log(V_s / V_s,ref)`` beside the ``e``
        residuals; positive.
    reference_params : dict, optional
        Values of the reference law's inputs other than its adhesion input (``{name: value}``), which
        a reference needs where one has no default (LIGGGHTS' ``coefficientRestitution`` of the sjkr
        law); the others take their defaults.

    Returns
    -------
    AdhesiveCalibration
        With the residual's root mean square, 0 when the law reproduces the reference; a law that
        cannot (an elastic law against a plastic reference) gets its best fit, the residual stating by
        how much it misses.

    Raises
    ------
    ValueError
        A law that does not capture particles, an unknown parameter, nothing to search, bad speeds,
        or a search that does not converge.
    """
    from scipy.optimize import least_squares

    from .models._base import bounded_value, unbounded_variable

    G = float(check_nonnegative("work_of_adhesion", work_of_adhesion))
    if isinstance(capture_weight, bool) or not (isinstance(capture_weight, (int, float)) and capture_weight > 0.0):
        raise ValueError(f"capture_weight must be a positive number, got {capture_weight!r}")
    if not math.isfinite(capture_weight):
        raise ValueError(f"capture_weight must be finite, got {capture_weight!r}")
    reference = _core.whole_law() if reference is None else reference
    mod, ref = _core.get(model), _core.get(reference)
    for what, m in (("model", mod), ("reference", ref)):
        if not (m.STICKS and m.sticking_velocity is not None):
            raise ValueError(f"{what} {m.NAME!r} does not capture particles (no sticking velocity)")
    pv = _pair_values(pair)
    V = _speeds(velocity)
    ref_params = _core.resolve_params(
        ref, dict(zip([q.name for q in ref.PARAMETERS], _models.adhesion_inputs(reference, G, pv, reference_params)))
    )
    e_ref, _ = _run(reference, V, pv, ref_params)
    vs_ref = float(ref.sticking_velocity(*pv, ref_params))
    if not (vs_ref > 0.0 and math.isfinite(vs_ref)):
        raise ValueError(f"the reference {reference!r} has no finite positive capture velocity here ({vs_ref!r} m/s)")
    start = adhesion_inputs(model, G, pv, params)
    names = [p.name for p in mod.PARAMETERS]
    if free is None:
        moved = adhesion_inputs(model, 2.0 * G + 1.0, pv, params)
        free = tuple(n for n, a, b in zip(names, start, moved) if a != b or math.isnan(a))
        free = tuple(n for n in free if n not in (params or {}))
    free = _check_free(mod, tuple(free))
    if not free:
        raise ValueError(f"model {model!r}: nothing to calibrate (name its inputs to search in free=)")
    spec = {p.name: p for p in mod.PARAMETERS}

    def params_of(u):
        values = {}
        for n, s in zip(names, start):
            values[n] = bounded_value(spec[n], float(u[free.index(n)]), values) if n in free else s
        return tuple(values.values())

    def residuals(u):
        p = params_of(u)
        try:
            checked = mod.validate(p)
        except ValueError:
            return np.full(V.size + 1, 10.0)
        e, _ = _run(model, V, pv, checked)
        vs = float(mod.sticking_velocity(*pv, checked))
        cap = capture_weight * math.log(vs / vs_ref) if vs > 0.0 and math.isfinite(vs) else 10.0
        return np.append(np.nan_to_num(e - e_ref, nan=10.0), cap)

    values0 = {}
    u0 = []
    for n, s in zip(names, start):
        values0[n] = s
        if n in free:
            u0.append(unbounded_variable(spec[n], s, values0))
    sol = least_squares(residuals, np.array(u0), xtol=1e-14, ftol=1e-14, gtol=1e-14)
    if not np.all(np.isfinite(sol.x)):
        raise ValueError(f"model {model!r} could not be calibrated to {reference!r}: {sol.message}")
    found = tuple(mod.validate(params_of(sol.x)))
    e_c, t_c = _run(model, V, pv, found)
    _, t_ref = _run(reference, V, pv, ref_params)
    return AdhesiveCalibration(
        model=model,
        params=tuple(float(x) for x in found),
        names=tuple(names),
        velocity=V,
        target_restitution=np.asarray(e_ref, dtype=float),
        restitution=np.asarray(e_c, dtype=float),
        target_contact_time=np.asarray(t_ref, dtype=float),
        contact_time=np.asarray(t_c, dtype=float),
        effective_modulus=pv[0],
        effective_radius=pv[1],
        effective_mass=pv[2],
        reference=reference,
        work_of_adhesion=G,
        capture_velocity=float(mod.sticking_velocity(*pv, found)),
        target_capture_velocity=vs_ref,
        free=free,
        residual=float(np.sqrt(np.mean(sol.fun**2))),
    )


def code_prediction(pair, model: str, velocity, **params) -> dict:
    """What a code's adhesive law gives with the inputs ``params`` (its parameters by name):
    ``{"capture_velocity": V_s [m/s], "velocity": V, "restitution": e(V), "contact_time": t_c(V)}``."""
    mod = _core.get(model)
    if not (mod.STICKS and mod.sticking_velocity is not None):
        raise ValueError(f"model {model!r} does not capture particles (no sticking velocity)")
    pv = _pair_values(pair)
    V = _speeds(velocity)
    p = _core.resolve_params(mod, params)
    e, t = _run(model, V, pv, p)
    return {
        "capture_velocity": float(mod.sticking_velocity(*pv, p)),
        "velocity": V,
        "restitution": e,
        "contact_time": t,
    }
