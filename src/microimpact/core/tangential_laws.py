"""The tangential spring laws DEM codes run, along the seed's closed-form normal history.

One scalar source (``@jitable``, :mod:`math` only) for every tangential law of
:func:`microimpact.oblique.oblique_impact` other than the rigid model. Each law is an
incrementally loaded tangential spring with a Coulomb limit ``|T| <= mu P``, as the codes
compute it at every time step; here its continuous-time limit is integrated along the normal
history of :mod:`microimpact.core.tangential` (same normalised units, same stage variables).

What the codes compute (read in their sources; the equation each step follows is named):

* **LAMMPS** ``pair_style granular`` / ``fix wall/gran granular``, ``tangential`` sub-models
  (``src/GRANULAR/gran_sub_mod_tangential.cpp``, ``GranSubModTangentialMindlin::calculate_forces``
  and ``GranSubModTangentialLinearHistory::calculate_forces``, 22 Jul 2025). The history is a
  displacement ``xi`` (``mindlin``, ``mindlin_rescale``, ``linear_history``: ``xi += v_t dt``,
  force ``-k_t xi``) or the force itself (``mindlin/force``, ``mindlin_rescale/force``:
  ``T += -k_t v_t dt``), with ``k_t = k a`` (``mindlin*``: ``k = 8 G*`` from the material
  when given as ``NULL``, ``a`` the contact radius) or ``k_t = k`` constant (``linear_history``);
  the ``*_rescale*`` variants multiply the history by ``a / a_old`` whenever the contact radius
  shrinks (the documentation cites Thornton et al. 2013, eq. 18(b)). When ``|T| > mu P`` the
  force is scaled back to ``mu P`` and the history set to match it ("rescale frictional
  displacements and forces"). In the continuous limit the stuck force obeys

      dT/dt = -k_t u + c (da/dt / a) T

  with ``u`` the contact-point slip and ``c`` the power of ``a`` the stored force follows at a
  fixed history: ``c = 0`` for a force history without rescaling, ``1`` for a displacement
  history (``T = -k a xi``) or a rescaled force history while ``a`` shrinks, ``2`` for a
  rescaled displacement history while ``a`` shrinks (``xi`` and ``k a`` both scale with ``a``).
  So, as ``(c while a grows, c while a shrinks)``: ``mindlin`` (1, 1), ``mindlin/force`` (0, 0),
  ``mindlin_rescale`` (1, 2), ``mindlin_rescale/force`` (0, 1) (:mod:`microimpact.core.tangential`,
  the model ``"mindlin"``), ``linear_history`` (0, 0) with a constant stiffness.
* **LIGGGHTS-PUBLIC 3.8.0** ``tangential history`` (``src/tangential_model_history.h``): a
  displacement history ``shear += v_tr dt``, force ``-k_t shear`` with ``k_t = 8 G* (R delta)^(1/2)``
  from ``normal_model_hertz.h``, Coulomb rescaling of force and history: (1, 1) like LAMMPS
  ``mindlin``. For a wall contact the relative velocity and the torque use the arm ``cr``
  (``src/surface_model_default.h``: ``cr = r - delta/2``, ``delta`` the overlap), not ``r``:
  the arm shrinks with the overlap, which this module follows (``lam = 1/2`` below).
* **Di Renzo & Di Maio (2005)**, as MercuryDPM's ``MindlinInteraction::computeFrictionForce``
  (``kuwt/MercuryDPM_fork``, commit ``fb0ebf1d``) writes it with its equation numbers: elastic
  force ``-(2/3) k_t0 xi`` with ``k_t0 = 8 G* (R* delta)^(1/2)`` ("2.0/3.0 as a factor from Di
  Renzo and Di Maio (2005) eqn (15)"), the displacement history ``xi`` integrated from the
  relative tangential velocity, the Coulomb criterion of their eq. (36) and the spring reset
  ``xi = -T/((2/3) k_t0)`` when it is met (eq. 37): (1, 1) with the stiffness times ``2/3``.

* **Stronge's compliant frictional impact** (Stronge, *Impact Mechanics*; as ``ekiefl/pooltool``'s
  ``pooltool/physics/resolve/stronge_compliant.py`` at ``0e907548`` writes it for a sphere on a
  half-space): a linear normal spring, stiffer by ``1/e^2`` in restitution (normal force
  ``(m/beta_n) omega_n V sin(omega_n t)`` while compressing, ``sin(omega_n t/e + pi/2 (1 - 1/e))``
  after, so the normal impulse is ``(1 + e) m V/beta_n``), and a linear tangential spring ``k_t =
  k_n/eta^2`` loaded by the slip of the contact point, with the Coulomb limit and the spring
  following the limit while sliding; ``beta_t/beta_n = 7/2`` for a solid sphere. The source's
  ``eta^2 = (2 - nu)/(2 (1 - nu))`` is ``1/kappa`` for one material on a rigid flat; here
  ``eta^2 = 1/kappa`` in general, and ``e`` is the seed's. The source solves the three cases
  (stick–slip, slip–stick–slip, gross slip) in closed form; :func:`integrate_stronge` integrates the
  same equations (the tests compare with the closed forms). Its normal force is not Hertz's: the
  outcome depends on ``u0/(mu V)``, ``kappa`` and ``e`` only.

Normalised units (:mod:`microimpact.core.tangential`): lengths in ``alpha_m``, time in ``alpha_m/V``,
normal force in ``m V^2/alpha_m``, tangential force in ``mu m V^2/alpha_m``, velocities of the
contact plane in ``mu V``. A Mindlin stiffness is ``k^ = 15/8 kappa f (a/a_m)`` (``f`` the law's
factor, ``kappa = 4 G*/E*``); a constant stiffness ``k_t`` is ``k^ = 15/8 kappa`` with
``kappa = k_t / (2 E* a_m)`` (the ratio of ``k_t`` to the Hertz normal stiffness at the elastic
maximum approach; it depends on ``V``). The centre's tangential velocity ``v`` and the rim speed
``w = R omega`` change as ``dv/dtau = T^``, ``dw/dtau = 5/2 rho T^`` (a solid sphere), the slip is
``u = v + rho w`` with the arm ``rho = 1 - lam eps alpha^`` (``eps = alpha_m / R``; ``lam = 0``: the
arm is ``R``, as LAMMPS, DR&DM and the rigid model take it). With ``lam = 0`` the outcome depends
on ``psi = kappa u0/(mu V)``, ``kappa`` and ``V_y/V`` only (the universal curve of each law).

The stuck state is kept as ``X = T / a^c`` (``c`` of the stage: 0, 1 or 2), which makes the stuck
rate ``dX/dtau = -k^ u / a^c`` free of ``da/dtau``. Sliding, ``T = -sign mu P``; the contact sticks
again when the stuck force would fall inside the limit: ``sign k^ u + c (da/dtau / a) P^ < dP^/dtau``.
"""

from __future__ import annotations

import math

from ._jit import jitable
from .tangential import (
    REGIME_MICROSLIP,
    REGIME_SLIDING,
    REGIME_STICKING,
    history_constants,
    leave_slip,
    stage_point,
    switch_function,
    tangential_rates,
)

__all__ = [
    "LAWS",
    "ALL_LAWS",
    "law_code",
    "law_parameters",
    "law_rates",
    "law_switch",
    "integrate_law",
    "stronge_normal",
    "integrate_stronge",
    "KIND_SEED",
    "KIND_LAW",
    "KIND_STRONGE",
    "step_rates",
    "step_switch",
    "stick_state",
    "step_rk4",
    "integrate_stage",
    "regime_code",
]

#: Laws by name, their integer code (the order of :func:`law_parameters`).
LAWS = (
    "lammps_mindlin_rescale_force",
    "lammps_mindlin",
    "lammps_mindlin_force",
    "lammps_mindlin_rescale",
    "lammps_linear_history",
    "liggghts_history",
    "di_renzo_di_maio",
)


#: Every law of this module by name: :data:`LAWS` (integrated by :func:`integrate_law`) and
#: ``"stronge"`` (:func:`integrate_stronge`).
ALL_LAWS = (*LAWS, "stronge")


def law_code(name):
    """Integer code of a law of :data:`LAWS` (a float, as the array paths pass it)."""
    return float(LAWS.index(name))


@jitable
def law_parameters(code):
    """``(c_load, c_unload, factor, linear, lam)`` of the law ``code`` (module docstring).

    ``c_load``/``c_unload``: power of ``a`` the stored force follows while the contact grows /
    shrinks; ``factor``: the stiffness is ``factor 8 G* a``; ``linear``: 1 for a constant
    stiffness; ``lam``: the arm is ``R - lam delta``.
    """
    c = int(code)
    if c == 0:  # LAMMPS mindlin_rescale/force
        return (0.0, 1.0, 1.0, 0.0, 0.0)
    if c == 1:  # LAMMPS mindlin
        return (1.0, 1.0, 1.0, 0.0, 0.0)
    if c == 2:  # LAMMPS mindlin/force
        return (0.0, 0.0, 1.0, 0.0, 0.0)
    if c == 3:  # LAMMPS mindlin_rescale
        return (1.0, 2.0, 1.0, 0.0, 0.0)
    if c == 4:  # LAMMPS linear_history
        return (0.0, 0.0, 1.0, 1.0, 0.0)
    if c == 5:  # LIGGGHTS tangential history, wall arm r - delta/2
        return (1.0, 1.0, 1.0, 0.0, 0.5)
    # Di Renzo & Di Maio (2005): eq. 15's 2/3
    return (1.0, 1.0, 2.0 / 3.0, 0.0, 0.0)


@jitable
def _power(a, c):
    """``a^c`` for ``c`` in {0, 1, 2} (exact products)."""
    if c == 0.0:
        return 1.0
    if c == 1.0:
        return a
    return a * a


@jitable
def _arm(stage, a, adot_a, hc, lam_eps):
    """Arm ``rho = 1 - lam eps alpha^`` and its rate ``d rho / d tau`` at a stage point."""
    if lam_eps == 0.0:
        return (1.0, 0.0)
    a2 = a * a
    if stage == 3:
        alpha = hc[11] + a2 / hc[10]
        alphadot = 2.0 * a2 * adot_a / hc[10]
    else:
        alpha = a2
        alphadot = 2.0 * a2 * adot_a
    return (1.0 - lam_eps * alpha, -lam_eps * alphadot)


@jitable
def law_rates(stage, v, xs, vt, wr, sliding, sign, hc, kappa, c, factor, linear, lam_eps):
    """``(dX/dv, dv^/dv, dw^/dv, T^)`` along the stage variable ``v`` (module docstring)."""
    dtau, a, adot_a, p, _, _ = stage_point(stage, v, hc)
    rho, _ = _arm(stage, a, adot_a, hc, lam_eps)
    if sliding:
        t = -sign * p
        return (0.0, dtau * t, dtau * 2.5 * rho * t, t)
    ac = _power(a, c)
    t = xs * ac
    u = vt + rho * wr
    k = 1.875 * kappa * factor
    if linear == 0.0:
        k = k * a
    dx = 0.0
    if ac > 0.0:
        dx = -dtau * k * u / ac
    return (dx, dtau * t, dtau * 2.5 * rho * t, t)


@jitable
def law_switch(stage, v, xs, vt, wr, sliding, sign, hc, kappa, c, factor, linear, lam_eps):
    """Positive when the contact must change regime: stuck ``|T^| - P^``; sliding, minus the
    excess of the stuck force's rate over the limit's (module docstring)."""
    _, a, adot_a, p, pdot, _ = stage_point(stage, v, hc)
    if sliding:
        rho, _ = _arm(stage, a, adot_a, hc, lam_eps)
        k = 1.875 * kappa * factor
        if linear == 0.0:
            k = k * a
        g = sign * k * (vt + rho * wr) - pdot
        if a > 0.0:
            g += c * p * adot_a
        return -g
    return abs(xs * _power(a, c)) - p


@jitable
def integrate_law(code, v0_hat, w0_hat, kappa, x, eps, steps):
    """Tangential outcome of one impact under the law ``code`` (fixed-step RK4, bisected switches).

    Parameters
    ----------
    code : float
        Index of the law in :data:`LAWS`.
    v0_hat, w0_hat : float
        Tangential velocity of the centre and rim speed ``R omega`` before the impact, in
        ``mu V`` [-]; the slip is ``u0 = v0 + w0``.
    kappa : float
        ``4 G*/E*`` [-] (constant-stiffness law: ``k_t / (2 E* a_m)``).
    x : float
        ``V_y / V`` [-] (1 or more: elastic).
    eps : float
        ``alpha_m / R`` [-], used by laws whose arm shrinks with the overlap only.
    steps : int
        RK4 steps per stage.

    Returns
    -------
    tuple
        ``(v_r, w_r, regime)``: the two velocities after the impact (``mu V`` units) and the
        regime code of :mod:`microimpact.core.tangential`.
    """
    c_load, c_unload, factor, linear, lam = law_parameters(code)
    lam_eps = lam * eps
    hc = history_constants(x)
    elastic = hc[0] == 1.0
    vt = v0_hat
    wr = w0_hat
    u0 = v0_hat + w0_hat
    xs = 0.0
    if linear != 0.0:
        sliding = u0 != 0.0
    else:
        sliding = kappa * factor * abs(u0) * 3.0 / (3.0 - c_load) > 1.0
    sign = 1.0 if u0 >= 0.0 else -1.0
    slid = sliding
    stuck = not sliding
    steps = int(steps)
    h = 1.0 / steps
    c_prev = c_load
    a_prev = 0.0
    for stage in range(1, 4):
        if stage == 2 and elastic:
            continue
        c = c_unload if stage == 3 else c_load
        if not sliding and c != c_prev:  # same force, new state variable
            _, a_new, _, _, _, _ = stage_point(stage, 0.0, hc)
            t_prev = xs * _power(a_prev, c_prev)
            xs = t_prev / _power(a_new, c)
        c_prev = c
        q = (kappa, c, factor, linear, lam_eps, 0.0, 0.0)
        xs, vt, wr, sliding, sign, slid, stuck = integrate_stage(
            KIND_LAW, stage, 0.0, h, steps, xs, vt, wr, sliding, sign, slid, stuck, hc, q
        )
        _, a_prev, _, _, _, _ = stage_point(stage, 1.0, hc)
    return vt, wr, regime_code(slid, stuck)


@jitable
def stronge_normal(stage, s, e):
    """Normal force and its rate of Stronge's linear compliant impact at the phase ``s = omega_n t``.

    In units of ``m omega_n V/beta_n``: ``sin(s)`` while compressing (``stage`` 1, ``s`` in
    ``[0, pi/2]``), ``sin(s/e + pi/2 (1 - 1/e))`` in restitution (``stage`` 3, ``s`` in
    ``[pi/2, pi/2 (1 + e)]``). Returns ``(P, dP/ds)``.
    """
    if stage == 1:
        return (math.sin(s), math.cos(s))
    ph = s / e + 0.5 * math.pi * (1.0 - 1.0 / e)
    return (math.sin(ph), math.cos(ph) / e)


@jitable
def _stronge_rates(stage, s, xs, u, sliding, sign, e, eta2):
    """``(dX/ds, du/ds, T)``: stuck, ``X = T`` with ``dT/ds = -u/eta^2``; sliding, ``T = -sign P``."""
    p, _ = stronge_normal(stage, s, e)
    if sliding:
        t = -sign * p
        return (0.0, 3.5 * t, t)
    return (-u / eta2, 3.5 * xs, xs)


@jitable
def _stronge_switch(stage, s, xs, u, sliding, sign, e, eta2):
    p, pdot = stronge_normal(stage, s, e)
    if sliding:
        return -(sign * u / eta2 - pdot)
    return abs(xs) - p


@jitable
def integrate_stronge(u0_hat, kappa, e, steps):
    """Tangential outcome of Stronge's compliant frictional impact (fixed-step RK4, bisected switches).

    Parameters
    ----------
    u0_hat : float
        Slip of the contact point before the impact, ``u0 / (mu V)`` [-].
    kappa : float
        Tangential over normal spring stiffness, ``1/eta^2`` [-] (``4 G*/E*``).
    e : float
        Normal restitution coefficient [-], in (0, 1].
    steps : int
        RK4 steps per phase (compression, restitution).

    Returns
    -------
    tuple
        ``(u_r_hat, regime)``: the slip after the impact in ``mu V`` (it changes by ``7/2`` of the
        tangential impulse per mass) and the regime code.
    """
    eta2 = 1.0 / kappa
    u = u0_hat
    xs = 0.0
    z = 0.0
    sliding = abs(u0_hat) > eta2
    sign = 1.0 if u0_hat >= 0.0 else -1.0
    slid = sliding
    stuck = not sliding
    steps = int(steps)
    q = (kappa, 0.0, 0.0, 0.0, 0.0, e, eta2)
    for stage in (1, 3):
        s_start = 0.0 if stage == 1 else 0.5 * math.pi
        span = 0.5 * math.pi if stage == 1 else 0.5 * math.pi * e
        h = span / steps
        xs, u, z, sliding, sign, slid, stuck = integrate_stage(
            KIND_STRONGE, stage, s_start, h, steps, xs, u, z, sliding, sign, slid, stuck, NO_HISTORY, q
        )
    return u, regime_code(slid, stuck)


# ============================================================================ one stepping routine
#
# Every law above, and the model of :mod:`microimpact.core.tangential`, is integrated by the same
# fixed-step RK4 with bisected regime switches: :func:`integrate_stage` steps one stage of the normal
# history, the law chosen by ``kind`` (:data:`KIND_SEED`, :data:`KIND_LAW`, :data:`KIND_STRONGE`)
# through :func:`step_rates` and :func:`step_switch`. numba cannot pass a function to a compiled
# function, hence the integer dispatch; the constants of every law travel in one tuple ``q`` of
# floats, ``(kappa, c, factor, linear, lam_eps, e, eta2)`` (each law reads its own).

#: ``kind`` of :func:`integrate_stage`: the model of :mod:`microimpact.core.tangential`, state
#: ``(X, u^, unused)``.
KIND_SEED = 0
#: ``kind``: a law of :data:`LAWS` (:func:`law_rates`), state ``(X, v^, w^)``.
KIND_LAW = 1
#: ``kind``: Stronge's compliant impact (:func:`stronge_normal`), state ``(T, u, unused)``.
KIND_STRONGE = 2

#: Stand-in for the normal history's constants where a law has its own normal force (Stronge).
NO_HISTORY = (0.0,) * 14


@jitable(inline=True)
def step_rates(kind, stage, s, x, y, z, sliding, sign, hc, q):
    """``(dx/ds, dy/ds, dz/ds, T)`` of the law ``kind`` at the stage variable ``s`` (state ``x, y, z``)."""
    if kind == KIND_SEED:
        dx, dy, t = tangential_rates(stage, s, x, y, sliding, sign, hc, q[0])
        return (dx, dy, 0.0, t)
    if kind == KIND_STRONGE:
        dx, dy, t = _stronge_rates(stage, s, x, y, sliding, sign, q[5], q[6])
        return (dx, dy, 0.0, t)
    return law_rates(stage, s, x, y, z, sliding, sign, hc, q[0], q[1], q[2], q[3], q[4])


@jitable(inline=True)
def step_switch(kind, stage, s, x, y, z, sliding, sign, hc, q):
    """Positive when the law ``kind`` must change regime (stick to slip, or slip to stick)."""
    if kind == KIND_SEED:
        return switch_function(stage, s, x, y, sliding, sign, hc, q[0])
    if kind == KIND_STRONGE:
        return _stronge_switch(stage, s, x, y, sliding, sign, q[5], q[6])
    return law_switch(stage, s, x, y, z, sliding, sign, hc, q[0], q[1], q[2], q[3], q[4])


@jitable
def stick_state(kind, stage, s, sign, hc, q):
    """Stuck state ``x`` at the instant sliding in direction ``sign`` stops: ``T = -sign P`` in the law's variable."""
    if kind == KIND_SEED:
        return leave_slip(stage, s, sign, hc, q[0])
    if kind == KIND_STRONGE:
        p, _ = stronge_normal(stage, s, q[5])
        return -sign * p
    _, a, _, p, _, _ = stage_point(stage, s, hc)
    ac = _power(a, q[1])
    return -sign * p / ac if ac > 0.0 else 0.0


@jitable(inline=True)
def step_rk4(kind, stage, s, h, x, y, z, sliding, sign, hc, q):
    """One classical RK4 step of length ``h`` of :func:`step_rates` from ``s``: the new ``(x, y, z)``."""
    k1x, k1y, k1z, _ = step_rates(kind, stage, s, x, y, z, sliding, sign, hc, q)
    h2 = 0.5 * h
    k2x, k2y, k2z, _ = step_rates(kind, stage, s + h2, x + h2 * k1x, y + h2 * k1y, z + h2 * k1z, sliding, sign, hc, q)
    k3x, k3y, k3z, _ = step_rates(kind, stage, s + h2, x + h2 * k2x, y + h2 * k2y, z + h2 * k2z, sliding, sign, hc, q)
    k4x, k4y, k4z, _ = step_rates(kind, stage, s + h, x + h * k3x, y + h * k3y, z + h * k3z, sliding, sign, hc, q)
    return (
        x + h * (k1x + 2.0 * k2x + 2.0 * k3x + k4x) / 6.0,
        y + h * (k1y + 2.0 * k2y + 2.0 * k3y + k4y) / 6.0,
        z + h * (k1z + 2.0 * k2z + 2.0 * k3z + k4z) / 6.0,
    )


@jitable
def integrate_stage(kind, stage, start, h, steps, x, y, z, sliding, sign, slid, stuck, hc, q):
    """Integrate one stage of an impact under the law ``kind``: ``steps`` RK4 steps of ``h`` from ``start``.

    A step that ends past a regime switch (:func:`step_switch` positive) is bisected (60 halvings)
    to the switch, the regime changed there (sliding stops: :func:`stick_state`; the stuck force
    reaches the limit: the contact slides against it, the state ``x`` unused), and the rest of the
    step integrated in the new regime, up to 16 switches within one step.

    Returns
    -------
    tuple
        ``(x, y, z, sliding, sign, slid, stuck)``: the state at the stage's end, the regime then
        (sliding, and its direction), and whether the contact ever slid / stuck (for :func:`regime_code`).
    """
    for i in range(steps):
        s0 = start + i * h
        rem = h
        for _ in range(16):  # at most a few regime changes within one step
            xn, yn, zn = step_rk4(kind, stage, s0, rem, x, y, z, sliding, sign, hc, q)
            if step_switch(kind, stage, s0 + rem, xn, yn, zn, sliding, sign, hc, q) <= 0.0:
                x, y, z = xn, yn, zn
                break
            lo, hi = 0.0, 1.0
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                xm, ym, zm = step_rk4(kind, stage, s0, mid * rem, x, y, z, sliding, sign, hc, q)
                if step_switch(kind, stage, s0 + mid * rem, xm, ym, zm, sliding, sign, hc, q) > 0.0:
                    hi = mid
                else:
                    lo = mid
            xm, ym, zm = step_rk4(kind, stage, s0, hi * rem, x, y, z, sliding, sign, hc, q)
            ss = s0 + hi * rem
            if sliding:
                x = stick_state(kind, stage, ss, sign, hc, q)
                sliding = False
                stuck = True
            else:
                _, _, _, t = step_rates(kind, stage, ss, xm, ym, zm, False, sign, hc, q)
                sign = -1.0 if t > 0.0 else 1.0
                sliding = True
                slid = True
                x = 0.0
            y, z = ym, zm
            s0 = ss
            rem = rem * (1.0 - hi)
            if rem <= 0.0:
                break
    return x, y, z, sliding, sign, slid, stuck


@jitable
def regime_code(slid, stuck):
    """The regime code of :mod:`microimpact.core.tangential` (a float) of an impact that slid / stuck."""
    if slid and stuck:
        return float(REGIME_MICROSLIP)
    if slid:
        return float(REGIME_SLIDING)
    return float(REGIME_STICKING)
