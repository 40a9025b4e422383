"""Contact times of an elastic-plastic impact, in closed form (seed eqs. 20, 23, 26, 30-33).

The seed integrates the times numerically ("no simple expressions are
available"). They exist; the derivation is on the theory page, section
"Contact times in closed form" (:ref:`theory-times`):

* stage 1, Hertz loading to ``alpha_1 = min(alpha_y, alpha_m)``:
  ``t1 = (2/5)(alpha_m/V) B(u; 2/5, 1/2)``, ``u = (alpha_1/alpha_m)^(5/2) = min(1, (V_y/V)^2)``
* stage 2, plastic loading, a harmonic oscillation of angular frequency
  ``omega = (pi p_y R*/m*)^(1/2)`` about ``alpha_y/3``:
  ``t2 = (pi/2 - atan2(2 omega alpha_y / 3, (V^2 - V_y^2)^(1/2))) / omega``
* stage 3, Hertz unloading with ``R_p`` from ``alpha*`` to ``alpha_p``:
  ``t_U = (2/5) B(2/5, 1/2) (alpha* - alpha_p) / V_r``

``B(u; a, b)`` is the incomplete beta function (not regularised).

Time histories of one impact (:func:`impact_history`, :class:`ImpactHistory`)
follow from the same integrals by inverting the incomplete beta function
(stages 1 and 3) and as a sinusoid (stage 2). :func:`integrate_impact`
integrates Newton's equation with the force law of :mod:`microimpact.contact`
numerically: the seed's own route, kept as an independent check.

The seed's closed forms (the contact times, :func:`impact_history`) are its array face, written
once in :mod:`microimpact.models.thornton_ning_2016`; this module names them, beside what every
model's history shares: :class:`ImpactHistory`, the stage names and the integration of Newton's
equation with any model's force law (:func:`integrate_model`; :func:`integrate_impact` for the seed's),
one integrator and one stitching of its pieces. A history's time grid, stage codes and free flight
are shared with the seed's closed form (``microimpact._face``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from ._face import free_flight, scalar_pair, stage_of, time_grid
from .core import hertz, quantities
from .core import models as _models
from .core.models import thornton_ning_2016 as _seed
from .core.special import BETA_25_12, HERTZ_TIME_CONSTANT
from .models.thornton_ning_2016 import (
    contact_times,
    deresiewicz_contact_time,
    elastic_stage_time,
    hertz_contact_time,
    hertz_force_along,
    impact_history,
    incomplete_beta,
    ning_loading_time,
    plastic_frequency,
    plastic_stage_time,
    unloading_time,
)

__all__ = [
    "BETA_25_12",
    "HERTZ_TIME_CONSTANT",
    "incomplete_beta",
    "hertz_contact_time",
    "deresiewicz_contact_time",
    "ning_loading_time",
    "plastic_frequency",
    "elastic_stage_time",
    "plastic_stage_time",
    "unloading_time",
    "contact_times",
    "STAGE_NAMES",
    "GENERIC_STAGE_NAMES",
    "stage_names",
    "HISTORY_COLUMNS",
    "HISTORY_SCALARS",
    "impact_history",
    "hertz_force_along",
    "ImpactHistory",
    "integrate_impact",
    "integrate_model",
    "CLOSED_FORM_HISTORY",
]

#: Names of the models whose time history exists in closed form: those whose face declares
#: ``closed_form_history`` (:mod:`microimpact.models._base`; the seed's is :func:`impact_history`).
#: The others are integrated numerically (:func:`integrate_model`). Read from the declarations at each
#: access (the module's ``__getattr__``), so that a model added by ``register_path`` counts.
CLOSED_FORM_HISTORY: tuple


#: Stage codes of a history.
STAGE_NAMES = {0: "no contact (free flight before first contact or after separation)", **_seed.STAGES}
#: Stage codes of a history of any other model (loading to the maximum approach, then unloading).
GENERIC_STAGE_NAMES = {0: STAGE_NAMES[0], 1: "loading", 3: "unloading"}


def stage_names(model=None) -> dict:
    """``{stage code: name}`` of a history of ``model`` (a name; default the seed's): code 0, no
    contact, and the model's own ``STAGES`` (:mod:`microimpact.core.models`)."""
    from .core import models as _models

    return {0: STAGE_NAMES[0], **_models.get(_models.DEFAULT if model is None else model).STAGES}


def __getattr__(name):
    if name == "CLOSED_FORM_HISTORY":  # declared above; the faces are read on access
        from .models import closed_form_histories

        return closed_form_histories()
    if name == "SEED_STAGE_MODELS":  # deprecated: each model declares its STAGES
        import warnings

        from .core import models as _models

        warnings.warn(
            "microimpact.dynamics.SEED_STAGE_MODELS is deprecated; use microimpact.dynamics.stage_names(model) "
            "(each model declares its STAGES in microimpact.core.models)",
            DeprecationWarning,
            stacklevel=2,
        )
        return tuple(n for n in _models.available() if _models.get(n).STAGES == _seed.STAGES)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


#: Columns of a history: name -> (unit, description), from the one table of quantities.
HISTORY_COLUMNS: dict[str, tuple[str, str]] = quantities.table(quantities.HISTORY_FIELDS)

#: Scalars of a history: name -> (unit, description), from the one table of quantities.
HISTORY_SCALARS: dict[str, tuple[str, str]] = quantities.table(
    (
        "velocity",
        "rebound_velocity",
        "max_approach",
        "plastic_approach",
        "max_force",
        "elastic_stage_time",
        "plastic_stage_time",
        "loading_time",
        "unloading_time",
        "contact_time",
        "yield_velocity",
        "effective_modulus",
        "effective_radius",
        "effective_mass",
        "limiting_pressure",
    )
)


# ============================================================================ the history object


@dataclass(frozen=True, eq=False)
class ImpactHistory:
    """Time history of one impact: what :meth:`ContactPair.history` returns.

    Attributes
    ----------
    time : ndarray
        Time since first contact [s].
    approach : ndarray
        Approach ``alpha`` [m] (negative outside the contact: a gap).
    approach_velocity : ndarray
        ``dalpha/dt`` [m/s]: ``+V`` at first contact, 0 at the maximum approach,
        ``-V_r`` at separation.
    force : ndarray
        Contact force ``P`` [N].
    stage : ndarray of int
        0 no contact, 1 Hertz loading, 2 plastic loading, 3 elastic unloading.
    velocity, rebound_velocity : float
        Impact speed ``V`` and rebound speed ``V_r`` [m/s].
    max_approach, plastic_approach : float
        ``alpha*`` and ``alpha_p`` [m].
    max_force : float
        ``P*`` [N].
    elastic_stage_time, plastic_stage_time, loading_time, unloading_time, contact_time : float
        ``t1, t2, t_L, t_U, t_c`` [s].
    yield_velocity : float
        ``V_y`` [m/s].
    effective_modulus, effective_radius, effective_mass, limiting_pressure : float
        The pair [Pa, m, kg, Pa].
    method : str
        ``"closed"`` (closed form) or ``"ode"`` (numerical integration).
    model : str
        Name of the impact model (:func:`microimpact.models.available`); for a model other than
        the seed's, ``stage`` is 1 while loading and 3 while unloading, and
        ``elastic_stage_time``, ``plastic_stage_time``, ``yield_velocity`` are those of the
        model's outcome (NaN where it does not define them).
    """

    time: np.ndarray
    approach: np.ndarray
    approach_velocity: np.ndarray
    force: np.ndarray
    stage: np.ndarray
    velocity: float
    rebound_velocity: float
    max_approach: float
    plastic_approach: float
    max_force: float
    elastic_stage_time: float
    plastic_stage_time: float
    loading_time: float
    unloading_time: float
    contact_time: float
    yield_velocity: float
    effective_modulus: float
    effective_radius: float
    effective_mass: float
    limiting_pressure: float
    method: str = "closed"
    model: str = _models.DEFAULT

    def __post_init__(self):
        for name in HISTORY_COLUMNS:
            arr = np.array(getattr(self, name), dtype=np.int8 if name == "stage" else float)
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        for name in HISTORY_SCALARS:
            object.__setattr__(self, name, float(getattr(self, name)))

    @classmethod
    def from_dict(cls, data: dict, method: str = "closed") -> ImpactHistory:
        """Build from the dict of :func:`impact_history` or :func:`integrate_impact` (extra keys ignored)."""
        keys = [f.name for f in fields(cls) if f.name not in ("method", "model")]
        return cls(
            **{k: data[k] for k in keys}, method=data.get("method", method), model=data.get("model", _models.DEFAULT)
        )

    def __len__(self):
        return int(self.time.size)

    def to_dict(self) -> dict:
        """All arrays and scalars as a dict."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def hertz_force(self):
        """Hertz force along the loading stages, the seed's Fig. 7 comparison [N]: :func:`hertz_force_along`."""
        return hertz_force_along(self)

    def to_csv(self, path_or_buffer, *, progress=False) -> None:
        """Write the history as CSV: a header row with units, ``#`` lines with the scalars, then the rows.

        ``path_or_buffer`` is a file name (written through a temporary file renamed into
        place when complete, :func:`microimpact.io.write_csv`) or an open text file. The
        first line names the columns with their units (``time [s],approach [m],...``);
        the ``#`` lines that follow give the impact's scalars (``# name = value unit``);
        floats are written in their shortest exact form. Read it back with
        ``numpy.genfromtxt(f, delimiter=",", names=True)``, ``numpy.loadtxt(f,
        delimiter=",", skiprows=1)`` or ``pandas.read_csv(f, comment="#")``.
        ``progress=True`` shows a progress bar while the rows are written.
        """
        from .io import write_csv

        comments = [
            f"microimpact impact history ({self.method}; model {self.model}; each quantity as this model "
            "defines it, nan where it defines none; equation numbers are the seed's)"
        ]
        for name, (unit, desc) in HISTORY_SCALARS.items():
            comments.append(f"{name} = {getattr(self, name):.17g} {unit}  ({desc})")
        stages = stage_names(self.model)
        comments.append("stage: " + "; ".join(f"{k} = {v}" for k, v in stages.items()))
        columns = [(name, unit, getattr(self, name)) for name, (unit, _) in HISTORY_COLUMNS.items()]
        stage = columns[-1]
        columns[-1] = (stage[0], stage[1], np.asarray(stage[2]).astype(np.int64))
        write_csv(path_or_buffer, columns, comments, progress=progress)


# ============================================================================ Newton's equation, numerically
# m* d2alpha/dt2 = -P(alpha, dalpha/dt, alpha_max), alpha(0) = 0, dalpha/dt(0) = V, with P a model's
# force (microimpact.core.models), integrated by scipy's solve_ivp phase by phase, each phase ended
# by a terminal event: loading, until the maximum approach (dalpha/dt = 0), split into stage 1 and
# stage 2 where the model declares stage_two_approach (the seed: its yield approach, eq. 5);
# unloading with alpha_max frozen, until the approach falls to the model's separation_approach_after
# / separation_approach (0 by default) or, when ends_at_zero_force(params), until its signed_force
# vanishes, conditioned by the model's ZERO_FORCE_ORDER so that the solver's root finder sees a
# simple zero. _integrate is the one integrator behind integrate_impact (the seed's model) and
# integrate_model (any model).

#: The parameters of the integrators' docstrings (:func:`microimpact.dynamics.integrate_impact`,
#: :func:`microimpact.dynamics.integrate_model`), each written once, numpydoc, unindented; a
#: docstring names them with a line ``{key}`` (:func:`_shared_parameters`).
_PARAMETER_DOCS = {
    "model": """model : str
    Name of the model (:func:`microimpact.models.available`).""",
    "pair": """velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure : float
    ``V`` [m/s] (positive, finite), ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], ``p_y`` [Pa].""",
    "params": """params : dict or tuple, optional
    The model's parameters by name (defaults filled in) or as its tuple.""",
    "tolerances": """rtol, atol : float
    Tolerances of the solver (``atol`` on the scaled variables). 1e-17, not 1e-14: with 1e-14 the
    scaled state near the first contact, where the seed's force grows as ``alpha^(3/2)``, is
    controlled too loosely (its rebound speed 1e-10 off the closed form instead of 1e-11), and a
    force that jumps at a small approach, as the fitted laws do at their regime limits, is crossed
    at the wrong place (at ``E*/Y = 2500`` Kogut-Etsion's maximum approach was 1.3e-7 off with
    1e-14, 5e-12 with 1e-17); the seed's cost is unchanged.""",
    "method": """method : str
    A :func:`~scipy.integrate.solve_ivp` method; ``"DOP853"`` (default) or ``"Radau"``.""",
    "grid": """n, times : optional
    If either is given, also return the history on that grid, as
    :func:`~microimpact.dynamics.impact_history`.""",
}


def _shared_parameters(fn):
    """Decorator: each line ``{key}`` of ``fn``'s docstring (``key`` of :data:`_PARAMETER_DOCS`)
    becomes that parameter's text, indented as the line was."""
    lines = []
    for line in fn.__doc__.split("\n"):
        key = line.strip()
        if key.startswith("{") and key.endswith("}") and key[1:-1] in _PARAMETER_DOCS:
            indent = line[: len(line) - len(line.lstrip())]
            lines.extend(indent + part if part else part for part in _PARAMETER_DOCS[key[1:-1]].split("\n"))
        else:
            lines.append(line)
    fn.__doc__ = "\n".join(lines)
    return fn


def _model_and_params(model, params):
    """The model's :class:`~microimpact.core.models.Model` and its parameter tuple, from a name (or
    module) and a dict (keyword values, defaults filled in) or a tuple."""
    mod = _models.get(model) if isinstance(model, str) else _models.get(getattr(model, "NAME", model))
    if params is None:
        params = {}
    if isinstance(params, dict):
        return mod, _models.resolve_params(mod, params)
    return mod, tuple(mod.validate(tuple(params)))


# ----------------------------------------------------------------------------- the phases
def _event(fun, direction):
    fun.terminal = True
    fun.direction = direction
    return fun


#: Most right-hand-side evaluations one phase of an impact may take (loading, the second loading
#: stage, unloading). The phases of every model's impacts take 250-2000 (DOP853 at rtol 1e-12); a
#: phase that needs fifty times that follows a force law the solver cannot step through in bounded
#: time (Jackson-Green + Brake at S_y = 1 Pa crawls off the surface at e = 2e-5 and was not done
#: after ten minutes), and is refused rather than left running.
MAX_RHS_EVALUATIONS = 1_000_000
#: The precise run's bound on a phase relative to the loose run's evaluations of the same phase
#: (``PRECISE_FACTOR n + PRECISE_EXTRA``): DOP853's steps grow as ``tol^(-1/8)``, 4.2 times from rtol
#: 1e-7 to 1e-12, so twenty times (and 5000 more) is far beyond what a phase the loose run followed can need; it stops a
#: force law the precise run crawls through (Jackson-Green + Brake at S_y = 1 Pa: 44 evaluations of the
#: loose unloading, more than 4000 of 15 ms each without getting 1e-6 of the way in the precise one).
PRECISE_FACTOR = 20
PRECISE_EXTRA = 5_000


class _Budget:
    """``rhs`` counting its evaluations, raising the bound's ValueError past ``limit``."""

    def __init__(self, rhs, limit):
        self.rhs = rhs
        self.limit = limit
        self.count = 0

    def __call__(self, t, y):
        self.count += 1
        if self.count > self.limit:
            raise ValueError(
                f"the ODE integration reached its bound of {self.limit} right-hand-side evaluations in one "
                f"phase of the impact (at t/T = {t:.6g}) before the phase ended: the force law cannot be "
                "integrated here in bounded time (use method='closed', or other parameters)"
            )
        return self.rhs(t, y)


class _SpanBoundError(ValueError):
    """The phase's terminal event did not occur within the tries' doubled spans. A ValueError for the
    user (the integration cannot answer there); the unloading phase catches it by this class, where it
    means that the particle does not separate within ~500 loading times: it sticks."""


def _integrate_phase(rhs, t0, y0, span, events, method, rtol, atol, tries=60, limit=MAX_RHS_EVALUATIONS):
    """Integrate until a terminal event; extend the span if none occurred. At most ``limit``
    evaluations of ``rhs`` over all the tries (ValueError beyond).

    Returns ``(pieces, event index, t, y, nfev)``: the dense solutions ``(t_start, t_end, sol)``.
    """
    from scipy.integrate import solve_ivp  # imported here: the ODE is only the cross-check

    pieces = []
    nfev = 0
    rhs = _Budget(rhs, limit)
    for _ in range(tries):
        sol = solve_ivp(rhs, (t0, t0 + span), y0, method=method, rtol=rtol, atol=atol, events=events, dense_output=True)
        if not sol.success:  # pragma: no cover - solver failure
            raise RuntimeError(f"integration failed: {sol.message}")
        pieces.append((sol.t[0], sol.t[-1], sol.sol))
        nfev += sol.nfev
        if sol.status == 1:
            for i, te in enumerate(sol.t_events):
                if te.size:
                    return pieces, i, float(te[0]), np.array(sol.y_events[i][0], dtype=float), nfev
        t0, y0, span = sol.t[-1], sol.y[:, -1], 2.0 * span
    raise _SpanBoundError(
        f"the ODE integration reached its bound of {tries} extensions of the time span (to t/T = {t0:.6g}) "
        "before the phase of the impact ended (use method='closed', or other parameters)"
    )


def _zero_force_event(mod, params, force_at_state):
    """The event ``P = 0`` on unloading, conditioned as ``sign(P)|P|^(1/n)`` with ``n`` the model's
    ``ZERO_FORCE_ORDER``: a force vanishing as ``d^n`` (Hertz: ``n = 3/2``) becomes linear in the
    distance ``d`` to its zero, so that the solver's root finder (brentq) converges; a force flat
    at its root made it fail (Kogut-Etsion at E*/Y = 2500), and a simple zero (a dashpot, a linear
    spring) is left as it is."""
    inverse = 1.0 / float(mod.ZERO_FORCE_ORDER)
    if inverse == 1.0:
        return _event(lambda t, y: force_at_state(y), -1)

    def zero_force(t, y):
        p = force_at_state(y)
        return math.copysign(abs(p) ** inverse, p)

    return _event(zero_force, -1)


def _run(mod, V, E, R, m, p_y, params, T, rtol, atol, method, counts=None, limits=None):
    """Integrate in ``tau = t/T``, ``x = alpha/(V T)``, ``u = alpha'/V``: loading (stages 1 and 2)
    to the maximum approach, then unloading (stage 3) to the end of the contact.

    Returns ``(pieces, t1, t_L, x_star, t_c, x_end, u_end, nfev)`` (scaled; the pieces are
    ``(tau_start, tau_end, sol, stage)``); ``t_c`` is None where the particle has not left after
    many loading times (it sticks). ``counts`` (a dict), if given, receives the evaluations of each
    stage's phase; ``limits`` bounds them (by stage; default :data:`MAX_RHS_EVALUATIONS`).
    """
    counts = {} if counts is None else counts
    limits = {} if limits is None else limits
    X = V * T
    c = T / (m * V)  # u' = -P c
    f = mod.force

    def rhs1(t, y):
        a = y[0] * X if y[0] > 0.0 else 0.0  # loading starts at zero approach
        return [y[1], -f(a, y[1] * V, a, E, R, m, p_y, params) * c]

    events = [_event(lambda t, y: y[1], -1)]
    x2 = math.inf
    if mod.stage_two_approach is not None:
        x2 = mod.stage_two_approach(E, R, m, p_y, params) / X
        if x2 < math.inf:
            events.append(_event(lambda t, y: y[0] - x2, 1))
    lim = limits.get(1, MAX_RHS_EVALUATIONS)
    pc, which, t_ev, y, nfev = _integrate_phase(rhs1, 0.0, [0.0, 1.0], 2.0, events, method, rtol, atol, limit=lim)
    counts[1] = nfev
    pieces = [(a, b, s, 1) for a, b, s in pc]
    t1 = t_ev
    if which == 1:  # stage 2 from the event's own state, exactly on the boundary
        y[0] = x2
        lim = limits.get(2, MAX_RHS_EVALUATIONS)
        pc, _, t_ev, y, nf = _integrate_phase(rhs1, t1, y, 2.0, events[:1], method, rtol, atol, limit=lim)
        counts[2] = nf
        pieces += [(a, b, s, 2) for a, b, s in pc]
        nfev += nf
    tL = t_ev
    x_star = float(y[0])
    amax = x_star * X

    def rhs2(t, y):
        return [y[1], -f(y[0] * X, y[1] * V, amax, E, R, m, p_y, params) * c]

    if mod.separation_approach_after is not None:  # where the contact breaks depends on alpha_max
        sep = mod.separation_approach_after(amax, E, R, m, p_y, params) / X
    elif mod.separation_approach is not None:
        sep = mod.separation_approach(E, R, m, p_y, params) / X
    else:
        sep = 0.0
    events = [_event(lambda t, y: y[0] - sep, -1)]
    if mod.ends_at_zero_force is not None and mod.ends_at_zero_force(params):
        g = mod.signed_force
        events.append(_zero_force_event(mod, params, lambda y: g(y[0] * X, y[1] * V, amax, E, R, m, p_y, params)))
    try:
        lim = limits.get(3, MAX_RHS_EVALUATIONS)
        pc, which, tc, y, nf = _integrate_phase(rhs2, tL, [x_star, 0.0], 2.0 * tL, events, method, rtol, atol, 8, lim)
        counts[3] = nf
    except _SpanBoundError:  # no separation within ~500 loading times: the particle sticks
        return pieces, t1, tL, x_star, None, None, 0.0, nfev
    if which == 0:
        y[0] = sep  # the event's own state, exactly on the boundary
    else:
        # A force clipped at zero (or vanishing with zero slope) does not change sign, so the
        # solver's root finder may stop anywhere where it is already zero: bisect, within the last
        # step, for the first time the force is no longer positive.
        sol = pc[-1][2]
        steps = np.asarray(getattr(sol, "ts", [pc[-1][0]]), dtype=float)
        before = steps[steps < tc]
        lo, hi = (float(before[-1]) if before.size else pc[-1][0]), tc

        def positive(t):
            x, u = sol(t)
            return events[1](t, (x, u)) > 0.0

        if positive(lo):
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if not lo < mid < hi:
                    break
                lo, hi = (mid, hi) if positive(mid) else (lo, mid)
            tc, y = hi, sol(hi)
    pieces += [(a, b, s, 3) for a, b, s in pc]
    return pieces, t1, tL, x_star, tc, float(y[0]), float(y[1]), nfev + nf


def _sample_pieces(pieces, tau, stage, X, V, out, force_of):
    """Fill ``out = (approach, approach_velocity, force)`` at the scaled times ``tau`` from the dense
    solutions ``pieces`` (``(tau_start, tau_end, sol, stage)``, the phases of :func:`_run`).

    ``X`` and ``V`` turn the scaled state back into metres and m/s; ``force_of(k, alpha,
    alpha_dot)`` gives the force at the selected states of stage ``k``. The last piece of a stage
    also takes the times just past its end (rounding at the boundary). The one stitching loop.
    """
    approach, vel, force = out
    for k in (1, 2, 3):
        idx = np.flatnonzero(stage == k)
        ends = [p[1] for p in pieces if p[3] == k]
        last_b = max(ends) if ends else None
        for a, b, sol, st in pieces:
            if st != k or idx.size == 0:
                continue
            sel = idx[(tau[idx] >= a) & ((tau[idx] <= b) | (b == last_b))]
            if sel.size:
                y = sol(np.clip(tau[sel], a, b))
                approach[sel] = X * y[0]
                vel[sel] = V * y[1]
                force[sel] = force_of(k, approach[sel], vel[sel])
            idx = np.setdiff1d(idx, sel)


# ----------------------------------------------------------------------------- the integrator
def _stuck_error(mod, V):
    """The ValueError of a particle that does not leave the surface (no finite history)."""
    return ValueError(
        f"with model {mod.NAME!r} the particle does not leave the surface at velocity {V:g} m/s "
        "(e = 0, contact_time = inf): there is no finite history"
    )


def _leaves(mod, params, V, E, R, m, p_y, *, rtol=1e-12, atol=1e-14, method="DOP853"):
    """True where Newton's equation with the force law of ``mod`` separates (the particle leaves the
    surface), False where it does not after many loading times (it sticks): the integration's own
    verdict, whatever the model's closed form says."""
    T0 = float(hertz.time_scale(V, E, R, m))
    rough = _run(mod, V, E, R, m, p_y, params, T0, 1e-7, 1e-9, method)
    if rough[4] is None:
        return False
    return _run(mod, V, E, R, m, p_y, params, T0 * rough[2], rtol, atol, method)[4] is not None


def _integrate(mod, params, V, E, R, m, p_y, *, rtol, atol, method, n=None, times=None):
    """One impact of model ``mod`` (a :class:`~microimpact.core.models.Model`, ``params`` its
    checked tuple) at the checked floats ``V, E*, R*, m*, p_y``, by Newton's equation.

    A loose run in Hertz's time scale, then the precise one scaled by its loading time, so that
    the tolerances act on numbers of order one. Returns the dict of
    :func:`microimpact.dynamics.integrate_model` (with ``n`` or ``times``, the history too):
    ``elastic_stage_time`` and ``plastic_stage_time`` are the integration's own where the model
    declares ``stage_two_approach``, else its outcome's; ``yield_velocity`` is the outcome's.
    """
    if n is not None or times is not None:  # check the grid before integrating
        time_grid(1001 if n is None else n, times, (), 1.0)
    closed = dict(zip(quantities.OUTCOME_FIELDS, mod.outcome(V, E, R, m, p_y, params)))
    if closed["contact_time"] == np.inf:  # the model's own solution says it sticks
        raise _stuck_error(mod, V)
    if math.isnan(closed["restitution"]):  # the law itself has no impact here: nothing to integrate
        raise ValueError(
            f"model {mod.NAME!r} gives no outcome at velocity {V:g} m/s (outside what its law can say: "
            "see its outside_validity): there is no history"
        )
    T0 = float(hertz.time_scale(V, E, R, m))
    counts = {}
    rough = _run(mod, V, E, R, m, p_y, params, T0, 1e-7, 1e-9, method, counts)
    if rough[4] is None:
        raise _stuck_error(mod, V)
    T = T0 * rough[2]
    limits = {k: min(MAX_RHS_EVALUATIONS, PRECISE_FACTOR * n + PRECISE_EXTRA) for k, n in counts.items()}
    pieces, t1, tL, x_star, tc, x_end, u_end, nfev = _run(
        mod, V, E, R, m, p_y, params, T, rtol, atol, method, None, limits
    )
    if tc is None:  # pragma: no cover - the loose run would have seen it
        raise _stuck_error(mod, V)
    X = V * T
    amax = x_star * X
    f = mod.force

    def force_at(tau):
        for a, b, sol, st in pieces:
            if a <= tau <= b:
                x, u = sol(tau)
                if st < 3:
                    al = max(x, 0.0) * X
                    return f(al, u * V, al, E, R, m, p_y, params)
                return f(x * X, u * V, amax, E, R, m, p_y, params)
        return 0.0

    # the largest force: on a grid, refined around its best point
    from scipy.optimize import minimize_scalar

    grid = np.concatenate([np.linspace(0.0, tL, 257), np.linspace(tL, tc, 257)[1:]])
    vals = np.array([force_at(t) for t in grid])
    i = int(np.argmax(vals))
    P_star = float(vals[i])
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    if hi > lo:
        r = minimize_scalar(lambda t: -force_at(t), bounds=(lo, hi), method="bounded", options={"xatol": 1e-12})
        P_star = max(P_star, -float(r.fun))
    V_r = -V * u_end
    a_end = x_end * X
    staged = mod.stage_two_approach is not None
    out = {
        "velocity": V,
        "rebound_velocity": V_r,
        "max_approach": amax,
        "plastic_approach": a_end,
        "max_force": P_star,
        "elastic_stage_time": T * t1 if staged else closed["elastic_stage_time"],
        "plastic_stage_time": T * (tL - t1) if staged else closed["plastic_stage_time"],
        "loading_time": T * tL,
        "unloading_time": T * (tc - tL),
        "contact_time": T * tc,
        "yield_velocity": closed["yield_velocity"],
        "effective_modulus": E,
        "effective_radius": R,
        "effective_mass": m,
        "limiting_pressure": p_y,
        "model": mod.NAME,
        "method": "ode",
        "nfev": nfev,
    }
    if n is None and times is None:
        return out
    t = time_grid(1001 if n is None else n, times, (T * t1, T * tL), T * tc)
    stage = stage_of(t, T * t1, T * tL, T * tc)
    approach, vel = free_flight(t, V, T * tc, a_end, V_r)
    force = np.zeros_like(t)

    def force_of(k, alpha, alpha_dot):
        if k < 3:
            return [f(max(a, 0.0), ad, max(a, 0.0), E, R, m, p_y, params) for a, ad in zip(alpha, alpha_dot)]
        return [f(a, ad, amax, E, R, m, p_y, params) for a, ad in zip(alpha, alpha_dot)]

    _sample_pieces(pieces, t / T, stage, X, V, (approach, vel, force), force_of)
    out.update(time=t, approach=approach, approach_velocity=vel, force=force, stage=stage)
    return out


@_shared_parameters
def integrate_impact(
    velocity,
    effective_modulus,
    effective_radius,
    effective_mass,
    limiting_pressure,
    *,
    rtol=1e-12,
    atol=1e-17,
    method="DOP853",
    n=None,
    times=None,
):
    """One impact by integrating Newton's equation ``m* d2alpha/dt2 = -P`` numerically (seed eqs. 16-26).

    The independent check of the closed forms (:func:`contact_times`,
    :func:`impact_history`), following the seed's own route: :func:`integrate_model` applied to
    the seed's model (the one integrator, :mod:`microimpact.core.models.thornton_ning_2016`). The
    force is its history-dependent law: Hertz (eq. 2) up to the yield approach, plastic loading
    (eq. 8) up to the maximum approach, then elastic unloading (eq. 10) with ``R_p`` (eq. 9) and
    ``alpha_p`` (eq. 11) fixed by the maximum approach the integration reached.
    :func:`scipy.integrate.solve_ivp` locates, with terminal events, the yield (``alpha =
    alpha_y``, the model's ``stage_two_approach``), the maximum approach (``dalpha/dt = 0``) and
    the separation (``alpha = alpha_p``, its ``separation_approach_after``).

    The equation is integrated in scaled variables (time in units of the loading time of a first,
    loose run, length in units of ``V`` times that), so that the tolerances act on numbers of
    order one.

    Parameters
    ----------
    {pair}
    {tolerances}
    {method}
    {grid}

    Returns
    -------
    dict
        The scalars of :data:`HISTORY_SCALARS` (``elastic_stage_time``,
        ``plastic_stage_time``, ``loading_time``, ``unloading_time``, ``contact_time``
        [s], ``max_approach``, ``plastic_approach`` [m], ``max_force`` [N],
        ``rebound_velocity`` [m/s], ...), ``nfev`` (right-hand-side evaluations of the
        precise run), ``method`` = ``"ode"``, and with ``n`` or ``times`` the arrays ``time``,
        ``approach``, ``approach_velocity``, ``force``, ``stage``.
    """
    V, E, R, m, p_y = scalar_pair(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure)
    out = _integrate(
        _models.get(_models.DEFAULT), (), V, E, R, m, p_y, rtol=rtol, atol=atol, method=method, n=n, times=times
    )
    del out["model"]  # the seed's: this function's result has always been the seed's alone
    return out


@_shared_parameters
def integrate_model(
    model,
    velocity,
    effective_modulus,
    effective_radius,
    effective_mass,
    limiting_pressure,
    params=None,
    *,
    rtol=1e-12,
    atol=1e-17,
    method="DOP853",
    n=None,
    times=None,
):
    """One impact of any model by integrating Newton's equation with the model's own force law.

    ``m* d2alpha/dt2 = -P(alpha, dalpha/dt, alpha_max)``, ``alpha(0) = 0``, ``dalpha/dt(0) = V``,
    with ``P`` the model file's ``force`` (:mod:`microimpact.core.models`). The loading ends at the
    maximum approach (``dalpha/dt = 0``, located by a terminal event of
    :func:`scipy.integrate.solve_ivp`), from where ``alpha_max`` is frozen; the contact ends where
    the approach falls to the model's ``separation_approach`` (0 unless the model defines one) or,
    when ``ends_at_zero_force(params)``, where its ``signed_force`` vanishes, whichever comes first;
    a model that declares ``stage_two_approach`` (the seed: its yield approach) has its loading
    split there into stages 1 and 2. The equation is scaled by the loading time of a first, loose
    run, so that the tolerances act on numbers of order one. The one integrator (also behind
    :func:`integrate_impact`). It is the independent check of
    every model's closed form (:meth:`ContactPair.impact <microimpact.pair.ContactPair.impact>`).

    Parameters
    ----------
    {model}
    {pair}
    {params}
    {tolerances}
    {method}
    {grid}

    Returns
    -------
    dict
        The scalars of :data:`HISTORY_SCALARS` (``rebound_velocity`` [m/s], ``max_approach``,
        ``plastic_approach`` (the approach where the contact ends) [m], ``max_force`` [N],
        ``loading_time``, ``unloading_time``, ``contact_time`` [s]; ``elastic_stage_time``,
        ``plastic_stage_time`` and ``yield_velocity`` from the model's outcome, NaN where it
        does not define them), ``model``, ``method`` = ``"ode"``, ``nfev``, and with ``n`` or
        ``times`` the arrays ``time``, ``approach``, ``approach_velocity``, ``force`` and
        ``stage`` (1 loading, 2 the second loading stage where the model has one, 3 unloading,
        0 apart). ``elastic_stage_time`` and ``plastic_stage_time`` are the integration's own
        where the model declares ``stage_two_approach``.

    Raises
    ------
    ValueError
        Bad inputs or parameters (named), or a particle that does not leave the surface (an
        adhesive or strongly damped model below its sticking speed: ``e = 0``, no finite history).

    Examples
    --------
    >>> m = 4 / 3 * 3.141592653589793 * 2.45e-6**3 * 1350
    >>> r = integrate_model("liggghts_thornton_ning", 50.0, 1.31e9, 2.45e-6, m, 156e6)
    >>> round(r["rebound_velocity"] / 50.0, 4)  # the model's closed form: 0.6905
    0.6905
    """
    mod, p = _model_and_params(model, params)
    V, E, R, m, p_y = scalar_pair(velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure)
    return _integrate(mod, p, V, E, R, m, p_y, rtol=rtol, atol=atol, method=method, n=n, times=times)
