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
equation (:func:`integrate_impact`, :func:`integrate_model`; the machinery in ``microimpact._history``).
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from . import _history
from .core import models as _models
from .core import quantities
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

#: Models whose time history exists in closed form (:func:`impact_history`); the others are
#: integrated numerically (:func:`integrate_model`).
CLOSED_FORM_HISTORY = (_seed.NAME,)


#: Stage codes of a history.
STAGE_NAMES = {0: "no contact (free flight before first contact or after separation)", **_seed.STAGES}
#: Stage codes of a history of any other model (loading to the maximum approach, then unloading).
GENERIC_STAGE_NAMES = {0: STAGE_NAMES[0], 1: "loading", 3: "unloading"}


def stage_names(model=None) -> dict:
    """``{stage code: name}`` of a history of ``model`` (a name; default the seed's): code 0, no
    contact, and the model's own ``STAGES`` (:mod:`microimpact.core.models`)."""
    from .core import models as _models

    return {0: STAGE_NAMES[0], **_models.get(_seed.NAME if model is None else model).STAGES}


def __getattr__(name):
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
    model: str = _seed.NAME

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
        return cls(**{k: data[k] for k in keys}, method=data.get("method", method), model=data.get("model", _seed.NAME))

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

        if self.model == _seed.NAME:
            comments = [f"microimpact impact history ({self.method}; seed eqs. 17-26)"]
        else:
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


@_history.shared_parameters
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
    V, E, R, m, p_y = _history.scalar_pair(
        velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure
    )
    out = _history.integrate(
        _models.get(_seed.NAME), (), V, E, R, m, p_y, rtol=rtol, atol=atol, method=method, n=n, times=times
    )
    del out["model"]  # the seed's: this function's result has always been the seed's alone
    return out


@_history.shared_parameters
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
    mod, p = _history.model_and_params(model, params)
    V, E, R, m, p_y = _history.scalar_pair(
        velocity, effective_modulus, effective_radius, effective_mass, limiting_pressure
    )
    return _history.integrate(mod, p, V, E, R, m, p_y, rtol=rtol, atol=atol, method=method, n=n, times=times)
