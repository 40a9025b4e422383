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

* **Mindlin–Deresiewicz incremental stiffness with turning points** (``"mindlin_deresiewicz"``), as
  MercuryDPM's ``MindlinInteraction::updateK_t`` writes it (``kuwt/MercuryDPM_fork`` at ``fb0ebf1d``,
  ``Kernel/Interactions/FrictionForceInteractions/MindlinInteraction.cc`` l. 226–277, with
  ``k_t0 = 8 G* (R delta)^(1/2)`` of ``updateTangentialStiffnessZero``, l. 212–216): virgin loading
  ``K_t = K_t0 (1 - T/(mu P))^(1/3)`` (l. 248–261), from a turning point ``T*``
  ``K_t = K_t0 (1 - m (T - T*)/(2 mu P))^(1/3)``, ``m = +1`` loading, ``-1`` unloading (l. 264–275),
  the turning point used until the force exceeds it (the comment l. 223–224). MercuryDPM defines
  ``updateK_t`` and never calls it: ``git log -G updateK_t`` over all 784 commits of the fork's three
  branches finds the name only where its definition and declaration were added (``126c08fa``,
  2018-04-09) and reformatted; ``computeFrictionForce`` runs Di Renzo & Di Maio's law. So no peer code
  runs this law, and its bookkeeping is this module's (:func:`md_stiffness_factor`, :func:`step_event`):
  the force is a history, ``dT = -K_t u dt``; where the slip reverses while stuck the force is a turning
  point ``T_b`` (and ``T_a``, if it left the virgin curve there), the branch from ``T_b`` holds until
  ``|T|`` passes ``|T_a|`` (Masing: there it meets the virgin curve) and the virgin curve takes over;
  sticking again after sliding is a turning point at the limit where the slip has reversed, virgin
  loading at the limit where it has not. Two turning points are kept, as MercuryDPM's interaction
  stores two: a reversal inside an inner loop starts a branch from ``T_b`` bounded by ``T_a`` (where
  Masing's rule would return to the branch before). The bracket is clamped at 0 (``K_t = 0``: the
  whole contact slips). The law is Mindlin & Deresiewicz's for a *constant* normal force; along the
  impact the stored force and the turning points follow the rule of LAMMPS ``mindlin_rescale/force``
  (code 0, this package's ``"mindlin"``): kept while the contact grows, scaled by ``a/a_old`` while it
  shrinks, and ``P`` enters through the ratios at its current value, not by rescaling the force. Why:
  as ``mu -> inf`` the ratios vanish and the law is code 0 exactly, so it differs from ``"mindlin"`` by
  the Mindlin–Deresiewicz stiffness and memory alone; scaling the force with ``P`` instead would raise
  it at zero slip while the contact grows (energy from nothing). What this gives along the impact: under
  a growing ``P`` the virgin curve never reaches the limit (``K_t = 0`` there while ``mu P`` grows), so
  the contact never slides at first touch (``T/(mu P) = r`` with ``r = psi (1 - r)^(1/3) < 1`` for every
  ``psi``; the other laws slide from the start where ``psi > 1``) and its regime is micro-slip, never
  sliding, at large angles (the impulse within ``psi^-3`` of Coulomb's). A step that passes the limit
  there (the RK4 at the cube root's infinite slope) is held at ``K_t = 0`` with the force on the sphere
  capped at ``mu P``; the fixed steps converge at about first order where the force hugs the limit
  (``2.5e-4 mu m V`` between 400 and 1600 steps at ``psi = 3.5``, ``1e-9`` below ``psi = 0.5``).
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
from .tangential_stages import (
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
    "MD_CODE",
    "md_stiffness_factor",
    "mindlin_deresiewicz_cycle",
    "KIND_SEED",
    "KIND_LAW",
    "KIND_STRONGE",
    "KIND_MD",
    "KIND_MD_CYCLE",
    "step_rates",
    "step_switch",
    "stick_state",
    "step_event",
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
    "mindlin_deresiewicz",
)

#: Code of ``"mindlin_deresiewicz"`` in :data:`LAWS` (integrated with its memory of turning points).
MD_CODE = 7.0


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
    if c == 6:  # Di Renzo & Di Maio (2005): eq. 15's 2/3
        return (1.0, 1.0, 2.0 / 3.0, 0.0, 0.0)
    # Mindlin-Deresiewicz incremental stiffness: K_t0 = 8 G* a times md_stiffness_factor, the force
    # history kept while a grows and scaled by a/a_old while it shrinks (as code 0)
    return (0.0, 1.0, 1.0, 0.0, 0.0)


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
    md = code == MD_CODE
    if md:  # r = psi (1 - r)^(1/3) has a root r < 1 for every psi: never slides at first touch
        sliding = False
    elif linear != 0.0:
        sliding = u0 != 0.0
    else:
        sliding = kappa * factor * abs(u0) * 3.0 / (3.0 - c_load) > 1.0
    kind = KIND_MD if md else KIND_LAW
    mem = (-1.0 if u0 > 0.0 else 1.0, 0.0, 0.0, 0.0) if md else NO_MEMORY
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
            if md:  # the turning points are forces in the same variable
                scale = _power(a_prev, c_prev) / _power(a_new, c)
                mem = (mem[0], mem[1], mem[2] * scale, mem[3] * scale)
        c_prev = c
        q = (kappa, c, factor, linear, lam_eps, 0.0, 0.0)
        xs, vt, wr, sliding, sign, slid, stuck, mem = integrate_stage(
            kind, stage, 0.0, h, steps, xs, vt, wr, sliding, sign, slid, stuck, hc, q, mem
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
        xs, u, z, sliding, sign, slid, stuck, _ = integrate_stage(
            KIND_STRONGE, stage, s_start, h, steps, xs, u, z, sliding, sign, slid, stuck, NO_HISTORY, q, NO_MEMORY
        )
    return u, regime_code(slid, stuck)


# ============================================================================ one stepping routine
#
# Every law above, and the model of :mod:`microimpact.core.tangential`, is integrated by the same
# fixed-step RK4 with bisected regime switches: :func:`integrate_stage` steps one stage of the normal
# history, the law chosen by ``kind`` (:data:`KIND_SEED`, :data:`KIND_LAW`, :data:`KIND_STRONGE`,
# :data:`KIND_MD`, :data:`KIND_MD_CYCLE`) through :func:`step_rates`, :func:`step_switch` and
# :func:`step_event`. numba cannot pass a function to a compiled function, hence the integer
# dispatch; the constants of every law travel in one tuple ``q`` of floats, ``(kappa, c, factor,
# linear, lam_eps, e, eta2)`` (each law reads its own), and a law's memory of its loading path in one
# tuple ``mem`` of four floats (the Mindlin-Deresiewicz law's ``(d, mode, T_a, T_b)``; the other laws
# carry :data:`NO_MEMORY` unread).

#: ``kind`` of :func:`integrate_stage`: the model of :mod:`microimpact.core.tangential`, state
#: ``(X, u^, unused)``.
KIND_SEED = 0
#: ``kind``: a law of :data:`LAWS` (:func:`law_rates`), state ``(X, v^, w^)``.
KIND_LAW = 1
#: ``kind``: Stronge's compliant impact (:func:`stronge_normal`), state ``(T, u, unused)``.
KIND_STRONGE = 2
#: ``kind``: the Mindlin-Deresiewicz law along the normal history (:func:`md_stiffness_factor`),
#: state ``(X, v^, w^)`` as :data:`KIND_LAW`.
KIND_MD = 3
#: ``kind``: the same law at a constant normal force, driven by a prescribed slip rate
#: (:func:`mindlin_deresiewicz_cycle`), state ``(T, delta, u)``.
KIND_MD_CYCLE = 4

#: Stand-in for the normal history's constants where a law has its own normal force (Stronge).
NO_HISTORY = (0.0,) * 14
#: The constants ``q`` of :func:`mindlin_deresiewicz_cycle` (its units make ``K_t0`` and ``mu P`` 1).
Q_UNIT = (1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0)
#: Stage-variable step over which a Mindlin-Deresiewicz contact sliding at the limit is followed
#: stuck to decide whether it sticks (:func:`step_event`).
MD_PROBE = 1e-6
#: The memory of a law that keeps none.
NO_MEMORY = (0.0, 0.0, 0.0, 0.0)


@jitable
def md_stiffness_factor(t, t_b, p, mode):
    """``K_t / K_t0`` of the Mindlin-Deresiewicz law (MercuryDPM's ``MindlinInteraction::updateK_t``).

    Virgin loading (``mode`` 0): ``(1 - |T|/(mu P))^(1/3)``; from the turning point ``T_b``
    (``mode`` 1): ``(1 - |T - T_b|/(2 mu P))^(1/3)``. ``t``, ``t_b`` and ``p`` are forces in one unit
    (here ``T^`` and ``P^``: ``mu P`` is ``P^``); 0 where the bracket is not positive (the whole
    contact slips), 1 at ``P = 0`` (first touch, ``T = 0``).
    """
    if p <= 0.0:
        return 1.0
    if mode == 0.0:
        r = abs(t) / p
    else:
        r = abs(t - t_b) / (2.0 * p)
    if r >= 1.0:
        return 0.0
    return (1.0 - r) ** (1.0 / 3.0)


@jitable
def _md_point(kind, stage, s, x, y, z, hc, q, mem):
    """``(T, P, u, a^c, dP/ds)`` of the Mindlin-Deresiewicz law at a point: force, limit, slip, state
    scale and the rate of the limit."""
    if kind == KIND_MD_CYCLE:
        return (x, 1.0, z, 1.0, 0.0)
    _, a, _, p, pdot, _ = stage_point(stage, s, hc)
    ac = _power(a, q[1])
    return (x * ac, p, y + z, ac, pdot)


@jitable(inline=True)
def step_rates(kind, stage, s, x, y, z, sliding, sign, hc, q, mem):
    """``(dx/ds, dy/ds, dz/ds, T)`` of the law ``kind`` at the stage variable ``s`` (state ``x, y, z``)."""
    if kind == KIND_SEED:
        dx, dy, t = tangential_rates(stage, s, x, y, sliding, sign, hc, q[0])
        return (dx, dy, 0.0, t)
    if kind == KIND_STRONGE:
        dx, dy, t = _stronge_rates(stage, s, x, y, sliding, sign, q[5], q[6])
        return (dx, dy, 0.0, t)
    if kind == KIND_LAW:
        return law_rates(stage, s, x, y, z, sliding, sign, hc, q[0], q[1], q[2], q[3], q[4])
    return _md_rates(kind, stage, s, x, y, z, sliding, sign, hc, q, mem)


@jitable
def _md_rates(kind, stage, s, x, y, z, sliding, sign, hc, q, mem):
    """:func:`step_rates` of the Mindlin-Deresiewicz law: :func:`law_rates` with the stiffness times
    :func:`md_stiffness_factor`; at a constant normal force, ``dT = -K_t u``, ``d delta = u``."""
    t, p, u, ac, pdot = _md_point(kind, stage, s, x, y, z, hc, q, mem)
    f = 0.0
    if not sliding:
        f = md_stiffness_factor(t, mem[3] * ac, p, mem[1])
    if kind == KIND_MD_CYCLE:
        if sliding:
            return (0.0, u, 0.0, -sign * p)
        return (-f * u, u, 0.0, t)
    dx, dv, dw, t = law_rates(stage, s, x, y, z, sliding, sign, hc, q[0], q[1], q[2] * f, q[3], q[4])
    if not sliding and abs(t) > p:
        # past the limit only by the RK4's step under a growing normal force (_md_events): the force
        # on the sphere is capped at mu P, as the codes cap it
        r = p / abs(t)
        return (dx, dv * r, dw * r, t * r)
    return (dx, dv, dw, t)


@jitable
def _md_events(kind, stage, s, x, y, z, sliding, sign, hc, q, mem):
    """``(limit, reversal, rejoin)`` of the Mindlin-Deresiewicz law, each positive past its event.

    Stuck: the Coulomb limit ``|T| - mu P``; the reversal of the slip ``d u`` (``d`` the direction
    the force is being moved in, ``-sign(u)``); on a turning-point curve, ``|T| - |T_a|``: the force
    is past the turning point ``T_a`` reached from the virgin curve, which it rejoins there.
    Sliding: minus the excess of the stuck force's rate over the limit's (as :func:`law_switch`), the
    stuck force's stiffness ``K_t0`` where the slip has reversed (a turning point at the limit) and 0
    where it has not (virgin loading at the limit), in ``limit``.
    """
    if sliding:
        t, p, u, ac, pdot = _md_point(kind, stage, s, x, y, z, hc, q, mem)
        if kind == KIND_MD_CYCLE:
            return (-(sign * u), -1.0, -1.0)
        if sign * u > 0.0:  # virgin loading at the limit: K_t = 0
            return (law_switch(stage, s, x, y, z, True, sign, hc, q[0], q[1], 0.0, q[3], q[4]), -1.0, -1.0)
        # A turning point at the limit: the stuck force leaves it at the rate law_switch gives (K_t0),
        # but its stiffness falls as it goes, and where that rate is near 0 the stuck force can
        # come back past the limit at once (the contact stays at the limit: sliding). So the
        # contact sticks where the stuck force, followed for MD_PROBE, is inside the limit.
        xs = stick_state(kind, stage, s, sign, hc, q)
        tp = (sign, 1.0, xs, xs)
        x1, y1, z1 = step_rk4(kind, stage, s, MD_PROBE, xs, y, z, False, sign, hc, q, tp)
        t1, p1, _, _, _ = _md_point(kind, stage, s + MD_PROBE, x1, y1, z1, hc, q, tp)
        return (p1 - abs(t1), -1.0, -1.0)
    t, p, u, ac, pdot = _md_point(kind, stage, s, x, y, z, hc, q, mem)
    rejoin = abs(x) - abs(mem[2]) if mem[1] != 0.0 else -1.0
    limit = abs(t) - p
    if mem[1] == 0.0 and pdot > 0.0:
        # Virgin loading under a growing normal force never reaches the limit: at |T| = mu P its
        # stiffness is 0 while mu P grows (d(T/P)/dt = -dP/dt / P there). A step that passes it is
        # the RK4's error at the cube root's infinite slope; it falls back (K_t = 0 until mu P
        # passes T) rather than sliding.
        limit = -1.0
    return (limit, mem[0] * u, rejoin)


@jitable(inline=True)
def step_switch(kind, stage, s, x, y, z, sliding, sign, hc, q, mem):
    """Positive when the law ``kind`` must change regime (stick to slip, or slip to stick) or, for a
    law with a memory, pass a turning point."""
    if kind == KIND_SEED:
        return switch_function(stage, s, x, y, sliding, sign, hc, q[0])
    if kind == KIND_STRONGE:
        return _stronge_switch(stage, s, x, y, sliding, sign, q[5], q[6])
    if kind == KIND_LAW:
        return law_switch(stage, s, x, y, z, sliding, sign, hc, q[0], q[1], q[2], q[3], q[4])
    return _md_switch(kind, stage, s, x, y, z, sliding, sign, hc, q, mem)


@jitable
def _md_switch(kind, stage, s, x, y, z, sliding, sign, hc, q, mem):
    """:func:`step_switch` of the Mindlin-Deresiewicz law: the largest of its events."""
    g_lim, g_rev, g_rej = _md_events(kind, stage, s, x, y, z, sliding, sign, hc, q, mem)
    return max(g_lim, max(g_rev, g_rej))


@jitable
def stick_state(kind, stage, s, sign, hc, q):
    """Stuck state ``x`` at the instant sliding in direction ``sign`` stops: ``T = -sign P`` in the law's variable."""
    if kind == KIND_SEED:
        return leave_slip(stage, s, sign, hc, q[0])
    if kind == KIND_STRONGE:
        p, _ = stronge_normal(stage, s, q[5])
        return -sign * p
    if kind == KIND_MD_CYCLE:
        return -sign
    _, a, _, p, _, _ = stage_point(stage, s, hc)
    ac = _power(a, q[1])
    return -sign * p / ac if ac > 0.0 else 0.0


@jitable
def step_event(kind, stage, s, x, y, z, sliding, sign, hc, q, mem):
    """The law's state after the event :func:`step_switch` located at ``s``: ``(x, sliding, sign, mem)``.

    Sliding stops: the stuck state :func:`stick_state`. The stuck force reaches the limit: the contact
    slides against it (``x`` unused). The Mindlin-Deresiewicz law also: the slip reverses while
    stuck, a turning point ``T_b = T`` (and ``T_a = T`` if the force was on the virgin curve); the
    force passes ``T_a``, back to the virgin curve; sliding stops where the slip has reversed, a turning
    point at the limit, else virgin loading at the limit.
    """
    md = kind == KIND_MD or kind == KIND_MD_CYCLE
    if sliding:
        xs = stick_state(kind, stage, s, sign, hc, q)
        if md:
            u = z if kind == KIND_MD_CYCLE else y + z
            if sign * u > 0.0:
                mem = (-sign, 0.0, 0.0, 0.0)
            else:
                mem = (sign, 1.0, xs, xs)
        return (xs, False, sign, mem)
    if md:
        g_lim, g_rev, g_rej = _md_events(kind, stage, s, x, y, z, False, sign, hc, q, mem)
        if g_lim <= 0.0:
            if g_rev > 0.0:
                t_a = mem[2] if mem[1] != 0.0 else x
                return (x, False, sign, (-mem[0], 1.0, t_a, x))
            return (x, False, sign, (mem[0], 0.0, 0.0, 0.0))
    _, _, _, t = step_rates(kind, stage, s, x, y, z, False, sign, hc, q, mem)
    return (0.0, True, -1.0 if t > 0.0 else 1.0, mem)


@jitable(inline=True)
def step_rk4(kind, stage, s, h, x, y, z, sliding, sign, hc, q, mem):
    """One classical RK4 step of length ``h`` of :func:`step_rates` from ``s``: the new ``(x, y, z)``."""
    k1x, k1y, k1z, _ = step_rates(kind, stage, s, x, y, z, sliding, sign, hc, q, mem)
    h2 = 0.5 * h
    k2x, k2y, k2z, _ = step_rates(
        kind, stage, s + h2, x + h2 * k1x, y + h2 * k1y, z + h2 * k1z, sliding, sign, hc, q, mem
    )
    k3x, k3y, k3z, _ = step_rates(
        kind, stage, s + h2, x + h2 * k2x, y + h2 * k2y, z + h2 * k2z, sliding, sign, hc, q, mem
    )
    k4x, k4y, k4z, _ = step_rates(kind, stage, s + h, x + h * k3x, y + h * k3y, z + h * k3z, sliding, sign, hc, q, mem)
    return (
        x + h * (k1x + 2.0 * k2x + 2.0 * k3x + k4x) / 6.0,
        y + h * (k1y + 2.0 * k2y + 2.0 * k3y + k4y) / 6.0,
        z + h * (k1z + 2.0 * k2z + 2.0 * k3z + k4z) / 6.0,
    )


@jitable
def integrate_stage(kind, stage, start, h, steps, x, y, z, sliding, sign, slid, stuck, hc, q, mem):
    """Integrate one stage of an impact under the law ``kind``: ``steps`` RK4 steps of ``h`` from ``start``.

    A step that ends past an event (:func:`step_switch` positive) is bisected (60 halvings) to the
    event, the law's state changed there (:func:`step_event`: sliding stops, the stuck force reaches
    the limit, or a turning point of a law with a memory), and the rest of the step integrated from
    there, up to 16 events within one step.

    Returns
    -------
    tuple
        ``(x, y, z, sliding, sign, slid, stuck, mem)``: the state at the stage's end, the regime then
        (sliding, and its direction), whether the contact ever slid / stuck (for :func:`regime_code`),
        and the law's memory.
    """
    for i in range(steps):
        s0 = start + i * h
        rem = h
        for _ in range(16):  # at most a few events within one step
            xn, yn, zn = step_rk4(kind, stage, s0, rem, x, y, z, sliding, sign, hc, q, mem)
            if step_switch(kind, stage, s0 + rem, xn, yn, zn, sliding, sign, hc, q, mem) <= 0.0:
                x, y, z = xn, yn, zn
                break
            lo, hi = 0.0, 1.0
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                xm, ym, zm = step_rk4(kind, stage, s0, mid * rem, x, y, z, sliding, sign, hc, q, mem)
                if step_switch(kind, stage, s0 + mid * rem, xm, ym, zm, sliding, sign, hc, q, mem) > 0.0:
                    hi = mid
                else:
                    lo = mid
            xm, ym, zm = step_rk4(kind, stage, s0, hi * rem, x, y, z, sliding, sign, hc, q, mem)
            ss = s0 + hi * rem
            x, sliding, sign, mem = step_event(kind, stage, ss, xm, ym, zm, sliding, sign, hc, q, mem)
            if sliding:
                slid = True
            else:
                stuck = True
            y, z = ym, zm
            s0 = ss
            rem = rem * (1.0 - hi)
            if rem <= 0.0:
                break
    return x, y, z, sliding, sign, slid, stuck, mem


@jitable
def regime_code(slid, stuck):
    """The regime code of :mod:`microimpact.core.tangential` (a float) of an impact that slid / stuck."""
    if slid and stuck:
        return float(REGIME_MICROSLIP)
    if slid:
        return float(REGIME_SLIDING)
    return float(REGIME_STICKING)


@jitable
def mindlin_deresiewicz_cycle(d1, d2, d3, steps):
    """The Mindlin-Deresiewicz spring at a constant normal force, moved ``0 -> d1 -> d2 -> d3``.

    The law of :data:`LAWS`' ``"mindlin_deresiewicz"`` (:func:`md_stiffness_factor`, turning points
    and Coulomb limit) on its own, integrated by :func:`integrate_stage` (``steps`` RK4 steps a leg):
    the slip moves at a constant rate along each leg, the force obeys ``dT = -K_t d(delta)``.
    Units: force ``mu P``, displacement ``mu P / K_t0``.

    Returns
    -------
    tuple
        ``(T1, T2, T3, regime)``: the force at the end of each leg and the regime code.
    """
    steps = int(steps)
    x = 0.0
    y = 0.0
    sliding = False
    sign = 1.0
    slid = False
    stuck = True
    d0 = 0.0
    mem = (-1.0 if d1 > 0.0 else 1.0, 0.0, 0.0, 0.0)
    t1 = 0.0
    t2 = 0.0
    for leg in range(3):
        d = d1 if leg == 0 else (d2 if leg == 1 else d3)
        u = 1.0 if d > d0 else -1.0
        x, y, _, sliding, sign, slid, stuck, mem = integrate_stage(
            KIND_MD_CYCLE,
            0,
            0.0,
            abs(d - d0) / steps,
            steps,
            x,
            y,
            u,
            sliding,
            sign,
            slid,
            stuck,
            NO_HISTORY,
            Q_UNIT,
            mem,
        )
        t = -sign if sliding else x
        if leg == 0:
            t1 = t
        elif leg == 1:
            t2 = t
        d0 = d
    return (t1, t2, -sign if sliding else x, regime_code(slid, stuck))
