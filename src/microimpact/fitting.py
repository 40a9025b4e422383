"""Fit a model's free parameter(s) to measured restitution data, and rank models on one data set.

The seed paper notes that the limiting contact pressure ``p_y`` is uncertain and
"may be modified by fitting the experimental data". :func:`fit_restitution` does
that: given measured impact speeds ``V_i`` and restitution coefficients ``e_i``
(optionally their standard uncertainties ``sigma_i``) and a known
:class:`~microimpact.pair.ContactPair`, it adjusts the free parameter(s) so that
the model's ``e(V)`` (for the seed: eq. 27, with ``V_y`` from eq. 28) matches the
data. :func:`rank_models` fits several models to the same data and ranks them.

Models
------
A model is named as in :mod:`microimpact.core.models` (``model="thornton_ning_2016"``,
the seed, is the default) and is evaluated through one function,
``_restitution_of(model, pair, params, V)``: the seed by its array formula, every
other model of the zoo by its scalar ``outcome`` (field ``"restitution"`` of
:data:`microimpact.core.quantities.OUTCOME_FIELDS`). Free parameters are one
parameter of the pair (:data:`FREE_PARAMETERS`) and/or the model's own
``PARAMETERS`` (positive, fitted in ``ln``); fixed model parameters come from the
model's ``DEFAULTS`` or ``model_params=``.

What restitution data can and cannot determine (seed model)
------------------------------------------------------------
The seed's restitution depends on the impact speed only through ``V / V_y``
(seed eqs. 22, 27) and ``V_y`` depends on the pair only through
``p_y^(5/2) E*^(-2) m*^(-1/2) R*^0`` (eq. 28 and its general energy form: ``R*``
cancels). Restitution data therefore determine ``V_y`` and *exactly one*
parameter of the pair given the others: scaling ``E*`` by ``lambda`` and ``p_y`` by
``lambda^(4/5)`` leaves every ``e(V)`` unchanged, whatever the speed range of
the data. Asking for two pair parameters raises a :class:`ValueError` that says so.
The pair parameter is one of

* ``"limiting_pressure"`` ``p_y`` [Pa] (default);
* ``"k"``: ``p_y = k Y`` with a known yield strength ``Y`` (``yield_strength=``
  or the smaller yield strength of the pair's materials);
* ``"effective_modulus"`` ``E*`` [Pa];
* ``"density"`` [kg/m^3] of the particle of a sphere-on-flat pair (changes ``m*``);
* ``"yield_velocity"`` ``V_y`` [m/s] itself (the pair's ``p_y`` is then adjusted).

Whatever the free parameter, the result also reports the derived ``V_y`` with
its confidence interval.

Measured values above 1 and stuck particles
-------------------------------------------
Near ``V_y`` the true ``e`` is 1, so measurement scatter gives values above 1.
Every finite ``e_i >= 0`` is accepted and fitted as measured (no clipping: clipping
or dropping such points biases ``p_y``). ``e_i = 0`` ("stuck") is accepted only by
a model that can stick (its declaration has ``STICKS = True``: the adhesive models); the seed never gives
``e = 0`` at a finite speed. A :class:`FitWarning` names the points that lie *far*
above 1: ``e_i - 1 > 3 s_i``, with ``s_i = sigma_i`` when absolute uncertainties
are given, else the robust residual scatter ``s = 1.4826 MAD`` of the residuals at
the solution. Such points are unlikely under the stated noise (one in 740 for
Gaussian noise) and usually mean a tracking or calibration error.

Method
------
* Objective: ``sum_i L(r_i)`` with the losses of :func:`scipy.optimize.least_squares`
  (``"linear"``, ``"soft_l1"``, ``"huber"``, ``"cauchy"``, ``"arctan"``; ``L(r) = f^2/2 rho((r/f)^2)``).
* Optimiser: Levenberg-Marquardt on the normal equations ``(H + lambda diag H) du = -g``, with
  ``g = sum psi(r_i) J_i`` and ``H = sum max(psi'(r_i), eps) J_i J_i^T`` (least_squares' own
  scaling of a robust loss), both accumulated over blocks of 32,768 points: a fit has at most a few
  free parameters, so its memory beyond the data is its residuals (a result attribute) and one
  block, not the ``n x p`` Jacobian and the other ``n``-sized arrays a general solver holds (a
  10^7-point fit: 0.5 GB for the whole ``microimpact fit`` instead of 1.7 GB). It reaches the same
  minimum as :func:`~scipy.optimize.least_squares` (``tests/test_fitting_blockwise.py``: to 1e-7
  for every loss, one and two parameters).
* Parametrisation: ``u = ln(theta / theta_ref)`` for every free parameter (keeps it
  positive and the problem well scaled).
* Start: a grid search of the least-absolute-deviation objective over ``V_y``
  on at most 2048 points spread evenly over the sorted speeds (memory does not grow
  with the grid), then the local refinement on all points. Memory grows linearly
  with the number of points, by the residuals the result keeps (8 bytes a point;
  10 bytes a point traced at 10^6 points, ``benchmarks/fit_memory.py``).
* Elastic points: the model gives ``e = 1`` at and below the fitted ``V_y``; such
  points stay in the fit with the residual ``e_i - 1`` and are counted in
  :attr:`FitResult.n_elastic`.
* Residuals ``r_i = (e_i - e(V_i)) / sigma_i`` (``sigma_i = 1`` if not given).
* Covariance of ``u`` from the Jacobian ``J = dr/du`` of the *raw* residuals at the
  solution (central differences, step 1e-6 in ``u``; ``J^T J`` accumulated block by block),
  not the Jacobian rescaled by the robust loss:

  - ``loss="linear"``: ``C = s^2 (J^T J)^-1``. Without ``sigma``, ``s^2`` is the
    residual variance ``sum r_i^2 / (n - p)``. With ``sigma`` the uncertainties are
    taken as absolute (``s^2 = 1``; ``absolute_sigma=False`` rescales by the
    reduced chi-square instead, treating ``sigma`` as relative weights).
  - robust losses: Huber's asymptotic covariance of a regression M-estimator,
    ``C = kappa^2 [sum psi_i^2 / (n - p)] / [mean psi'_i]^2 (J^T J)^-1`` with
    ``kappa^2 = 1 + (p/n) var(psi') / mean(psi')^2`` and ``psi`` the derivative of
    the loss (Huber, *Robust Statistics*, 1981, as given in the NAG Library
    documentation of ``g02hfc``). We use this analytic sandwich rather than a
    bootstrap because it costs one Jacobian (a bootstrap refits hundreds of times,
    prohibitive for 1e6 points) and because a bootstrap of 10-20 points
    under-covers; the coverage tests in ``tests/test_fitting.py`` check that it
    gives the stated coverage for every loss. It reduces to the linear case when
    ``psi(r) = r``.
* Confidence intervals (``interval=``):

  - ``"wald"``: ``u_hat +- q sqrt(C_jj)`` mapped back by ``exp`` (asymmetric in
    the parameter, always positive), with ``q`` the Student ``t`` quantile with
    ``n - p`` degrees of freedom when the scale is estimated from the residuals,
    and the normal quantile when ``sigma`` is absolute;
  - ``"profile"``: the set of ``u_j`` where the profile statistic
    ``D(u_j) = [Q(u_j) - Q_hat] / (s^2 mean psi')`` stays below ``q^2``, with ``Q``
    the summed loss (``sum r_i^2`` for least squares) minimised over the other
    parameters. For least squares this is the usual F (unknown scale) or
    chi-square (absolute sigma) likelihood-ratio interval; for a robust loss the
    same drop in the objective, scaled so that ``D`` equals the Wald statistic to
    second order. It follows the curvature of ``e(V)`` near the identifiability
    edge, where the delta method is poor;
  - ``"auto"`` (default): the profile interval when fewer than 10 points lie
    above the fitted ``V_y``, the Wald interval otherwise.

  Standard errors in parameter units are ``theta_hat sqrt(C_jj)`` (delta method).
* Uncertainty forward: :meth:`FitResult.predict` with ``band=True`` gives ``e(V)``,
  the rebound speed and the contact time at the ends of the parameter's interval
  (one free parameter: exact for a quantity monotone in it) or by the delta method
  over all free parameters; :meth:`FitResult.band_ends` gives the fitted model at
  the interval's ends for exports.

Ranking (:func:`rank_models`)
-----------------------------
Each model is fitted to the same data; the table gives ``AIC = -2 ln L + 2K``,
the small-sample ``AICc = AIC + 2K(K+1)/(n-K-1)`` and ``BIC = -2 ln L + K ln n``
with Gaussian ``-2 ln L = n ln(RSS/n)`` (``K`` counts the scale) or ``chi^2``
with absolute sigma (astropy's ``akaike_info_criterion_lsq`` documentation),
the Akaike weights ``w_i = exp(-Delta_i/2) / sum exp(-Delta_j/2)`` of the AICc
differences (Burnham & Anderson, *Model Selection and Multimodel Inference*,
2002), and a K-fold cross-validated error. When the second model lies within 2
units of AICc of the best (the rule of thumb of Burnham & Anderson 2002), the
ranking carries a caveat that the data cannot tell these models apart.

Measured accuracy (tests/test_fitting.py): noise-free data give ``p_y`` back to
better than 1e-6 relative; over seeded synthetic data sets with points near and
above 1 the 95 % intervals cover the true value at the stated rate for every loss.
"""

from __future__ import annotations

import csv
import io
import math
import os
import sys
import warnings
from dataclasses import dataclass, field

import numpy as np

from . import quantities
from ._optional import require
from ._validation import is_number_text
from .adhesion import ADDITIVE_RULE as _ADDITIVE_RULE
from .adhesion import FIT_RULES
from .core.models import DEFAULT as _DEFAULT_MODEL
from .impact import outcome_arrays, restitution_arrays
from .materials import DEFAULT_K, sphere_mass
from .pair import ContactPair

__all__ = [
    "ADDITIVE_RULE",
    "FAR_ABOVE_ONE",
    "FREE_PARAMETERS",
    "INTERVALS",
    "LOSSES",
    "PROFILE_BELOW",
    "SEED_MODEL",
    "TUNING",
    "FitResult",
    "FitWarning",
    "ModelRanking",
    "Prediction",
    "RestitutionData",
    "available_models",
    "fit_restitution",
    "load_restitution_csv",
    "plot_fit",
    "plot_models",
    "plot_residuals",
    "rank_models",
]

#: The seed's model (Thornton & Ning form, seed eqs. 22-28): the default ``model=``.
SEED_MODEL = _DEFAULT_MODEL

#: Pair parameters that :func:`fit_restitution` can leave free, with the exponent ``c``
#: of ``V_y ~ theta^c`` (eq. 28: ``V_y ~ p_y^(5/2) E*^(-2) rho^(-1/2)``), the SI unit,
#: the unit shown to people and the scale from SI to that unit, the symbol and its TeX: all but the
#: exponent from :data:`microimpact.core.quantities.QUANTITIES`.
FREE_PARAMETERS: dict[str, dict] = {
    name: {
        "exponent": exponent,
        "si": quantities.QUANTITIES[name].unit,
        "unit": "" if quantities.QUANTITIES[name].shown_unit == "1" else quantities.QUANTITIES[name].shown_unit,
        "scale": quantities.QUANTITIES[name].scale,
        "symbol": quantities.QUANTITIES[name].symbol,
        "tex": quantities.QUANTITIES[name].tex,
    }
    for name, exponent in (
        ("limiting_pressure", 2.5),
        ("k", 2.5),
        ("effective_modulus", -2.0),
        ("density", -0.5),
        ("yield_velocity", 1.0),
    )
}

#: Losses of :func:`scipy.optimize.least_squares` accepted by :func:`fit_restitution`.
LOSSES = ("linear", "soft_l1", "huber", "cauchy", "arctan")

#: Default ``f_scale`` of each loss in units of the noise's standard deviation: the value at which
#: the M-estimator has 95 % asymptotic efficiency for Gaussian noise, ``E[psi']^2 / E[psi^2] = 0.95``,
#: computed numerically for the losses of :func:`scipy.optimize.least_squares` (for Huber's loss it
#: reproduces the classical 1.345, for Cauchy's 2.385).
TUNING = {"linear": 1.0, "soft_l1": 1.287, "huber": 1.345, "cauchy": 2.385, "arctan": 2.571}

#: Interval methods of :func:`fit_restitution`.
INTERVALS = ("auto", "wald", "profile")

#: ``interval="auto"`` uses the profile interval below this many points above ``V_y``.
PROFILE_BELOW = 10

#: A point is "far above 1" when ``e - 1`` exceeds this many standard uncertainties.
FAR_ABOVE_ONE = 3.0

#: The profile search looks this far from the estimate in ``ln theta`` (a factor e^8 ~ 3000).
_PROFILE_REACH = 8.0

#: Largest number of points the start's grid search looks at.
_START_POINTS = 2048

#: Above this many points the start's subset is chosen from every k-th point (a bounded sort).
_SORT_POINTS = 1 << 20

#: About how many times a fit evaluates its model (start grid, steps, Jacobians, band): see
#: :func:`_compile_if_costly`.
_FIT_CALLS = 50

#: Points per block of the fit's passes over the data: its working memory is a few such blocks.
#: Below :data:`microimpact.core.arrays.PARALLEL_MIN`: serial compiled loops (threads bought no
#: time on two cores and their runtime cost 15 MB of a 10^7-point fit's peak).
_BLOCK = 1 << 15

#: Step in ``u = ln(theta/theta_ref)`` of the Jacobian's central differences.
_JAC_STEP = 1e-6

#: The fit stops when a Levenberg-Marquardt step in ``u`` is below ``_XTOL (1 + |u|)``.
_XTOL = 1e-10

#: ... or when the decrease of ``Q`` that the step predicts is below ``_FTOL Q``.
_FTOL = 1e-13

#: Largest step in ``u`` (a factor e^10 in a parameter).
_MAX_STEP = 10.0

_DBL_EPS = float(np.finfo(float).eps)

#: Bins of a round of :func:`_order_statistics`, and the number of values it sorts at the end.
_BINS = 4096
_GATHER = 1 << 18

# Column names accepted by load_restitution_csv (lower case, units stripped).
_VELOCITY_NAMES = ("velocity", "v", "speed", "impact_velocity", "impact_speed")
_RESTITUTION_NAMES = ("restitution", "e", "cor", "coefficient_of_restitution")
_SIGMA_NAMES = ("sigma", "e_err", "uncertainty", "e_sigma", "restitution_err", "restitution_sigma")
_VELOCITY_UNITS = ("m/s", "m s-1", "m s^-1", "m.s-1", "m*s^-1", "m s**-1")


class FitWarning(UserWarning):
    """Something in the data or the fit the user should look at (points far above 1, ...)."""


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
        non-numeric or non-finite cells, negative (or zero) speeds, negative
        restitution, non-positive uncertainties, no data rows. Measured values
        above 1 are kept (scatter near the yield velocity); ``e = 0`` is kept as
        "stuck" (:func:`fit_restitution` decides whether the model allows it).

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
    from array import array

    name = os.fspath(path)
    where = os.path.basename(name)
    # Streamed line by line into typed arrays (8 bytes a value, 4 a line number until a file passes
    # 2^31 lines): memory grows with the data by a small constant, not by Python objects per cell
    # (10^7 rows: 0.2 GB, not 3 GB).
    V, e, s, lines = array("d"), array("d"), array("d"), array("i")
    header = None
    with open(name, encoding="utf-8-sig") as fh:
        for lineno, line in enumerate(fh, start=1):
            text = line.split("#", 1)[0].strip()
            if not text:
                continue
            if header is None:
                header = (lineno, text)
                hline, htext = header
                delimiter = next((d for d in (",", ";", "\t") if d in htext), None)
                cells = _split(htext, delimiter)
                keys = [_column_key(c) for c in cells]
                iv = _find_column(keys, cells, where, hline, htext, _VELOCITY_NAMES, "velocity")
                ie = _find_column(keys, cells, where, hline, htext, _RESTITUTION_NAMES, "restitution")
                isg = _find_column(keys, cells, where, hline, htext, _SIGMA_NAMES, "sigma", required=False)
                unit = keys[iv][1].lower()
                if unit and unit not in _VELOCITY_UNITS:
                    raise ValueError(f"{where} line {hline}: velocity must be in m/s, the header says {cells[iv]!r}")
                continue
            row = text.split(delimiter) if delimiter and '"' not in text else _split(text, delimiter)
            if len(row) != len(cells):
                raise ValueError(
                    f"{where} line {lineno}: expected {len(cells)} cells like the header, found {len(row)}"
                )
            v = _cell_number(row[iv], where, lineno, "velocity")
            if v < 0:
                raise ValueError(f"{where} line {lineno}: negative impact speed {v:g} m/s")
            if v == 0:
                raise ValueError(f"{where} line {lineno}: impact speed must be positive, got 0")
            r = _cell_number(row[ie], where, lineno, "restitution")
            if r < 0.0:
                raise ValueError(f"{where} line {lineno}: restitution must be >= 0, got {r:g}")
            if isg is not None:
                sg = _cell_number(row[isg], where, lineno, "sigma")
                if sg <= 0:
                    raise ValueError(f"{where} line {lineno}: sigma must be positive, got {sg:g}")
                s.append(sg)
            V.append(v)
            e.append(r)
            try:
                lines.append(lineno)
            except OverflowError:  # past 2^31 - 1 lines: 8-byte line numbers from here on
                lines = array("q", lines)
                lines.append(lineno)
    if header is None:
        raise ValueError(f"{where}: no header line (expected columns velocity, restitution)")
    if not lines:
        raise ValueError(f"{where}: no data rows after the header on line {header[0]}")
    # numpy views of the arrays' buffers (no copy; each view keeps its array alive)
    sigma = np.frombuffer(s, dtype=float) if isg is not None else None
    return RestitutionData(
        np.frombuffer(V, dtype=float),
        np.frombuffer(e, dtype=float),
        sigma,
        np.frombuffer(lines, dtype=f"i{lines.itemsize}"),
        source=where,
    )


def _find_column(keys, cells, where, hline, htext, names, what, required=True):
    """The index of the header cell naming ``what`` (one of ``names``); errors name the file and line."""
    hits = [i for i, (k, _) in enumerate(keys) if k in names]
    if len(hits) > 1:
        raise ValueError(
            f"{where} line {hline}: more than one {what} column: " + ", ".join(repr(cells[i]) for i in hits)
        )
    if not hits:
        if required:
            raise ValueError(
                f"{where} line {hline}: missing column {what} (accepted names: {', '.join(names[:3])}); header is {htext!r}"
            )
        return None
    return hits[0]


def _cell_number(cell, where, lineno, what) -> float:
    """A finite decimal number from a data cell, or a ValueError naming the file, line and column."""
    cell = cell.strip()
    if cell == "":
        raise ValueError(f"{where} line {lineno}: empty {what} cell")
    if not is_number_text(cell):  # float() would also take 1_0 (as 10) and 0x1p3
        raise ValueError(f"{where} line {lineno}: {what} {cell!r} is not a number")
    x = float(cell)
    if not math.isfinite(x):
        raise ValueError(f"{where} line {lineno}: {what} {cell!r} is not a finite number")
    return x


# --------------------------------------------------------------------------- models
def _zoo():
    from .core import models  # imported here: keeps `import microimpact` fast

    return models


def _arrays():
    from .core import arrays  # imported here: keeps `import microimpact` fast

    return arrays


def available_models() -> list[str]:
    """Names accepted as ``model=``: the models of :func:`microimpact.models.available`, the seed first."""
    names = [n for n in _zoo().available() if n != SEED_MODEL]
    return [SEED_MODEL, *names]


_MODULES: dict = {}


#: The name under which :func:`fit_restitution` and :func:`rank_models` take Thornton & Ning's
#: additive rule (``e^2 = e_p^2 - (V_s/V)^2``; free parameters ``limiting_pressure`` and
#: ``work_of_adhesion`` like the whole law's), to rank it against the whole law on data with stuck
#: points (:data:`microimpact.adhesion.ADDITIVE_RULE`, where it is declared).
ADDITIVE_RULE = _ADDITIVE_RULE


def _rules() -> dict:
    """The rules for ``e`` taken beside the models (:data:`microimpact.adhesion.FIT_RULES`), by name."""
    return {rule.NAME: rule for rule in FIT_RULES}


def _model_module(name):
    """The :class:`~microimpact.core.models.Model` declaration of ``name`` (ValueError naming it if
    unknown); a rule's of :data:`microimpact.adhesion.FIT_RULES` for its name."""
    rule = _rules().get(name) if isinstance(name, str) else None
    if rule is not None:
        return rule
    if not isinstance(name, str):
        raise ValueError(f"model must be a model's name (one of {', '.join(available_models())}), got {name!r}")
    zoo = _zoo()
    key = (name, zoo.get)  # the registry's function in the key: a replaced registry is looked up anew
    if key not in _MODULES:
        if name not in available_models():
            raise ValueError(f"model must be one of {', '.join(available_models())}; got {name!r}")
        _MODULES[key] = zoo.get(name)
    return _MODULES[key]


def _fast_restitution(name):
    """The face's ``e(V, V_y)`` of a model whose ``e`` depends on the pair only through ``V_y`` (the
    seed's eq. 27), else None (:func:`microimpact.models.face`)."""
    if name in _rules():
        return None
    from .models import face

    return face(name).restitution_of_yield_velocity


def _model_sticks(name) -> bool:
    return _model_module(name).STICKS


def _outcome_of(model_name, pair, params, V, fields=("restitution", "rebound_velocity", "contact_time")):
    """Outcome ``fields`` of model ``model_name`` for ``pair`` and model ``params`` at speeds ``V`` [m/s].

    The model's scalar ``outcome(V, E, R, m, p_y, params)`` over the array
    (:func:`microimpact.impact.outcome_arrays`: compiled loops for a ``@jitable`` outcome); the
    restitution alone of a model whose face gives ``e(V, V_y)`` (the seed's eq. 27) from that, else
    by the model's ``restitution_only`` hook where it has one (:func:`microimpact.impact.restitution_arrays`).
    """
    V = np.asarray(V, dtype=float)
    rule = _rules().get(model_name)
    if rule is not None:  # e alone: a rule has no contact times
        e = rule.restitution_of_pair(pair, params, V)
        out = {"restitution": e, "rebound_velocity": e * V, "contact_time": np.full(V.shape, math.nan)}
        return {f: out[f] for f in fields}
    fast = _fast_restitution(model_name)
    if fields == ("restitution",) and fast is not None:
        return {"restitution": fast(V, pair.yield_velocity)}
    module = _model_module(model_name)
    E, R, m, p_y = (
        np.asarray(float(x))
        for x in (pair.effective_modulus, pair.effective_radius, pair.effective_mass, pair.limiting_pressure)
    )
    params = tuple(float(x) for x in params)
    if fields == ("restitution",):  # what fitting and ranking compare: e alone (the model's hook)
        if _group_hooks(module) is not None and np.all(V > 0):
            return {"restitution": _restitution_by_group(module, V, E, R, m, p_y, params)}
        _compile_if_costly(module, V.size, outcome=module.restitution_only is None)
        return {"restitution": np.asarray(restitution_arrays(module, V.ravel(), E, R, m, p_y, params)).reshape(V.shape)}
    _compile_if_costly(module, V.size, outcome=True)
    out = outcome_arrays(module, V.ravel(), E, R, m, p_y, params)
    return {f: np.asarray(out[f], dtype=float).reshape(V.shape) for f in fields}


def _group_hooks(module):
    """``(restitution_group, restitution_of_group)`` of a model whose ``e`` is one function of one
    dimensionless number (the model contract), else None."""
    if module.restitution_group is None or module.restitution_of_group is None:
        return None
    return module.restitution_group, module.restitution_of_group


def _restitution_by_group(module, V, E, R, m, p_y, params):
    """``e`` at speeds ``V > 0``, evaluated once per distinct group ``g`` of the model (bit for bit the
    outcome's field: the model computes its outcome's ``e`` from the same ``g``)."""
    group, of_group = _group_hooks(module)
    arrays = _arrays()
    g = arrays.evaluate(group, V.ravel(), E, R, m, p_y, params=params)[0]
    distinct, where = np.unique(g, return_inverse=True)
    _compile_if_costly(module, distinct.size, outcome=False)
    return arrays.evaluate(of_group, distinct, params=params)[0][where.ravel()].reshape(V.shape)


def _compile_if_costly(module, n, outcome):
    """Import numba (from then on the array layer runs compiled loops:
    :func:`microimpact.core.arrays.backend_for`; bit for bit the same numbers) where a fit's
    :data:`_FIT_CALLS` evaluations of ``n`` points in Python loops would exceed the array layer's
    budget for one call (:data:`microimpact.core.arrays.PYTHON_BUDGET`), at the nominal time per
    point of the model's declared cost class (:data:`microimpact.core.models.COST_CLASSES`: its
    ``OUTCOME_COST`` for the whole outcome, else its ``COST``). Deterministic: no timing decides. A
    model that integrates its equation of motion for ``e`` costs ~0.5-2 ms a point in Python,
    ~10-50 us compiled."""
    if "numba" in sys.modules or os.environ.get("MICROIMPACT_BACKEND"):
        return
    cost = _zoo().COST_CLASSES[module.OUTCOME_COST if outcome else module.COST]
    if cost * n * _FIT_CALLS > _arrays().PYTHON_BUDGET:
        import numba  # noqa: F401  (the array layer compiles its loops once numba is imported)


def _restitution_of(model_name, pair, params, V):
    """Restitution ``e(V)`` [-] of model ``model_name`` with ``pair`` and model ``params``: the one
    function through which fitting and ranking evaluate every model."""
    return _outcome_of(model_name, pair, params, V, fields=("restitution",))["restitution"]


# --------------------------------------------------------------------------- checks
def _where(i, line_numbers):
    return f"line {int(line_numbers[i])}" if line_numbers is not None else f"point {int(i)}"


def _check_data(velocity, restitution, sigma, line_numbers):
    for what, x in (("velocity", velocity), ("restitution", restitution), ("sigma", sigma)):
        if x is None:
            continue
        if isinstance(x, bool) or (isinstance(x, np.ndarray) and x.dtype == bool):
            raise ValueError(f"{what} must be numbers, got booleans")
        if np.iscomplexobj(x):
            raise ValueError(f"{what} must be real numbers, got complex values")
        if np.ma.isMaskedArray(x):
            raise ValueError(f"{what}: masked arrays are not accepted; drop the masked points first")
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
    bad = ~(np.isfinite(e) & (e >= 0))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"restitution must be finite and >= 0, got {float(e[i])!r} ({_where(i, line_numbers)})")
    if sigma is not None:
        s = np.broadcast_to(np.asarray(sigma, dtype=float), V.shape).copy()
        bad = ~(np.isfinite(s) & (s > 0))
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"sigma must be positive and finite, got {float(s[i])!r} ({_where(i, line_numbers)})")
        sigma = s
    return V, e, sigma, line_numbers


def _parse_params(params, allow_empty=False):
    if isinstance(params, str):
        params = [p.strip() for p in params.split(",") if p.strip()]
    params = tuple(params)
    if not params and not allow_empty:
        raise ValueError("params: give at least one free parameter")
    for p in params:
        if not isinstance(p, str):
            raise ValueError(f"params: names of parameters, got {p!r}")
    if len(set(params)) != len(params):
        raise ValueError(f"params: each parameter once, got {params!r}")
    pair_level = [p for p in params if p in FREE_PARAMETERS]
    if len(pair_level) > 1:
        raise ValueError(
            f"params {', '.join(pair_level)}: restitution data determine only one parameter of the pair. The "
            "model's e depends on V only through V/V_y, and V_y on p_y^(5/2) E*^(-2) m*^(-1/2) (seed eqs. 27-28), "
            "so these parameters are not separately identifiable whatever the speed range; "
            "fix all but one (e.g. params=('limiting_pressure',))"
        )
    return params


def _number(name, value):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    return float(value)


class _YieldOnly:
    """Stands for a pair where only ``yield_velocity`` [m/s] is read (the seed's e(V), eq. 27)."""

    __slots__ = ("yield_velocity",)

    def __init__(self, yield_velocity):
        self.yield_velocity = yield_velocity


class _Model:
    """Maps the free parameters ``u`` (logs) to a pair and model parameters, and those to ``e(V)``.

    At most one pair parameter (by ``pair.replace``) and any of the model's own
    ``PARAMETERS``; ``theta_j = ref_j exp(u_j)``.
    """

    def __init__(self, pair: ContactPair, names, *, model=SEED_MODEL, model_params=None, yield_strength=None):
        if not isinstance(pair, ContactPair):
            raise ValueError(f"pair must be a ContactPair, got {type(pair).__name__}")
        module = _model_module(model)
        self.model = model
        self.pair = pair
        spec = tuple(module.PARAMETERS)
        self.own = tuple(p[0] for p in spec)
        self.own_units = {p[0]: p[1] for p in spec}
        values = dict(zip(self.own, (float(d) for d in module.DEFAULTS)))
        for k, v in (model_params or {}).items():
            if k not in self.own:
                have = ", ".join(self.own) or "none"
                raise ValueError(f"model_params: model {model} has no parameter {k!r} (its parameters: {have})")
            values[k] = _number(f"model_params[{k!r}]", v)
        unknown = [n for n in names if n not in FREE_PARAMETERS and n not in self.own]
        if unknown:
            allowed = ", ".join([*FREE_PARAMETERS, *self.own])
            raise ValueError(f"params must be among {allowed} for model {model}, got {unknown[0]!r}")
        pair_names = [n for n in names if n in FREE_PARAMETERS]
        self.own_free = tuple(n for n in names if n in self.own)
        self.names = tuple(pair_names) + self.own_free
        for n in self.own:
            v = values[n]
            if n in self.own_free and not (math.isfinite(v) and v > 0):
                raise ValueError(
                    f"model parameter {n} is fitted in ln and needs a positive start value: "
                    f"give model_params={{{n!r}: ...}}, got {v!r}"
                )
            if not math.isfinite(v):
                raise ValueError(f"model {model} needs a value of its parameter {n}: give model_params={{{n!r}: ...}}")
        self.values = values
        self.name = pair_names[0] if pair_names else None
        self.yield_strength = None
        finite_py = math.isfinite(pair.limiting_pressure)
        self.ref = None
        if self.name is not None:
            self._init_pair_parameter(pair, self.name, yield_strength, finite_py)
        self.refs = np.array(([self.ref] if self.name else []) + [values[n] for n in self.own_free], dtype=float)

    def _init_pair_parameter(self, pair, name, yield_strength, finite_py):
        self.exponent = FREE_PARAMETERS[name]["exponent"]
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
            Y = _number("yield_strength", Y)
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
        # Every pair parameter enters V_y as a power law; a pair with p_y = inf has no
        # finite V_y, so the reference pair takes a nominal finite p_y there.
        self.ref_pair = self.pair_at(0.0) if not finite_py else pair
        self.ref_vy = self.ref_pair.yield_velocity

    def pair_at(self, u) -> ContactPair:
        """The pair with the free pair parameter at ``ref * exp(u)`` (via :meth:`ContactPair.vary`)."""
        theta = float(self.ref * math.exp(float(u)))
        if self.name == "k":
            return self.pair.vary(limiting_pressure=theta * self.yield_strength)
        if self.name == "yield_velocity":
            return self.base.vary(yield_velocity=theta)
        return self.pair.vary(**{self.name: theta})

    def split(self, u):
        """``(pair, params)`` at ``u``: the pair and the model's parameter tuple."""
        u = np.atleast_1d(np.asarray(u, dtype=float))
        i = 0
        pair = self.pair
        if self.name is not None:
            pair = self.pair_at(u[0])
            i = 1
        vals = dict(self.values)
        for j, n in enumerate(self.own_free):
            vals[n] = float(self.refs[i + j] * math.exp(float(u[i + j])))
        return pair, tuple(vals[n] for n in self.own)

    def theta(self, u):
        """Free parameters in their own units at ``u``."""
        return self.refs * np.exp(np.asarray(u, dtype=float))

    def restitution(self, u, V):
        """Model ``e(V)`` at ``u`` (via :func:`_restitution_of`).

        The seed's ``e(V)`` reads only ``pair.yield_velocity``, which is the power law
        ``V_y,ref exp(c u)`` of the free pair parameter (eq. 28); the optimiser's many
        evaluations get it from :class:`_YieldOnly` instead of building a
        :class:`ContactPair` each time (0.3 ms of validation per pair).
        """
        if self.name is not None and not self.own and _fast_restitution(self.model) is not None:
            u0 = float(np.atleast_1d(u)[0])
            return _restitution_of(self.model, _YieldOnly(self.ref_vy * math.exp(self.exponent * u0)), (), V)
        pair, params = self.split(u)
        return _restitution_of(self.model, pair, params, V)

    def outcome(self, u, V, fields=("restitution", "rebound_velocity", "contact_time")):
        pair, params = self.split(u)
        return _outcome_of(self.model, pair, params, V, fields)

    def u_of_yield_velocity(self, vy):
        """Inverse of the power law ``V_y = V_y,ref exp(c u)`` (start values)."""
        return np.log(np.asarray(vy) / self.ref_vy) / self.exponent

    def unit(self, name):
        return FREE_PARAMETERS[name]["si"] if name in FREE_PARAMETERS else self.own_units.get(name, "")


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


def _loss_terms(loss, r, f_scale):
    """``2 L(r_i) = f^2 rho((r_i/f)^2)`` per point (``r_i^2`` for least squares)."""
    z = (r / f_scale) ** 2
    if loss == "linear":
        rho = z
    elif loss == "soft_l1":
        rho = 2.0 * (np.sqrt(1.0 + z) - 1.0)
    elif loss == "huber":
        rho = np.where(z <= 1.0, z, 2.0 * np.sqrt(z) - 1.0)
    elif loss == "cauchy":
        rho = np.log1p(z)
    else:
        rho = np.arctan(z)
    return f_scale**2 * rho


def _objective(loss, r, f_scale):
    """``Q = sum 2 L(r_i)`` (``sum r_i^2`` for least squares)."""
    return float(np.sum(_loss_terms(loss, r, f_scale)))


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
        confidence = _check_confidence(confidence)
        return _quantile(confidence, self.dof, self.absolute_sigma and self.loss == "linear")

    def to_dict(self) -> dict:
        """Estimates, errors and fit statistics as plain Python values (SI units)."""
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
            "residuals": np.asarray(self.residuals).tolist(),
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
            rows.append(("yield_velocity (derived)", self.yield_velocity, self.yield_velocity_stderr, lo, hi, "m/s"))
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


def _check_confidence(confidence):
    c = _number("confidence", confidence)
    if not 0.0 < c < 1.0:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence!r}")
    return c


def _quantile(confidence, dof, known_scale):
    p = 0.5 + confidence / 2.0
    from scipy import special  # imported where used: the export command imports this module

    return float(special.ndtri(p) if known_scale else special.stdtrit(max(dof, 1), p))


# ---------------------------------------------------------------------- the fit
def fit_restitution(
    velocity,
    restitution,
    pair: ContactPair,
    *,
    sigma=None,
    params=("limiting_pressure",),
    model: str = SEED_MODEL,
    model_params=None,
    loss: str = "linear",
    f_scale=None,
    confidence: float = 0.95,
    interval: str = "auto",
    yield_strength=None,
    absolute_sigma=None,
    line_numbers=None,
    max_nfev=None,
) -> FitResult:
    """Fit free parameter(s) of a model to measured restitution coefficients.

    Parameters
    ----------
    velocity : array_like
        Measured impact speeds ``V_i`` [m/s], positive.
    restitution : array_like
        Measured restitution coefficients ``e_i`` [-], finite and >= 0; values above 1
        (scatter near ``V_y``) are fitted as measured; ``0`` ("stuck") only for a model
        that can stick.
    pair : ContactPair
        The known pair; its value of a free pair parameter is only a reference (the
        start comes from a grid search over the data).
    sigma : array_like or float, optional
        Standard uncertainty of each ``e_i`` [-]; absolute unless ``absolute_sigma=False``.
    params : sequence of str or str
        The free parameters: at most one pair parameter (``"limiting_pressure"``,
        default, ``"k"``, ``"effective_modulus"``, ``"density"`` or
        ``"yield_velocity"``; the seed's data determine ``V_y`` only) and any of the
        model's own parameters.
    model : str
        Name of the model (:func:`available_models`), or :data:`ADDITIVE_RULE` (Thornton & Ning's
        additive rule, ``e`` only: its predictions have no contact time); default the seed.
    model_params : dict, optional
        Values of the model's own parameters (start values of the free ones).
    loss : str
        ``"linear"`` (least squares) or a robust loss of
        :func:`scipy.optimize.least_squares`: ``"soft_l1"``, ``"huber"``,
        ``"cauchy"``, ``"arctan"``.
    f_scale : float, optional
        Residual size at which a robust loss starts to down-weight, in units of
        ``e`` (or of ``sigma`` when given). Default: the loss's :data:`TUNING`
        constant (95 % efficiency for Gaussian noise) times the noise scale: 1 with
        ``sigma``, else ``1.4826 * MAD`` of the residuals at the robust start.
    confidence : float
        Level of the confidence intervals, default 0.95.
    interval : str
        ``"auto"`` (default), ``"wald"`` or ``"profile"`` (module docstring).
    yield_strength : float, optional
        ``Y`` [Pa] for ``params=("k",)``; default: the smaller yield strength of the
        pair's materials.
    absolute_sigma : bool, optional
        Default True when ``sigma`` is given.
    line_numbers : array_like of int, optional
        Source line of each point, quoted in error messages and warnings.
    max_nfev : int, optional
        Largest number of evaluations of the objective at trial steps (those of the Jacobian's
        differences not counted, as :func:`scipy.optimize.least_squares` counts them); default
        100 per free parameter. A fit stopped by it warns (:class:`FitWarning`).

    Returns
    -------
    FitResult

    Raises
    ------
    ValueError
        Bad data (naming the point or line), unknown or non-identifiable parameter
        sets, or too few points above the yield velocity for the parameters asked.

    Warns
    -----
    FitWarning
        Points far above 1 (``e_i - 1 > 3 s_i``, module docstring), or an optimiser
        that did not converge.

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
    return _fit(
        velocity,
        restitution,
        pair,
        names=names,
        sigma=sigma,
        model=model,
        model_params=model_params,
        loss=loss,
        f_scale=f_scale,
        confidence=confidence,
        interval=interval,
        yield_strength=yield_strength,
        absolute_sigma=absolute_sigma,
        line_numbers=line_numbers,
        max_nfev=max_nfev,
    )


def _start_subset(V, n_max=_START_POINTS):
    """Indices of at most ``n_max`` points spread evenly over the sorted speeds.

    Above :data:`_SORT_POINTS` points the speeds are first thinned to every k-th point (which
    keeps the sort's memory bounded: the start needs a spread of speeds, not every point)."""
    if V.size <= n_max:
        return np.arange(V.size)
    if V.size > _SORT_POINTS:
        stride = -(-V.size // _SORT_POINTS)
        idx = np.arange(0, V.size, stride)
        return idx[_start_subset(V[idx], n_max)]
    order = np.argsort(V, kind="stable")
    return order[np.linspace(0, V.size - 1, n_max).astype(np.intp)]


def _blocks(n, size=None):
    """Slices of at most :data:`_BLOCK` points covering ``range(n)`` (the fit's passes over the data)."""
    size = _BLOCK if size is None else size
    return (slice(a, min(a + size, n)) for a in range(0, n, size))


class _Passes:
    """The fit's passes over the data, block by block: memory per pass is O(block), not O(n).

    ``r_i = (e(V_i; u) - e_i) w_i`` are the weighted residuals (model minus data, the sign of
    :func:`scipy.optimize.least_squares`), ``J = dr/du`` by central differences with step
    :data:`_JAC_STEP` in ``u``, and the loss is ``L(r) = f^2/2 rho((r/f)^2)``.
    """

    def __init__(self, mdl, V, e, w, loss, f_scale):
        self.mdl, self.V, self.e, self.w, self.loss, self.f_scale = mdl, V, e, w, loss, f_scale
        self.last = None  # (u, r) of the last objective() of data that fit in one block

    def resid(self, u, s=slice(None)):
        r = self.mdl.restitution(u, self.V[s]) - self.e[s]
        return r if self.w is None else r * self.w[s]

    def objective(self, u):
        """``Q(u) = sum_i 2 L(r_i)`` (``sum r_i^2`` for least squares)."""
        if self.V.size <= _BLOCK:  # kept: a step taken needs them again for its normal equations
            r = self.resid(u)
            self.last = (np.array(u, dtype=float), r)
            return _objective(self.loss, r, self.f_scale)
        return math.fsum(_objective(self.loss, self.resid(u, s), self.f_scale) for s in _blocks(self.V.size))

    def _kept(self, u):
        """The residuals at ``u`` if the last objective() computed them (one block), else None."""
        if self.last is not None and np.array_equal(self.last[0], u):
            return self.last[1]
        return None

    def jacobian_block(self, u, s, cols, r=None):
        """``(r, J)`` on the block ``s``: ``J[c] = dr/du_cols[c]`` (central differences; one row per
        parameter, so that products over the points run on contiguous rows)."""
        r = self.resid(u, s) if r is None else r
        J = np.empty((len(cols), r.size))
        for c, j in enumerate(cols):
            up, um = u.copy(), u.copy()
            up[j] += _JAC_STEP
            um[j] -= _JAC_STEP
            J[c] = self.resid(up, s)
            J[c] -= self.resid(um, s)
            J[c] /= 2 * _JAC_STEP
        return r, J

    def normal_equations(self, u, cols):
        """``(Q, g, H)`` at ``u`` over the parameters ``cols``: the objective, the gradient
        ``g = sum psi(r_i) J_i`` of ``Q/2`` and the Gauss-Newton matrix ``H = sum w_i J_i J_i^T`` with
        ``w_i = max(psi'(r_i), eps)`` (for least squares ``J^T J``): least_squares' scaling of a robust
        loss (``scale_for_robust_loss_function``), accumulated block by block."""
        k = len(cols)
        parts, g, H = [], np.zeros(k), np.zeros((k, k))
        for s in _blocks(self.V.size):
            r, J = self.jacobian_block(u, s, cols, r=self._kept(u) if self.V.size <= _BLOCK else None)
            psi, dpsi = _psi(self.loss, r, self.f_scale)
            parts.append(_objective(self.loss, r, self.f_scale))
            g += np.einsum("am,m->a", J, psi)  # (numpy's own loops: BLAS threads buy nothing at k <= 3)
            H += np.einsum("am,bm->ab", J, J * np.maximum(dpsi, _DBL_EPS))
        return math.fsum(parts), g, H


def _minimise(passes, u0, cols=None, max_nfev=None):
    """Levenberg-Marquardt on the normal equations of ``Q(u)`` over the components ``cols`` of ``u``.

    Each iteration is one pass over the data for ``(Q, g, H)`` (:meth:`_Passes.normal_equations`,
    ``k x k`` matrices for ``k`` free parameters) and one pass for ``Q`` at each trial step
    ``(H + lambda diag H) du = -g``: memory O(block), not O(n k) as a Jacobian held whole. A step
    is taken when ``Q`` does not grow; ``lambda`` shrinks tenfold after a taken step and grows tenfold
    after a refused one. Stops when a step is below ``xtol (1 + |u|)`` (``xtol`` =
    :data:`_XTOL`), taken, or after ``max_nfev`` trial evaluations (default ``100 k``).
    Returns ``(u, success, message, nfev)``; ``nfev`` counts the evaluations of ``Q`` (not those of
    the Jacobian's differences, as :func:`scipy.optimize.least_squares` counts).
    """
    u = np.array(u0, dtype=float)
    cols = list(range(u.size)) if cols is None else list(cols)
    if not cols:
        return u, True, "no free parameter", 0
    max_nfev = 100 * len(cols) if max_nfev is None else int(max_nfev)
    Q, g, H = passes.normal_equations(u, cols)
    nfev, lam = 1, 1e-6
    if not (math.isfinite(Q) and np.all(np.isfinite(g)) and np.all(np.isfinite(H))):
        return u, False, "the residuals or their Jacobian are not finite at the start", nfev
    while True:
        D = np.diag(np.maximum(np.diag(H), _DBL_EPS * max(float(np.max(np.diag(H))), _DBL_EPS)))
        try:
            step = np.linalg.solve(H + lam * D, -g)
        except np.linalg.LinAlgError:
            step = np.full(len(cols), np.nan)
        if not np.all(np.isfinite(step)):
            return u, False, "singular normal equations", nfev
        size = float(np.linalg.norm(step))
        if size <= _XTOL * (1.0 + float(np.linalg.norm(u[cols]))):
            u[cols] += step
            return u, True, "converged: the step fell below xtol", nfev
        # The decrease of Q the quadratic model predicts: below Q's own rounding (and a model's
        # quadrature noise) no trial can confirm it, so the step is taken as it is and the fit ends.
        predicted = -(2.0 * float(g @ step) + float(step @ H @ step))
        if lam <= 1e-3 and 0.0 <= predicted <= _FTOL * abs(Q):
            u[cols] += step
            return u, True, "converged: the predicted decrease fell below ftol", nfev
        if nfev >= max_nfev:
            return u, False, f"the maximum number of evaluations ({max_nfev}) was reached", nfev
        if size > _MAX_STEP:  # a factor e^_MAX_STEP in a parameter at most per step
            step *= _MAX_STEP / size
        trial = u.copy()
        trial[cols] += step
        try:
            Qt = passes.objective(trial)
        except (OverflowError, ZeroDivisionError, FloatingPointError):  # a parameter out of range
            Qt = math.inf
        nfev += 1
        if math.isfinite(Qt) and Qt <= Q:
            u = trial
            lam = max(lam / 10.0, 1e-12)
            Q, g, H = passes.normal_equations(u, cols)
            if not (np.all(np.isfinite(g)) and np.all(np.isfinite(H))):
                return u, False, "the Jacobian is not finite", nfev
        else:
            lam *= 10.0
            if lam > 1e20:
                return u, True, "converged: no step lowers the objective", nfev


def _order_statistics(values, n, ks):
    """The ``ks``-th smallest (0-based, sorted) of ``n`` values that ``values(s)`` gives block by block.

    Exact, in memory bounded by :data:`_BLOCK` (not O(n) as a sort or :func:`numpy.partition` of a
    copy): each round bins the values still in play into :data:`_BINS` equal bins between their
    smallest and largest (a monotone map, so a run of bins is an interval of values), keeps the bins
    that hold the wanted ranks and counts those below; once at most :data:`_GATHER` values remain in
    play they are gathered and sorted."""
    lo, hi, below = -math.inf, math.inf, 0
    cnt, mn, mx = n, math.inf, -math.inf
    for s in _blocks(n):
        x = values(s)
        if x.size:
            mn, mx = min(mn, float(x.min())), max(mx, float(x.max()))
    lo, hi = mn, mx
    while cnt > _GATHER and lo < hi and math.isfinite(hi - lo):
        scale = _BINS / (hi - lo)
        hist = np.zeros(_BINS, dtype=np.int64)
        for s in _blocks(n):
            x = values(s)
            x = x[(x >= lo) & (x <= hi)]
            hist += np.bincount(np.minimum(((x - lo) * scale).astype(np.int64), _BINS - 1), minlength=_BINS)
        cum = np.cumsum(hist)
        b0, b1 = (int(np.searchsorted(cum, k - below, side="right")) for k in (ks[0], ks[-1]))
        below += int(cum[b0 - 1]) if b0 else 0
        cnt = int(cum[b1] - (cum[b0 - 1] if b0 else 0))
        nlo, nhi = math.inf, -math.inf
        for s in _blocks(n):
            x = values(s)
            x = x[(x >= lo) & (x <= hi)]
            idx = np.minimum(((x - lo) * scale).astype(np.int64), _BINS - 1)
            x = x[(idx >= b0) & (idx <= b1)]
            if x.size:
                nlo, nhi = min(nlo, float(x.min())), max(nhi, float(x.max()))
        lo, hi = nlo, nhi
    if lo == hi:
        return [lo for _ in ks]
    kept = np.sort(np.concatenate([x[(x >= lo) & (x <= hi)] for x in (values(s) for s in _blocks(n))]))
    return [float(kept[k - below]) for k in ks]


def _median(values, n):
    """``numpy.median`` of the ``n`` values ``values(s)`` gives block by block, in bounded memory."""
    ks = [n // 2] if n % 2 else [n // 2 - 1, n // 2]
    a = _order_statistics(values, n, ks)
    return a[0] if len(a) == 1 else (a[0] + a[1]) / 2.0


def _mad_scale(r):
    """Robust scatter ``1.4826 median |r - median r|`` (consistent with the sd for Gaussian noise).

    Small arrays by :func:`numpy.median`; above :data:`_GATHER` points by :func:`_median` (exact,
    without a copy of ``r``)."""
    if not r.size:
        return 0.0
    if r.size <= _GATHER:
        return 1.4826 * float(np.median(np.abs(r - np.median(r))))
    med = _median(lambda s: r[s], r.size)
    return 1.4826 * float(_median(lambda s: np.abs(r[s] - med), r.size))


def _fit(
    velocity,
    restitution,
    pair,
    *,
    names,
    sigma=None,
    model=SEED_MODEL,
    model_params=None,
    loss="linear",
    f_scale=None,
    confidence=0.95,
    interval="auto",
    yield_strength=None,
    absolute_sigma=None,
    line_numbers=None,
    max_nfev=None,
    warn=True,
):
    if loss not in LOSSES:
        raise ValueError(f"loss must be one of {', '.join(LOSSES)}, got {loss!r}")
    if interval not in INTERVALS:
        raise ValueError(f"interval must be one of {', '.join(INTERVALS)}, got {interval!r}")
    confidence = _check_confidence(confidence)
    V, e, sigma, line_numbers = _check_data(velocity, restitution, sigma, line_numbers)
    mdl = _Model(pair, names, model=model, model_params=model_params, yield_strength=yield_strength)
    if not _model_sticks(model) and not np.all(e):
        i = int(np.flatnonzero(e == 0.0)[0])
        raise ValueError(
            f"restitution 0 (stuck) at {_where(i, line_numbers)}: model {model} never sticks "
            "(e > 0 at every finite speed); drop stuck points or choose a model with adhesion"
        )
    if absolute_sigma is None:
        absolute_sigma = sigma is not None
    absolute_sigma = bool(absolute_sigma) and sigma is not None
    w = None if sigma is None else 1.0 / sigma  # weights; None: all 1 (no array of ones)
    p = len(mdl.names)
    n = V.size
    if n <= p:
        raise ValueError(f"{n} point(s) for {p} free parameter(s): need at least {p + 1}")

    n_plastic = sum(int(np.count_nonzero(e[s] < 1.0)) for s in _blocks(n))
    if mdl.name is not None and n_plastic < p + 1:
        at = ", ".join(_where(i, line_numbers) for i in np.flatnonzero(e < 1.0)[:10]) or "none"
        raise ValueError(
            f"too few points above the yield velocity for {p} free parameter(s): "
            f"{n_plastic} point(s) with e < 1 ({at}); need at least {p + 1}"
        )

    # Robust start: least absolute deviations over a log grid of V_y, on a subset.
    u0 = np.zeros(p)
    sub = _start_subset(V)
    Vs, es = V[sub], e[sub]
    ws = 1.0 if w is None else w[sub]
    if mdl.name is not None:
        fast = _fast_restitution(model) if not mdl.own else None
        vy_grid = np.geomspace(Vs.min() * 1e-3, Vs.max() * 2.0, 600 if fast is not None else 60)
        if fast is not None:
            lad = np.concatenate(
                [
                    np.sum(np.abs((es - fast(Vs[None, :], blk[:, None])) * ws), axis=1)
                    for blk in np.array_split(vy_grid, 10)  # blocks of 60 x 2048: about 1 MB each
                ]
            )
        else:
            lad = []
            for vy in vy_grid:
                ug = u0.copy()
                ug[0] = float(mdl.u_of_yield_velocity(vy))
                lad.append(np.sum(np.abs((es - mdl.restitution(ug, Vs)) * ws)))
            lad = np.asarray(lad)
        u0[0] = float(mdl.u_of_yield_velocity(vy_grid[int(np.argmin(lad))]))

    if f_scale is None:
        f_scale = TUNING[loss]
        if loss != "linear" and sigma is None:
            f_scale *= max(_mad_scale((es - mdl.restitution(u0, Vs)) * ws), 1e-6)
    else:
        f_scale = _number("f_scale", f_scale)
        if not (math.isfinite(f_scale) and f_scale > 0):
            raise ValueError(f"f_scale must be positive and finite, got {f_scale!r}")

    passes = _Passes(mdl, V, e, w, loss, f_scale)
    u, success, message, nfev = _minimise(passes, u0, max_nfev=max_nfev)
    fitted, params_now = mdl.split(u)
    fitted = fitted.replace(label=(pair.label + " (fitted)").strip() if pair.label else "fitted")
    vy = fitted.yield_velocity
    n_above = sum(int(np.count_nonzero(V[s] > vy)) for s in _blocks(n))
    if mdl.name is not None and n_above < p + 1:
        at = ", ".join(_where(i, line_numbers) for i in np.flatnonzero(V > vy)[:10]) or "none"
        raise ValueError(
            f"too few points above the fitted yield velocity V_y = {vy:.4g} m/s for {p} free "
            f"parameter(s): {n_above} ({at}); need at least {p + 1}"
        )
    dof = n - p

    # One pass at the solution: the residuals kept (data minus model), their sums, and J^T J of the
    # raw residuals for the covariance (not least_squares' loss-scaled Jacobian).
    resid_raw = np.empty(n)
    JTJ = np.zeros((p, p))
    chi2_parts, rss_parts, psi2_parts, d1_parts, d2_parts = [], [], [], [], []
    cols = list(range(p))
    for s in _blocks(n):
        raw = resid_raw[s]
        np.subtract(e[s], mdl.restitution(u, V[s]), out=raw)
        r_w = raw if w is None else raw * w[s]  # weighted residuals, data minus model
        J = passes.jacobian_block(u, s, cols, r=r_w)[1]
        JTJ += np.einsum("am,bm->ab", J, J)
        chi2_parts.append(float(np.einsum("m,m->", r_w, r_w)))
        rss_parts.append(float(np.einsum("m,m->", raw, raw)))
        if loss != "linear":
            psi, dpsi = _psi(loss, r_w, f_scale)
            psi2_parts.append(float(np.einsum("m,m->", psi, psi)))
            d1_parts.append(float(np.sum(dpsi)))
            d2_parts.append(float(np.einsum("m,m->", dpsi, dpsi)))
    chi2, rss = math.fsum(chi2_parts), math.fsum(rss_parts)
    if p:
        if not np.all(np.isfinite(JTJ)) or np.linalg.matrix_rank(JTJ) < p:
            raise ValueError("the data do not constrain the free parameters (singular Jacobian at the solution)")
        JTJ_inv = np.linalg.inv(JTJ)
    else:
        JTJ_inv = np.zeros((0, 0))
    if loss == "linear":
        s2 = 1.0 if absolute_sigma else chi2 / max(dof, 1)
        m1 = 1.0
    else:
        m1 = math.fsum(d1_parts) / n
        if m1 <= 0:  # redescending loss with most points beyond f_scale
            raise ValueError(f"loss {loss!r} with f_scale = {f_scale:g} rejects most points; increase f_scale")
        var_d = max(math.fsum(d2_parts) / n - m1 * m1, 0.0)
        kappa2 = 1.0 + (p / n) * var_d / m1**2
        s2 = kappa2 * (math.fsum(psi2_parts) / max(dof, 1)) / m1**2
    cov_u = s2 * JTJ_inv
    known_scale = absolute_sigma and loss == "linear"
    q = _quantile(confidence, dof, known_scale)

    theta = mdl.theta(u)
    se_u = np.sqrt(np.diag(cov_u))
    params_ = {nm: float(t) for nm, t in zip(mdl.names, theta)}
    stderr = {nm: float(t * s) for nm, t, s in zip(mdl.names, theta, se_u)}
    wald_u = {nm: (float(uu - q * s), float(uu + q * s)) for nm, uu, s in zip(mdl.names, u, se_u)}
    method = interval
    if method == "auto":
        method = "profile" if (p and n_above < PROFILE_BELOW) else "wald"
    ci_u = dict(wald_u)
    if method == "profile" and p and s2 * m1 > 0:  # (a perfect fit has a zero-width interval: Wald's)
        objective = _Objective(passes, s2 * m1, u, q)
        ci_u = {nm: objective.interval(j, se_u[j]) for j, nm in enumerate(mdl.names)}

    def to_theta(ref, a, b):
        return (float(ref * math.exp(a)) if a > -700 else 0.0, float(ref * math.exp(b)) if b < 700 else math.inf)

    conf = {nm: to_theta(r, *ci_u[nm]) for nm, r in zip(mdl.names, mdl.refs)}
    wald = {nm: to_theta(r, *wald_u[nm]) for nm, r in zip(mdl.names, mdl.refs)}
    cov = cov_u * np.outer(theta, theta)
    if mdl.name is not None:
        c = mdl.exponent
        se_vy = abs(c) * float(se_u[0])
        a, b = ci_u[mdl.name]
        ends = sorted((c * (a - u[0]), c * (b - u[0])))
        vy_ci = (float(vy * math.exp(max(ends[0], -700))), float(vy * math.exp(min(ends[1], 700))))
    else:
        se_vy, vy_ci = 0.0, (float(vy), float(vy))

    # Points far above 1: more than FAR_ABOVE_ONE standard uncertainties.
    scale = None if absolute_sigma else (_mad_scale(resid_raw) or math.sqrt(rss / n))
    far = np.concatenate(
        [
            s.start + np.flatnonzero(e[s] - 1.0 > FAR_ABOVE_ONE * (sigma[s] if scale is None else scale))
            for s in _blocks(n)
        ]
    )
    if warn and far.size:
        what = "sigma" if absolute_sigma else f"the residual scatter 1.4826 MAD = {scale:.3g}"
        at = ", ".join(f"{_where(i, line_numbers)} (e = {e[i]:.4g})" for i in far[:5])
        more = f" and {far.size - 5} more" if far.size > 5 else ""
        warnings.warn(
            f"{far.size} point(s) lie more than {FAR_ABOVE_ONE:g} x {what} above e = 1: {at}{more}; "
            "check them (kept in the fit)",
            FitWarning,
            stacklevel=3,
        )
    if warn and not success:
        warnings.warn(f"the optimiser did not converge: {message}", FitWarning, stacklevel=3)
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
        chi2=chi2,
        rss=rss,
        dof=int(dof),
        n_points=int(n),
        n_elastic=int(n - n_above),
        pair=fitted,
        success=success,
        message=message,
        confidence=confidence,
        loss=loss,
        f_scale=float(f_scale),
        absolute_sigma=bool(absolute_sigma),
        quantile=q,
        velocity=V,
        restitution=e,
        sigma=sigma,
        nfev=nfev,
        model=model,
        model_params=dict(zip(mdl.own, params_now)),
        interval=method,
        wald_conf_int=wald,
        units={nm: mdl.unit(nm) for nm in mdl.names},
        n_far_above_one=int(far.size),
        _model=mdl,
        _u=u,
    )


class _Objective:
    """Profile statistic ``D(u_j) = [Q(u_j) - Q_hat] / s2_eff``, ``Q`` minimised over the other ``u``."""

    def __init__(self, passes, s2_eff, u_hat, q):
        self.passes, self.s2 = passes, s2_eff
        self.u_hat = np.asarray(u_hat, dtype=float)
        self.q2 = q * q
        self.q_hat = passes.objective(self.u_hat)

    def profile(self, j, t):
        u = self.u_hat.copy()
        u[j] = t
        if u.size > 1:
            u = _minimise(self.passes, u, cols=[i for i in range(u.size) if i != j])[0]
        q = self.passes.objective(u)
        return max(q - self.q_hat, 0.0) / self.s2

    def interval(self, j, se):
        """``(lo, hi)`` in ``u_j`` where ``D <= q^2``; ``-inf``/``inf`` where ``D`` never reaches it."""
        from scipy import optimize

        u0 = float(self.u_hat[j])
        step = max(math.sqrt(self.q2) * float(se), 1e-6)
        ends = []
        for sign in (-1.0, 1.0):
            inner, found = 0.0, None
            d = min(step, _PROFILE_REACH)
            while True:
                if self.profile(j, u0 + sign * d) > self.q2:
                    found = d
                    break
                inner = d
                if d >= _PROFILE_REACH:
                    break
                d = min(2.0 * d, _PROFILE_REACH)
            if found is None:
                ends.append(sign * math.inf)
                continue
            g = lambda x: self.profile(j, u0 + sign * x) - self.q2  # noqa: E731
            ends.append(sign * optimize.brentq(g, inner, found, xtol=1e-10, rtol=1e-10))
        return (u0 + ends[0], u0 + ends[1])


# ---------------------------------------------------------------------- ranking
def _parse_spec(spec):
    """``"name"``, ``"name:a+b"``, ``"name:none"``, ``(name, free)`` or a dict -> (label, name, free, model_params)."""
    if isinstance(spec, dict):
        name = spec.get("model", SEED_MODEL)
        free = _parse_params(spec.get("params", ("limiting_pressure",)), allow_empty=True)
        label = spec.get("label") or f"{name}:{'+'.join(free) or 'none'}"
        return label, name, free, spec.get("model_params")
    if isinstance(spec, tuple) and len(spec) == 2:
        name, free = spec
        free = _parse_params(free, allow_empty=True)
        return f"{name}:{'+'.join(free) or 'none'}", name, free, None
    if not isinstance(spec, str) or not spec.strip():
        raise ValueError(f"models: each model is a name, 'name:free1+free2' or 'name:none', got {spec!r}")
    text = spec.strip()
    name, _, rest = text.partition(":")
    name = name.strip()
    if rest.strip().lower() == "none":
        free = ()
    elif rest.strip():
        free = _parse_params([r.strip() for r in rest.split("+")], allow_empty=False)
    else:
        free = ("limiting_pressure",)
    return text, name, free, None


def _information(fit, n, absolute):
    """``(-2 ln L, K)`` of a least-squares fit: Gaussian with estimated scale, or chi^2 with absolute sigma."""
    p = len(fit.params)
    if absolute:
        return fit.chi2, p
    rss_w = max(fit.chi2, 1e-300)
    return n * math.log(rss_w / n), p + 1


@dataclass(frozen=True, eq=False)
class ModelRanking:
    """Models fitted to one data set, ranked by AICc (see :func:`rank_models`).

    Attributes
    ----------
    rows : list of dict
        One per model, best first: ``label``, ``model``, ``free``, ``k`` (counted
        parameters), ``rss``, ``aic``, ``aicc``, ``bic``, ``delta_aicc``, ``weight``
        (Akaike weight from AICc), ``cv_error`` (K-fold cross-validated RMS of the
        weighted residuals [-], or of ``sqrt(2 L)`` for a robust loss).
    fits : dict
        ``label -> FitResult`` on all points.
    caveat : str
        Empty, or why the data cannot tell the leading models apart.
    k_folds : int
        Folds of the cross-validation.
    """

    rows: list
    fits: dict
    caveat: str
    k_folds: int
    velocity: np.ndarray = field(repr=False)
    restitution: np.ndarray = field(repr=False)
    sigma: np.ndarray | None = field(repr=False)

    @property
    def best(self) -> str:
        """Label of the model with the lowest AICc."""
        return self.rows[0]["label"]

    def table(self) -> str:
        """The ranking as aligned text."""
        head = ("rank", "model", "k", "rss", "AIC", "AICc", "BIC", "dAICc", "weight", f"CV({self.k_folds}) error")
        out = [head]
        for i, r in enumerate(self.rows, start=1):
            out.append(
                (
                    str(i),
                    r["label"],
                    str(r["k"]),
                    f"{r['rss']:.4g}",
                    f"{r['aic']:.2f}",
                    f"{r['aicc']:.2f}",
                    f"{r['bic']:.2f}",
                    f"{r['delta_aicc']:.2f}",
                    f"{r['weight']:.3f}",
                    f"{r['cv_error']:.4g}",
                )
            )
        widths = [max(len(r[j]) for r in out) for j in range(len(head))]
        lines = ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in out]
        lines.insert(1, "  ".join("-" * w for w in widths))
        if self.caveat:
            lines.append("caveat: " + self.caveat)
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.table()

    def __repr__(self) -> str:
        models = ", ".join(f"{r['label']} (w={r['weight']:.2f})" for r in self.rows)
        return f"ModelRanking(best={self.best!r}, {models}{', caveat' if self.caveat else ''})"

    def _repr_html_(self) -> str:
        import html

        head = "".join(f"<th>{h}</th>" for h in ("rank", "model", "k", "AICc", "dAICc", "weight", "BIC", "CV error"))
        body = "".join(
            f"<tr><td>{i}</td><td>{html.escape(r['label'])}</td><td>{r['k']}</td><td>{r['aicc']:.2f}</td>"
            f"<td>{r['delta_aicc']:.2f}</td><td>{r['weight']:.3f}</td><td>{r['bic']:.2f}</td>"
            f"<td>{r['cv_error']:.4g}</td></tr>"
            for i, r in enumerate(self.rows, start=1)
        )
        cap = html.escape(self.caveat) if self.caveat else "ranked by AICc"
        return f"<table><caption>{cap}</caption><tr>{head}</tr>{body}</table>"

    def to_dict(self) -> dict:
        """Plain values: the rows, the caveat and each model's fit (SI units)."""
        rows = [{**r, "free": list(r["free"])} for r in self.rows]
        fits = {}
        for label, fit in self.fits.items():
            d = fit.to_dict()
            d.pop("residuals", None)
            fits[label] = d
        return {"ranking": rows, "caveat": self.caveat, "k_folds": self.k_folds, "fits": fits}


def rank_models(
    velocity,
    restitution,
    pair: ContactPair,
    models,
    *,
    sigma=None,
    loss: str = "linear",
    k_folds: int = 5,
    seed: int = 0,
    confidence: float = 0.95,
    yield_strength=None,
    absolute_sigma=None,
    line_numbers=None,
) -> ModelRanking:
    """Fit several models to the same data and rank them (AIC, AICc, BIC, Akaike weights, K-fold CV).

    Parameters
    ----------
    velocity, restitution : array_like
        Measured speeds [m/s] and restitution coefficients [-] (as :func:`fit_restitution`).
    pair : ContactPair
        The known pair.
    models : sequence
        Each a model name (free parameter ``limiting_pressure``; :data:`ADDITIVE_RULE`,
        ``"additive"``, is Thornton & Ning's additive rule, to rank against their whole law on
        data with stuck points), ``"name:a+b"`` (free
        parameters ``a`` and ``b``), ``"name:none"`` (nothing fitted: the pair and
        model parameters as given), ``(name, free)`` or a dict with keys ``model``,
        ``params``, ``model_params``, ``label``.
    sigma : array_like or float, optional
        Standard uncertainty of each ``e_i`` [-].
    loss : str
        Loss of every fit (:data:`LOSSES`). The information criteria use the Gaussian
        likelihood of the residuals; with a robust loss they are approximate.
    k_folds : int
        Folds of the cross-validation (at most the number of points), default 5.
    seed : int
        Seed of the random split into folds (the ranking is reproducible).
    confidence : float
        Level of each fit's intervals.
    yield_strength : float, optional
        ``Y`` [Pa] for models with ``k`` free.
    absolute_sigma : bool, optional
        As :func:`fit_restitution`; with absolute sigma ``-2 ln L = chi^2``.
    line_numbers : array_like of int, optional
        Source lines of the points, for messages.

    Returns
    -------
    ModelRanking
        Best first. ``caveat`` is set when the second model is within 2 units of
        AICc of the best (Burnham & Anderson 2002): the data cannot tell them apart.
    """
    specs = [_parse_spec(s) for s in (models.split(",") if isinstance(models, str) else models)]
    if not specs:
        raise ValueError("models: give at least one model")
    labels = [s[0] for s in specs]
    if len(set(labels)) != len(labels):
        raise ValueError(f"models: each model once, got {labels!r}")
    if isinstance(k_folds, bool) or not isinstance(k_folds, (int, np.integer)) or k_folds < 2:
        raise ValueError(f"k_folds must be an integer >= 2, got {k_folds!r}")
    V, e, sg, line_numbers = _check_data(velocity, restitution, sigma, line_numbers)
    n = V.size
    absolute = (sg is not None) if absolute_sigma is None else (bool(absolute_sigma) and sg is not None)
    common = {
        "loss": loss,
        "confidence": confidence,
        "yield_strength": yield_strength,
        "absolute_sigma": absolute_sigma,
    }
    folds = np.array_split(np.random.default_rng(seed).permutation(n), min(int(k_folds), n))
    rows, fits = [], {}
    for label, name, free, mparams in specs:
        fit = _fit(
            V, e, pair, names=free, sigma=sg, model=name, model_params=mparams, line_numbers=line_numbers, **common
        )
        fits[label] = fit
        m2lnl, k = _information(fit, n, absolute and loss == "linear")
        aic = m2lnl + 2 * k
        aicc = aic + (2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else math.inf)
        bic = m2lnl + k * math.log(n)
        # K-fold cross-validation: refit without each fold, score the held-out points.
        held = np.empty(n)
        for idx in folds:
            train = np.ones(n, dtype=bool)
            train[idx] = False
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", FitWarning)
                    fk = _fit(
                        V[train],
                        e[train],
                        pair,
                        names=free,
                        sigma=None if sg is None else sg[train],
                        model=name,
                        model_params=mparams,
                        interval="wald",
                        warn=False,
                        **{**common, "confidence": 0.95},
                    )
            except ValueError:
                held[idx] = np.nan
                continue
            r = (e[idx] - fk.predict(V[idx])) * (1.0 if sg is None else 1.0 / sg[idx])
            held[idx] = _loss_terms(loss, r, fit.f_scale)
        cv = math.sqrt(float(np.mean(held))) if np.all(np.isfinite(held)) else math.nan
        rows.append(
            {
                "label": label,
                "model": name,
                "free": tuple(free),
                "k": int(k),
                "n": int(n),
                "rss": fit.rss,
                "chi2": fit.chi2,
                "aic": aic,
                "aicc": aicc,
                "bic": bic,
                "cv_error": cv,
            }
        )
    best = min(r["aicc"] for r in rows)
    weights = [math.exp(-(r["aicc"] - best) / 2) for r in rows]
    total = sum(weights)
    for r, wgt in zip(rows, weights):
        r["delta_aicc"] = r["aicc"] - best
        r["weight"] = wgt / total
    rows.sort(key=lambda r: round(r["aicc"], 6))  # stable: ties (to 1e-6) keep the order given
    close = [r["label"] for r in rows[1:] if r["delta_aicc"] < 2.0]
    caveat = ""
    if close:
        caveat = (
            f"the data cannot tell {rows[0]['label']} from {', '.join(close)} apart "
            "(AICc within 2, Burnham & Anderson 2002); more points, less scatter or a wider speed range "
            "would be needed to prefer one"
        )
    return ModelRanking(rows=rows, fits=fits, caveat=caveat, k_folds=len(folds), velocity=V, restitution=e, sigma=sg)


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
    lab = "model fit" + (f", {_param_label(fit_result)}" if fit_result.params else "")
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
    ax.set_ylim(0.0, max(1.05, float(np.max(e)) + 0.03) if e.size else 1.05)
    ax.set_ylabel("coefficient of restitution $e$ [-]")
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
    ax.set_ylabel(r"$e - e_\mathrm{fit}$ [-]")
    ax.grid(True, alpha=0.3)
    return ax


def _param_label(fit, tex=True):
    """``p_y = 156 MPa`` style text of a fit's free parameters."""
    parts = []
    for name, value in fit.params.items():
        if name in FREE_PARAMETERS:
            info = FREE_PARAMETERS[name]
            sym, scale, unit = (info["tex"] if tex else info["symbol"]), info["scale"], info["unit"]
        else:
            sym, scale, unit = name, 1.0, fit.units.get(name, "")
        parts.append(f"{sym} = {value * scale:.4g}" + (f" {unit}" if unit else ""))
    return ", ".join(parts)


def plot_models(ranking, ax=None, *, residual_ax=None, data_kws=None):
    """Data, each ranked model's fitted ``e(V)`` and their residuals.

    Parameters
    ----------
    ranking : ModelRanking
        From :func:`rank_models`.
    ax : matplotlib Axes, optional
        Axes for data and curves; when None a new figure with two panels (curves
        above, residuals below, shared speed axis).
    residual_ax : matplotlib Axes, optional
        Where to draw residuals when ``ax`` is given (skipped if None).
    data_kws : dict, optional
        Passed to ``errorbar`` for the measured points.

    Returns
    -------
    (Axes, Axes or None)
        Curve axes (speed [m/s] against ``e`` [-]) and residual axes (``e - e_fit`` [-]).
    """
    plt = require("matplotlib.pyplot", "plotting")
    V, e, sigma = ranking.velocity, ranking.restitution, ranking.sigma
    if ax is None:
        _, (ax, residual_ax) = plt.subplots(
            2,
            1,
            sharex=True,
            figsize=(7.0, 6.2),
            gridspec_kw={"height_ratios": [3, 1.4]},
            layout="constrained",
        )
    many = V.size > 2000
    dk = {
        "fmt": "o",
        "color": "0.15",
        "markersize": 1.5 if many else 4.5,
        "capsize": 0 if many else 2,
        "elinewidth": 0.8,
        "markerfacecolor": "white",
        "label": f"measured ({V.size} points)",
        "zorder": 1,
    }
    if many:
        dk.update(alpha=0.3, rasterized=True)
    dk.update(data_kws or {})
    ax.errorbar(V, e, yerr=None if many else sigma, **dk)
    vmax = float(np.max(V)) * 1.08
    vys = [f.yield_velocity for f in ranking.fits.values()]
    grid = np.union1d(np.geomspace(max(1e-3 * vmax, 1e-9), vmax, 500), [v for v in vys if v < vmax])
    styles = ["-", "--", "-.", ":", (0, (5, 1, 1, 1)), (0, (3, 1, 1, 1, 1, 1))]
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    span = 0.0
    for i, row in enumerate(ranking.rows):
        fit = ranking.fits[row["label"]]
        style = {"color": colors[i % len(colors)], "linestyle": styles[i % len(styles)], "linewidth": 1.8}
        detail = _param_label(fit)
        lab = f"{row['label']}: " + (detail + ", " if detail else "")
        lab += rf"$\Delta$AICc = {row['delta_aicc']:.1f}, w = {row['weight']:.2f}"
        ax.plot(grid, fit.predict(grid), label=lab, zorder=3, **style)
        if residual_ax is not None:
            r = e - fit.predict(V)
            span = max(span, float(np.max(np.abs(r))) if r.size else 0.0)
            off = (i - (len(ranking.rows) - 1) / 2) * 0.006 * vmax
            residual_ax.plot(
                V + (0 if many else off),
                r,
                marker="os^dvx"[i % 6],
                linestyle="none",
                markersize=1.5 if many else 4,
                color=style["color"],
                alpha=0.4 if many else 0.9,
                rasterized=many,
            )
    ax.set_xlim(0.0, vmax)
    ax.set_ylim(0.0, max(1.08, float(np.max(e)) + 0.04))
    ax.axhline(1.0, color="0.6", linewidth=0.8, linestyle=":")
    ax.set_ylabel("coefficient of restitution $e$ [-]")
    title = f"ranked by AICc; best: {ranking.best}"
    if ranking.caveat:
        title += "\n(the data cannot tell the leading models apart: AICc within 2)"
    ax.set_title(title, fontsize="medium")
    ax.legend(loc="lower left", frameon=False, fontsize="small")
    ax.grid(True, alpha=0.3)
    if residual_ax is not None:
        residual_ax.axhline(0.0, color="0.3", linewidth=1.0)
        span = max(span * 1.15, 1e-3)
        residual_ax.set_ylim(-span, span)
        residual_ax.set_xlabel("impact velocity $V$ [m/s]")
        residual_ax.set_ylabel(r"$e - e_\mathrm{fit}$ [-]")
        residual_ax.grid(True, alpha=0.3)
        ax.tick_params(labelbottom=False)
    else:
        ax.set_xlabel("impact velocity $V$ [m/s]")
    return ax, residual_ax
