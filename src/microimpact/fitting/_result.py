"""What a fit returns: :class:`~microimpact.fitting.FitResult` and the bands of its
:class:`~microimpact.fitting.Prediction`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..pair import ContactPair
from ..quantities import QUANTITIES
from ._models import FREE_PARAMETERS, SEED_MODEL, FitModel, real_number

# Public as microimpact.fitting.FAR_ABOVE_ONE, documented there.
FAR_ABOVE_ONE = 3.0


# ---------------------------------------------------------------------- result
@dataclass(frozen=True)
class Prediction:
    """``e(V)``, rebound speed and contact time of a fitted model, each with its band.

    Every ``*_lo`` / ``*_hi`` pair bounds the quantity pointwise at the confidence
    of the fit; ``method`` says how (``"interval ends"`` or ``"delta method"``).

    Attributes
    ----------
    velocity : ndarray
        Impact speeds ``V`` [m/s].
    restitution, restitution_lo, restitution_hi : ndarray
        Coefficient of restitution ``e`` [-] and its band.
    rebound_velocity, rebound_velocity_lo, rebound_velocity_hi : ndarray
        Rebound speed ``V_r = e V`` [m/s] and its band.
    contact_time, contact_time_lo, contact_time_hi : ndarray
        Contact time [s] and its band (seed eqs. 29-33 for the seed).
    confidence : float
        Level of the band.
    method : str
        How the band was obtained.
    """

    velocity: np.ndarray
    restitution: np.ndarray
    restitution_lo: np.ndarray
    restitution_hi: np.ndarray
    rebound_velocity: np.ndarray
    rebound_velocity_lo: np.ndarray
    rebound_velocity_hi: np.ndarray
    contact_time: np.ndarray
    contact_time_lo: np.ndarray
    contact_time_hi: np.ndarray
    confidence: float
    method: str

    def to_dict(self) -> dict:
        """Plain lists (SI units)."""
        return {
            k: (np.asarray(v).tolist() if isinstance(v, np.ndarray) else v)
            for k, v in self.__dict__.items()  # noqa: SIM118
        }


_QUANTITIES = ("restitution", "rebound_velocity", "contact_time")


@dataclass(frozen=True, eq=False)
class FitResult:
    """Outcome of :func:`fit_restitution`.

    Attributes
    ----------
    params : dict
        Estimate of each free parameter, SI units (``k`` dimensionless); see :attr:`units`.
    stderr : dict
        Standard error of each (delta method: ``theta sqrt(C_uu)``).
    conf_int : dict
        ``(lo, hi)`` confidence interval of each at :attr:`confidence`, by :attr:`interval`.
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
    model : str
        Name of the model (``model=`` of :func:`fit_restitution`).
    model_params : dict
        All of the model's own parameters at the solution (fitted or fixed).
    interval : str
        ``"wald"`` or ``"profile"``: how :attr:`conf_int` was obtained.
    units : dict
        SI unit of each free parameter.
    n_far_above_one : int
        Points with ``e_i - 1 > 3 s_i`` (see the module docstring); a :class:`FitWarning` names them.
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
    model: str = SEED_MODEL
    model_params: dict = field(default_factory=dict)
    interval: str = "wald"
    wald_conf_int: dict = field(default_factory=dict)
    units: dict = field(default_factory=dict)
    n_far_above_one: int = 0
    _model: FitModel = field(repr=False, default=None)
    _u: np.ndarray = field(repr=False, default=None)

    @property
    def free(self) -> tuple:
        """Names of the free parameters."""
        return tuple(self.params)

    @property
    def reduced_chi2(self) -> float:
        """``chi2 / dof`` (about 1 when ``sigma`` describes the scatter)."""
        return self.chi2 / self.dof if self.dof > 0 else math.nan

    def predict(self, velocity, band=False):
        """Restitution of the fitted model at ``velocity`` [m/s]; with ``band=True`` a :class:`Prediction`.

        Parameters
        ----------
        velocity : array_like
            Impact speeds [m/s], >= 0.
        band : bool
            False (default): return ``e(V)`` [-] as an array. True: return a
            :class:`Prediction` with ``e(V)``, the rebound speed [m/s] and the
            contact time [s], each with its band at :attr:`confidence`. With one
            free parameter the band is the range of each quantity over the
            parameter's interval :attr:`conf_int` (evaluated at its ends and the
            estimate: exact for a quantity monotone in the parameter, which ``e``,
            ``V_r`` and the contact time are for the seed); with several, the delta
            method over all of them (:attr:`log_covariance`): ``e``'s gradient by
            central differences of ``e`` alone (as :meth:`confidence_band`), ``V_r``'s
            as ``V`` times it, the contact time's by forward differences (step 1e-6 in
            ``ln theta``). It costs ``1 + p`` evaluations of the whole outcome
            (contact times) for ``p`` free parameters, and ``2p`` of ``e`` alone; a
            model whose outcome is slow in Python runs compiled (as in the fit).

        Returns
        -------
        ndarray or Prediction
        """
        if not band:
            return self._model.restitution(self._u, velocity)
        V = np.asarray(velocity, dtype=float)
        mid = self._model.outcome(self._u, V)
        if not self.params:  # nothing fitted: no band
            lo, hi = dict(mid), dict(mid)
            method = "no free parameter"
        elif len(self.params) == 1:
            ends = [self._model.outcome(u, V) for u in self._end_us()]
            lo = {q: np.minimum(mid[q], np.minimum(ends[0][q], ends[1][q])) for q in _QUANTITIES}
            hi = {q: np.maximum(mid[q], np.maximum(ends[0][q], ends[1][q])) for q in _QUANTITIES}
            method = "interval ends"
        else:
            # e by the model's e alone (central differences, as confidence_band), V_r = e V from
            # e's, the contact time (a quadrature in most models: the costly field) by forward
            # differences from the estimate: 1 + p whole outcomes, not 1 + 2p.
            lo, hi = {}, {}
            g_e = self._gradients(lambda u: {"e": self._model.restitution(u, V)}, ("e",))["e"]
            grads = {
                "restitution": g_e,
                "rebound_velocity": g_e * V[..., None],
                "contact_time": self._forward(lambda u: self._model.outcome(u, V)["contact_time"], mid["contact_time"]),
            }
            for q in _QUANTITIES:
                half = self.quantile * np.sqrt(self._quadratic(grads[q]))
                lo[q], hi[q] = mid[q] - half, mid[q] + half
            method = "delta method"
        lo["restitution"] = np.clip(lo["restitution"], 0.0, 1.0)
        hi["restitution"] = np.clip(hi["restitution"], 0.0, 1.0)
        kw = {}
        for q in _QUANTITIES:
            kw[q], kw[q + "_lo"], kw[q + "_hi"] = mid[q], lo[q], hi[q]
        return Prediction(velocity=V, confidence=self.confidence, method=method, **kw)

    def _end_us(self):
        name = self.free[0]
        lo, hi = self.conf_int[name]
        ref = self._model.refs[0]
        out = []
        for t in (lo, hi):
            if t > 0 and math.isfinite(t):
                out.append(np.array([math.log(t / ref)]))
            else:  # an open profile interval: no finite end on that side
                out.append(np.array([self._u[0] + (50.0 if t > 0 else -50.0)]))
        return out

    def band_ends(self) -> list[dict]:
        """The fitted model at the two ends of the parameter's confidence interval.

        What an export needs to write tables at the band's ends: for each end a dict
        with ``"end"`` (``"lower"``/``"upper"`` end of the parameter interval),
        ``"parameter"``, ``"value"`` (SI), ``"pair"`` (:class:`ContactPair`),
        ``"model"`` and ``"model_params"`` (dict). Defined for one free parameter.
        """
        if len(self.params) != 1:
            raise ValueError(f"band_ends needs exactly one free parameter, this fit has {len(self.params)}")
        name = self.free[0]
        out = []
        for end, u, value in zip(("lower", "upper"), self._end_us(), self.conf_int[name]):
            pair, params = self._model.split(u)
            out.append(
                {
                    "end": end,
                    "parameter": name,
                    "value": float(value),
                    "pair": pair,
                    "model": self.model,
                    "model_params": dict(zip(self._model.own, params)),
                }
            )
        return out

    def _gradients(self, f, keys, h=1e-6):
        """Central differences of ``f(u)[key]`` with respect to every component of ``u``."""
        u = np.asarray(self._u, dtype=float)
        cols = {k: [] for k in keys}
        for j in range(u.size):
            up, um = u.copy(), u.copy()
            up[j] += h
            um[j] -= h
            fp, fm = f(up), f(um)
            for k in keys:
                cols[k].append((np.asarray(fp[k]) - np.asarray(fm[k])) / (2 * h))
        return {k: np.stack(v, axis=-1) for k, v in cols.items()}

    def _forward(self, f, f0, h=1e-6):
        """Forward differences ``(f(u + h e_j) - f0) / h`` for every component of ``u`` (last axis)."""
        u = np.asarray(self._u, dtype=float)
        cols = []
        for j in range(u.size):
            up = u.copy()
            up[j] += h
            cols.append((np.asarray(f(up)) - np.asarray(f0)) / h)
        return np.stack(cols, axis=-1)

    def _quadratic(self, g):
        return np.maximum(np.einsum("...i,ij,...j->...", g, self.log_covariance, g), 0.0)

    def confidence_band(self, velocity, confidence=None):
        """Pointwise confidence band ``(lo, hi)`` of the fitted ``e(V)`` (delta method).

        ``var e(V) = g C g^T`` with ``g = de/du`` (central differences in *every*
        free log-parameter ``u_j``) and ``C`` the fit's :attr:`log_covariance`; the
        band is ``e +- q sqrt(var)``, clipped to ``[0, 1]``, with ``q`` the quantile
        used for the Wald interval (or the one for ``confidence``).

        Parameters
        ----------
        velocity : array_like
            Impact speeds [m/s].
        confidence : float, optional
            Level; default :attr:`confidence`.

        Returns
        -------
        (ndarray, ndarray)
            Lower and upper ends [-].
        """
        V = np.asarray(velocity, dtype=float)
        q = self.quantile if confidence is None else self._quantile(confidence)
        e = self._model.restitution(self._u, V)
        if len(self.params) == 0:
            return e.copy(), e.copy()
        g = self._gradients(lambda u: {"e": self._model.restitution(u, V)}, ("e",))["e"]
        half = q * np.sqrt(self._quadratic(g))
        return np.clip(e - half, 0.0, 1.0), np.clip(e + half, 0.0, 1.0)

    def _quantile(self, confidence):
        confidence = check_confidence(confidence)
        return t_quantile(confidence, self.dof, self.absolute_sigma and self.loss == "linear")

    def to_dict(self, *, lists: bool = True) -> dict:
        """Estimates, errors and fit statistics as plain Python values (SI units).

        ``lists=False`` leaves the residuals the numpy array they are (one value a data point):
        :func:`microimpact.io.write_json` writes it a block at a time, where a list holds a Python
        float (32 bytes) per point.
        """
        return {
            "model": self.model,
            "model_params": {k: float(v) for k, v in self.model_params.items()},
            "params": {k: float(v) for k, v in self.params.items()},
            "units": dict(self.units),
            "stderr": {k: float(v) for k, v in self.stderr.items()},
            "conf_int": {k: [float(a), float(b)] for k, (a, b) in self.conf_int.items()},
            "interval": self.interval,
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
            "n_far_above_one": self.n_far_above_one,
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
            "residuals": np.asarray(self.residuals).tolist() if lists else np.asarray(self.residuals),
        }

    def _display(self, name):
        """(scale, unit) shown to people for parameter ``name``."""
        if name in FREE_PARAMETERS:
            return FREE_PARAMETERS[name]["scale"], FREE_PARAMETERS[name]["unit"]
        return 1.0, self.units.get(name, "")

    def _rows(self):
        rows = []
        for name, value in self.params.items():
            scale, unit = self._display(name)
            lo, hi = self.conf_int[name]
            rows.append((name, value * scale, self.stderr[name] * scale, lo * scale, hi * scale, unit))
        if "yield_velocity" not in self.params:
            lo, hi = self.yield_velocity_conf_int
            unit = QUANTITIES["yield_velocity"].unit
            rows.append(("yield_velocity (derived)", self.yield_velocity, self.yield_velocity_stderr, lo, hi, unit))
        return rows

    def summary(self) -> str:
        """The estimates with standard errors and confidence intervals, in readable units."""
        pct = f"{100 * self.confidence:g} %"
        rows = [("parameter", "estimate", "std. error", f"{pct} confidence interval ({self.interval})")]
        for label, value, err, lo, hi, unit in self._rows():
            u = f" {unit}" if unit else ""
            rows.append((label, f"{value:.6g}{u}", f"{err:.3g}{u}", f"[{lo:.6g}, {hi:.6g}]{u}"))
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
            f"fit of e(V), model {self.model}: {self.n_points} points, {self.n_elastic} at or below V_y "
            f"(elastic), loss {self.loss}; {how}; {qname} quantile"
        )
        stats_line = (
            f"rss = {self.rss:.4g}   chi2 = {self.chi2:.4g}   dof = {self.dof}   "
            f"reduced chi2 = {self.reduced_chi2:.4g}   "
            f"rms residual = {math.sqrt(self.rss / self.n_points):.3g}"
        )
        tail = [] if self.success else [f"WARNING: the optimiser did not converge: {self.message}"]
        if self.n_far_above_one:
            tail.append(f"note: {self.n_far_above_one} point(s) lie more than {FAR_ABOVE_ONE:g} sigma above e = 1")
        return "\n".join([head, *table, stats_line, *tail])

    def __str__(self) -> str:
        return self.summary()

    def __repr__(self) -> str:
        pct = f"{100 * self.confidence:g}%"
        parts = []
        for label, value, _err, lo, hi, unit in self._rows():
            u = f" {unit}" if unit else ""
            parts.append(f"{label.split(' ')[0]}={value:.4g}{u} [{pct}: {lo:.4g}, {hi:.4g}]")
        rms = math.sqrt(self.rss / self.n_points)
        return (
            f"FitResult(model={self.model!r}, {', '.join(parts)}, n={self.n_points} ({self.n_elastic} elastic), "
            f"loss={self.loss!r}, interval={self.interval!r}, rms={rms:.3g})"
        )

    def _repr_html_(self) -> str:
        import html

        pct = f"{100 * self.confidence:g} %"
        head = (
            "<tr><th>parameter</th><th>estimate</th><th>std. error</th>"
            f"<th>{pct} interval ({html.escape(self.interval)})</th><th>unit</th></tr>"
        )
        body = "".join(
            f"<tr><td>{html.escape(label)}</td><td>{value:.6g}</td><td>{err:.3g}</td>"
            f"<td>[{lo:.6g}, {hi:.6g}]</td><td>{html.escape(unit)}</td></tr>"
            for label, value, err, lo, hi, unit in self._rows()
        )
        rms = math.sqrt(self.rss / self.n_points)
        caption = (
            f"fit of e(V), model {html.escape(self.model)}: {self.n_points} points "
            f"({self.n_elastic} elastic), loss {html.escape(self.loss)}, rms residual {rms:.3g}"
        )
        return f"<table><caption>{caption}</caption>{head}{body}</table>"


def check_confidence(confidence):
    c = real_number("confidence", confidence)
    if not 0.0 < c < 1.0:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence!r}")
    return c


def t_quantile(confidence, dof, known_scale):
    p = 0.5 + confidence / 2.0
    from scipy import special  # imported where used: the export command imports this module

    return float(special.ndtri(p) if known_scale else special.stdtrit(max(dof, 1), p))
