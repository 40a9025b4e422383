"""The object layer users hold: :class:`ContactPair` and :class:`ImpactResult`.

A :class:`ContactPair` stores the four effective values the model needs
(``E*``, ``R*``, ``m*``, ``p_y``) and where they came from; every method
delegates to the vectorized functions of :mod:`microimpact.contact`,
:mod:`microimpact.impact` and :mod:`microimpact.dynamics`.

A package by subject; the class holds the interface and its documentation, each method's work is
done in the room of its subject: ``_result`` the result and its warnings, ``_construct`` the
constructors, ``_inputs`` a pair's inputs and how varying one moves the effective values,
``_impact`` the impacts by model (outcome, restitution, DEM time step, history), ``_adhesion``
Tabor's range and the sticking velocity, ``_describe`` the text and the notebook table.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

from .. import contact
from .._validation import TINY_LIMITING_PRESSURE, TINY_NORMAL, check_pair_scales, check_positive, check_yield_velocity
from ..core import models
from ..core.models import thornton_ning_2016 as _seed
from ..materials import Material
from . import _adhesion, _construct, _describe, _impact, _inputs
from ._inputs import DEFAULT_POISSON, DEFAULT_SURFACE_MODULUS, PAIR_INPUTS
from ._result import RESULT_FIELDS as RESULT_FIELDS  # the sweep and the CLI table read it here
from ._result import AdhesionRangeWarning, ImpactResult, LargeStrainWarning

if TYPE_CHECKING:  # the history machinery loads only when a history is asked for
    from ..dynamics import ImpactHistory

__all__ = [
    "ContactPair",
    "ImpactResult",
    "LargeStrainWarning",
    "AdhesionRangeWarning",
    "PAIR_INPUTS",
    "DEFAULT_POISSON",
    "DEFAULT_SURFACE_MODULUS",
]


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
        # every model divides by V_y (V/V_y, eqs. 22-27): a pair whose V_y is no normal float
        # (E* = 1e308 Pa: alpha_y underflows) is refused here, naming the input, not divided by later.
        # The pair's own yield point (computed once, kept) decides; the array check names the input.
        try:
            V_y = self._yield_point[2]
        except (ZeroDivisionError, OverflowError):
            V_y = math.nan
        if not V_y >= TINY_NORMAL:
            check_pair_scales(*self._args)
        if self.density is not None:
            object.__setattr__(self, "density", check_positive("density", self.density, scalar=True))

    # ----------------------------------------------------------------- constructors
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
        return _construct.sphere_on_flat(
            cls, radius, density, effective_modulus, limiting_pressure, mass, yield_strength, k, label
        )

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
        return _construct.from_materials(cls, particle, surface, radius, limiting_pressure, k, yield_strength, label)

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
        return _construct.two_spheres(
            cls, material1, material2, radius1, radius2, limiting_pressure, k, yield_strength, label
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
        return _construct.paper_case(cls, name)

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
        return _inputs.material_inputs(self)

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
        return _inputs.effective_values(self, inputs)

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
        return _inputs.vary(self, inputs)

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
        return _impact.impact(self._args, velocity, model, warn, params)

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
        return _adhesion.adhesion_range(self, model, equilibrium_separation, params)

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
            Closed form, where the model's face declares one (``closed_form_history``,
            :mod:`microimpact.models._base`: the seed's is :func:`~microimpact.dynamics.impact_history`;
            :data:`~microimpact.dynamics.CLOSED_FORM_HISTORY`), or numerical integration of
            Newton's equation with the model's own force law
            (:func:`~microimpact.dynamics.integrate_model`, for the seed its three-stage
            cross-check). Default: ``"closed"`` where the model has a closed-form history, ``"ode"``
            otherwise.
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
        return _impact.history(self._args, velocity, n, times, method, model, params)

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
        return _adhesion.sticking_velocity(self, diameter, model, params)

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
        # V_y read from the cached yield point, not through the property (a tenth of a one-speed call)
        return _impact.restitution(velocity, self._yield_point[2], out)

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
        return _impact.dem_time_step(self, velocity, model, steps_per_contact, params)

    def ning_loading_time(self) -> float:
        """Ning's high-speed loading time [s] (seed eq. 31).

        Returns
        -------
        float
            ``t_L = (pi/2)(m*/(pi p_y R*))^(1/2)`` [s].
        """
        return _impact.ning_loading_time(self)

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
        return _impact.deresiewicz_contact_time(self, velocity)

    def _repr_html_(self) -> str:
        """The pair's effective values and yield point as a table (notebooks)."""
        return _describe.html_table(self)

    def describe(self) -> str:
        """A few lines naming the pair's effective values and yield point.

        Returns
        -------
        str
            Text with ``E*`` [Pa], ``R*`` [m], ``m*`` [kg], ``p_y`` [Pa] and the yield point.
        """
        return _describe.describe(self)
