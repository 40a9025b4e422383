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
``restitution_of(model, pair, params, V)``: the seed by its array formula, every
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

from ..adhesion import ADDITIVE_RULE as _ADDITIVE_RULE
from . import _fit, _models, _result, _solver
from ._data import FitWarning
from ._fit import fit_restitution
from ._models import available_models
from ._ranking import ModelRanking, rank_models
from ._result import FitResult, Prediction

#: The seed's model (Thornton & Ning form, seed eqs. 22-28): the default ``model=``.
SEED_MODEL = _models.SEED_MODEL

#: Pair parameters that :func:`fit_restitution` can leave free, with the exponent ``c``
#: of ``V_y ~ theta^c`` (eq. 28: ``V_y ~ p_y^(5/2) E*^(-2) rho^(-1/2)``), the SI unit,
#: the unit shown to people and the scale from SI to that unit, the symbol and its TeX: all but the
#: exponent from :data:`microimpact.core.quantities.QUANTITIES`.
FREE_PARAMETERS = _models.FREE_PARAMETERS

#: The name under which :func:`fit_restitution` and :func:`rank_models` take Thornton & Ning's
#: additive rule (``e^2 = e_p^2 - (V_s/V)^2``; free parameters ``limiting_pressure`` and
#: ``work_of_adhesion`` like the whole law's), to rank it against the whole law on data with stuck
#: points (:data:`microimpact.adhesion.ADDITIVE_RULE`, where it is declared).
ADDITIVE_RULE = _ADDITIVE_RULE

#: Losses of :func:`scipy.optimize.least_squares` accepted by :func:`fit_restitution`.
LOSSES = _solver.LOSSES

#: Default ``f_scale`` of each loss in units of the noise's standard deviation: the value at which
#: the M-estimator has 95 % asymptotic efficiency for Gaussian noise, ``E[psi']^2 / E[psi^2] = 0.95``,
#: computed numerically for the losses of :func:`scipy.optimize.least_squares` (for Huber's loss it
#: reproduces the classical 1.345, for Cauchy's 2.385).
TUNING = _solver.TUNING

#: Interval methods of :func:`fit_restitution`.
INTERVALS = _fit.INTERVALS

#: ``interval="auto"`` uses the profile interval below this many points above ``V_y``.
PROFILE_BELOW = _fit.PROFILE_BELOW

#: A point is "far above 1" when ``e - 1`` exceeds this many standard uncertainties.
FAR_ABOVE_ONE = _result.FAR_ABOVE_ONE

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
    "available_models",
    "fit_restitution",
    "rank_models",
]

#: Plot functions that moved to :mod:`microimpact.figures.fit` (plots live in figures, above
#: fitting): still read here for one release, with a DeprecationWarning naming their home.
_MOVED_PLOTS = ("plot_fit", "plot_models", "plot_residuals")


#: The reader of restitution data that moved to :mod:`microimpact.io` (reading and writing live
#: there): still read here for one release, with a DeprecationWarning naming its home.
_MOVED_TO_IO = ("RestitutionData", "load_restitution_csv")


def __getattr__(name):
    if name in _MOVED_TO_IO:
        import warnings

        from .. import io as _io

        warnings.warn(
            f"microimpact.fitting.{name} is deprecated; use microimpact.io.{name}",
            DeprecationWarning,
            stacklevel=2,
        )
        return getattr(_io, name)
    if name in _MOVED_PLOTS:
        import warnings

        warnings.warn(
            f"microimpact.fitting.{name} is deprecated; use microimpact.figures.fit.{name}",
            DeprecationWarning,
            stacklevel=2,
        )
        # The one import from fitting up to figures, a deprecation shim (DEPRECATION_SHIMS of
        # tests/test_architecture.py): it goes with these aliases.
        from ..figures import fit as plots

        return getattr(plots, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
