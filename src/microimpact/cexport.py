"""Export for CFD codes: restitution tables (CSV) and a self-contained C99 wall function.

Tables of the adhesive restitution (:func:`restitution_table`, :func:`write_tables`) and a
C function computing the same outgoing velocity, spin and stick flag as
:func:`microimpact.wall.wall_interaction` for one particle, for Fluent UDFs and OpenFOAM patch
interaction models (:func:`generate_c_source`), with the rigid or the compliant
(``tangential="mindlin"``) tangential model. :func:`write_band` writes both for a fit's
estimate and the two ends of its confidence band. Sign conventions are those of
:mod:`microimpact.wall`.
"""

from __future__ import annotations

import math

import numpy as np

from ._validation import check_nonnegative, check_positive
from .adhesion import STICKING_CONSTANT, adhesive_restitution, sticking_velocity

__all__ = [
    "restitution_table",
    "write_tables",
    "generate_c_source",
    "write_c_source",
    "BAND_ENDS",
    "band_pairs",
    "write_band",
]


def restitution_table(v_over_vy, vs_over_vy_values):
    """Normal restitution ``e`` against ``V/V_y`` for several ``V_s/V_y`` (a lookup table for other codes).

    Everything scales: ``e`` depends on ``V`` only through ``V/V_y`` (seed
    eq. 27) and on adhesion only through ``V_s/V`` (:func:`adhesive_restitution`).

    Parameters
    ----------
    v_over_vy : array_like (M,)
        Normal impact speed over the yield velocity, ``V/V_y`` >= 0.
    vs_over_vy_values : array_like (K,)
        Sticking velocity over yield velocity, ``V_s/V_y`` >= 0 (0: no adhesion).

    Returns
    -------
    ndarray (M, K)
        ``e``; 0 where the particle sticks.

    Examples
    --------
    >>> restitution_table([0.5, 2.0, 10.0], [0.0, 0.5]).round(4)
    array([[1.    , 0.    ],
           [0.9306, 0.8964],
           [0.6586, 0.6567]])
    """
    v = np.atleast_1d(check_nonnegative("v_over_vy", v_over_vy)).reshape(-1)
    s = np.atleast_1d(check_nonnegative("vs_over_vy_values", vs_over_vy_values)).reshape(-1)
    return adhesive_restitution(v[:, None], 1.0, s[None, :])


def _fmt_num(x):
    """Shortest text that reads back to the same double."""
    x = float(x)
    if not math.isfinite(x):
        return "inf" if x > 0 else ("-inf" if x < 0 else "nan")
    return str(int(x)) if x.is_integer() and abs(x) < 1e15 else repr(x)


def _slug(text):
    keep = "".join(c if c.isalnum() else "_" for c in str(text).lower())
    return "_".join(p for p in keep.split("_") if p) or "pair"


def _write_csv(path, comments, header, columns):
    """One table in the project's CSV layout (:mod:`microimpact.io`), written atomically."""
    from .io import write_csv

    write_csv(path, [(name, unit, col) for (name, unit), col in zip(header, columns)], comments)


def _comment_text(text) -> str:
    """``text`` made safe inside a C block comment and on one line of a CSV comment.

    Control characters and line breaks become spaces, anything outside printable
    ASCII becomes ``?``, and the comment delimiters ``*/`` and ``/*`` are broken
    apart (``* /``, ``/ *``), so a label cannot end the comment and inject code.
    """
    out = "".join(
        c if 32 <= ord(c) < 127 else (" " if ord(c) < 32 or c in "\u2028\u2029\x85" else "?") for c in str(text)
    )
    while "*/" in out or "/*" in out:
        out = out.replace("*/", "* /").replace("/*", "/ *")
    return out


def _sized_pair(pair, diameter):
    if pair.density is None:
        raise ValueError("the pair needs a particle density to be rescaled to other diameters")
    return pair.vary(diameter=float(check_positive("diameter", diameter)))


#: Default grid of :func:`write_tables`: ``V/V_y`` from 0 to 100.
DEFAULT_V_OVER_VY = np.concatenate([np.linspace(0.0, 2.0, 41)[:-1], np.geomspace(2.0, 100.0, 80)])
#: Default ``V_s/V_y`` columns of the dimensionless table.
DEFAULT_VS_OVER_VY = (0.0, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0)
#: Default normal speeds of the per-size tables [m/s].
DEFAULT_SPEEDS = np.geomspace(0.01, 200.0, 161)


def write_tables(
    directory,
    pairs,
    diameters=None,
    velocities=None,
    *,
    work_of_adhesion=0.0,
    v_over_vy=None,
    vs_over_vy_values=DEFAULT_VS_OVER_VY,
):
    """Write restitution tables as CSV for use in other codes.

    Files (units in the header; ``#`` lines are comments):

    * ``restitution_vs_v_over_vy.csv``: ``e`` against ``V/V_y`` with one column
      per ``V_s/V_y`` value (:func:`restitution_table`); valid for any pair.
    * ``restitution_<pair>_d<diameter>um.csv`` for each pair and diameter:
      normal impact speed [m/s], ``e`` [1] and the stick flag (0/1), with the
      pair's ``V_y`` and the size's ``V_s`` in the comments.

    Layout: the project's CSV layout (:mod:`microimpact.io`): the header
    ``name [unit]`` on the first line, then ``#`` comment lines, then the rows.
    Each file is written to a temporary name and renamed into place when
    complete; a label reaches the comments only made safe (one line, printable).

    Parameters
    ----------
    directory : path
        Created if missing.
    pairs : ContactPair or sequence of ContactPair
        Sphere-on-flat pairs with a known density (rescaled to each diameter).
    diameters : sequence of float, optional
        Particle diameters [m]; default each pair's own.
    velocities : array_like, optional
        Normal impact speeds [m/s]; default :data:`DEFAULT_SPEEDS` (0.01-200 m/s).
    work_of_adhesion : float, optional
        ``G`` [J/m^2] (work of adhesion, not surface energy; see :func:`work_of_adhesion`).
    v_over_vy, vs_over_vy_values : array_like, optional
        Grid of the dimensionless table.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    from pathlib import Path

    from .pair import ContactPair

    out_dir = Path(directory)
    pairs = [pairs] if isinstance(pairs, ContactPair) else list(pairs)
    if not pairs:
        raise ValueError("pairs: give at least one ContactPair")
    G = float(check_nonnegative("work_of_adhesion", work_of_adhesion))
    v = DEFAULT_V_OVER_VY if v_over_vy is None else np.atleast_1d(check_nonnegative("v_over_vy", v_over_vy))
    s = np.atleast_1d(check_nonnegative("vs_over_vy_values", vs_over_vy_values)).reshape(-1)
    V = DEFAULT_SPEEDS if velocities is None else np.atleast_1d(check_nonnegative("velocities", velocities))
    multi = len(pairs) > 1
    jobs = []  # every size checked before any file is written
    for i, pair in enumerate(pairs):
        sizes = [2.0 * pair.effective_radius] if diameters is None else list(np.atleast_1d(diameters))
        tag = f"{_slug(pair.label or f'pair{i}')}_" if multi else ""
        jobs += [(pair, tag, d, _sized_pair(pair, d)) for d in sizes]
    out_dir.mkdir(parents=True, exist_ok=True)
    written = [_write_universal_table(out_dir, v, s)]
    for pair, tag, d, p in jobs:
        path = out_dir / f"restitution_{tag}d{float(d) * 1e6:g}um.csv"
        _write_size_table(path, pair, d, p, V, G)
        written.append(path)
    return written


def _write_universal_table(out_dir, v, s):
    """``restitution_vs_v_over_vy.csv`` of :func:`write_tables`; returns its path."""
    path = out_dir / "restitution_vs_v_over_vy.csv"
    table = restitution_table(v, s)
    _write_csv(
        path,
        [
            "microimpact: normal restitution e against V/V_y, one column per V_s/V_y",
            "seed eq. 27 with the adhesive loss of Thornton & Ning (1998): e^2 = e_p^2 - (V_s/V)^2, "
            "e = 0 (stick) when e_p V <= V_s",
            "V: normal impact speed, V_y: yield velocity (eq. 28), V_s: sticking velocity",
        ],
        [("V/V_y", "1")] + [(f"e at V_s/V_y={_fmt_num(x)}", "1") for x in s],
        [v, *np.asarray(table).T],
    )
    return path


def _write_size_table(path, pair, d, p, V, G, extra=()):
    """One per-size table of :func:`write_tables` (``p`` is ``pair`` at diameter ``d``)."""
    Vy = p.yield_velocity
    Vs = float(sticking_velocity(G, p.effective_modulus, p.effective_radius, p.effective_mass))
    e = adhesive_restitution(V, Vy, Vs)
    stuck = (Vs > 0.0) & (e == 0.0)
    _write_csv(
        path,
        [
            f"microimpact: normal restitution of {_comment_text(pair.label or 'a sphere')} on a flat, "
            f"diameter {float(d):.6g} m",
            f"E* = {p.effective_modulus:.6g} Pa, p_y = {p.limiting_pressure:.6g} Pa, "
            f"density = {pair.density:.6g} kg/m^3, work of adhesion G = {G:.6g} J/m^2",
            f"yield velocity V_y = {Vy:.10g} m/s, sticking velocity V_s = {Vs:.10g} m/s",
            *(_comment_text(x) for x in extra),
        ],
        [("normal speed", "m/s"), ("restitution e", "1"), ("stuck", "1")],
        [V, e, np.broadcast_to(stuck, np.shape(V)).astype(np.int8)],
    )


# ----------------------------------------------------------------------------- C export
_C_TEMPLATE = r"""/*
 * microimpact_wall.c -- bounce or stick of one particle at a wall (generated by microimpact {version}).
 *
 * Self-contained C99, SI units. Computes exactly what the Python function
 * microimpact.wall.wall_interaction computes for one particle:
 *   normal:     the elastic-plastic restitution e_p(V/V_y) of Aerosol Sci. Tech. 50(4):321 (2016),
 *               eqs. 22, 27, 28, with the adhesive loss of Thornton & Ning (1998):
 *               e^2 = e_p^2 - (V_s/V)^2, stick when e_p V <= V_s,
 *               V_s = (14.18/m)^(1/2) (G^5 R^4 / E*^2)^(1/6), G = work of adhesion
 *               (NOT the surface energy per surface: G = 2 gamma for identical surfaces);
 *   tangential: rigid-body Coulomb impulse model of a solid sphere (I = 2/5 m r^2):
 *               rolling (slip stopped, J_t = -2m/7 u_t) if |J_t| <= mu J_n, else sliding.
 *
 * Conventions: n points OUT OF THE WALL INTO THE FLUID (it is normalised here);
 * velocities are relative to the wall; spins are angular velocity vectors [rad/s].
 * Return value:  1 stuck (v_out = omega_out = 0, *e_n = 0),
 *                0 bounced,
 *               -1 not approaching (v.n >= 0): outputs = inputs, *e_n = 1,
 *               -2 invalid input (diameter/density <= 0, zero normal): outputs = inputs.
 * omega_in may be NULL (no spin); omega_out and e_n may be NULL.
 *
 * Parameters baked in below (microimpact_wall_default): {description}
 *
 * Fluent (DEFINE_DPM_BC UDF; not compiled by microimpact -- adapt to your version):
 *   #include "udf.h"
 *   #include "microimpact_wall.c"
 *   DEFINE_DPM_BC(microimpact_bc, p, t, f, f_normal, dim)
 *   {{
 *       real A[ND_ND]; double v[3] = {{0, 0, 0}}, n[3] = {{0, 0, 0}}, vo[3], wo[3], e, a; int i;
 *       F_AREA(A, f, t); a = NV_MAG(A);           -- F_AREA points out of the fluid: negate it
 *       for (i = 0; i < dim; i++) {{ v[i] = P_VEL(p)[i]; n[i] = -A[i] / a; }}
 *       if (microimpact_wall_interaction(v, n, NULL, P_DIAM(p), P_RHO(p),
 *                                        &microimpact_wall_default, vo, wo, &e) == 1)
 *           return PATH_END;                       -- stuck: trapped on the wall
 *       for (i = 0; i < dim; i++) P_VEL(p)[i] = vo[i];
 *       return PATH_ACTIVE;
 *   }}
 *   (Newer Fluent versions name the particle tp and the macros TP_VEL(tp), TP_DIAM(tp), TP_RHO(tp);
 *    for a moving wall subtract the wall velocity before and add it after.)
 *
 * OpenFOAM (a custom PatchInteractionModel; not compiled by microimpact):
 *   template<class CloudType> bool MyWallModel<CloudType>::correct
 *   (typename CloudType::parcelType& p, const polyPatch& pp, bool& keepParticle)
 *   {{
 *       vector nw, Up;  this->owner().patchData(p, pp, nw, Up);   -- nw points out of the domain
 *       const vector Urel = p.U() - Up;
 *       double v[3] = {{Urel.x(), Urel.y(), Urel.z()}}, n[3] = {{-nw.x(), -nw.y(), -nw.z()}}, vo[3], wo[3], e;
 *       keepParticle = true;
 *       if (microimpact_wall_interaction(v, n, NULL, p.d(), p.rho(), &params_, vo, wo, &e) == 1)
 *       {{ p.active(false); p.U() = Zero; return true; }}        -- stuck
 *       p.U() = vector(vo[0], vo[1], vo[2]) + Up;
 *       return true;
 *   }}
 *   and include this file (extern "C" is not needed when it is compiled as part of the C++ source).
 */
#include <math.h>

typedef struct {{
    double effective_modulus;  /* E* [Pa] of the particle-wall pair */
    double limiting_pressure;  /* p_y [Pa]; INFINITY: the contact never yields */
    double work_of_adhesion;   /* G [J/m^2], work of adhesion (2 gamma for identical surfaces); 0: none */
    double friction;           /* Coulomb friction coefficient mu [-] */
}} microimpact_wall_params;

#if defined(__GNUC__)
#define MICROIMPACT_UNUSED __attribute__((unused))
#else
#define MICROIMPACT_UNUSED
#endif

static const microimpact_wall_params microimpact_wall_default MICROIMPACT_UNUSED = {{
    {E}, {p_y}, {G}, {mu}
}};

#define MICROIMPACT_PI 3.141592653589793
#define MICROIMPACT_STICKING_CONSTANT {stick}

/* Yield velocity, 1/2 m V_y^2 = 2/5 P_y alpha_y (eq. 28) [m/s]. */
double microimpact_yield_velocity(double p_y, double E, double r, double m)
{{
    double a_y, alpha_y, P_y;
    if (isinf(p_y)) return INFINITY;
    a_y = MICROIMPACT_PI * p_y * r / (2.0 * E);
    alpha_y = a_y * a_y / r;
    P_y = 4.0 / 3.0 * E * sqrt(r) * (alpha_y * sqrt(alpha_y));
    return sqrt(0.8 * P_y * alpha_y / m);
}}

/* Thornton & Ning (1998) sticking velocity [m/s]; G is the work of adhesion. */
double microimpact_sticking_velocity(double G, double E, double r, double m)
{{
    double g2;
    if (!(G > 0.0)) return 0.0;   /* no adhesion: skip the sixth root */
    g2 = G * G;
    return sqrt(MICROIMPACT_STICKING_CONSTANT / m) * pow(g2 * g2 * G * ((r * r) * (r * r)) / (E * E), 1.0 / 6.0);
}}

/* Seed restitution e_p(V/V_y), eq. 27 with eq. 22 (core: thornton_ning_2016.restitution). */
double microimpact_restitution(double V, double V_y)
{{
    double v, q;
    v = isinf(V_y) ? 0.0 : V / V_y;
    if (!(v > 1.0)) return 1.0;
    q = sqrt((24.0 - 4.0 / (v * v)) * 0.2);   /* q = s / v, s = ((24 v^2 - 4)/5)^(1/2) */
    return 0.5 * q / sqrt(sqrt((1.0 + v * q) * (1.0 / 3.0)));   /* e = P^ / (A^(1/4) v), A = (1 + s)/3 */
}}

int microimpact_wall_interaction(const double v_in[3], const double n_in[3], const double omega_in[3],
                                 double diameter, double density, const microimpact_wall_params *params,
                                 double v_out[3], double omega_out[3], double *e_n)
{{
    /* The operations of microimpact.core.wall.wall_impact, in its order: the same bits. */
    double n[3], w[3], vt[3], ut[3], jt[3];
    double len, r, m, V_y, V_s, vn, V, e_p, e, ratio, jn, ut_mag, stop, limit, scale, eV, k;
    int i, stuck;

    for (i = 0; i < 3; i++) w[i] = omega_in ? omega_in[i] : 0.0;
    for (i = 0; i < 3; i++) {{ v_out[i] = v_in[i]; if (omega_out) omega_out[i] = w[i]; }}
    len = sqrt(n_in[0] * n_in[0] + n_in[1] * n_in[1] + n_in[2] * n_in[2]);
    if (!(diameter > 0.0) || !(density > 0.0) || !(len > 0.0)) return -2;
    for (i = 0; i < 3; i++) n[i] = n_in[i] / len;

    vn = v_in[0] * n[0] + v_in[1] * n[1] + v_in[2] * n[2];
    if (!(vn < 0.0)) {{ if (e_n) *e_n = 1.0; return -1; }}
    V = -vn;

    r = 0.5 * diameter;
    m = 4.0 / 3.0 * MICROIMPACT_PI * (r * r * r) * density;
    V_y = microimpact_yield_velocity(params->limiting_pressure, params->effective_modulus, r, m);
    V_s = microimpact_sticking_velocity(params->work_of_adhesion, params->effective_modulus, r, m);

    /* normal: seed restitution with the adhesive loss */
    e_p = microimpact_restitution(V, V_y);
    stuck = (V_s > 0.0) && (e_p * V <= V_s);
    if (stuck) {{
        for (i = 0; i < 3; i++) {{ v_out[i] = 0.0; if (omega_out) omega_out[i] = 0.0; }}
        if (e_n) *e_n = 0.0;
        return 1;
    }}
    ratio = V > 0.0 ? V_s / V : 0.0;
    e = sqrt(fmax(e_p * e_p - ratio * ratio, 0.0));
    jn = (1.0 + e) * V;                      /* normal impulse / m */

    /* tangential: slip of the contact point u_t = v_t + r n x omega */
    for (i = 0; i < 3; i++) vt[i] = v_in[i] - vn * n[i];
    ut[0] = vt[0] + r * (n[1] * w[2] - n[2] * w[1]);
    ut[1] = vt[1] + r * (n[2] * w[0] - n[0] * w[2]);
    ut[2] = vt[2] + r * (n[0] * w[1] - n[1] * w[0]);
    ut_mag = sqrt(ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2]);
    stop = (2.0 / 7.0) * ut_mag;             /* |impulse that stops the slip| / m */
    limit = params->friction * jn;           /* mu J_n / m */
    if (stop <= limit) scale = 2.0 / 7.0;    /* rolling */
    else scale = ut_mag > 0.0 ? limit / ut_mag : 0.0;  /* sliding */
    for (i = 0; i < 3; i++) jt[i] = ut[i] * -scale;

    eV = e * V;
    for (i = 0; i < 3; i++) v_out[i] = vt[i] + jt[i] + eV * n[i];
    if (omega_out) {{
        k = -2.5 / r;                        /* omega' = omega - 5/(2 m r) n x J_t */
        omega_out[0] = (n[1] * jt[2] - n[2] * jt[1]) * k + w[0];
        omega_out[1] = (n[2] * jt[0] - n[0] * jt[2]) * k + w[1];
        omega_out[2] = (n[0] * jt[1] - n[1] * jt[0]) * k + w[2];
    }}
    if (e_n) *e_n = e;
    return 0;
}}
"""


def _c_double(x):
    x = float(x)
    if math.isinf(x):
        return "INFINITY"
    return repr(x)


def generate_c_source(
    pair=None,
    *,
    effective_modulus=None,
    limiting_pressure=None,
    work_of_adhesion=0.0,
    friction=0.0,
    tangential="rigid",
    poisson_ratio=None,
    effective_shear_modulus=None,
    comment=None,
) -> str:
    """A self-contained C99 source computing :func:`wall_interaction` for one particle.

    The file defines ``microimpact_wall_params`` (a struct of ``E*`` [Pa],
    ``p_y`` [Pa], ``G`` [J/m^2], ``mu`` [-]), a constant
    ``microimpact_wall_default`` holding the values given here, and::

        int microimpact_wall_interaction(const double v_in[3], const double n[3],
                                         const double omega_in[3], double diameter, double density,
                                         const microimpact_wall_params *params,
                                         double v_out[3], double omega_out[3], double *e_n);

    returning 1 when the particle sticks, 0 when it bounces, -1 when it is not
    approaching the wall (``v.n >= 0``, outputs = inputs) and -2 on invalid
    input. SI units; ``n`` points out of the wall into the fluid. Its results
    equal the Python function's to rounding (the tests check 1e-12).

    Use in CFD codes (sketches in the file's header comment; microimpact has
    not compiled them): in a Fluent ``DEFINE_DPM_BC`` UDF, ``#include`` the file,
    take ``P_VEL(p)``, ``P_DIAM(p)``, ``P_RHO(p)`` and the normal ``-F_AREA/|F_AREA|``
    (Fluent's face area vector points out of the fluid), write ``v_out`` back to
    ``P_VEL(p)`` and return ``PATH_END`` when stuck, ``PATH_ACTIVE`` otherwise. In
    OpenFOAM, write a ``PatchInteractionModel`` whose ``correct(p, pp,
    keepParticle)`` gets ``nw, Up`` from ``owner().patchData``, calls the function
    with ``p.U() - Up`` and ``-nw``, and deactivates stuck parcels.

    Parameters
    ----------
    pair : ContactPair, optional
        Takes ``E*`` and ``p_y`` from it.
    effective_modulus, limiting_pressure : float, optional
        ``E*`` [Pa], ``p_y`` [Pa] (override the pair's).
    work_of_adhesion : float, optional
        ``G`` [J/m^2], the work of adhesion (``2 gamma`` for identical surfaces); default 0.
    friction : float, optional
        Coulomb coefficient ``mu`` [-]; default 0.
    tangential : {"rigid", "mindlin"}, optional
        Tangential model, as ``tangential=`` of :func:`~microimpact.wall.wall_interaction`.
        ``"rigid"`` (default): the rigid-body Coulomb impulse (the source is the same,
        byte for byte, as before the option existed). ``"mindlin"``: the compliant contact
        of :mod:`microimpact.oblique`; the file then also holds the
        :func:`~microimpact.oblique.universal_table` of the pair's ``kappa = 4 G*/E*``
        (:func:`~microimpact.oblique.table_c_source`, about 30 kB of constants) and the
        tangential impulse is ``J_t = -F(psi, V_y/V) mu J_n u_t/|u_t|`` with
        ``psi = kappa |u_t| / (mu V)``, as the Python function computes it. ``kappa``
        is a compile-time constant (``MICROIMPACT_KAPPA``): a struct with another
        ``E*`` keeps the ``kappa`` given here.
    poisson_ratio : float, optional
        ``"mindlin"`` only: one Poisson's ratio for particle and wall,
        ``kappa = 2(1 - nu)/(2 - nu)``.
    effective_shear_modulus : float, optional
        ``"mindlin"`` only: ``G*`` [Pa], ``kappa = 4 G*/E*`` with the ``E*`` used here.
        Without either, ``kappa`` comes from the pair's particle and surface materials
        (:func:`~microimpact.oblique.stiffness_ratio_of`).
    comment : str, optional
        A line added to the header comment (made safe: one line, printable ASCII, no
        comment delimiters), e.g. which end of a confidence band the parameters are.

    Returns
    -------
    str
        The C99 source text.

    Raises
    ------
    ValueError
        If neither a pair nor both ``effective_modulus`` and ``limiting_pressure``
        are given, a value is out of range, or ``tangential="mindlin"`` has no way to
        ``kappa`` (or gets both ``poisson_ratio`` and ``effective_shear_modulus``);
        ``poisson_ratio`` or ``effective_shear_modulus`` with ``"rigid"`` is refused
        too (it would be ignored).
    """
    from . import __version__

    E = effective_modulus if effective_modulus is not None else (pair.effective_modulus if pair else None)
    p_y = limiting_pressure if limiting_pressure is not None else (pair.limiting_pressure if pair else None)
    if E is None or p_y is None:
        raise ValueError("give a pair or both effective_modulus and limiting_pressure")
    E = float(check_positive("effective_modulus", E))
    p_y = float(check_positive("limiting_pressure", p_y, allow_inf=True))
    G = float(check_nonnegative("work_of_adhesion", work_of_adhesion))
    mu = float(check_nonnegative("friction", friction))
    if math.isinf(G) or math.isinf(mu):
        raise ValueError("work_of_adhesion and friction must be finite")
    kappa = _kappa_for_c(pair, E, tangential, poisson_ratio, effective_shear_modulus)
    label = f"{_comment_text(pair.label)}; " if pair is not None and pair.label else ""
    desc = f"{label}E* = {E:.6g} Pa, p_y = {p_y:.6g} Pa, G = {G:.6g} J/m^2, mu = {mu:.6g}"
    if kappa is not None:
        desc += f"; tangential: mindlin, kappa = 4 G* / E* = {kappa:.6g}"
    if comment is not None:
        desc += "\n *\n * " + _comment_text(comment)
    text = _C_TEMPLATE.format(
        version=__version__,
        description=desc,
        E=_c_double(E),
        p_y=_c_double(p_y),
        G=_c_double(G),
        mu=_c_double(mu),
        stick=repr(STICKING_CONSTANT),
    )
    return text if kappa is None else _mindlin_source(text, kappa)


def _kappa_for_c(pair, E, tangential, poisson_ratio, effective_shear_modulus):
    """``kappa = 4 G*/E*`` of the compliant model, or None for the rigid one (inputs checked)."""
    if tangential not in ("rigid", "mindlin"):
        raise ValueError(f"tangential must be 'rigid' or 'mindlin', got {tangential!r}")
    if tangential == "rigid":
        for name, value in (("poisson_ratio", poisson_ratio), ("effective_shear_modulus", effective_shear_modulus)):
            if value is not None:
                raise ValueError(f"{name} is used by tangential='mindlin' only, got it with tangential='rigid'")
        return None
    if poisson_ratio is not None and effective_shear_modulus is not None:
        raise ValueError("give poisson_ratio or effective_shear_modulus, not both (each sets kappa)")
    if effective_shear_modulus is not None:
        Gs = float(check_positive("effective_shear_modulus", effective_shear_modulus))
        if math.isinf(Gs):
            raise ValueError(f"effective_shear_modulus must be finite, got {effective_shear_modulus!r}")
        return 4.0 * Gs / E  # as wall_interaction: 4 G*/E* with the E* in use
    if poisson_ratio is not None:
        from ._validation import check_poisson

        nu = float(check_poisson("poisson_ratio", poisson_ratio, scalar=True))
        return 2.0 * (1.0 - nu) / (2.0 - nu)
    if pair is None or getattr(pair, "particle", None) is None or getattr(pair, "surface", None) is None:
        raise ValueError(
            "tangential='mindlin' needs poisson_ratio=..., effective_shear_modulus=... or a pair built from materials"
        )
    from .oblique import stiffness_ratio_of

    return stiffness_ratio_of(pair)


#: The rigid source's tangential lines and their compliant replacements (each must occur once).
_MINDLIN_EDITS = (
    (
        " *   tangential: rigid-body Coulomb impulse model of a solid sphere (I = 2/5 m r^2):\n"
        " *               rolling (slip stopped, J_t = -2m/7 u_t) if |J_t| <= mu J_n, else sliding.\n",
        " *   tangential: compliant contact (Mindlin's no-slip spring k_t = 8 G* a with a Coulomb limit, loaded\n"
        " *               along the seed's normal history; microimpact.oblique) of a solid sphere:\n"
        " *               J_t = -F(psi, V_y/V) mu J_n u_t/|u_t|, psi = kappa |u_t| / (mu V), kappa = 4 G* / E*,\n"
        " *               F from the universal table below (bilinear; error below 3e-3 of mu J_n).\n",
    ),
    (
        "    double len, r, m, V_y, V_s, vn, V, e_p, e, ratio, jn, ut_mag, stop, limit, scale, eV, k;\n",
        "    double len, r, m, V_y, V_s, vn, V, e_p, e, ratio, jn, ut_mag, limit, scale, eV, k;\n",
    ),
    (
        "    stop = (2.0 / 7.0) * ut_mag;             /* |impulse that stops the slip| / m */\n"
        "    limit = params->friction * jn;           /* mu J_n / m */\n"
        "    if (stop <= limit) scale = 2.0 / 7.0;    /* rolling */\n"
        "    else scale = ut_mag > 0.0 ? limit / ut_mag : 0.0;  /* sliding */\n",
        "    limit = params->friction * jn;           /* mu J_n / m */\n"
        "    if (params->friction > 0.0 && ut_mag > 0.0)  /* |J_t| / m = F mu J_n / m */\n"
        "        scale = microimpact_oblique_impulse_ratio(MICROIMPACT_KAPPA * ut_mag / (params->friction * V),\n"
        "                                                  V_y / V) * limit / ut_mag;\n"
        "    else scale = 0.0;\n",
    ),
)


def _mindlin_source(text, kappa):
    """The rigid source ``text`` turned into the compliant one for ``kappa``."""
    from .oblique import table_c_source, universal_table

    for old, new in _MINDLIN_EDITS:
        if text.count(old) != 1:  # pragma: no cover - the template changed
            raise RuntimeError("the C template no longer has the rigid tangential block")
        text = text.replace(old, new)
    table = table_c_source(universal_table(kappa), "microimpact_oblique")
    table = table.replace("#include <math.h>\n", "")  # already included
    table += (
        f"\n/* kappa = 4 G* / E* of psi, unrounded (the table is built for it rounded to 12 digits) */\n"
        f"#define MICROIMPACT_KAPPA {kappa!r}\n\n"
    )
    anchor = "int microimpact_wall_interaction("
    head, tail = text.split(anchor, 1)
    return head + table + anchor + tail


def write_c_source(path, pair=None, **kwargs):
    """Write the C99 source of :func:`generate_c_source` to a file.

    Parameters
    ----------
    path : str or os.PathLike
        File to write (overwritten; missing parent directories are made), or an
        existing directory, in which case the file is ``microimpact_wall.c`` in it.
    pair : ContactPair, optional
        Takes ``E*`` [Pa] and ``p_y`` [Pa] from it.
    **kwargs
        ``effective_modulus`` [Pa], ``limiting_pressure`` [Pa], ``work_of_adhesion``
        ``G`` [J/m^2], ``friction`` ``mu`` [-], ``tangential``, ``poisson_ratio``,
        ``effective_shear_modulus`` [Pa] and ``comment``, as for :func:`generate_c_source`.

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    ValueError
        If neither a pair nor both ``effective_modulus`` and ``limiting_pressure`` are
        given, or a value is out of range.
    """
    from pathlib import Path

    from .io import atomic_write

    path = Path(path)
    if path.is_dir():
        path = path / "microimpact_wall.c"
    text = generate_c_source(pair, **kwargs)  # every input checked before anything is created
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_write(path) as fh:
        fh.write(text)
    return path


# ----------------------------------------------------------------------------- confidence band
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
        Another model than the seed's (the export writes the seed's model), not one free
        parameter, or an interval open at one end (the data do not bound it; no table can
        stand for that end).
    """
    from .fitting import FREE_PARAMETERS, SEED_MODEL, FitResult

    if not isinstance(fit, FitResult):
        raise ValueError(f"fit must be a FitResult (from fit_restitution), got {type(fit).__name__}")
    if fit.model != SEED_MODEL:
        raise ValueError(f"fit: the export writes the seed's model ({SEED_MODEL}); this fit is of {fit.model!r}")
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

    from .io import atomic_write, owned_directory

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
    where = f" to {_comment_text(source)}" if source else ""
    # every input checked and every text made before anything is written
    jobs = []
    sources = {}
    for end in ends:
        pair = end["pair"]
        sizes = [2.0 * pair.effective_radius] if diameters is None else list(np.atleast_1d(diameters))
        jobs += [(end, d, _sized_pair(pair, d)) for d in sizes]
        if c_source:
            sources[end["name"]] = generate_c_source(
                pair,
                work_of_adhesion=G,
                friction=mu,
                tangential=tangential,
                poisson_ratio=poisson_ratio,
                effective_shear_modulus=effective_shear_modulus,
                comment=f"fit{where}: {end['text']}",
            )
    readme = _band_readme(fit, ends, where, c_source)
    target = Path(directory)
    names = []
    with owned_directory(target, "export", inputs=inputs) as tmp:
        with atomic_write(tmp / "README.txt") as fh:
            fh.write(readme)
        names.append("README.txt")
        names.append(_write_universal_table(tmp, v, s).name)
        for end, d, p in jobs:
            name = f"restitution_d{float(d) * 1e6:g}um_{end['name']}.csv"
            _write_size_table(tmp / name, end["pair"], d, p, V, G, extra=[f"fit{where}: {end['text']}"])
            names.append(name)
        for end_name, text in sources.items():
            with atomic_write(tmp / f"microimpact_wall_{end_name}.c") as fh:
                fh.write(text)
            names.append(f"microimpact_wall_{end_name}.c")
    return [target / n for n in names]


def _band_readme(fit, ends, where, c_source) -> str:
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
    return "\n".join(_comment_text(x) if x else "" for x in lines)
