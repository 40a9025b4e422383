"""Luding's adhesive elasto-plastic contact law, as LIGGGHTS' ``hooke/hysteresis`` computes it.

Source: Luding, S. (2008), "Cohesive, frictional powders: contact models for tension",
*Granular Matter* 10:235-246: linear loading, stiffer linear unloading, and an adhesive branch of
stiffness ``kc`` that limits the tensile force. The paper was not available to this project; the
law is read second-hand from the code that implements it, LIGGGHTS-PUBLIC
``src/normal_model_hooke_hysteresis.h`` (CFDEMproject/LIGGGHTS-PUBLIC, commit ``25fc3965``;
``gran model hooke/hysteresis``, method ``surfacesIntersect``), with its viscous damping off
(``coefficientRestitution = 1`` gives ``gamman = 0``). With ``kc = 0`` it gives the ``e``,
approaches and force of :mod:`~microimpact.core.models.luding_hysteretic` with
``plasticity_depth > 0``; its contact lasts longer, to zero approach.

The law, as the code runs it (``deltan`` is the approach ``alpha``, ``deltaMax`` the largest
approach ``alpha_max``, ``kn`` our ``k1``, ``k2Max`` our ``k2``):

* plasticity depth ``deltaMaxLim = (k2Max/(k2Max-kn))*phiF*2*reff``, ``delta_p = k2/(k2 - k1)
  phi_f 2 R*``;
* below it, ``k2(alpha_max) = kn + (k2Max-kn)*deltaMax/deltaMaxLim`` and the force is
  ``kn*deltan`` while loading, else ``fTmp = k2*(deltan-deltaMax) + kn*deltaMax``;
* from it on, ``fTmp = k2Max*(deltan-deltaMaxLim) + kn*deltaMaxLim`` in loading and unloading;
* the adhesive limit: where ``fTmp < -kc*deltan`` the force is ``-kc*deltan`` (and the code moves
  ``deltaMax`` so that reloading starts from there; an impact that separates never reloads).

The contact lasts while the approach is positive, so the particle leaves at zero approach after
crossing the adhesive branch.

Closed form (piecewise harmonic and hyperbolic motion; derived here, checked against the
integration of :func:`force` and against a step-by-step transcription of the code, history
update included, in ``tests/core/test_published_models.py``), ``omega_i = (k_i/m*)^(1/2)``:

* loading as in :mod:`~microimpact.core.models.luding_hysteretic`: ``alpha*``, ``P*``, the
  unloading stiffness ``K`` (``k2(alpha*)`` or ``k2``) and the zero-force approach of the
  unloading line ``alpha_0 = alpha* - P*/K``;
* unloading along ``P = K (alpha - alpha_0)``, harmonic about ``alpha_0`` with amplitude
  ``U = P*/K``, down to the adhesive limit ``alpha_c = K alpha_0/(K + kc)`` (speed
  ``v_c = omega_K (U^2 - (alpha_c - alpha_0)^2)^(1/2)``, after ``acos((alpha_c -
  alpha_0)/U)/omega_K``); if ``alpha_0 - alpha_c >= U`` the particle never gets there and sticks;
* the adhesive branch ``P = -kc alpha`` to zero approach: ``(e V)^2 = v_c^2 - omega_c^2
  alpha_c^2`` (the particle sticks if this is not positive), after
  ``atanh(omega_c alpha_c / v_c)/omega_c`` (``alpha_c/v_c`` for ``kc = 0``).

**Parameters of this model** (``params``, in this order):

``loading_stiffness`` ``k1`` [N/m]
    LIGGGHTS' ``kn``.
``unloading_stiffness`` ``k2`` [N/m], ``> k1``
    ``k2Max = kn * coefficientMaxElasticStiffness``.
``adhesion_stiffness`` ``kc`` [N/m], ``>= 0``
    ``kc = kn * coefficientAdhesionStiffness``.
``plasticity_depth`` ``phi_f`` [-], ``> 0``
    ``coefficientPlasticityDepth`` (``phiF``).

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is
``alpha_0`` (the contact itself ends at zero approach); ``max_contact_radius`` is the Hertz
geometry ``(R* alpha*)^(1/2)``, for comparison only; a stuck particle has ``e = 0`` and an
infinite ``unloading_time``. ``E*`` and ``p_y`` are not used.

Validity: a DEM contact law for plastic, adhesive (meso-)particles; linear springs, so its
stiffnesses are calibration parameters rather than material properties.
"""

from __future__ import annotations

import math

from .._jit import jitable
from ..constants import TINY_NORMAL, UNIT_ROUNDOFF
from . import Parameter, checks, deprecated_names
from ._common import dem_outcome, in_bounds, nan_outcome

NAME = "luding_adhesive"
TITLE = "Adhesive elasto-plastic linear law, k1 loading / k2 unloading / kc adhesion (Luding 2008; LIGGGHTS)"
CITATION = "Luding, Granular Matter 10:235 (2008); LIGGGHTS-PUBLIC normal_model_hooke_hysteresis.h"
LABEL = "Luding adhesive"
STICKS = True
PARAMETERS = (
    Parameter.of("loading_stiffness", "k1, stiffness of the loading branch (LIGGGHTS' kn)", low=0.0, low_open=True),
    Parameter.of(
        "unloading_stiffness",
        "k2 > k1, largest unloading stiffness (k2Max)",
        low="loading_stiffness",
        low_open=True,
    ),
    Parameter("adhesion_stiffness", "N/m", "kc >= 0, stiffness of the adhesive branch", low=0.0),
    Parameter.of("plasticity_depth", "phi_f > 0, LIGGGHTS' phiF", low=0.0, low_open=True),
)
BOUNDS, validate = checks(NAME, PARAMETERS)
__getattr__ = deprecated_names(__name__, NAME)  # released DEFAULTS: one release, with a warning


@jitable
def plasticity_overlap(R, params):
    """``delta_p = k2/(k2 - k1) phi_f 2 R*`` [m] (LIGGGHTS' ``deltaMaxLim``)."""
    return params[1] / (params[1] - params[0]) * params[3] * 2.0 * R


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (see the module docstring; ``E``, ``p_y`` unused)."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    k1 = params[0]
    k2 = params[1]
    kc = params[2]
    w1 = math.sqrt(k1 / m)
    if V == 0.0:
        t0 = 0.5 * math.pi / w1
        return dem_outcome(V, 1.0, 0.0, 0.0, 0.0, R, t0, t0)
    a1 = V / w1
    dp = plasticity_overlap(R, params)
    if a1 <= dp * UNIT_ROUNDOFF:
        # the plastic share of the approach, O(a1/dp), below the rounding: the small-impact limit, e = 1
        # to rounding and both stages a quarter period (below, a0 = a1 - U loses every digit, and with a1
        # subnormal or 0 the unloading's U would underflow into a spurious capture)
        t0 = 0.5 * math.pi / w1
        return dem_outcome(V, 1.0, a1, 0.0, k1 * a1, R, t0, t0)
    if a1 <= dp:
        K = k1 + (k2 - k1) * a1 / dp
        amax = a1
        Pm = k1 * a1
        t_load = 0.5 * math.pi / w1
        U = Pm / K
        a0 = amax - U
    else:
        K = k2
        w2 = math.sqrt(k2 / m)
        t1 = math.asin(w1 * dp / V) / w1
        vp2 = V * V - (w1 * dp) * (w1 * dp)
        up = k1 * dp / k2
        a0 = dp - up
        U = math.sqrt(up * up + vp2 / (w2 * w2))
        amax = a0 + U
        Pm = k2 * U
        t_load = t1 + (0.5 * math.pi - math.asin(up / U)) / w2
    wK = math.sqrt(K / m)
    ac = K * a0 / (K + kc)
    x = ac - a0  # <= 0: the adhesive limit lies beyond the zero-force approach
    if x > 0.0:  # rounded past a0 where kc is negligible beside K: the same difference, exactly <= 0
        x = -kc * a0 / (K + kc)
    if -x >= U:  # the unloading line turns the particle back before the adhesive branch
        return dem_outcome(V, 0.0, amax, a0, Pm, R, t_load, math.inf)
    s = (U - x) * (U + x)
    if s >= TINY_NORMAL:
        vc = wK * math.sqrt(s)
    else:  # U^2 leaves the normal doubles (a stiffness near the largest double, where K/m may overflow too)
        r = x / U
        vc = math.sqrt(K) * (U / math.sqrt(m)) * math.sqrt((1.0 - r) * (1.0 + r))
    t_un = math.acos(x / U) / wK
    if kc == 0.0:
        e = vc / V
        t_un += ac / vc
    else:
        wc = math.sqrt(kc / m)
        q = wc * ac / vc
        if q >= 1.0:  # the adhesive branch holds the particle
            return dem_outcome(V, 0.0, amax, a0, Pm, R, t_load, math.inf)
        e = vc * math.sqrt((1.0 - q) * (1.0 + q)) / V
        t_un += math.atanh(q) / wc
    return dem_outcome(V, e, amax, a0, Pm, R, t_load, t_un)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """LIGGGHTS' ``fHys`` [N] at approach ``alpha > 0`` with largest approach so far ``alpha_max``."""
    k1 = params[0]
    k2 = params[1]
    kc = params[2]
    dp = plasticity_overlap(R, params)
    amax = alpha_max if alpha_max > alpha else alpha
    if amax >= dp:
        f = k2 * (alpha - dp) + k1 * dp
    else:
        K = k1 + (k2 - k1) * amax / dp
        f = K * (alpha - amax) + k1 * amax
        if f >= k1 * alpha:
            f = k1 * alpha
    return f if f > -kc * alpha else -kc * alpha


@jitable
def ends_at_zero_force(params):
    """False: the contact lasts while the approach is positive (it ends at zero approach)."""
    return False


@jitable
def separation_approach(E, R, m, p_y, params):
    """Approach [m] at which the contact ends: 0."""
    return 0.0


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N]: :func:`signed_force` while the approach is positive, zero outside."""
    if alpha <= 0.0:
        return 0.0
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)
