"""One sphere bouncing off, or sticking to, a flat, fixed, massive wall: scalar floats in and out.

The physics of :func:`microimpact.wall.wall_interaction` for one particle, written once; the array
path (:func:`~microimpact.engine.evaluate`) runs this function, and the C export
(:mod:`microimpact.cexport`) is its one second copy, tested bit for bit against it.

* **Normal**: the seed's elastic-plastic restitution (eq. 27, yield point eqs. 5, 7, 28) with
  Thornton & Ning's (1998) adhesive loss (:mod:`microimpact.core.adhesion`); ``R* = r``, ``m* = m``.
  Either the additive rule (``D`` NaN) or, given the whole law's correction ``D`` interpolated from
  its table (:func:`~microimpact.core.adhesion.corrected_restitution`), Thornton & Ning's whole law.
* **Tangential**: the rigid-body impulse with Coulomb friction for a solid sphere (``I = 2/5 m r^2``;
  Walton 1993; Brach 1988): the impulse that stops the slip of the contact point, ``2/7 m |u_t|``,
  if it lies within ``mu J_n`` (rolling), else ``mu J_n`` against the slip (sliding). Or, given a
  ratio ``F = |J_t|/(mu J_n)`` from the compliant contact of :mod:`microimpact.oblique`, that impulse.
* Kinematics: ``n`` is normalised here; ``v_n = v.n`` (``< 0``: approaching, ``V = -v_n``);
  ``u_t = v_t + r n x omega`` with ``v_t = v - v_n n``; after the impact ``v' = v_t + J_t/m + e V n``
  and ``omega' = omega - 5/(2 m r) n x J_t``. A particle not approaching is returned unchanged.
"""

from __future__ import annotations

import math

from . import adhesion
from ._jit import jitable
from .models import thornton_ning_1998_adhesive_plastic as _whole
from .models.thornton_ning_2016 import yield_point

__all__ = [
    "sphere_mass",
    "contact_slip",
    "unit_normal",
    "approach_and_slip",
    "slip_split",
    "whole_law_capture_velocity",
    "wall_impact",
    "WALL_FIELDS",
    "NONE",
    "ROLLING",
    "SLIDING",
    "STUCK",
]

#: ``regime`` of a particle not approaching the wall (passed through unchanged).
NONE = 0.0
#: ``regime`` of a particle whose contact point stopped slipping (within the Coulomb limit).
ROLLING = 1.0
#: ``regime`` of a particle that slid throughout (impulse at the Coulomb limit).
SLIDING = 2.0
#: ``regime`` of a particle that stuck (adhesion).
STUCK = 3.0
#: The results of :func:`wall_impact`, in order.
WALL_FIELDS = (
    "vx",
    "vy",
    "vz",
    "wx",
    "wy",
    "wz",
    "restitution",
    "normal_speed",
    "regime",
    "yield_velocity",
    "sticking_velocity",
)


@jitable
def sphere_mass(r, rho):
    """Mass of a sphere of radius ``r`` [m] and density ``rho`` [kg/m^3], ``4/3 pi r^3 rho`` [kg].

    ``r^3`` as ``r r r`` (no ``pow``: the same bits in Python, numba and C).
    """
    return 4.0 / 3.0 * math.pi * (r * r * r) * rho


@jitable
def contact_slip(vx, vy, vz, nx, ny, nz, wx, wy, wz, r):
    """``(v_n, v_t, u_t)`` of a sphere at a wall with unit normal ``n``: ``v_n = v.n``, ``v_t = v - v_n n``
    and the slip of the contact point ``u_t = v_t + r n x omega`` [m/s] (7 floats)."""
    vn = vx * nx + vy * ny + vz * nz
    tx = vx - vn * nx
    ty = vy - vn * ny
    tz = vz - vn * nz
    return (
        vn,
        tx,
        ty,
        tz,
        tx + r * (ny * wz - nz * wy),
        ty + r * (nz * wx - nx * wz),
        tz + r * (nx * wy - ny * wx),
    )


@jitable
def unit_normal(nx, ny, nz):
    """``n/|n|`` (3 floats); the caller refuses a zero vector."""
    length = math.sqrt(nx * nx + ny * ny + nz * nz)
    return nx / length, ny / length, nz / length


@jitable
def approach_and_slip(vx, vy, vz, nx, ny, nz, wx, wy, wz, d, rho, E, p_y):
    """``(V, |u_t|, V_y)``: normal impact speed (0 if not approaching), slip speed and yield velocity
    [m/s], as :func:`wall_impact` sees them (what the compliant impulse ratio is looked up with)."""
    ux, uy, uz = unit_normal(nx, ny, nz)
    r = 0.5 * d
    vn, tx, ty, tz, sx, sy, sz = contact_slip(vx, vy, vz, ux, uy, uz, wx, wy, wz, r)
    Vy = yield_point(E, r, sphere_mass(r, rho), p_y)[2]
    return (-vn if vn < 0.0 else 0.0), math.sqrt(sx * sx + sy * sy + sz * sz), Vy


@jitable
def slip_split(vx, vy, vz, nx, ny, nz, wx, wy, wz, d):
    """``(v_u, w_u, s_x, s_y, s_z)``: the centre's tangential velocity ``v_t`` and the rim velocity
    ``r n x omega`` along the unit slip direction ``s = u_t/|u_t|`` [m/s] (``v_u + w_u = |u_t|``), and
    ``s``; all 0 where nothing slips.

    A law whose arm is not ``r`` (LIGGGHTS's ``r - delta/2``) moves the centre and the rim by different
    impulses, so its outcome depends on the two parts of the slip, not only on their sum."""
    ux, uy, uz = unit_normal(nx, ny, nz)
    r = 0.5 * d
    _, tx, ty, tz, sx, sy, sz = contact_slip(vx, vy, vz, ux, uy, uz, wx, wy, wz, r)
    slip = math.sqrt(sx * sx + sy * sy + sz * sz)
    if not slip > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    vu = (tx * sx + ty * sy + tz * sz) / slip
    return vu, slip - vu, sx / slip, sy / slip, sz / slip


@jitable
def whole_law_capture_velocity(d, rho, E, p_y, G):
    """The capture speed [m/s] of Thornton & Ning's whole law for a sphere of diameter ``d`` [m] and
    density ``rho`` [kg/m^3] at the wall (``R* = r``, ``m* = m``; ``E = E*`` [Pa], ``p_y`` [Pa], ``G``
    [J/m^2]): the model's own sticking velocity
    (:func:`~microimpact.core.models.thornton_ning_1998_adhesive_plastic.sticking_velocity`), at and
    below which the whole law sticks; 0 without adhesion. What the wall reports as ``sticking_velocity``
    with ``adhesion=`` the whole law (its table's stick boundary lies within 1.5e-3 of it)."""
    r = 0.5 * d
    return _whole.sticking_velocity(E, r, sphere_mass(r, rho), p_y, (G,))


@jitable
def wall_impact(vx, vy, vz, nx, ny, nz, wx, wy, wz, d, rho, E, p_y, G, mu, F, D):
    """Outcome of one particle hitting the wall, in the order of :data:`WALL_FIELDS`.

    ``v`` [m/s] and ``omega`` [rad/s] the incoming velocity and spin, ``n`` the wall normal (out of
    the wall; any length > 0), ``d`` [m] and ``rho`` [kg/m^3] the sphere's, ``E = E*`` [Pa],
    ``p_y`` [Pa] (``inf``: never yields), ``G`` [J/m^2] the work of adhesion, ``mu`` the friction
    coefficient, ``F`` the compliant impulse ratio (negative where a law's impulse adds to the slip) or NaN
    for the rigid-body impulse (module docstring), ``D`` the whole adhesive law's correction to ``e^2``
    (:func:`~microimpact.core.adhesion.whole_law_correction`) or NaN for the additive rule. ``regime`` is :data:`NONE`, :data:`ROLLING`, :data:`SLIDING` or :data:`STUCK`. A
    zero normal gives NaN everywhere (the caller refuses it).
    """
    if nx == 0.0 and ny == 0.0 and nz == 0.0:
        nan = math.nan
        return nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan
    ux, uy, uz = unit_normal(nx, ny, nz)
    r = 0.5 * d
    m = sphere_mass(r, rho)
    Vy = yield_point(E, r, m, p_y)[2]
    Vs = adhesion.sticking_velocity(G, E, r, m)
    vn, tx, ty, tz, sx, sy, sz = contact_slip(vx, vy, vz, ux, uy, uz, wx, wy, wz, r)
    if not vn < 0.0:  # moving away (or along): no impact
        return vx, vy, vz, wx, wy, wz, 1.0, 0.0, NONE, Vy, Vs
    V = -vn
    if math.isnan(D):  # the additive rule
        e, stuck = adhesion.restitution(V, Vy, Vs)
    else:  # the whole law, through its table
        e, stuck = adhesion.corrected_restitution(V, Vy, Vs, D)
    if stuck == 1.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, V, STUCK, Vy, Vs
    jn = (1.0 + e) * V  # normal impulse / m
    slip = math.sqrt(sx * sx + sy * sy + sz * sz)
    limit = mu * jn  # Coulomb limit mu J_n / m
    if math.isnan(F):  # rigid body: stop the slip if the friction allows it
        rolling = (2.0 / 7.0) * slip <= limit
        scale = 2.0 / 7.0 if rolling else (limit / slip if slip > 0.0 else 0.0)
    else:  # compliant: |J_t| = F mu J_n along the slip
        rolling = F < 1.0
        scale = F * limit / slip if slip > 0.0 else 0.0
    jx = sx * -scale  # tangential impulse / m
    jy = sy * -scale
    jz = sz * -scale
    k = -2.5 / r  # omega' = omega - 5/(2 m r) n x J_t
    eV = e * V
    return (
        tx + jx + eV * ux,
        ty + jy + eV * uy,
        tz + jz + eV * uz,
        (uy * jz - uz * jy) * k + wx,
        (uz * jx - ux * jz) * k + wy,
        (ux * jy - uy * jx) * k + wz,
        e,
        V,
        ROLLING if rolling else SLIDING,
        Vy,
        Vs,
    )
