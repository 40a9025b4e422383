"""Elastic adhesive impact with the DMT contact law, as LAMMPS' ``pair_style granular`` ``dmt`` computes it.

The force of Derjaguin, Muller & Toporov (1975, J. Colloid Interface Sci. 53, 314) between an
elastic sphere and a flat, as LAMMPS writes it (``doc/src/pair_granular.rst``, normal model ``dmt``:
"the force is simply Hertz with an additional attractive cohesion term"; the kernel
``gran_normal_dmt_force`` of ``src/GRANULAR``: ``Fne = k a delta - 4 pi gamma R``, ``k = 4/3 E``,
``a = (R delta)^(1/2)``):

.. math::  P = \\tfrac{4}{3} E^* R^{*1/2} \\alpha^{3/2} - 4 \\pi \\gamma R^* \\qquad (\\alpha \\ge 0),

with the surface energy ``gamma`` (LAMMPS' ``cohesion``; the work of adhesion is ``G = 2 gamma``, so
the constant pull ``4 pi gamma R* = 2 pi G R*`` is DMT's pull-off force, 4/3 of JKR's
``3 pi gamma R*``). Unlike LAMMPS' ``jkr``, the ``dmt`` model has no force beyond contact: the
contact exists while ``alpha >= 0`` (LAMMPS' default ``touch``, no ``beyond_contact``), so the force
jumps to ``-4 pi gamma R*`` at first touch and back to 0 when the approach returns to zero. No
damping (LAMMPS' damping coefficient 0).

The force is a function of the approach alone on ``alpha >= 0``: the impact is conservative. The
particle gains ``4 pi gamma R* alpha`` from the attraction on the way in and gives it back on the way
out, so it leaves at the speed it came, ``e = 1``, at every speed, and never sticks: in the DMT limit
(small, stiff particles: Tabor parameter well below 1, :func:`microimpact.core.adhesion.tabor_parameter`)
adhesion changes the contact (a deeper approach, a longer contact) but takes no energy. (Adhesive
losses in that limit come from elsewhere: plasticity, damping; this law has neither.)

Derived here: the energy ``W(alpha) = 2/5 k alpha^(5/2) - F_c alpha`` (``k = 4/3 E* R*^(1/2)``,
``F_c = 4 pi gamma R*``) gives the maximum approach from ``W(alpha_m) = m* V^2/2``, a polynomial in
``b = alpha^(1/2)`` with one positive root (Newton from above, where it is convex and increasing), and
the loading time ``t_L = int_0^alpha_m d alpha / v(alpha)``, by Gauss-Legendre quadratures after
substitutions that leave analytic integrands (:func:`loading_time`): ``b = b_m - w^2`` near the
turning point (``4 (b_m - w^2) / (2/m* Q(b))^(1/2)``, ``Q(b) = (W(b_m) - W(b))/(b_m - b)`` written
without cancellation) and ``b = (K/F_c)^(1/2) sinh u`` near first touch. The unloading retraces the loading: ``t_U = t_L``. (Agreement with the integration of
:func:`force` to 1e-8 is tested.)

**Parameters of this model** (``params``):

``surface_energy`` ``gamma`` [J/m^2], ``>= 0``
    LAMMPS' ``cohesion`` of the ``dmt`` normal model (work of adhesion ``2 gamma``); 0 gives
    Hertz's elastic impact.

Fields this model does not define (NaN): ``yield_velocity``, ``normalized_velocity``,
``unloading_radius``, ``elastic_stage_time``, ``plastic_stage_time``. ``plastic_approach`` is 0 (the
contact ends at zero approach). ``max_contact_radius`` is Hertz's ``(R* alpha_m)^(1/2)`` (DMT keeps
the Hertz profile). ``p_y`` is not used.

Validity: elastic spheres with a long-range, weak adhesion (DMT limit: small, stiff particles, Tabor
parameter well below 1); no plasticity, no damping.
"""

from __future__ import annotations

import math

from .._jit import jitable
from ..constants import UNIT_ROUNDOFF
from . import Parameter, checks
from ._common import dem_outcome, in_bounds, nan_outcome
from ._jkr import GW, GX

NAME = "dmt_elastic_adhesive"
TITLE = "DMT elastic adhesion: Hertz minus 4 pi gamma R while in contact (LAMMPS granular dmt)"
CITATION = "Derjaguin, Muller & Toporov, J. Colloid Interface Sci. 53:314 (1975); LAMMPS pair_style granular dmt"
LABEL = "DMT adhesive"
#: The particle never sticks (the law is conservative: ``e = 1``).
STICKS = False
#: Not the wall's adhesion law (:func:`microimpact.adhesion.check_adhesion_rule` gives the reason).
WALL_REFUSAL = (
    "the DMT elastic adhesive law returns all the energy (e = 1 at every speed, as LAMMPS' dmt), so at the wall "
    "it would never capture a particle and would drop the plastic loss (use it with pair.impact(model=...) for "
    "the contact itself)"
)
PARAMETERS = (Parameter.of("surface_energy", "gamma >= 0, LAMMPS' cohesion (work of adhesion 2 gamma)", low=0.0),)
BOUNDS, validate = checks(NAME, PARAMETERS)


@jitable
def pulloff_force(R, gamma):
    """DMT's pull-off force ``4 pi gamma R*`` [N] (LAMMPS ``F_pulloff`` of ``dmt``; ``2 pi G R*``)."""
    return 4.0 * math.pi * gamma * R


@jitable
def _q(x, y, k, Fc):
    """``(W(x) - W(y))/(x - y)`` in ``b = alpha^(1/2)``, ``W = 2/5 k b^5 - F_c b^2``, without cancellation."""
    x2 = x * x
    y2 = y * y
    return 0.4 * k * (x2 * x2 + x2 * x * y + x2 * y2 + x * y2 * y + y2 * y2) - Fc * (x + y)


@jitable
def _fifth(b):
    """``b^5`` as numba computes ``b**5``, ``(b^2)^2 b``: Python's ``**`` is libm's ``pow``, not always that."""
    b2 = b * b
    return (b2 * b2) * b


@jitable
def max_approach_root(K, k, Fc):
    """``b_m = alpha_m^(1/2)`` [m^(1/2)] where ``2/5 k b^5 - F_c b^2 = K >= 0`` (Newton from above)."""
    b = max((2.5 * K / k) ** 0.2, (2.5 * Fc / k) ** (1.0 / 3.0))
    while 0.4 * k * _fifth(b) - Fc * b * b <= K:
        b *= 1.5
    for _ in range(200):
        f = 0.4 * k * _fifth(b) - Fc * b * b - K
        step = f / (2.0 * k * ((b * b) * (b * b)) - 2.0 * Fc * b)
        b -= step
        if abs(step) <= 1e-16 * b:
            break
    return b


@jitable
def _loading_time_from_rest(bs, k, Fc, m):
    """``int_0^(bs^2) d alpha / v`` [s] at ``K = 0``: with ``v^2 = 2 (F_c b^2 - 2/5 k b^5)/m`` and
    ``d alpha = 2 b db`` the integrand ``2 (2 (F_c - 2/5 k b^3)/m)^(-1/2)`` is smooth (the adhesion pulls
    the particle in from rest as a constant force would), one 48-point Gauss-Legendre rule on
    ``[0, bs]``. The limit of :func:`loading_time`'s lower part as ``c = (K/F_c)^(1/2)`` falls below
    ``bs`` times the rounding (it differs by ``O(c/bs)``), where the ``sinh`` substitution's range
    ``asinh(bs/c)`` has grown past what its 48 points resolve, and ``K`` or ``c`` may underflow."""
    low = 0.0
    for i in range(48):
        b = 0.5 * bs * (GX[i] + 1.0)
        low += GW[i] * 2.0 / math.sqrt(2.0 * (Fc - 0.4 * k * (b * b * b)) / m)
    return 0.5 * bs * low


@jitable
def loading_time(bm, K, k, Fc, m):
    """``t_L = int_0^alpha_m d alpha / v`` [s] for the impact energy ``K`` (module docstring): two
    48-point Gauss-Legendre quadratures in ``b = alpha^(1/2)``, split at ``b_m/2``. Above it
    ``b = b_m - w^2`` (the turning point); below it, with adhesion, ``b = (K/F_c)^(1/2) sinh(u)``,
    which takes ``K + F_c b^2`` to ``K cosh^2 u`` (slow impacts: the attraction speeds the particle
    up within a short distance of first touch, where ``v`` in ``b`` varies on the scale
    ``(K/F_c)^(1/2)``)."""
    bs = 0.5 * bm if Fc > 0.0 else 0.0
    W = math.sqrt(bm - bs)
    top = 0.0
    for i in range(48):
        w = 0.5 * W * (GX[i] + 1.0)
        b = bm - w * w
        top += GW[i] * 4.0 * b / math.sqrt(2.0 * _q(bm, b, k, Fc) / m)
    t = 0.5 * W * top
    if bs > 0.0:
        c = math.sqrt(K / Fc)
        if not c > bs * UNIT_ROUNDOFF:  # K's share of the time below the rounding: its limit K = 0
            return t + _loading_time_from_rest(bs, k, Fc, m)
        U = math.asinh(bs / c)
        low = 0.0
        for i in range(48):
            u = 0.5 * U * (GX[i] + 1.0)
            sh = math.sinh(u)
            ch = math.cosh(u)
            b = c * sh
            low += GW[i] * 2.0 * c * c * sh * ch / math.sqrt(2.0 * (K * ch * ch - 0.4 * k * _fifth(b)) / m)
        t += 0.5 * U * low
    return t


@jitable
def outcome(V, E, R, m, p_y, params):
    """Outcome of one impact (see the module docstring; ``p_y`` unused)."""
    if not in_bounds(params, BOUNDS) or not (V >= 0.0 and V < math.inf):
        return nan_outcome(V)
    gamma = params[0]
    k = 4.0 / 3.0 * E * math.sqrt(R)
    Fc = pulloff_force(R, gamma)
    if V == 0.0:
        return dem_outcome(V, 1.0, 0.0, 0.0, 0.0, R, math.inf, math.inf)
    K = 0.5 * m * V * V
    bm = max_approach_root(K, k, Fc)
    am = bm * bm
    t = loading_time(bm, K, k, Fc, m)
    return dem_outcome(V, 1.0, am, 0.0, k * am * bm - Fc, R, t, t)


@jitable
def signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """The DMT force [N] at ``alpha >= 0``: Hertz minus ``4 pi gamma R*``."""
    a = math.sqrt(R * alpha) if alpha > 0.0 else 0.0
    return 4.0 / 3.0 * E * a * alpha - pulloff_force(R, params[0])


@jitable
def ends_at_zero_force(params):
    """False with adhesion: the contact ends at zero approach, where the force is ``-4 pi gamma R*``."""
    return params[0] == 0.0


@jitable
def separation_approach(E, R, m, p_y, params):
    """Approach [m] at which the contact ends: 0 (LAMMPS' ``dmt`` has no force beyond contact)."""
    return 0.0


@jitable
def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
    """Normal force [N]: :func:`signed_force` while in contact (``alpha >= 0``), zero apart."""
    if alpha < 0.0:
        return 0.0
    return signed_force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)


#: The adhesion limit the law is written for (``"JKR"``: Tabor parameter large; ``"DMT"``: small):
#: :meth:`microimpact.pair.ContactPair.impact` flags pairs outside it
#: (:func:`microimpact.core.adhesion.tabor_parameter`).
ADHESION_LIMIT = "DMT"


@jitable
def work_of_adhesion(params):
    """The work of adhesion ``G`` [J/m^2] of ``params`` (twice LAMMPS' ``cohesion``: ``2 gamma``), for Tabor's parameter."""
    return 2.0 * params[0]
