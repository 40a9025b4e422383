"""Example: particles in an impinging stagnation-point flow, bouncing or sticking on the plate.

A case a CFD user recognises, small enough to follow by hand. Gas: the
inviscid axisymmetric stagnation-point flow onto a plate at ``z = 0``,

    u_r = a r / 2,   u_z = -a z,        a = U / H  [1/s],

the flow at the centre of an impinging jet of speed ``U`` issuing at height
``H`` above the plate. Particles (diameter ``d``, density ``rho``) start at
``z = H`` with the gas velocity, spread over the jet cross-section
``r <= R_jet`` (equal area, hence equal flux, per particle), and follow
Stokes drag with Cunningham's slip correction,

    dv/dt = (u(x) - v) / tau,   tau = rho d^2 C_c / (18 mu),
    C_c = 1 + Kn (1.257 + 0.4 exp(-1.1/Kn)),   Kn = 2 lambda / d

(Davies 1945; air: ``lambda = 68 nm``, ``mu = 1.81e-5 Pa s``). Gravity,
Brownian diffusion, lift and the gas boundary layer are left out.

Because the flow is linear, the flight is solved in closed form: the axial
motion is a damped oscillator ``z'' + z'/tau + (a/tau) z = 0``, which reaches
the wall only if it is under-damped, i.e. above the critical Stokes number
``Stk = a tau = 1/4`` (particles below it follow the streamlines and never
touch the plate by impaction); the radial motion ``r'' + r'/tau - a r/(2 tau) = 0``
grows exponentially. (A numerical integration with ``scipy.integrate.solve_ivp``
and an event at the wall, ``method="ode"``, is kept as a cross-check.) Spin
decays with the rotational relaxation time ``rho d^2 / (60 mu)`` (the flow is
irrotational).

At the wall :func:`microimpact.wall.wall_interaction` decides: stick
(deposited) or bounce with the seed's restitution, adhesion and Coulomb
friction. A bounced particle flies again and may hit the plate again (up to
``max_impacts`` impacts); it counts as **not deposited** if it leaves the plate
(``r > R_plate`` at an impact), rises back above ``z = H``, or is still
bouncing after ``max_impacts``. With ``max_impacts=1`` the first impact decides,
as in the usual "a bounce is a loss" reading of impactor data.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ._optional import require
from ._validation import TINY_NORMAL, check_in_range, check_nonnegative, check_number, check_positive, describe_value
from .wall import wall_interaction

__all__ = [
    "AIR_MEAN_FREE_PATH",
    "AIR_VISCOSITY",
    "CRITICAL_STOKES_NUMBER",
    "cunningham_correction",
    "relaxation_time",
    "stokes_number",
    "flight_to_wall",
    "flight_to_wall_ode",
    "DepositionResult",
    "DepositionBoundWarning",
    "simulate_deposition",
    "plot_deposition",
]

#: Mean free path of air molecules at 293 K and 101.3 kPa [m].
AIR_MEAN_FREE_PATH = 68e-9
#: Dynamic viscosity of air at 293 K [Pa s].
AIR_VISCOSITY = 1.81e-5
#: Stokes number ``a tau`` above which particles reach the plate of a stagnation-point flow.
CRITICAL_STOKES_NUMBER = 0.25


def cunningham_correction(diameter, mean_free_path=AIR_MEAN_FREE_PATH):
    """Cunningham slip correction ``C_c = 1 + Kn (1.257 + 0.4 exp(-1.1/Kn))``, ``Kn = 2 lambda/d`` [-].

    Davies (1945) coefficients, as in Hinds, Aerosol Technology (2nd ed., 1999),
    eq. 3.20. Not part of the seed paper: it sets the drag of the example flow.

    Parameters
    ----------
    diameter : array_like
        Particle diameter ``d`` [m], positive.
    mean_free_path : array_like, optional
        Mean free path of the gas molecules ``lambda`` [m]; default
        :data:`AIR_MEAN_FREE_PATH` (air at 293 K, 101.3 kPa).

    Returns
    -------
    ndarray
        Slip correction factor ``C_c`` [-], >= 1.

    Raises
    ------
    ValueError
        If ``diameter`` or ``mean_free_path`` is not positive.

    Examples
    --------
    >>> round(float(cunningham_correction(1e-6, 66e-9)), 3)  # Kn = 0.132
    1.166
    """
    d = check_positive("diameter", diameter)
    lam = check_positive("mean_free_path", mean_free_path)
    # a Knudsen number that underflows (d >> lambda) makes 1.1/Kn overflow and exp(-1.1/Kn) the 0 it
    # rounds to anyway; one that overflows is refused below, naming the inputs
    with np.errstate(over="ignore"):
        kn = 2.0 * lam / d
        cc = 1.0 + kn * (1.257 + 0.4 * np.exp(-1.1 / kn))
    return check_in_range(cc, "the slip correction", diameter=diameter, mean_free_path=mean_free_path)


def relaxation_time(diameter, density, viscosity=AIR_VISCOSITY, mean_free_path=AIR_MEAN_FREE_PATH):
    """Particle relaxation time ``tau = rho d^2 C_c / (18 mu)`` [s] (Stokes drag with slip correction).

    Parameters
    ----------
    diameter : array_like
        Particle diameter ``d`` [m], positive.
    density : array_like
        Particle density ``rho`` [kg/m^3], positive.
    viscosity : array_like, optional
        Dynamic viscosity of the gas ``mu`` [Pa s]; default :data:`AIR_VISCOSITY`.
    mean_free_path : array_like, optional
        Mean free path of the gas ``lambda`` [m]; default :data:`AIR_MEAN_FREE_PATH`.

    Returns
    -------
    ndarray
        Relaxation time ``tau`` [s].

    Raises
    ------
    ValueError
        If an argument is not positive.

    Examples
    --------
    >>> round(float(relaxation_time(4.9e-6, 1350.0)) * 1e6, 2)  # us, the seed's NH4Fl particle in air
    102.96
    """
    d = check_positive("diameter", diameter)
    rho = check_positive("density", density)
    mu = check_positive("viscosity", viscosity)
    cc = cunningham_correction(d, mean_free_path)
    with np.errstate(over="ignore"):
        tau = rho * d**2 * cc / (18.0 * mu)
    names = dict(diameter=diameter, density=density, viscosity=viscosity, mean_free_path=mean_free_path)
    return check_in_range(tau, "the relaxation time", **names)


def stokes_number(diameter, density, strain_rate, viscosity=AIR_VISCOSITY, mean_free_path=AIR_MEAN_FREE_PATH):
    """Stokes number of the stagnation-point flow, ``Stk = a tau`` [-]; impaction needs ``Stk > 1/4``.

    Parameters
    ----------
    diameter : array_like
        Particle diameter ``d`` [m], positive.
    density : array_like
        Particle density ``rho`` [kg/m^3], positive.
    strain_rate : array_like
        Strain rate of the flow ``a = U/H`` [1/s], positive.
    viscosity : array_like, optional
        Dynamic viscosity of the gas ``mu`` [Pa s]; default :data:`AIR_VISCOSITY`.
    mean_free_path : array_like, optional
        Mean free path of the gas ``lambda`` [m]; default :data:`AIR_MEAN_FREE_PATH`.

    Returns
    -------
    ndarray
        Stokes number ``a tau`` [-]; compare with :data:`CRITICAL_STOKES_NUMBER`.

    Raises
    ------
    ValueError
        If an argument is not positive.
    """
    a = check_positive("strain_rate", strain_rate)
    tau = relaxation_time(diameter, density, viscosity, mean_free_path)
    with np.errstate(over="ignore"):
        stk = a * tau
    names = dict(diameter=diameter, density=density, viscosity=viscosity, mean_free_path=mean_free_path)
    return check_in_range(stk, "the Stokes number", strain_rate=strain_rate, **names)


def _axial(z0, w0, a, tau):
    """Closed-form axial flight: ``(t_hit, w_hit)``; ``t_hit = inf`` if the particle never reaches ``z = 0``."""
    beta = 0.5 / tau
    om2 = a / tau - beta * beta
    under = om2 > 0.0
    om = np.sqrt(np.where(under, om2, 1.0))
    D = (w0 + beta * z0) / om
    theta = np.arctan2(D, z0) + 0.5 * np.pi  # first zero of z0 cos + D sin, in (0, pi]
    t = theta / om
    w_hit = np.exp(-beta * t) * om * (D * np.cos(theta) - z0 * np.sin(theta))
    return np.where(under, t, np.inf), np.where(under, w_hit, np.nan)


def _axial_peak(w0, a, tau):
    """Highest point of a flight starting at ``z = 0`` with ``w0 > 0`` (under-damped) [m]."""
    beta = 0.5 / tau
    om = np.sqrt(np.maximum(a / tau - beta * beta, 0.0))
    ts = np.arctan2(om, beta) / np.where(om > 0, om, 1.0)
    return w0 / np.where(om > 0, om, 1.0) * np.exp(-beta * ts) * np.sin(om * ts)


def _radial(x0, u0, a, tau, t):
    """Closed-form radial motion: position and velocity at time ``t``."""
    beta = 0.5 / tau
    root = np.sqrt(beta * beta + 0.5 * a / tau)
    mp, mm = -beta + root, -beta - root
    cp = (u0 - mm * x0) / (mp - mm)
    cm = x0 - cp
    ep, em = np.exp(mp * t), np.exp(mm * t)
    return cp * ep + cm * em, mp * cp * ep + mm * cm * em


def flight_to_wall(x0, z0, u0, w0, strain_rate, tau):
    """Where and how a particle reaches the plate, in closed form.

    Parameters
    ----------
    x0, z0 : array_like
        Start: radial distance from the axis and height above the plate [m], ``z0 >= 0``.
    u0, w0 : array_like
        Start velocity, radial and axial [m/s].
    strain_rate : array_like
        Strain rate of the flow ``a`` [1/s].
    tau : array_like
        Relaxation time ``tau`` [s] (:func:`relaxation_time`).

    Returns
    -------
    dict of ndarray
        ``time`` to impact [s] (``inf`` when the particle never reaches the
        wall), ``x``, ``u``, ``w`` at impact (radial position [m], radial and axial
        velocity [m/s]; NaN without impact).
    """
    a = check_positive("strain_rate", strain_rate)
    tau = check_positive("tau", tau)
    z0 = check_nonnegative("z0", z0)
    start = {"x0": check_number("x0", x0), "z0": z0, "u0": check_number("u0", u0), "w0": check_number("w0", w0)}
    for k, v in start.items():
        if not np.isfinite(v).all():
            raise ValueError(f"{k} must be finite, got {float(np.asarray(v)[~np.isfinite(v)].flat[0])!r}")
    inputs = dict(x0=x0, z0=z0, u0=u0, w0=w0, strain_rate=strain_rate, tau=tau)
    # the flight's rates 1/(2 tau) and a/tau, and every state along it, must be doubles: an overflow
    # there would turn into a NaN or a flight that never lands, which is no answer
    with np.errstate(over="ignore", invalid="ignore"):
        check_in_range(0.5 / tau + a / tau, "the flight's rates 1/(2 tau) + a/tau", strain_rate=strain_rate, tau=tau)
        t, w = _axial(z0, start["w0"], a, tau)
        tt = np.where(np.isfinite(t), t, 0.0)
        x, u = _radial(start["x0"], start["u0"], a, tau, tt)
    hit = np.isfinite(t)
    if np.isnan(t).any() or (hit & ~(np.isfinite(x) & np.isfinite(u) & np.isfinite(w))).any():
        given = ", ".join(f"{k} {describe_value(v)}" for k, v in inputs.items())
        raise ValueError(f"{given} give a landing time, place or velocity beyond the float range: give inputs in range")
    return {"time": t, "x": np.where(hit, x, np.nan), "u": np.where(hit, u, np.nan), "w": w}


def flight_to_wall_ode(x0, z0, u0, w0, strain_rate, tau, *, t_max=None, rtol=1e-11, atol=None):
    """Same as :func:`flight_to_wall` for one particle, by ``solve_ivp`` with an event at the wall (cross-check).

    The event is placed ``1e-10`` of the start scale below ``z = 0`` so that
    round-off cannot fake an impact of a particle creeping toward the wall; the
    price is that impacts just above the critical Stokes number, which arrive
    after the axial motion has decayed by more than ``1e-10``, are not seen.

    Parameters
    ----------
    x0, z0 : float
        Start: radial distance from the axis and height above the plate [m].
    u0, w0 : float
        Start velocity, radial and axial [m/s].
    strain_rate : float
        Strain rate of the flow ``a`` [1/s].
    tau : float
        Relaxation time ``tau`` [s].
    t_max : float, optional
        End of the integration [s]; default ``40 (tau + 1/a)``.
    rtol : float, optional
        Relative tolerance of the solver (default ``1e-11``).
    atol : float, optional
        Absolute tolerance [m, m/s]; default ``1e-14`` times the start scale.

    Returns
    -------
    dict
        ``time`` to impact [s] (``inf`` if none before ``t_max``), ``x`` [m],
        ``u``, ``w`` [m/s] at impact (NaN without impact), as :func:`flight_to_wall`.
    """
    from scipy.integrate import solve_ivp

    a, tau = float(strain_rate), float(tau)

    def rhs(t, y):
        x, z, u, w = y
        return [u, w, (0.5 * a * x - u) / tau, (-a * z - w) / tau]

    # The event sits 1e-10 x (start scale) below the wall, so that the integration
    # noise of a particle creeping toward z = 0 (Stk <= 1/4) cannot fake an impact;
    # this shifts a real impact by ~1e-10 of the flight, far below the cross-check's tolerance.
    eps = 1e-10 * max(abs(x0), abs(z0), abs(w0) * tau, 1e-12)

    def wall(t, y):
        return y[1] + eps

    wall.terminal, wall.direction = True, -1
    scale = max(abs(x0), abs(z0), abs(w0) * tau, 1e-12)
    t_max = t_max if t_max is not None else 40.0 * (tau + 1.0 / a)
    sol = solve_ivp(
        rhs,
        (0.0, t_max),
        [x0, z0, u0, w0],
        method="DOP853",
        events=wall,
        rtol=rtol,
        atol=atol if atol is not None else 1e-14 * scale,
    )
    if sol.t_events[0].size == 0:
        return {"time": np.inf, "x": np.nan, "u": np.nan, "w": np.nan}
    x, _, u, w = sol.y_events[0][0]
    return {"time": float(sol.t_events[0][0]), "x": x, "u": u, "w": w}


class DepositionBoundWarning(UserWarning):
    """:func:`simulate_deposition` reached its bound ``max_impacts`` with particles still bouncing."""


@dataclass(frozen=True, eq=False)
class DepositionResult:
    """Outcome of :func:`simulate_deposition`; arrays shaped (jet speeds, diameters) unless noted.

    Attributes
    ----------
    diameters : ndarray, shape (D,)
        Particle diameters [m].
    jet_speeds : ndarray, shape (S,)
        Jet speeds ``U`` [m/s].
    strain_rate : ndarray, shape (S,)
        Strain rate ``a = U/H`` [1/s].
    stokes_number : ndarray
        Stokes number ``a tau`` [-].
    deposited_fraction : ndarray
        Fraction of the released particles that stick on the plate [-].
    impacted_fraction : ndarray
        Fraction that reach the plate at least once (within ``R_plate``) [-].
    first_impact_speed : ndarray
        Normal impact speed at the first impact [m/s] (NaN: none).
    mean_impacts : ndarray
        Mean number of impacts per released particle [-].
    yield_velocity, sticking_velocity : ndarray, shape (D,)
        Yield velocity ``V_y`` and sticking velocity ``V_s`` [m/s].
    parameters : dict
        The inputs of :func:`simulate_deposition`.
    unresolved_fraction : ndarray or None
        Fraction still bouncing after ``max_impacts`` impacts, neither deposited nor lost: the
        bound on the tracking was reached for them, and :func:`simulate_deposition` warns
        (:class:`DepositionBoundWarning`) unless ``max_impacts=1``, where a bounce is a loss by choice.
        ``None`` for a result made without it.
    """

    diameters: np.ndarray
    jet_speeds: np.ndarray
    strain_rate: np.ndarray
    stokes_number: np.ndarray
    deposited_fraction: np.ndarray
    impacted_fraction: np.ndarray
    first_impact_speed: np.ndarray
    mean_impacts: np.ndarray
    yield_velocity: np.ndarray
    sticking_velocity: np.ndarray
    parameters: dict = field(default_factory=dict)
    unresolved_fraction: np.ndarray | None = None

    def to_rows(self):
        """One dict per (jet speed, diameter): for CSV writers and tables."""
        rows = []
        for i, U in enumerate(self.jet_speeds):
            for j, d in enumerate(self.diameters):
                rows.append(
                    {
                        "jet_speed [m/s]": float(U),
                        "diameter [m]": float(d),
                        "stokes_number [-]": float(self.stokes_number[i, j]),
                        "deposited_fraction [-]": float(self.deposited_fraction[i, j]),
                        "impacted_fraction [-]": float(self.impacted_fraction[i, j]),
                        "first_impact_speed [m/s]": float(self.first_impact_speed[i, j]),
                        "mean_impacts [-]": float(self.mean_impacts[i, j]),
                    }
                )
        return rows


def simulate_deposition(
    diameters,
    jet_speeds=10.0,
    *,
    height=1e-3,
    jet_radius=None,
    plate_radius=None,
    n_particles=50,
    material="nh4fl",
    wall="silicon",
    density=None,
    limiting_pressure=None,
    effective_modulus=None,
    work_of_adhesion=0.0,
    friction=0.0,
    max_impacts=30,
    viscosity=AIR_VISCOSITY,
    mean_free_path=AIR_MEAN_FREE_PATH,
    method="analytic",
) -> DepositionResult:
    """Fraction of particles deposited on the plate of an impinging stagnation-point flow.

    See the module docstring for the flow, the drag law and what counts as
    deposited. Every (jet speed, diameter, start position) is tracked at once
    (vectorized); the wall decides by :func:`~microimpact.wall.wall_interaction`.

    Parameters
    ----------
    diameters : array_like (D,)
        Particle diameters [m].
    jet_speeds : array_like (S,)
        Jet speeds ``U`` [m/s]; strain rate ``a = U / height``.
    height : float
        Release height ``H`` above the plate [m] (default 1 mm).
    jet_radius : float, optional
        Particles start at ``r <= jet_radius`` (default ``H/2``), equal area each.
    plate_radius : float, optional
        Impacts beyond it are losses (default ``H``).
    n_particles : int
        Start positions per (speed, diameter).
    material, wall, density, limiting_pressure, effective_modulus, work_of_adhesion, friction
        Passed to :func:`~microimpact.wall.wall_interaction` (``work_of_adhesion``
        ``G`` [J/m^2] is the work of adhesion, ``2 gamma`` for identical surfaces).
    max_impacts : int
        Impacts tracked per particle (1: the first impact decides).
    viscosity, mean_free_path : float
        Gas properties [Pa s], [m] (air at 293 K by default).
    method : {"analytic", "ode"}
        Closed-form flights (default) or ``solve_ivp`` per flight (slow; a cross-check).

    Returns
    -------
    DepositionResult
        Deposited and impacted fractions, Stokes numbers, first-impact speeds
        and mean impact counts on the (jet speed, diameter) grid.
    """
    d = np.atleast_1d(check_positive("diameters", diameters)).astype(float).reshape(-1)
    U = np.atleast_1d(check_positive("jet_speeds", jet_speeds)).astype(float).reshape(-1)
    H = float(check_positive("height", height))
    R_jet = 0.5 * H if jet_radius is None else float(check_positive("jet_radius", jet_radius))
    R_plate = H if plate_radius is None else float(check_positive("plate_radius", plate_radius, allow_inf=True))
    if int(n_particles) < 1:
        raise ValueError(f"n_particles must be >= 1, got {n_particles!r}")
    if int(max_impacts) < 1:
        raise ValueError(f"max_impacts must be >= 1, got {max_impacts!r}")
    if method not in ("analytic", "ode"):
        raise ValueError(f"method must be 'analytic' or 'ode', got {method!r}")
    P = int(n_particles)
    if density is None:
        from .materials import get_material

        density = get_material(material).density
    rho = float(check_positive("density", density))

    with np.errstate(over="ignore"):
        a_s = U / H
    if not np.isfinite(a_s).all():
        raise ValueError(
            f"jet_speeds {describe_value(U)} over height {H!r} m give a strain rate U/H beyond the largest double: "
            "give them in range"
        )
    try:
        tau_d = relaxation_time(d, rho, viscosity, mean_free_path)
    except ValueError as exc:
        raise ValueError(f"diameters and density: {exc}") from None
    if (tau_d < TINY_NORMAL).any():  # the flight divides by tau: one that underflows has no flight
        raise ValueError(
            f"diameters {describe_value(d)} m and density {rho!r} kg/m^3 give a relaxation time "
            f"{float(tau_d.min())!r} s below the smallest normal double: give them in range"
        )
    with np.errstate(over="ignore"):
        rate = a_s[:, None] / tau_d[None, :]
    if not np.isfinite(rate).all():  # the flight's rate a/tau (flight_to_wall)
        raise ValueError(
            f"jet_speeds {describe_value(U)} over height {H!r} m, with diameters {describe_value(d)} m and density {rho!r} "
            "kg/m^3, give a flight rate a/tau beyond the largest double: give them in range"
        )
    tau_rot_d = rho * d**2 / (60.0 * viscosity)
    S, D = U.size, d.size
    shape = (S, D, P)
    a = np.broadcast_to(a_s[:, None, None], shape).reshape(-1)
    tau = np.broadcast_to(tau_d[None, :, None], shape).reshape(-1)
    tau_rot = np.broadcast_to(tau_rot_d[None, :, None], shape).reshape(-1)
    dia = np.broadcast_to(d[None, :, None], shape).reshape(-1)
    x_start = R_jet * np.sqrt((np.arange(P) + 0.5) / P)  # equal-area rings
    x = np.broadcast_to(x_start[None, None, :], shape).reshape(-1).copy()
    z = np.full(x.size, H)
    with np.errstate(over="ignore"):
        u = 0.5 * a * x  # gas velocity at the start
        w = -a * z
    if not (np.isfinite(u).all() and np.isfinite(w).all()):
        raise ValueError(
            f"jet_speeds {describe_value(U)}, height {H!r} and jet_radius {R_jet!r} give a gas velocity at the start "
            "beyond the largest double: give them in range"
        )
    spin = np.zeros((x.size, 3))

    alive = np.ones(x.size, bool)
    deposited = np.zeros(x.size, bool)
    impacted = np.zeros(x.size, bool)
    n_imp = np.zeros(x.size, int)
    first_speed = np.full(x.size, np.nan)
    wall_kw = dict(
        material=material,
        wall=wall,
        limiting_pressure=limiting_pressure,
        effective_modulus=effective_modulus,
        work_of_adhesion=work_of_adhesion,
        friction=friction,
    )
    for k in range(int(max_impacts)):
        idx = np.flatnonzero(alive)
        if idx.size == 0:
            break
        if method == "analytic":
            fl = flight_to_wall(x[idx], z[idx], u[idx], w[idx], a[idx], tau[idx])
        else:
            rows = [flight_to_wall_ode(x[i], z[i], u[i], w[i], a[i], tau[i]) for i in idx]
            fl = {key: np.array([r[key] for r in rows], dtype=float) for key in ("time", "x", "u", "w")}
        hit = np.isfinite(fl["time"]) & (np.abs(fl["x"]) <= R_plate)
        alive[idx[~hit]] = False
        idx, fl = idx[hit], {key: val[hit] for key, val in fl.items()}
        if idx.size == 0:
            break
        impacted[idx] = True
        n_imp[idx] += 1
        if k == 0:
            first_speed[idx] = -fl["w"]
        spin[idx] *= np.exp(-fl["time"] / tau_rot[idx])[:, None]
        vel = np.column_stack([fl["u"], np.zeros(idx.size), fl["w"]])
        out = wall_interaction(vel, [0.0, 0.0, 1.0], dia[idx], rho, spin=spin[idx], **wall_kw)
        deposited[idx[out.stuck]] = True
        alive[idx[out.stuck]] = False
        bounce = ~out.stuck
        b = idx[bounce]
        x[b], z[b] = fl["x"][bounce], 0.0
        u[b], w[b] = out.velocity[bounce, 0], out.velocity[bounce, 2]
        spin[b] = out.spin[bounce]
        # a particle thrown back above the release height has left the stagnation region
        up = _axial_peak(w[b], a[b], tau[b]) > H
        alive[b[up]] = False

    if alive.any() and int(max_impacts) > 1:
        # the tracking's bound: these particles have neither stuck nor left, and their fate is unknown
        # (with max_impacts=1 the first impact decides by choice: a bounce is a loss, no warning)
        import warnings

        warnings.warn(
            f"simulate_deposition reached its bound max_impacts={int(max_impacts)} with "
            f"{int(alive.sum())} of {alive.size} particles still bouncing: they count neither as "
            "deposited nor as lost (result.unresolved_fraction; raise max_impacts to follow them)",
            DepositionBoundWarning,
            stacklevel=2,
        )
    # yield and sticking velocities per diameter (independent of the jet speed)
    probe = wall_interaction(np.tile([0.0, 0.0, -1.0], (D, 1)), [0.0, 0.0, 1.0], d, rho, **wall_kw)
    frac = lambda m: m.reshape(shape).mean(axis=2)  # noqa: E731
    seen = np.isfinite(first_speed).reshape(shape)
    count = seen.sum(axis=2)
    with np.errstate(invalid="ignore", divide="ignore"):
        fs = np.where(count > 0, np.where(seen, first_speed.reshape(shape), 0.0).sum(axis=2) / count, np.nan)
    return DepositionResult(
        diameters=d,
        jet_speeds=U,
        strain_rate=a_s,
        stokes_number=a_s[:, None] * tau_d[None, :],
        deposited_fraction=frac(deposited),
        impacted_fraction=frac(impacted),
        first_impact_speed=fs,
        mean_impacts=n_imp.reshape(shape).mean(axis=2),
        unresolved_fraction=frac(alive),
        yield_velocity=np.asarray(probe.yield_velocity),
        sticking_velocity=np.asarray(probe.sticking_velocity),
        parameters=dict(
            height=H,
            jet_radius=R_jet,
            plate_radius=R_plate,
            n_particles=P,
            density=rho,
            max_impacts=int(max_impacts),
            viscosity=viscosity,
            mean_free_path=mean_free_path,
            method=method,
            **{k_: v_ for k_, v_ in wall_kw.items()},
        ),
    )


def plot_deposition(result: DepositionResult, ax=None, *, x="diameter", show_impacted=True, legend=True, **line_kws):
    """Deposited fraction against particle diameter (or Stokes number), one line per jet speed.

    Parameters
    ----------
    result : DepositionResult
        From :func:`simulate_deposition`.
    ax : matplotlib Axes, optional
        Axes to draw on; a new figure if None.
    x : {"diameter", "stokes"}
        Abscissa: diameter [um] or Stokes number ``a tau`` (critical value 1/4 marked).
    show_impacted : bool
        Also draw (dashed) the fraction that reached the plate: the gap to the
        solid line is what bounced off.
    legend : bool
        Draw a legend (one entry per jet speed [m/s]).
    **line_kws
        Passed to ``ax.plot`` for the deposited-fraction lines.

    Returns
    -------
    matplotlib Axes
        The Axes drawn on.
    """
    plt = require("matplotlib.pyplot", "plotting")
    from matplotlib.lines import Line2D
    from matplotlib.ticker import FuncFormatter, LogLocator

    if x not in ("diameter", "stokes"):
        raise ValueError(f"x must be 'diameter' or 'stokes', got {x!r}")
    if ax is None:
        _, ax = plt.subplots(figsize=(5.0, 3.6), constrained_layout=True)
    markers = "osD^vP*X"
    n = result.diameters.size
    every = max(1, n // 12)
    handles = []
    for i, U in enumerate(result.jet_speeds):
        xs = result.diameters * 1e6 if x == "diameter" else result.stokes_number[i]
        kws = dict(marker=markers[i % len(markers)], markersize=4, markevery=every, linewidth=1.5, label=f"{U:g} m/s")
        kws.update(line_kws)
        (line,) = ax.plot(xs, result.deposited_fraction[i], **kws)
        handles.append(line)
        if show_impacted:
            ax.plot(xs, result.impacted_fraction[i], color=line.get_color(), linestyle="--", linewidth=0.9, alpha=0.8)
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 3.0)))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    if x == "diameter":
        ax.set_xlabel(r"particle diameter $d$ [$\mu$m]")
    else:
        ax.axvline(CRITICAL_STOKES_NUMBER, color="0.4", linestyle=":", linewidth=1.2)
        ax.annotate(
            r"Stk$_c$ = 1/4",
            xy=(CRITICAL_STOKES_NUMBER, 1.0),
            xytext=(-4, -2),
            textcoords="offset points",
            ha="right",
            va="top",
            fontsize=8,
            color="0.3",
        )
        ax.set_xlabel(r"Stokes number Stk $= a\tau$ [-]")
    ax.set_ylabel("fraction of particles [-]" if show_impacted else "fraction deposited [-]")
    ax.set_ylim(-0.03, 1.05)
    ax.grid(True, which="major", alpha=0.3)
    if legend:
        extra = []
        if show_impacted:
            extra = [
                Line2D([], [], color="0.3", linewidth=1.5, label="deposited (stuck)"),
                Line2D([], [], color="0.3", linestyle="--", linewidth=0.9, label="reached the plate"),
            ]
        ax.legend(
            handles=handles + extra,
            frameon=True,
            framealpha=0.9,
            edgecolor="none",
            fontsize=7.5,
            title="jet speed U",
            title_fontsize=7.5,
            loc="center left",
            bbox_to_anchor=(1.01, 0.5),
        )
    return ax
