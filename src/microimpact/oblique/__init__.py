"""Oblique impacts of a sphere on a flat: tangential restitution, rebound angle and spin.

The normal direction is the seed's elastic–plastic model (restitution, eqs. 22, 27, 28;
closed-form history, THEORY.md sections 2–4). The tangential direction is one of

* ``tangential="mindlin"`` (default): the contact is a tangential spring of Mindlin's
  no-slip stiffness ``k_t = 8 G* a``, loaded incrementally along the closed-form normal
  history and limited by Coulomb friction ``|T| <= mu P``
  (:mod:`microimpact.core.tangential`). It sticks, slides or does both within one impact,
  stores and returns elastic energy, and so reverses the contact-point slip at small and
  moderate angles: the tangential restitution dips below ``5/7`` and the rebound spin and
  angle differ from the rigid model's exactly where most wall hits happen;
* ``tangential="rigid"``: the rigid-body Coulomb impulse model of
  :func:`microimpact.wall.wall_interaction` (sliding, or rolling with ``5/7`` of the
  tangential speed for a non-spinning sphere). It is the limit of the compliant model for
  an infinitely stiff contact.

The compliant outcome depends only on the normalised impact angle ``psi = kappa u0 / (mu
V_n)`` (``u0`` the contact-point slip, ``kappa = 4 G*/E*``), on ``kappa`` and on the seed's
``V_y / V_n``: :func:`universal_curve` returns it, and :class:`UniversalTable` tabulates
it so that ``method="table"`` costs an interpolation per impact; the default ``method="auto"``
interpolates where the table's own second differences bound its error (within 2.5e-4 of ``F``) and
integrates the impacts near the kinks of ``F(psi)``, which gives the integration's spin to 1e-3.

With adhesion (``work_of_adhesion=`` or ``adhesion=``, an adhesive normal law of the model zoo) the
normal and tangential contact are integrated together and each impact classified as a bounce or a
capture (at rest, rolling or sliding): :mod:`microimpact.oblique.adhesive`.

Conventions: ``angle`` is the impact angle from the wall normal [deg] (0 = head-on); the
resultant speed is ``velocity``, so ``V_n = velocity cos(angle)`` and ``v_t = velocity
sin(angle)``. ``spin`` [rad/s] is counted positive when it adds to the contact point's
slip, ``u0 = v_t + r omega`` (a sphere rolling without slip has ``omega = -v_t / r``).
The tangential restitution is that of the centre, ``e_t = v_t' / v_t``; the rebound
angles are ``atan(v_t' / V_n')`` (centre) and ``atan(u_r / V_n')`` (contact point, the one
Kharaz et al. 2001 report), from the normal, positive in the incident direction.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, fields

import numpy as np

from .._validation import check_nonnegative, check_not_subnormal, check_poisson, check_positive
from ..core import hertz
from ..core import tangential as tg
from ..core import tangential_laws as tl
from ..engine import cache, evaluate
from ..impact import elastic_max_approach, restitution_coefficient, yield_velocity

__all__ = [
    "ObliqueImpact",
    "OBLIQUE_REGIMES",
    "TANGENTIAL_MODELS",
    "DEM_LAWS",
    "UNIVERSAL_LAWS",
    "oblique_impact",
    "stiffness_ratio_of",
    "universal_curve",
    "UniversalTable",
    "universal_table",
    "integrate_oblique_ode",
    "table_c_source",
    "ALUMINA_CASE",
    "alumina_pair",
    "measured_alumina",
]

#: The DEM codes' tangential laws, by name: :data:`microimpact.core.tangential_laws.ALL_LAWS` (the
#: same tuple), for code above the core (``microimpact export --tangential``).
DEM_LAWS = tl.ALL_LAWS
#: Tangential models :func:`oblique_impact` knows, by name: the compliant contact of
#: :mod:`microimpact.core.tangential`, the rigid-body impulse, and the DEM codes' laws of
#: :mod:`microimpact.core.tangential_laws` (:data:`DEM_LAWS`; ``"lammps_mindlin_rescale_force"`` is
#: ``"mindlin"``).
TANGENTIAL_MODELS = ("mindlin", "rigid", *DEM_LAWS)
#: Laws whose outcome is a universal curve of ``psi``, ``kappa`` and ``V_y/V_n`` (tabulated for
#: ``method="table"``). LIGGGHTS's arm ``R - delta/2`` adds ``alpha_m/R``, and a constant stiffness
#: given in N/m makes ``kappa`` depend on the speed: those two are always integrated.
UNIVERSAL_LAWS = tuple(m for m in TANGENTIAL_MODELS if m not in ("rigid", "liggghts_history"))
#: Regime names by code (:mod:`microimpact.core.tangential`).
OBLIQUE_REGIMES = {
    tg.REGIME_STICKING: "sticking",
    tg.REGIME_SLIDING: "sliding",
    tg.REGIME_MICROSLIP: "micro-slip",
    tg.REGIME_ROLLING: "rolling",
}
#: Steps per stage of the fixed-step integration (error below 1e-7 of ``mu V``; see tests).
DEFAULT_STEPS = 400


# ============================================================================ compiled integrator


def _integrate(u0_hat, kappa, x, steps, law="mindlin"):
    """Final slip and regime of :func:`~microimpact.core.tangential.integrate_tangential` (``"mindlin"``)
    or :func:`~microimpact.core.tangential_laws.integrate_law` (the others, with the arm ``R``) over arrays."""
    u0_hat, kappa, x = (np.asarray(a, dtype=float) for a in (u0_hat, kappa, x))
    if law in ("mindlin", "lammps_mindlin_rescale_force"):
        ur, rg = evaluate(tg.integrate_tangential, u0_hat, kappa, x, np.asarray(float(steps)), nout=2)
        return ur, rg.astype(np.int8)
    if law == "stronge":
        e = np.vectorize(lambda v: tg.history_constants(v)[13], otypes=[float])(x)
        return _integrate_stronge(u0_hat, kappa, e, steps)
    vr, wr, rg = _integrate_law(law, u0_hat, 0.0, kappa, x, 0.0, steps)
    return vr + wr, rg


def _integrate_stronge(u0_hat, kappa, e, steps):
    """Final slip and regime of :func:`~microimpact.core.tangential_laws.integrate_stronge` over arrays."""
    args = (np.asarray(a, dtype=float) for a in (u0_hat, kappa, e))
    ur, rg = evaluate(tl.integrate_stronge, *args, np.asarray(float(steps)), nout=2)
    return ur, rg.astype(np.int8)


def _integrate_law(law, v0_hat, w0_hat, kappa, x, eps, steps):
    """``(v_r, w_r, regime)`` of :func:`~microimpact.core.tangential_laws.integrate_law` over arrays."""
    args = (np.asarray(a, dtype=float) for a in (v0_hat, w0_hat, kappa, x, eps))
    vr, wr, rg = evaluate(tl.integrate_law, np.asarray(tl.law_code(law)), *args, np.asarray(float(steps)), nout=3)
    return vr, wr, rg.astype(np.int8)


# ============================================================================ the universal curve


def universal_curve(psi, kappa, x=1.0, *, steps=DEFAULT_STEPS, law="mindlin"):
    """Tangential impulse of a compliant law as a function of the normalised angle.

    Returns ``F = |J_t| / (mu J_n)`` in [0, 1] (1: sliding throughout, the Coulomb limit)
    and the final slip ratio ``u_r / u0`` at each ``psi``, for the stiffness ratio
    ``kappa = 4 G*/E*`` and the seed's ``x = V_y / V_n`` (1 or more: elastic impact).
    The rigid model is ``F = min(1, 2 psi / (7 kappa (1 + e)))``.

    Parameters
    ----------
    psi : array_like
        Normalised impact angle ``kappa u0 / (mu V_n)`` [-], >= 0.
    kappa : float
        ``4 G*/E*`` [-] (``2(1 - nu)/(2 - nu)`` for one material on a rigid flat).
    x : float, optional
        ``V_y / V_n`` [-]; default 1 (elastic).
    steps : int, optional
        Integration steps per contact stage.
    law : str, optional
        One of :data:`UNIVERSAL_LAWS` (default ``"mindlin"``). For ``"lammps_linear_history"``
        ``kappa`` is ``k_t/(2 E* a_m)``.

    Returns
    -------
    F, slip_ratio, regime : ndarray
        ``|J_t|/(mu J_n)`` [-], ``u_r/u0`` [-] (NaN at ``psi = 0``) and regime codes.
    """
    if law not in UNIVERSAL_LAWS:
        raise ValueError(f"law must be one of {UNIVERSAL_LAWS}, got {law!r}")
    psi = np.atleast_1d(check_nonnegative("psi", psi)).astype(float)
    if np.isinf(psi).any():
        raise ValueError("psi must be finite, got inf")
    kappa = float(check_not_subnormal("kappa", _check_kappa(kappa)))  # u0 = psi/kappa overflows
    x = float(check_nonnegative("x", x))
    if not (x > 0.0):
        raise ValueError(f"x must be positive, got {x!r}")
    check_not_subnormal("x", x)  # the history's scales divide by x = V_y/V_n
    with np.errstate(over="ignore"):
        u0 = psi / kappa
    if np.isinf(u0).any():
        raise ValueError(
            f"psi {float(psi[np.isinf(u0)][0])!r} and kappa {kappa!r} give the slip u0 = psi/kappa beyond the "
            "largest double: give psi and kappa in range"
        )
    F = np.empty_like(psi)
    ratio = np.full_like(psi, np.nan)
    regime = np.empty(psi.shape, dtype=np.int8)
    try:
        one_e = 1.0 + float(tg.history_constants(x)[13])
        ur, regime[...] = _integrate(u0, kappa, x, steps, law)
    except ZeroDivisionError:  # a power of x or of psi/kappa underflowed to zero inside the law's scales
        raise ValueError(
            f"psi (up to {float(psi.max())!r}), kappa {kappa!r} and x {x!r} leave the float range: a scale "
            "of the tangential history underflows to zero; give them in range"
        ) from None
    F[...] = (u0 - ur) / tg.SLIP_FACTOR / one_e
    pos = u0 > 0.0
    ratio[pos] = ur[pos] / u0[pos]
    return F, ratio, regime


def _check_kappa(kappa):
    if isinstance(kappa, (bool, np.bool_)):
        raise ValueError(f"kappa must be a number, got {kappa!r}")
    k = float(kappa)
    if not (0.0 < k < math.inf):
        raise ValueError(f"kappa must be positive and finite, got {kappa!r}")
    return k


@dataclass(frozen=True, eq=False)
class UniversalTable:
    """``F(psi, x) = |J_t| / (mu J_n)`` of the compliant model on a grid, for one ``kappa``.

    Bilinear interpolation in ``psi`` (uniform, step ``dpsi``, a node at ``psi = 1`` where
    sliding from first touch begins) and in ``log10(x)`` (uniform from ``x_min`` to 1;
    ``x >= 1`` is elastic, ``x < x_min`` is clamped and flagged). Beyond ``psi_max`` the
    contact slides throughout (checked when the table is built): ``F = 1``.

    Attributes
    ----------
    kappa : float
        ``4 G*/E*`` [-].
    psi : ndarray (n_psi,)
        Grid of the normalised angle [-].
    log_x : ndarray (n_x,)
        Grid of ``log10(V_y/V_n)`` [-].
    values : ndarray (n_x, n_psi)
        ``F`` [-].
    law : str
        The tangential law tabulated (one of :data:`UNIVERSAL_LAWS`).
    """

    kappa: float
    psi: np.ndarray
    log_x: np.ndarray
    values: np.ndarray
    law: str = "mindlin"

    @property
    def psi_max(self) -> float:
        return float(self.psi[-1])

    @property
    def x_min(self) -> float:
        return float(10.0 ** self.log_x[0])

    @functools.cached_property
    def _node_error(self):
        """``(in_psi, in_x)`` per node: a quarter of the absolute second difference of ``F`` along ``psi`` and
        along ``log10 x`` (0 at the grid's edges).

        Where ``F`` is smooth the linear interpolation's error in a cell is ``h^2 |F''|/8 = |D2|/8`` (``D2``
        the second difference over its nodes); across a kink (a change of regime: sliding from first
        touch at ``psi = 1``, sliding throughout, a reversal) it is up to ``|D2|/4``: the estimate
        :meth:`trusted` reads."""
        v = self.values
        in_psi = np.zeros_like(v)
        in_psi[:, 1:-1] = 0.25 * np.abs(v[:, :-2] - 2.0 * v[:, 1:-1] + v[:, 2:])
        in_x = np.zeros_like(v)
        if v.shape[0] > 2:
            in_x[1:-1, :] = 0.25 * np.abs(v[:-2, :] - 2.0 * v[1:-1, :] + v[2:, :])
        return in_psi, in_x

    def trusted(self, psi, x, rtol=2.5e-4, atol=2e-6):
        """True where the interpolated ``F`` at ``psi`` [-] and ``x = V_y/V_n`` [-] is within ``rtol F +
        atol`` of the law by the error estimate of the cell's nodes (:attr:`_node_error`: along ``psi`` on
        the rows interpolated, along ``log10 x`` where ``x`` lies between rows), and beyond ``psi_max``
        (``F = 1`` exactly). ``F``'s relative error is the rebound spin's and the tangential impulse's:
        2.5e-4 keeps the spin within 1e-3 of the direct integration, with room for the estimate."""
        psi, x = np.broadcast_arrays(np.asarray(psi, dtype=float), np.asarray(x, dtype=float))
        in_psi, in_x = self._node_error
        v = self.values
        lx = np.clip(np.log10(np.maximum(np.where(np.isnan(x), 1.0, x), 1e-300)), self.log_x[0], 0.0)
        p = np.where(np.isfinite(psi), psi, 0.0)
        with np.errstate(over="ignore"):  # psi beyond the largest double: the table's last node, sliding
            fp = np.clip(p / (self.psi[1] - self.psi[0]), 0.0, self.psi.size - 1.0)
        fl = np.clip((lx - self.log_x[0]) / (self.log_x[1] - self.log_x[0]), 0.0, self.log_x.size - 1.0)
        near = np.round(fl)
        fl = np.where(np.abs(fl - near) < 1e-9, near, fl)  # on a row (x = 1: 3/0.1 is 29.999999999999996)
        i = np.minimum(fp.astype(np.intp), self.psi.size - 2)
        j = np.minimum(fl.astype(np.intp), self.log_x.size - 2)
        tl = fl - j
        bound = np.zeros(psi.shape)
        fmin = np.full(psi.shape, np.inf)
        for row, used in ((j, tl < 1.0), (j + 1, tl > 0.0)):  # the rows the interpolation weighs
            b = np.maximum(in_psi[row, i], in_psi[row, i + 1])
            between = (tl > 0.0) & (tl < 1.0)
            b = b + np.where(between, np.maximum(in_x[row, i], in_x[row, i + 1]), 0.0)
            bound = np.where(used, np.maximum(bound, b), bound)
            fmin = np.where(used, np.minimum(fmin, np.minimum(v[row, i], v[row, i + 1])), fmin)
        ok = bound <= rtol * np.abs(fmin) + atol
        return ok | (psi >= self.psi[-1]) | ~np.isfinite(psi)

    def __call__(self, psi, x):
        """Interpolated ``F`` at ``psi`` [-] and ``x = V_y/V_n`` [-] (arrays broadcast)."""
        psi, x = np.broadcast_arrays(np.asarray(psi, dtype=float), np.asarray(x, dtype=float))
        lx = np.clip(np.log10(np.maximum(x, 1e-300)), self.log_x[0], 0.0)
        dp = self.psi[1] - self.psi[0]
        dl = self.log_x[1] - self.log_x[0]
        with np.errstate(over="ignore"):  # psi beyond the largest double: the table's last node, sliding
            fp = np.clip(psi / dp, 0.0, self.psi.size - 1.0)
        fl = np.clip((lx - self.log_x[0]) / dl, 0.0, self.log_x.size - 1.0)
        i = np.minimum(fp.astype(np.intp), self.psi.size - 2)
        j = np.minimum(fl.astype(np.intp), self.log_x.size - 2)
        tp = fp - i
        tl = fl - j
        v = self.values
        out = (1 - tl) * ((1 - tp) * v[j, i] + tp * v[j, i + 1]) + tl * ((1 - tp) * v[j + 1, i] + tp * v[j + 1, i + 1])
        return np.where(psi >= self.psi[-1], 1.0, out)


@functools.lru_cache(maxsize=16)
def _table(kappa, dpsi, psi_max, n_x, x_min, steps, law):
    psi = np.linspace(0.0, psi_max, int(round(psi_max / dpsi)) + 1)
    log_x = np.linspace(math.log10(x_min), 0.0, n_x)
    kind = "universal_table" if law == "mindlin" else f"universal_table_{law}"
    key = _table_key(kappa, dpsi, psi_max, n_x, x_min, steps)
    # Mindlin-Deresiewicz never slides throughout (it sticks at first touch, T/(mu P) =
    # 1 - O(psi^-3)): its curve reaches 1 within the table's error (1.4e-3 at psi = 10)
    short = 3e-3 if law == "mindlin_deresiewicz" else 0.0
    values = _cached_values(kind, key, (n_x, psi.size), short)
    if values is None:
        # processes started together on an empty cache: one builds the table, the others wait and read it
        with cache.locked(cache.cache_dir() / "tables", f"{kind}_{key}"):
            values = _cached_values(kind, key, (n_x, psi.size), short)
            if values is None:
                values = np.empty((n_x, psi.size))
                for j, lx in enumerate(log_x):
                    F, _, regime = universal_curve(psi, kappa, 10.0**lx, steps=steps, law=law)
                    values[j] = np.where(regime == tg.REGIME_SLIDING, 1.0, F)  # exactly the Coulomb limit
                if not np.all(values[:, -1] >= 1.0 - short):  # pragma: no cover - grid too short for this kappa
                    raise RuntimeError(f"psi_max = {psi_max} does not reach sliding throughout for kappa = {kappa}")
                cache.store_array(kind, key, values)
    values.setflags(write=False)
    return UniversalTable(kappa, psi, log_x, values, law)


def _table_key(*args) -> str:
    """Name of a table on disk: its arguments, the core's sources and this module's (what computes it)."""
    import hashlib

    h = hashlib.sha256(cache.core_hash().encode())
    with open(__file__, "rb") as fh:
        h.update(fh.read())
    h.update(repr(tuple(float(a) for a in args)).encode())
    return h.hexdigest()[:16]


def _cached_values(kind, key, shape, short=0.0):
    """The stored table ``F`` of that key, or None (absent, corrupt, of another shape, or not reaching
    sliding at its end: ``F = 1`` there, within ``short`` for a law that never slides throughout, the
    test a table passes before it is stored)."""
    values = cache.load_array(kind, key)
    if values is None or values.shape != shape:
        return None
    end = values[:, -1]
    if not (np.all(end >= 1.0 - short) if short else np.all(end == 1.0)):
        return None
    return values


def universal_table(kappa, *, dpsi=0.025, psi_max=None, n_x=31, x_min=1e-3, steps=200, law="mindlin"):
    """The :class:`UniversalTable` of ``kappa`` (built on first use, then cached).

    Building integrates ``n_psi x n_x`` impacts (about 10^4, compiled: 3-4 s in a new process with
    the compiled loop cached on disk), once: the table is kept in the cache folder beside the compiled
    loops (:mod:`microimpact.engine.cache`; named by its arguments and a hash of the sources that compute
    it), so later processes read it (a few ms). Where the cache cannot be read or written it is built
    again, as before. Its error against direct integration is
    below ``3e-3`` of ``mu J_n`` (largest 2.96e-3, mean 6e-5, over random ``psi``, ``x`` and
    ``kappa`` in 0.65–1.2 in ``tests/test_oblique.py``).

    Parameters
    ----------
    kappa : float
        ``4 G*/E*`` [-].
    dpsi : float, optional
        Grid step in ``psi`` (``1/dpsi`` must be an integer, so that ``psi = 1`` is a node).
    psi_max : float, optional
        End of the grid; default ``8 kappa + 2`` (sliding throughout beyond it).
    n_x, x_min : optional
        Number of ``log10(V_y/V_n)`` nodes from ``log10(x_min)`` to 0.
    steps : int, optional
        Integration steps per stage for each node.
    law : str, optional
        One of :data:`UNIVERSAL_LAWS` (default ``"mindlin"``; ``"lammps_mindlin_rescale_force"`` is
        the same table).
    """
    if law not in UNIVERSAL_LAWS:
        raise ValueError(f"law must be one of {UNIVERSAL_LAWS}, got {law!r}")
    if law == "lammps_mindlin_rescale_force":
        law = "mindlin"
    kappa = _check_kappa(kappa)
    if psi_max is None:
        psi_max = math.ceil(8.0 * kappa + 2.0)
    dpsi = check_positive("dpsi", dpsi, scalar=True)
    if math.isinf(dpsi) or abs(1.0 / dpsi - round(1.0 / dpsi)) > 1e-9:
        raise ValueError(f"1/dpsi must be an integer, got dpsi = {dpsi!r}")
    return _table(round(kappa, 12), float(dpsi), float(psi_max), int(n_x), float(x_min), int(steps), law)


# ============================================================================ the application


@dataclass(frozen=True, eq=False)
class ObliqueImpact:
    """Outcome of :func:`oblique_impact` (arrays broadcast over the inputs; SI units).

    Attributes
    ----------
    angle : ndarray
        Impact angle from the normal [deg].
    normal_speed, tangential_speed : ndarray
        ``V_n`` and ``v_t`` before the impact [m/s].
    normalized_angle : ndarray
        ``psi = kappa u0 / (mu V_n)`` [-] (inf without friction).
    normal_restitution : ndarray
        ``e = V_n'/V_n``, the seed's (eq. 27) [-].
    tangential_restitution : ndarray
        ``e_t = v_t'/v_t`` of the centre [-] (NaN where ``v_t = 0``).
    slip_ratio : ndarray
        ``u_r/u0`` of the contact point [-] (negative: the slip reversed; NaN where ``u0 = 0``).
    rebound_angle, contact_rebound_angle : ndarray
        ``atan(v_t'/V_n')`` and ``atan(u_r/V_n')`` [deg] from the normal.
    rebound_spin : ndarray
        ``omega'`` [rad/s] (sign as ``spin``: positive adds to the slip).
    tangential_velocity : ndarray
        ``v_t'`` [m/s].
    impulse_ratio : ndarray
        ``|J_t| / (mu J_n)`` [-]: 1 when the contact slid throughout.
    regime : ndarray of str
        ``"sticking"``, ``"sliding"``, ``"micro-slip"`` (compliant) or ``"rolling"``,
        ``"sliding"`` (rigid).
    tangential : str
        The tangential model used.
    kappa : float
        ``4 G*/E*`` [-].
    large_strain : ndarray of bool
        Where the normal impact is outside the seed's small-strain range (flagged, not refused).
    """

    angle: np.ndarray
    normal_speed: np.ndarray
    tangential_speed: np.ndarray
    normalized_angle: np.ndarray
    normal_restitution: np.ndarray
    tangential_restitution: np.ndarray
    slip_ratio: np.ndarray
    rebound_angle: np.ndarray
    contact_rebound_angle: np.ndarray
    rebound_spin: np.ndarray
    tangential_velocity: np.ndarray
    impulse_ratio: np.ndarray
    regime: np.ndarray
    tangential: str
    kappa: float
    large_strain: np.ndarray

    def to_dict(self) -> dict:
        """All fields as a dict."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def __len__(self):
        return int(np.size(self.angle))


def stiffness_ratio_of(pair, poisson_ratio=None, effective_shear_modulus=None):
    """``kappa = 4 G*/E*`` of a pair [-].

    From ``effective_shear_modulus`` ``G*`` [Pa] if given; else from one Poisson's ratio
    for particle and wall (``2(1 - nu)/(2 - nu)``, exact for equal materials or a rigid
    wall); else from the pair's particle and surface materials
    (:func:`~microimpact.core.tangential.effective_shear_modulus`).
    """
    E = float(pair.effective_modulus)
    if effective_shear_modulus is not None:
        G = float(np.asarray(effective_shear_modulus, dtype=float))
        if not (0.0 < G < math.inf):
            raise ValueError(f"effective_shear_modulus must be positive and finite, got {effective_shear_modulus!r}")
        return float(tg.stiffness_ratio(G, E))
    if poisson_ratio is not None:
        nu = float(check_poisson("poisson_ratio", poisson_ratio))
        return tg.stiffness_ratio_same_poisson(nu)
    p, s = getattr(pair, "particle", None), getattr(pair, "surface", None)
    if p is None or s is None:
        raise ValueError(
            "the tangential stiffness needs poisson_ratio=..., effective_shear_modulus=... "
            "or a pair built from materials"
        )
    G = tg.effective_shear_modulus(p.youngs_modulus, p.poisson_ratio, s.youngs_modulus, s.poisson_ratio)
    E_mat = hertz.effective_modulus(p.youngs_modulus, p.poisson_ratio, s.youngs_modulus, s.poisson_ratio)
    return float(tg.stiffness_ratio(G, E_mat))


def oblique_impact(
    pair,
    velocity,
    angle,
    friction,
    *,
    poisson_ratio=None,
    effective_shear_modulus=None,
    tangential="mindlin",
    spin=0.0,
    method="auto",
    steps=DEFAULT_STEPS,
    tangential_stiffness=None,
    adhesion=None,
    adhesion_params=None,
    work_of_adhesion=None,
    coulomb=None,
) -> ObliqueImpact:
    """Rebound of a sphere hitting a flat wall obliquely (vectorized over impacts).

    Parameters
    ----------
    pair : ContactPair
        Sphere on a flat (``R*`` is the sphere's radius, ``m*`` its mass).
    velocity : array_like
        Resultant impact speed [m/s], > 0.
    angle : array_like
        Impact angle from the wall normal [deg], in [0, 90).
    friction : array_like
        Coulomb friction coefficient ``mu`` [-], >= 0.
    poisson_ratio, effective_shear_modulus : optional
        How to get ``G*`` (see :func:`stiffness_ratio_of`); not needed for ``"rigid"``.
    tangential : str
        Tangential model, one of :data:`TANGENTIAL_MODELS`: ``"mindlin"`` (default), ``"rigid"``
        (module docstring), or a DEM code's law (:mod:`microimpact.core.tangential_laws`):
        ``"lammps_mindlin"``, ``"lammps_mindlin_force"``, ``"lammps_mindlin_rescale"``,
        ``"lammps_mindlin_rescale_force"`` (the same as ``"mindlin"``), ``"lammps_linear_history"``,
        ``"liggghts_history"``, ``"di_renzo_di_maio"``, the Mindlin-Deresiewicz incremental stiffness
        with turning points ``"mindlin_deresiewicz"`` (no DEM code runs it), or Stronge's compliant
        impact ``"stronge"`` (its own linear normal spring with the seed's ``e``; only the
        tangential outcome is its).
    spin : array_like, optional
        Incoming spin ``omega`` [rad/s], positive adding to the slip (``u0 = v_t + r omega``).
    method : {"auto", "table", "direct"}
        Compliant models: ``"table"`` interpolates the :func:`universal_table` of the pair's ``kappa``
        and the law (error below ``3e-3 mu J_n``: up to 5e-3 of the rebound spin near the regime
        changes, where ``F(psi)`` has kinks); ``"direct"`` integrates each impact (about 0.4 ms an
        impact, a hundred times the table); ``"auto"`` (default) interpolates where the table's own
        second differences bound the interpolation's error within ``2.5e-4 F + 2e-6``
        (:meth:`UniversalTable.trusted`) and integrates the rest: the direct path's outcome to 1e-3
        of the spin, at a few per cent of its cost for elastic impacts (the cells near the kinks; a
        third or more of the impacts where ``V_y/V_n`` spreads below 1, whose grid is coarser). Laws
        without a universal curve (``"liggghts_history"``, ``"lammps_linear_history"`` with a
        ``tangential_stiffness``) are always integrated. The Mindlin-Deresiewicz table's own nodes
        (200 steps a stage) are 1.5e-3 off its 400-step integration: ``"auto"`` keeps that.
    steps : int
        Integration steps per stage where an impact is integrated.
    tangential_stiffness : float, optional
        ``"lammps_linear_history"`` only: the constant stiffness ``k_t`` [N/m]. Default: each
        impact's Mindlin stiffness at its largest contact radius, ``8 G* a_m`` (``a_m`` of the
        elastic impact at ``V_n``), which gives the law a universal curve.

    Returns
    -------
    ObliqueImpact

    Examples
    --------
    >>> import microimpact as mi
    >>> pair = mi.ContactPair.sphere_on_flat(radius=2.5e-3, density=4000.0,
    ...     effective_modulus=3.8e11 / (1 - 0.23**2), limiting_pressure=float("inf"))
    >>> out = oblique_impact(pair, 3.9, [10.0, 45.0], 0.092, poisson_ratio=0.23,
    ...                      tangential="rigid")
    >>> out.tangential_restitution.round(3).tolist(), out.regime.tolist()
    ([0.714, 0.816], ['rolling', 'sliding'])
    """
    if tangential not in TANGENTIAL_MODELS:
        raise ValueError(f"tangential must be one of {TANGENTIAL_MODELS}, got {tangential!r}")
    if adhesion is not None or work_of_adhesion is not None:
        from .adhesive import adhesive_law

        law_params = adhesive_law(adhesion, adhesion_params, work_of_adhesion)
        if law_params is not None:
            from .adhesive import adhesive_oblique_impact

            kappa = None
            if tangential != "rigid":
                kappa = stiffness_ratio_of(pair, poisson_ratio, effective_shear_modulus)
            return adhesive_oblique_impact(
                pair,
                velocity,
                angle,
                friction,
                model=law_params[0],
                params=law_params[1],
                tangential=tangential,
                spin=spin,
                kappa=kappa,
                coulomb=coulomb,
                tangential_stiffness=tangential_stiffness,
            )
    if method not in ("auto", "table", "direct"):
        raise ValueError(f"method must be 'auto', 'table' or 'direct', got {method!r}")
    if method == "auto":
        kw = dict(
            poisson_ratio=poisson_ratio,
            effective_shear_modulus=effective_shear_modulus,
            tangential=tangential,
            steps=steps,
            tangential_stiffness=tangential_stiffness,
        )
        out = oblique_impact(pair, velocity, angle, friction, spin=spin, method="table", **kw)
        law = "mindlin" if tangential == "lammps_mindlin_rescale_force" else tangential
        if law == "rigid" or law not in (*UNIVERSAL_LAWS, "mindlin") or tangential_stiffness is not None:
            return out  # no table: already integrated (or rigid)
        table = universal_table(out.kappa) if law == "mindlin" else universal_table(out.kappa, law=law)
        Vy = float(
            yield_velocity(pair.limiting_pressure, pair.effective_modulus, pair.effective_radius, pair.effective_mass)
        )
        with np.errstate(over="ignore"):  # V_y/V_n beyond the largest double: elastic all the same (x = 1)
            x = np.minimum(Vy / out.normal_speed, 1.0)
        redo = ~table.trusted(out.normalized_angle, x)
        if not redo.any():
            return out
        args = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (velocity, angle, friction, spin)))
        sub = oblique_impact(pair, *(a[redo] for a in args[:3]), spin=args[3][redo], method="direct", **kw)
        merged = {}
        for f in fields(ObliqueImpact):
            full = getattr(out, f.name)
            if isinstance(full, np.ndarray) and full.shape == redo.shape:
                part = getattr(sub, f.name)
                full = full.astype(np.result_type(full.dtype, part.dtype))
                full[redo] = part
            merged[f.name] = full
        return ObliqueImpact(**merged)
    if tangential_stiffness is not None:
        if tangential != "lammps_linear_history":
            raise ValueError(
                f"tangential_stiffness is used by tangential='lammps_linear_history' only, got tangential={tangential!r}"
            )
        k_lin = float(np.asarray(tangential_stiffness, dtype=float))
        if not (0.0 < k_lin < math.inf):
            raise ValueError(f"tangential_stiffness must be positive and finite, got {tangential_stiffness!r}")
    speed = np.asarray(velocity, dtype=float)
    if np.any(~(speed > 0)) or np.any(~np.isfinite(speed)):
        raise ValueError(
            f"velocity must be positive and finite, got {float(speed[~(speed > 0) | ~np.isfinite(speed)].flat[0])!r}"
        )
    theta = np.asarray(angle, dtype=float)
    bad = ~((theta >= 0.0) & (theta < 90.0))
    if np.any(bad):
        raise ValueError(f"angle must be in [0, 90) degrees, got {float(theta[bad].flat[0])!r}")
    check_not_subnormal("velocity", speed)  # the precision is lost there
    mu = check_not_subnormal("friction", check_nonnegative("friction", friction))
    if np.any(np.isinf(mu)):
        raise ValueError("friction must be finite, got inf")
    w0 = np.asarray(spin, dtype=float)
    if not np.all(np.isfinite(w0)):
        raise ValueError(f"spin must be finite, got {float(w0[~np.isfinite(w0)].flat[0])!r}")
    speed, theta, mu, w0 = np.broadcast_arrays(speed, theta, mu, w0)

    E, R, m, p_y = pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure
    rad = np.radians(theta)
    Vn = speed * np.cos(rad)
    vt = speed * np.sin(rad)
    u0 = vt + R * w0
    Vy = float(yield_velocity(p_y, E, R, m))
    e = np.asarray(restitution_coefficient(Vn, Vy), dtype=float)
    one_e = 1.0 + e
    kappa = math.nan if tangential == "rigid" and poisson_ratio is None and effective_shear_modulus is None else None
    if kappa is None:
        try:
            kappa = stiffness_ratio_of(pair, poisson_ratio, effective_shear_modulus)
        except ValueError:
            if tangential != "rigid":
                raise
            kappa = math.nan
    # over: mu V_n beyond the largest double leaves no slip to speak of (sticking)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        u0_hat = np.where(mu > 0, u0 / (mu * Vn), np.copysign(np.inf, u0))  # slip in mu V_n
        psi = np.abs(kappa * u0_hat) if not math.isnan(kappa) else np.full(u0.shape, np.nan)

    # Tangential impulse in units of mu m V_n (signed along u0's axis), and the regime.
    J = np.zeros(u0.shape)
    regime = np.empty(u0.shape, dtype=np.int8)
    frictionless = (mu == 0.0) | (u0 == 0.0)
    dw = None  # change of R omega [m/s] where it is not 5/2 J_t/m (an arm other than R)
    law = "mindlin" if tangential == "lammps_mindlin_rescale_force" else tangential
    if law not in ("mindlin", "rigid"):
        x = np.where(Vn > 0, Vy / np.where(Vn > 0, Vn, 1.0), np.inf)
        kap = kappa
        if tangential_stiffness is not None:
            a_m = np.sqrt(R * np.asarray(elastic_max_approach(Vn, E, R, m), dtype=float))
            kap = k_lin / (2.0 * E * a_m)
            psi = np.abs(kap * u0_hat)
        if method == "table" and law in UNIVERSAL_LAWS and tangential_stiffness is None:
            table = universal_table(kappa, law=law)
            F = table(np.where(frictionless, 0.0, psi), np.minimum(x, 1.0))
            J = np.where(frictionless, 0.0, -np.sign(u0) * F * one_e)
            regime[...] = np.where(F >= 1.0, tg.REGIME_SLIDING, tg.REGIME_MICROSLIP)
        elif law == "stronge":
            u0s = np.where(frictionless, 0.0, u0_hat)
            ur, rg = _integrate_stronge(u0s, kappa, e, steps)
            J = (ur - u0s) / tg.SLIP_FACTOR
            regime[...] = rg
        else:
            eps = 0.0
            if law == "liggghts_history":
                eps = np.asarray(elastic_max_approach(Vn, E, R, m), dtype=float) / R
            scale = np.where(frictionless, 1.0, mu * Vn)
            v0h = np.where(frictionless, 0.0, vt / scale)
            w0h = np.where(frictionless, 0.0, R * w0 / scale)
            vr, wr, rg = _integrate_law(law, v0h, w0h, kap, np.minimum(x, 1.0), eps, steps)
            J = np.where(frictionless, 0.0, vr - v0h)
            dw = np.where(frictionless, 0.0, (wr - w0h) * mu * Vn)
            regime[...] = rg
        regime[frictionless & (mu > 0.0)] = tg.REGIME_STICKING
        regime[mu == 0.0] = tg.REGIME_SLIDING
    elif tangential == "rigid":
        stop = np.abs(u0_hat) / tg.SLIP_FACTOR
        rolling = stop <= one_e
        J = np.where(frictionless, 0.0, -np.sign(u0) * np.where(rolling, stop, one_e))
        regime[...] = np.where(rolling & ~frictionless, tg.REGIME_ROLLING, tg.REGIME_SLIDING)
        regime[(u0 == 0.0) & (mu > 0.0)] = tg.REGIME_ROLLING
    else:
        with np.errstate(over="ignore"):  # V_y/V_n beyond the largest double: elastic all the same (x >= 1)
            x = np.where(Vn > 0, Vy / np.where(Vn > 0, Vn, 1.0), np.inf)
        if method == "table":
            table = universal_table(kappa)
            F = table(np.where(frictionless, 0.0, psi), np.minimum(x, 1.0))
            J = np.where(frictionless, 0.0, -np.sign(u0) * F * one_e)
            # A stuck contact always slips as it opens (T falls as a, mu P as a^3), so
            # "sticking" throughout needs zero slip; F = 1 is sliding throughout.
            regime[...] = np.where(F >= 1.0, tg.REGIME_SLIDING, tg.REGIME_MICROSLIP)
        else:
            ur, rg = _integrate(u0_hat, kappa, np.minimum(x, 1.0), steps)
            J[...] = np.where(frictionless, J, (ur - u0_hat) / tg.SLIP_FACTOR)
            regime[...] = np.where(frictionless, regime, rg)
        regime[frictionless & (mu > 0.0)] = tg.REGIME_STICKING
        regime[mu == 0.0] = tg.REGIME_SLIDING

    Jt = np.where(frictionless, 0.0, J * mu * Vn)  # J_t / m [m/s]
    vt_out = vt + Jt
    with np.errstate(over="ignore"):  # a spin beyond the largest double (speeds near it over R): inf
        if dw is None:
            w_out = w0 + tg.SLIP_FACTOR * 5.0 / 7.0 * Jt / R  # r omega' = r omega + 5/2 J_t/m
            ur = u0 + tg.SLIP_FACTOR * Jt
        else:
            w_out = w0 + dw / R
            ur = u0 + Jt + dw
    Vn_out = e * Vn
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # over: as u0_hat above
        e_t = np.where(vt != 0.0, vt_out / vt, np.nan)
        slip_ratio = np.where(u0 != 0.0, ur / u0, np.nan)
        F_out = np.where(mu > 0, np.abs(Jt) / (mu * one_e * Vn), 0.0)
    return ObliqueImpact(
        angle=theta,
        normal_speed=Vn,
        tangential_speed=vt,
        normalized_angle=psi,
        normal_restitution=e,
        tangential_restitution=e_t,
        slip_ratio=slip_ratio,
        rebound_angle=np.degrees(np.arctan2(vt_out, Vn_out)),
        contact_rebound_angle=np.degrees(np.arctan2(ur, Vn_out)),
        rebound_spin=w_out,
        tangential_velocity=vt_out,
        impulse_ratio=F_out,
        regime=np.asarray([OBLIQUE_REGIMES[int(c)] for c in regime.ravel()]).reshape(regime.shape),
        tangential=tangential,
        kappa=float(kappa),
        large_strain=_large_strain(Vn, E, R, m, p_y),
    )


def _large_strain(Vn, E, R, m, p_y):
    """The seed model's small-strain flag (``a*/R* > 0.3``) of the normal impact."""
    from ..impact import impact_outcome

    out = impact_outcome(np.maximum(Vn, 1e-300), E, R, m, p_y)
    return np.asarray(out["large_strain"], dtype=bool)


# ============================================================================ the independent check


#: Most segments between events (stick/slip changes, yield, maximum approach, end) that
#: :func:`integrate_oblique_ode` follows: an impact has a handful; reaching the bound is a ValueError
#: naming it, not a result taken in the middle of the contact.
ODE_MAX_SEGMENTS = 200


def integrate_oblique_ode(u0_hat, kappa, x, *, rtol=1e-12, atol=1e-14, record=False):
    """The same impact as a 3-degree-of-freedom ODE: normal approach, tangential velocity, spin.

    Newton's equations ``alpha'' = -P(alpha)``, ``v_t' = T/m``, ``r omega' = 5/2 T/m`` are
    integrated together with :func:`scipy.integrate.solve_ivp` (DOP853), the normal force
    from the force law (Hertz eq. 2, plastic eq. 8, unloading eq. 10 with ``R_p`` and
    ``alpha_p`` from the maximum approach the integration reaches, eqs. 9, 11), the contact
    radius from the approach, and the same tangential law; terminal events locate the
    yield, the maximum approach, the separation and every stick/slip change. This is the
    independent check of the closed-form-history integration
    (:func:`~microimpact.core.tangential.integrate_tangential`). Normalised units as there.

    Parameters
    ----------
    u0_hat, kappa, x : float
        Initial slip ``u0/(mu V)`` [-], ``4 G*/E*`` [-], ``V_y/V`` [-].
    rtol, atol : float
        Solver tolerances.
    record : bool
        Also return ``time`` and ``energy``: the tangential energy (translational
        ``v_t^2/2`` plus rotational ``(r omega)^2/5`` plus stored ``T^2/(2 k_t)``, in
        ``m (mu V)^2``) at 40 points of every segment between events.

    Returns
    -------
    dict
        ``u_r`` (final slip ``u_r/(mu V)``), ``v_t``, ``r_omega`` (the two parts of the
        change, ``mu V`` units, starting from ``v_t = u0``, ``r omega = 0``), ``e`` (normal
        restitution), ``regime`` (code), ``switches`` (number of regime changes).
    """
    from scipy.integrate import solve_ivp

    hc = tg.history_constants(x)
    elastic = hc[0] == 1.0
    a_y, k_pl = hc[2], hc[3]
    p_y = 1.25 * a_y**1.5
    state = {"stage": 1, "rp": 1.0, "ap": 0.0}

    def normal(al, ad):
        """(P, a, kn, adot/a) at approach al, velocity ad."""
        st = state["stage"]
        if st == 1:
            al = max(al, 0.0)
            a = math.sqrt(al)
            return 1.25 * al**1.5, a, 1.875 * a, (ad / (2 * al) if al > 0 else 0.0)
        if st == 2:
            return p_y + k_pl * (al - a_y), math.sqrt(al), k_pl, ad / (2 * al)
        d = max(al - state["ap"], 0.0)
        a = math.sqrt(state["rp"] * d)
        return 1.25 * math.sqrt(state["rp"]) * d**1.5, a, 1.875 * a, (ad / (2 * d) if d > 0 else 0.0)

    def tforce(y, sliding, sign):
        P, a, _, _ = normal(y[0], y[1])
        if sliding:
            return -sign * P
        if state["stage"] == 3:
            return 1.875 * kappa * a * y[4]
        return y[4]

    def rhs_factory(sliding, sign):
        def rhs(t, y):
            P, a, _, _ = normal(y[0], y[1])
            T = tforce(y, sliding, sign)
            u = y[2] + y[3]
            if sliding:
                dx = 0.0
            elif state["stage"] == 3:
                dx = -u
            else:
                dx = -1.875 * kappa * a * u
            return [y[1], -P, T, 2.5 * T, dx]

        return rhs

    def switch_factory(sliding, sign):
        def g(t, y):
            P, a, kn, ada = normal(y[0], y[1])
            kt = 1.875 * kappa * a
            if sliding:
                val = sign * kt * (y[2] + y[3]) - kn * y[1]
                if state["stage"] == 3:
                    val += P * ada
                return -val
            return abs(tforce(y, False, sign)) - P

        g.terminal = True
        g.direction = 1
        return g

    def ev(fun, direction):
        fun.terminal = True
        fun.direction = direction
        return fun

    u0 = float(u0_hat)
    sliding = kappa * abs(u0) > 1.0
    sign = 1.0 if u0 >= 0 else -1.0
    slid, stuck, switches = sliding, not sliding, 0
    y = np.array([0.0, 1.0, u0, 0.0, 0.0])
    t = 0.0
    a_star = None
    times, energy = [], []
    for _ in range(ODE_MAX_SEGMENTS):
        st = state["stage"]
        events = [switch_factory(sliding, sign)]
        if st == 1 and not elastic:
            events.append(ev(lambda t, y: y[0] - a_y, 1))
        if st in (1, 2):
            events.append(ev(lambda t, y: y[1], -1))
        else:
            events.append(ev(lambda t, y: y[0] - state["ap"], -1))
        sol = solve_ivp(
            rhs_factory(sliding, sign),
            (t, t + 50.0),
            y,
            method="DOP853",
            rtol=rtol,
            atol=atol,
            events=events,
            dense_output=record,
        )
        hit = [i for i, te in enumerate(sol.t_events) if te.size]
        if not hit:  # pragma: no cover - a segment is at most a contact time (about 3.2 here) long
            raise ValueError(f"integrate_oblique_ode reached no event within 50 time units of t = {t:.6g}")
        i = min(hit, key=lambda k: sol.t_events[k][0])
        if record:
            for tt in np.linspace(t, float(sol.t_events[i][0]), 40):
                yy = sol.sol(tt)
                T = tforce(yy, sliding, sign)
                kt = 1.875 * kappa * normal(yy[0], yy[1])[1]
                stored = 0.5 * T * T / kt if kt > 0 else 0.0
                times.append(float(tt))
                energy.append(0.5 * yy[2] ** 2 + 0.2 * yy[3] ** 2 + stored)
        t = float(sol.t_events[i][0])
        y = np.array(sol.y_events[i][0], dtype=float)
        if i == 0:  # regime change
            switches += 1
            if sliding:
                P = normal(y[0], y[1])[0]
                T = -sign * P
                y[4] = T / (1.875 * kappa * normal(y[0], y[1])[1]) if st == 3 else T
                sliding, stuck = False, True
            else:
                T = tforce(y, False, sign)
                sign = -1.0 if T > 0 else 1.0
                sliding, slid = True, True
            continue
        name = "yield" if (st == 1 and not elastic and i == 1) else ("end" if st == 3 else "top")
        if name == "yield":
            y[0] = a_y
            state["stage"] = 2
        elif name == "top":
            a_star = float(y[0])
            y[1] = 0.0
            P_star = 1.25 * a_star**1.5 if st == 1 else p_y + k_pl * (a_star - a_y)
            F_e = 1.25 * a_star**1.5
            state["rp"] = F_e / P_star
            state["ap"] = a_star * (1.0 - P_star / F_e)
            if not sliding:  # the stuck state becomes S = T / k_t (a = alpha*^(1/2) here)
                y[4] = y[4] / (1.875 * kappa * math.sqrt(a_star))
            state["stage"] = 3
        else:
            break
    else:
        raise ValueError(
            f"integrate_oblique_ode reached its bound of {ODE_MAX_SEGMENTS} segments between events "
            f"(stage {state['stage']} after {switches} stick/slip changes) before the contact ended: "
            f"the tangential law chatters here (u0_hat={u0_hat!r}, kappa={kappa!r}, x={x!r})"
        )
    regime = tg.REGIME_MICROSLIP if (slid and stuck) else (tg.REGIME_SLIDING if slid else tg.REGIME_STICKING)
    extra = {"time": np.array(times), "energy": np.array(energy)} if record else {}
    return {
        **extra,
        "u_r": float(y[2] + y[3]),
        "v_t": float(y[2]),
        "r_omega": float(y[3]),
        "e": float(-y[1]),
        "regime": regime,
        "switches": switches,
    }


# The C source of a table and the published alumina case, each in a room of its own
from ._cases import ALUMINA_CASE, alumina_pair, measured_alumina  # noqa: E402
from ._csource import table_c_source  # noqa: E402
