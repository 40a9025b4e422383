"""Stick or bounce: capture velocities against particle size, and stick/bounce maps.

A particle sticks when its restitution coefficient is 0. Two adhesive laws of Thornton & Ning
(1998) are compared:

``"additive"``
    Their additive rule (eq. 78): the seed's plastic loss and the elastic adhesive loss add as
    energies, ``e^2 = e_p^2 - (V_s/V)^2`` (:func:`microimpact.core.adhesion.restitution`), with the
    undeformed sphere's sticking velocity ``V_s`` (eq. 54) and the seed's yield velocity.
``"thornton_ning_1998_adhesive_plastic"``
    Their whole law (:mod:`~microimpact.core.models.thornton_ning_1998_adhesive_plastic`): yield at
    the adhesion-reduced limiting pressure and unloading on the flattened radius ``R_p`` with its
    enhanced pull-off force.

Every other law that can capture a particle (a model declaring ``STICKS`` and its
``sticking_velocity``; :func:`adhesion_laws` lists them: JKR, DMT, the DEM codes' adhesive laws) is
mapped the same way: its adhesion input is set from the work of adhesion by its face
(``params_for_work_of_adhesion``, :mod:`microimpact.models._base`), its other parameters taken from
``params`` or their defaults. A parameter without a default must be given in ``params`` (ValueError
naming it otherwise): LIGGGHTS' ``coefficientRestitution`` of the sjkr law, whose damping alone
captures. A law whose adhesion no work of adhesion sets (a liquid bridge: its liquid, surface tension
and contact angle; its face's hook returns None) takes all of it from ``params``, and the work of
adhesion does not act on its map.

The pair's ``E*``, ``p_y`` and density are kept and its particle resized (a sphere on a flat).
"""

from __future__ import annotations

import math

import numpy as np

from ._face import restitution_arrays
from ._validation import TINY_NORMAL, check_nonnegative, check_pair_scales, check_positive
from .adhesion import ADDITIVE_RULE
from .core import adhesion as _adh
from .core import models as _models
from .core.models import thornton_ning_2016 as _seed
from .engine import evaluate

__all__ = ["ADHESION_LAWS", "FULL_LAW", "adhesion_laws", "capture_velocities", "parting_diameter", "stick_map"]

#: The full law's model name (:mod:`~microimpact.core.models.thornton_ning_1998_adhesive_plastic`):
#: the model that declares ``WALL_ADHESION`` (:func:`microimpact.core.models.whole_law`), whose
#: ``sticking_velocity``, ``yield_velocity_of`` and ``restitution_only`` this module calls.
FULL_LAW = _models.whole_law()
#: The adhesive laws compared, in plotting order.
ADHESION_LAWS = (ADDITIVE_RULE, FULL_LAW)


#: Sizes whose radii and masses are made Python floats at once in :func:`capture_velocities`.
_BLOCK = 1 << 14


def adhesion_laws() -> tuple:
    """Every law a stick/bounce map can take: the additive rule, then each model that captures a
    particle (``STICKS`` with a ``sticking_velocity``), in :func:`microimpact.models.available` order."""
    found = [n for n in _models.available() if _models.get(n).STICKS and _models.get(n).sticking_velocity is not None]
    return (ADDITIVE_RULE, *found)


def _law(name):
    known = adhesion_laws()
    if name not in known:
        raise ValueError(f"law must be one of {', '.join(known)}; got {name!r}")
    return name


def _law_params(law, G, pair_values, given):
    """The checked parameter tuple of model ``law`` for the work of adhesion ``G`` at ``pair_values``
    (:func:`microimpact.models.adhesion_inputs`: the work of adhesion sets its adhesion input)."""
    from .models import adhesion_inputs

    model = _models.get(law)
    values = adhesion_inputs(law, G, pair_values, given)
    names = [p.name for p in model.PARAMETERS]
    missing = [n for n, v in zip(names, values) if math.isnan(v)]
    if missing:
        from .models import face

        sets = face(law).params_for_work_of_adhesion(G, tuple(pair_values), tuple(model.DEFAULTS))
        why = (
            "the work of adhesion sets none of its inputs (its adhesion is its own parameters')"
            if sets is None
            else "the work of adhesion sets only its adhesion input"
        )
        raise ValueError(
            f"law {law!r} needs {', '.join(repr(n) for n in missing)} (no default) in params "
            f"({{{law!r}: {{{missing[0]!r}: value}}}}; --param {law}:{missing[0]}=VALUE): {why}"
        )
    return _models.resolve_params(model, dict(zip(names, values)))


def _check_pair(pair):
    if pair.density is None:
        raise ValueError("a stick/bounce map needs a pair with a particle density (a sphere on a flat)")


def _sizes(pair, diameter):
    """``(R, m)`` arrays of the pair resized to each diameter [m]; a mass beyond the doubles is ``inf``
    or 0, which :func:`_check_sizes` names."""
    R = 0.5 * np.asarray(diameter, dtype=float)
    with np.errstate(over="ignore", under="ignore"):
        return R, 4.0 / 3.0 * math.pi * R**3 * pair.density


def _check_sizes(pair, name, d):
    """ValueError naming ``name`` and the diameter where the particle of diameter ``d`` (1-D, positive
    and finite) cannot be modelled in double precision: its mass ``4/3 pi R^3 rho`` not a normal
    double, or its yield velocity out of range (:func:`~microimpact._validation.check_pair_scales`)."""
    E, p_y = pair.effective_modulus, pair.limiting_pressure
    R, m = _sizes(pair, d)
    for dd, r, mm in zip(d, R, m):  # 4/3 pi R^3 rho and the yield velocity must be numbers double precision holds
        if not (TINY_NORMAL <= mm < math.inf):
            raise ValueError(
                f"{name} {float(dd)!r} m is outside what double precision can model: the particle mass "
                f"4/3 pi R^3 rho is {float(mm)!r} kg"
            )
        try:
            check_pair_scales(E, float(r), float(mm), p_y)
        except ValueError as exc:
            raise ValueError(f"{name} {float(dd)!r} m: {exc}") from None
    return R, m


def _one(law, E, R, m, p_y, G, given=None):
    """``(capture velocity, yield velocity)`` [m/s] of one size."""
    if law == ADDITIVE_RULE:
        Vy = _seed.yield_point(E, R, m, p_y)[2]
        return _adh.capture_velocity(Vy, _adh.sticking_velocity(G, E, R, m)), Vy
    model = _models.get(law)
    p = _law_params(law, G, (E, R, m, p_y), given or {})
    Vy = model.yield_velocity_of(E, R, m, p_y, p) if model.yield_velocity_of is not None else math.nan
    return model.sticking_velocity(E, R, m, p_y, p), Vy


def capture_velocities(pair, diameter, work_of_adhesion, laws=ADHESION_LAWS, params=None) -> dict:
    """Capture (sticking) velocity and yield velocity of each law over particle diameters.

    Parameters
    ----------
    pair : ContactPair
        A sphere-on-flat pair (its ``E*``, ``p_y`` and density are kept).
    diameter : array_like
        Particle diameters [m], positive and finite.
    work_of_adhesion : float
        ``G`` [J/m^2], >= 0.
    laws : sequence of str
        Names from :func:`adhesion_laws` (default :data:`ADHESION_LAWS`).
    params : dict, optional
        ``{law: {parameter: value}}``: a law's parameters other than its adhesion input (which the work
        of adhesion sets), or all of them for a law without one (a liquid bridge, on which the work of
        adhesion does not act); required for a parameter without a default.

    Returns
    -------
    dict
        ``diameter`` [m] (1-D), and for each law ``{law: {"capture_velocity": ..., "yield_velocity": ...}}``
        [m/s]: the particle sticks at and below the capture velocity; the yield velocity of the full
        law is reduced by adhesion (0 where the contact yields at any speed).
    """
    _check_pair(pair)
    d = np.atleast_1d(check_positive("diameter", diameter)).ravel()
    G = float(check_nonnegative("work_of_adhesion", work_of_adhesion))
    laws = [_law(n) for n in laws]
    E, p_y = pair.effective_modulus, pair.limiting_pressure
    R, m = _check_sizes(pair, "diameter", d)
    out = {"diameter": d}
    for law in laws:
        given = _given(params, law)
        # one size at a time through the scalar law, each result put straight into its array: 16 bytes
        # a size, where a list of result pairs held about 120 (a tuple and two Python floats)
        capture, yielding = np.empty(d.size), np.empty(d.size)
        for start in range(0, d.size, _BLOCK):
            block = zip(R[start : start + _BLOCK].tolist(), m[start : start + _BLOCK].tolist())
            for i, (r, mm) in enumerate(block, start):
                capture[i], yielding[i] = _one(law, E, r, mm, p_y, G, given)
        out[law] = {"capture_velocity": capture, "yield_velocity": yielding}
    return out


def parting_diameter(pair, work_of_adhesion, ratio=1.1, *, lo=1e-9, hi=1e-3) -> float:
    """The largest diameter [m] below which the whole law's capture velocity exceeds the additive
    rule's by more than ``ratio`` (bisection in ``log d`` to 1e-6); NaN if they never part so in
    ``[lo, hi]``, ``hi`` if they part over all of it.

    Where the sticking velocity is below the yield velocity the two laws capture at the same speed
    (to the rounding of TN98's 14.18); they part once the contact yields before it can stick.

    ``lo`` and ``hi`` [m] must be positive and finite, ``lo < hi``, and both sizes whose mass and yield
    velocity double precision holds (ValueError naming them otherwise).
    """
    _check_pair(pair)
    G = float(check_nonnegative("work_of_adhesion", work_of_adhesion))
    E, p_y = pair.effective_modulus, pair.limiting_pressure
    lo = check_positive("lo", lo, scalar=True)
    hi = check_positive("hi", hi, scalar=True)
    if not lo < hi:
        raise ValueError(f"lo must be below hi, got lo {lo!r} m and hi {hi!r} m")
    # every diameter the bisection tries lies in [lo, hi]: both ends must be sizes double precision can model
    _check_sizes(pair, "lo", np.array([lo]))
    _check_sizes(pair, "hi", np.array([hi]))

    def parted(d):
        R, m = _sizes(pair, d)
        a = _one(ADDITIVE_RULE, E, float(R), float(m), p_y, G)[0]
        f = _one(FULL_LAW, E, float(R), float(m), p_y, G)[0]
        return f > ratio * a

    if not parted(lo):
        return math.nan
    if parted(hi):
        return hi
    a, b = math.log(lo), math.log(hi)
    while b - a > 1e-6:
        mid = 0.5 * (a + b)
        a, b = (mid, b) if parted(math.exp(mid)) else (a, mid)
    return math.exp(a)


def _given(params, law) -> dict:
    """The parameters given for ``law`` in ``params`` (``{law: {name: value}}``), checked."""
    if params is None:
        return {}
    if not isinstance(params, dict):
        raise ValueError(f"params must be a dict of law -> {{parameter: value}}, got {params!r}")
    for name in params:
        if name not in adhesion_laws():
            raise ValueError(f"params names {name!r}, which is not one of the laws: {', '.join(adhesion_laws())}")
    if law == ADDITIVE_RULE and params.get(law):
        raise ValueError("the additive rule takes no parameters beyond the work of adhesion")
    return dict(params.get(law) or {})


def stick_map(pair, work_of_adhesion, diameter, velocity, laws=ADHESION_LAWS, params=None) -> dict:
    """Restitution over a grid of particle diameters and impact speeds, for each law.

    Parameters
    ----------
    pair : ContactPair
        A sphere-on-flat pair.
    work_of_adhesion : float
        ``G`` [J/m^2], >= 0.
    diameter, velocity : array_like
        1-D grids [m] and [m/s], positive and finite.
    laws : sequence of str
        Names from :func:`adhesion_laws` (default :data:`ADHESION_LAWS`).
    params : dict, optional
        ``{law: {parameter: value}}``, as for :func:`capture_velocities`.

    Returns
    -------
    dict
        ``diameter`` [m], ``velocity`` [m/s] and for each law ``{"restitution": (n_velocity,
        n_diameter) array, "capture_velocity", "yield_velocity"}`` (the last two over ``diameter``).
    """
    _check_pair(pair)
    d = np.atleast_1d(check_positive("diameter", diameter)).ravel()
    V = np.atleast_1d(check_positive("velocity", velocity)).ravel()
    G = float(check_nonnegative("work_of_adhesion", work_of_adhesion))
    laws = [_law(n) for n in laws]
    caps = capture_velocities(pair, d, G, laws, params)
    R, m = _sizes(pair, d)
    RR, VV = np.meshgrid(R, V)
    MM = np.meshgrid(m, V)[0]
    E = np.full_like(VV, pair.effective_modulus)
    P = np.full_like(VV, pair.limiting_pressure)
    out = {"diameter": d, "velocity": V}
    for law in laws:
        if law == ADDITIVE_RULE:
            Vy = evaluate(_seed.yield_point, E, RR, MM, P, nout=3)[2]
            Vs = evaluate(_adh.sticking_velocity, np.full_like(VV, G), E, RR, MM)[0]
            e = evaluate(_adh.restitution, VV, Vy, Vs, nout=2)[0]
        else:
            model, given = _models.get(law), _given(params, law)
            each = [
                _law_params(law, G, (pair.effective_modulus, float(r), float(mm), pair.limiting_pressure), given)
                for r, mm in zip(R, m)
            ]
            if all(p == each[0] for p in each):  # one parameter set: the grid at once
                e = restitution_arrays(model, VV, E, RR, MM, P, each[0])
            else:  # an input that depends on the size (a code's cohesion energy density): column by column
                e = np.empty(VV.shape)
                for j, p in enumerate(each):
                    e[:, j] = restitution_arrays(model, VV[:, j], E[:, j], RR[:, j], MM[:, j], P[:, j], p)
        out[law] = {"restitution": np.asarray(e, dtype=float).reshape(VV.shape), **caps[law]}
    return out
