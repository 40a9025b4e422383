"""The object layer users hold: :class:`ContactPair` and :class:`ImpactResult`.

A :class:`ContactPair` stores the four effective values the model needs
(``E*``, ``R*``, ``m*``, ``p_y``) and where they came from; every method
delegates to the vectorized functions of :mod:`microimpact.contact`,
:mod:`microimpact.impact` and :mod:`microimpact.dynamics`.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass, field, fields, replace
from typing import TYPE_CHECKING

import numpy as np

from . import contact, impact
from ._validation import (
    TINY_LIMITING_PRESSURE,
    check_nonnegative,
    check_poisson,
    check_positive,
    check_velocity,
    check_yield_velocity,
)
from .core import adhesion as _adhesion
from .core import hertz as _hertz
from .core import models, quantities
from .core.constants import LARGE_STRAIN_RATIO
from .core.models import thornton_ning_2016 as _seed
from .core.quantities import FLAG_FIELDS, OUTCOME_FIELDS
from .core.wall import sphere_mass as _sphere_mass
from .engine import evaluate as _evaluate

if TYPE_CHECKING:  # the history machinery loads only when a history is asked for
    from .dynamics import ImpactHistory
from .materials import PAPER_CASES, Material, effective_modulus, get_material, sphere_mass
from .materials import limiting_pressure as _k_times_yield

__all__ = [
    "ContactPair",
    "ImpactResult",
    "LargeStrainWarning",
    "AdhesionRangeWarning",
    "PAIR_INPUTS",
    "DEFAULT_POISSON",
    "DEFAULT_SURFACE_MODULUS",
]

#: Poisson ratio of both bodies when a pair has no materials (the seed's Fig. 4 takes 0.3).
DEFAULT_POISSON = 0.3
#: Surface Young's modulus [Pa] when a pair has no materials (the seed's Fig. 4: 150 GPa).
DEFAULT_SURFACE_MODULUS = 150e9

#: The inputs of a pair that :meth:`ContactPair.vary` and :meth:`ContactPair.effective_values` take.
PAIR_INPUTS = (
    "limiting_pressure",
    "yield_strength",
    "k",
    "yield_velocity",
    "effective_modulus",
    "particle_modulus",
    "particle_poisson",
    "surface_modulus",
    "surface_poisson",
    "radius",
    "diameter",
    "density",
    "effective_radius",
    "effective_mass",
)
_MATERIAL_INPUTS = ("particle_modulus", "particle_poisson", "surface_modulus", "surface_poisson")
# Names that set the same value: any of the first tuple with any of the second is refused.
_EXCLUSIVE = (
    (("limiting_pressure",), ("yield_strength", "k", "yield_velocity")),
    (("yield_velocity",), ("yield_strength", "k")),
    (("effective_modulus",), _MATERIAL_INPUTS),
    (("radius", "diameter", "density"), ("effective_radius", "effective_mass")),
)
_CHECKS = {
    "limiting_pressure": lambda n, x: check_positive(n, x, allow_inf=True),
    "particle_poisson": lambda n, x: check_poisson(n, x),
    "surface_poisson": lambda n, x: check_poisson(n, x),
}


class LargeStrainWarning(UserWarning):
    """The contact radius exceeds the small-strain range of the model (``a/R* > 0.3``)."""


class AdhesionRangeWarning(UserWarning):
    """The pair lies outside the adhesion limit (JKR or DMT) its adhesive model is written for, by
    Tabor's parameter (:meth:`ContactPair.adhesion_range`)."""


_TRUE, _FALSE = np.bool_(True), np.bool_(False)
_LARGE = OUTCOME_FIELDS.index("large_strain")
_FLAG_INDEX = tuple((OUTCOME_FIELDS.index(k), k) for k in FLAG_FIELDS)


class _OneImpactField:
    """A field of :class:`ImpactResult` not yet read (a one-impact result, ``ImpactResult._of_one``).

    A non-data descriptor: Python reaches it only when the instance does not hold the name. The
    first read writes all 18 numpy scalars (flags numpy booleans) into the instance, so that every
    later read is a plain look-up; on the class itself it is no attribute (as a dataclass field
    without a default).
    """

    __slots__ = ("name",)

    def __init__(self, name):
        self.name = name

    def __get__(self, obj, owner=None):
        one = None if obj is None else obj.__dict__.pop("_one", None)
        if one is None:
            raise AttributeError(f"{(owner or type(obj)).__name__!r} object has no attribute {self.name!r}")
        d = obj.__dict__
        d.update(zip(OUTCOME_FIELDS, map(np.float64, one)))
        for i, flag in _FLAG_INDEX:
            d[flag] = _TRUE if one[i] == 1.0 else _FALSE
        return d[self.name]


def _adhesion_range_text(name, limit, mu):
    """The warning of a pair outside its adhesive model's limit."""
    if limit == "JKR":
        where = f"below {_adhesion.TABOR_JKR:g}: the JKR limit of {name} does not hold"
        if mu < _adhesion.TABOR_DMT:
            where += " (the DMT limit does: small, stiff particles)"
    else:
        where = f"above {_adhesion.TABOR_DMT:g}: the DMT limit of {name} does not hold"
        if mu > _adhesion.TABOR_JKR:
            where += " (the JKR limit does)"
    return f"Tabor parameter {mu:.3g} (z0 = 0.3 nm) {where}; results flagged in .outside_adhesion_range"


def _ignored(category) -> bool:
    """True when the first of :data:`warnings.filters` ignores every ``category`` warning.

    :func:`warnings.warn` then shows nothing, whatever the text or the caller; this test costs a
    tenth of it (its frame look-up, registry and filter walk, and formatting the text first), the
    warning of ``pair.impact(50.0)`` under ``warnings.simplefilter("ignore")`` (issue 25). Any other
    first filter (an ``"error"``, a message or module pattern) leaves the decision to ``warnings``.
    """
    filters = warnings.filters
    if not filters:
        return False
    action, message, cat, module, lineno = filters[0]
    return action == "ignore" and message is None and module is None and not lineno and issubclass(category, cat)


def _scalar_or_array(x):
    if type(x) is not np.ndarray:
        x = np.asarray(x)
    return x[()] if x.ndim == 0 else x


#: Quantities of an ImpactResult: name -> (unit, description), from the one table
#: (:data:`microimpact.core.quantities.QUANTITIES`); the CLI table, the sweep's attrs and CSV headers use it.
RESULT_FIELDS: dict[str, tuple[str, str]] = quantities.table([f for f in OUTCOME_FIELDS if f != "yield_velocity"])


@dataclass(frozen=True, eq=False)
class ImpactResult:
    """Outcome of one or many impacts of a :class:`ContactPair`.

    Every attribute is shaped like the ``velocity`` given to
    :meth:`ContactPair.impact` (a numpy scalar for a scalar speed). Units: SI.

    Attributes
    ----------
    velocity : ndarray
        Impact speed ``V`` [m/s].
    yield_velocity : ndarray
        Yield velocity ``V_y`` [m/s] (seed eq. 28).
    normalized_velocity : ndarray
        ``v = V/V_y`` [-].
    elastic : ndarray of bool
        True where the impact is elastic, ``V <= V_y``.
    restitution : ndarray
        Coefficient of restitution ``e`` [-] (eq. 27).
    rebound_velocity : ndarray
        Rebound speed ``V_r = e V`` [m/s].
    energy_loss : ndarray
        Fraction of the kinetic energy lost, ``1 - e^2`` [-] (eq. 29).
    max_approach : ndarray
        Maximum approach ``alpha*`` [m] (eq. 22).
    plastic_approach : ndarray
        Plastic approach ``alpha_p`` [m] (eq. 11).
    max_force : ndarray
        Maximum force ``P*`` [N] (eq. 14 at ``alpha*``).
    unloading_radius : ndarray
        Radius of the flattened contact ``R_p`` [m] (eq. 9).
    max_contact_radius : ndarray
        Contact radius at the maximum approach ``a* = (R* alpha*)^(1/2)`` [m] (eq. 3).
    large_strain : ndarray of bool
        True where ``a*/R* > 0.3``: outside the model's small-strain range.
    elastic_stage_time : ndarray
        Stage-1 (Hertz loading) time ``t1`` [s] (eq. 20).
    plastic_stage_time : ndarray
        Stage-2 (plastic loading) time ``t2`` [s] (eq. 23).
    loading_time : ndarray
        Loading time ``t_L = t1 + t2`` [s] (eq. 32).
    unloading_time : ndarray
        Unloading time ``t_U`` [s] (eq. 26).
    contact_time : ndarray
        Contact time ``t_c = t_L + t_U`` [s] (eq. 33).
    tabor_parameter : float
        Adhesive models only (NaN otherwise): Tabor's parameter ``mu`` [-] of the pair and the
        model's work of adhesion (:meth:`ContactPair.adhesion_range`, ``z_0 = 0.3`` nm).
    outside_adhesion_range : bool
        True where the model is written for the JKR limit and ``mu < 5``, or for the DMT limit
        and ``mu > 0.1``: the pair is outside the law's range (flagged, not refused; as
        ``large_strain``). False for the other models.
    """

    #: Set by :meth:`ContactPair.impact` for an adhesive model (not a field of the outcome table).
    tabor_parameter = math.nan
    #: Set by :meth:`ContactPair.impact` for an adhesive model.
    outside_adhesion_range = _FALSE

    velocity: np.ndarray
    yield_velocity: np.ndarray
    normalized_velocity: np.ndarray
    elastic: np.ndarray
    restitution: np.ndarray
    rebound_velocity: np.ndarray
    energy_loss: np.ndarray
    max_approach: np.ndarray
    plastic_approach: np.ndarray
    max_force: np.ndarray
    unloading_radius: np.ndarray
    max_contact_radius: np.ndarray
    large_strain: np.ndarray
    elastic_stage_time: np.ndarray
    plastic_stage_time: np.ndarray
    loading_time: np.ndarray
    unloading_time: np.ndarray
    contact_time: np.ndarray

    @classmethod
    def _trusted(cls, values: dict) -> ImpactResult:
        """Build from a complete dict of already-checked values, skipping the dataclass ``__init__`` (hot path)."""
        obj = object.__new__(cls)
        obj.__dict__.update(values)
        return obj

    @classmethod
    def _of_one(cls, values: tuple) -> ImpactResult:
        """One impact from the core's tuple (in the order of ``OUTCOME_FIELDS``), kept as it is until a
        field is read: then all 18 become numpy scalars (flags numpy booleans) at once, written into the
        instance (the hot path of ``pair.impact(50.0)``: building them cost about half the outcome)."""
        obj = object.__new__(cls)
        obj.__dict__["_one"] = values
        return obj

    @property
    def any_large_strain(self) -> bool:
        """True if any impact lies outside the small-strain range."""
        flags = self.large_strain
        return bool(flags.any() if type(flags) is np.ndarray else np.any(flags))

    def to_dict(self) -> dict:
        """All quantities as a dict of arrays (or scalars)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def __len__(self):
        return int(np.size(self.velocity))

    def _rows(self):
        """(name, unit, description, value text) of every field, for the displays below."""
        rows = []
        for name in OUTCOME_FIELDS:
            q = quantities.QUANTITIES[name]
            x = np.asarray(getattr(self, name))
            if x.dtype == bool:
                text = str(bool(x)) if x.ndim == 0 else f"{int(x.sum())} of {x.size}"
            elif x.size == 0:
                text = "(empty)"
            elif x.ndim == 0 or np.all(x == x.flat[0]):
                text = f"{float(x.flat[0]):.6g}"
            else:
                text = f"{np.nanmin(x):.6g} .. {np.nanmax(x):.6g}"
            rows.append((name, q.unit, q.description, text))
        return rows

    def __repr__(self) -> str:
        n = int(np.size(self.velocity))
        pick = {r[0]: r for r in self._rows()}
        parts = [
            f"{k} = {pick[k][3]}" + ("" if pick[k][1] == "1" else f" {pick[k][1]}")  # no unit for a ratio
            for k in ("velocity", "restitution", "contact_time")
        ]
        return f"ImpactResult({n} impact{'s' if n != 1 else ''}: " + ", ".join(parts) + ")"

    def _repr_html_(self) -> str:
        """A table of every field with its unit (notebooks)."""
        import html

        n = int(np.size(self.velocity))
        body = "".join(
            f"<tr><td><code>{html.escape(name)}</code></td><td>{html.escape(text)}</td>"
            f"<td>{html.escape(unit)}</td><td>{html.escape(desc)}</td></tr>"
            for name, unit, desc, text in self._rows()
        )
        return (
            f"<table><caption>ImpactResult: {n} impact{'s' if n != 1 else ''} (a range shows min .. max)"
            "</caption><tr><th>field</th><th>value</th><th>unit</th><th>meaning</th></tr>"
            f"{body}</table>"
        )


for _name in OUTCOME_FIELDS:  # after the dataclass took its fields: no defaults, the same __init__
    setattr(ImpactResult, _name, _OneImpactField(_name))
del _name


@dataclass(frozen=True)
class ContactPair:
    """A particle and the body it hits, reduced to the model's effective values.

    Most users build one with :meth:`sphere_on_flat`, :meth:`from_materials` or
    :meth:`two_spheres`.

    Parameters
    ----------
    effective_modulus : float
        ``E*`` [Pa].
    effective_radius : float
        ``R*`` [m].
    effective_mass : float
        ``m*`` [kg].
    limiting_pressure : float
        ``p_y`` [Pa]; ``inf`` makes every impact elastic.
    density : float, optional
        Particle density [kg/m^3], when known (sphere on flat).
    label : str
        A name for tables and legends.
    particle, surface : Material, optional
        Where the effective values came from.

    Examples
    --------
    >>> import microimpact as mi
    >>> pair = mi.ContactPair.sphere_on_flat(radius=2.45e-6, density=1350.0,
    ...                                      effective_modulus=1.31e9, limiting_pressure=156e6)
    >>> round(float(pair.yield_velocity), 2)
    7.52
    >>> out = pair.impact([30.0, 50.0, 70.0])
    >>> out.restitution.round(3)
    array([0.813, 0.725, 0.67 ])
    """

    effective_modulus: float
    effective_radius: float
    effective_mass: float
    limiting_pressure: float
    density: float | None = None
    label: str = ""
    particle: Material | None = field(default=None, compare=False)
    surface: Material | None = field(default=None, compare=False)

    def __post_init__(self):
        for name in ("effective_modulus", "effective_radius", "effective_mass"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name), scalar=True))
        object.__setattr__(
            self,
            "limiting_pressure",
            check_positive("limiting_pressure", self.limiting_pressure, allow_inf=True, scalar=True),
        )
        if self.limiting_pressure < TINY_LIMITING_PRESSURE:  # V_y ~ p_y^(5/2) may underflow (eq. 28)
            check_yield_velocity(
                self.effective_modulus, self.effective_radius, self.effective_mass, self.limiting_pressure
            )
        if self.density is not None:
            object.__setattr__(self, "density", check_positive("density", self.density, scalar=True))

    # ----------------------------------------------------------------- constructors
    @staticmethod
    def _limiting_pressure(limiting_pressure, k, yield_strength, particle=None, surface=None):
        if limiting_pressure is not None:
            if yield_strength is not None or k is not None:
                raise ValueError("limiting_pressure was given together with k/yield_strength; give one or the other")
            return limiting_pressure
        if k is not None:
            check_positive("k", k, scalar=True)
        if yield_strength is None:
            known = [m.yield_strength for m in (particle, surface) if m is not None and m.yield_strength]
            if not known:
                raise ValueError(
                    "limiting_pressure is needed: give limiting_pressure=..., or yield_strength=... "
                    "(p_y = k * Y), or a material with a yield strength"
                )
            yield_strength = min(known)  # the softer body yields first
        return _k_times_yield(yield_strength, k)

    @classmethod
    def sphere_on_flat(
        cls,
        radius,
        density=None,
        effective_modulus=None,
        limiting_pressure=None,
        *,
        mass=None,
        yield_strength=None,
        k=None,
        label="",
    ) -> ContactPair:
        """A sphere of ``radius`` [m] hitting a flat, fixed surface, from effective values.

        Parameters
        ----------
        radius : float
            Particle radius [m] (``R* = R``).
        density : float
            Particle density [kg/m^3]; or give ``mass`` [kg] instead.
        effective_modulus : float
            ``E*`` [Pa].
        limiting_pressure : float
            ``p_y`` [Pa]; or give ``yield_strength`` ``Y`` [Pa] and optionally ``k``
            (default :data:`~microimpact.materials.DEFAULT_K` = 2.2): ``p_y = k Y``.
        mass : float, optional
            Particle mass [kg] (``m* = m``), instead of ``density``.
        yield_strength : float, optional
            Yield strength ``Y`` [Pa], instead of ``limiting_pressure``.
        k : float, optional
            ``p_y / Y`` [-], with ``yield_strength``.
        label : str, optional
            A name for tables and legends.

        Returns
        -------
        ContactPair
            The pair (``m* = m``, ``R* = R``).

        Raises
        ------
        ValueError
            If a value is out of range, or ``limiting_pressure`` is given together with
            ``k``/``yield_strength``, or neither is available.
        """
        if effective_modulus is None:
            raise ValueError("effective_modulus is needed for sphere_on_flat (or use from_materials)")
        radius = check_positive("radius", radius, scalar=True)
        if (density is None) == (mass is None):
            raise ValueError("give exactly one of density or mass")
        if density is not None:
            m = float(sphere_mass(radius, density))
        else:
            m = check_positive("mass", mass, scalar=True)
            density = m / _sphere_mass(radius, 1.0)
        p_y = cls._limiting_pressure(limiting_pressure, k, yield_strength)
        return cls(effective_modulus, radius, m, p_y, density=density, label=label)

    @classmethod
    def from_materials(
        cls,
        particle,
        surface,
        radius,
        *,
        limiting_pressure=None,
        k=None,
        yield_strength=None,
        label=None,
    ) -> ContactPair:
        """A sphere of a named material hitting a flat of another.

        ``E*`` follows from the two materials (seed, after eq. 2), ``m*`` is the
        particle's mass from its density.

        Parameters
        ----------
        particle, surface : str or Material
            Names from :data:`~microimpact.materials.MATERIALS` or :class:`Material` objects.
        radius : float
            Particle radius [m].
        limiting_pressure : float, optional
            ``p_y`` [Pa]. If not given, ``p_y = k Y`` with ``Y`` the smaller yield
            strength of the two materials (or ``yield_strength``).
        k : float, optional
            ``p_y / Y`` [-]; default :data:`~microimpact.materials.DEFAULT_K` = 2.2.
        yield_strength : float, optional
            Yield strength ``Y`` [Pa], overriding the materials'.
        label : str, optional
            A name for tables and legends; default ``"<particle> on <surface>"``.

        Returns
        -------
        ContactPair
            The pair, with ``particle`` and ``surface`` set.

        Raises
        ------
        ValueError
            If a value is out of range, or ``limiting_pressure`` is given together with
            ``k``/``yield_strength``, or neither is available.

        Examples
        --------
        >>> import microimpact as mi
        >>> pair = mi.ContactPair.from_materials("nh4fl", "silicon", radius=2.45e-6,
        ...                                      limiting_pressure=156e6)
        >>> round(pair.effective_modulus / 1e9, 3)
        1.309
        """
        p, s = get_material(particle), get_material(surface)
        E = float(effective_modulus(p.youngs_modulus, p.poisson_ratio, s.youngs_modulus, s.poisson_ratio))
        radius = check_positive("radius", radius, scalar=True)
        m = float(sphere_mass(radius, p.density))
        p_y = cls._limiting_pressure(limiting_pressure, k, yield_strength, p, s)
        return cls(E, radius, m, p_y, density=p.density, label=label or f"{p.name} on {s.name}", particle=p, surface=s)

    @classmethod
    def two_spheres(
        cls,
        material1,
        material2,
        radius1,
        radius2,
        *,
        limiting_pressure=None,
        k=None,
        yield_strength=None,
        label=None,
    ) -> ContactPair:
        """Two free spheres colliding head on; ``V`` is then their relative normal speed.

        ``R* = 1/(1/R1 + 1/R2)``, ``m* = 1/(1/m1 + 1/m2)``; the rebound velocity is
        the relative separation speed ``e V``.

        Parameters
        ----------
        material1, material2 : str or Material
            Names from :data:`~microimpact.materials.MATERIALS` or :class:`Material` objects.
        radius1, radius2 : float
            Radii of the two spheres [m].
        limiting_pressure : float, optional
            ``p_y`` [Pa]. If not given, ``p_y = k Y`` with ``Y`` the smaller yield
            strength of the two materials (or ``yield_strength``).
        k : float, optional
            ``p_y / Y`` [-]; default :data:`~microimpact.materials.DEFAULT_K` = 2.2.
        yield_strength : float, optional
            Yield strength ``Y`` [Pa], overriding the materials'.
        label : str, optional
            A name for tables and legends.

        Returns
        -------
        ContactPair
            The pair of effective values.

        Raises
        ------
        ValueError
            If a value is out of range, or ``limiting_pressure`` is given together with
            ``k``/``yield_strength``, or neither is available.
        """
        p, s = get_material(material1), get_material(material2)
        E = float(effective_modulus(p.youngs_modulus, p.poisson_ratio, s.youngs_modulus, s.poisson_ratio))
        r1 = check_positive("radius1", radius1, scalar=True)
        r2 = check_positive("radius2", radius2, scalar=True)
        m1, m2 = float(sphere_mass(r1, p.density)), float(sphere_mass(r2, s.density))
        p_y = cls._limiting_pressure(limiting_pressure, k, yield_strength, p, s)
        return cls(
            E,
            1.0 / (1.0 / r1 + 1.0 / r2),
            1.0 / (1.0 / m1 + 1.0 / m2),
            p_y,
            label=label or f"{p.name} sphere on {s.name} sphere",
            particle=p,
            surface=s,
        )

    @classmethod
    def paper_case(cls, name: str = "silicon") -> ContactPair:
        """The seed paper's NH4Fl particle (d = 4.9 um) on ``"silicon"`` or ``"mica"`` (Sec. 3.1).

        Parameters
        ----------
        name : {"silicon", "mica"}
            The case of :data:`~microimpact.materials.PAPER_CASES`.

        Returns
        -------
        ContactPair
            The sphere-on-flat pair with the paper's effective values.

        Raises
        ------
        ValueError
            If ``name`` is not one of the cases.

        Examples
        --------
        >>> round(ContactPair.paper_case("silicon").yield_velocity, 2)  # seed prints 7.59
        7.52
        """
        key = str(name).lower()
        if key not in PAPER_CASES:
            raise ValueError(f"case must be one of {', '.join(PAPER_CASES)}, got {name!r}")
        c = PAPER_CASES[key]
        return cls.sphere_on_flat(
            c["radius"], c["density"], c["effective_modulus"], c["limiting_pressure"], label=c["label"]
        )

    # ----------------------------------------------------------------- varying an input
    def material_inputs(self) -> tuple[dict, str]:
        """``{particle_modulus, particle_poisson, surface_modulus, surface_poisson}`` behind ``E*``, and where from.

        From the pair's materials when it has them. A pair made from effective values only (the
        paper cases) takes ``nu1 = nu2 =`` :data:`DEFAULT_POISSON` and ``E2 =``
        :data:`DEFAULT_SURFACE_MODULUS`, as the seed's Fig. 4 does, and the ``E1`` that gives its
        ``E*`` (``nan`` when no such ``E1`` exists).

        Returns
        -------
        dict, str
            The four inputs [Pa, -, Pa, -] and a sentence saying where they come from.
        """
        if self.particle is not None and self.surface is not None:
            p, s = self.particle, self.surface
            return (
                {
                    "particle_modulus": p.youngs_modulus,
                    "particle_poisson": p.poisson_ratio,
                    "surface_modulus": s.youngs_modulus,
                    "surface_poisson": s.poisson_ratio,
                },
                f"from the base pair's materials ({p.name}, {s.name})",
            )
        nu, E2 = DEFAULT_POISSON, DEFAULT_SURFACE_MODULUS
        E1 = _hertz.particle_modulus(self.effective_modulus, nu, E2, nu)
        return (
            {"particle_modulus": E1, "particle_poisson": nu, "surface_modulus": E2, "surface_poisson": nu},
            f"the base pair has effective values only: nu1 = nu2 = {nu}, E2 = {E2 / 1e9:g} GPa (as the seed's "
            f"Fig. 4) and E1 = {E1:.6g} Pa so that E* equals the base pair's {self.effective_modulus:.6g} Pa",
        )

    def effective_values(self, **inputs):
        """``(E*, R*, m*, p_y)`` of this pair with the named inputs changed, the derived values following.

        The one way microimpact varies a pair (sweeps, fits and figures use it). Values may be
        arrays; they broadcast.

        * ``effective_modulus``; or any of ``particle_modulus``, ``particle_poisson``,
          ``surface_modulus``, ``surface_poisson``: ``E* = 1/((1-nu1^2)/E1 + (1-nu2^2)/E2)``, the
          others from :meth:`material_inputs`;
        * ``radius`` (or ``diameter``) and/or ``density``: a sphere on a flat, ``R* = R`` and
          ``m* = 4/3 pi R^3 rho`` (the missing one from this pair); or ``effective_radius``,
          ``effective_mass`` directly;
        * ``limiting_pressure``; or ``yield_strength`` and/or ``k`` (``p_y = k Y``, the missing one
          from this pair); or ``yield_velocity`` (``p_y`` scaled so that ``V_y`` takes that value at
          the new ``E*``, ``R*``, ``m*``: ``V_y`` grows as ``p_y^(5/2)``, eq. 28).

        Parameters
        ----------
        **inputs : float or array_like
            Names from :data:`PAIR_INPUTS`.

        Returns
        -------
        tuple of ndarray
            ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], ``p_y`` [Pa].

        Raises
        ------
        ValueError
            An unknown name, two names that set the same value (naming both), an invalid value, or a
            value this pair cannot take (a density without a radius and density to start from).

        Examples
        --------
        >>> pair = ContactPair.paper_case("silicon")
        >>> E, R, m, p_y = pair.effective_values(limiting_pressure=[100e6, 200e6], radius=1e-6)
        >>> p_y.tolist(), float(R)
        ([100000000.0, 200000000.0], 1e-06)
        """
        unknown = sorted(set(inputs) - set(PAIR_INPUTS))
        if unknown:
            raise ValueError(f"cannot vary {unknown[0]!r}; a pair's inputs: {', '.join(PAIR_INPUTS)}")
        for group in _EXCLUSIVE:
            given = [n for n in group[0] if n in inputs]
            other = [n for n in group[1] if n in inputs]
            if given and other:
                raise ValueError(f"{given[0]} was given together with {other[0]}: they set the same value")
        if "diameter" in inputs and "radius" in inputs:
            raise ValueError("diameter was given together with radius: they set the same value")
        v = {k: _CHECKS.get(k, check_positive)(k, x) for k, x in inputs.items()}
        if "diameter" in v:
            v["radius"] = 0.5 * v.pop("diameter")
        # E*
        material = [k for k in _MATERIAL_INPUTS if k in v]
        if "effective_modulus" in v:
            E = v["effective_modulus"]
        elif material:
            defaults, _ = self.material_inputs()
            mat = {k: v.get(k, defaults[k]) for k in _MATERIAL_INPUTS}
            for k, x in mat.items():
                if k not in v and not math.isfinite(x):
                    raise ValueError(
                        f"{k} is needed: this pair's E* = {self.effective_modulus:g} Pa is too stiff to come "
                        f"from a surface of E2 = {DEFAULT_SURFACE_MODULUS:g} Pa"
                    )
            E = effective_modulus(
                mat["particle_modulus"], mat["particle_poisson"], mat["surface_modulus"], mat["surface_poisson"]
            )
        else:
            E = np.float64(self.effective_modulus)
        # R*, m*
        if "radius" in v or "density" in v:
            if "density" not in v and self.density is None:
                raise ValueError(
                    "density is needed: a radius or density change treats the particle as a sphere on a flat, "
                    "and this pair has no density (a two-sphere pair?)"
                )
            R = v.get("radius", np.float64(self.effective_radius))
            m = sphere_mass(R, v.get("density", self.density))
        else:
            R = v.get("effective_radius", np.float64(self.effective_radius))
            m = v.get("effective_mass", np.float64(self.effective_mass))
        # p_y
        if "limiting_pressure" in v:
            p_y = v["limiting_pressure"]
        elif "k" in v or "yield_strength" in v:
            Y = v["yield_strength"] if "yield_strength" in v else self._yield_strength()
            k = v["k"] if "k" in v else self.limiting_pressure / Y
            p_y = k * Y
        elif "yield_velocity" in v:
            if not math.isfinite(self.limiting_pressure):
                raise ValueError("yield_velocity can be set only on a pair with a finite limiting_pressure")
            Vy0 = impact.yield_velocity(self.limiting_pressure, E, R, m)
            p_y = _seed.limiting_pressure_for_yield_velocity(v["yield_velocity"], self.limiting_pressure, Vy0)
        else:
            p_y = np.float64(self.limiting_pressure)
        return E, R, m, p_y

    def vary(self, **inputs) -> ContactPair:
        """This pair with the named inputs changed and the derived values following (:meth:`effective_values`).

        Parameters
        ----------
        **inputs : float
            Names from :data:`PAIR_INPUTS`, one value each.

        Returns
        -------
        ContactPair
            The new pair (label kept; materials kept unless a material input changed); this one is unchanged.

        Examples
        --------
        >>> pair = ContactPair.paper_case("silicon")
        >>> round(pair.vary(density=2700.0).effective_mass / pair.effective_mass, 6)
        2.0
        """
        for k, x in inputs.items():
            if np.ndim(x) != 0:
                raise ValueError(f"{k} must be a single value to vary a pair, got shape {np.shape(x)}")
        E, R, m, p_y = (float(x) for x in self.effective_values(**inputs))
        rho = inputs.get("density", self.density)
        if ("radius" in inputs or "diameter" in inputs or "density" in inputs) and rho is not None:
            rho = float(rho)
        elif "effective_radius" in inputs or "effective_mass" in inputs:
            rho = None
        changed_material = any(k in inputs for k in (*_MATERIAL_INPUTS, "effective_modulus"))
        return replace(
            self,
            effective_modulus=E,
            effective_radius=R,
            effective_mass=m,
            limiting_pressure=p_y,
            density=rho,
            particle=None if changed_material else self.particle,
            surface=None if changed_material else self.surface,
        )

    def _yield_strength(self) -> float:
        known = [x.yield_strength for x in (self.particle, self.surface) if x is not None and x.yield_strength]
        if not known:
            raise ValueError(
                "yield_strength is needed: this pair has no material with a yield strength (give yield_strength=...)"
            )
        return min(known)

    def replace(self, **changes) -> ContactPair:
        """A copy with some effective values changed (e.g. ``limiting_pressure``).

        Parameters
        ----------
        **changes
            New values of the fields, by name, in their SI units
            (``effective_modulus`` [Pa], ``limiting_pressure`` [Pa], ...).

        Returns
        -------
        ContactPair
            The new pair; this one is unchanged.
        """
        return replace(self, **changes)

    def resized(self, radius=None, density=None) -> ContactPair:
        """The same sphere-on-flat pair with another particle radius and/or density.

        ``R* = R`` and ``m* = 4/3 pi R^3 rho`` are recomputed; ``E*`` and ``p_y`` are kept.

        Parameters
        ----------
        radius : float, optional
            New particle radius [m]; default this pair's.
        density : float, optional
            New particle density [kg/m^3]; default this pair's.

        Returns
        -------
        ContactPair
            The new pair; this one is unchanged.

        Raises
        ------
        ValueError
            If a value is not positive and finite, or the pair has no density and none is given
            (a two-sphere pair).

        Examples
        --------
        >>> pair = ContactPair.paper_case("silicon")
        >>> round(pair.resized(radius=1e-6).effective_mass / pair.effective_mass, 5)  # (1/2.45)^3
        0.068
        """
        if density is None and self.density is None:
            raise ValueError("density is needed to resize this pair (it has no particle density)")
        return self.vary(
            radius=self.effective_radius if radius is None else radius,
            **({} if density is None else {"density": density}),
        )

    def elastic_equivalent(self) -> ContactPair:
        """The same pair with no yielding (``p_y = inf``): the seed's "equivalent elastic impact" (Fig. 7).

        Returns
        -------
        ContactPair
            A copy with ``limiting_pressure = inf``.
        """
        return replace(self, limiting_pressure=math.inf, label=(self.label + " (elastic)").strip())

    # ----------------------------------------------------------------- yield point
    @functools.cached_property
    def _yield_point(self):
        # the core's scalar function, once per pair (the pair is frozen): pair.restitution(50.0) paid
        # for it at every call
        return _seed.yield_point(*self._args)

    @property
    def yield_velocity(self) -> float:
        """``V_y`` [m/s], the speed below which impacts are elastic (eq. 28, general energy form)."""
        return self._yield_point[2]

    @property
    def yield_approach(self) -> float:
        """``alpha_y`` [m] (eq. 5)."""
        return self._yield_point[0]

    @property
    def yield_force(self) -> float:
        """``P_y`` [N] (eq. 7)."""
        return self._yield_point[1]

    @property
    def yield_contact_radius(self) -> float:
        """``a_y`` [m] (eq. 4)."""
        return _seed.yield_contact_radius(self.limiting_pressure, self.effective_modulus, self.effective_radius)

    @property
    def _args(self):
        return (self.effective_modulus, self.effective_radius, self.effective_mass, self.limiting_pressure)

    # ----------------------------------------------------------------- force law
    def force(self, alpha, max_approach=None):
        """Contact force [N] at approach ``alpha`` [m]: loading, or unloading from ``max_approach`` (seed eqs. 2, 8, 10).

        Parameters
        ----------
        alpha : array_like
            Approach ``alpha`` [m].
        max_approach : array_like, optional
            Maximum approach ``alpha*`` [m] when unloading; None (default) for loading.

        Returns
        -------
        ndarray
            Contact force ``P`` [N], as :func:`microimpact.contact.contact_force`.
        """
        return contact.contact_force(
            alpha, self.effective_modulus, self.effective_radius, self.limiting_pressure, max_approach=max_approach
        )

    # ----------------------------------------------------------------- impact
    def impact(self, velocity, *, model: str = models.DEFAULT, warn: bool = True, **params) -> ImpactResult:
        """Outcome and contact times of impacts at ``velocity`` [m/s] (scalar or array).

        Issues a :class:`LargeStrainWarning` (unless ``warn=False``) when some
        impact reaches ``a*/R* > 0.3``; the ``large_strain`` attribute says which.

        Parameters
        ----------
        velocity : float or array_like
            Impact speed ``V`` [m/s], >= 0 and finite.
        model : str, optional
            Name of the impact model (:func:`microimpact.models.available`); default the seed's,
            ``"thornton_ning_2016"``. Fields a model does not define are NaN.
        warn : bool, optional
            Warn about large strain (default True).
        **params : float
            The model's own parameters by name (``microimpact.models.parameters(model)``).

        Returns
        -------
        ImpactResult
            Restitution, rebound speed, approaches, forces and contact times (seed
            eqs. 5-33 for the default model), shaped like ``velocity``.

        Raises
        ------
        ValueError
            If ``velocity`` is negative, NaN or infinite, the model is unknown or a parameter
            is missing, unknown or invalid.
        """
        mod = models.get(model)
        p = models.resolve_params(mod, params)
        if type(velocity) is float or type(velocity) is int:
            # One speed: the model's scalar outcome itself (microseconds; no numpy per field).
            V = float(velocity)
            if not 0.0 <= V < math.inf:
                check_velocity("velocity", V)
            values = mod.outcome(V, *self._args, p)
            res = ImpactResult._of_one(values)
            flagged = values[_LARGE] == 1.0
            vmin = V
        else:
            V = check_velocity("velocity", velocity)
            # the pair's floats as they are: numpy scalars would make a small array's Python loop
            # compute in numpy's scalar arithmetic, ~3x slower for a model that integrates
            out = impact.outcome_arrays(mod, V, *self._args, p)
            # arrays of V's shape, or 0-d ones for a 0-d V (then numpy scalars, as for one speed)
            res = ImpactResult._trusted(out if V.ndim else {k: v[()] for k, v in out.items()})
            flagged = res.any_large_strain
            vmin = None
        if warn and flagged and not _ignored(LargeStrainWarning):
            if vmin is None:
                vmin = np.min(np.asarray(res.velocity)[np.asarray(res.large_strain)])
            warnings.warn(
                f"contact radius exceeds {LARGE_STRAIN_RATIO} R* from V = {vmin:.4g} m/s: "
                "outside the small-strain range of the model (results flagged in .large_strain)",
                LargeStrainWarning,
                stacklevel=2,
            )
        limit = mod.ADHESION_LIMIT
        if limit is not None:
            mu, outside = self._adhesion_range(mod, limit, p, _adhesion.EQUILIBRIUM_SEPARATION)
            res.__dict__["tabor_parameter"] = mu
            res.__dict__["outside_adhesion_range"] = _TRUE if outside else _FALSE
            if warn and outside and not _ignored(AdhesionRangeWarning):
                warnings.warn(_adhesion_range_text(mod.NAME, limit, mu), AdhesionRangeWarning, stacklevel=2)
        return res

    def _adhesion_range(self, mod, limit, p, z0):
        G = float(mod.work_of_adhesion(p))
        mu = _adhesion.tabor_parameter(self.effective_modulus, self.effective_radius, G, z0) if G > 0.0 else 0.0
        outside = mu < _adhesion.TABOR_JKR if limit == "JKR" else mu > _adhesion.TABOR_DMT
        return mu, bool(outside and G > 0.0)

    def adhesion_range(self, *, model: str, equilibrium_separation: float | None = None, **params) -> dict:
        """Tabor's parameter of this pair and an adhesive model's work of adhesion, and whether the
        pair lies in the adhesion limit the model is written for.

        ``mu = (R* G^2/(E*^2 z_0^3))^(1/3)`` (:func:`microimpact.core.adhesion.tabor_parameter`):
        the JKR limit (Thornton & Ning's laws, LAMMPS' ``jkr``) needs ``mu > 5``, the DMT limit
        (LAMMPS' ``dmt``) ``mu < 0.1``; between them neither is exact. :meth:`impact` flags a pair
        outside its model's limit (``outside_adhesion_range``, an :class:`AdhesionRangeWarning`).

        Parameters
        ----------
        model : str
            An adhesive model (one that declares its limit, ``ADHESION_LIMIT``).
        equilibrium_separation : float, optional
            ``z_0`` [m], the range of the surface forces; default 0.3 nm
            (:data:`microimpact.core.adhesion.EQUILIBRIUM_SEPARATION`).
        **params : float
            The model's parameters by name (its work of adhesion or surface energy [J/m^2]).

        Returns
        -------
        dict
            ``tabor_parameter`` [-], ``limit`` (``"JKR"`` or ``"DMT"``), ``inside`` (bool),
            ``work_of_adhesion`` ``G`` [J/m^2], ``equilibrium_separation`` [m].

        Raises
        ------
        ValueError
            If the model is unknown or not adhesive, a parameter is invalid, or
            ``equilibrium_separation`` is not positive and finite.

        Examples
        --------
        >>> pair = ContactPair.paper_case("silicon")
        >>> r = pair.adhesion_range(model="jkr_elastic_adhesive", surface_energy=0.05)
        >>> r["limit"], round(r["tabor_parameter"], 2), r["inside"]
        ('JKR', 8.09, True)
        """
        mod = models.get(model)
        limit = mod.ADHESION_LIMIT
        if limit is None:
            raise ValueError(f"model {model!r} has no adhesion limit (it is not a JKR or DMT adhesive law)")
        p = models.resolve_params(mod, params)
        z0 = _adhesion.EQUILIBRIUM_SEPARATION if equilibrium_separation is None else equilibrium_separation
        z0 = float(check_positive("equilibrium_separation", z0, scalar=True))
        if not math.isfinite(z0):
            raise ValueError(f"equilibrium_separation must be positive and finite, got {equilibrium_separation!r}")
        mu, outside = self._adhesion_range(mod, limit, p, z0)
        return {
            "tabor_parameter": mu,
            "limit": limit,
            "inside": not outside,
            "work_of_adhesion": float(mod.work_of_adhesion(p)),
            "equilibrium_separation": z0,
        }

    def history(
        self,
        velocity,
        n: int = 1001,
        times=None,
        method: str | None = None,
        *,
        model: str = models.DEFAULT,
        **params,
    ) -> ImpactHistory:
        """Time history of one impact at ``velocity`` [m/s]: approach, velocity, force, stage (eqs. 17-26).

        Parameters
        ----------
        velocity : float
            Impact speed [m/s], positive and finite.
        n : int
            Number of points spaced uniformly from first contact to separation
            (the stage boundaries are added).
        times : array_like, optional
            Times [s] since first contact instead; outside the contact the
            bodies fly apart (stage 0, force 0).
        method : {"closed", "ode"}, optional
            Closed form (:func:`~microimpact.dynamics.impact_history`; the seed's model only) or
            numerical integration of Newton's equation with the model's own force law
            (:func:`~microimpact.dynamics.integrate_impact` for the seed's model, its three-stage
            cross-check; :func:`~microimpact.dynamics.integrate_model` for the others). Default:
            ``"closed"`` where the model has a closed-form history, ``"ode"`` otherwise.
        model : str, optional
            Name of the impact model (:func:`microimpact.models.available`); default the seed's.
        **params : float
            The model's own parameters by name (``microimpact.models.parameters(model)``).

        Returns
        -------
        ImpactHistory

        Raises
        ------
        ValueError
            Bad speed, unknown model or parameter, ``method="closed"`` for a model without a
            closed-form history (naming both), or a particle that sticks (no finite history).

        Examples
        --------
        >>> pair = ContactPair.paper_case("silicon")
        >>> h = pair.history(50.0)
        >>> round(h.loading_time * 1e6, 5), round(h.unloading_time * 1e6, 5)  # seed: 0.01365, 0.01112 us
        (0.01364, 0.01112)
        >>> h = pair.history(50.0, model="liggghts_thornton_ning")  # integrated: no closed-form history
        >>> h.method, round(h.rebound_velocity / 50.0, 4)
        ('ode', 0.6905)
        """
        mod = models.get(model)
        from . import dynamics  # imported here: one impact (and the CLI) need no history machinery

        closed = mod.NAME in dynamics.CLOSED_FORM_HISTORY
        if method is None:
            method = "closed" if closed else "ode"
        if method not in ("closed", "ode"):
            raise ValueError(f"method must be 'closed' or 'ode', got {method!r}")
        if method == "closed" and not closed:
            raise ValueError(
                f"model {mod.NAME!r} has no closed-form history (method 'closed'); use method='ode', "
                "the integration of its force law"
            )
        if mod.NAME == models.DEFAULT:
            models.resolve_params(mod, params)  # the seed's takes none: refuse any
            fn = dynamics.impact_history if method == "closed" else dynamics.integrate_impact
            data = fn(velocity, *self._args, n=n, times=times)
        else:
            data = dynamics.integrate_model(mod.NAME, velocity, *self._args, params, n=n, times=times)
        return dynamics.ImpactHistory.from_dict(data, method=method)

    def sticking_velocity(self, diameter=None, *, model: str | None = None, **params):
        """The capture (sticking) velocity [m/s]: the particle sticks (``e = 0``) at and below it.

        Parameters
        ----------
        diameter : float or array_like, optional
            Particle diameters [m] (positive, finite) at which to evaluate it, the pair resized to
            each (:meth:`resized`: ``E*``, ``p_y`` and density kept; a sphere-on-flat pair); default
            this pair's particle.
        model : str, optional
            An adhesive model of :func:`microimpact.models.available` that defines its sticking
            velocity (``"thornton_ning_1998_adhesive_plastic"``, Thornton & Ning's whole law, the
            default: the model that declares ``WALL_ADHESION``, :func:`microimpact.core.models.whole_law`;
            ``"thornton_ning_1998_elastic_adhesive"``; ``"jkr_elastic_adhesive"``), or
            ``"additive"``: Thornton & Ning's additive rule (their eq. 78, the seed's plastic loss
            plus the elastic adhesive one, :func:`microimpact.core.adhesion.restitution`), which
            takes ``work_of_adhesion``.
        **params : float
            The model's parameters by name (``work_of_adhesion`` [J/m^2] for Thornton & Ning's).

        Returns
        -------
        float or ndarray
            ``V_s`` [m/s], a float for one diameter (or none), else shaped like ``diameter``.

        Raises
        ------
        ValueError
            If the model is unknown or has no sticking velocity, a parameter is missing or invalid,
            a diameter is not positive and finite, or diameters are given for a pair without density.

        Examples
        --------
        >>> pair = ContactPair.paper_case("silicon")
        >>> round(pair.sticking_velocity(work_of_adhesion=0.1), 4)  # V_s < V_y: Thornton & Ning's eq. 54
        0.3184
        >>> pair.sticking_velocity([0.1e-6, 0.2e-6], work_of_adhesion=1.0).round(1)
        array([253.5,  94.5])
        """
        if model is None:
            model = models.whole_law()
        if model == "additive":
            from .core import adhesion as _adh

            unknown = sorted(set(params) - {"work_of_adhesion"})
            if unknown or "work_of_adhesion" not in params:
                raise ValueError(
                    "the additive rule takes one parameter, work_of_adhesion"
                    + (f"; got {unknown[0]!r}" if unknown else " (no default)")
                )
            G = params["work_of_adhesion"]
            G = float(check_nonnegative("work_of_adhesion", G))

            def one(pair):
                E, R, m, p_y = pair._args
                return _adh.capture_velocity(_seed.yield_point(E, R, m, p_y)[2], _adh.sticking_velocity(G, E, R, m))

        else:
            mod = models.get(model)
            fn = mod.sticking_velocity
            if fn is None:
                names = [n for n in models.available() if models.get(n).sticking_velocity is not None]
                raise ValueError(
                    f"model {model!r} has no sticking velocity; models that have one: {', '.join(names)}, additive"
                )
            p = models.resolve_params(mod, params)

            def one(pair):
                return fn(*pair._args, p)

        if diameter is None:
            return float(one(self))
        d = check_positive("diameter", diameter)
        if self.density is None:
            raise ValueError("diameters need a pair with a particle density (a sphere on a flat)")
        out = np.array([one(self.resized(radius=0.5 * x)) for x in d.ravel()]).reshape(d.shape)
        return float(out) if np.ndim(diameter) == 0 else out

    def restitution(self, velocity, *, out=None):
        """Restitution coefficient only (seed eq. 27), the fastest path.

        Parameters
        ----------
        velocity : array_like
            Impact speed ``V`` [m/s], >= 0.
        out : ndarray, optional
            Float64 array, C-contiguous, shaped like ``velocity``, to write ``e`` into.

        Returns
        -------
        numpy scalar or ndarray
            Coefficient of restitution ``e`` [-], shaped like ``velocity``.
        """
        if out is not None:
            return impact.restitution_coefficient(velocity, self.yield_velocity, out=out)
        if type(velocity) is float or type(velocity) is int:  # one speed: the core's scalar function itself
            V = float(velocity)
            if not 0.0 <= V < math.inf:
                check_velocity("velocity", V)
            # V_y read from the cached yield point, not through the property (0.1 us of a 0.8 us call)
            return np.float64(_seed.restitution_at(V, self._yield_point[2]))
        # the pair's own V_y was checked with the pair: only the speeds are (a fixed cost per call)
        V = check_velocity("velocity", velocity)
        return _scalar_or_array(_evaluate(_seed.restitution_at, V, self._yield_point[2])[0])

    def dem_time_step(self, velocity, *, model: str = models.DEFAULT, steps_per_contact=50, **params) -> float:
        """A DEM time step [s] that resolves the contact: the shortest contact time of ``model`` at
        the speeds ``velocity`` [m/s] over ``steps_per_contact``.

        How fine is fine enough, measured in LAMMPS 22 Jul 2025 and LIGGGHTS-PUBLIC 3.8.0 on single
        impacts of the calibrated laws (``tests/test_dem.py``, :mod:`microimpact.dem`): both codes
        integrate with velocity Verlet and evaluate the damping force with the half-step velocity, so
        for the damped laws (linear spring-dashpot, Hertz with Tsuji's or viscoelastic damping) the
        relative error of ``e`` and of the contact time falls as ``c/N`` with ``N`` steps per contact,
        where ``c`` grows with the damping: 0.01-0.06 for ``e = 0.9``, 0.05-0.19 for ``e = 0.7``,
        0.18-0.71 for ``e = 0.5`` and 0.3-0.84 for ``e = 0.3`` (LAMMPS, the three laws). So ``N = 50``
        (the default) gives ``e`` within about 0.4 % for ``e >= 0.7`` and 2 % for ``e >= 0.3``; for
        a relative accuracy ``tol`` take ``N = 1/tol``. The undamped hysteretic spring is off by
        about 1e-7 at ``N = 5000``. Hertz's contact time falls with the speed (``V^(-1/5)``), so the
        fastest impact sets the step.

        Parameters
        ----------
        velocity : float or array_like
            Impact speed(s) [m/s], > 0.
        model : str, optional
            The contact law the DEM code runs (a model of :func:`microimpact.models.available`),
            default the seed's; ``**params`` are its parameters, as for :meth:`impact`.
        steps_per_contact : float, optional
            Steps per contact time, >= 1 (default 50).

        Returns
        -------
        float
            The time step [s].

        Raises
        ------
        ValueError
            A bad speed or step count (named), or a law without a finite contact time there.
        """
        if isinstance(steps_per_contact, bool) or not isinstance(
            steps_per_contact, (int, float, np.integer, np.floating)
        ):
            raise ValueError(f"steps_per_contact must be a number >= 1, got {steps_per_contact!r}")
        if not (steps_per_contact >= 1.0 and math.isfinite(steps_per_contact)):
            raise ValueError(f"steps_per_contact must be a finite number >= 1, got {steps_per_contact!r}")
        V = np.atleast_1d(check_velocity("velocity", velocity))
        if not np.all(V > 0.0):
            raise ValueError(f"velocity must be positive (no contact at 0), got {float(V[V <= 0.0][0])!r}")
        tc = np.asarray(self.impact(V, model=model, warn=False, **params).contact_time, dtype=float)
        if not np.all(np.isfinite(tc) & (tc > 0.0)):
            bad = float(V.ravel()[~(np.isfinite(tc) & (tc > 0.0)).ravel()][0])
            raise ValueError(f"model {model!r} has no finite contact time at velocity {bad!r}: no step resolves it")
        return float(np.min(tc)) / float(steps_per_contact)

    def ning_loading_time(self) -> float:
        """Ning's high-speed loading time [s] (seed eq. 31).

        Returns
        -------
        float
            ``t_L = (pi/2)(m*/(pi p_y R*))^(1/2)`` [s].
        """
        from . import dynamics

        return float(dynamics.ning_loading_time(self.limiting_pressure, self.effective_radius, self.effective_mass))

    def deresiewicz_contact_time(self, velocity):
        """Deresiewicz's elastic contact time [s] (seed eq. 30).

        Parameters
        ----------
        velocity : array_like
            Impact speed ``V`` [m/s], >= 0.

        Returns
        -------
        numpy scalar or ndarray
            ``t_c = 2.87 (m*^2/(R* E*^2 V))^(1/5)`` [s], shaped like ``velocity``.
        """
        from . import dynamics

        return _scalar_or_array(
            dynamics.deresiewicz_contact_time(
                velocity, self.effective_modulus, self.effective_radius, self.effective_mass
            )
        )

    def _repr_html_(self) -> str:
        """The pair's effective values and yield point as a table (notebooks)."""
        import html

        rows = [
            ("E*", self.effective_modulus, "Pa"),
            ("R*", self.effective_radius, "m"),
            ("m*", self.effective_mass, "kg"),
            ("p_y", self.limiting_pressure, "Pa"),
        ]
        if self.density is not None:
            rows.append(("density", self.density, "kg/m^3"))
        if math.isfinite(self.limiting_pressure):
            rows += [("V_y", self.yield_velocity, "m/s"), ("alpha_y", self.yield_approach, "m")]
        body = "".join(f"<tr><td>{k}</td><td>{v:.6g}</td><td>{u}</td></tr>" for k, v, u in rows)
        return (
            f"<table><caption>ContactPair {html.escape(self.label or 'unnamed')}</caption>"
            f"<tr><th>quantity</th><th>value</th><th>unit</th></tr>{body}</table>"
        )

    def describe(self) -> str:
        """A few lines naming the pair's effective values and yield point.

        Returns
        -------
        str
            Text with ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], ``p_y`` [Pa] and the yield point.
        """
        lines = [
            f"pair: {self.label or 'unnamed'}",
            f"  E* = {self.effective_modulus:.6g} Pa   R* = {self.effective_radius:.6g} m   "
            f"m* = {self.effective_mass:.6g} kg   p_y = {self.limiting_pressure:.6g} Pa",
        ]
        if math.isfinite(self.limiting_pressure):
            lines.append(
                f"  yield: V_y = {self.yield_velocity:.6g} m/s   alpha_y = {self.yield_approach:.6g} m   "
                f"P_y = {self.yield_force:.6g} N"
            )
        return "\n".join(lines)
