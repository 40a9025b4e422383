"""The fit itself: :func:`~microimpact.fitting.fit_restitution` (start, solve, covariance, intervals)."""

from __future__ import annotations

import math
import warnings

import numpy as np

from ..pair import ContactPair
from ._data import FitWarning, check_data, point_name
from ._models import SEED_MODEL, FitModel, fast_restitution, model_sticks, parse_params, real_number
from ._result import FAR_ABOVE_ONE, FitResult, check_confidence, t_quantile
from ._solver import LOSSES, TUNING, Passes, ProfileObjective, blocks, loss_psi, mad_scale, minimise, start_subset

# Public as microimpact.fitting.INTERVALS, documented there.
INTERVALS = ("auto", "wald", "profile")

# Public as microimpact.fitting.PROFILE_BELOW, documented there.
PROFILE_BELOW = 10


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
    names = parse_params(params)
    return fit_data(
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


def fit_data(
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
    confidence = check_confidence(confidence)
    V, e, sigma, line_numbers = check_data(velocity, restitution, sigma, line_numbers)
    mdl = FitModel(pair, names, model=model, model_params=model_params, yield_strength=yield_strength)
    if not model_sticks(model) and not np.all(e):
        i = int(np.flatnonzero(e == 0.0)[0])
        raise ValueError(
            f"restitution 0 (stuck) at {point_name(i, line_numbers)}: model {model} never sticks "
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

    n_plastic = sum(int(np.count_nonzero(e[s] < 1.0)) for s in blocks(n))
    if mdl.name is not None and n_plastic < p + 1:
        at = ", ".join(point_name(i, line_numbers) for i in np.flatnonzero(e < 1.0)[:10]) or "none"
        raise ValueError(
            f"too few points above the yield velocity for {p} free parameter(s): "
            f"{n_plastic} point(s) with e < 1 ({at}); need at least {p + 1}"
        )

    # Robust start: least absolute deviations over a log grid of V_y, on a subset.
    u0 = np.zeros(p)
    sub = start_subset(V)
    Vs, es = V[sub], e[sub]
    ws = 1.0 if w is None else w[sub]
    if mdl.name is not None:
        fast = fast_restitution(model) if not mdl.own else None
        vy_grid = np.geomspace(Vs.min() * 1e-3, Vs.max() * 2.0, 600 if fast is not None else 60)
        if fast is not None:
            lad = np.concatenate(
                [
                    np.sum(np.abs((es - fast(Vs[None, :], blk[:, None])) * ws), axis=1)
                    for blk in np.array_split(vy_grid, 10)  # blocks of 60 x 2048: about 1 MB each
                ]
            )
        else:
            us = np.tile(u0, (vy_grid.size, 1))
            us[:, 0] = [float(mdl.u_of_yield_velocity(vy)) for vy in vy_grid]
            rows = mdl.restitution_rows(us, Vs)  # one array call where only the pair's values change
            lad = np.asarray([np.sum(np.abs((es - row) * ws)) for row in rows])
        u0[0] = float(mdl.u_of_yield_velocity(vy_grid[int(np.argmin(lad))]))

    if f_scale is None:
        f_scale = TUNING[loss]
        if loss != "linear" and sigma is None:
            f_scale *= max(mad_scale((es - mdl.restitution(u0, Vs)) * ws), 1e-6)
    else:
        f_scale = real_number("f_scale", f_scale)
        if not (math.isfinite(f_scale) and f_scale > 0):
            raise ValueError(f"f_scale must be positive and finite, got {f_scale!r}")

    passes = Passes(mdl, V, e, w, loss, f_scale)
    u, success, message, nfev = minimise(passes, u0, max_nfev=max_nfev)
    fitted, params_now = mdl.split(u)
    fitted = fitted.replace(label=(pair.label + " (fitted)").strip() if pair.label else "fitted")
    vy = fitted.yield_velocity
    n_above = sum(int(np.count_nonzero(V[s] > vy)) for s in blocks(n))
    if mdl.name is not None and n_above < p + 1:
        at = ", ".join(point_name(i, line_numbers) for i in np.flatnonzero(V > vy)[:10]) or "none"
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
    for s in blocks(n):
        raw = resid_raw[s]
        np.subtract(e[s], mdl.restitution(u, V[s]), out=raw)
        r_w = raw if w is None else raw * w[s]  # weighted residuals, data minus model
        J = passes.jacobian_block(u, s, cols, r=r_w)[1]
        JTJ += np.einsum("am,bm->ab", J, J)
        chi2_parts.append(float(np.einsum("m,m->", r_w, r_w)))
        rss_parts.append(float(np.einsum("m,m->", raw, raw)))
        if loss != "linear":
            psi, dpsi = loss_psi(loss, r_w, f_scale)
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
    q = t_quantile(confidence, dof, known_scale)

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
        objective = ProfileObjective(passes, s2 * m1, u, q)
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
    scale = None if absolute_sigma else (mad_scale(resid_raw) or math.sqrt(rss / n))
    far = np.concatenate(
        [
            s.start + np.flatnonzero(e[s] - 1.0 > FAR_ABOVE_ONE * (sigma[s] if scale is None else scale))
            for s in blocks(n)
        ]
    )
    if warn and far.size:
        what = "sigma" if absolute_sigma else f"the residual scatter 1.4826 MAD = {scale:.3g}"
        at = ", ".join(f"{point_name(i, line_numbers)} (e = {e[i]:.4g})" for i in far[:5])
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
