"""Fit the limiting contact pressure (or ``k``, ``E*``, density) to measured restitution data.

The seed paper notes that the limiting contact pressure ``p_y`` is uncertain and
"may be modified by fitting the experimental data". :func:`fit_restitution` does
that: given measured impact speeds ``V_i`` and restitution coefficients ``e_i``
(optionally their standard uncertainties ``sigma_i``) and a known
:class:`~microimpact.pair.ContactPair`, it adjusts one free parameter so that the
model's ``e(V)`` (seed eq. 27, with ``V_y`` from eq. 28) matches the data.

What restitution data can and cannot determine
----------------------------------------------
The model's restitution depends on the impact speed only through ``V / V_y``
(seed eqs. 22, 27) and ``V_y`` depends on the pair only through
``p_y^(5/2) E*^(-2) m*^(-1/2) R*^0`` (eq. 28 and its general energy form: ``R*``
cancels). Restitution data therefore determine ``V_y`` and *exactly one*
parameter given the others: scaling ``E*`` by ``lambda`` and ``p_y`` by
``lambda^(4/5)`` leaves every ``e(V)`` unchanged, whatever the speed range of
the data. Asking for two free parameters raises a :class:`ValueError` that says
so (their Jacobian columns are proportional, so no data set can separate them).
The free parameter is one of

* ``"limiting_pressure"`` ``p_y`` [Pa] (default);
* ``"k"``: ``p_y = k Y`` with a known yield strength ``Y`` (``yield_strength=``
  or the smaller yield strength of the pair's materials);
* ``"effective_modulus"`` ``E*`` [Pa];
* ``"density"`` [kg/m^3] of the particle of a sphere-on-flat pair (changes ``m*``);
* ``"yield_velocity"`` ``V_y`` [m/s] itself (the pair's ``p_y`` is then adjusted).

Whatever the free parameter, the result also reports the derived ``V_y`` with
its confidence interval.

Method
------
* Optimiser: :func:`scipy.optimize.least_squares` (trust-region reflective).
  We chose it over lmfit because it adds no dependency (scipy is already a
  runtime requirement), it has the robust losses built in (``"soft_l1"``,
  ``"huber"``, ``"cauchy"``, ``"arctan"``), and it returns the Jacobian at the
  solution, which is all the covariance needs. lmfit would wrap the same
  routine and add parameter objects this one-parameter problem does not need.
* Parametrisation: the fit runs in ``u = ln(theta / theta_ref)``, which keeps the
  parameter positive and the problem well scaled (``p_y`` ~ 1e8 Pa); ``V_y`` is a
  power law of every free parameter, so ``e`` is smooth in ``u``.
* Start: a grid search of the least-absolute-deviation objective over ``V_y``
  (robust to outliers and to the flat region where every point is elastic),
  then the local least-squares refinement.
* Elastic points: the model gives ``e = 1`` at and below the fitted ``V_y``; such
  points stay in the fit with the residual ``e_i - 1`` (they constrain ``V_y``
  from above) and are counted in :attr:`FitResult.n_elastic`.
* Residuals ``r_i = (e_i - e(V_i)) / sigma_i`` (``sigma_i = 1`` if not given).
* Covariance of ``u`` (delta method from the Jacobian ``J`` at the solution):

  - ``loss="linear"``: ``C = s^2 (J^T J)^-1``. Without ``sigma``, ``s^2`` is the
    residual variance ``sum r_i^2 / (n - p)``. With ``sigma`` the uncertainties are
    taken as absolute (``s^2 = 1``; ``absolute_sigma=False`` rescales by the
    reduced chi-square instead, treating ``sigma`` as relative weights).
  - robust losses: Huber's asymptotic covariance of an M-estimator,
    ``C = [sum psi_i^2 / (n - p)] / [mean psi'_i]^2 (J^T J)^-1`` with ``psi`` the
    derivative of the loss (Huber, *Robust Statistics*, 1981, ch. 7); the scale
    always comes from the residuals here. It reduces to the linear case when
    ``psi(r) = r``.
* Confidence intervals: ``u_hat +- q sqrt(C)`` mapped back by ``exp`` (so they
  are asymmetric in the parameter and stay positive), with ``q`` the Student
  ``t`` quantile with ``n - p`` degrees of freedom when the scale is estimated
  from the residuals, and the normal quantile when ``sigma`` is absolute (known
  variance). Standard errors in parameter units are ``theta_hat sqrt(C)``
  (first-order delta method). :meth:`FitResult.confidence_band` propagates
  ``C`` to ``e(V)`` the same way.

Measured accuracy (tests/test_fitting.py): noise-free data give ``p_y`` back to
better than 1e-6 relative; over 200 seeded synthetic data sets the 95 %
intervals cover the true value in about 95 % of draws.
"""

from __future__ import annotations

import csv
import io
import math
import os
from dataclasses import dataclass, field

import numpy as np
from scipy import special

from ._optional import require
from .impact import restitution_coefficient
from .materials import DEFAULT_K, sphere_mass
from .pair import ContactPair

__all__ = [
    "FREE_PARAMETERS",
    "LOSSES",
    "FitResult",
    "RestitutionData",
    "fit_restitution",
    "load_restitution_csv",
    "plot_fit",
    "plot_residuals",
]

#: Parameters that :func:`fit_restitution` can leave free, with the exponent ``c``
#: of ``V_y ~ theta^c`` (eq. 28: ``V_y ~ p_y^(5/2) E*^(-2) rho^(-1/2)``), the
#: unit shown to people, and the scale from SI to that unit.
FREE_PARAMETERS: dict[str, dict] = {
    "limiting_pressure": {"exponent": 2.5, "unit": "MPa", "scale": 1e-6, "symbol": "p_y", "tex": "$p_y$"},
    "k": {"exponent": 2.5, "unit": "", "scale": 1.0, "symbol": "k = p_y/Y", "tex": "$k = p_y/Y$"},
    "effective_modulus": {"exponent": -2.0, "unit": "GPa", "scale": 1e-9, "symbol": "E*", "tex": "$E^*$"},
    "density": {"exponent": -0.5, "unit": "kg/m^3", "scale": 1.0, "symbol": "rho", "tex": r"$\rho$"},
    "yield_velocity": {"exponent": 1.0, "unit": "m/s", "scale": 1.0, "symbol": "V_y", "tex": "$V_y$"},
}

#: Losses of :func:`scipy.optimize.least_squares` accepted by :func:`fit_restitution`.
LOSSES = ("linear", "soft_l1", "huber", "cauchy", "arctan")

# Column names accepted by load_restitution_csv (lower case, units stripped).
_VELOCITY_NAMES = ("velocity", "v", "speed", "impact_velocity", "impact_speed")
_RESTITUTION_NAMES = ("restitution", "e", "cor", "coefficient_of_restitution")
_SIGMA_NAMES = ("sigma", "e_err", "uncertainty", "e_sigma", "restitution_err", "restitution_sigma")
_VELOCITY_UNITS = ("m/s", "m s-1", "m s^-1", "m.s-1", "m*s^-1", "m s**-1")


# --------------------------------------------------------------------------- data
class RestitutionData(tuple):
    """``(velocity, restitution, sigma)`` as read from a file, plus where each point came from.

    Unpacks like a 3-tuple; ``.lines`` holds the 1-based line number of each
    point in the file and ``.source`` the file name (used in error messages).
    """

    def __new__(cls, velocity, restitution, sigma, lines, source=""):
        self = super().__new__(cls, (velocity, restitution, sigma))
        self.lines = lines
        self.source = source
        return self

    velocity = property(lambda self: self[0], doc="impact speeds [m/s]")
    restitution = property(lambda self: self[1], doc="restitution coefficients [-]")
    sigma = property(lambda self: self[2], doc="standard uncertainties of e [-], or None")


def _column_key(text: str) -> tuple[str, str]:
    """Header cell -> (name, unit): ``"Velocity [m/s]"`` -> ``("velocity", "m/s")``."""
    text = text.strip().strip('"').strip()
    unit = ""
    for open_, close in (("[", "]"), ("(", ")")):
        if open_ in text:
            head, _, rest = text.partition(open_)
            unit = rest.split(close)[0].strip()
            text = head
    name = text.strip().lower().replace(" ", "_").replace("-", "_")
    return name, unit


def _split(line: str, delimiter):
    if delimiter is None:
        return line.split()
    return [c.strip() for c in next(csv.reader(io.StringIO(line), delimiter=delimiter))]


def load_restitution_csv(path) -> RestitutionData:
    """Read measured impact speeds and restitution coefficients from a CSV file.

    The first non-comment line is a header naming the columns (case-insensitive,
    units in brackets allowed): the speed as ``velocity``, ``V`` or ``speed``
    [m/s]; the restitution coefficient as ``restitution`` or ``e``; optionally its
    standard uncertainty as ``sigma``, ``e_err`` or ``uncertainty``. Other columns
    are ignored. Lines starting with ``#`` and blank lines are skipped, text after
    a ``#`` is a comment. Cells are separated by commas (or semicolons, tabs, or
    blanks if the header uses them).

    Parameters
    ----------
    path : str or os.PathLike
        The file.

    Returns
    -------
    RestitutionData
        Unpacks as ``velocity, restitution, sigma`` (float arrays [m/s], [-], [-];
        ``sigma`` is None without that column); ``.lines`` gives each point's line.

    Raises
    ------
    ValueError
        With the file's line number: missing columns, a wrong number of cells,
        non-numeric or non-finite cells, negative (or zero) speeds, restitution
        outside (0, 1], non-positive uncertainties, no data rows.

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
    ...     _ = f.write("# speed in m/s\\nvelocity,e\\n20,0.88\\n40,0.78\\n")
    >>> V, e, sigma = load_restitution_csv(f.name)
    >>> V, e, sigma
    (array([20., 40.]), array([0.88, 0.78]), None)
    >>> os.unlink(f.name)
    """
    name = os.fspath(path)
    with open(name, encoding="utf-8-sig") as fh:
        raw = fh.read().splitlines()
    where = os.path.basename(name)
    header = None
    rows = []
    for lineno, line in enumerate(raw, start=1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        if header is None:
            header = (lineno, text)
            continue
        rows.append((lineno, text))
    if header is None:
        raise ValueError(f"{where}: no header line (expected columns velocity, restitution)")
    hline, htext = header
    delimiter = next((d for d in (",", ";", "\t") if d in htext), None)
    cells = _split(htext, delimiter)
    keys = [_column_key(c) for c in cells]

    def find(names, what, required=True):
        hits = [i for i, (k, _) in enumerate(keys) if k in names]
        if len(hits) > 1:
            raise ValueError(
                f"{where} line {hline}: more than one {what} column: " + ", ".join(repr(cells[i]) for i in hits)
            )
        if not hits:
            if required:
                raise ValueError(
                    f"{where} line {hline}: missing column {what} (accepted names: "
                    f"{', '.join(names[:3])}); header is {htext!r}"
                )
            return None
        return hits[0]

    iv = find(_VELOCITY_NAMES, "velocity")
    ie = find(_RESTITUTION_NAMES, "restitution")
    isg = find(_SIGMA_NAMES, "sigma", required=False)
    unit = keys[iv][1].lower()
    if unit and unit not in _VELOCITY_UNITS:
        raise ValueError(f"{where} line {hline}: velocity must be in m/s, the header says {cells[iv]!r}")
    if not rows:
        raise ValueError(f"{where}: no data rows after the header on line {hline}")

    V, e, s, lines = [], [], [], []
    for lineno, text in rows:
        row = _split(text, delimiter)
        if len(row) != len(cells):
            raise ValueError(f"{where} line {lineno}: expected {len(cells)} cells like the header, found {len(row)}")

        def number(i, what):
            cell = row[i]
            if cell == "":
                raise ValueError(f"{where} line {lineno}: empty {what} cell")
            try:
                x = float(cell)
            except ValueError:
                raise ValueError(f"{where} line {lineno}: {what} {cell!r} is not a number") from None
            if not math.isfinite(x):
                raise ValueError(f"{where} line {lineno}: {what} {cell!r} is not a finite number")
            return x

        v = number(iv, "velocity")
        if v < 0:
            raise ValueError(f"{where} line {lineno}: negative impact speed {v:g} m/s")
        if v == 0:
            raise ValueError(f"{where} line {lineno}: impact speed must be positive, got 0")
        r = number(ie, "restitution")
        if not 0.0 < r <= 1.0:
            raise ValueError(f"{where} line {lineno}: restitution {r:g} is outside (0, 1]")
        if isg is not None:
            sg = number(isg, "sigma")
            if sg <= 0:
                raise ValueError(f"{where} line {lineno}: sigma must be positive, got {sg:g}")
            s.append(sg)
        V.append(v)
        e.append(r)
        lines.append(lineno)
    sigma = np.asarray(s, dtype=float) if isg is not None else None
    return RestitutionData(
        np.asarray(V, dtype=float), np.asarray(e, dtype=float), sigma, np.asarray(lines, dtype=int), source=where
    )


# --------------------------------------------------------------------------- model
def _where(i, line_numbers):
    return f"line {int(line_numbers[i])}" if line_numbers is not None else f"point {int(i)}"


def _check_data(velocity, restitution, sigma, line_numbers):
    V = np.asarray(velocity, dtype=float).ravel()
    e = np.asarray(restitution, dtype=float).ravel()
    if V.size != e.size:
        raise ValueError(f"velocity and restitution must have the same length, got {V.size} and {e.size}")
    if V.size == 0:
        raise ValueError("no data points")
    if line_numbers is not None:
        line_numbers = np.asarray(line_numbers).ravel()
        if line_numbers.size != V.size:
            raise ValueError("line_numbers must have one entry per data point")
    bad = ~(np.isfinite(V) & (V > 0))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"velocity must be positive and finite, got {float(V[i])!r} ({_where(i, line_numbers)})")
    bad = ~((e > 0) & (e <= 1))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"restitution must lie in (0, 1], got {float(e[i])!r} ({_where(i, line_numbers)})")
    if sigma is not None:
        s = np.broadcast_to(np.asarray(sigma, dtype=float), V.shape).copy()
        bad = ~(np.isfinite(s) & (s > 0))
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"sigma must be positive and finite, got {float(s[i])!r} ({_where(i, line_numbers)})")
        sigma = s
    return V, e, sigma, line_numbers


def _parse_params(params):
    if isinstance(params, str):
        params = [p.strip() for p in params.split(",") if p.strip()]
    params = tuple(params)
    if not params:
        raise ValueError("params: give at least one free parameter")
    for p in params:
        if p not in FREE_PARAMETERS:
            raise ValueError(f"params must be among {', '.join(FREE_PARAMETERS)}, got {p!r}")
    if len(set(params)) != len(params):
        raise ValueError(f"params: each parameter once, got {params!r}")
    if len(params) > 1:
        raise ValueError(
            f"params {', '.join(params)}: restitution data determine only one parameter. The model's "
            "e depends on V only through V/V_y, and V_y on p_y^(5/2) E*^(-2) m*^(-1/2) (seed eqs. 27-28), "
            "so these parameters are not separately identifiable whatever the speed range; "
            "fix all but one (e.g. params=('limiting_pressure',))"
        )
    return params


class _Model:
    """Maps the free parameter to a :class:`ContactPair` (by ``pair.replace``) and ``e(V)``."""

    def __init__(self, pair: ContactPair, name: str, yield_strength=None):
        if not isinstance(pair, ContactPair):
            raise ValueError(f"pair must be a ContactPair, got {type(pair).__name__}")
        self.pair = pair
        self.name = name
        self.exponent = FREE_PARAMETERS[name]["exponent"]
        self.yield_strength = None
        finite_py = math.isfinite(pair.limiting_pressure)
        if not finite_py and name in ("effective_modulus", "density"):
            raise ValueError(f"pair has limiting_pressure = inf (never yields): give it a finite p_y to fit {name}")
        if name == "k":
            Y = yield_strength
            if Y is None:
                known = [m.yield_strength for m in (pair.particle, pair.surface) if m is not None and m.yield_strength]
                Y = min(known) if known else None
            if Y is None:
                raise ValueError(
                    "yield_strength is needed to fit k = p_y / Y: give yield_strength=... or a pair "
                    "built from materials with a yield strength"
                )
            Y = float(Y)
            if not (math.isfinite(Y) and Y > 0):
                raise ValueError(f"yield_strength must be positive and finite, got {Y!r}")
            self.yield_strength = Y
            self.ref = pair.limiting_pressure / Y if finite_py else DEFAULT_K
        elif name == "limiting_pressure":
            self.ref = pair.limiting_pressure if finite_py else 1e8
        elif name == "effective_modulus":
            self.ref = pair.effective_modulus
        elif name == "density":
            rho = pair.density
            if rho is None or not math.isclose(
                pair.effective_mass, float(sphere_mass(pair.effective_radius, rho)), rel_tol=1e-9
            ):
                raise ValueError(
                    "density can be fitted only for a sphere on a flat with a known radius and density "
                    "(ContactPair.sphere_on_flat or from_materials)"
                )
            self.ref = rho
        elif name == "yield_velocity":
            # V_y ~ p_y^(5/2) at fixed E*, m*: vary p_y from this base pair.
            self.base = pair if finite_py else pair.replace(limiting_pressure=1e8)
            self.ref = self.base.yield_velocity
        # Every free parameter enters V_y as a power law; a pair with p_y = inf has no
        # finite V_y, so the reference pair takes a nominal finite p_y there.
        self.ref_pair = self.pair_at(0.0) if not finite_py else pair
        self.ref_vy = self.ref_pair.yield_velocity

    def pair_at(self, u) -> ContactPair:
        """The pair with the free parameter at ``ref * exp(u)``."""
        theta = float(self.ref * math.exp(float(u)))
        p = self.pair
        if self.name == "limiting_pressure":
            return p.replace(limiting_pressure=theta)
        if self.name == "k":
            return p.replace(limiting_pressure=theta * self.yield_strength)
        if self.name == "effective_modulus":
            return p.replace(effective_modulus=theta)
        if self.name == "density":
            return p.resized(density=theta)
        # yield_velocity
        return self.base.replace(limiting_pressure=self.base.limiting_pressure * (theta / self.ref) ** 0.4)

    def yield_velocity(self, u):
        """``V_y`` [m/s] at ``u``, from the pair (eq. 28, general energy form)."""
        return self.pair_at(u).yield_velocity

    def restitution(self, u, V):
        """Model ``e(V)`` (eq. 27) of the pair at ``u``."""
        return restitution_coefficient(V, self.yield_velocity(u))

    def u_of_yield_velocity(self, vy):
        """Inverse of the power law ``V_y = V_y,ref exp(c u)`` (start values)."""
        return np.log(np.asarray(vy) / self.ref_vy) / self.exponent


# ---------------------------------------------------------------------- losses
def _psi(loss, r, f_scale):
    """``psi(r) = dL/dr`` and ``psi'(r)`` of the loss ``L(r) = f^2/2 rho((r/f)^2)`` of least_squares."""
    z = (r / f_scale) ** 2
    if loss == "linear":
        d1, d2 = np.ones_like(z), np.zeros_like(z)
    elif loss == "soft_l1":
        d1 = 1.0 / np.sqrt(1.0 + z)
        d2 = -0.5 * (1.0 + z) ** -1.5
    elif loss == "huber":
        small = z <= 1.0
        d1 = np.where(small, 1.0, 1.0 / np.sqrt(np.where(small, 1.0, z)))
        d2 = np.where(small, 0.0, -0.5 * np.where(small, 1.0, z) ** -1.5)
    elif loss == "cauchy":
        d1 = 1.0 / (1.0 + z)
        d2 = -1.0 / (1.0 + z) ** 2
    else:  # arctan
        d1 = 1.0 / (1.0 + z**2)
        d2 = -2.0 * z / (1.0 + z**2) ** 2
    return r * d1, d1 + 2.0 * z * d2


# ---------------------------------------------------------------------- result
@dataclass(frozen=True, eq=False)
class FitResult:
    """Outcome of :func:`fit_restitution`.

    Attributes
    ----------
    params : dict
        Estimate of each free parameter, SI units (``k`` dimensionless).
    stderr : dict
        Standard error of each (delta method: ``theta sqrt(C_uu)``).
    conf_int : dict
        ``(lo, hi)`` confidence interval of each, at :attr:`confidence` (exact image of the
        symmetric interval in ``ln theta``).
    covariance : ndarray
        Covariance of the free parameters, SI units (delta method from ``log_covariance``).
    log_covariance : ndarray
        Covariance of ``ln theta`` (what the fit computes).
    yield_velocity : float
        Fitted ``V_y`` [m/s]; ``yield_velocity_stderr`` and ``yield_velocity_conf_int`` likewise.
    residuals : ndarray
        ``e_i - e(V_i)`` at the solution, in the order of the data.
    chi2 : float
        ``sum ((e_i - e(V_i)) / sigma_i)^2`` (``sigma_i = 1`` without sigma, then equal to ``rss``).
    rss : float
        ``sum (e_i - e(V_i))^2``.
    dof : int
        ``n_points - len(params)``.
    n_points, n_elastic : int
        Number of points, and of points at or below the fitted ``V_y`` (model ``e = 1``).
    pair : ContactPair
        The fitted pair, ready to use (``fit.pair.impact(V)``).
    success : bool
        The optimiser converged.
    message : str
        The optimiser's message.
    """

    params: dict
    stderr: dict
    conf_int: dict
    covariance: np.ndarray
    log_covariance: np.ndarray
    yield_velocity: float
    yield_velocity_stderr: float
    yield_velocity_conf_int: tuple
    residuals: np.ndarray
    chi2: float
    rss: float
    dof: int
    n_points: int
    n_elastic: int
    pair: ContactPair
    success: bool
    message: str
    confidence: float
    loss: str
    f_scale: float
    absolute_sigma: bool
    quantile: float
    velocity: np.ndarray = field(repr=False)
    restitution: np.ndarray = field(repr=False)
    sigma: np.ndarray | None = field(repr=False)
    nfev: int = 0
    _model: _Model = field(repr=False, default=None)
    _u: np.ndarray = field(repr=False, default=None)

    @property
    def free(self) -> tuple:
        """Names of the free parameters."""
        return tuple(self.params)

    @property
    def reduced_chi2(self) -> float:
        """``chi2 / dof`` (about 1 when ``sigma`` describes the scatter)."""
        return self.chi2 / self.dof if self.dof > 0 else math.nan

    def predict(self, velocity):
        """Restitution coefficient of the fitted pair at ``velocity`` [m/s] (seed eq. 27)."""
        return self.pair.restitution(velocity)

    def confidence_band(self, velocity, confidence=None):
        """Pointwise confidence band ``(lo, hi)`` of the fitted ``e(V)``.

        Delta method: ``var e(V) = g C g^T`` with ``g = de/du`` (central difference
        in the log-parameter ``u``) and ``C`` the fit's :attr:`log_covariance`;
        the band is ``e +- q sqrt(var)``, clipped to ``[0, 1]``, with ``q`` the
        quantile used for :attr:`conf_int` (or the one for ``confidence``).
        """
        V = np.asarray(velocity, dtype=float)
        q = self.quantile if confidence is None else self._quantile(confidence)
        h = 1e-6
        u = self._u
        grads = []
        for j in range(u.size):
            up, um = u.copy(), u.copy()
            up[j] += h
            um[j] -= h
            grads.append((self._model.restitution(up[0], V) - self._model.restitution(um[0], V)) / (2 * h))
        g = np.stack(grads, axis=-1)
        var = np.einsum("...i,ij,...j->...", g, self.log_covariance, g)
        e = self._model.restitution(u[0], V)
        half = q * np.sqrt(np.maximum(var, 0.0))
        return np.clip(e - half, 0.0, 1.0), np.clip(e + half, 0.0, 1.0)

    def _quantile(self, confidence):
        confidence = _check_confidence(confidence)
        return _quantile(confidence, self.dof, self.absolute_sigma and self.loss == "linear")

    def to_dict(self) -> dict:
        """Estimates, errors and fit statistics as plain Python values (SI units)."""
        return {
            "params": {k: float(v) for k, v in self.params.items()},
            "stderr": {k: float(v) for k, v in self.stderr.items()},
            "conf_int": {k: [float(a), float(b)] for k, (a, b) in self.conf_int.items()},
            "confidence": self.confidence,
            "yield_velocity": self.yield_velocity,
            "yield_velocity_stderr": self.yield_velocity_stderr,
            "yield_velocity_conf_int": [float(x) for x in self.yield_velocity_conf_int],
            "covariance": np.asarray(self.covariance).tolist(),
            "chi2": self.chi2,
            "rss": self.rss,
            "dof": self.dof,
            "reduced_chi2": self.reduced_chi2,
            "n_points": self.n_points,
            "n_elastic": self.n_elastic,
            "loss": self.loss,
            "f_scale": self.f_scale,
            "absolute_sigma": self.absolute_sigma,
            "success": self.success,
            "message": self.message,
            "pair": {
                "label": self.pair.label,
                "effective_modulus": self.pair.effective_modulus,
                "effective_radius": self.pair.effective_radius,
                "effective_mass": self.pair.effective_mass,
                "density": self.pair.density,
                "limiting_pressure": self.pair.limiting_pressure,
            },
            "residuals": np.asarray(self.residuals).tolist(),
        }

    def summary(self) -> str:
        """The estimates with standard errors and confidence intervals, in readable units."""
        pct = f"{100 * self.confidence:g} %"
        rows = [("parameter", "estimate", "std. error", f"{pct} confidence interval")]

        def fmt_row(label, value, err, lo, hi, unit, scale):
            u = f" {unit}" if unit else ""
            return (
                label,
                f"{value * scale:.6g}{u}",
                f"{err * scale:.3g}{u}",
                f"[{lo * scale:.6g}, {hi * scale:.6g}]{u}",
            )

        for name, value in self.params.items():
            info = FREE_PARAMETERS[name]
            lo, hi = self.conf_int[name]
            rows.append(fmt_row(name, value, self.stderr[name], lo, hi, info["unit"], info["scale"]))
        if "yield_velocity" not in self.params:
            lo, hi = self.yield_velocity_conf_int
            rows.append(
                fmt_row("yield_velocity (derived)", self.yield_velocity, self.yield_velocity_stderr, lo, hi, "m/s", 1.0)
            )
        widths = [max(len(r[j]) for r in rows) for j in range(4)]
        table = ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows]
        table.insert(1, "  ".join("-" * w for w in widths))
        if self.loss == "linear":
            if self.sigma is None:
                how = "scale from the residual variance"
            elif self.absolute_sigma:
                how = "absolute sigma"
            else:
                how = "sigma as relative weights, scaled by the reduced chi-square"
        else:
            how = f"Huber M-estimator covariance, f_scale = {self.f_scale:.3g}"
        qname = "normal" if (self.absolute_sigma and self.loss == "linear") else f"Student t ({self.dof} dof)"
        head = (
            f"fit of e(V) (seed eq. 27): {self.n_points} points, {self.n_elastic} at or below V_y "
            f"(elastic), loss {self.loss}; {how}; {qname} quantile"
        )
        stats_line = (
            f"rss = {self.rss:.4g}   chi2 = {self.chi2:.4g}   dof = {self.dof}   "
            f"reduced chi2 = {self.reduced_chi2:.4g}   "
            f"rms residual = {math.sqrt(self.rss / self.n_points):.3g}"
        )
        tail = [] if self.success else [f"WARNING: the optimiser did not converge: {self.message}"]
        return "\n".join([head, *table, stats_line, *tail])

    def __str__(self) -> str:
        return self.summary()


def _check_confidence(confidence):
    c = float(confidence)
    if not 0.0 < c < 1.0:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence!r}")
    return c


def _quantile(confidence, dof, known_scale):
    p = 0.5 + confidence / 2.0
    return float(special.ndtri(p) if known_scale else special.stdtrit(dof, p))


# ---------------------------------------------------------------------- the fit
def fit_restitution(
    velocity,
    restitution,
    pair: ContactPair,
    *,
    sigma=None,
    params=("limiting_pressure",),
    loss: str = "linear",
    f_scale=None,
    confidence: float = 0.95,
    yield_strength=None,
    absolute_sigma=None,
    line_numbers=None,
    max_nfev=None,
) -> FitResult:
    """Fit one parameter of a contact pair to measured restitution coefficients.

    Parameters
    ----------
    velocity : array_like
        Measured impact speeds ``V_i`` [m/s], positive.
    restitution : array_like
        Measured restitution coefficients ``e_i``, in (0, 1].
    pair : ContactPair
        The known pair; its value of the free parameter is only a reference (the
        start comes from a grid search over the data).
    sigma : array_like or float, optional
        Standard uncertainty of each ``e_i``; absolute unless ``absolute_sigma=False``.
    params : sequence of str or str
        The free parameter: ``"limiting_pressure"`` (default), ``"k"``,
        ``"effective_modulus"``, ``"density"`` or ``"yield_velocity"``. Only one
        can be free (see the module docstring: the data determine ``V_y`` only).
    loss : str
        ``"linear"`` (least squares) or a robust loss of
        :func:`scipy.optimize.least_squares`: ``"soft_l1"``, ``"huber"``,
        ``"cauchy"``, ``"arctan"``.
    f_scale : float, optional
        Residual size at which a robust loss starts to down-weight, in units of
        ``e`` (or of ``sigma`` when given). Default: 1 with ``sigma``; without,
        ``1.4826 * MAD`` of the residuals at the robust start (a robust estimate of
        the scatter).
    confidence : float
        Level of the confidence intervals, default 0.95.
    yield_strength : float, optional
        ``Y`` [Pa] for ``params=("k",)``; default: the smaller yield strength of the
        pair's materials.
    absolute_sigma : bool, optional
        Default True when ``sigma`` is given.
    line_numbers : array_like of int, optional
        Source line of each point, quoted in error messages (the CLI passes
        :attr:`RestitutionData.lines`).
    max_nfev : int, optional
        Passed to :func:`scipy.optimize.least_squares`.

    Returns
    -------
    FitResult

    Raises
    ------
    ValueError
        Bad data (naming the point or line), unknown or non-identifiable parameter
        sets, or too few points above the yield velocity for the parameters asked.

    Examples
    --------
    >>> import numpy as np
    >>> import microimpact as mi
    >>> from microimpact.fitting import fit_restitution
    >>> pair = mi.ContactPair.paper_case("silicon")
    >>> V = np.array([5.0, 10.0, 20.0, 40.0, 80.0])
    >>> e = pair.restitution(V) + np.array([0.0, 0.01, -0.01, 0.005, -0.005])
    >>> fit = fit_restitution(V, e, pair.replace(limiting_pressure=100e6))
    >>> round(fit.params["limiting_pressure"] / 1e6, 1), fit.n_elastic
    (155.6, 1)
    """
    names = _parse_params(params)
    if loss not in LOSSES:
        raise ValueError(f"loss must be one of {', '.join(LOSSES)}, got {loss!r}")
    confidence = _check_confidence(confidence)
    V, e, sigma, line_numbers = _check_data(velocity, restitution, sigma, line_numbers)
    if absolute_sigma is None:
        absolute_sigma = sigma is not None
    absolute_sigma = bool(absolute_sigma) and sigma is not None
    w = np.ones_like(V) if sigma is None else 1.0 / sigma
    p = len(names)
    n = V.size

    plastic = e < 1.0
    if plastic.sum() < p + 1:
        at = ", ".join(_where(i, line_numbers) for i in np.flatnonzero(plastic)) or "none"
        raise ValueError(
            f"too few points above the yield velocity for {p} free parameter(s): "
            f"{int(plastic.sum())} point(s) with e < 1 ({at}); need at least {p + 1}"
        )

    model = _Model(pair, names[0], yield_strength=yield_strength)

    # Robust start: least absolute deviations over a log grid of V_y.
    vy_grid = np.geomspace(V.min() * 1e-3, V.max() * 2.0, 600)
    e_grid = restitution_coefficient(V[None, :], vy_grid[:, None])
    lad = np.sum(np.abs((e[None, :] - e_grid) * w[None, :]), axis=1)
    vy0 = vy_grid[int(np.argmin(lad))]
    u0 = np.atleast_1d(model.u_of_yield_velocity(vy0)).astype(float)

    if f_scale is None:
        if loss == "linear" or sigma is not None:
            f_scale = 1.0
        else:
            r0 = e - restitution_coefficient(V, vy0)
            f_scale = max(1.4826 * float(np.median(np.abs(r0 - np.median(r0)))), 1e-6)
    else:
        f_scale = float(f_scale)
        if not (math.isfinite(f_scale) and f_scale > 0):
            raise ValueError(f"f_scale must be positive and finite, got {f_scale!r}")

    def resid(u):
        return (model.restitution(u[0], V) - e) * w

    kw = {} if max_nfev is None else {"max_nfev": int(max_nfev)}
    from scipy import optimize  # imported here: keeps `import microimpact` fast

    sol = optimize.least_squares(
        resid, u0, jac="3-point", loss=loss, f_scale=f_scale, x_scale=1.0, xtol=1e-12, ftol=1e-12, gtol=1e-12, **kw
    )
    u = np.asarray(sol.x, dtype=float)
    fitted = model.pair_at(u[0])
    fitted = fitted.replace(label=(pair.label + " (fitted)").strip() if pair.label else "fitted")
    vy = fitted.yield_velocity
    e_fit = restitution_coefficient(V, vy)
    above = V > vy
    if above.sum() < p + 1:
        at = ", ".join(_where(i, line_numbers) for i in np.flatnonzero(above)) or "none"
        raise ValueError(
            f"too few points above the fitted yield velocity V_y = {vy:.4g} m/s for {p} free "
            f"parameter(s): {int(above.sum())} ({at}); need at least {p + 1}"
        )
    dof = n - p
    r_w = (e - e_fit) * w  # weighted residuals, data minus model
    J = np.asarray(sol.jac, dtype=float)
    JTJ = J.T @ J
    if not np.all(np.isfinite(JTJ)) or np.linalg.matrix_rank(JTJ) < p:
        raise ValueError("the data do not constrain the free parameter (singular Jacobian at the solution)")
    JTJ_inv = np.linalg.inv(JTJ)
    if loss == "linear":
        s2 = 1.0 if absolute_sigma else float(np.sum(r_w**2) / dof)
    else:
        psi, dpsi = _psi(loss, r_w, f_scale)
        mean_dpsi = float(np.mean(dpsi))
        if mean_dpsi <= 0:  # redescending loss with most points beyond f_scale
            raise ValueError(f"loss {loss!r} with f_scale = {f_scale:g} rejects most points; increase f_scale")
        s2 = float(np.sum(psi**2) / dof) / mean_dpsi**2
    cov_u = s2 * JTJ_inv
    known_scale = absolute_sigma and loss == "linear"
    q = _quantile(confidence, dof, known_scale)

    theta = model.ref * np.exp(u)
    se_u = np.sqrt(np.diag(cov_u))
    params_ = {nm: float(t) for nm, t in zip(names, theta)}
    stderr = {nm: float(t * s) for nm, t, s in zip(names, theta, se_u)}
    conf = {nm: (float(t * math.exp(-q * s)), float(t * math.exp(q * s))) for nm, t, s in zip(names, theta, se_u)}
    cov = cov_u * np.outer(theta, theta)
    c = model.exponent
    se_vy = abs(c) * float(se_u[0])
    vy_ci = (float(vy * math.exp(-q * se_vy)), float(vy * math.exp(q * se_vy)))
    resid_raw = e - e_fit
    return FitResult(
        params=params_,
        stderr=stderr,
        conf_int=conf,
        covariance=cov,
        log_covariance=cov_u,
        yield_velocity=float(vy),
        yield_velocity_stderr=float(vy * se_vy),
        yield_velocity_conf_int=vy_ci,
        residuals=resid_raw,
        chi2=float(np.sum(r_w**2)),
        rss=float(np.sum(resid_raw**2)),
        dof=int(dof),
        n_points=int(n),
        n_elastic=int(n - above.sum()),
        pair=fitted,
        success=bool(sol.success),
        message=str(sol.message),
        confidence=confidence,
        loss=loss,
        f_scale=float(f_scale),
        absolute_sigma=bool(absolute_sigma),
        quantile=q,
        velocity=V,
        restitution=e,
        sigma=sigma,
        nfev=int(sol.nfev),
        _model=model,
        _u=u,
    )


# ---------------------------------------------------------------------- plots
def _fit_curve_grid(fit, V):
    vmax = max(float(np.max(V)), fit.yield_velocity) * 1.08
    grid = np.union1d(np.linspace(0.0, vmax, 600)[1:], [fit.yield_velocity])
    return grid


def plot_fit(
    fit_result,
    data_velocity,
    data_restitution,
    ax=None,
    *,
    sigma=None,
    residual_ax=None,
    residuals=True,
    show_yield=True,
    data_kws=None,
    fit_kws=None,
    band_kws=None,
):
    """Measured restitution, the fitted ``e(V)`` with its confidence band, and residuals.

    Parameters
    ----------
    fit_result : FitResult
        From :func:`fit_restitution`.
    data_velocity, data_restitution : array_like
        The measured points [m/s], [-].
    ax : matplotlib Axes, optional
        Axes for data and curve. When None, a new figure with two panels (curve
        above, residuals below, shared speed axis) is made.
    sigma : array_like, optional
        Error bars; default the fit's ``sigma`` when the data are the fitted ones.
    residual_ax : matplotlib Axes, optional
        Where to draw the residuals when ``ax`` is given (skipped if None).
    residuals : bool
        Draw the residual panel in a new figure.
    show_yield : bool
        Mark the fitted ``V_y``.
    data_kws, fit_kws, band_kws : dict, optional
        Passed to ``errorbar``, ``plot`` and ``fill_between``.

    Returns
    -------
    (Axes, Axes or None)
        The curve axes and the residual axes.
    """
    plt = require("matplotlib.pyplot", "plotting")
    V = np.asarray(data_velocity, dtype=float).ravel()
    e = np.asarray(data_restitution, dtype=float).ravel()
    if sigma is None and fit_result.sigma is not None and fit_result.sigma.size == V.size:
        sigma = fit_result.sigma
    if ax is None:
        if residuals:
            fig, (ax, residual_ax) = plt.subplots(
                2,
                1,
                sharex=True,
                figsize=(6.4, 5.6),
                gridspec_kw={"height_ratios": [3, 1.2], "hspace": 0.08},
                layout="constrained",
            )
        else:
            fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
    grid = _fit_curve_grid(fit_result, V)
    lo, hi = fit_result.confidence_band(grid)
    pct = f"{100 * fit_result.confidence:g} %"
    band = {"color": "tab:blue", "alpha": 0.25, "linewidth": 0, "label": f"{pct} confidence band"}
    band.update(band_kws or {})
    ax.fill_between(grid, lo, hi, **band)
    name, value = next(iter(fit_result.params.items()))
    info = FREE_PARAMETERS[name]
    unit = f" {info['unit']}" if info["unit"] else ""
    lab = f"model fit, {info['tex']} = {value * info['scale']:.4g}{unit}"
    line = {"color": "tab:blue", "linewidth": 1.8, "label": lab}
    line.update(fit_kws or {})
    ax.plot(grid, fit_result.predict(grid), **line)
    dk = {
        "fmt": "o",
        "color": "0.15",
        "markersize": 4.5,
        "capsize": 2,
        "elinewidth": 0.8,
        "markerfacecolor": "white",
        "label": "measured",
    }
    dk.update(data_kws or {})
    ax.errorbar(V, e, yerr=sigma, **dk)
    if show_yield:
        ax.axvline(
            fit_result.yield_velocity,
            color="0.4",
            linestyle=":",
            linewidth=1.0,
            label=f"$V_y$ = {fit_result.yield_velocity:.3g} m/s",
        )
    ax.set_xlim(0.0, grid[-1])
    ax.set_ylim(0.0, 1.05)
    ax.set_ylabel("coefficient of restitution $e$")
    ax.legend(loc="lower left", frameon=False, fontsize="small")
    ax.grid(True, alpha=0.3)
    if residual_ax is not None:
        plot_residuals(fit_result, V, e, ax=residual_ax, sigma=sigma)
        ax.tick_params(labelbottom=False)
    else:
        ax.set_xlabel("impact velocity $V$ [m/s]")
    return ax, residual_ax


def plot_residuals(fit_result, data_velocity, data_restitution, ax=None, *, sigma=None, data_kws=None):
    """Residuals ``e - e_fit`` of a restitution fit against the impact speed.

    Parameters
    ----------
    fit_result : FitResult
        From :func:`fit_restitution`; ``e_fit`` is ``fit_result.predict(V)``.
    data_velocity : array_like
        Measured impact speeds ``V`` [m/s].
    data_restitution : array_like
        Measured coefficients of restitution ``e`` [-].
    ax : matplotlib Axes, optional
        Axes to draw on; a new figure if None.
    sigma : array_like, optional
        Error bars [-]; default the fit's ``sigma`` when the data are the fitted ones.
    data_kws : dict, optional
        Passed to ``ax.errorbar`` for the points.

    Returns
    -------
    matplotlib Axes
        The Axes drawn on (speed [m/s] against ``e - e_fit`` [-]).
    """
    plt = require("matplotlib.pyplot", "plotting")
    V = np.asarray(data_velocity, dtype=float).ravel()
    e = np.asarray(data_restitution, dtype=float).ravel()
    if sigma is None and fit_result.sigma is not None and fit_result.sigma.size == V.size:
        sigma = fit_result.sigma
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 2.4), layout="constrained")
    r = e - fit_result.predict(V)
    ax.axhline(0.0, color="tab:blue", linewidth=1.2)
    dk = {"fmt": "o", "color": "0.15", "markersize": 4, "capsize": 2, "elinewidth": 0.8, "markerfacecolor": "white"}
    dk.update(data_kws or {})
    ax.errorbar(V, r, yerr=sigma, **dk)
    span = float(np.max(np.abs(r) + (0 if sigma is None else np.asarray(sigma)))) if r.size else 0.0
    span = max(span * 1.15, 1e-3)
    ax.set_ylim(-span, span)
    ax.set_xlabel("impact velocity $V$ [m/s]")
    ax.set_ylabel(r"$e - e_\mathrm{fit}$")
    ax.grid(True, alpha=0.3)
    return ax
