"""Oblique impacts with adhesion: does the particle bounce, stick, roll or slide on the wall?

The normal contact is any law of the model zoo (:mod:`microimpact.core.models`) through its contract
alone: ``signed_force`` (negative: attractive), ``separation_approach`` /
``separation_approach_after`` / ``ends_at_zero_force`` (where the contact breaks), ``outcome``
(restitution and capture, exact), and, where a model declares it, ``tangential_contact_radius``
(below). No model is named here: a new adhesive law plugs in by its declaration.

**Normal and tangential together.** The sphere's approach ``alpha``, its tangential velocity ``v``,
its rim speed ``w = R omega`` and the tangential force ``T`` are integrated together in time
(velocity Verlet for the centre, as the DEM codes do; ``steps`` steps per Hertz contact time at the
normal speed, or per twice the law's own loading time where that is shorter):
``m alpha'' = -P(alpha, alpha', alpha_max)``, ``m v' = T``, ``m w' = 5/2 T rho/R``
(solid sphere, arm ``rho``). The tangential law is one of :data:`microimpact.core.tangential_laws.LAWS`
(their continuous-time form, that module's docstring): the stored force follows the contact radius
as ``a^c`` (``c`` of the law, loading / unloading), is loaded by ``-k_t u dt`` with ``k_t = f 8 G* a``
(``u = v + rho omega`` the contact point's slip), and is held at the Coulomb limit ``mu F_crit``.
On a sphere and a flat nothing tangential acts back on the normal motion, so the normal restitution
and the capture decision are the normal law's own (:meth:`ContactPair.impact`, bit for bit); the
integration gives the tangential outcome, and its own normal rebound checks the law's.

**Contact radius.** A Mindlin stiffness needs ``a``. A model whose contact radius is not Hertz's
``(R alpha)^(1/2)`` declares ``tangential_contact_radius(alpha, alpha_max, E, R, m, p_y, params)``
(JKR: the JKR radius, positive at negative approach down to pull-off, as LAMMPS'
``GranSubModNormalJKR::calculate_contact_radius`` gives it to ``mindlin``). Without it, Hertz's
radius of the approach (0 at ``alpha <= 0``: no tangential stiffness in tension).

**Coulomb limit with adhesion** (``coulomb=``):

* ``"adhesive"``: ``mu |F_n + 2 F_c|``, with ``F_c`` the pull-off force. Thornton (1991) and
  Thornton & Yin (1991) give ``mu (P + 2 P_c)`` for a JKR contact (as cited by the two codes below;
  the papers themselves were not read here, so their peeling stage before sliding is not modelled);
  LAMMPS writes it for both cohesive normal models (``lammps/lammps:src/GRANULAR/gran_sub_mod_normal.cpp``,
  ``GranSubModNormalDMT::set_fncrit`` and ``GranSubModNormalJKR::set_fncrit``:
  ``Fncrit = fabs(Fne + 2.0 * F_pulloff)``, ``F_pulloff`` ``3 pi gamma R`` for ``jkr`` and ``4 pi gamma
  R`` for ``dmt``; ``gran_sub_mod_tangential.cpp``: ``Fscrit = mu * Fncrit`` in every tangential
  model), and Lethe's documentation of its JKR and DMT models states the same ``mu |F_n + 2 F_po|``
  (``chaos-polymtl/lethe:doc/source/theory/multiphase/cfd_dem/dem.rst``, "Cohesive force models";
  the header ``include/dem/particle_wall_jkr_force.h@f36b16dd`` declares the force only). Here
  ``F_c`` is the law's own largest pull along its unloading branch from the impact's maximum
  approach, ``-min signed_force`` (JKR: ``3 pi gamma R*``, DMT: ``4 pi gamma R*``, as LAMMPS;
  Thornton & Ning's plastic law: the enhanced pull-off of its flattened contact). The default of
  every LAMMPS law, ``"mindlin"``, Di Renzo & Di Maio.
* ``"load"``: ``mu |F_n|``, the total normal force, attraction included: LIGGGHTS-PUBLIC's
  ``tangential_model_history.h`` (``Ft_friction = xmu * fabs(sidata.Fn)``, ``3d5c00f2``) with a
  cohesion model that adds its force to ``Fn`` (``cohesion_model_sjkr.h``: ``if(tangentialReduce_)
  sidata.Fn += Fn_coh``): the default of ``"liggghts_history"``. (The law's force cannot be split
  into a repulsive and a cohesive part through the contract: the whole force is used.)

**Outcome** (:data:`OUTCOMES`): ``"bounce"``; a captured particle (the normal law's ``e = 0``) is
followed to the first turning point of its normal motion in tension (the moment the particle, having
failed to leave, is pulled back: captured) and classified there: ``"captured sliding"`` where the
contact slides, ``"captured rolling"`` where it sticks and the centre still moves along the wall,
``"stick"`` where it sticks and the centre's tangential speed is below ``rest_tolerance`` of the
impact speed. The velocities a captured particle keeps are those at that moment. What follows
without rolling resistance (none of these laws has any): ``R omega - 5/2 v`` is conserved by any
tangential force on a solid sphere, so a sliding particle ends rolling at ``v = (5 v - 2 R omega)/7``
(the field ``rolling_velocity``), stopped only by the adhesive friction ``mu F_c > 0``; a particle that
hits without spin never comes to rest on a flat (``(5 v_t)/7`` stays), which is why ``"stick"`` is
the rare outcome (head-on, or with back spin ``R omega = 5/2 v``).
"""

from __future__ import annotations

import contextlib
import functools
import math
from dataclasses import dataclass, fields

import numpy as np

from .. import _atomic
from ..core import hertz
from ..core import tangential_laws as tl
from ..core.tangential_stages import SLIP_FACTOR

__all__ = [
    "OUTCOMES",
    "AdhesiveObliqueImpact",
    "adhesive_oblique_impact",
    "adhesive_rule",
    "check_adhesive_tangential",
    "COULOMB_LIMITS",
    "ADHESIVE_LAWS",
]

#: Outcome names.
OUTCOMES = ("bounce", "stick", "captured rolling", "captured sliding")
#: Coulomb limits with adhesion (module docstring).
COULOMB_LIMITS = ("adhesive", "load")
#: Tangential laws the adhesive integration runs: :data:`~microimpact.core.tangential_laws.LAWS` but the
#: Mindlin-Deresiewicz law (its memory of turning points is integrated along the seed's history only),
#: plus ``"mindlin"`` (``lammps_mindlin_rescale_force``) and ``"rigid"``.
ADHESIVE_LAWS = ("mindlin", "rigid", *(law for law in tl.LAWS if law != "mindlin_deresiewicz"))
#: Fixed steps per Hertz contact time at the normal speed: ``v_t'`` and ``R omega'`` within 1e-4 of the
#: impact speed of the converged values, the integrated ``e_n`` within 3e-4 (the force's jump at the
#: contact's end converges at first order; the reported ``e_n`` is the law's own): tests.
DEFAULT_STEPS = 4000
#: A captured particle is followed at most this many contact times.
MAX_CONTACT_TIMES = 40.0


@dataclass(frozen=True, eq=False)
class AdhesiveObliqueImpact:
    """Outcome of :func:`adhesive_oblique_impact` (arrays over the impacts; SI units).

    Attributes
    ----------
    angle, normal_speed, tangential_speed : ndarray
        Impact angle from the normal [deg], ``V_n`` and ``v_t`` before [m/s].
    normal_restitution : ndarray
        ``e`` of the normal law (its outcome, exact) [-]; 0 where captured.
    integrated_normal_restitution : ndarray
        The same from this integration (its step error; 0 where captured).
    tangential_restitution : ndarray
        ``v_t'/v_t`` [-] (NaN at ``v_t = 0``).
    tangential_velocity, rebound_spin : ndarray
        ``v_t'`` [m/s] and ``omega'`` [rad/s] (positive adding to the slip) after the bounce; a captured
        particle's at capture where it slides, its rolling motion where the contact sticks (the stuck
        contact rings on its undamped tangential spring about that motion).
    slip : ndarray
        The contact point's slip ``v_t' + R omega'`` [m/s] then.
    rolling_velocity : ndarray
        ``(5 v_t' - 2 R omega')/7`` [m/s]: where a captured particle ends rolling (module docstring).
    outcome : ndarray of str
        One of :data:`OUTCOMES`.
    captured : ndarray of bool
    pulloff_force : ndarray
        ``F_c`` [N] of the Coulomb limit.
    tangential, coulomb : str
    sliding : ndarray of bool
        True where the contact was sliding (at its Coulomb limit) at its last step: as it broke for a
        bounce, at capture for a captured particle (the rigid law: where the impulse reached the limit).
    held : ndarray of bool
        True where the contact was within its Coulomb limit at some step (it stuck at some time: with
        adhesion nearly always, from first touch, where the adhesive limit ``mu 2 F_c`` exceeds the
        spring's force; the rigid law: where the slip was stopped).
    """

    angle: np.ndarray
    normal_speed: np.ndarray
    tangential_speed: np.ndarray
    normal_restitution: np.ndarray
    integrated_normal_restitution: np.ndarray
    tangential_restitution: np.ndarray
    tangential_velocity: np.ndarray
    rebound_spin: np.ndarray
    slip: np.ndarray
    rolling_velocity: np.ndarray
    outcome: np.ndarray
    captured: np.ndarray
    pulloff_force: np.ndarray
    tangential: str
    coulomb: str
    sliding: np.ndarray | None = None
    held: np.ndarray | None = None

    def to_dict(self) -> dict:
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def __len__(self):
        return int(np.size(self.angle))


def libm(fn, *xs):
    """``fn`` (one of :mod:`math`'s functions, the C library's) element by element over ``xs``: numpy may
    evaluate ``cos``, ``sin`` or ``arctan2`` of float64 arrays with its own vectorised routines (on
    AVX-512 machines), a few ulp from the C library's, and the exported C wall function
    (:mod:`microimpact.cexport`), which calls the C library, must reproduce this path bit for bit."""
    return np.vectorize(fn, otypes=[float])(*xs)


def _hertz_time(Vn, E, R, m):
    """Hertz contact time [s] at ``Vn`` (:func:`microimpact.core.hertz.contact_time`): the step's scale."""
    return float(hertz.contact_time(Vn, E, R, m))


def _hertz_radius(alpha, alpha_max, E, R, m, p_y, params):
    """Hertz's contact radius ``(R alpha)^(1/2)`` [m], 0 apart: where a model declares none."""
    return math.sqrt(R * alpha) if alpha > 0.0 else 0.0


def _kernel(model):
    """The integrator of one model: compiled (:func:`_compiled`), or the same source in Python where
    ``MICROIMPACT_BACKEND=python`` (about 30 us a step instead of 30 ns: for checks, not for maps)."""
    import os

    if os.environ.get("MICROIMPACT_BACKEND") == "python":
        return _integrator(model, _hertz_radius)
    return _compiled(model)


@functools.lru_cache(maxsize=32)
def _compiled(model):
    """The compiled integrator of one model: numba compiles one per normal law (its force and contact
    radius bound in as the core's registered functions), since a compiled function cannot take another
    as an argument."""
    import numba

    from ..engine import registry

    registry.register_all()
    fallback = numba.njit(error_model="numpy")(_hertz_radius)
    return numba.njit(error_model="numpy")(_integrator(model, fallback))


def _integrator(model, fallback):
    """The time-stepping integrator of one impact under ``model`` (module docstring), a plain function;
    ``fallback``: the contact radius where the model declares none (Hertz's)."""
    sforce = model.signed_force
    radius = model.tangential_contact_radius or fallback

    def run(Vn, v0, w0, E, R, m, p_y, params, mu, kG, c_load, c_unload, lin, k_lin, lam, limit_mode, Fc, a_sep,
            zero_end, dt, max_steps, t_end):  # fmt: skip
        alpha = 0.0
        adot = Vn
        amax = 0.0
        v = v0
        w = w0
        T = 0.0
        a_old = 0.0
        F = sforce(0.0, adot, 0.0, E, R, m, p_y, params)
        acc = -F / m
        sliding = False
        slid = False
        held = False
        unloading = False
        captured = False
        t = 0.0
        n = 0
        while n < max_steps:
            n += 1
            arm = R - lam * alpha
            adot += 0.5 * dt * acc
            v += 0.5 * dt * T / m
            w += 0.5 * dt * 2.5 * T * arm / (m * R)
            alpha += dt * adot
            t += dt
            if alpha > amax:
                amax = alpha
            if adot < 0.0:
                unloading = True
            if unloading:
                if zero_end:
                    gone = sforce(alpha, adot, amax, E, R, m, p_y, params) <= 0.0 and adot < 0.0
                else:
                    gone = alpha < a_sep
                if gone:
                    T = 0.0
                    acc = 0.0
                    break
            F = sforce(alpha, adot, amax, E, R, m, p_y, params)
            a = radius(alpha, amax, E, R, m, p_y, params)
            arm = R - lam * alpha
            u = v + arm * w / R
            if a_old > 0.0 and a > 0.0:
                c = c_load if a >= a_old else c_unload
                if c == 1.0:
                    T *= a / a_old
                elif c == 2.0:
                    T *= (a / a_old) * (a / a_old)
            elif a <= 0.0:
                T = 0.0
            kt = k_lin if lin != 0.0 else kG * a
            T -= kt * u * dt
            if limit_mode == 0.0:
                crit = mu * abs(F + 2.0 * Fc)
            else:
                crit = mu * abs(F)
            if abs(T) > crit:
                T = crit if T > 0.0 else -crit
                sliding = True
                slid = True
            else:
                sliding = False
                held = True
            a_old = a
            acc = -F / m
            adot += 0.5 * dt * acc
            v += 0.5 * dt * T / m
            w += 0.5 * dt * 2.5 * T * arm / (m * R)
            if t_end > 0.0:
                if t >= t_end:
                    captured = True
                    break
            elif unloading and adot > 0.0:  # pulled back before leaving: captured
                captured = True
                break
        return -adot / Vn, v, w, captured, sliding, slid, t, held

    return run


def _pulloff(model, params, alpha_max, E, R, m, p_y):
    """``F_c = -min signed_force`` on the unloading branch from ``alpha_max`` to where it breaks [N] (>= 0)."""
    a_sep = _separation(model, params, alpha_max, E, R, m, p_y)
    lo, hi = min(a_sep, alpha_max), alpha_max
    xs = np.linspace(lo, hi, 401)
    f = np.array([model.signed_force(float(x), -1.0, alpha_max, E, R, m, p_y, params) for x in xs])
    i = int(np.argmin(f))
    a, b = xs[max(i - 1, 0)], xs[min(i + 1, xs.size - 1)]
    for _ in range(60):  # golden section on the bracket of the sampled minimum
        c1, c2 = b - 0.618 * (b - a), a + 0.618 * (b - a)
        f1 = model.signed_force(c1, -1.0, alpha_max, E, R, m, p_y, params)
        f2 = model.signed_force(c2, -1.0, alpha_max, E, R, m, p_y, params)
        if f1 < f2:
            b = c2
        else:
            a = c1
    fmin = min(float(f.min()), model.signed_force(0.5 * (a + b), -1.0, alpha_max, E, R, m, p_y, params))
    return max(-fmin, 0.0)


def _separation(model, params, alpha_max, E, R, m, p_y):
    if model.separation_approach_after is not None:
        return float(model.separation_approach_after(alpha_max, E, R, m, p_y, params))
    if model.separation_approach is not None:
        return float(model.separation_approach(E, R, m, p_y, params))
    return 0.0


def default_coulomb(tangential):
    """The Coulomb limit (:data:`COULOMB_LIMITS`) of ``tangential``'s code: ``"load"`` for LIGGGHTS'
    ``"liggghts_history"``, ``"adhesive"`` for the others (module docstring)."""
    return "load" if tangential == "liggghts_history" else "adhesive"


def law_constants(tangential, coulomb=None):
    """``(c_load, c_unload, factor, linear, lam, limit_mode)`` the integration takes for the compliant
    ``tangential`` (one of :data:`ADHESIVE_LAWS` but ``"rigid"``; ``"mindlin"`` is LAMMPS'
    ``mindlin_rescale/force``) from :func:`~microimpact.core.tangential_laws.law_parameters`, and the
    Coulomb limit's mode: 0 for ``"adhesive"`` (``mu |F + 2 F_c|``), 1 for ``"load"`` (``mu |F|``);
    ``coulomb`` None: the law's own (module docstring). The C wall function bakes in the same."""
    if coulomb is None:
        coulomb = default_coulomb(tangential)
    law = "lammps_mindlin_rescale_force" if tangential == "mindlin" else tangential
    c_load, c_unload, factor, linear, lam = tl.law_parameters(tl.law_code(law))
    return c_load, c_unload, factor, linear, lam, 0.0 if coulomb == "adhesive" else 1.0


def check_adhesive_tangential(
    tangential, work_of_adhesion, tangential_name="tangential", adhesion_name="work_of_adhesion"
):
    """Refuse ``tangential`` where there is adhesion (``work_of_adhesion > 0``, a number) and this integration
    does not run the law (:data:`ADHESIVE_LAWS`): the one refusal of every caller that integrates adhesive
    oblique impacts (:func:`microimpact.wall.wall_interaction`, the C wall function of
    :mod:`microimpact.cexport`, ``microimpact export``), each naming its inputs its own way
    (``tangential_name``, ``adhesion_name``: the command line's options). Returns ``tangential``."""
    if work_of_adhesion > 0.0 and tangential not in ADHESIVE_LAWS:
        runs = ", ".join(repr(x) for x in ADHESIVE_LAWS if x != "rigid")
        raise ValueError(
            f"{tangential_name}={tangential!r} with adhesion ({adhesion_name} = {work_of_adhesion:g} J/m^2): "
            f"adhesive oblique impacts (wall_interaction and the C wall function) are integrated with {runs} "
            "or 'rigid' only; use one of those or no adhesion"
        )
    return tangential


def adhesive_rule(adhesion, tangential, stacklevel=3):
    """The adhesion rule an adhesive oblique impact under ``tangential`` (a compliant law) integrates for
    the rule asked for, ``adhesion``: that rule, or, for the additive rule, the whole law it approximates,
    with a DeprecationWarning. The additive rule gives ``e`` but no force history to integrate the
    tangential contact along; it is the default of :func:`microimpact.wall.wall_interaction` and of the
    C export, so calls of the releases before keep running (it will be refused there in the next one)."""
    import warnings

    from ..adhesion import ADDITIVE_RULE, WHOLE_LAW

    if adhesion != ADDITIVE_RULE:
        return adhesion
    warnings.warn(
        f"adhesion={adhesion!r} with work_of_adhesion > 0 and tangential={tangential!r}: the additive rule "
        f"gives e but no force history to integrate the tangential contact along, so the whole law it "
        f"approximates is integrated instead; pass adhesion={WHOLE_LAW!r} to say so (the additive rule "
        "will be refused here in the next release), or tangential='rigid' for the additive rule",
        DeprecationWarning,
        stacklevel=stacklevel,
    )
    return WHOLE_LAW


def adhesive_law(adhesion=None, params=None, work_of_adhesion=None):
    """``(model, params)`` of an adhesive normal law, or None where its work of adhesion is 0 (no adhesion).

    ``adhesion``: a model name (default where only ``work_of_adhesion`` is given: the whole adhesive
    elastic-plastic law, :func:`microimpact.core.models.whole_law`, the law of the wall interaction's
    ``adhesion=``; with ``p_y = inf`` it is the elastic JKR contact of work of adhesion ``G``); ``params``: its parameters (default its defaults); ``work_of_adhesion`` ``G`` [J/m^2] sets the
    parameter that is a work of adhesion (``work_of_adhesion``) or a surface energy (``G/2``) by the
    parameter's name, the quantity it declares.
    """
    from ..core import models as _models

    name = _models.whole_law() if adhesion is None else adhesion
    mod = _models.get(name)
    values = list(mod.DEFAULTS if params is None else params)
    if work_of_adhesion is not None:
        G = float(work_of_adhesion)
        if not (0.0 <= G < math.inf):
            raise ValueError(f"work_of_adhesion must be non-negative and finite, got {work_of_adhesion!r}")
        names = [p.name for p in mod.PARAMETERS]
        if "work_of_adhesion" in names:
            values[names.index("work_of_adhesion")] = G
        elif "surface_energy" in names:
            values[names.index("surface_energy")] = 0.5 * G
        else:
            raise ValueError(
                f"adhesion={name!r} has no work of adhesion or surface energy to set from work_of_adhesion"
            )
    values = tuple(mod.validate(tuple(values)))
    if mod.work_of_adhesion is not None and float(mod.work_of_adhesion(values)) == 0.0:
        return None
    return name, values


def adhesive_oblique_impact(
    pair,
    velocity,
    angle,
    friction,
    *,
    model,
    params=None,
    tangential="mindlin",
    spin=0.0,
    kappa=None,
    coulomb=None,
    steps=DEFAULT_STEPS,
    tangential_stiffness=None,
    rest_tolerance=1e-3,
    end_time=None,
) -> AdhesiveObliqueImpact:
    """Oblique impact of a sphere on a flat under an adhesive normal law (module docstring).

    Parameters
    ----------
    pair : ContactPair
        Sphere on a flat.
    velocity, angle, friction, spin : array_like
        Impact speed [m/s], angle from the normal [deg], Coulomb ``mu`` [-], incoming spin [rad/s]
        (positive adding to the slip), broadcast together.
    model : str
        The normal law (any model of :func:`microimpact.models.available`).
    params : tuple, optional
        The model's parameters (default: its defaults).
    tangential : str
        One of :data:`ADHESIVE_LAWS`.
    kappa : float
        ``4 G*/E*`` (:func:`microimpact.oblique.stiffness_ratio_of`); not needed for ``"rigid"``.
    coulomb : str, optional
        One of :data:`COULOMB_LIMITS`; default ``"load"`` for ``"liggghts_history"``, else ``"adhesive"``.
    steps : int
        Time steps per Hertz contact time at the normal speed.
    tangential_stiffness : float, optional
        ``k_t`` [N/m] of ``"lammps_linear_history"`` (required there).
    rest_tolerance : float
        ``"stick"`` where a captured particle's ``|v_t'|`` is below this fraction of ``velocity``.
    end_time : float, optional
        Follow every impact to this time [s] after first touch (unless it bounces) instead of to capture:
        for comparisons with a DEM run of fixed length.
    """
    from ..core import models as _models

    if tangential not in ADHESIVE_LAWS:
        raise ValueError(f"tangential must be one of {ADHESIVE_LAWS}, got {tangential!r}")
    if coulomb is None:
        coulomb = default_coulomb(tangential)
    if coulomb not in COULOMB_LIMITS:
        raise ValueError(f"coulomb must be one of {COULOMB_LIMITS}, got {coulomb!r}")
    mod = _models.get(model)
    params = tuple(mod.DEFAULTS) if params is None else tuple(mod.validate(tuple(params)))
    steps = int(steps)
    if steps < 10:
        raise ValueError(f"steps must be at least 10, got {steps!r}")
    speed, theta, mu, w0 = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (velocity, angle, friction, spin)))
    if np.any(~(speed > 0)) or not np.all(np.isfinite(speed)):
        raise ValueError(f"velocity must be positive and finite, got {velocity!r}")
    if np.any(~((theta >= 0.0) & (theta < 90.0))):
        raise ValueError(f"angle must be in [0, 90) degrees, got {angle!r}")
    if np.any(~(mu >= 0.0)) or not np.all(np.isfinite(mu)):
        raise ValueError(f"friction must be non-negative and finite, got {friction!r}")
    if not np.all(np.isfinite(w0)):
        raise ValueError(f"spin must be finite, got {spin!r}")
    E, R, m, p_y = (float(x) for x in (pair.effective_modulus, pair.effective_radius, pair.effective_mass,
                                       pair.limiting_pressure))  # fmt: skip
    rad = np.radians(theta)
    Vn = speed * libm(math.cos, rad)
    vt = speed * libm(math.sin, rad)
    out = pair.impact(Vn, model=model, warn=False, **dict(zip((p.name for p in mod.PARAMETERS), params)))
    e = np.asarray(out.restitution, dtype=float)
    amax_all = np.asarray(out.max_approach, dtype=float)
    # the step's time scale: Hertz's contact time, or the law's own where shorter (a stiff linear law)
    scale = 2.0 * np.asarray(out.loading_time, dtype=float)
    scale = np.where(np.isfinite(scale) & (scale > 0.0), scale, np.inf)
    captured_law = ~(e > 0.0)
    shape = speed.shape
    res = {k: np.full(shape, np.nan) for k in ("e_int", "v", "w", "Fc")}
    captured = np.zeros(shape, dtype=bool)
    sliding = np.zeros(shape, dtype=bool)
    held = np.zeros(shape, dtype=bool)
    elastic_fc = None
    if mod.separation_approach_after is None:  # the pull-off does not depend on the maximum approach
        elastic_fc = _pulloff(mod, params, float(np.nanmax(amax_all)) if amax_all.size else 0.0, E, R, m, p_y)
    if tangential == "rigid":
        _rigid(mod, params, pair, out, E, R, m, p_y, vt, R * w0, mu, captured_law, elastic_fc, amax_all, res, sliding)
        captured[...] = captured_law
        held[...] = ~sliding
        res["e_int"][...] = e
    else:
        if kappa is None or not (0.0 < float(kappa) < math.inf):
            raise ValueError(f"kappa must be positive and finite for tangential={tangential!r}, got {kappa!r}")
        c_load, c_unload, factor, linear, lam, limit_mode = law_constants(tangential, coulomb)
        k_lin = 0.0
        if linear:
            if tangential_stiffness is None or not (0.0 < float(tangential_stiffness) < math.inf):
                raise ValueError(f"tangential_stiffness must be positive and finite, got {tangential_stiffness!r}")
            k_lin = float(tangential_stiffness)
        kG = factor * 2.0 * float(kappa) * E  # 8 G* = 2 kappa E*
        run = _kernel(mod)
        zero_end = bool(mod.ends_at_zero_force(params)) if mod.ends_at_zero_force is not None else False
        for k, idx in enumerate(np.ndindex(shape)):
            am = float(amax_all[idx])
            Fc = elastic_fc if elastic_fc is not None else _pulloff(mod, params, am, E, R, m, p_y)
            a_sep = _separation(mod, params, am, E, R, m, p_y)
            dt = min(_hertz_time(float(Vn[idx]), E, R, m), float(scale[idx])) / steps
            t_end = -1.0 if end_time is None else float(end_time)
            max_steps = int(MAX_CONTACT_TIMES * steps) if end_time is None else int(t_end / dt) + 2
            # the first call compiles the integrator: one step for a signal (microimpact._atomic)
            with _atomic.step() if k == 0 else contextlib.nullcontext():
                ei, v, w, cap, sl, _, _, hd = run(float(Vn[idx]), float(vt[idx]), float(R * w0[idx]), E, R, m, p_y,
                                              params, float(mu[idx]), kG, c_load, c_unload, linear, k_lin, lam,
                                              limit_mode, Fc, a_sep, zero_end, dt, max_steps, t_end)  # fmt: skip
            res["e_int"][idx] = 0.0 if cap else ei
            res["v"][idx], res["w"][idx], res["Fc"][idx] = v, w, Fc
            captured[idx] = cap if end_time is not None else bool(captured_law[idx])
            sliding[idx] = sl
            held[idx] = hd
    v, wr = res["v"], res["w"]
    roll_v = (5.0 * v - 2.0 * wr) / 7.0
    # A captured contact that sticks rings on its tangential spring (undamped in these laws) about
    # rolling: what it keeps is the rolling motion, R omega - 5/2 v conserved (module docstring)
    kept = captured & ~sliding & (end_time is None)
    v = np.where(kept, roll_v, v)
    wr = np.where(kept, -roll_v, wr)
    outcome = np.where(
        ~captured,
        "bounce",
        np.where(
            sliding, "captured sliding", np.where(np.abs(v) <= rest_tolerance * speed, "stick", "captured rolling")
        ),
    )
    with np.errstate(divide="ignore", invalid="ignore"):
        e_t = np.where(vt != 0.0, v / vt, np.nan)
    return AdhesiveObliqueImpact(
        angle=theta,
        normal_speed=Vn,
        tangential_speed=vt,
        normal_restitution=e,
        integrated_normal_restitution=res["e_int"],
        tangential_restitution=e_t,
        tangential_velocity=v,
        rebound_spin=wr / R,
        slip=v + wr,
        rolling_velocity=roll_v,
        outcome=outcome,
        captured=captured,
        pulloff_force=res["Fc"],
        tangential=tangential,
        coulomb=coulomb,
        sliding=sliding,
        held=held,
    )


def _rigid(mod, params, pair, out, E, R, m, p_y, vt, w0r, mu, captured, elastic_fc, amax_all, res, sliding):
    """The rigid-body impulse with the adhesive limit: the tangential impulse is at most
    ``mu int (F_n + 2 F_c) dt = mu (m (1 + e) V_n + 2 F_c t_c)`` (``t_c`` the law's contact time; unbounded
    for a captured particle), else the contact point stops (rolling: ``J = -m u0 / (7/2)``, ``7/2`` the slip factor of a solid sphere)."""
    e = np.asarray(out.restitution, dtype=float)
    Vn = np.asarray(out.velocity, dtype=float)
    tc = np.asarray(out.contact_time, dtype=float)
    Fc = np.empty(vt.shape)
    for idx in np.ndindex(vt.shape):
        Fc[idx] = elastic_fc if elastic_fc is not None else _pulloff(mod, params, float(amax_all[idx]), E, R, m, p_y)
    u0 = vt + w0r
    with np.errstate(invalid="ignore"):
        limit = np.where(
            captured & (mu > 0.0), np.inf, mu * ((1.0 + e) * Vn + 2.0 * Fc * np.where(captured, 0.0, tc) / m)
        )
    stop = np.abs(u0) / SLIP_FACTOR
    roll = stop <= limit
    J = -np.sign(u0) * np.where(roll, stop, limit)
    J = np.where(u0 == 0.0, 0.0, J)
    res["v"][...] = vt + J
    res["w"][...] = w0r + 2.5 * J
    res["Fc"][...] = Fc
    sliding[...] = ~roll & (u0 != 0.0)
