"""Impact models: one file each, found by name; the contract every model declares, with its defaults.

A model is one module of this package (or of a package added with :func:`register_path`), named
as users name it (``model=NAME``). It declares what it is with module-level names; everything but
``NAME``, ``TITLE``, ``outcome`` and ``force`` has a default, supplied here (the way a
``scipy.stats`` distribution inherits what it does not override), so a small model is small:

.. code-block:: python

    import math
    from microimpact.core.models import Parameter, checks, in_bounds, jitable, pack

    NAME = "my_law"                                   # the file's name
    TITLE = "One line: the law and its source"
    PARAMETERS = (Parameter("restitution", "1", "e in (0, 1]", low=0.0, high=1.0, low_open=True),)
    BOUNDS, validate = checks(NAME, PARAMETERS)       # the compiled and the Python check

    @jitable
    def outcome(V, E, R, m, p_y, params):
        if not in_bounds(params, BOUNDS):
            return nan_outcome(V)
        ...
        return pack(V, Vy, v, elastic, e, e * V, a_max, a_p, P_max, R_p, a_c, R, t1, t2, t_L, t_U)

    @jitable
    def force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params):
        ...

**Required**

``NAME``
    The module's name, the string users pass as ``model=``.
``TITLE``
    One line: the law and its source.
``outcome(V, E, R, m, p_y, params)``
    Marked ``@jitable``; plain floats in (speed [m/s], ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], ``p_y``
    [Pa], the model's parameters as a tuple of floats), the tuple of
    :data:`~microimpact.core.quantities.OUTCOME_FIELDS` out, built by :func:`pack` (or
    :func:`dem_outcome`, :func:`nan_outcome`): NaN where the model does not define a field, flags
    as 1.0/0.0. Invalid ``params`` give :func:`nan_outcome` (never an exception).
``force(alpha, alpha_dot, alpha_max, E, R, m, p_y, params)``
    Marked ``@jitable``; the normal force [N] at approach ``alpha`` [m], approach rate ``alpha_dot``
    [m/s] and largest approach so far ``alpha_max`` [m]: the law whose integration
    (:func:`microimpact.pair.ContactPair.history`) checks :func:`outcome` independently.

**Optional** (default in brackets)

``PARAMETERS`` [``()``]
    The model's own parameters beyond the pair's ``E*``, ``R*``, ``m*``, ``p_y``, in the order
    ``params`` holds them: :class:`Parameter` (name, unit, description, default, bounds). A plain
    ``(name, unit, description)`` tuple with a ``DEFAULTS`` tuple beside it is still read.
``BOUNDS``, ``validate`` [from ``PARAMETERS``]
    The compiled check (:func:`in_bounds` reads ``BOUNDS``) and the Python check (ValueError naming
    the parameter and its value) are both generated from ``PARAMETERS`` by :func:`checks`; a model
    writes its own ``validate`` only for a rule bounds cannot state.
``STICKS`` [``False``]
    True when the model can give ``e = 0`` (a stuck particle) at a finite speed: fitting accepts
    stuck data points only for such a model.
``STAGES`` [:data:`GENERIC_STAGES`]
    ``{stage code: name}`` of a history: 1 loading, 2 a second loading stage, 3 unloading (0, no
    contact, is everyone's).
``LABEL`` [``NAME``]
    Short name for legends and tables.
``CITATION`` [``None``: the source ``TITLE`` names]
    The published source of the law, as a reference (journal, volume, pages, year): what a data
    set computed with the model cites (the ``model`` attribute of a sweep, :func:`microimpact.sweep.sweep`).
``signed_force`` [``None``: ``force``]
    The force law before clipping at zero (negative: attractive), where the contact may end at zero force.
``ends_at_zero_force(params)`` [``None``: never]
    True when the contact ends where ``signed_force`` vanishes (else where the approach falls to
    ``separation_approach``).
``ZERO_FORCE_ORDER`` [``1.5``: Hertzian]
    The order ``n`` of that zero: near the end of the contact ``signed_force`` vanishes as
    ``d^n`` in the distance ``d`` to it (``3/2`` for a Hertzian unloading, the common case; ``1``
    where the force crosses zero with a slope, as a dashpot's or a linear spring's). A history's
    integration (:mod:`microimpact.dynamics`) locates the end on ``sign(P)|P|^(1/n)``, a simple
    zero, which its root finder needs.
``separation_approach(E, R, m, p_y, params)`` [``None``: 0]
    Approach [m] at which the contact breaks on unloading (negative for adhesive laws).
``separation_approach_after(alpha_max, E, R, m, p_y, params)`` [``None``: ``separation_approach``]
    The same where it depends on the largest approach ``alpha_max`` [m] reached (a law that
    flattens the contact, whose unloading curve is set at the turning point).
``stage_two_approach(E, R, m, p_y, params)`` [``None``: one loading stage]
    Approach [m] at which loading passes from stage 1 to stage 2 of ``STAGES`` (the seed: its
    yield approach, eq. 5; ``inf``: never), for a law whose loading changes there; a history's
    integration then locates it and times both stages.
``sticking_velocity(E, R, m, p_y, params)`` [``None``: none known]
    The speed [m/s] at and below which the particle sticks (``e = 0``), for a law with ``STICKS``
    (:meth:`ContactPair.sticking_velocity <microimpact.pair.ContactPair.sticking_velocity>`).
``tangential_contact_radius(alpha, alpha_max, E, R, m, p_y, params)`` [``None``: Hertz's ``(R alpha)^(1/2)``]
    Marked ``@jitable``; the contact radius [m] at approach ``alpha`` after the largest approach
    ``alpha_max``, for a law whose contact is not Hertz's (JKR's larger radius under adhesion, a
    flattened plastic contact): the tangential stiffness of an oblique adhesive impact grows with it
    (:mod:`microimpact.oblique.adhesive`).

*What is evaluated at many speeds* (fitting and ranking compare only ``e``; the stick/bounce maps
read ``V_y``), without what only the outcome's other fields need (a contact time by quadrature, an
integration). Each is the outcome's own field, bit for bit (``V_y``: to rounding), computed by the
model's own functions that :func:`outcome` calls, never a second copy of a formula:

``restitution_group(V, E, R, m, p_y, params)`` and ``restitution_of_group(g, params)`` [``None``]
    Both ``@jitable``, declared together: the one declaration that ``e`` depends on the speed and
    the pair through one dimensionless group ``g`` alone (with the model's ``params``). ``g`` at
    speed ``V > 0`` exactly as :func:`outcome` computes it, and ``e`` at ``g``. Fitting evaluates
    ``e`` once per distinct ``g`` of its data (:mod:`microimpact.fitting`): Hertz-Tsuji's ``g`` is
    its damping ratio up to rounding, a handful of distinct values for any set of speeds. The
    seed's is ``V/V_y`` (eq. 27), so its face also gives ``e`` of ``V`` and ``V_y`` alone
    (``restitution_of_yield_velocity``, :mod:`microimpact.models._base`), which fitting's grid
    search over ``V_y`` uses.
``restitution_only(V, E, R, m, p_y, params)`` [``None``: from the group where declared, else the outcome's field]
    Marked ``@jitable``; ``e`` [-] alone at any speed, with the arguments of :func:`outcome`
    (:func:`microimpact.impact.restitution_arrays`, which derives ``e`` from the group of a model
    that declares one and not this hook, at positive speeds). (Not ``restitution``: the seed's
    module has a function of that name, ``e`` of ``V/V_y``.)
``yield_velocity_of(E, R, m, p_y, params)`` [``None``: the field ``yield_velocity`` of ``outcome``]
    Marked ``@jitable``; ``V_y`` [m/s] alone (0 where the contact yields at any speed), which
    :mod:`microimpact.stick` maps over particle sizes.

``WALL_ADHESION`` [``False``]
    True for the adhesive law the wall interaction can take as its normal law: ``adhesion=NAME`` of
    :func:`~microimpact.wall.wall_interaction`, of the C export and of its tables (the rules
    :data:`microimpact.adhesion.ADHESION_RULES` lists), through the table of the law's correction to
    the additive rule (:func:`microimpact.core.adhesion.whole_law_correction`, which that law
    computes). Declared by Thornton & Ning's whole law, and by one model only: that table is its.
    The same declaration names the whole adhesive elastic-plastic law wherever one is meant
    (:func:`whole_law`): the default of :meth:`ContactPair.sticking_velocity
    <microimpact.pair.ContactPair.sticking_velocity>` and the law :mod:`microimpact.stick` sets
    against the additive rule.
``WALL_REFUSAL`` [``None``]
    Why the law cannot be the wall's adhesion law, for a law a user may expect there (one clause:
    :func:`microimpact.adhesion.check_adhesion_rule` gives it after refusing the name).
``C_EXPORT`` [``False``]
    True for the law whose restitution the generated C source writes (``e_p(V/V_y)``,
    :mod:`microimpact.cexport`): a fit of that law can be exported with its confidence band
    (:func:`microimpact.cexport.write_band`); a fit of any other is refused, naming it. One model.
``COST`` [``"cheap"``]
    The cost class of the model's ``e`` over a data set in Python loops (what fitting evaluates):
    ``"cheap"``, closed forms or a short root search, microseconds a point; ``"slow"``, an
    integration of the equation of motion or a quadrature per point, about a millisecond. Its
    nominal time per point is :data:`COST_CLASSES`; fitting compiles its loops where that, times
    the points and the evaluations of a fit, exceeds the array layer's budget (deterministic: no
    timing decides).
``OUTCOME_COST`` [``COST``]
    The same for the whole outcome (a fit's predictions with contact times): ``"slow"`` where the
    contact times take a quadrature though ``e`` is cheap.
``outside_validity(V, E, R, m, p_y, params)`` [``None``: always inside]
    Marked ``@jitable``; a code, 0.0 where the impact at ``V`` lies within what the published law can
    say, else the sum of the reasons of :data:`VALIDITY_REASONS` that hold: 1 where its published
    unloading would return more work than the loading stored (``e > 1``, energy created; the outcome
    gives ``e = 1``, the contact retracing its loading), 2 where the contact radius ``a*`` exceeds the
    sphere's radius (a fit extrapolated past any geometry: its ``e`` can rise with ``V`` there), 4 where
    an integrated outcome reached its bound on the work before the contact ended. The
    outcome is kept as computed (flagged, not refused, not clipped further); the layer above flags and
    warns (:func:`validity_reasons`), as it does ``large_strain``.
``ADHESION_LIMIT`` [``None``: no adhesion]
    ``"JKR"`` or ``"DMT"``: the adhesion limit the law is written for; with
    ``work_of_adhesion(params)`` (the work of adhesion ``G`` [J/m^2] its parameters give),
    :meth:`ContactPair.impact <microimpact.pair.ContactPair.impact>` flags a pair outside it by
    Tabor's parameter (:func:`microimpact.core.adhesion.tabor_parameter`).

:func:`get` returns the :class:`Model` declaration of a name: the module's names with these
defaults filled in. The generic machinery (arrays, histories, fitting, calibration, sweeps, the C
export) asks the declaration and never a model's name: no room outside a model's own two asks "is
this that model?" (``tests/test_architecture.py`` lists any such branch), and the default model,
:data:`DEFAULT`, is only the model used when none is named. Everything else a user touches about a
model (its calibration, DEM input lines, plot style, a history in closed form,
``closed_form_history``) is its face, :mod:`microimpact.models`, whose contract
(:mod:`microimpact.models._base`) declares those hooks with their defaults the same way.
"""

from __future__ import annotations

import importlib
import math
import pkgutil
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, NamedTuple

from .._jit import jitable
from ._common import dem_outcome, in_bounds, nan_outcome, pack

__all__ = [
    "available",
    "get",
    "parameters",
    "resolve_params",
    "register_path",
    "unregister_path",
    "DEFAULT",
    "GENERIC_STAGES",
    "COST_CLASSES",
    "Parameter",
    "LIMIT_FORCE",
    "Model",
    "declare",
    "deprecated_names",
    "whole_law",
    "VALIDITY_REASONS",
    "validity_reasons",
    "checks",
    "bounds",
    "in_bounds",
    "pack",
    "dem_outcome",
    "nan_outcome",
    "jitable",
]

#: The seed's model (Aerosol Sci. Tech. 50(4), 2016), used when no model is named.
DEFAULT = "thornton_ning_2016"

#: Nominal time [s] per point of a model's ``e`` (or outcome) in Python loops, by cost class
#: (``COST``, ``OUTCOME_COST``): the orders of magnitude measured on the zoo (closed forms 3-50 us a
#: point; integrations and quadratures 0.1-2.3 ms a point).
COST_CLASSES = {"cheap": 1e-5, "slow": 1e-3}

#: Stage names of a history of a law without stages of its own: loading to the maximum approach,
#: then unloading (codes 1 and 3; 0 is "no contact").
GENERIC_STAGES = {1: "loading", 3: "unloading"}


class Parameter(NamedTuple):
    """One parameter of a model: what it is, its default and the interval it must lie in.

    ``low`` is a number or the name of an earlier parameter (``unloading_stiffness >=
    loading_stiffness``); ``low_open``/``high_open`` make the bound strict; every value must be
    finite unless ``high`` is finite (``(0, 1]``). ``flag``: a 0/1 switch. ``default`` NaN: the user
    must give a value. ``normal``: a nonzero subnormal is refused (see :attr:`refuses_subnormal`). The first three fields are the old ``(name, unit, description)`` triple.

    A parameter that is a quantity of :data:`~microimpact.core.quantities.QUANTITIES` (a work of
    adhesion, a yield strength, a restitution, ...) is made with :meth:`of`, which takes its unit
    from that row, so that the unit is written once for every model that has it.
    """

    name: str
    unit: str
    description: str
    default: float = math.nan
    low: Any = -math.inf
    high: float = math.inf
    low_open: bool = False
    high_open: bool = False
    flag: bool = False
    normal: bool = False

    @property
    def refuses_subnormal(self) -> bool:
        """True where a nonzero subnormal value is refused: a parameter that must be positive (the law
        divides by it, and a subnormal's reciprocal overflows), or one marked ``normal`` (the law's
        search from it does not end: JKR's pull-off with ``pi gamma/E*`` underflowing to zero). Elsewhere
        a subnormal is the value it is (a Poisson's ratio or an adhesive stiffness of 1e-310 is as good
        as zero, and the laws compute with it)."""
        return self.normal or (self.low_open and not isinstance(self.low, str) and self.low == 0.0)

    @classmethod
    def of(cls, quantity: str, description: str | None = None, **kwargs) -> Parameter:
        """The parameter named ``quantity``, a row of :data:`~microimpact.core.quantities.QUANTITIES`:
        its unit is the row's; its description the row's unless the model gives its own, which states
        what the row cannot (the bounds and the part the quantity plays in that law). ``kwargs``: the
        default and bounds, as for the class.

        >>> Parameter.of("work_of_adhesion", low=0.0)[:3]
        ('work_of_adhesion', 'J/m^2', 'work of adhesion G')
        """
        from ..quantities import QUANTITIES

        if quantity not in QUANTITIES:
            raise ValueError(f"quantity must name a row of QUANTITIES, got {quantity!r}")
        row = QUANTITIES[quantity]
        return cls(quantity, row.unit, row.description if description is None else description, **kwargs)

    def check(self, value: float, values: dict) -> None:
        """ValueError naming this parameter and ``value`` when it is out of bounds (``values``: the
        parameters before it, by name)."""
        name = self.name
        if self.flag:
            if value not in (0.0, 1.0):
                raise ValueError(f"{name} must be 0 or 1, got {value!r}")
            return
        if isinstance(self.low, str):
            ref = values[self.low]
            ok = (value > ref if self.low_open else value >= ref) and math.isfinite(value)
            if not ok:
                raise ValueError(
                    f"{name} must be finite and {'>' if self.low_open else '>='} {self.low} ({ref!r}), got {value!r}"
                )
            return
        lo_ok = value > self.low if self.low_open else value >= self.low
        hi_ok = value < self.high if self.high_open else value <= self.high
        if lo_ok and hi_ok and math.isfinite(value):
            if self.refuses_subnormal and value != 0.0 and abs(value) < 2.2250738585072014e-308:
                raise ValueError(
                    f"{name} must be 0 or a normal float (at least 2.2250738585072014e-308), got {value!r}"
                )
            return
        if self.high == math.inf and self.low == 0.0:
            raise ValueError(
                f"{name} must be {'positive' if self.low_open else 'non-negative'} and finite, got {value!r}"
            )
        if self.high == math.inf:
            raise ValueError(f"{name} must be finite and {'>' if self.low_open else '>='} {self.low!r}, got {value!r}")
        lo = "(" if self.low_open else "["
        hi = ")" if self.high_open else "]"
        raise ValueError(f"{name} must lie in {lo}{self.low:g}, {self.high:g}{hi}, got {value!r}")


#: The 0/1 switch ``limit_force`` of the damped DEM laws (``hertz_tsuji``, ``hertz_viscoelastic``,
#: ``linear_spring_dashpot``): 1, the force is clipped at zero and the contact ends when it vanishes
#: (LAMMPS' ``limit_damping``); 0, the contact ends at zero approach. Declared once here; each law
#: puts it in its ``PARAMETERS`` with its default (1 here; ``LIMIT_FORCE._replace(default=0.0)`` for
#: another).
LIMIT_FORCE = Parameter(
    "limit_force",
    "1",
    "1: force clipped at zero, contact ends when it vanishes; 0: ends at zero approach",
    default=1.0,
    flag=True,
)


def bounds(params_spec) -> tuple:
    """The table :func:`in_bounds` reads, one row of seven floats per parameter:
    ``(low, high, low_open, high_open, index of the parameter low refers to or -1, flag,
    refuses_subnormal)``."""
    names = [p.name for p in params_spec]
    rows = []
    for p in params_spec:
        ref = -1.0
        low = p.low
        if isinstance(low, str):
            ref = float(names.index(low))
            low = -math.inf
        rows.append(
            (
                float(low),
                float(p.high),
                float(p.low_open),
                float(p.high_open),
                ref,
                1.0 if p.flag else 0.0,
                1.0 if p.refuses_subnormal else 0.0,
            )
        )
    return tuple(rows)


def _validator(name: str, params_spec) -> Callable:
    def validate(params):
        """Check ``params`` (ValueError naming the parameter and its value); return it as floats."""
        n = len(params_spec)
        if n == 0 and len(params):
            raise ValueError(f"model {name!r} takes no parameters, got {params!r}")
        if len(params) != n:
            names = ", ".join(p.name for p in params_spec)
            raise ValueError(f"params must hold {n} value{'s' if n != 1 else ''} ({names}), got {params!r}")
        out = {}
        for p, x in zip(params_spec, params):
            if isinstance(x, bool):
                raise ValueError(f"{p.name} must be a number, not a bool, got {x!r}")
            out[p.name] = float(x)
        for p in params_spec:
            p.check(out[p.name], out)
        return tuple(out.values())

    validate.__qualname__ = validate.__name__ = "validate"
    return validate


def checks(name: str, params_spec) -> tuple:
    """``(BOUNDS, validate)`` of a model from its ``PARAMETERS``: the table the compiled check
    :func:`in_bounds` reads and the Python check, one source for both."""
    return bounds(params_spec), _validator(name, params_spec)


@dataclass(frozen=True, eq=False)
class Model:
    """A model's declaration: its module's names with the contract's defaults filled in.

    Attribute names are the module's (``NAME``, ``PARAMETERS``, ``outcome``, ...); ``module`` is
    the module itself, whose other functions are reached through it (and, for one release,
    through this object).
    """

    NAME: str
    TITLE: str
    PARAMETERS: tuple
    DEFAULTS: tuple
    outcome: Callable
    force: Callable
    validate: Callable
    STICKS: bool = False
    STAGES: dict = field(default_factory=lambda: dict(GENERIC_STAGES))
    LABEL: str = ""
    signed_force: Callable | None = None
    ends_at_zero_force: Callable | None = None
    separation_approach: Callable | None = None
    separation_approach_after: Callable | None = None
    stage_two_approach: Callable | None = None
    ZERO_FORCE_ORDER: float = 1.5
    sticking_velocity: Callable | None = None
    yield_velocity_of: Callable | None = None
    restitution_only: Callable | None = None
    restitution_group: Callable | None = None
    restitution_of_group: Callable | None = None
    outside_validity: Callable | None = None
    tangential_contact_radius: Callable | None = None
    ADHESION_LIMIT: str | None = None
    work_of_adhesion: Callable | None = None
    WALL_ADHESION: bool = False
    WALL_REFUSAL: str | None = None
    CITATION: str | None = None
    C_EXPORT: bool = False
    COST: str = "cheap"
    OUTCOME_COST: str = "cheap"
    module: Any = None

    def __getattr__(self, name):  # the model's own helpers (e.g. a calibration's inverse)
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(object.__getattribute__(self, "module"), name)

    def __repr__(self):
        return f"<model {self.NAME}: {self.TITLE}>"


_HOOKS = (
    "signed_force",
    "ends_at_zero_force",
    "separation_approach",
    "separation_approach_after",
    "stage_two_approach",
    "sticking_velocity",
    "yield_velocity_of",
    "restitution_only",
    "restitution_group",
    "restitution_of_group",
    "outside_validity",
    "work_of_adhesion",
    "tangential_contact_radius",
)

#: The reasons an impact lies outside what its law can say, by the bit of ``outside_validity``'s code.
VALIDITY_REASONS = {
    1: "the published unloading would return more work than the loading stored (e > 1; e = 1 is returned)",
    2: "the contact radius exceeds the sphere's radius (a* > R: the fit is extrapolated past the geometry)",
    4: "the integration reached its bound before the contact ended (e = 0 and contact_time = inf returned: "
    "the particle creeps out of an over-damped contact)",
    8: "the DEM code does not run this input (it refuses it, or stops with an error there): the result is what "
    "its force routine computes where it would run",
    16: "the DEM code applies no adhesion here (its source skips the cohesive force below a threshold): the "
    "result is what the code computes, without the adhesion the physics has",
}


def validity_reasons(code) -> list:
    """The texts of :data:`VALIDITY_REASONS` whose bits the ``outside_validity`` ``code`` holds (a float
    or an integer; NaN or 0: none)."""
    if not code == code or not code:
        return []
    c = int(code)
    return [text for bit, text in VALIDITY_REASONS.items() if c & bit]


def declare(module) -> Model:
    """The :class:`Model` of ``module`` (or of any object with a model's names): the one place
    where the contract's defaults meet what the model declares."""
    ns = vars(module) if hasattr(module, "__dict__") else {}
    missing = [k for k in ("NAME", "TITLE", "outcome", "force") if k not in ns]
    if missing:
        raise ValueError(f"model {ns.get('NAME', module)!r} does not define {', '.join(missing)}")
    name = ns["NAME"]
    spec = []
    old_defaults = ns.get("DEFAULTS")
    for i, p in enumerate(ns.get("PARAMETERS", ())):
        if not isinstance(p, Parameter):  # the old (name, unit, description) triple, DEFAULTS beside it
            p = Parameter(*p[:3], default=float(old_defaults[i]) if old_defaults is not None else math.nan)
        spec.append(p)
    spec = tuple(spec)
    defaults = tuple(float(d) for d in old_defaults) if old_defaults is not None else tuple(p.default for p in spec)
    cost = ns.get("COST", "cheap")
    outcome_cost = ns.get("OUTCOME_COST", cost)
    for what, value in (("COST", cost), ("OUTCOME_COST", outcome_cost)):
        if value not in COST_CLASSES:
            raise ValueError(f"model {name!r}: {what} must be one of {', '.join(COST_CLASSES)}, got {value!r}")
    hooks = {h: ns.get(h) for h in _HOOKS}
    if hooks["signed_force"] is None:
        hooks["signed_force"] = ns["force"]
    return Model(
        NAME=name,
        TITLE=ns["TITLE"],
        PARAMETERS=spec,
        DEFAULTS=defaults,
        outcome=ns["outcome"],
        force=ns["force"],
        validate=ns.get("validate") or _validator(name, spec),
        STICKS=bool(ns.get("STICKS", False)),
        STAGES=dict(ns.get("STAGES", GENERIC_STAGES)),
        LABEL=ns.get("LABEL") or name,
        ADHESION_LIMIT=ns.get("ADHESION_LIMIT"),
        ZERO_FORCE_ORDER=float(ns.get("ZERO_FORCE_ORDER", 1.5)),
        WALL_ADHESION=bool(ns.get("WALL_ADHESION", False)),
        WALL_REFUSAL=ns.get("WALL_REFUSAL"),
        CITATION=ns.get("CITATION"),
        C_EXPORT=bool(ns.get("C_EXPORT", False)),
        COST=cost,
        OUTCOME_COST=outcome_cost,
        module=module,
        **hooks,
    )


def deprecated_names(module_name: str, name: str, **moved: str) -> Callable:
    """The ``__getattr__`` of a model file written before the parameter spec, keeping its released
    names for one release: ``DEFAULTS`` (now each :class:`Parameter`'s default, collected by the
    declaration, ``get(name).DEFAULTS``) and each ``old=new`` of ``moved`` (a name now read from
    the declaration, ``get(name).new``). Each warns (:class:`DeprecationWarning`) naming where to
    read it; any other name is an AttributeError as usual."""
    moved = {"DEFAULTS": "DEFAULTS", **moved}

    def __getattr__(attr):
        if attr not in moved:
            raise AttributeError(f"module {module_name!r} has no attribute {attr!r}")
        import warnings

        new = moved[attr]
        warnings.warn(
            f"{module_name}.{attr} is deprecated; use microimpact.models.get({name!r}).{new}",
            DeprecationWarning,
            stacklevel=2,
        )
        return getattr(get(name), new)

    return __getattr__


# ----------------------------------------------------------------------------- the registry
#: Packages searched for model files, in order: this one, then those of :func:`register_path`.
_PACKAGES: list = [__name__]
_NAMES: list = []
_WHERE: dict = {}
_MODELS: dict = {}


def register_path(package: str) -> None:
    """Add the importable package ``package`` (a dotted name) to the packages searched for models.

    Each public module of it (``package/my_law.py``) is a model named after its file, following
    the contract of this module; it then appears in :func:`available` and works wherever a model
    name is taken (``pair.impact(V, model="my_law")``, histories, sweeps, comparisons, fits,
    calibration). Its face (calibration, DEM lines, style; :mod:`microimpact.models`) is read from
    ``package.faces.my_law`` if that module exists, else the defaults apply. A name that an
    earlier package already has is refused (ValueError).
    """
    if not isinstance(package, str) or not package:
        raise ValueError(f"package must be an importable package name, got {package!r}")
    try:
        pkg = importlib.import_module(package)
    except ImportError as exc:
        raise ValueError(f"package {package!r} cannot be imported: {exc}") from None
    if not hasattr(pkg, "__path__"):
        raise ValueError(f"package must be a package (a folder with __init__.py), got the module {package!r}")
    if package in _PACKAGES:
        return
    names = _scan(package)
    clash = sorted(set(names) & set(available()))
    if clash:
        raise ValueError(f"package {package!r} has a model named {clash[0]!r}, which exists already")
    _PACKAGES.append(package)
    _reset()


def unregister_path(package: str) -> None:
    """Undo :func:`register_path` (its models leave :func:`available`)."""
    if package in _PACKAGES[1:]:
        _PACKAGES.remove(package)
        _reset()


def _reset():
    _NAMES.clear()
    _WHERE.clear()
    _MODELS.clear()


def _scan(package: str) -> list:
    path = importlib.import_module(package).__path__
    return [m.name for m in pkgutil.iter_modules(path) if not m.name.startswith("_") and m.name != "faces"]


def available() -> list[str]:
    """Names of the models, the seed's first, then alphabetical (the files, read once per process)."""
    if not _NAMES:
        for package in _PACKAGES:
            for name in _scan(package):
                _WHERE.setdefault(name, package)
        _NAMES.extend([DEFAULT, *sorted(set(_WHERE) - {DEFAULT})])  # the default first: an order, not a behaviour
    return list(_NAMES)


def package_of(name: str) -> str:
    """The package that holds model ``name`` (ValueError if unknown)."""
    get(name)
    return _WHERE.get(name, __name__)


def get(name: str = DEFAULT) -> Model:
    """The :class:`Model` declaration of model ``name`` (see :func:`available`); ValueError naming it if unknown."""
    found = _MODELS.get(name) if isinstance(name, str) else None
    if found is not None:
        return found
    names = available()
    if not isinstance(name, str) or name not in names:
        raise ValueError(f"model must be one of {', '.join(names)}; got {name!r}")
    found = _MODELS[name] = declare(importlib.import_module(f"{_WHERE[name]}.{name}"))
    return found


def whole_law() -> str:
    """The name of the whole adhesive elastic-plastic law: the one model that declares
    ``WALL_ADHESION`` (Thornton & Ning 1998, :mod:`~microimpact.core.models.thornton_ning_1998_adhesive_plastic`).

    Read from the declarations (every model's, once per process), so that no room names it; ValueError
    if none or more than one model declares it (the wall's table is one law's).
    """
    laws = [n for n in available() if get(n).WALL_ADHESION]
    if len(laws) > 1:
        raise ValueError(f"one model may declare WALL_ADHESION (the wall's table is one law's), got {', '.join(laws)}")
    if not laws:
        raise ValueError("no model declares WALL_ADHESION (the whole adhesive law)")
    return laws[0]


def parameters(name: str = DEFAULT) -> dict:  # noqa: D401
    """``{parameter: (unit, description, default)}`` of model ``name`` (``nan`` default: required)."""
    mod = get(name)
    return {p[0]: (p[1], p[2], d) for p, d in zip(mod.PARAMETERS, mod.DEFAULTS)}


def resolve_params(module, given: dict) -> tuple:
    """The model's parameters as the float tuple its functions take, from keyword values and defaults.

    ValueError naming the parameter when one is unknown, missing (no default), not a real number,
    or not finite.
    """
    if not given and not module.PARAMETERS:  # the common case, on the path of one impact
        return ()
    names = [p[0] for p in module.PARAMETERS]
    unknown = sorted(set(given) - set(names))
    if unknown:
        raise ValueError(
            f"model {module.NAME!r} has no parameter {unknown[0]!r}; its parameters: {', '.join(names) or 'none'}"
        )
    out = []
    for name, default in zip(names, module.DEFAULTS):
        value = given.get(name, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)) and not hasattr(value, "__float__"):
            raise ValueError(f"{name} must be a real number, got {value!r}")
        value = float(value)
        if math.isnan(value):
            raise ValueError(f"model {module.NAME!r} needs the parameter {name!r} (no default)")
        if not math.isfinite(value):
            raise ValueError(f"{name} must be finite, got {value!r}")
        out.append(value)
    return tuple(module.validate(tuple(out)))


_ = jitable  # re-exported for model files outside the core: ``from microimpact.core.models import jitable``
