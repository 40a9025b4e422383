"""What an impact gives: :class:`ImpactResult` (every field of the outcome, as arrays or numpy
scalars) and the warnings that flag a result outside its model's range."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from ..core import quantities
from ..core.quantities import FLAG_FIELDS, OUTCOME_FIELDS

__all__ = [
    "ImpactResult",
    "LargeStrainWarning",
    "AdhesionRangeWarning",
    "RESULT_FIELDS",
    "TRUE",
    "FALSE",
    "LARGE",
    "trusted_result",
    "one_result",
]


class LargeStrainWarning(UserWarning):
    """The contact radius exceeds the small-strain range of the model (``a/R* > 0.3``)."""


class AdhesionRangeWarning(UserWarning):
    """The pair lies outside the adhesion limit (JKR or DMT) its adhesive model is written for, by
    Tabor's parameter (:meth:`ContactPair.adhesion_range`)."""


#: The flags of a result as numpy booleans (as numpy gives them for an array of results).
TRUE, FALSE = np.bool_(True), np.bool_(False)
#: Where the large-strain flag stands in the outcome tuple of a model.
LARGE = OUTCOME_FIELDS.index("large_strain")
_FLAG_INDEX = tuple((OUTCOME_FIELDS.index(k), k) for k in FLAG_FIELDS)


class _OneImpactField:
    """A field of :class:`ImpactResult` not yet read (a one-impact result, :func:`one_result`).

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
            d[flag] = TRUE if one[i] == 1.0 else FALSE
        return d[self.name]


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
    outside_validity : ndarray of bool
        True where the impact lies outside what the model's published law can say (its
        ``outside_validity`` hook: an unloading that would return more work than the loading
        stored, where ``e = 1`` is returned, or a contact radius beyond the sphere's); flagged, not
        refused, with an :class:`~microimpact.models.OutsideValidityWarning`. False for the models
        without the hook.
    """

    #: Set by :meth:`ContactPair.impact` for an adhesive model (not a field of the outcome table).
    tabor_parameter = math.nan
    #: Set by :meth:`ContactPair.impact` for an adhesive model.
    outside_adhesion_range = FALSE
    #: Set by :meth:`ContactPair.impact` for a model with an ``outside_validity`` hook.
    outside_validity = FALSE

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


def trusted_result(values: dict) -> ImpactResult:
    """An :class:`ImpactResult` from a complete dict of already-checked values, skipping the dataclass
    ``__init__`` (hot path)."""
    obj = object.__new__(ImpactResult)
    obj.__dict__.update(values)
    return obj


def one_result(values: tuple) -> ImpactResult:
    """One impact from the core's tuple (in the order of ``OUTCOME_FIELDS``), kept as it is until a
    field is read: then all 18 become numpy scalars (flags numpy booleans) at once, written into the
    instance (the hot path of ``pair.impact(50.0)``: building them cost about half the outcome)."""
    obj = object.__new__(ImpactResult)
    obj.__dict__["_one"] = values
    return obj


# Their home is the package (pickles and reprs name microimpact.pair, where users import them from).
for _cls in (ImpactResult, LargeStrainWarning, AdhesionRangeWarning):
    _cls.__module__ = "microimpact.pair"
del _cls
