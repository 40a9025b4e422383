"""The defaults of a model's face: what a model without a face file (or a face file that leaves
something out) gets.

A face is a module of :mod:`microimpact.models` named after its model (or ``PACKAGE.faces.NAME``
for a model added with :func:`~microimpact.models.register_path`). Every name below is optional
in it; :func:`microimpact.models.face` fills in the default of each name it lacks:

``STYLE`` [``{}``: the next colour and line style of :func:`microimpact.figures.style.series_style`]
    Matplotlib keywords of the model's line in comparison figures (colour, line style, width), so
    that a model looks the same in every figure.
``calibrate(pair_values, velocity, target_restitution, target_contact_time, **options)``
    [:func:`calibrate`: least squares of ``e`` over the parameters without a default]
    The model's parameters (a tuple in the order of its ``PARAMETERS``) that reproduce the target
    ``e`` (and, where the law has a free stiffness, the contact time) at the speeds ``velocity``
    [m/s]; ``pair_values`` is ``(E*, R*, m*, p_y)`` in SI units, the targets are arrays of the
    speeds' shape. Keyword options are the model's own (``limit_force``, say); ValueError naming
    a target the law cannot reach. A face that defines it makes the model one of the DEM laws
    :func:`microimpact.calibrate.calibrate_all` covers.
``COMPARE_OPTIONS`` [``{}``]
    Options of ``calibrate`` used when :func:`microimpact.compare.compare_models` calibrates the
    model to the seed.
``lammps(calibration)`` [refuse]
    ``(coeff, comment)``: the ``pair_coeff``/``fix wall/gran granular`` arguments of LAMMPS'
    ``pair_style granular`` for a :class:`~microimpact.calibrate.Calibration`, and one comment line.
``liggghts(calibration, poisson, wall)`` [refuse]
    LIGGGHTS-PUBLIC input lines after ``units si``.
``restitution_of_yield_velocity(velocity, yield_velocity)`` [``None``]
    ``e`` of the speeds and ``V_y`` alone, for a model whose declared group (the core contract's
    ``restitution_group``) is ``V/V_y``, the same bits: fitting's grid search over ``V_y`` uses it.
``closed_form_history(velocity, pair_values, params, n, times)`` [``None``: integrated]
    The time history of one impact in closed form, for a model that has one: the dict of
    :func:`microimpact.dynamics.integrate_model` (approach, velocity, force and stage at the times of
    ``n`` or ``times``, the scalars of :data:`~microimpact.dynamics.HISTORY_SCALARS`) at the speed
    ``velocity`` [m/s] with ``pair_values = (E*, R*, m*, p_y)`` and the checked ``params``.
    :meth:`ContactPair.history <microimpact.pair.ContactPair.history>` takes it as its method
    ``"closed"`` (its default where the face declares it); every model has the integration of
    its force law (method ``"ode"``). :data:`microimpact.dynamics.CLOSED_FORM_HISTORY` lists the
    models that declare it.
"""

from __future__ import annotations

import math

import numpy as np

from ..core.quantities import OUTCOME_FIELDS

__all__ = [
    "run",
    "calibrate",
    "bounded_value",
    "unbounded_variable",
    "lammps",
    "liggghts",
    "limit_force_option",
    "STYLE",
    "COMPARE_OPTIONS",
    "LAMMPS_TANGENTIAL",
    "I_RESTITUTION",
    "I_CONTACT_TIME",
    "restitution_of_yield_velocity",
    "closed_form_history",
    "params_for_work_of_adhesion",
]

#: Position of ``restitution`` in an outcome tuple.
I_RESTITUTION = OUTCOME_FIELDS.index("restitution")
#: Position of ``contact_time`` in an outcome tuple.
I_CONTACT_TIME = OUTCOME_FIELDS.index("contact_time")

#: The tangential part of LAMMPS ``pair_coeff`` lines: no tangential force (a normal impact).
LAMMPS_TANGENTIAL = "tangential linear_nohistory 0.0 0.0"

STYLE: dict = {}
COMPARE_OPTIONS: dict = {}
restitution_of_yield_velocity = None
closed_form_history = None


def run(model, velocity, pair_values, params):
    """``(e, contact_time)`` of ``model`` (a :class:`~microimpact.core.models.Model`) at the speeds
    ``velocity`` [m/s] for ``pair_values = (E*, R*, m*, p_y)`` and ``params``: arrays [-], [s]."""
    E, R, m, p_y = pair_values
    p = tuple(float(x) for x in params)
    rows = [model.outcome(float(v), E, R, m, p_y, p) for v in np.atleast_1d(velocity)]
    return np.array([r[I_RESTITUTION] for r in rows]), np.array([r[I_CONTACT_TIME] for r in rows])


def limit_force_option(value, law) -> float:
    """The ``limit_force`` option of a calibration as 0.0/1.0 (the default of ``law``'s ``limit_force``
    parameter when None); ValueError otherwise."""
    if value is None:
        return next(p.default for p in law.PARAMETERS if p.name == "limit_force")
    if isinstance(value, bool) or value not in (0, 1):
        raise ValueError(f"limit_force must be 0 or 1, got {value!r}")
    return float(value)


def bounded_value(spec, u, values):
    """Parameter value from the unconstrained variable ``u`` within the bounds of ``spec``."""
    low = values[spec.low] if isinstance(spec.low, str) else spec.low
    if math.isfinite(low) and math.isfinite(spec.high):
        return low + (spec.high - low) / (1.0 + math.exp(-u))
    if math.isfinite(low):
        return low + math.exp(u)
    if math.isfinite(spec.high):
        return spec.high - math.exp(u)
    return u


def unbounded_variable(spec, x, values):
    """The inverse of :func:`bounded_value`: the unconstrained variable of the value ``x`` within the
    bounds of ``spec`` (0, the middle of the bounds, for a value not strictly inside them)."""
    low = values[spec.low] if isinstance(spec.low, str) else spec.low
    high = spec.high
    if not math.isfinite(x):
        return 0.0
    if math.isfinite(low) and math.isfinite(high):
        return math.log((x - low) / (high - x)) if low < x < high else 0.0
    if math.isfinite(low):
        return math.log(x - low) if x > low else 0.0
    if math.isfinite(high):
        return math.log(high - x) if x < high else 0.0
    return x


def _scan_cost(residuals, u):
    """Squared residuals at ``u``, inf where the model cannot be evaluated there (an extreme value of the
    parameter, 1e-13 of its unit: not a start for the search)."""
    try:
        return float(np.sum(residuals(np.array([u])) ** 2))
    except (ArithmeticError, ValueError):
        return math.inf


def calibrate(model, pair_values, velocity, target_restitution, target_contact_time):
    """The default calibration: the parameters of ``model`` without a default, chosen by least
    squares of ``e(V) - e_target`` over the speeds (each mapped into its bounds; start in the
    middle of them, and for one parameter that misses from there, again from the best point of a scan
    over its range), the others at their defaults. The contact time is not matched (a model that
    can match it has a calibration of its own); ValueError if the fit does not converge (a fit that
    converges away from the target is refused by :func:`microimpact.calibrate.calibrate`)."""
    from scipy.optimize import least_squares

    spec = model.PARAMETERS
    free = [i for i, p in enumerate(spec) if math.isnan(p.default)]
    if not free:
        return tuple(model.DEFAULTS)

    def params_of(u):
        values = {}
        for i, p in enumerate(spec):
            values[p.name] = bounded_value(p, float(u[free.index(i)]), values) if i in free else p.default
        return tuple(values.values())

    def residuals(u):
        e, _ = run(model, velocity, pair_values, params_of(u))
        return np.nan_to_num(e - target_restitution, nan=10.0)

    sol = least_squares(residuals, np.zeros(len(free)), xtol=1e-15, ftol=1e-15, gtol=1e-15)
    if not sol.success:
        raise ValueError(f"model {model.NAME!r} could not be calibrated to the target e: {sol.message}")
    if len(free) == 1 and not np.all(np.abs(sol.fun) <= 1e-9):
        # The middle of the bounds (u = 0) is a unit of the parameter: 1 Pa for a yield strength, where a
        # law can be flat (e = 0 whatever the step) and the search stops at its start. One parameter:
        # start again from the best of a scan over its range (exp(u) from 1e-13 to 1e26 of its unit).
        grid = np.linspace(-30.0, 60.0, 46)
        cost = [_scan_cost(residuals, u) for u in grid]
        best = grid[int(np.argmin(cost))]
        again = least_squares(residuals, np.array([best]), xtol=1e-15, ftol=1e-15, gtol=1e-15)
        if again.success and again.cost < sol.cost:
            sol = again
    return params_of(sol.x)


def lammps(calibration):
    """Refuse: the model has no LAMMPS normal contact model."""
    raise ValueError(f"LAMMPS has no normal contact model for {calibration.model!r}; use liggghts()")


def liggghts(calibration, poisson, wall):
    """Refuse: the model has no LIGGGHTS normal model."""
    raise ValueError(f"LIGGGHTS has no normal model for {calibration.model!r} with these parameters")


def params_for_work_of_adhesion(model, work_of_adhesion, pair_values, params):
    """``params`` of ``model`` with its parameter ``work_of_adhesion`` set to ``G``, or its
    ``surface_energy`` to ``G/2`` (Dupre: ``G = 2 gamma`` for like surfaces); None where it has
    neither (the default face hook; ``pair_values`` is not needed by a law whose input is ``G`` itself)."""
    names = [p.name for p in model.PARAMETERS]
    out = list(params)
    if "work_of_adhesion" in names:
        out[names.index("work_of_adhesion")] = float(work_of_adhesion)
    elif "surface_energy" in names:
        out[names.index("surface_energy")] = 0.5 * float(work_of_adhesion)
    else:
        return None
    return tuple(out)
