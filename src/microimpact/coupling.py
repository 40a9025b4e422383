"""Bounce or stick at a wall, for whole particle arrays: coupling to gas-particle flow codes.

The seed's last conclusion is that its model "can be easily coupled to numerical
simulations of gas-particle flows to calculate whether the particles stick or
bounce off the impacting surface". This module does that for an array of
particles hitting walls, in three parts:

* **Normal direction**: the seed's elastic-plastic restitution ``e_p(V/V_y)``
  (eqs. 22, 27, 28) of the normal impact speed ``V``, combined with the
  adhesion loss of Thornton & Ning (1998): the elastic-adhesive sticking
  velocity ``V_s`` (:func:`sticking_velocity`) enters as an additional energy
  loss, ``e^2 = e_p^2 - (V_s/V)^2``; the particle sticks when ``e_p V <= V_s``
  (:func:`adhesive_restitution`). With no adhesion (``G = 0``) nothing sticks
  and ``e = e_p``, the seed's model unchanged.
* **Tangential direction**: the rigid-body impulse model with Coulomb friction
  (Walton 1993; Brach 1988) for a solid sphere (moment of inertia
  ``I = 2/5 m r^2``): the tangential impulse that would stop the slip of the
  contact point is applied if it lies within the Coulomb limit ``mu J_n``
  ("rolling": the particle leaves rolling on the wall), otherwise the impulse is
  ``mu J_n`` against the slip ("sliding"). No energy is ever gained.
* **Export**: CSV tables of ``e`` and a self-contained C99 function computing
  the same outgoing velocity, spin and stick flag for one particle, for Fluent
  UDFs and OpenFOAM patch interaction models (:func:`generate_c_source`).

Sign conventions (used everywhere in this module and in the C code)
--------------------------------------------------------------------
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
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ._validation import check_nonnegative, check_positive
from .impact import _restitution, yield_velocity
from .materials import DEFAULT_K, Material, get_material
from .materials import effective_modulus as _effective_modulus

__all__ = [
    "STICKING_CONSTANT",
    "work_of_adhesion",
    "sticking_velocity",
    "adhesive_restitution",
    "wall_interaction",
    "WallInteraction",
    "restitution_table",
    "write_tables",
    "generate_c_source",
    "write_c_source",
]

#: ``14.18``: the constant of Thornton & Ning's (1998) sticking velocity. It is
#: ``2 x 7.092``, the JKR work (in units of ``(G^5 R*^4 / E*^2)^(1/3)``) needed to pull
#: a contact from zero approach (contact radius ``a_0``) to separation at
#: ``a_0 / 4^(2/3)``, with ``G`` the work of adhesion (pull-off force ``1.5 pi G R*``).
STICKING_CONSTANT = 14.18


# ----------------------------------------------------------------------------- adhesion
def work_of_adhesion(surface_energy_1, surface_energy_2=None):
    """Work of adhesion ``G`` [J/m^2] from the surface energies of the two solids.

    Dupre: ``G = gamma_1 + gamma_2 - gamma_12``. Without a measured interface
    energy ``gamma_12`` the usual estimate is the geometric mean (Berthelot /
    Fowkes rule for dispersive solids), ``G = 2 (gamma_1 gamma_2)^(1/2)``, and for
    two identical surfaces ``G = 2 gamma``.

    **The factor 2 that trips users**: a *surface energy* ``gamma`` is a
    property of one free surface (energy per area to create it); the *work of
    adhesion* ``G`` is the energy per area to separate an interface, which
    creates two surfaces. The JKR pull-off force is ``1.5 pi G R* = 3 pi gamma
    R*`` (identical solids). :func:`sticking_velocity` and
    :func:`wall_interaction` take the **work of adhesion** ``G``; this function
    takes **surface energies per surface** ``gamma`` and returns ``G``.

    Parameters
    ----------
    surface_energy_1 : array_like
        Surface energy ``gamma_1`` of the particle [J/m^2], >= 0.
    surface_energy_2 : array_like, optional
        Surface energy ``gamma_2`` of the wall [J/m^2]; default: same as the particle.

    Returns
    -------
    ndarray
        ``G = 2 (gamma_1 gamma_2)^(1/2)`` [J/m^2].

    Examples
    --------
    >>> float(work_of_adhesion(0.05))  # identical surfaces: G = 2 gamma
    0.1
    """
    g1 = check_nonnegative("surface_energy_1", surface_energy_1)
    g2 = g1 if surface_energy_2 is None else check_nonnegative("surface_energy_2", surface_energy_2)
    return 2.0 * np.sqrt(g1 * g2)


def sticking_velocity(work_of_adhesion, effective_modulus, effective_radius, effective_mass):
    """Elastic-adhesive sticking velocity of Thornton & Ning (1998) [m/s].

    ``V_s = (14.18 / m*)^(1/2) (G^5 R*^4 / E*^2)^(1/6)``

    the normal impact speed below which an elastic JKR contact cannot separate
    again: ``1/2 m* V_s^2`` is the work needed to break the adhesive contact.

    Parameters
    ----------
    work_of_adhesion : array_like
        ``G`` [J/m^2], the **work of adhesion** (energy per area to separate the
        interface; JKR pull-off force ``1.5 pi G R*``), **not** the surface
        energy per surface ``gamma``: for identical surfaces ``G = 2 gamma``
        (see :func:`work_of_adhesion`). ``G = 0`` gives ``V_s = 0``.
    effective_modulus : array_like
        ``E*`` [Pa].
    effective_radius : array_like
        ``R*`` [m].
    effective_mass : array_like
        ``m*`` [kg].

    Returns
    -------
    ndarray
        ``V_s`` [m/s].

    Notes
    -----
    Thornton & Ning (1998), Powder Technol. 99:154-162, eq. for ``V_s``; the
    constant 14.18 is twice the JKR separation work 7.09 (see
    :data:`STICKING_CONSTANT`), checked in the tests by integrating the JKR
    force-approach curve.

    Examples
    --------
    >>> m = 4 / 3 * math.pi * 0.5e-6**3 * 1350.0   # 1 um NH4Fl sphere
    >>> round(float(sticking_velocity(0.1, 1.31e9, 0.5e-6, m)), 3)
    1.197
    """
    G = check_nonnegative("work_of_adhesion", work_of_adhesion)
    E = check_positive("effective_modulus", effective_modulus)
    R = check_positive("effective_radius", effective_radius)
    m = check_positive("effective_mass", effective_mass)
    return np.sqrt(STICKING_CONSTANT / m) * (G**5 * R**4 / E**2) ** (1.0 / 6.0)


def _adhesive(V, e_p, Vs):
    """``(e, stuck)`` from the plastic restitution ``e_p`` and ``V_s`` (no checks)."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        stuck = (Vs > 0.0) & (e_p * V <= Vs)
        ratio = np.where(stuck, 0.0, Vs / np.where(V > 0.0, V, 1.0))
        e = np.sqrt(np.maximum(e_p * e_p - ratio * ratio, 0.0))
    return np.where(stuck, 0.0, e), stuck


def adhesive_restitution(velocity, yield_velocity, sticking_velocity):
    """Normal restitution with plastic and adhesive losses (Thornton & Ning 1998).

    ``e^2 = e_p^2 - (V_s / V)^2``, where ``e_p`` is the seed's elastic-plastic
    restitution (eq. 27, :func:`~microimpact.impact.restitution_coefficient`)
    and ``V_s`` the sticking velocity (:func:`sticking_velocity`). The two
    losses add as energies. The particle sticks (``e = 0``) when
    ``e_p V <= V_s``. With ``V_s = 0`` (no adhesion) nothing sticks and
    ``e = e_p``: the seed's model unchanged.

    Parameters
    ----------
    velocity : array_like
        Normal impact speed ``V`` [m/s], finite, >= 0.
    yield_velocity : array_like
        ``V_y`` [m/s] (eq. 28); ``inf`` for a wall that never yields.
    sticking_velocity : array_like
        ``V_s`` [m/s], >= 0.

    Returns
    -------
    ndarray
        ``e`` [-], 0 where the particle sticks.

    Examples
    --------
    >>> adhesive_restitution([0.5, 2.0, 50.0], 7.52, 1.0).round(4)
    array([0.    , 0.866 , 0.7245])
    """
    V = check_nonnegative("velocity", velocity)
    if np.any(np.isinf(V)):
        raise ValueError(f"velocity must be finite, got {float(V[np.isinf(V)].flat[0])!r}")
    Vy = check_positive("yield_velocity", yield_velocity, allow_inf=True)
    Vs = check_nonnegative("sticking_velocity", sticking_velocity)
    e, _ = _adhesive(V, _restitution(V, Vy), Vs)
    return e


# ----------------------------------------------------------------------------- wall interaction
#: Codes of :attr:`WallInteraction.regime`.
REGIMES = {0: "none", 1: "rolling", 2: "sliding", 3: "stuck"}


@dataclass(frozen=True, eq=False)
class WallInteraction:
    """Outcome of :func:`wall_interaction` for ``N`` particles (SI units).

    Attributes
    ----------
    velocity : ndarray (N, 3)
        Outgoing velocity [m/s]; zero where stuck; the incoming one where the
        particle was not approaching.
    spin : ndarray (N, 3) or None
        Outgoing angular velocity [rad/s]; None when no spin was given and
        there is no friction.
    stuck : ndarray of bool (N,)
        True where the particle sticks (adhesion; never with ``G = 0``).
    restitution : ndarray (N,)
        Normal restitution ``e`` used: ``-v'.n / v.n``; 0 where stuck, 1 where
        the particle was not approaching.
    normal_speed : ndarray (N,)
        Incoming normal impact speed ``V = -v.n`` [m/s]; 0 where not approaching.
    approaching : ndarray of bool (N,)
        False where ``v . n >= 0``: no impact, passed through unchanged.
    rolling : ndarray of bool (N,)
        True where the tangential impulse stopped the slip (within the Coulomb limit).
    yield_velocity, sticking_velocity : ndarray (N,)
        ``V_y`` (eq. 28) and ``V_s`` (Thornton & Ning) [m/s] of each particle.
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
    _single: bool = field(default=False, repr=False)

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


def _vectors(name, value, n_expected=None):
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


def _cross(a, b):
    """Cross product of component rows: ``a``, ``b`` shaped (3, ...)."""
    return np.stack([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


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
    single = np.ndim(velocity) == 1
    v = _vectors("velocity", velocity)
    N = v.shape[0]
    nrm = _vectors("normal", normal)
    if nrm.shape[0] not in (1, N):
        raise ValueError(f"normal must be one vector or one per particle ({N}), got {nrm.shape[0]}")
    length = np.sqrt(np.einsum("ij,ij->i", nrm, nrm))
    if np.any(length == 0.0):
        raise ValueError("normal must not be a zero vector")
    nrm = nrm / length[:, None]  # (1, 3) or (N, 3)

    d = _per_particle("diameter", check_positive("diameter", diameter), N)
    mats = _materials(material, N) if material is not None else None
    if density is None:
        if mats is None:
            raise ValueError("density is needed (or give material=...)")
        rho = mats[2]
    else:
        rho = _per_particle("density", check_positive("density", density), N)

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
    has_spin = spin is not None
    if has_spin:
        w = _vectors("spin", spin)
        if w.shape[0] not in (1, N):
            raise ValueError(f"spin must have one vector per particle ({N}), got {w.shape[0]}")
        w = np.broadcast_to(w, (N, 3))

    r = 0.5 * d
    m = 4.0 / 3.0 * np.pi * r**3 * rho  # as materials.sphere_mass: same bits as ContactPair
    Vy = np.broadcast_to(yield_velocity(p_y, E, r, m), (N,))
    Vs = np.broadcast_to(sticking_velocity(G, E, r, m), (N,)) if np.any(G > 0.0) else np.zeros(N)

    # Components as contiguous rows (structure of arrays): (3, N) and (3, N or 1).
    vT = np.ascontiguousarray(v.T)
    nT = np.ascontiguousarray(nrm.T)

    # Normal direction.
    vn = vT[0] * nT[0] + vT[1] * nT[1] + vT[2] * nT[2]
    approaching = vn < 0.0
    V = np.where(approaching, -vn, 0.0)
    e, stuck = _adhesive(V, _restitution(V, Vy), Vs)
    stuck &= approaching
    e = np.where(approaching, e, 1.0)
    Jn_over_m = (1.0 + e) * V  # normal impulse / m

    # Tangential direction: slip of the contact point, u_t = v_t + r n x omega.
    # (In-place updates keep the number of passes over (3, N) arrays low.)
    vtT = vT - vn * nT
    if has_spin:
        wT = np.ascontiguousarray(w.T)
        utT = _cross(nT, wT)
        utT *= r
        utT += vtT
    else:
        utT = vtT
    ut_mag = np.sqrt(utT[0] * utT[0] + utT[1] * utT[1] + utT[2] * utT[2])
    stop = (2.0 / 7.0) * ut_mag  # |J_stop| / m
    limit = mu * Jn_over_m  # mu J_n / m; 0 where not approaching (V = 0)
    rolling = approaching & ~stuck & (stop <= limit)
    with np.errstate(invalid="ignore", divide="ignore"):
        scale = np.where(rolling, 2.0 / 7.0, np.where(ut_mag > 0.0, limit / ut_mag, 0.0))
    JtT = utT * -scale  # tangential impulse / m; 0 where not approaching

    v_outT = vtT + JtT
    v_outT += np.where(approaching, e * V, vn) * nT
    v_out = np.ascontiguousarray(v_outT.T)
    away = ~approaching
    if away.any():
        v_out[away] = v[away]  # passed through bit for bit
    v_out[stuck] = 0.0
    w_out = None
    if has_spin or np.any(mu > 0.0):
        # omega' = omega + (-r n) x J / I = omega - 5/(2 m r) n x J
        w_outT = _cross(nT, JtT)
        w_outT *= -2.5 / r
        if has_spin:
            w_outT += wT
        w_out = np.ascontiguousarray(w_outT.T)
        w_out[stuck] = 0.0
    return WallInteraction(
        velocity=v_out[0] if single else v_out,
        spin=None if w_out is None else (w_out[0] if single else w_out),
        stuck=stuck[0] if single else stuck,
        restitution=e[0] if single else e,
        normal_speed=V[0] if single else V,
        approaching=approaching[0] if single else approaching,
        rolling=rolling[0] if single else rolling,
        yield_velocity=Vy[0] if single else np.array(Vy),
        sticking_velocity=Vs[0] if single else np.array(Vs),
        _single=single,
    )


# ----------------------------------------------------------------------------- tables
def restitution_table(v_over_vy, vs_over_vy_values):
    """Normal restitution ``e`` against ``V/V_y`` for several ``V_s/V_y`` (a lookup table for other codes).

    Everything scales: ``e`` depends on ``V`` only through ``V/V_y`` (seed
    eq. 27) and on adhesion only through ``V_s/V`` (:func:`adhesive_restitution`).

    Parameters
    ----------
    v_over_vy : array_like (M,)
        Normal impact speed over the yield velocity, ``V/V_y`` >= 0.
    vs_over_vy_values : array_like (K,)
        Sticking velocity over yield velocity, ``V_s/V_y`` >= 0 (0: no adhesion).

    Returns
    -------
    ndarray (M, K)
        ``e``; 0 where the particle sticks.

    Examples
    --------
    >>> restitution_table([0.5, 2.0, 10.0], [0.0, 0.5]).round(4)
    array([[1.    , 0.    ],
           [0.9306, 0.8964],
           [0.6586, 0.6567]])
    """
    v = np.atleast_1d(check_nonnegative("v_over_vy", v_over_vy)).reshape(-1)
    s = np.atleast_1d(check_nonnegative("vs_over_vy_values", vs_over_vy_values)).reshape(-1)
    return adhesive_restitution(v[:, None], 1.0, s[None, :])


def _fmt_num(x):
    """Shortest text that reads back to the same double."""
    x = float(x)
    if not math.isfinite(x):
        return "inf" if x > 0 else ("-inf" if x < 0 else "nan")
    return str(int(x)) if x.is_integer() and abs(x) < 1e15 else repr(x)


def _slug(text):
    keep = "".join(c if c.isalnum() else "_" for c in str(text).lower())
    return "_".join(p for p in keep.split("_") if p) or "pair"


def _write_csv(path, comments, header, rows):
    with open(path, "w", encoding="utf-8", newline="") as fh:
        for c in comments:
            fh.write(f"# {c}\n")
        fh.write(",".join(header) + "\n")
        for row in rows:
            fh.write(",".join(_fmt_num(float(x)) for x in row) + "\n")


def _sized_pair(pair, diameter):
    if pair.density is None:
        raise ValueError("the pair needs a particle density to be rescaled to other diameters")
    return pair.resized(radius=0.5 * float(check_positive("diameter", diameter)))


#: Default grid of :func:`write_tables`: ``V/V_y`` from 0 to 100.
DEFAULT_V_OVER_VY = np.concatenate([np.linspace(0.0, 2.0, 41)[:-1], np.geomspace(2.0, 100.0, 80)])
#: Default ``V_s/V_y`` columns of the dimensionless table.
DEFAULT_VS_OVER_VY = (0.0, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0)
#: Default normal speeds of the per-size tables [m/s].
DEFAULT_SPEEDS = np.geomspace(0.01, 200.0, 161)


def write_tables(
    directory,
    pairs,
    diameters=None,
    velocities=None,
    *,
    work_of_adhesion=0.0,
    v_over_vy=None,
    vs_over_vy_values=DEFAULT_VS_OVER_VY,
):
    """Write restitution tables as CSV for use in other codes.

    Files (units in the header; ``#`` lines are comments):

    * ``restitution_vs_v_over_vy.csv``: ``e`` against ``V/V_y`` with one column
      per ``V_s/V_y`` value (:func:`restitution_table`); valid for any pair.
    * ``restitution_<pair>_d<diameter>um.csv`` for each pair and diameter:
      normal impact speed [m/s], ``e`` [-] and the stick flag (0/1), with the
      pair's ``V_y`` and the size's ``V_s`` in the comments.

    Parameters
    ----------
    directory : path
        Created if missing.
    pairs : ContactPair or sequence of ContactPair
        Sphere-on-flat pairs with a known density (rescaled to each diameter).
    diameters : sequence of float, optional
        Particle diameters [m]; default each pair's own.
    velocities : array_like, optional
        Normal impact speeds [m/s]; default :data:`DEFAULT_SPEEDS` (0.01-200 m/s).
    work_of_adhesion : float, optional
        ``G`` [J/m^2] (work of adhesion, not surface energy; see :func:`work_of_adhesion`).
    v_over_vy, vs_over_vy_values : array_like, optional
        Grid of the dimensionless table.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    from pathlib import Path

    from .pair import ContactPair

    out_dir = Path(directory)
    out_dir.mkdir(parents=True, exist_ok=True)
    pairs = [pairs] if isinstance(pairs, ContactPair) else list(pairs)
    if not pairs:
        raise ValueError("pairs: give at least one ContactPair")
    G = float(check_nonnegative("work_of_adhesion", work_of_adhesion))
    v = DEFAULT_V_OVER_VY if v_over_vy is None else np.atleast_1d(check_nonnegative("v_over_vy", v_over_vy))
    s = np.atleast_1d(check_nonnegative("vs_over_vy_values", vs_over_vy_values)).reshape(-1)
    V = DEFAULT_SPEEDS if velocities is None else np.atleast_1d(check_nonnegative("velocities", velocities))

    written = []
    path = out_dir / "restitution_vs_v_over_vy.csv"
    table = restitution_table(v, s)
    _write_csv(
        path,
        [
            "microimpact: normal restitution e against V/V_y, one column per V_s/V_y",
            "seed eq. 27 with the adhesive loss of Thornton & Ning (1998): e^2 = e_p^2 - (V_s/V)^2, "
            "e = 0 (stick) when e_p V <= V_s",
            "V: normal impact speed, V_y: yield velocity (eq. 28), V_s: sticking velocity",
        ],
        ["V/V_y [-]"] + [f"e at V_s/V_y={_fmt_num(x)} [-]" for x in s],
        np.column_stack([v, table]),
    )
    written.append(path)

    multi = len(pairs) > 1
    for i, pair in enumerate(pairs):
        sizes = [2.0 * pair.effective_radius] if diameters is None else list(np.atleast_1d(diameters))
        tag = f"{_slug(pair.label or f'pair{i}')}_" if multi else ""
        for d in sizes:
            p = _sized_pair(pair, d)
            Vy = p.yield_velocity
            Vs = float(sticking_velocity(G, p.effective_modulus, p.effective_radius, p.effective_mass))
            e = adhesive_restitution(V, Vy, Vs)
            stuck = (Vs > 0.0) & (e == 0.0)
            path = out_dir / f"restitution_{tag}d{float(d) * 1e6:g}um.csv"
            _write_csv(
                path,
                [
                    f"microimpact: normal restitution of {pair.label or 'a sphere'} on a flat, "
                    f"diameter {float(d):.6g} m",
                    f"E* = {p.effective_modulus:.6g} Pa, p_y = {p.limiting_pressure:.6g} Pa, "
                    f"density = {pair.density:.6g} kg/m^3, work of adhesion G = {G:.6g} J/m^2",
                    f"yield velocity V_y = {Vy:.10g} m/s, sticking velocity V_s = {Vs:.10g} m/s",
                ],
                ["normal speed [m/s]", "restitution e [-]", "stuck [0/1]"],
                np.column_stack([V, e, stuck.astype(float)]),
            )
            written.append(path)
    return written


# ----------------------------------------------------------------------------- C export
_C_TEMPLATE = r"""/*
 * microimpact_wall.c -- bounce or stick of one particle at a wall (generated by microimpact {version}).
 *
 * Self-contained C99, SI units. Computes exactly what the Python function
 * microimpact.coupling.wall_interaction computes for one particle:
 *   normal:     the elastic-plastic restitution e_p(V/V_y) of Aerosol Sci. Tech. 50(4):321 (2016),
 *               eqs. 22, 27, 28, with the adhesive loss of Thornton & Ning (1998):
 *               e^2 = e_p^2 - (V_s/V)^2, stick when e_p V <= V_s,
 *               V_s = (14.18/m)^(1/2) (G^5 R^4 / E*^2)^(1/6), G = work of adhesion
 *               (NOT the surface energy per surface: G = 2 gamma for identical surfaces);
 *   tangential: rigid-body Coulomb impulse model of a solid sphere (I = 2/5 m r^2):
 *               rolling (slip stopped, J_t = -2m/7 u_t) if |J_t| <= mu J_n, else sliding.
 *
 * Conventions: n points OUT OF THE WALL INTO THE FLUID (it is normalised here);
 * velocities are relative to the wall; spins are angular velocity vectors [rad/s].
 * Return value:  1 stuck (v_out = omega_out = 0, *e_n = 0),
 *                0 bounced,
 *               -1 not approaching (v.n >= 0): outputs = inputs, *e_n = 1,
 *               -2 invalid input (diameter/density <= 0, zero normal): outputs = inputs.
 * omega_in may be NULL (no spin); omega_out and e_n may be NULL.
 *
 * Parameters baked in below (microimpact_wall_default): {description}
 *
 * Fluent (DEFINE_DPM_BC UDF; not compiled by microimpact -- adapt to your version):
 *   #include "udf.h"
 *   #include "microimpact_wall.c"
 *   DEFINE_DPM_BC(microimpact_bc, p, t, f, f_normal, dim)
 *   {{
 *       real A[ND_ND]; double v[3] = {{0, 0, 0}}, n[3] = {{0, 0, 0}}, vo[3], wo[3], e, a; int i;
 *       F_AREA(A, f, t); a = NV_MAG(A);           -- F_AREA points out of the fluid: negate it
 *       for (i = 0; i < dim; i++) {{ v[i] = P_VEL(p)[i]; n[i] = -A[i] / a; }}
 *       if (microimpact_wall_interaction(v, n, NULL, P_DIAM(p), P_RHO(p),
 *                                        &microimpact_wall_default, vo, wo, &e) == 1)
 *           return PATH_END;                       -- stuck: trapped on the wall
 *       for (i = 0; i < dim; i++) P_VEL(p)[i] = vo[i];
 *       return PATH_ACTIVE;
 *   }}
 *   (Newer Fluent versions name the particle tp and the macros TP_VEL(tp), TP_DIAM(tp), TP_RHO(tp);
 *    for a moving wall subtract the wall velocity before and add it after.)
 *
 * OpenFOAM (a custom PatchInteractionModel; not compiled by microimpact):
 *   template<class CloudType> bool MyWallModel<CloudType>::correct
 *   (typename CloudType::parcelType& p, const polyPatch& pp, bool& keepParticle)
 *   {{
 *       vector nw, Up;  this->owner().patchData(p, pp, nw, Up);   -- nw points out of the domain
 *       const vector Urel = p.U() - Up;
 *       double v[3] = {{Urel.x(), Urel.y(), Urel.z()}}, n[3] = {{-nw.x(), -nw.y(), -nw.z()}}, vo[3], wo[3], e;
 *       keepParticle = true;
 *       if (microimpact_wall_interaction(v, n, NULL, p.d(), p.rho(), &params_, vo, wo, &e) == 1)
 *       {{ p.active(false); p.U() = Zero; return true; }}        -- stuck
 *       p.U() = vector(vo[0], vo[1], vo[2]) + Up;
 *       return true;
 *   }}
 *   and include this file (extern "C" is not needed when it is compiled as part of the C++ source).
 */
#include <math.h>

typedef struct {{
    double effective_modulus;  /* E* [Pa] of the particle-wall pair */
    double limiting_pressure;  /* p_y [Pa]; INFINITY: the contact never yields */
    double work_of_adhesion;   /* G [J/m^2], work of adhesion (2 gamma for identical surfaces); 0: none */
    double friction;           /* Coulomb friction coefficient mu [-] */
}} microimpact_wall_params;

#if defined(__GNUC__)
#define MICROIMPACT_UNUSED __attribute__((unused))
#else
#define MICROIMPACT_UNUSED
#endif

static const microimpact_wall_params microimpact_wall_default MICROIMPACT_UNUSED = {{
    {E}, {p_y}, {G}, {mu}
}};

#define MICROIMPACT_PI 3.141592653589793
#define MICROIMPACT_STICKING_CONSTANT {stick}

static double microimpact_dot(const double a[3], const double b[3])
{{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}}

static void microimpact_cross(const double a[3], const double b[3], double c[3])
{{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}}

/* Yield velocity, 1/2 m V_y^2 = 2/5 P_y alpha_y (eq. 28) [m/s]. */
double microimpact_yield_velocity(double p_y, double E, double r, double m)
{{
    double a_y, alpha_y, P_y;
    if (isinf(p_y)) return INFINITY;
    a_y = MICROIMPACT_PI * p_y * r / (2.0 * E);
    alpha_y = a_y * a_y / r;
    P_y = 4.0 / 3.0 * E * sqrt(r) * pow(alpha_y, 1.5);
    return sqrt(0.8 * P_y * alpha_y / m);
}}

/* Thornton & Ning (1998) sticking velocity [m/s]; G is the work of adhesion. */
double microimpact_sticking_velocity(double G, double E, double r, double m)
{{
    return sqrt(MICROIMPACT_STICKING_CONSTANT / m) * pow(pow(G, 5.0) * pow(r, 4.0) / pow(E, 2.0), 1.0 / 6.0);
}}

/* Seed restitution e_p(V/V_y), eq. 27 with eq. 22. */
double microimpact_restitution(double V, double V_y)
{{
    double v, q;
    v = isinf(V_y) ? 0.0 : V / V_y;
    if (v <= 1.0) return 1.0;
    q = sqrt((24.0 - 4.0 / (v * v)) / 5.0);   /* q = s / v, s = ((24 v^2 - 4)/5)^(1/2) */
    return 0.5 * q / sqrt(sqrt((1.0 + v * q) / 3.0));   /* e = P^ / (A^(1/4) v), A = (1 + s)/3 */
}}

int microimpact_wall_interaction(const double v_in[3], const double n_in[3], const double omega_in[3],
                                 double diameter, double density, const microimpact_wall_params *params,
                                 double v_out[3], double omega_out[3], double *e_n)
{{
    double n[3], w[3], vt[3], ut[3], nxw[3], nxj[3], jt[3];
    double len, r, m, V_y, V_s, vn, V, e_p, e, ratio, jn, ut_mag, stop, limit, scale;
    int i, stuck;

    for (i = 0; i < 3; i++) w[i] = omega_in ? omega_in[i] : 0.0;
    for (i = 0; i < 3; i++) {{ v_out[i] = v_in[i]; if (omega_out) omega_out[i] = w[i]; }}
    len = sqrt(microimpact_dot(n_in, n_in));
    if (!(diameter > 0.0) || !(density > 0.0) || !(len > 0.0)) return -2;
    for (i = 0; i < 3; i++) n[i] = n_in[i] / len;

    vn = microimpact_dot(v_in, n);
    if (!(vn < 0.0)) {{ if (e_n) *e_n = 1.0; return -1; }}
    V = -vn;

    r = 0.5 * diameter;
    m = 4.0 / 3.0 * MICROIMPACT_PI * pow(r, 3.0) * density;
    V_y = microimpact_yield_velocity(params->limiting_pressure, params->effective_modulus, r, m);
    V_s = microimpact_sticking_velocity(params->work_of_adhesion, params->effective_modulus, r, m);

    /* normal: seed restitution with the adhesive loss */
    e_p = microimpact_restitution(V, V_y);
    stuck = (V_s > 0.0) && (e_p * V <= V_s);
    if (stuck) {{
        for (i = 0; i < 3; i++) {{ v_out[i] = 0.0; if (omega_out) omega_out[i] = 0.0; }}
        if (e_n) *e_n = 0.0;
        return 1;
    }}
    ratio = V_s / V;
    e = sqrt(fmax(e_p * e_p - ratio * ratio, 0.0));
    jn = (1.0 + e) * V;                      /* normal impulse / m */

    /* tangential: slip of the contact point u_t = v_t + r n x omega */
    microimpact_cross(n, w, nxw);
    for (i = 0; i < 3; i++) {{
        vt[i] = v_in[i] - vn * n[i];
        ut[i] = vt[i] + r * nxw[i];
    }}
    ut_mag = sqrt(microimpact_dot(ut, ut));
    stop = (2.0 / 7.0) * ut_mag;             /* |impulse that stops the slip| / m */
    limit = params->friction * jn;           /* mu J_n / m */
    if (stop <= limit) scale = 2.0 / 7.0;    /* rolling */
    else scale = ut_mag > 0.0 ? limit / ut_mag : 0.0;  /* sliding */
    for (i = 0; i < 3; i++) jt[i] = -scale * ut[i];

    for (i = 0; i < 3; i++) v_out[i] = vt[i] + jt[i] + (e * V) * n[i];
    if (omega_out) {{
        microimpact_cross(n, jt, nxj);
        for (i = 0; i < 3; i++) omega_out[i] = w[i] - (2.5 / r) * nxj[i];
    }}
    if (e_n) *e_n = e;
    return 0;
}}
"""


def _c_double(x):
    x = float(x)
    if math.isinf(x):
        return "INFINITY"
    return repr(x)


def generate_c_source(
    pair=None,
    *,
    effective_modulus=None,
    limiting_pressure=None,
    work_of_adhesion=0.0,
    friction=0.0,
) -> str:
    """A self-contained C99 source computing :func:`wall_interaction` for one particle.

    The file defines ``microimpact_wall_params`` (a struct of ``E*`` [Pa],
    ``p_y`` [Pa], ``G`` [J/m^2], ``mu`` [-]), a constant
    ``microimpact_wall_default`` holding the values given here, and::

        int microimpact_wall_interaction(const double v_in[3], const double n[3],
                                         const double omega_in[3], double diameter, double density,
                                         const microimpact_wall_params *params,
                                         double v_out[3], double omega_out[3], double *e_n);

    returning 1 when the particle sticks, 0 when it bounces, -1 when it is not
    approaching the wall (``v.n >= 0``, outputs = inputs) and -2 on invalid
    input. SI units; ``n`` points out of the wall into the fluid. Its results
    equal the Python function's to rounding (the tests check 1e-12).

    Use in CFD codes (sketches in the file's header comment; microimpact has
    not compiled them): in a Fluent ``DEFINE_DPM_BC`` UDF, ``#include`` the file,
    take ``P_VEL(p)``, ``P_DIAM(p)``, ``P_RHO(p)`` and the normal ``-F_AREA/|F_AREA|``
    (Fluent's face area vector points out of the fluid), write ``v_out`` back to
    ``P_VEL(p)`` and return ``PATH_END`` when stuck, ``PATH_ACTIVE`` otherwise. In
    OpenFOAM, write a ``PatchInteractionModel`` whose ``correct(p, pp,
    keepParticle)`` gets ``nw, Up`` from ``owner().patchData``, calls the function
    with ``p.U() - Up`` and ``-nw``, and deactivates stuck parcels.

    Parameters
    ----------
    pair : ContactPair, optional
        Takes ``E*`` and ``p_y`` from it.
    effective_modulus, limiting_pressure : float, optional
        ``E*`` [Pa], ``p_y`` [Pa] (override the pair's).
    work_of_adhesion : float, optional
        ``G`` [J/m^2], the work of adhesion (``2 gamma`` for identical surfaces); default 0.
    friction : float, optional
        Coulomb coefficient ``mu`` [-]; default 0.

    Returns
    -------
    str
        The C99 source text.

    Raises
    ------
    ValueError
        If neither a pair nor both ``effective_modulus`` and ``limiting_pressure``
        are given, or a value is out of range.
    """
    from . import __version__

    E = effective_modulus if effective_modulus is not None else (pair.effective_modulus if pair else None)
    p_y = limiting_pressure if limiting_pressure is not None else (pair.limiting_pressure if pair else None)
    if E is None or p_y is None:
        raise ValueError("give a pair or both effective_modulus and limiting_pressure")
    E = float(check_positive("effective_modulus", E))
    p_y = float(check_positive("limiting_pressure", p_y, allow_inf=True))
    G = float(check_nonnegative("work_of_adhesion", work_of_adhesion))
    mu = float(check_nonnegative("friction", friction))
    if math.isinf(G) or math.isinf(mu):
        raise ValueError("work_of_adhesion and friction must be finite")
    label = f"{pair.label}; " if pair is not None and pair.label else ""
    desc = f"{label}E* = {E:.6g} Pa, p_y = {p_y:.6g} Pa, G = {G:.6g} J/m^2, mu = {mu:.6g}"
    return _C_TEMPLATE.format(
        version=__version__,
        description=desc,
        E=_c_double(E),
        p_y=_c_double(p_y),
        G=_c_double(G),
        mu=_c_double(mu),
        stick=repr(STICKING_CONSTANT),
    )


def write_c_source(path, pair=None, **kwargs):
    """Write the C99 source of :func:`generate_c_source` to a file.

    Parameters
    ----------
    path : str or os.PathLike
        File to write (overwritten; missing parent directories are made), or an
        existing directory, in which case the file is ``microimpact_wall.c`` in it.
    pair : ContactPair, optional
        Takes ``E*`` [Pa] and ``p_y`` [Pa] from it.
    **kwargs
        ``effective_modulus`` [Pa], ``limiting_pressure`` [Pa], ``work_of_adhesion``
        ``G`` [J/m^2] and ``friction`` ``mu`` [-], as for :func:`generate_c_source`.

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    ValueError
        If neither a pair nor both ``effective_modulus`` and ``limiting_pressure`` are
        given, or a value is out of range.
    """
    from pathlib import Path

    path = Path(path)
    if path.is_dir():
        path = path / "microimpact_wall.c"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(generate_c_source(pair, **kwargs), encoding="utf-8")
    return path
