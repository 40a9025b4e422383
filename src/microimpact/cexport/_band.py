"""A fit's estimate and the two ends of its confidence band, exported as tables and C functions."""

from __future__ import annotations

import math

import numpy as np

from .._validation import check_nonnegative
from ._common import check_size_names, comment_text, sized_pair
from ._csource import generate_c_source
from ._tables import DEFAULT_SPEEDS, DEFAULT_V_OVER_VY, DEFAULT_VS_OVER_VY, write_size_table, write_universal_table

__all__ = ["BAND_ENDS", "band_pairs", "write_band"]


#: Names of the three parameter sets :func:`write_band` exports, in file names.
BAND_ENDS = ("estimate", "lower", "upper")


def band_pairs(fit) -> list[dict]:
    """The fitted pair at the estimate and at the two ends of the fit's confidence band.

    For each of :data:`BAND_ENDS` a dict with ``"name"``, ``"pair"`` (:class:`ContactPair`),
    ``"parameter"``, ``"value"`` (SI) and ``"text"`` (one line saying which end, the
    parameter's value and the confidence). ``"lower"`` and ``"upper"`` name the ends of the
    *restitution* band, which is what a CFD run with the band's ends needs: the seed's
    ``e`` depends on the free parameter only through ``V/V_y`` and grows with ``V_y``, so
    the end with the smaller ``V_y`` gives the lower ``e`` at every speed (for
    ``limiting_pressure`` that is the lower end of its interval; for ``density`` the upper
    one).

    Parameters
    ----------
    fit : FitResult
        A fit of the seed's model (:func:`~microimpact.fitting.fit_restitution`) with one
        free parameter and a closed confidence interval.

    Returns
    -------
    list of dict

    Raises
    ------
    ValueError
        A model that does not declare ``C_EXPORT`` (the export writes the seed's ``e_p(V/V_y)``,
        :mod:`microimpact.core.models`), not one free
        parameter, or an interval open at one end (the data do not bound it; no table can
        stand for that end).
    """
    from ..core import models
    from ..fitting import FREE_PARAMETERS, FitResult

    if not isinstance(fit, FitResult):
        raise ValueError(f"fit must be a FitResult (from fit_restitution), got {type(fit).__name__}")
    writable = [n for n in models.available() if models.get(n).C_EXPORT]  # the law the C source writes
    if fit.model not in writable:
        raise ValueError(
            f"fit: the export writes the seed's e_p(V/V_y), the law declaring C_EXPORT ({', '.join(writable)}); "
            f"this fit is of {fit.model!r}"
        )
    if len(fit.params) != 1:
        raise ValueError(f"fit: the band's ends need exactly one free parameter, this fit has {len(fit.params)}")
    name = fit.free[0]
    unit = FREE_PARAMETERS.get(name, {}).get("si", "") or "-"
    conf = f"{100.0 * fit.confidence:g} %"
    ends = fit.band_ends()
    for end in ends:
        if not (0.0 < end["value"] < math.inf):
            raise ValueError(
                f"fit: the {end['end']} end of the {conf} interval of {name} is open ({end['value']:g}): the data do "
                "not bound it, so no table can stand for it (lower the confidence or add points above V_y)"
            )
    if ends[0]["pair"].yield_velocity > ends[1]["pair"].yield_velocity:
        ends = ends[::-1]  # the smaller V_y gives the lower restitution
    out = [
        {
            "name": "estimate",
            "pair": fit.pair,
            "parameter": name,
            "value": float(fit.params[name]),
            "text": f"best estimate of the fit: {name} = {fit.params[name]:.10g} {unit} "
            f"(V_y = {fit.pair.yield_velocity:.6g} m/s); the {conf} confidence band is in the *_lower and *_upper files",
        }
    ]
    for band_end, end in zip(("lower", "upper"), ends):
        out.append(
            {
                "name": band_end,
                "pair": end["pair"],
                "parameter": name,
                "value": end["value"],
                "text": f"{band_end} end of the {conf} confidence band of e(V): {name} = {end['value']:.10g} {unit} "
                f"({end['end']} end of its {conf} interval, {fit.interval}; V_y = {end['pair'].yield_velocity:.6g} m/s)",
            }
        )
    return out


def write_band(
    fit,
    directory,
    diameters=None,
    velocities=None,
    *,
    work_of_adhesion=0.0,
    friction=0.0,
    v_over_vy=None,
    vs_over_vy_values=DEFAULT_VS_OVER_VY,
    c_source=True,
    tangential="rigid",
    poisson_ratio=None,
    effective_shear_modulus=None,
    source=None,
    inputs=(),
    adhesion="additive",
):
    """Write the tables and C source of a fit at its estimate and at both ends of its band.

    So that a CFD user can run with the band's ends (:func:`band_pairs` says which
    parameter value each end is). One output folder (:func:`microimpact.io.owned_directory`:
    it owns only what it wrote, listed in its manifest ``.microimpact-manifest.json``;
    nothing is written unless every input is good):

    * ``README.txt``: the fit, the confidence, and which file is which;
    * ``restitution_vs_v_over_vy.csv``: the dimensionless table (the same for every end:
      ``e`` depends on the fit only through ``V_y``);
    * ``restitution_d<diameter>um_<end>.csv`` for each diameter and each ``<end>`` of
      ``estimate``, ``lower``, ``upper`` (of the restitution band), as :func:`write_tables`;
    * ``microimpact_wall_<end>.c`` (unless ``c_source=False``), as :func:`write_c_source`.

    Every file has a comment line saying which end it is and at which confidence.

    Parameters
    ----------
    fit : FitResult
        A fit of the seed's model with one free parameter (:func:`band_pairs`); its pair
        needs a density (the tables are rescaled to each diameter).
    directory : path
        The output folder (written into only when it holds nothing but files an earlier export wrote).
    diameters, velocities, work_of_adhesion, v_over_vy, vs_over_vy_values
        As :func:`write_tables` (diameters [m], speeds [m/s], ``G`` [J/m^2]).
    friction, tangential, poisson_ratio, effective_shear_modulus
        As :func:`generate_c_source` (``mu`` [-], ``G*`` [Pa]); C source only.
    adhesion : str, optional
        ``"additive"`` (default) or ``"thornton_ning_1998_adhesive_plastic"``: the normal restitution with
        adhesion of the tables and the C files, as :func:`write_tables` and :func:`generate_c_source`.
    c_source : bool
        Write the C files (default True).
    source : str, optional
        Where the data came from (a file name), quoted in the comments.
    inputs : sequence of path, optional
        Files the caller read (the fit's data): refused when inside ``directory``.

    Returns
    -------
    list of pathlib.Path
        The files written (at their final place).

    Examples
    --------
    >>> import numpy as np, tempfile, microimpact as mi
    >>> from microimpact.fitting import fit_restitution
    >>> pair = mi.ContactPair.paper_case("silicon")
    >>> V = np.array([5.0, 10.0, 20.0, 40.0, 80.0])
    >>> fit = fit_restitution(V, pair.restitution(V) + [0.0, 0.01, -0.01, 0.005, -0.005], pair)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     files = write_band(fit, tmp + "/band")
    >>> sorted(p.name for p in files)[:3]
    ['README.txt', 'microimpact_wall_estimate.c', 'microimpact_wall_lower.c']
    """
    from pathlib import Path

    from ..adhesion import check_adhesion_rule
    from ..io import atomic_write, owned_directory

    check_adhesion_rule(adhesion)
    ends = band_pairs(fit)
    if not c_source and (tangential != "rigid" or poisson_ratio is not None or effective_shear_modulus is not None):
        raise ValueError("tangential, poisson_ratio and effective_shear_modulus set the C source: c_source=False")
    mu = float(check_nonnegative("friction", friction))
    G = float(check_nonnegative("work_of_adhesion", work_of_adhesion))
    if math.isinf(G):
        raise ValueError(f"work_of_adhesion must be finite, got {work_of_adhesion!r}")
    v = DEFAULT_V_OVER_VY if v_over_vy is None else np.atleast_1d(check_nonnegative("v_over_vy", v_over_vy))
    s = np.atleast_1d(check_nonnegative("vs_over_vy_values", vs_over_vy_values)).reshape(-1)
    V = DEFAULT_SPEEDS if velocities is None else np.atleast_1d(check_nonnegative("velocities", velocities))
    where = f" to {comment_text(source)}" if source else ""
    # every input checked and every text made before anything is written
    jobs = []
    sources = {}
    for end in ends:
        pair = end["pair"]
        sizes = [2.0 * pair.effective_radius] if diameters is None else list(np.atleast_1d(diameters))
        check_size_names(sizes)
        jobs += [(end, d, sized_pair(pair, d)) for d in sizes]
        if c_source:
            sources[end["name"]] = generate_c_source(
                pair,
                work_of_adhesion=G,
                friction=mu,
                tangential=tangential,
                poisson_ratio=poisson_ratio,
                effective_shear_modulus=effective_shear_modulus,
                comment=f"fit{where}: {end['text']}",
                adhesion=adhesion,
            )
    readme = _band_readme(fit, ends, where, c_source, adhesion)
    target = Path(directory)
    names = []
    with owned_directory(target, "export", inputs=inputs) as tmp:
        with atomic_write(tmp / "README.txt") as fh:
            fh.write(readme)
        names.append("README.txt")
        names.append(write_universal_table(tmp, v, s, adhesion).name)
        for end, d, p in jobs:
            name = f"restitution_d{float(d) * 1e6:g}um_{end['name']}.csv"
            write_size_table(
                tmp / name, end["pair"], d, p, V, G, extra=[f"fit{where}: {end['text']}"], adhesion=adhesion
            )
            names.append(name)
        for end_name, text in sources.items():
            with atomic_write(tmp / f"microimpact_wall_{end_name}.c") as fh:
                fh.write(text)
            names.append(f"microimpact_wall_{end_name}.c")
    return [target / n for n in names]


def _band_readme(fit, ends, where, c_source, adhesion="additive") -> str:
    name = ends[0]["parameter"]
    lines = [
        f"microimpact export of a fit{where}: restitution tables"
        + (" and C wall functions" if c_source else "")
        + f" at the estimate and at both ends of the {100.0 * fit.confidence:g} % confidence band.",
        "",
        f"Model: {fit.model} (seed eqs. 22, 27, 28); free parameter: {name}; {fit.n_points} points; "
        f"loss {fit.loss}; interval {fit.interval}.",
        "",
    ]
    if adhesion != "additive":
        lines[-1:-1] = [
            f"Adhesion in the tables and C files: {adhesion} (Thornton & Ning's whole law, through its table)."
        ]
    for end in ends:
        lines.append(f"*_{end['name']}: {end['text']}")
    lines += [
        "",
        "The band is pointwise in the speed, but each end is one parameter value: the seed's e depends on the",
        "parameter only through V/V_y and grows with V_y, so the 'lower' files give the lowest e of the band at",
        "every speed and the 'upper' files the highest (fitting.FitResult.predict(V, band=True)).",
        "restitution_vs_v_over_vy.csv is the same for every end (e against V/V_y).",
        "",
    ]
    return "\n".join(comment_text(x) if x else "" for x in lines)
