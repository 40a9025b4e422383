"""Adhesion at impact: Thornton & Ning's (1998) sticking velocity and the adhesive restitution.

The seed's elastic-plastic restitution ``e_p(V/V_y)`` (eqs. 22, 27, 28) of the normal impact
speed ``V`` combined with the adhesion loss of Thornton & Ning (1998): the elastic-adhesive
sticking velocity ``V_s`` (:func:`sticking_velocity`) enters as an additional energy loss,
``e^2 = e_p^2 - (V_s/V)^2``; the particle sticks when ``e_p V <= V_s``
(:func:`adhesive_restitution`). With no adhesion (``G = 0``) nothing sticks and ``e = e_p``,
the seed's model unchanged.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ._validation import TINY_NORMAL, check_nonnegative, check_positive
from .core import adhesion as _core
from .core.adhesion import STICKING_CONSTANT  # noqa: F401  (its old home; the core's is the one)
from .core.models import Parameter, declare
from .engine import evaluate

__all__ = [
    "work_of_adhesion",
    "sticking_velocity",
    "adhesive_restitution",
    "ADDITIVE_RULE",
    "ADDITIVE",
    "FIT_RULES",
    "ADHESION_RULES",
    "WHOLE_LAW",
    "check_adhesion_rule",
    "whole_law_correction",
    "whole_law_restitution",
    "WholeLawTable",
    "whole_law_table",
]

#: The name of Thornton & Ning's (1998) additive rule (:func:`adhesive_restitution`): the wall's default
#: ``adhesion=``, and a candidate of :func:`~microimpact.fitting.fit_restitution` and
#: :func:`~microimpact.fitting.rank_models` beside the models (:data:`ADDITIVE`).
ADDITIVE_RULE = "additive"


class _AdditiveRule:
    """Thornton & Ning's (1998) additive rule as a candidate of fitting and ranking
    (:data:`ADDITIVE_RULE`): the seed's ``e_p(V/V_y)`` (eq. 27) with the adhesive loss
    ``e^2 = e_p^2 - (V_s/V)^2``, stuck where ``e_p V <= V_s`` (:func:`adhesive_restitution`; ``V_s``
    their eq. 54). It is a rule for ``e``, not a model of the zoo (no force law, no contact times):
    it is fitted and ranked only. Declared to the model contract for its parameter spec."""

    NAME = ADDITIVE_RULE
    TITLE = "Thornton & Ning (1998) additive rule: e^2 = e_p^2 - (V_s/V)^2 (seed eq. 27, TN98 eq. 54)"
    PARAMETERS = (Parameter.of("work_of_adhesion", "G >= 0, the work of adhesion (TN98's interface energy)", low=0.0),)
    STICKS = True
    outcome = None  # e alone, by restitution_of_pair
    force = None

    @staticmethod
    def restitution_of_pair(pair, params, V):
        """``e`` [-] at speeds ``V`` [m/s] for ``pair`` (a :class:`~microimpact.pair.ContactPair`)
        and ``params = (G,)``: :func:`adhesive_restitution` with :func:`sticking_velocity`."""
        Vs = sticking_velocity(float(params[0]), pair.effective_modulus, pair.effective_radius, pair.effective_mass)
        return adhesive_restitution(V, pair.yield_velocity, Vs)


#: The additive rule's declaration (:class:`~microimpact.core.models.Model`): its parameter spec
#: (``work_of_adhesion`` [J/m^2]), ``STICKS``, and ``restitution_of_pair(pair, params, V)``, its ``e``
#: [-] over speeds [m/s] (it has no outcome or force law: a rule for ``e``, fitted and ranked only).
ADDITIVE = declare(_AdditiveRule)

#: The rules for ``e`` that :func:`~microimpact.fitting.fit_restitution` and
#: :func:`~microimpact.fitting.rank_models` take beside the models, by their declarations (each with
#: ``restitution_of_pair(pair, params, V)`` in place of an outcome): the additive rule.
FIT_RULES = (ADDITIVE,)

#: What ``adhesion=`` of :func:`~microimpact.wall.wall_interaction` and the C export accept: the
#: additive rule (:func:`adhesive_restitution`, the default) and each model that declares
#: ``WALL_ADHESION`` (the model contract, :mod:`microimpact.core.models`): Thornton & Ning's whole
#: law, through :func:`whole_law_table`. Derived from the declarations on first use.
ADHESION_RULES: tuple

#: The whole adhesive elastic-plastic law of Thornton & Ning (1998) by its model name: the model
#: that declares ``WALL_ADHESION`` (:mod:`~microimpact.core.models.thornton_ning_1998_adhesive_plastic`).
WHOLE_LAW: str


def _wall_laws() -> tuple:
    from .core import models

    # the wall's table is one law's (core.adhesion.whole_law_correction): never another's
    return (models.whole_law(),)


def __getattr__(name):  # ADHESION_RULES and WHOLE_LAW: read from the models' declarations once, when asked
    if name == "ADHESION_RULES":
        value = (ADDITIVE_RULE, *_wall_laws())
    elif name == "WHOLE_LAW":
        value = _wall_laws()[0]
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def check_adhesion_rule(adhesion, name="adhesion"):
    """``adhesion`` if it is one of :data:`ADHESION_RULES`; else a ValueError naming ``name``, the value
    and the allowed values.

    A model that declares why it cannot be the wall's adhesion law (``WALL_REFUSAL`` of the model
    contract) is refused with that reason: the DMT elastic adhesive law
    (:mod:`~microimpact.core.models.dmt_elastic_adhesive`) is conservative (``e = 1`` at every
    speed, as LAMMPS' ``dmt``), so as the wall's normal law it would never capture a particle and
    would drop the plastic loss, and no source read here combines DMT adhesion with yield (the
    additive rule adds TN98's JKR loss, eq. 54, which DMT does not have).
    """
    if isinstance(adhesion, str) and adhesion == ADDITIVE_RULE:  # the default: no model need be read
        return adhesion
    rules = globals().get("ADHESION_RULES") or __getattr__("ADHESION_RULES")
    if isinstance(adhesion, str) and adhesion in rules:
        return adhesion
    allowed = ", ".join(repr(r) for r in rules)
    reason = None
    if isinstance(adhesion, str):
        from .core import models

        if adhesion in models.available():
            reason = models.get(adhesion).WALL_REFUSAL
    if reason:
        raise ValueError(f"{name} must be one of {allowed}, got {adhesion!r}: {reason}")
    raise ValueError(f"{name} must be one of {allowed}, got {adhesion!r}")


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

    ``V_s = (14.1844 / m*)^(1/2) (G^5 R*^4 / E*^2)^(1/6)``

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
    Thornton & Ning (1998), Powder Technol. 99:154-162, eq. 54; the constant
    is twice the JKR separation work 7.0922 (see :data:`STICKING_CONSTANT`:
    derived, where the paper prints the rounded 14.18), checked in the tests by
    integrating the JKR force-approach curve.

    Examples
    --------
    >>> import math
    >>> m = 4 / 3 * math.pi * 0.5e-6**3 * 1350.0   # 1 um NH4Fl sphere
    >>> round(float(sticking_velocity(0.1, 1.31e9, 0.5e-6, m)), 3)
    1.197
    """
    G = check_nonnegative("work_of_adhesion", work_of_adhesion)
    E = check_positive("effective_modulus", effective_modulus)
    R = check_positive("effective_radius", effective_radius)
    m = check_positive("effective_mass", effective_mass)
    small = np.asarray(E < math.sqrt(TINY_NORMAL)) & np.asarray(G > 0.0)
    tiny = np.broadcast_to(E, small.shape)[small]
    if tiny.size:  # the formula divides by E*^2, which underflows to zero
        raise ValueError(
            f"effective_modulus {float(tiny.flat[0])!r} Pa is so small that E*^2 underflows (below "
            f"{math.sqrt(TINY_NORMAL):.4g} Pa): V_s = (C/m*)^(1/2) (G^5 R*^4/E*^2)^(1/6) has no value there"
        )
    return evaluate(_core.sticking_velocity, G, E, R, m)[0]


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
    V, Vy, Vs = _checked_speeds(velocity, yield_velocity, sticking_velocity)
    return evaluate(_core.restitution, V, Vy, Vs, nout=2)[0]


# ----------------------------------------------------------------------------- the whole law's table
@dataclass(frozen=True, eq=False)
class WholeLawTable:
    """The whole law's correction ``D(V/V_y, V_s/V_y)`` on a grid (:func:`whole_law_table`).

    ``D`` (:func:`microimpact.core.adhesion.whole_law_correction`) is what the whole adhesive
    elastic-plastic law of Thornton & Ning (1998) adds to the additive rule's ``e^2``:
    ``e^2 = e_p(V/V_y)^2 - (V_s/V)^2 + D``, the particle sticking where that is not positive
    (:func:`microimpact.core.adhesion.corrected_restitution`). Nodes are uniform in
    ``t = log10(V/V_y)`` (one at ``t = 0``, the seed's yield) and in ``u = (V_s/V_y)^(3/5)``
    (proportional to ``lambda = s R*/a_y0^(3/2)``, in which ``D`` grows linearly from ``u = 0``,
    where it is 0); bilinear interpolation, in the order of operations the C export copies.

    Below the first ``t`` node the value at it is used: exact there (the whole law does not yield
    below ``V/V_y = 10^t_lo`` unless it sticks: the tests check it). Above the last ``t`` node or the
    last ``u`` node the value at the edge is used and the point is flagged (``outside``).

    Attributes
    ----------
    t : ndarray (n_t,)
        ``log10(V/V_y)`` [-] of the nodes.
    u : ndarray (n_u,)
        ``(V_s/V_y)^(3/5)`` [-] of the nodes.
    values : ndarray (n_u, n_t)
        ``D`` [-] at the nodes.
    """

    t: np.ndarray
    u: np.ndarray
    values: np.ndarray

    @property
    def t_scale(self) -> float:
        """``1/dt``: nodes per unit of ``t``."""
        return (self.t.size - 1) / (float(self.t[-1]) - float(self.t[0]))

    @property
    def u_scale(self) -> float:
        """``1/du``: nodes per unit of ``u``."""
        return (self.u.size - 1) / float(self.u[-1])

    @property
    def x_max(self) -> float:
        """The largest ``V/V_y`` of the table [-]."""
        return 10.0 ** float(self.t[-1])

    @property
    def y_max(self) -> float:
        """The largest ``V_s/V_y`` of the table [-]."""
        return float(self.u[-1]) ** (5.0 / 3.0)

    def __call__(self, x, y):
        """``(D, outside)`` at ``x = V/V_y`` >= 0 and ``y = V_s/V_y`` >= 0 (arrays broadcast).

        ``outside`` is True where ``t > t[-1]`` or ``u > u[-1]`` (the edge's value is used).
        """
        x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
        t0, t1, u1 = float(self.t[0]), float(self.t[-1]), float(self.u[-1])
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(x > 0.0, np.log10(np.where(x > 0.0, x, 1.0)), t0)
            u = np.power(y, 0.6)
        outside = (t > t1) | (u > u1)
        ft = np.minimum(np.maximum((t - t0) * self.t_scale, 0.0), self.t.size - 1.0)
        fu = np.minimum(np.maximum(u * self.u_scale, 0.0), self.u.size - 1.0)
        i = np.minimum(ft.astype(np.intp), self.t.size - 2)
        j = np.minimum(fu.astype(np.intp), self.u.size - 2)
        a = ft - i
        b = fu - j
        v = self.values
        D = (1.0 - b) * ((1.0 - a) * v[j, i] + a * v[j, i + 1]) + b * ((1.0 - a) * v[j + 1, i] + a * v[j + 1, i + 1])
        return D, outside


def whole_law_table(*, t_min=-1.0, t_max=3.0, n_t=161, y_max=10.0, n_u=81) -> WholeLawTable:
    """The :class:`WholeLawTable` (built on first use from the model, then cached on disk).

    Building evaluates :func:`microimpact.core.adhesion.whole_law_correction` at every node
    (``n_t x n_u`` impacts of the whole law, in closed form; compiled, well under a second);
    the table is kept in the cache folder (:mod:`microimpact.engine.cache`), named by its grid and
    a hash of the sources that compute it.

    The default grid (``V/V_y`` from 0.1 to 1000, ``V_s/V_y`` from 0 to 10, 161 x 81 nodes) against
    the whole law, measured over 10^6 random points of that range: ``|de|`` at most 3.5e-3 where
    ``e > 0.3`` and 1.05e-2 where ``e > 0.1``; next to the capture speed, where ``e`` rises from 0
    like a square root, up to 3.7e-2; ``|d(e^2)|`` at most 2.6e-3; mean ``|de|`` 3e-5; the capture
    speed within 1.4e-3 (relative) of the model's. Below ``V/V_y = 0.1`` it is exact (the law has
    not yielded there, or the particle sticks). The test-suite holds these bounds
    (``tests/test_wall_adhesion.py``).

    Parameters
    ----------
    t_min, t_max : float
        ``log10(V/V_y)`` of the first and last nodes [-]; ``t_min < 0 < t_max`` and 0 a node.
    n_t : int
        Number of nodes in ``t`` (>= 3).
    y_max : float
        Largest ``V_s/V_y`` [-] (> 0).
    n_u : int
        Number of nodes in ``u = (V_s/V_y)^(3/5)`` from 0 to ``y_max^(3/5)`` (>= 2).
    """
    t_min, t_max, y_max = float(t_min), float(t_max), float(y_max)
    if not (math.isfinite(t_min) and math.isfinite(t_max) and t_min < 0.0 < t_max):
        raise ValueError(f"t_min < 0 < t_max must hold (finite), got t_min={t_min!r}, t_max={t_max!r}")
    if isinstance(n_t, bool) or int(n_t) != n_t or n_t < 3:
        raise ValueError(f"n_t must be an integer >= 3, got {n_t!r}")
    if isinstance(n_u, bool) or int(n_u) != n_u or n_u < 2:
        raise ValueError(f"n_u must be an integer >= 2, got {n_u!r}")
    k0 = -t_min * (int(n_t) - 1) / (t_max - t_min)
    if abs(k0 - round(k0)) > 1e-9:
        raise ValueError(f"t = 0 must be a node: -t_min (n_t - 1)/(t_max - t_min) = {k0!r} is not an integer")
    if not (0.0 < y_max < math.inf):
        raise ValueError(f"y_max must be positive and finite, got {y_max!r}")
    return _whole_law_table(t_min, t_max, int(n_t), y_max, int(n_u))


def _checked_speeds(velocity, yield_velocity, sticking_velocity):
    V = check_nonnegative("velocity", velocity)
    if np.any(np.isinf(V)):
        raise ValueError(f"velocity must be finite, got {float(V[np.isinf(V)].flat[0])!r}")
    Vy = check_positive("yield_velocity", yield_velocity, allow_inf=True)
    Vs = check_nonnegative("sticking_velocity", sticking_velocity)
    return V, Vy, Vs


def whole_law_correction(velocity, yield_velocity, sticking_velocity):
    """The whole law's correction ``D`` to the additive rule's ``e^2``, read from its table.

    ``D(V/V_y, V_s/V_y)`` interpolated in :func:`whole_law_table` at the two groups of each point:
    what the whole adhesive elastic-plastic law of Thornton & Ning (1998) adds to the additive rule,
    ``e^2 = e_p(V/V_y)^2 - (V_s/V)^2 + D`` (:func:`microimpact.core.adhesion.whole_law_correction`
    at the nodes). The one lookup behind :func:`whole_law_restitution`, the wall's
    ``adhesion="thornton_ning_1998_adhesive_plastic"`` (:func:`~microimpact.wall.wall_interaction`)
    and the C export's tables. Where ``V_y = inf`` (a pair that never yields) both groups are 0
    (``D = 0``: the whole law is the additive rule there).

    Parameters
    ----------
    velocity : array_like
        Normal impact speed ``V`` [m/s], finite, >= 0.
    yield_velocity : array_like
        ``V_y`` [m/s] (seed eq. 28), > 0; ``inf`` for a wall that never yields.
    sticking_velocity : array_like
        ``V_s`` [m/s] (Thornton & Ning 1998, eq. 54: :func:`sticking_velocity`), >= 0.

    Returns
    -------
    D : ndarray
        The correction to ``e^2`` [-], broadcast shape of the inputs.
    outside_table : ndarray of bool
        True where ``V/V_y`` or ``V_s/V_y`` lies beyond the table (its edge's value was used;
        flagged, not refused).

    Examples
    --------
    >>> D, outside = whole_law_correction([20.0, 50.0, 1e4], 7.52, 1.0)  # V/V_y = 1330: beyond the table
    >>> D.round(4), outside
    (array([-0.0065,  0.0062,  0.0009]), array([False, False,  True]))
    """
    V, Vy, Vs = np.broadcast_arrays(*_checked_speeds(velocity, yield_velocity, sticking_velocity))
    # a V_y so small that V/V_y overflows puts the point beyond the table's edge: flagged there (outside)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        x = np.where(Vy < math.inf, V / Vy, 0.0)
        y = np.where(Vy < math.inf, Vs / Vy, 0.0)
    return whole_law_table()(x, y)


def whole_law_restitution(velocity, yield_velocity, sticking_velocity):
    """Normal restitution of Thornton & Ning's whole law through its table, as the wall computes it.

    ``e^2 = e_p(V/V_y)^2 - (V_s/V)^2 + D(V/V_y, V_s/V_y)`` with ``D`` interpolated in
    :func:`whole_law_table` (:func:`whole_law_correction`) and the particle sticking (``e = 0``) where that is not positive
    (:func:`microimpact.core.adhesion.corrected_restitution`): the operations of
    :func:`~microimpact.wall.wall_interaction` with ``adhesion="thornton_ning_1998_adhesive_plastic"``
    (and of the C export) for a head-on impact, so tables written with it
    (:func:`microimpact.cexport.write_tables`) agree with both. At ``V = 0`` the particle sticks where
    ``V_s > 0`` (as in the additive rule) and ``e = 1`` without adhesion.

    Parameters
    ----------
    velocity : array_like
        Normal impact speed ``V`` [m/s], finite, >= 0.
    yield_velocity : array_like
        ``V_y`` [m/s] (seed eq. 28); ``inf`` for a wall that never yields.
    sticking_velocity : array_like
        ``V_s`` [m/s] (eq. 54, :func:`sticking_velocity`), >= 0.

    Returns
    -------
    e : ndarray
        ``e`` [-], 0 where the particle sticks.
    outside_table : ndarray of bool
        True where ``V/V_y`` or ``V_s/V_y`` lies beyond the table (its edge was used; flagged, not refused).

    Examples
    --------
    >>> e, outside = whole_law_restitution([0.5, 2.0, 50.0], 7.52, 1.0)
    >>> e.round(4), outside
    (array([0.    , 0.866 , 0.7287]), array([False, False, False]))
    """
    V, Vy, Vs = _checked_speeds(velocity, yield_velocity, sticking_velocity)
    V, Vy, Vs = (np.array(a, dtype=float) for a in np.broadcast_arrays(V, Vy, Vs))
    D, outside = whole_law_correction(V, Vy, Vs)
    e = evaluate(_core.corrected_restitution, V, Vy, Vs, np.asarray(D, dtype=float), nout=2)[0]
    return np.where((V == 0.0) & (Vs > 0.0), 0.0, e), outside


@functools.lru_cache(maxsize=4)
def _whole_law_table(t_min, t_max, n_t, y_max, n_u):
    import hashlib

    from .engine import cache

    t = np.linspace(t_min, t_max, n_t)
    t[int(round(-t_min * (n_t - 1) / (t_max - t_min)))] = 0.0  # the seed's yield, exactly
    u = np.linspace(0.0, y_max**0.6, n_u)
    h = hashlib.sha256(cache.core_hash().encode())
    with open(__file__, "rb") as fh:
        h.update(fh.read())
    h.update(repr((t_min, t_max, n_t, y_max, n_u)).encode())
    key = h.hexdigest()[:16]
    values = cache.load_array("whole_law_table", key)
    if values is None or values.shape != (n_u, n_t):
        with cache.locked(cache.cache_dir() / "tables", f"whole_law_table_{key}"):
            values = cache.load_array("whole_law_table", key)
            if values is None or values.shape != (n_u, n_t):
                x = np.array([10.0 ** float(a) for a in t])  # Python's pow: the nodes do not depend on numpy's
                y = np.array([float(b) ** (5.0 / 3.0) for b in u])
                values = evaluate(_core.whole_law_correction, x[None, :], y[:, None])[0]
                values = np.ascontiguousarray(values, dtype=float)
                cache.store_array("whole_law_table", key, values)
    values.setflags(write=False)
    t.setflags(write=False)
    u.setflags(write=False)
    return WholeLawTable(t, u, values)
