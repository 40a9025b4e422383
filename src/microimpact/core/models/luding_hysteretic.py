"""Linear hysteretic (elastic-plastic) spring of Walton & Braun and Luding, without damping or adhesion.

The contact law DEM codes offer for plastic particles, known after Walton & Braun (1986, J. Rheol.
30, 949) and Luding (2008, Granular Matter 10, 235); those papers were not available to this
project, and the formulas here are those of the two codes read, DEMLab
(``src/interactions/force_models/ContactForceN_ElastoPlasticLinear.m``) and LIGGGHTS-PUBLIC
(``src/normal_model_hooke_hysteresis.h``): loading along a soft spring ``k1``, unloading along a stiffer one ``k2`` from the largest approach
``alpha_max``, down to the plastic approach ``alpha_0 = (1 - k1/k2) alpha_max`` where the force
vanishes and the particle leaves:

.. math::  P = \\min\\left(k_1 \\alpha,\\; k_1 \\alpha_{max} + k_2 (\\alpha - \\alpha_{max})\\right), \\qquad P \\ge 0 .

Two variants, chosen by ``plasticity_depth``:

* ``plasticity_depth = 0`` (default): ``k2`` constant (Walton & Braun's constant unloading
  stiffness; DEMLab ``ContactForceN_ElastoPlasticLinear`` with ``unload_stiff = stiff / e^2``):
  ``e = (k1/k2)^(1/2)`` at every speed.
* ``plasticity_depth = phi_f > 0``: Luding's unloading stiffness growing with ``alpha_max`` up to
  ``k2`` at the plasticity depth ``delta_p = k2/(k2 - k1) phi_f 2 R*``, as LIGGGHTS-PUBLIC's
  ``gran model hooke/hysteresis`` computes it (``src/normal_model_hooke_hysteresis.h``:
  ``k2(alpha_max) = k1 + (k2 - k1) alpha_max/delta_p`` below ``delta_p``; above it the contact
  follows the line ``k2 (alpha - delta_p) + k1 delta_p`` in loading and unloading), with its
  adhesion stiffness ``kc`` and its viscous damping set to zero (``kn2kc = 0``,
  ``coefficientRestitution = 1``).

**Parameters of this model** (``params``, in this order):

``loading_stiffness`` ``k1`` [N/m]
    Stiffness of the loading branch.
``unloading_stiffness`` ``k2`` [N/m], ``>= k1``
    Stiffness of the unloading branch (the largest one, ``k2Max``, for ``plasticity_depth > 0``).
``plasticity_depth`` ``phi_f`` [-], ``>= 0``
    0 for a constant ``k2``; otherwise LIGGGHTS' ``phiF``.

Closed form (piecewise harmonic motion; derived here, checked against the integration of
:func:`force` in ``tests/core/test_models.py``), ``omega_i = (k_i/m*)^(1/2)``:

* constant ``k2`` (and Luding's law while ``alpha_max = V/omega_1 <= delta_p``, with ``k2`` replaced
  by ``k2(alpha_max)``): ``alpha* = V/omega_1``, ``P* = k1 alpha*``, ``e = (k1/k2)^(1/2)``,
  ``alpha_0 = (1 - k1/k2) alpha*`` (DEMLab's residual overlap ``V (m*/k1)^(1/2) (1 - e^2)``),
  ``t_L = pi/(2 omega_1)``, ``t_U = pi/(2 omega_2)``;
* Luding's law beyond ``delta_p``: ``k1`` loading to ``delta_p`` (reached at speed
  ``v_p = (V^2 - omega_1^2 delta_p^2)^(1/2)`` after ``asin(omega_1 delta_p / V)/omega_1``), then
  harmonic motion with ``omega_2`` about ``delta_0 = (1 - k1/k2) delta_p``, of amplitude
  ``U = ((k1 delta_p/k2)^2 + v_p^2/omega_2^2)^(1/2)``: ``alpha* = delta_0 + U``, ``P* = k2 U``,
  ``e = omega_2 U / V``, ``alpha_p = delta_0``.

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``max_contact_radius`` is
the Hertz geometry ``(R* alpha*)^(1/2)``, for comparison only. ``E*`` and ``p_y`` are not used.

Validity: a numerical contact law; with constant ``k2`` its ``e`` does not depend on the speed.
"""

from __future__ import annotations

import math

from .._jit import jitable
from . import Parameter, checks, deprecated_names
from ._common import dem_outcome, in_bounds, nan_outcome

NAME = "luding_hysteretic"
TITLE = "Linear hysteretic spring, k1 loading / k2 unloading (Walton & Braun 1986; Luding 2008)"
CITATION = "Walton & Braun, J. Rheol. 30:949 (1986); Luding, Granular Matter 10:235 (2008)"
LABEL = "Luding hysteretic"
PARAMETERS = (
    Parameter.of("loading_stiffness", "k1, stiffness of the loading branch", low=0.0, low_open=True),
    Parameter.of(
        "unloading_stiffness",
        "k2 >= k1, stiffness of the unloading branch (largest one if plasticity_depth > 0)",
        low="loading_stiffness",
    ),
    Parameter.of(
        "plasticity_depth",
        "phi_f = 0: constant k2; > 0: Luding's k2(alpha_max) with LIGGGHTS' phiF",
        default=0.0,
        low=0.0,
    ),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(__name__, NAME)  # released DEFAULTS: one release, with a warning
#: Order of the zero of :func:`signed_force` where the contact ends: the unloading branch
#: ``k2 (alpha - alpha_0)`` is linear, a simple zero.
ZERO_FORCE_ORDER = 1.0


@jitable
def plasticity_overlap(R, params):
    """Luding's plasticity depth ``delta_p = k2/(k2 - k1) phi_f 2 R*`` [m] (inf for constant ``k2``)."""
    k1 = params[0]
    k2 = params[1]
    phi = params[2]
    if phi == 0.0:
        return math.inf
    if k2 == k1:
        return math.inf
    return k2 / (k2 - k1) * phi * 2.0 * R


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (see the module docstring; ``E``, ``p_y`` unused)."""
    if not in_bounds(params, BOUNDS):
        return nan_outcome(V)
    k1 = params[0]
    k2 = params[1]
    w1 = math.sqrt(k1 / m)
    a1 = V / w1
    dp = plasticity_overlap(R, params)
    if a1 <= dp:
        if params[2] > 0.0:
            k2 = k1 + (k2 - k1) * a1 / dp
        w2 = math.sqrt(k2 / m)
        e = math.sqrt(k1 / k2)
        return dem_outcome(V, e, a1, (1.0 - k1 / k2) * a1, k1 * a1, R, 0.5 * math.pi / w1, 0.5 * math.pi / w2)
    w2 = math.sqrt(k2 / m)
    t1 = math.asin(w1 * dp / V) / w1
    vp2 = V * V - (w1 * dp) * (w1 * dp)
    up = k1 * dp / k2
    d0 = dp - up
    U = math.sqrt(up * up + vp2 / (w2 * w2))
    t2 = (0.5 * math.pi - math.asin(up / U)) / w2
    # e <= 1 exactly in arithmetic (U <= V/w2); rounding gave 1 + 1 ulp where dp -> 0
    e = min(w2 * U / V, 1.0)
    return dem_outcome(V, e, d0 + U, d0, k2 * U, R, t1 + t2, 0.5 * math.pi / w2)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """The hysteretic law [N] before clipping at zero (negative below ``alpha_0``)."""
    k1 = params[0]
    k2 = params[1]
    dp = plasticity_overlap(R, params)
    amax = alpha_max if alpha_max > alpha else alpha
    if amax >= dp:
        return k2 * (alpha - dp) + k1 * dp
    if params[2] > 0.0:
        k2 = k1 + (k2 - k1) * amax / dp
    p_un = k1 * amax + k2 * (alpha - amax)
    p_lo = k1 * alpha
    return p_un if p_un < p_lo else p_lo


@jitable
def ends_at_zero_force(params):
    """Always True: the particle leaves where the unloading force vanishes (at ``alpha_0 > 0``)."""
    return True


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N] at approach ``alpha`` with largest approach so far ``alpha_max`` (>= 0)."""
    p = signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)
    return p if p > 0.0 else 0.0


@jitable
def loading_stiffness_for(e, t_c, m):
    """``k1 = m* (pi (1 + e)/(2 t_c))^2`` [N/m]: the loading stiffness whose impact lasts ``t_c`` [s] with ``e``.

    The inverse of the contact time of the constant-``k2`` spring (module docstring):
    ``t_c = pi/(2 omega_1) + pi/(2 omega_2)`` with ``omega_2 = omega_1/e`` (``e = (k1/k2)^(1/2)``).
    """
    w = math.pi * (1.0 + e) / (2.0 * t_c)
    return m * (w * w)


@jitable
def plasticity_depth_for(V, e, k1, k2, m, R):
    """Luding's ``phi_f`` [-] that gives the restitution ``e`` at the speed ``V`` [m/s], given ``k1 < k2``.

    While ``alpha* = V/omega_1 <= delta_p`` (module docstring), ``e^2 = k1/k2(alpha*)`` with
    ``k2(alpha*) = k1 + (k2 - k1) alpha*/delta_p``; so ``delta_p = (k2 - k1) alpha*/(k1/e^2 - k1)``, and
    ``phi_f = delta_p (k2 - k1)/(2 k2 R*)`` inverts :func:`plasticity_overlap`.
    """
    a1 = V * math.sqrt(m / k1)
    dp = (k2 - k1) * a1 / (k1 / (e * e) - k1)
    return dp * (k2 - k1) / (k2 * 2.0 * R)


@jitable
def characteristic_velocity(k1, E, R, m):
    """LIGGGHTS' ``characteristicVelocity`` ``v_c`` [m/s] that makes its ``hooke`` stiffness equal ``k1`` [N/m].

    LIGGGHTS-PUBLIC ``src/normal_model_hooke.h`` sets
    ``k_n = 16/15 R^(1/2) Y* (15 m* v_c^2/(16 R^(1/2) Y*))^(1/5)``; with ``Y* = E*`` this is
    ``v_c = ((15 k1/(16 R^(1/2) E*))^5 16 R^(1/2) E*/(15 m*))^(1/2)``.
    """
    sq = math.sqrt(R)
    q = 15.0 * k1 / (16.0 * sq * E)
    q2 = q * q
    return math.sqrt((q2 * q2) * q * 16.0 * sq * E / (15.0 * m))
