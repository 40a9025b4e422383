"""Models ranked on one data set: :func:`~microimpact.fitting.rank_models` and
:class:`~microimpact.fitting.ModelRanking`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from ..pair import ContactPair
from ._data import FitWarning, check_data
from ._fit import fit_data
from ._models import SEED_MODEL, parse_params
from ._solver import loss_terms


# ---------------------------------------------------------------------- ranking
def _parse_spec(spec):
    """``"name"``, ``"name:a+b"``, ``"name:none"``, ``(name, free)`` or a dict -> (label, name, free, model_params)."""
    if isinstance(spec, dict):
        name = spec.get("model", SEED_MODEL)
        free = parse_params(spec.get("params", ("limiting_pressure",)), allow_empty=True)
        label = spec.get("label") or f"{name}:{'+'.join(free) or 'none'}"
        return label, name, free, spec.get("model_params")
    if isinstance(spec, tuple) and len(spec) == 2:
        name, free = spec
        free = parse_params(free, allow_empty=True)
        return f"{name}:{'+'.join(free) or 'none'}", name, free, None
    if not isinstance(spec, str) or not spec.strip():
        raise ValueError(f"models: each model is a name, 'name:free1+free2' or 'name:none', got {spec!r}")
    text = spec.strip()
    name, _, rest = text.partition(":")
    name = name.strip()
    if rest.strip().lower() == "none":
        free = ()
    elif rest.strip():
        free = parse_params([r.strip() for r in rest.split("+")], allow_empty=False)
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
            d = fit.to_dict(lists=False)
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
    V, e, sg, line_numbers = check_data(velocity, restitution, sigma, line_numbers)
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
        fit = fit_data(
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
                    fk = fit_data(
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
            held[idx] = loss_terms(loss, r, fit.f_scale)
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
