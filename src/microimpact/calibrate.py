"""Calibrate the DEM contact laws to the seed's model (or to any target ``e(V)``).

A DEM engineer whose code offers a linear spring-dashpot, Hertz with viscoelastic damping or a
linear hysteretic spring wants the inputs that make it bounce like the seed's elastic-plastic
model: :func:`calibrate` returns them for one law, :func:`calibrate_all` for the three, and
:meth:`Calibration.lammps` / :meth:`Calibration.liggghts` write them as input-script lines.

What is matched
---------------
* The restitution coefficient ``e`` at the calibration speed (to the last digits: the laws
  reproduce the target to 1e-10 and better), or, over several speeds, in the least-squares sense.
* The contact time where the law has a free stiffness (linear spring-dashpot: ``k``; hysteretic
  spring: ``k1``): the target's contact time at that speed (the mean over several speeds). Hertz's
  stiffness is fixed by ``E*`` and ``R*``, so the two Hertz laws match ``e`` only.

Targets default to the seed's model (``thornton_ning_2016``) for the pair; pass
``target_restitution`` (and ``target_contact_time``) as callables of the speed [m/s], or as
arrays of the calibration speeds' shape, to calibrate to measurements or another model.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from .core import hertz as _hertz
from .core import models as _models
from .core.models import luding_hysteretic as _luding
from .core.quantities import OUTCOME_FIELDS

__all__ = ["Calibration", "CalibrationWarning", "calibrate", "calibrate_all", "DEM_MODELS"]

#: The DEM laws :func:`calibrate` knows.
DEM_MODELS = ("linear_spring_dashpot", "hertz_viscoelastic", "hertz_tsuji", "luding_hysteretic")

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
    return v


def _target(values, V, default, name):
    if values is None:
        return default
    out = np.asarray(values(V) if callable(values) else values, dtype=float)
    out = np.broadcast_to(out, V.shape).astype(float)
    return out


def _run(model, V, pv, params):
    mod = _models.get(model)
    E, R, m, p_y = pv
    rows = [mod.outcome(float(v), E, R, m, p_y, tuple(float(p) for p in params)) for v in V]
    return np.array([r[_E] for r in rows]), np.array([r[_TC] for r in rows])


class CalibrationWarning(UserWarning):
    """The calibrated law matches the target at the calibration speeds but behaves unlike it elsewhere
    (its ``e(V)`` rises and falls between a tenth of the lowest and ten times the highest speed)."""


def _check_monotonic(model, params, V, pv):
    """Warn (:class:`CalibrationWarning`) when the law's ``e(V)`` is not monotonic from ``min(V)/10`` to ``10 max(V)``."""
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
        warnings.warn(
            f"the calibrated {model} law's e(V) is not monotonic: it {way[0]} from {e[0]:.4g} at {g[0]:.4g} m/s "
            f"to {e[k]:.4g} at {g[k]:.4g} m/s, then {way[1]} ({e[-1]:.4g} at {g[-1]:.4g} m/s); it was calibrated "
            f"at {', '.join(f'{v:.4g}' for v in np.atleast_1d(V)[:5])} m/s and does not follow the target "
            "away from there",
            CalibrationWarning,
            stacklevel=3,
        )


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
        if model not in DEM_MODELS:
            raise ValueError(f"model must be one of {', '.join(DEM_MODELS)}; got {model!r}")
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

        ``hertz_tsuji`` may also be written with ``damping="tsuji"`` (Marshall's polynomial): the
        ``e_n`` printed is then the one whose ``alpha_T`` is the law's for the LAMMPS version:
        ``tsuji_sqrt2=False`` (default) for LAMMPS 22 Jul 2025 and earlier, ``True`` for the
        development source that multiplies the polynomial by ``2^(1/2)``
        (:func:`microimpact.core.models.hertz_tsuji.alpha_tsuji`).

        Syntax of ``doc/src/pair_granular.rst`` (normal models ``hooke``/``hertz``, damping
        ``coeff_restitution``/``viscoelastic``, ``tangential linear_nohistory`` with zero damping and
        friction, ``limit_damping``) and ``doc/src/fix_wall_gran.rst``. The hysteretic spring has no
        LAMMPS normal model: ValueError. For ``linear_spring_dashpot`` the legacy
        ``pair_style gran/hooke`` line (``gamma_n = eta/m*``) is given as a comment.
        """
        if damping not in ("coeff_restitution", "tsuji"):
            raise ValueError(f"damping must be 'coeff_restitution' or 'tsuji', got {damping!r}")
        if damping == "tsuji" and self.model != "hertz_tsuji":
            raise ValueError(f"damping='tsuji' is for model 'hertz_tsuji' only, not {self.model!r}")
        if not isinstance(tsuji_sqrt2, bool):
            raise ValueError(f"tsuji_sqrt2 must be True or False, got {tsuji_sqrt2!r}")
        tang = "tangential linear_nohistory 0.0 0.0"
        p = self.as_dict()
        if self.model == "linear_spring_dashpot":
            from .core.models.linear_spring_dashpot import damping_coefficient

            k, e = p["stiffness"], p["restitution"]
            lim = " limit_damping" if p["limit_force"] == 1.0 else ""
            coeff = f"hooke {k:.12g} {e:.12g} {tang} damping coeff_restitution{lim}"
            gamma_n = damping_coefficient(k, e, self.effective_mass) / self.effective_mass
            legacy = f"# legacy equivalent: pair_style gran/hooke {k:.12g} NULL {gamma_n:.12g} 0.0 0.0 0{lim}"
        elif self.model == "hertz_viscoelastic":
            A = p["dissipative_constant"]
            k_n = 4.0 / 3.0 * self.effective_modulus
            eta0 = 4.0 * self.effective_modulus * A / (3.0 * self.effective_mass)
            lim = " limit_damping" if p["limit_force"] == 1.0 else ""
            coeff = f"hertz {k_n:.12g} {eta0:.12g} {tang} damping viscoelastic{lim}"
            legacy = f"# eta_n0 = 4 E* A / (3 m*) for m* = {self.effective_mass:.12g} kg (one particle size only)"
        elif self.model == "hertz_tsuji":
            from .core.models.hertz_tsuji import code_restitution

            k_n = 4.0 / 3.0 * self.effective_modulus
            lim = " limit_damping" if p["limit_force"] == 1.0 else ""
            if damping == "tsuji":
                e_n = _tsuji_input(p["damping_ratio"], tsuji_sqrt2)
                coeff = f"hertz {k_n:.12g} {e_n:.12g} {tang} damping tsuji{lim}"
                legacy = "# damping tsuji: eta_n = alpha_T (m* k_nd)^(1/2), alpha_T = Marshall's polynomial of e_n" + (
                    " times 2^(1/2) (LAMMPS development source after July 2026)"
                    if tsuji_sqrt2
                    else " (LAMMPS 22 Jul 2025 and earlier)"
                )
            else:
                coeff = f"hertz {k_n:.12g} {code_restitution(p['damping_ratio']):.12g} {tang} damping coeff_restitution{lim}"
                legacy = "# coeff_restitution with hertz: eta_n = alpha_T (m* k_nd)^(1/2), k_nd = 4/3 E* a"
        else:
            raise ValueError(f"LAMMPS has no normal contact model for {self.model!r}; use liggghts()")
        return "\n".join(
            [
                f"# {self.model}: {', '.join(f'{n} = {v:.12g}' for n, v in zip(self.names, self.params))}",
                "units si",
                "comm_modify vel yes",
                "pair_style granular",
                f"pair_coeff * * {coeff}",
                f"fix wall all wall/gran granular {coeff} {wall}",
                legacy,
            ]
        )

    # ---------------------------------------------------------------- LIGGGHTS
    def liggghts(self, poisson: float = 0.3, wall: str = "zplane 0.0") -> str:
        """LIGGGHTS-PUBLIC input lines (``units si``, one atom type for particle and wall).

        ``linear_spring_dashpot``: ``gran model hooke/stiffness`` with ``kn`` and ``gamman = eta/m*``
        (``src/normal_model_hooke_stiffness.h``; ``limitForce`` for the clipped convention).
        ``luding_hysteretic`` (``plasticity_depth > 0``): ``gran model hooke/hysteresis``, whose
        ``k1`` comes from ``youngsModulus``/``poissonsRatio`` and ``characteristicVelocity``
        (``kn = 16/15 R^(1/2) Y* (15 m v_c^2/(16 R^(1/2) Y*))^(1/5)``, ``src/normal_model_hooke.h``),
        here ``youngsModulus = 2 (1 - nu^2) E*`` so that ``Y* = E*``, and ``v_c`` solved for ``k1``;
        ``coefficientRestitution 1`` (no viscous damping) and ``coefficientAdhesionStiffness 0``.
        Hertz with Brilliantov's damping and the constant-``k2`` spring have no LIGGGHTS model:
        ValueError.
        """
        p = self.as_dict()
        if self.model == "linear_spring_dashpot":
            from .core.models.linear_spring_dashpot import damping_coefficient

            k, e = p["stiffness"], p["restitution"]
            lim = "on" if p["limit_force"] == 1.0 else "off"
            gamma_n = damping_coefficient(k, e, self.effective_mass) / self.effective_mass
            lines = [
                f"pair_style gran model hooke/stiffness tangential no_history limitForce {lim}",
                "pair_coeff * *",
                f"fix m1 all property/global kn peratomtypepair 1 {k:.12g}",
                f"fix m2 all property/global kt peratomtypepair 1 {2.0 / 7.0 * k:.12g}",
                f"fix m3 all property/global gamman peratomtypepair 1 {gamma_n:.12g}",
                "fix m4 all property/global gammat peratomtypepair 1 0.0",
                "fix m5 all property/global coefficientFriction peratomtypepair 1 0.0",
                f"fix wall all wall/gran model hooke/stiffness tangential no_history primitive type 1 {wall} limitForce {lim}",
            ]
        elif self.model == "hertz_tsuji":
            from .core.models.hertz_tsuji import code_restitution

            e_n = code_restitution(p["damping_ratio"])
            if not e_n > 0.05:
                raise ValueError(f"LIGGGHTS requires coefficientRestitution > 0.05; this law needs {e_n!r}")
            lim = "on" if p["limit_force"] == 1.0 else "off"
            Y = _hertz.equal_bodies_modulus(self.effective_modulus, poisson)
            lines = [
                f"pair_style gran model hertz tangential no_history limitForce {lim}",
                "pair_coeff * *",
                f"fix m1 all property/global youngsModulus peratomtype {Y:.12g}",
                f"fix m2 all property/global poissonsRatio peratomtype {poisson:.12g}",
                f"fix m3 all property/global coefficientRestitution peratomtypepair 1 {e_n:.12g}",
                "fix m4 all property/global coefficientFriction peratomtypepair 1 0.0",
                f"fix wall all wall/gran model hertz tangential no_history primitive type 1 {wall} limitForce {lim}",
            ]
        elif self.model == "luding_hysteretic" and p["plasticity_depth"] > 0.0:
            k1, k2, phi = p["loading_stiffness"], p["unloading_stiffness"], p["plasticity_depth"]
            E, R, m = self.effective_modulus, self.effective_radius, self.effective_mass
            vc = _luding.characteristic_velocity(k1, E, R, m)
            Y = _hertz.equal_bodies_modulus(E, poisson)
            lines = [
                "pair_style gran model hooke/hysteresis tangential no_history",
                "pair_coeff * *",
                f"fix m1 all property/global youngsModulus peratomtype {Y:.12g}",
                f"fix m2 all property/global poissonsRatio peratomtype {poisson:.12g}",
                "fix m3 all property/global coefficientRestitution peratomtypepair 1 1.0",
                "fix m4 all property/global coefficientFriction peratomtypepair 1 0.0",
                f"fix m5 all property/global characteristicVelocity scalar {vc:.12g}",
                f"fix m6 all property/global coefficientMaxElasticStiffness peratomtypepair 1 {k2 / k1:.12g}",
                "fix m7 all property/global coefficientAdhesionStiffness peratomtypepair 1 0.0",
                f"fix m8 all property/global coefficientPlasticityDepth peratomtypepair 1 {phi:.12g}",
                f"fix wall all wall/gran model hooke/hysteresis tangential no_history primitive type 1 {wall}",
            ]
        else:
            raise ValueError(
                f"LIGGGHTS has no normal model for {self.model!r} with these parameters"
                + (" (use plasticity_depth > 0: hooke/hysteresis)" if self.model == "luding_hysteretic" else "")
            )
        head = f"# {self.model}: {', '.join(f'{n} = {v:.12g}' for n, v in zip(self.names, self.params))}"
        return "\n".join([head, "units si"] + lines)


def calibrate(
    pair,
    model: str,
    velocity,
    *,
    target_restitution=None,
    target_contact_time=None,
    limit_force: int | None = None,
    plasticity: bool = False,
    unloading_ratio: float | None = None,
) -> Calibration:
    """Inputs of the DEM law ``model`` that reproduce a target ``e`` at ``velocity``.

    Parameters
    ----------
    pair : ContactPair
        The particle and surface (its ``E*``, ``R*``, ``m*``, ``p_y``).
    model : {"linear_spring_dashpot", "hertz_viscoelastic", "hertz_tsuji", "luding_hysteretic"}
        The law to calibrate.
    velocity : float or array_like
        Calibration speed [m/s], or several: then ``e`` is matched in the least-squares sense
        (the mean target ``e`` for the laws whose ``e`` does not depend on the speed).
    target_restitution, target_contact_time : callable or array_like, optional
        Target ``e`` [-] and contact time [s] at ``velocity``; default: the seed's model.
    limit_force : {0, 1}, optional
        Force-sign convention of the linear and Hertz laws (see their model files); default: the
        model's default (0 for the linear law, 1 for the Hertz laws).
    plasticity : bool
        ``luding_hysteretic`` only: False (default) calibrates the constant-``k2`` spring; True
        Luding's ``k2(alpha_max)`` (LIGGGHTS ``hooke/hysteresis``), whose free ``plasticity_depth``
        is then set to match ``e``.
    unloading_ratio : float, optional
        ``plasticity=True`` only: ``k2/k1``, > ``1/e^2`` (default ``2/e^2``).

    Returns
    -------
    Calibration

    Raises
    ------
    ValueError
        Unknown model, bad speed or option (named), or a target the law cannot reach.

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
    if model not in DEM_MODELS:
        raise ValueError(f"model must be one of {', '.join(DEM_MODELS)}; got {model!r}")
    if limit_force is None:
        limit_force = 1 if model in ("hertz_viscoelastic", "hertz_tsuji") else 0
    if isinstance(limit_force, bool) or limit_force not in (0, 1):
        raise ValueError(f"limit_force must be 0 or 1, got {limit_force!r}")
    if not isinstance(plasticity, bool):
        raise ValueError(f"plasticity must be True or False, got {plasticity!r}")
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
    e_mean = float(np.mean(e_t))
    t_mean = float(np.mean(t_t))

    if model == "linear_spring_dashpot":
        params = _linear(e_mean, t_mean, float(limit_force), pv)
    elif model == "luding_hysteretic":
        if plasticity:
            params = _luding_plastic(V, e_t, t_t, unloading_ratio, pv)
        else:
            if unloading_ratio is not None:
                raise ValueError(f"unloading_ratio applies to plasticity=True only, got {unloading_ratio!r}")
            k1 = _luding.loading_stiffness_for(e_mean, t_mean, m)
            params = (k1, k1 / (e_mean * e_mean), 0.0)
    elif model == "hertz_tsuji":
        params = _tsuji(e_mean, float(limit_force), pv)
    else:
        params = _viscoelastic(V, e_t, float(limit_force), pv)
    e_c, t_c = _run(model, V, pv, params)
    _check_monotonic(model, params, V, pv)
    mod = _models.get(model)
    return Calibration(
        model=model,
        params=tuple(float(p) for p in params),
        names=tuple(p[0] for p in mod.PARAMETERS),
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

    ``options`` are passed on (``plasticity`` and ``unloading_ratio`` to the hysteretic spring only).
    """
    lud = {k: options.pop(k) for k in ("plasticity", "unloading_ratio") if k in options}
    return {
        name: calibrate(pair, name, velocity, **options, **(lud if name == "luding_hysteretic" else {}))
        for name in DEM_MODELS
    }


# ----------------------------------------------------------------------------- per law


def _tsuji_input(alpha, sqrt2):
    """The ``e_n`` LAMMPS' ``damping tsuji`` turns into ``alpha`` (Marshall's polynomial decreases on [0, 1])."""
    from .core.models.hertz_tsuji import alpha_tsuji

    lo, hi = alpha_tsuji(1.0, sqrt2), alpha_tsuji(0.0, sqrt2)
    if not lo <= alpha <= hi:
        raise ValueError(
            f"damping tsuji cannot give damping_ratio {alpha!r}: its e_n in [0, 1] covers {lo:.6g} to {hi:.6g}; "
            "use damping='coeff_restitution'"
        )
    return brentq(lambda x: alpha_tsuji(x, sqrt2) - alpha, 0.0, 1.0, xtol=1e-15, rtol=1e-15, maxiter=500)


def _tsuji(e_t, limit, pv):
    from .core.models import hertz_tsuji as ht

    E, R, m, p_y = pv

    def f(a):
        return ht.outcome(1.0, E, R, m, p_y, (a, limit))[_E] - e_t

    if e_t == 1.0:
        return (0.0, limit)
    hi = math.sqrt(5.0) * (1.0 - 1e-9)  # critical damping of coeff_restitution's formula
    if f(hi) > 0.0:
        e_min = f(hi) + e_t
        raise ValueError(f"target_restitution {e_t!r} is below what this law can give ({e_min:.6g})")
    return (brentq(f, 0.0, hi, xtol=1e-16, rtol=1e-15, maxiter=500), limit)


def _linear(e_t, t_t, limit, pv):
    from .core.models import linear_spring_dashpot as lin

    E, R, m, p_y = pv
    if limit == 1.0:
        # e(e_n) with the force clipped: increasing in e_n, from its value at e_n -> 0 to 1
        def f(en):
            return lin.outcome(1.0, E, R, m, p_y, (1.0, en, 1.0))[_E] - e_t

        lo = 1e-300
        if f(lo) > 0.0:
            e_min = f(lo) + e_t
            raise ValueError(
                f"target_restitution {e_t!r} is below what the clipped linear law can give ({e_min:.6g}); use limit_force=0"
            )
        e_n = 1.0 if e_t == 1.0 else brentq(f, lo, 1.0, xtol=1e-300, rtol=1e-15, maxiter=500)
    else:
        e_n = e_t
    # the contact time scales as k^(-1/2) at fixed e_n
    t1 = lin.outcome(1.0, E, R, m, p_y, (1.0, e_n, limit))[_TC]
    k = (t1 / t_t) ** 2
    return (k, e_n, limit)


def _luding_plastic(V, e_t, t_t, ratio, pv):
    E, R, m, p_y = pv
    e0 = float(e_t[0]) if V.size == 1 else float(np.mean(e_t))
    t0 = float(np.mean(t_t))
    if ratio is None:
        ratio = 2.0 / (e0 * e0)
    if isinstance(ratio, bool) or not (ratio > 1.0 / (e0 * e0) and math.isfinite(ratio)):
        raise ValueError(f"unloading_ratio must be finite and > 1/e^2 = {1.0 / (e0 * e0):.6g}, got {ratio!r}")
    k1 = _luding.loading_stiffness_for(e0, t0, m)
    k2 = ratio * k1
    if V.size == 1:
        return (k1, k2, _luding.plasticity_depth_for(float(V[0]), e0, k1, k2, m, R))

    def cost(logphi):
        e, _ = _run("luding_hysteretic", V, pv, (k1, k2, math.exp(logphi)))
        return float(np.sum((e - e_t) ** 2))

    a1 = float(np.max(V)) * math.sqrt(m / k1)
    guess = math.log(a1 / (2.0 * R))  # phi_f of order alpha_max/(2 R*)
    r = minimize_scalar(cost, bounds=(guess - 20.0, guess + 20.0), method="bounded", options={"xatol": 1e-10})
    return (k1, k2, math.exp(r.x))


def _viscoelastic(V, e_t, limit, pv):
    from .core.models import hertz_viscoelastic as hv

    E, R, m, p_y = pv

    if V.size == 1:
        e0 = float(e_t[0])
        if e0 == 1.0:
            return (0.0, limit)

        def f(kappa):
            return hv.scaled_impact(kappa, limit == 1.0)[0] - e0

        hi = 1.0
        while f(hi) > 0.0:
            hi *= 2.0
            if hi > 1e6:
                raise ValueError(f"target_restitution {e0!r} cannot be reached by the viscoelastic law")
        kappa = brentq(f, 0.0, hi, xtol=1e-16, rtol=1e-15, maxiter=500)
        return (kappa * _hertz.dem_time_scale(float(V[0]), E, R, m), limit)

    def cost(logA):
        e, _ = _run("hertz_viscoelastic", V, pv, (math.exp(logA), limit))
        return float(np.sum((e - e_t) ** 2))

    # start from the single-speed value at the middle speed
    mid = float(np.median(V))
    A0 = _viscoelastic(np.array([mid]), np.array([float(np.interp(mid, V, e_t))]), limit, pv)[0]
    g = math.log(A0) if A0 > 0.0 else 0.0
    r = minimize_scalar(cost, bounds=(g - 5.0, g + 5.0), method="bounded", options={"xatol": 1e-10})
    return (math.exp(r.x), limit)
