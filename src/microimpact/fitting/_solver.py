"""The fit's numerics: the robust losses, the blockwise Levenberg-Marquardt solver, order statistics over
blocks and the profile objective (the method of :mod:`microimpact.fitting`).
"""

from __future__ import annotations

import math

import numpy as np

# Public as microimpact.fitting.LOSSES, documented there.
LOSSES = ("linear", "soft_l1", "huber", "cauchy", "arctan")

# Public as microimpact.fitting.TUNING, documented there.
TUNING = {"linear": 1.0, "soft_l1": 1.287, "huber": 1.345, "cauchy": 2.385, "arctan": 2.571}

#: The profile search looks this far from the estimate in ``ln theta`` (a factor e^8 ~ 3000).
_PROFILE_REACH = 8.0

#: Largest number of points the start's grid search looks at.
_START_POINTS = 2048

#: Above this many points the start's subset is chosen from every k-th point (a bounded sort).
_SORT_POINTS = 1 << 20

#: Points per block of the fit's passes over the data: its working memory is a few such blocks.
#: Below :data:`microimpact.engine.PARALLEL_MIN`: serial compiled loops (threads bought no
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


# ---------------------------------------------------------------------- losses
def loss_psi(loss, r, f_scale):
    """``psi(r) = dL/dr`` and ``psi'(r)`` of the loss ``L(r) = f^2/2 rho((r/f)^2)`` of least_squares."""
    # a residual past 1e154 squares to inf (and 0 * inf is NaN): Q, g and H are then not finite, which
    # minimise reports at the start and refuses as a step
    with np.errstate(over="ignore", invalid="ignore"):
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


def loss_terms(loss, r, f_scale):
    """``2 L(r_i) = f^2 rho((r_i/f)^2)`` per point (``r_i^2`` for least squares)."""
    with np.errstate(over="ignore"):  # as in loss_psi: an infinite Q
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
    return float(np.sum(loss_terms(loss, r, f_scale)))


def start_subset(V, n_max=_START_POINTS):
    """Indices of at most ``n_max`` points spread evenly over the sorted speeds.

    Above :data:`_SORT_POINTS` points the speeds are first thinned to every k-th point (which
    keeps the sort's memory bounded: the start needs a spread of speeds, not every point)."""
    if V.size <= n_max:
        return np.arange(V.size)
    if V.size > _SORT_POINTS:
        stride = -(-V.size // _SORT_POINTS)
        idx = np.arange(0, V.size, stride)
        return idx[start_subset(V[idx], n_max)]
    order = np.argsort(V, kind="stable")
    return order[np.linspace(0, V.size - 1, n_max).astype(np.intp)]


def blocks(n, size=None):
    """Slices of at most :data:`_BLOCK` points covering ``range(n)`` (the fit's passes over the data)."""
    size = _BLOCK if size is None else size
    return (slice(a, min(a + size, n)) for a in range(0, n, size))


class Passes:
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
        return math.fsum(_objective(self.loss, self.resid(u, s), self.f_scale) for s in blocks(self.V.size))

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
        for s in blocks(self.V.size):
            r, J = self.jacobian_block(u, s, cols, r=self._kept(u) if self.V.size <= _BLOCK else None)
            psi, dpsi = loss_psi(self.loss, r, self.f_scale)
            parts.append(_objective(self.loss, r, self.f_scale))
            g += np.einsum("am,m->a", J, psi)  # (numpy's own loops: BLAS threads buy nothing at k <= 3)
            H += np.einsum("am,bm->ab", J, J * np.maximum(dpsi, _DBL_EPS))
        return math.fsum(parts), g, H


def minimise(passes, u0, cols=None, max_nfev=None):
    """Levenberg-Marquardt on the normal equations of ``Q(u)`` over the components ``cols`` of ``u``.

    Each iteration is one pass over the data for ``(Q, g, H)`` (:meth:`Passes.normal_equations`,
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
    for s in blocks(n):
        x = values(s)
        if x.size:
            mn, mx = min(mn, float(x.min())), max(mx, float(x.max()))
    lo, hi = mn, mx
    while cnt > _GATHER and lo < hi and math.isfinite(hi - lo):
        scale = _BINS / (hi - lo)
        hist = np.zeros(_BINS, dtype=np.int64)
        for s in blocks(n):
            x = values(s)
            x = x[(x >= lo) & (x <= hi)]
            hist += np.bincount(np.minimum(((x - lo) * scale).astype(np.int64), _BINS - 1), minlength=_BINS)
        cum = np.cumsum(hist)
        b0, b1 = (int(np.searchsorted(cum, k - below, side="right")) for k in (ks[0], ks[-1]))
        below += int(cum[b0 - 1]) if b0 else 0
        cnt = int(cum[b1] - (cum[b0 - 1] if b0 else 0))
        nlo, nhi = math.inf, -math.inf
        for s in blocks(n):
            x = values(s)
            x = x[(x >= lo) & (x <= hi)]
            idx = np.minimum(((x - lo) * scale).astype(np.int64), _BINS - 1)
            x = x[(idx >= b0) & (idx <= b1)]
            if x.size:
                nlo, nhi = min(nlo, float(x.min())), max(nhi, float(x.max()))
        lo, hi = nlo, nhi
    if lo == hi:
        return [lo for _ in ks]
    kept = np.sort(np.concatenate([x[(x >= lo) & (x <= hi)] for x in (values(s) for s in blocks(n))]))
    return [float(kept[k - below]) for k in ks]


def _median(values, n):
    """``numpy.median`` of the ``n`` values ``values(s)`` gives block by block, in bounded memory."""
    ks = [n // 2] if n % 2 else [n // 2 - 1, n // 2]
    a = _order_statistics(values, n, ks)
    return a[0] if len(a) == 1 else (a[0] + a[1]) / 2.0


def mad_scale(r):
    """Robust scatter ``1.4826 median |r - median r|`` (consistent with the sd for Gaussian noise).

    Small arrays by :func:`numpy.median`; above :data:`_GATHER` points by :func:`_median` (exact,
    without a copy of ``r``)."""
    if not r.size:
        return 0.0
    if r.size <= _GATHER:
        return 1.4826 * float(np.median(np.abs(r - np.median(r))))
    med = _median(lambda s: r[s], r.size)
    return 1.4826 * float(_median(lambda s: np.abs(r[s] - med), r.size))


class ProfileObjective:
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
            u = minimise(self.passes, u, cols=[i for i in range(u.size) if i != j])[0]
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
