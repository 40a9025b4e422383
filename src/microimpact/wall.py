"""Bounce or stick at a wall, for whole particle arrays: the wall interaction CFD codes call.

* **Normal direction**: the seed's elastic-plastic restitution with Thornton & Ning's (1998)
  adhesion loss (:mod:`microimpact.adhesion`): their additive rule (``adhesion="additive"``, the
  default) or their whole adhesive elastic-plastic law (``adhesion="thornton_ning_1998_adhesive_plastic"``)
  through the table of its universal curve (:func:`~microimpact.adhesion.whole_law_table`).
* **Tangential direction**: the rigid-body impulse model with Coulomb friction
  (Walton 1993; Brach 1988) for a solid sphere (moment of inertia
  ``I = 2/5 m r^2``): the tangential impulse that would stop the slip of the
  contact point is applied if it lies within the Coulomb limit ``mu J_n``
  ("rolling": the particle leaves rolling on the wall), otherwise the impulse is
  ``mu J_n`` against the slip ("sliding"). No energy is ever gained.
* ``n`` is the unit wall normal pointing **out of the wall, into the fluid**.
  (Fluent's ``F_AREA`` and OpenFOAM's patch ``Sf`` point out of the fluid
  domain, i.e. into the wall: pass their negatives.)
* ``v_n = v . n``; a particle approaches the wall when ``v_n < 0`` and its
  normal impact speed is ``V = -v . n > 0``. Particles with ``v . n >= 0`` are
  moving away: they are passed through unchanged and flagged
  (``approaching = False``).
* The contact point is at ``-r n`` from the particle centre (``r = d/2``); its
  slip velocity is ``u_t = v_t + omega x (-r n) = v_t + r n x omega`` with
  ``v_t = v - v_n n``; spins ``omega`` [rad/s] are angular velocity vectors,
  right-handed, in the same frame as ``v``.
* After the impact ``v_n' = +e V`` (away from the wall); the tangential impulse
  ``J_t`` changes ``v_t' = v_t + J_t/m`` and ``omega' = omega - 5/(2 m r) n x J_t``.

The wall is flat, fixed and massive (``R* = R``, ``m* = m``); spin about the
normal is not changed (no torsional friction); the tangential impulse does not
feed back on the normal restitution.

``tangential="mindlin"`` replaces the rigid impulse by the compliant contact of
:mod:`microimpact.oblique` (Mindlin's no-slip spring ``k_t = 8 G* a`` with a Coulomb
limit, along the seed's normal history): the impulse is ``J_t = -F mu J_n u_t/|u_t|``
with ``F`` from the universal table of ``kappa = 4 G*/E*`` at the normalised angle
``psi = kappa |u_t| / (mu V)`` and ``V_y/V``. It keeps the slip's direction, and
never adds energy.

With adhesion (``G > 0``) and a compliant law (anything but ``"rigid"``), each particle's impact is
integrated, normal and tangential together, under Thornton & Ning's whole adhesive law with the
adhesive Coulomb limit ``mu |F_n + 2 F_c|`` (``mu |F_n|`` of the whole normal force for
``"liggghts_history"``, as LIGGGHTS; :func:`microimpact.oblique.adhesive.adhesive_oblique_impact`,
called with the particle's own pair, speed, angle, friction and spin along its slip direction): the
particle bounces or is captured, and a captured particle keeps the tangential velocity and spin the
integration gives (it rolls or slides along the wall; :attr:`WallInteraction.outcome`). The normal
restitution and the capture are the law's own, exact (not its table). This needs
``adhesion=`` the whole law: the additive rule is a rule for ``e`` with no force history to integrate
along, so the whole law is integrated in its place, with a DeprecationWarning (the additive rule is
the default, and calls of the releases before keep running this release). The rigid impulse and
``G = 0`` are unchanged.

The DEM codes' laws of :mod:`microimpact.core.tangential_laws` (``"lammps_mindlin"``,
``"lammps_mindlin_force"``, ``"lammps_mindlin_rescale"``, ``"lammps_mindlin_rescale_force"`` (=
``"mindlin"``), ``"lammps_linear_history"`` (stiffness ``8 G* a_m`` of each impact),
``"di_renzo_di_maio"``) and Stronge's compliant impact (``"stronge"``) are applied the same way, each
through its own universal table (the names of :func:`microimpact.oblique.oblique_impact`; its
``method="table"`` gives the same outcome). The linear law's stiffness follows each impact's speed
here instead of being one constant. ``"liggghts_history"`` has no universal table: LIGGGHTS's wall arm
``r - delta/2`` (``src/surface_model_default.h``) moves the rim by less than ``5/2`` of the centre's
impulse and makes the outcome depend on ``alpha_m/r`` and on the incoming spin, so each impact is
integrated as :func:`~microimpact.oblique.oblique_impact` integrates it (along the slip's initial
direction; about 0.4 ms an impact), and the spin takes the rim's own impulse. Unlike the compliant
``"mindlin"``, the laws ``"lammps_mindlin"``, ``"liggghts_history"`` and ``"di_renzo_di_maio"`` can
create energy at small angles (their stored force grows with the contact radius at a fixed
displacement): so do the codes. With adhesion ``"stronge"`` and ``"mindlin_deresiewicz"`` are refused
(the adhesive integration does not run them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ._validation import check_nonnegative, check_positive
from .adhesion import check_adhesion_rule, whole_law_correction
from .core import wall as _wall
from .core.tangential_laws import ALL_LAWS as LAWS
from .engine import evaluate
from .io import check_memory
from .materials import DEFAULT_K, Material, get_material, sphere_mass
from .materials import effective_modulus as _effective_modulus

__all__ = ["REGIMES", "OUTCOMES", "WallInteraction", "wall_interaction"]

#: Codes of :attr:`WallInteraction.regime`.
REGIMES = {0: "none", 1: "rolling", 2: "sliding", 3: "stuck"}
#: The outcomes of an impact (:attr:`WallInteraction.outcome`, after ``"none"``), those of
#: :data:`microimpact.oblique.adhesive.OUTCOMES`, in their order.
OUTCOMES = ("bounce", "stick", "captured rolling", "captured sliding")


@dataclass(frozen=True, eq=False)
class WallInteraction:
    """Outcome of :func:`wall_interaction` for ``N`` particles (SI units).

    Attributes
    ----------
    velocity : ndarray (N, 3)
        Outgoing velocity [m/s]; the incoming one where the particle was not approaching. Where stuck:
        zero, or, with adhesion and a compliant tangential law, the velocity along the wall the captured
        particle keeps (no normal part).
    spin : ndarray (N, 3) or None
        Outgoing angular velocity [rad/s]; None when no spin was given and
        there is no friction.
    stuck : ndarray of bool (N,)
        True where the particle sticks (adhesion; never with ``G = 0``): it stays on the wall. With the
        rigid impulse it stops dead (zero velocity and spin); with adhesion and a compliant tangential
        law it is captured, and ``velocity`` and ``spin`` are what it keeps along the wall (rolling or
        sliding; :attr:`outcome`).
    restitution : ndarray (N,)
        Normal restitution ``e`` used: ``-v'.n / v.n``; 0 where stuck, 1 where
        the particle was not approaching.
    normal_speed : ndarray (N,)
        Incoming normal impact speed ``V = -v.n`` [m/s]; 0 where not approaching.
    approaching : ndarray of bool (N,)
        False where ``v . n >= 0``: no impact, passed through unchanged.
    rolling : ndarray of bool (N,)
        True where the tangential impulse stopped the slip (within the Coulomb limit).
    yield_velocity : ndarray (N,)
        ``V_y`` [m/s] (seed eq. 28) of each particle.
    sticking_velocity : ndarray (N,)
        The capture speed [m/s] of each particle under the chosen rule. ``"additive"``: Thornton &
        Ning's ``V_s`` of the undeformed sphere (eq. 54), as in the releases before ``adhesion=``
        (where ``V_s > V_y`` the additive rule captures up to the root of ``e_p V = V_s``, above
        ``V_s``: :func:`microimpact.core.adhesion.capture_velocity`). The whole law: its own capture
        speed, the model's sticking velocity
        (:func:`~microimpact.core.models.thornton_ning_1998_adhesive_plastic.sticking_velocity`;
        ``pair.sticking_velocity(model=...)``), at and below which the law sticks; the table the
        restitution is read from sticks up to within 1.5e-3 (relative) of it. (The table's groups stay
        ``V/V_y`` and eq. 54's ``V_s/V_y``.) 0 without adhesion.
    outside_table : ndarray of bool (N,)
        ``adhesion="thornton_ning_1998_adhesive_plastic"`` only (all False otherwise): True where
        ``V/V_y`` or ``V_s/V_y`` lies beyond the whole law's table
        (:class:`~microimpact.adhesion.WholeLawTable`: ``V/V_y > 1000`` or ``V_s/V_y > 10``); the
        table's edge was used there (flagged, not refused).
    adhesion : str
        The adhesion rule used (``"additive"`` or the whole law's name).
    outcome : ndarray of str (N,)
        ``"none"`` (not approaching), ``"bounce"``, ``"stick"`` (captured at rest; with the rigid impulse
        every stuck particle), ``"captured rolling"`` or ``"captured sliding"`` (adhesion and a compliant
        law: the captured particle rolls, or slides, along the wall with ``velocity`` and ``spin``; the
        outcomes of :data:`microimpact.oblique.adhesive.OUTCOMES`).
    """

    velocity: np.ndarray
    spin: np.ndarray | None
    stuck: np.ndarray
    restitution: np.ndarray
    normal_speed: np.ndarray
    approaching: np.ndarray
    rolling: np.ndarray
    yield_velocity: np.ndarray
    sticking_velocity: np.ndarray
    outside_table: np.ndarray | None = None
    adhesion: str = "additive"
    _single: bool = field(default=False, repr=False)
    # index into OUTCOMES of each particle's adhesive integration, -1 where it was not integrated
    _outcome: np.ndarray | None = field(default=None, repr=False)

    @property
    def outcome(self) -> np.ndarray:
        """Per particle: ``"none"``, ``"bounce"``, ``"stick"``, ``"captured rolling"`` or ``"captured sliding"``."""
        names = np.asarray(("none", *OUTCOMES))
        code = np.where(~np.asarray(self.approaching), 0, np.where(np.asarray(self.stuck), 2, 1))
        if self._outcome is not None:
            code = np.where(self._outcome >= 0, self._outcome + 1, code)
        return names[code]

    @property
    def regime(self) -> np.ndarray:
        """Per particle: ``"none"`` (not approaching), ``"stuck"``, ``"rolling"`` or ``"sliding"``."""
        code = np.where(~self.approaching, 0, np.where(self.stuck, 3, np.where(self.rolling, 1, 2)))
        return np.asarray(list(REGIMES.values()))[code]

    @property
    def deposited_fraction(self) -> float:
        """Fraction of the approaching particles that stick."""
        n = int(np.count_nonzero(self.approaching))
        return float(np.count_nonzero(self.stuck)) / n if n else 0.0

    def __len__(self):
        return int(np.size(self.stuck))


def _vectors(name, value):
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 1:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"{name} must have shape (N, 3) or (3,), got shape {np.shape(value)}")
    if not np.all(np.isfinite(arr)):
        bad = arr[~np.isfinite(arr)].flat[0]
        raise ValueError(f"{name} must be finite, got {float(bad)!r}")
    return arr


def _per_particle(name, arr, n):
    arr = np.asarray(arr, dtype=float)
    if arr.ndim > 1 or (arr.ndim == 1 and arr.size not in (1, n)):
        raise ValueError(f"{name} must be a scalar or have one value per particle ({n}), got shape {arr.shape}")
    return np.broadcast_to(arr.reshape(-1) if arr.ndim else arr, (n,))


def _materials(material, n):
    """Per-particle arrays (E, nu, rho, Y) from one material or one per particle."""
    if isinstance(material, (str, Material)):
        m = get_material(material)
        y = m.yield_strength if m.yield_strength else math.nan
        return tuple(np.full(n, x, dtype=float) for x in (m.youngs_modulus, m.poisson_ratio, m.density, y))
    arr = np.asarray(material, dtype=object).reshape(-1)
    if arr.size != n:
        raise ValueError(f"material must be one material or one per particle ({n}), got {arr.size}")
    keys: dict = {}
    inv = np.fromiter((keys.setdefault(x, len(keys)) for x in arr), dtype=np.intp, count=n)
    table = np.array(
        [
            (m.youngs_modulus, m.poisson_ratio, m.density, m.yield_strength or math.nan)
            for m in (get_material(k) for k in keys)
        ],
        dtype=float,
    )
    return tuple(table[inv, j] for j in range(4))


# Peak bytes per particle of wall_interaction (result table, regime, flags, temporaries).
_BYTES_PER_PARTICLE = 8 * (11 + 1 + 6 + 3) + 3
# and with the whole adhesive law: its prepass (V, slip, V_y, r, m, V_s, x, y) and the table
# lookup's temporaries (t, u, ft, fu, i, j, a, b, four corner values, D), at most 21 columns at once,
# The capture speeds after it (_capture_speeds: the sort's permutation, 5 sorted columns, the group
# index, the result: about 9 columns) stay below that peak.
_BYTES_WHOLE_LAW = 8 * 22 + 2
# and with LIGGGHTS's law, integrated per particle: kappa, the two slip parts, x, eps, e, the scaled
# velocities, the integration's three results, F and W (at most 12 columns at once)
_BYTES_ARM_LAW = 8 * 12 + 1
# and with adhesion and a compliant law (the particles integrated one pair at a time): the selection,
# its 3-D prepass (v, n, omega, the unit normal, v_t, the slip direction and its normal companion: 24
# columns), the 1-D inputs (speed, angle, spin, r, m, the group keys: 10), the outcome codes, and what
# the adhesive integration holds for a group of at most all particles (the normal law's outcome, its
# inputs and results, the outcome names as 16-character strings); measured with tracemalloc: 0.7-0.95
# kB a particle over 100 to 200 particles
_BYTES_ADHESIVE_OBLIQUE = 8 * 128 + 1


def wall_interaction(
    velocity,
    normal,
    diameter,
    density=None,
    *,
    material=None,
    wall="silicon",
    limiting_pressure=None,
    effective_modulus=None,
    work_of_adhesion=0.0,
    friction=0.0,
    spin=None,
    k=DEFAULT_K,
    tangential="rigid",
    poisson_ratio=None,
    effective_shear_modulus=None,
    adhesion="additive",
) -> WallInteraction:
    """Outgoing velocities, spins and stick flags of particles hitting a wall.

    Normal: the seed's restitution (eqs. 22, 27, 28) of the normal impact speed
    ``V = -v.n`` with the adhesive loss of Thornton & Ning (1998)
    (:func:`adhesive_restitution`). Tangential: rigid-body Coulomb impulse model
    for a solid sphere (Walton 1993; Brach 1988). Sign conventions: see the
    module docstring (``n`` points from the wall into the fluid).

    Tangential impulse: the contact-point slip ``u_t = v_t + r n x omega``
    would be stopped by ``J_stop = -(2 m / 7) u_t`` (a sphere's slip changes by
    ``J (1/m + r^2/I) = 7 J / (2 m)``). If ``|J_stop| <= mu J_n`` with the
    normal impulse ``J_n = m (1 + e) V``, that impulse is applied (rolling: a
    non-spinning sphere leaves with ``5/7`` of its tangential velocity);
    otherwise ``J_t = -mu J_n u_t / |u_t|`` (sliding). Either way the slip
    keeps its direction and shrinks, so the kinetic energy (translational plus
    rotational) never increases. Stuck particles get zero velocity and spin.

    Parameters
    ----------
    velocity : array_like (N, 3) or (3,)
        Incoming particle velocities [m/s] in the wall's frame.
    normal : array_like (N, 3) or (3,)
        Wall normals, pointing out of the wall into the fluid; normalised here.
    diameter : array_like (N,) or scalar
        Particle diameters [m].
    density : array_like (N,) or scalar, optional
        Particle densities [kg/m^3]; default: the particle material's.
    material : str, Material or sequence of them, optional
        Particle material, one for all or one per particle (names from
        :data:`~microimpact.materials.MATERIALS`). Needed unless ``density`` and
        ``effective_modulus`` are given.
    wall : str or Material, optional
        Wall material (default ``"silicon"``); not used when ``effective_modulus`` is given.
    limiting_pressure : array_like, optional
        ``p_y`` [Pa] of the pair (scalar or per particle); ``inf`` for no
        yielding. Default: ``k Y`` with ``Y`` the smaller known yield strength
        of particle and wall.
    effective_modulus : array_like, optional
        ``E*`` [Pa], overriding the materials' value.
    work_of_adhesion : array_like, optional
        ``G`` [J/m^2] (the work of adhesion, ``2 gamma`` for identical surfaces;
        see :func:`work_of_adhesion`), scalar or per particle. Default 0: no
        adhesion, nothing sticks.
    friction : array_like, optional
        Coulomb friction coefficient ``mu`` >= 0, scalar or per particle. Default 0.
    spin : array_like (N, 3), optional
        Incoming angular velocities [rad/s]; default zero.
    k : float, optional
        ``p_y / Y`` when ``limiting_pressure`` is not given (default 2.2).
    tangential : str, optional
        Tangential model: ``"rigid"``, the rigid-body Coulomb impulse (default), the compliant
        contact ``"mindlin"`` or a DEM code's law of
        :data:`microimpact.core.tangential_laws.ALL_LAWS` (module docstring); ``rolling`` then
        flags particles whose contact stuck at some time during the impact. With ``G > 0`` a compliant
        law integrates each adhesive particle's impact
        (:func:`~microimpact.oblique.adhesive.adhesive_oblique_impact`, module docstring; it needs
        ``adhesion=`` the whole law): measured 11-15 ms a particle (100 random impacts at 0.03-3 m/s and
        0-85 degrees, elastic and plastic, one pair or all distinct; a shared two-core host, up to 50 ms
        when it is loaded; 4000 steps a contact time, a captured particle followed until it is pulled
        back; most of it the pull-off of each impact's unloading branch and the per-pair setup), plus a
        few seconds' compilation once per process, against microseconds for the table; memory about
        1 kB a particle. A wall function meeting many adhesive particles should use the rigid impulse,
        or pass them in blocks. Particles with ``G = 0`` take the table as before.
    poisson_ratio : float, optional
        Compliant laws only: one Poisson's ratio for particle and wall, giving
        ``kappa = 2(1 - nu)/(2 - nu)``; default from the materials.
    effective_shear_modulus : float, optional
        Compliant laws only: ``G*`` [Pa], giving ``kappa = 4 G*/E*``.
    adhesion : str, optional
        The normal restitution with adhesion: ``"additive"`` (default; Thornton & Ning's additive
        rule, :func:`~microimpact.adhesion.adhesive_restitution`: the results are those of the
        releases before the option, bit for bit) or ``"thornton_ning_1998_adhesive_plastic"``
        (their whole law: ``e^2 = e_p^2 - (V_s/V)^2 + D(V/V_y, V_s/V_y)`` with ``D`` interpolated in
        :func:`~microimpact.adhesion.whole_law_table`; the particle sticks where that is not
        positive; points beyond the table are flagged in ``outside_table``). Anything else is refused
        (:func:`~microimpact.adhesion.check_adhesion_rule`), the DMT elastic adhesive law with its
        reason: it is conservative (``e = 1`` at every speed), so at the wall it would never capture.
        With ``G > 0`` and a compliant ``tangential`` the additive rule has no force history to
        integrate the tangential contact along: the whole law is integrated in its place, with a
        DeprecationWarning (pass it; the additive rule will be refused there in the next release).

    Returns
    -------
    WallInteraction

    Examples
    --------
    >>> out = wall_interaction([[3.0, 0.0, -50.0]], [0, 0, 1], 4.9e-6, 1350.0,
    ...                        effective_modulus=1.31e9, limiting_pressure=156e6, friction=0.3)
    >>> out.velocity.round(3)
    array([[ 2.143,  0.   , 36.241]])
    >>> out.restitution.round(4), out.regime
    (array([0.7248]), array(['rolling'], dtype='<U7'))
    """
    if tangential not in ("rigid", "mindlin", *LAWS):
        raise ValueError(f"tangential must be 'rigid', 'mindlin' or one of {LAWS}, got {tangential!r}")
    check_adhesion_rule(adhesion)
    single = np.ndim(velocity) == 1
    v = _vectors("velocity", velocity)
    N = v.shape[0]
    # Refused before anything of size N is made: the (N, 11) result table, the per-particle inputs
    # made here (modulus, p_y, yield strength) and the compliant prepass (3 columns), 8 bytes each.
    per = _BYTES_PER_PARTICLE + (0 if adhesion == "additive" else _BYTES_WHOLE_LAW)
    per += _BYTES_ARM_LAW if tangential == "liggghts_history" else 0
    check_memory(N * per, f"wall_interaction of {N} particles", "pass the particles in blocks")
    nrm = _vectors("normal", normal)
    if nrm.shape[0] not in (1, N):
        raise ValueError(f"normal must be one vector or one per particle ({N}), got {nrm.shape[0]}")
    if nrm.shape[0] == 1 and not np.any(nrm):
        raise ValueError("normal must not be a zero vector")  # one per particle: found by the core

    d = _per_particle("diameter", check_positive("diameter", diameter), N)
    mats = _materials(material, N) if material is not None else None
    if density is None:
        if mats is None:
            raise ValueError("density is needed (or give material=...)")
        rho = mats[2]
    else:
        rho = _per_particle("density", check_positive("density", density), N)

    try:  # every law divides by the mass 4/3 pi (d/2)^3 rho: it must be a normal double
        sphere_mass(0.5 * d, rho)
    except ValueError as exc:
        raise ValueError(f"diameter and density: {exc}") from None

    if effective_modulus is not None:
        E = _per_particle("effective_modulus", check_positive("effective_modulus", effective_modulus), N)
        wall_mat = None
    else:
        if mats is None or wall is None:
            raise ValueError("effective_modulus is needed (or give material=... and wall=...)")
        wall_mat = get_material(wall)
        E = _effective_modulus(mats[0], mats[1], wall_mat.youngs_modulus, wall_mat.poisson_ratio)

    if limiting_pressure is None:
        Y = np.full(N, math.nan) if mats is None else mats[3].copy()
        if wall_mat is not None and wall_mat.yield_strength:
            Y = np.fmin(Y, wall_mat.yield_strength)
        if np.any(np.isnan(Y)):
            raise ValueError(
                "limiting_pressure is needed: give limiting_pressure=... or materials with a yield strength"
            )
        p_y = float(check_positive("k", k)) * Y
    else:
        p_y = _per_particle(
            "limiting_pressure", check_positive("limiting_pressure", limiting_pressure, allow_inf=True), N
        )
    G = _per_particle("work_of_adhesion", check_nonnegative("work_of_adhesion", work_of_adhesion), N)
    mu = _per_particle("friction", check_nonnegative("friction", friction), N)
    if np.any(np.isinf(G)) or np.any(np.isinf(mu)):
        raise ValueError("work_of_adhesion and friction must be finite")
    adhesive_oblique = tangential != "rigid" and bool(np.any(G > 0.0))
    if adhesive_oblique:
        from .oblique.adhesive import adhesive_rule, check_adhesive_tangential

        # refused, before anything of size N is made, where the integration does not run the law
        check_adhesive_tangential(tangential, float(np.max(G)))
        adhesion = adhesive_rule(adhesion, tangential)
        per += _BYTES_ADHESIVE_OBLIQUE  # known once G is: still before anything of size N is made
        check_memory(N * per, f"wall_interaction of {N} particles", "pass the particles in blocks")
    has_spin = spin is not None
    if has_spin:
        w = _vectors("spin", spin)
        if w.shape[0] not in (1, N):
            raise ValueError(f"spin must have one vector per particle ({N}), got {w.shape[0]}")

    # One particle's physics is core.wall.wall_impact (the C export is its copy); here only arrays,
    # passed as columns (strided views, read in place) and filled into one (N, 11) table.
    vT = tuple(v[:, j] for j in range(3))
    nT = tuple(nrm[:, j] if nrm.shape[0] == N else np.array(nrm[0, j]) for j in range(3))
    wT = (
        tuple(w[:, j] if w.shape[0] == N else np.array(w[0, j]) for j in range(3)) if has_spin else (np.array(0.0),) * 3
    )
    W = None  # the rim's impulse ratio of a law whose arm is not r (LIGGGHTS)
    if tangential == "rigid":
        F = np.array(math.nan)
    else:
        V0, slip, Vy0 = evaluate(_wall.approach_and_slip, *vT, *nT, *wT, d, rho, E, p_y, nout=3)
        kappa = _stiffness_ratios(N, E, mats, wall_mat, poisson_ratio, effective_shear_modulus, tangential)
        # the particles integrated with adhesion below need no table (nor its first build)
        skip = (G > 0.0) if adhesive_oblique else np.zeros(N, dtype=bool)
        if tangential == "liggghts_history":
            F, W, slip_dir = _arm_law_ratios(vT, nT, wT, d, rho, E, V0, Vy0, mu, kappa, skip)
        else:
            F = _compliant_impulse_ratio(slip, V0, Vy0, mu, kappa, tangential, skip)
    if adhesion == "additive":
        D = np.array(math.nan)
        outside = np.zeros(N, dtype=bool)
    else:
        D, outside = _whole_law_correction(vT, nT, wT, d, rho, E, p_y, G)
    table = np.empty((N, len(_wall.WALL_FIELDS)))
    out = evaluate(_wall.wall_impact, *vT, *nT, *wT, d, rho, E, p_y, G, mu, F, D, nout=table.shape[1], out=table.T)
    o = dict(zip(_wall.WALL_FIELDS, out))
    regime = o["regime"].copy()  # one pass over the strided column, then contiguous
    if np.isnan(regime).any():
        raise ValueError("normal must not be a zero vector")
    if W is not None:
        _correct_spin(table, nT, slip_dir, d, mu, F, W)
    codes = None
    if adhesive_oblique:
        codes = _adhesive_oblique(table, vT, nT, wT, d, rho, E, p_y, G, mu, kappa, tangential, adhesion)
        regime = table[:, 8].copy()
        outside = np.where(codes >= 0, False, outside)  # the law itself, not its table
    approaching = regime != _wall.NONE
    stuck = regime == _wall.STUCK
    rolling = regime == _wall.ROLLING
    v_out = table[:, 0:3]
    w_out = table[:, 3:6] if (has_spin or np.any(mu > 0.0)) else None
    e, V = o["restitution"], o["normal_speed"]
    Vy, Vs = o["yield_velocity"], o["sticking_velocity"]
    if adhesion != "additive":  # the whole law's own capture speed, not eq. 54's V_s
        Vs = _capture_speeds(d, rho, E, p_y, G)
    return WallInteraction(
        velocity=v_out[0] if single else v_out,
        spin=None if w_out is None else (w_out[0] if single else w_out),
        stuck=stuck[0] if single else stuck,
        restitution=e[0] if single else e,
        normal_speed=V[0] if single else V,
        approaching=approaching[0] if single else approaching,
        rolling=rolling[0] if single else rolling,
        yield_velocity=Vy[0] if single else Vy,
        sticking_velocity=Vs[0] if single else Vs,
        outside_table=outside[0] if single else outside,
        adhesion=adhesion,
        _single=single,
        _outcome=None if codes is None else (codes[0] if single else codes),
    )


def _capture_speeds(d, rho, E, p_y, G):
    """The whole law's capture speed of each particle (:func:`~microimpact.core.wall.whole_law_capture_velocity`),
    computed once per distinct particle ``(d, rho, E*, p_y, G)``: the model's hook searches the rebound
    work's sign change (20-30 us a particle where the contact yields before it can stick, 50 times the
    rest of the interaction), while a particle stream often holds few distinct particles (size
    classes, one material). The same values, bit for bit, as evaluating every particle. Measured
    (2e5 particles, two shared cores): 5 size classes 1.0 us a particle (0.55 us before the field
    was the law's own); all particles distinct (random sizes, materials, p_y, G) 34 us (0.6 us)."""
    cols = np.broadcast_arrays(d, rho, E, p_y, G)
    order = np.lexsort(cols)  # numeric sorts: np.unique(axis=0) compares rows as bytes, 50 times slower
    cols = [c[order] for c in cols]
    first = np.zeros(order.size, dtype=bool)  # the first particle of each distinct row
    first[:1] = True
    for c in cols:
        first[1:] |= c[1:] != c[:-1]
    Vc = evaluate(_wall.whole_law_capture_velocity, *(c[first] for c in cols))[0]
    out = np.empty(order.size)
    out[order] = Vc[np.cumsum(first) - 1]
    return out


def _whole_law_correction(vT, nT, wT, d, rho, E, p_y, G):
    """``(D, outside)`` per particle: the whole law's table at ``(V/V_y, V_s/V_y)``
    (:func:`~microimpact.adhesion.whole_law_correction`; 0 and False where the particle does not
    approach the wall)."""
    from .core import adhesion as _adh

    V, _, Vy = evaluate(_wall.approach_and_slip, *vT, *nT, *wT, d, rho, E, p_y, nout=3)
    if np.isnan(V).any():  # a zero normal (refused below as well, after the interaction)
        raise ValueError("normal must not be a zero vector")
    Vs = evaluate(_adh.sticking_velocity, G, E, 0.5 * d, evaluate(_wall.sphere_mass, 0.5 * d, rho)[0])[0]
    D, outside = whole_law_correction(V, Vy, Vs)
    approaching = V > 0.0
    return np.where(approaching, D, 0.0), outside & approaching


def _stiffness_ratios(n, E, mats, wall_mat, poisson_ratio, effective_shear_modulus, law):
    """``kappa = 4 G*/E*`` per particle (:func:`microimpact.core.tangential.stiffness_ratio`)."""
    from .core import hertz as _hertz
    from .core import tangential as _tg

    if effective_shear_modulus is not None:
        G = _per_particle(
            "effective_shear_modulus", check_positive("effective_shear_modulus", effective_shear_modulus), n
        )
        return _tg.stiffness_ratio(G, E)
    if poisson_ratio is not None:
        nu = float(poisson_ratio)
        if isinstance(poisson_ratio, bool) or not (-1.0 < nu <= 0.5):
            raise ValueError(f"poisson_ratio must be in (-1, 0.5], got {poisson_ratio!r}")
        return np.full(n, _tg.stiffness_ratio_same_poisson(nu))
    if mats is not None and wall_mat is not None:
        Ew, nuw = wall_mat.youngs_modulus, wall_mat.poisson_ratio
        G = np.array([_tg.effective_shear_modulus(e1, n1, Ew, nuw) for e1, n1 in zip(mats[0], mats[1])])
        return _tg.stiffness_ratio(G, _hertz.effective_modulus(mats[0], mats[1], Ew, nuw))
    raise ValueError(
        f"tangential={law!r} needs poisson_ratio=..., effective_shear_modulus=... or material=... and wall=..."
    )


def _arm_law_ratios(vT, nT, wT, d, rho, E, V, Vy, mu, kappa, skip):
    """``(F, W)`` per particle of LIGGGHTS's ``tangential history`` at a wall, integrated impact by impact.

    LIGGGHTS applies the wall's tangential force and takes the contact point's velocity at the arm
    ``r - delta/2`` (``src/surface_model_default.h``), so the centre and the rim are moved by
    different impulses and the outcome depends on ``alpha_m/r`` and on how the slip splits between
    the centre's velocity and the rim's (:func:`~microimpact.core.wall.slip_split`): no universal
    table holds it. Each impact is integrated as :func:`microimpact.oblique.oblique_impact` integrates
    it (:func:`~microimpact.core.tangential_laws.integrate_law`, law ``"liggghts_history"``, its
    ``steps``), along the slip's initial direction (the codes' force turns with the slip; here the
    slip keeps its direction, exact where ``v_t`` and ``n x omega`` are parallel, as without spin).
    About 0.4 ms an impact, a hundred times the table's cost.

    ``F = |J_t|/(mu J_n)`` signed as :func:`~microimpact.core.wall.wall_impact` takes it (the centre's
    impulse), and ``W`` the rim velocity's change in the same unit (``5/2 F`` for an arm ``r``), both
    normalised by the seed's ``1 + e`` (particles with adhesion are ``skip``-ped: they are integrated
    with it, :func:`_adhesive_oblique`); and the unit slip direction's three columns. Particles where
    ``skip`` is True are not integrated (0).
    """
    from .core import tangential as _tg
    from .core import tangential_laws as _tl
    from .impact import elastic_max_approach, restitution_coefficient
    from .oblique import DEFAULT_STEPS

    vu, wu, sx, sy, sz = evaluate(_wall.slip_split, *vT, *nT, *wT, d, nout=5)
    active = (V > 0.0) & (mu > 0.0) & ((vu + wu) > 0.0) & ~skip
    if np.all(skip):  # every particle integrated with adhesion: nothing to do (nor to compile) here
        zero = np.zeros(V.shape)
        return zero, zero, (sx, sy, sz)
    Vs = np.where(active, V, 1.0)
    scale = mu * Vs
    x = np.minimum(Vy / Vs, 1.0)
    r = 0.5 * d
    m = evaluate(_wall.sphere_mass, r, rho)[0]
    eps = np.asarray(elastic_max_approach(Vs, E, r, m), dtype=float) / r
    v0 = np.where(active, vu / scale, 0.0)
    w0 = np.where(active, wu / scale, 0.0)
    code = np.asarray(_tl.law_code("liggghts_history"))
    vr, wr, rg = evaluate(_tl.integrate_law, code, v0, w0, kappa, x, eps, np.asarray(float(DEFAULT_STEPS)), nout=3)
    one_e = 1.0 + np.asarray(restitution_coefficient(Vs, Vy), dtype=float)
    F = np.where(rg == _tg.REGIME_SLIDING, 1.0, (v0 - vr) / one_e)  # sliding throughout: the Coulomb limit
    W = (w0 - wr) / one_e
    return np.where(active, F, 0.0), np.where(active, W, 0.0), (sx, sy, sz)


def _correct_spin(table, nT, slip_dir, d, mu, F, W):
    """The spin columns of ``table`` (:data:`~microimpact.core.wall.WALL_FIELDS`) with the rim's own impulse.

    :func:`~microimpact.core.wall.wall_impact` changes the rim velocity ``r n x omega`` by ``5/2`` of the
    centre's impulse ``-F mu J_n s`` (arm ``r``; ``s`` the unit slip direction); a law with another arm
    changes it by ``-W mu J_n s``. The difference ``c = (5/2 F - W) mu J_n s`` is added to the rim
    velocity: ``omega -= (1/r) n x c`` (``r n x (-(1/r) n x c) = c`` for ``c`` in the wall's plane).
    Stuck particles (zero spin) and particles not approaching are left as they are."""
    e, V, regime = table[:, 6], table[:, 7], table[:, 8]
    moved = ((regime == _wall.ROLLING) | (regime == _wall.SLIDING)) & (mu > 0.0)
    if not np.any(moved):
        return
    nx, ny, nz = (np.broadcast_to(c, e.shape) for c in nT)
    length = np.sqrt(nx * nx + ny * ny + nz * nz)
    coef = np.where(moved, (2.5 * F - W) * mu * (1.0 + e) * V / (0.5 * d * length), 0.0)
    sx, sy, sz = slip_dir
    table[:, 3] -= coef * (ny * sz - nz * sy)
    table[:, 4] -= coef * (nz * sx - nx * sz)
    table[:, 5] -= coef * (nx * sy - ny * sx)


def _compliant_impulse_ratio(ut_mag, V, Vy, mu, kappa, law, skip):
    """``|J_t| / (mu J_n)`` of the compliant law per particle, from the universal tables (0 where ``skip``)."""
    from .oblique import universal_table

    n = ut_mag.size
    F = np.zeros(n)
    approaching = (V > 0.0) & ~skip
    with np.errstate(invalid="ignore", divide="ignore"):
        psi = np.where(approaching & (mu > 0.0), kappa * ut_mag / (mu * np.where(V > 0, V, 1.0)), 0.0)
        x = np.where(V > 0.0, Vy / np.where(V > 0, V, 1.0), 1.0)
    # the distinct kappas in ascending order, as np.unique finds them; not np.unique itself, which
    # imports numpy.ma (15-20 ms of a script's first compliant call, row 11 of the benchmarks)
    rounded = np.round(kappa, 12)
    keys = np.sort(rounded[~skip])
    first = np.zeros(keys.size, dtype=bool)
    first[:1] = True
    first[1:] = keys[1:] != keys[:-1]
    for kap in keys[first]:
        sel = (rounded == kap) & ~skip
        F[sel] = universal_table(float(kap), law=law)(psi[sel], np.minimum(x[sel], 1.0))
    return np.where(approaching & (mu > 0.0), F, 0.0)


def _adhesive_oblique(table, vT, nT, wT, d, rho, E, p_y, G, mu, kappa, tangential, adhesion):
    """Overwrite the rows of ``table`` (:data:`~microimpact.core.wall.WALL_FIELDS`) of the particles that
    approach with ``G > 0`` by their integrated adhesive impact; return each particle's index into
    :data:`OUTCOMES` (-1 where not integrated).

    The impact is the one-dimensional one of :func:`~microimpact.oblique.adhesive.adhesive_oblique_impact`
    along the unit slip direction ``e`` (that of ``v_t`` where nothing slips): the tangential force
    stays along the slip of a sphere whose arm is ``r`` (the slip changes by ``7/(2m)`` of it), so the
    parts of ``v_t`` and of the rim velocity across ``e`` (equal and opposite) are left as they are,
    exact; for LIGGGHTS's arm ``r - delta/2`` it is the same approximation as without adhesion. With
    ``b = e x n``: ``v_e = v_t.e`` (taken >= 0, the direction flipped where it is negative) and
    ``omega_b = omega.b`` (the rim speed along ``e`` is ``r omega_b``) go in as the impact's tangential
    speed and spin, at speed ``(V^2 + v_e^2)^(1/2)`` and angle ``atan(v_e/V)``; out come
    ``v' = v_t - v_e e + v_e' e + e_n V n`` and ``omega' = omega - omega_b b + omega_b' b`` (no normal part
    where captured). Particles sharing ``(d, rho, E*, p_y, G, kappa)`` go in one call (each impact is
    integrated on its own, so the results are those of one call per particle; the pull-off of the whole
    law depends on each impact's maximum approach and is found per impact). ``"lammps_linear_history"``
    takes each impact's ``8 G* a_m`` as without adhesion (``a_m`` of the elastic impact at ``V``)."""
    from .impact import elastic_max_approach
    from .oblique.adhesive import adhesive_law, adhesive_oblique_impact, libm
    from .pair import ContactPair

    N = table.shape[0]
    codes = np.full(N, -1, dtype=np.int8)
    V_all = table[:, 7]
    sel = np.flatnonzero((V_all > 0.0) & (G > 0.0) & (table[:, 8] != _wall.NONE))
    if sel.size == 0:
        return codes

    def pick(c):
        return np.broadcast_to(c, (N,))[sel]

    vx, vy, vz = (pick(c) for c in vT)
    wx, wy, wz = (pick(c) for c in wT)
    ux, uy, uz = evaluate(_wall.unit_normal, *(pick(c) for c in nT), nout=3)
    r = 0.5 * d[sel]
    V = V_all[sel]
    # v_t and the contact point's slip u_t = v_t + r n x omega, as the rigid and table paths take them
    _, tx, ty, tz, sx, sy, sz = evaluate(_wall.contact_slip, vx, vy, vz, ux, uy, uz, wx, wy, wz, r, nout=7)
    slip = np.sqrt(sx * sx + sy * sy + sz * sz)
    tmag = np.sqrt(tx * tx + ty * ty + tz * tz)
    slips = slip > 0.0
    den = np.where(slips, slip, np.where(tmag > 0.0, tmag, 1.0))
    ex, ey, ez = (np.where(slips, a, b) / den for a, b in ((sx, tx), (sy, ty), (sz, tz)))
    bx, by, bz = ey * uz - ez * uy, ez * ux - ex * uz, ex * uy - ey * ux  # b = e x n
    v_e = tx * ex + ty * ey + tz * ez
    w_b = wx * bx + wy * by + wz * bz
    sign = np.where(v_e < 0.0, -1.0, 1.0)
    speed = np.hypot(V, v_e)
    angle = np.minimum(np.degrees(libm(math.atan2, np.abs(v_e), V)), np.nextafter(90.0, 0.0))
    rho_s, E_s, py_s, G_s, mu_s, kap_s = rho[sel], E[sel], p_y[sel], G[sel], mu[sel], kappa[sel]
    m = evaluate(_wall.sphere_mass, r, rho_s)[0]
    k_lin = np.zeros(sel.size)
    if tangential == "lammps_linear_history":  # 8 G* a_m = 2 kappa E* (r alpha_m)^(1/2), per impact
        k_lin = 2.0 * kap_s * E_s * np.sqrt(r * np.asarray(elastic_max_approach(V, E_s, r, m), dtype=float))

    cols = [r, rho_s, E_s, py_s, G_s, kap_s, k_lin]
    order = np.lexsort(cols)
    first = np.zeros(sel.size, dtype=bool)
    first[:1] = True
    for c in cols:
        c = c[order]
        first[1:] |= c[1:] != c[:-1]
    starts = np.flatnonzero(first)
    e_n = np.empty(sel.size)
    v1 = np.empty(sel.size)
    w1 = np.empty(sel.size)
    cap = np.empty(sel.size, dtype=bool)
    held = np.empty(sel.size, dtype=bool)
    code = np.empty(sel.size, dtype=np.int8)
    for a, b in zip(starts, [*starts[1:], sel.size]):
        g = order[a:b]
        k = g[0]
        pair = ContactPair.sphere_on_flat(
            float(r[k]), mass=float(m[k]), effective_modulus=float(E_s[k]), limiting_pressure=float(py_s[k])
        )
        name, params = adhesive_law(adhesion, None, float(G_s[k]))
        out = adhesive_oblique_impact(
            pair, speed[g], angle[g], mu_s[g], model=name, params=params, tangential=tangential,
            spin=sign[g] * w_b[g], kappa=float(kap_s[k]),
            tangential_stiffness=float(k_lin[k]) if tangential == "lammps_linear_history" else None,
        )  # fmt: skip
        e_n[g] = out.normal_restitution
        v1[g] = sign[g] * out.tangential_velocity
        w1[g] = sign[g] * out.rebound_spin
        cap[g] = out.captured
        held[g] = out.held
        code[g] = [OUTCOMES.index(x) for x in out.outcome]
    eV = np.where(cap, 0.0, e_n * V)
    rows = table[sel]
    rows[:, 0] = (tx - v_e * ex) + v1 * ex + eV * ux
    rows[:, 1] = (ty - v_e * ey) + v1 * ey + eV * uy
    rows[:, 2] = (tz - v_e * ez) + v1 * ez + eV * uz
    rows[:, 3] = (wx - w_b * bx) + w1 * bx
    rows[:, 4] = (wy - w_b * by) + w1 * by
    rows[:, 5] = (wz - w_b * bz) + w1 * bz
    rows[:, 6] = np.where(cap, 0.0, e_n)
    rows[:, 8] = np.where(cap, _wall.STUCK, np.where(held, _wall.ROLLING, _wall.SLIDING))
    table[sel] = rows
    codes[sel] = code
    return codes
