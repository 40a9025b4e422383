"""The C wall function's adhesive oblique impact: the integration of :mod:`microimpact.oblique.adhesive`.

With adhesion and a compliant tangential law :func:`microimpact.wall.wall_interaction` integrates each
particle's impact, normal and tangential together, under Thornton & Ning's (1998) whole adhesive
elastic-plastic law (:mod:`microimpact.core.models.thornton_ning_1998_adhesive_plastic`), along the
slip's direction (``wall._adhesive_oblique``, then
:func:`~microimpact.oblique.adhesive.adhesive_oblique_impact`). :func:`adhesive_c_source` writes the
C99 text that performs the same scalar operations in the same order for one particle: the law's
loading, unloading, contact radius and exact outcome (restitution, maximum approach, loading time),
the pull-off of the unloading branch (401 samples, then golden section), the Hertz contact time that
sets the step, the velocity-Verlet integration, the outcome's classification and the wall's geometry
(slip direction ``e``, ``b = e x n``, the outgoing ``v'`` and ``omega'``). Every step is a
translation of the Python source, expression by expression (C's ``*``, ``/``, ``+``, ``-`` group
from the left as Python's do, and ``x ** y`` is the C library's ``pow``), so the results are the
same bits: the Python path calls the C library's ``atan2``, ``cos`` and ``sin`` through :mod:`math`
(:func:`microimpact.oblique.adhesive.libm`: numpy's own vectorised routines may differ by an ulp),
``hypot`` through numpy, and ``pow`` where numba or Python raise to a power (the tests measure it).

The constants come from their Python homes (the tangential law's ``(c_load, c_unload, factor,
linear, lam, limit_mode)`` from :func:`microimpact.oblique.adhesive.law_constants`, the Gauss-Legendre rule,
``B(2/5, 1/2)``, the step counts and the rest tolerance), not retyped.
"""

from __future__ import annotations

import math

__all__ = ["adhesive_c_source", "adhesive_laws", "ADHESIVE_CALL", "ADHESIVE_HEADER"]

#: The line of the compliant wall function that hands an adhesive particle to the integration
#: (after the unit normal, ``vn``, ``r`` and ``m`` are known, as ``wall_interaction`` has them).
ADHESIVE_CALL = (
    "    if (params->work_of_adhesion > 0.0)      /* adhesion: the integrated impact (header) */\n"
    "        return microimpact__adhesive_wall(v_in, n, w, vn, r, m, params, v_out, omega_out, e_n);\n"
)

#: The header comment's lines on the return value of an adhesive particle.
ADHESIVE_HEADER = (
    " *               With params->work_of_adhesion > 0 the impact is integrated, normal and tangential\n"
    " *               together, as microimpact.oblique.adhesive.adhesive_oblique_impact integrates it under\n"
    " *               Thornton & Ning's whole adhesive elastic-plastic law\n"
    " *               (@LAW@), along the slip's direction\n"
    " *               (microimpact.wall): 0 bounced (*e_n the law's exact restitution),\n"
    " *               1 captured (*e_n = 0): v_out and omega_out are then the velocity along the wall and\n"
    " *               the spin the captured particle keeps (rolling or sliding on the wall; no normal part;\n"
    " *               zero only where it stops), not zero as for a stuck particle without it.\n"
)


def adhesive_laws():
    """The compliant tangential laws the adhesive integration runs (the C function integrates them; any
    other compliant law returns -3 with adhesion): those of
    :data:`~microimpact.oblique.adhesive.ADHESIVE_LAWS` but ``"rigid"``."""
    from ..oblique.adhesive import ADHESIVE_LAWS

    return tuple(law for law in ADHESIVE_LAWS if law != "rigid")


def _c_list(values):
    return ",\n    ".join(", ".join(repr(float(v)) for v in values[i : i + 4]) for i in range(0, len(values), 4))


def adhesive_c_source(law) -> str:
    """The C99 text of the adhesive integration for the compliant ``law`` (one of :func:`adhesive_laws`):
    the static function ``microimpact__adhesive_wall`` the wall function calls (:data:`ADHESIVE_CALL`)
    and what it needs. Needs ``<math.h>`` and ``MICROIMPACT_PI``, ``MICROIMPACT_KAPPA`` and
    ``microimpact_wall_params`` defined before it."""
    from ..adhesion import WHOLE_LAW
    from ..core.gauss_legendre import RULES
    from ..core.special import BETA_25_12
    from ..oblique import adhesive as adh

    if law not in adhesive_laws():
        raise ValueError(f"tangential={law!r} is not integrated with adhesion; one of {adhesive_laws()}")
    steps = adh.DEFAULT_STEPS
    gx, gw = RULES[48]
    text = _C_ADHESIVE
    for key, value in (
        ("@LAW@", law),
        ("@WHOLE_LAW@", WHOLE_LAW),
        ("@LAWCONST@", ", ".join(repr(float(c)) for c in adh.law_constants(law))),
        ("@THIRD@", repr(1.0 / 3.0)),
        ("@BETA@", repr(float(BETA_25_12))),
        ("@STEPS@", repr(float(steps))),
        ("@MAX_STEPS@", str(int(adh.MAX_CONTACT_TIMES * steps))),
        ("@NGL@", str(len(gx))),
        ("@GX@", _c_list(gx)),
        ("@GW@", _c_list(gw)),
        ("@ANGLE_MAX@", repr(math.nextafter(90.0, 0.0))),
    ):
        text = text.replace(key, value)
    return text


_C_ADHESIVE = r"""
/*
 * Adhesive oblique impact (generated by microimpact.cexport from microimpact.oblique.adhesive and the
 * normal law of microimpact.core.models.@WHOLE_LAW@): each function below is the
 * Python function of the same name there, translated expression by expression (the same operations in
 * the same order).
 * Tangential law @LAW@: (c_load, c_unload, factor, linear, lam, limit_mode) of
 * microimpact.oblique.adhesive.law_constants; limit_mode 0: Coulomb limit mu |F + 2 F_c|,
 * 1: mu |F| (LIGGGHTS).
 */
static const double microimpact_adh_law[6] = {@LAWCONST@};
#define MICROIMPACT_ADH_THIRD @THIRD@
#define MICROIMPACT_ADH_BETA @BETA@             /* B(2/5, 1/2): Hertz's contact time */
#define MICROIMPACT_ADH_STEPS @STEPS@            /* steps per contact time */
#define MICROIMPACT_ADH_MAX_STEPS @MAX_STEPS@    /* a captured particle is followed at most this far */
#define MICROIMPACT_ADH_ANGLE_MAX @ANGLE_MAX@    /* the largest angle below 90 degrees */
/* @NGL@-point Gauss-Legendre rule on [-1, 1] (microimpact.core.gauss_legendre) */
static const double microimpact_adh_gx[@NGL@] = {
    @GX@
};
static const double microimpact_adh_gw[@NGL@] = {
    @GW@
};

/* One pair's constants of the law: E*, R*, m*, p_y, G and yield_constants' (s, b0, by, bY, K, PY). */
typedef struct {
    double E, R, m, p_y, G, s, b0, by, bY, K, PY;
} microimpact_adh_pair;

static double microimpact_adh_force_b(double b, double E, double R, double s)
{
    double b3 = b * b * b;
    return 4.0 * E * b3 * b3 / (3.0 * R) - 4.0 * E * s * b3;
}

static double microimpact_adh_work_integral(double b, double E, double R, double s)
{
    double b2 = b * b, b4 = b2 * b2;
    return 8.0 * E / (15.0 * R * R) * b4 * b4 * b2 - 8.0 * E * s / (3.0 * R) * b4 * b2 * b + 2.0 * E * s * s * b4;
}

static double microimpact_adh_work_difference(double x, double y, double E, double R, double s)
{
    double p10 = 0.0, p7 = 0.0, p4 = 0.0, xk = 1.0, yk, yk7, yk4;
    int k, j;
    for (k = 0; k < 10; k++) {
        yk = 1.0;
        for (j = 0; j < 9 - k; j++) yk *= y;
        p10 += xk * yk;
        if (k < 7) {
            yk7 = 1.0;
            for (j = 0; j < 6 - k; j++) yk7 *= y;
            p7 += xk * yk7;
        }
        if (k < 4) {
            yk4 = 1.0;
            for (j = 0; j < 3 - k; j++) yk4 *= y;
            p4 += xk * yk4;
        }
        xk *= x;
    }
    return 8.0 * E / (15.0 * R * R) * p10 - 8.0 * E * s / (3.0 * R) * p7 + 2.0 * E * s * s * p4;
}

static double microimpact_adh_pd(double x, double y, int n)
{
    double total = 0.0, xk = 1.0, yk;
    int k, j;
    for (k = 0; k < n; k++) {
        yk = 1.0;
        for (j = 0; j < n - 1 - k; j++) yk *= y;
        total += xk * yk;
        xk *= x;
    }
    return total;
}

static double microimpact_adh_time_to_top(double b_lo, double bm, double E, double R, double m, double s)
{
    double W = sqrt(bm - b_lo), total = 0.0, w, b, q;
    int i;
    for (i = 0; i < @NGL@; i++) {
        w = 0.5 * W * (microimpact_adh_gx[i] + 1.0);
        b = bm - w * w;
        q = microimpact_adh_work_difference(bm, b, E, R, s);
        total += microimpact_adh_gw[i] * 2.0 * (4.0 * b * b * b / R - 2.0 * s) / sqrt(2.0 * q / m);
    }
    return 0.5 * W * total;
}

static double microimpact_adh_b_of_alpha(double alpha, double E, double R, double s)
{
    double bf = pow(0.5 * s * R, 1.0 / 3.0), b, c, f, d, step;
    int i;
    (void)E;
    if (alpha <= (bf * bf) * (bf * bf) / R - 2.0 * s * bf) return bf;
    b = pow(R * fabs(alpha), 0.25);
    c = 2.0 * bf;
    if (c > b) b = c;
    while ((b * b) * (b * b) / R - 2.0 * s * b < alpha) b *= 2.0;
    for (i = 0; i < 200; i++) {
        f = (b * b) * (b * b) / R - 2.0 * s * b - alpha;
        d = 4.0 * b * b * b / R - 2.0 * s;
        step = f / d;
        b -= step;
        if (step <= 1e-15 * b) break;
    }
    return bf > b ? bf : b;
}

static double microimpact_adh_yield_root(double E, double R, double p_y, double s)
{
    double c, q, b, step;
    int i;
    if (p_y == INFINITY) return INFINITY;
    c = MICROIMPACT_PI * p_y * R / (2.0 * E);
    q = s * R;
    b = sqrt(c) + pow(q, MICROIMPACT_ADH_THIRD);
    for (i = 0; i < 200; i++) {
        step = (b * b * b - c * b - q) / (3.0 * b * b - c);
        b -= step;
        if (step <= 1e-16 * b) break;
    }
    return b;
}

static void microimpact_adh_setup(microimpact_adh_pair *t, double E, double R, double m, double p_y, double G)
{
    t->E = E; t->R = R; t->m = m; t->p_y = p_y; t->G = G;
    t->s = sqrt(0.5 * MICROIMPACT_PI * G / E);
    t->b0 = pow(2.0 * R * t->s, MICROIMPACT_ADH_THIRD);
    t->by = microimpact_adh_yield_root(E, R, p_y, t->s);
    t->bY = t->b0 > t->by ? t->b0 : t->by;
    t->K = 4.0 * E * t->s * t->by * t->by;
    t->PY = t->bY < INFINITY ? microimpact_adh_force_b(t->bY, E, R, t->s) : INFINITY;
}

static double microimpact_adh_plastic_force_b(double b, double bY, double PY, double K, double p_y)
{
    double b2 = b * b, bY2 = bY * bY;
    return PY + MICROIMPACT_PI * p_y * (b2 - bY2) * (b2 + bY2) - K * (b - bY);
}

static double microimpact_adh_loading_force_b(const microimpact_adh_pair *t, double b)
{
    if (b <= t->bY) return microimpact_adh_force_b(b, t->E, t->R, t->s);
    return microimpact_adh_plastic_force_b(b, t->bY, t->PY, t->K, t->p_y);
}

static double microimpact_adh_plastic_work_quotient(const microimpact_adh_pair *t, double x, double y)
{
    double R = t->R, p_y = t->p_y, s = t->s, bY = t->bY, K = t->K;
    double A0 = t->PY - MICROIMPACT_PI * p_y * bY * bY * bY * bY + K * bY;
    return A0 * (microimpact_adh_pd(x, y, 4) / R - 2.0 * s) + MICROIMPACT_PI * p_y * microimpact_adh_pd(x, y, 8) / (2.0 * R)
           - (0.4 * s * MICROIMPACT_PI * p_y + 0.8 * K / R) * microimpact_adh_pd(x, y, 5) + K * s * microimpact_adh_pd(x, y, 2);
}

static double microimpact_adh_plastic_turning_point(const microimpact_adh_pair *t, double K2)
{
    double bY = t->bY, b = 1.5 * bY, f, d, step;
    int i;
    while ((b - bY) * microimpact_adh_plastic_work_quotient(t, b, bY) < K2) b *= 1.5;
    for (i = 0; i < 200; i++) {
        f = (b - bY) * microimpact_adh_plastic_work_quotient(t, b, bY) - K2;
        d = microimpact_adh_plastic_force_b(b, bY, t->PY, t->K, t->p_y) * (4.0 * b * b * b / t->R - 2.0 * t->s);
        step = f / d;
        b -= step;
        if (fabs(step) <= 1e-16 * b) break;
    }
    return b;
}

/* microimpact.core.models._jkr.turning_point with G_0 = work_integral(b0) */
static double microimpact_adh_jkr_turning_point(double Kin, double b0, double E, double R, double s)
{
    double G0 = microimpact_adh_work_integral(b0, E, R, s), bm = b0, f, d, step;
    int i;
    while (microimpact_adh_work_integral(bm, E, R, s) - G0 < Kin) bm *= 1.5;
    for (i = 0; i < 200; i++) {
        f = microimpact_adh_work_integral(bm, E, R, s) - G0 - Kin;
        d = microimpact_adh_force_b(bm, E, R, s) * (4.0 * bm * bm * bm / R - 2.0 * s);
        step = f / d;
        bm -= step;
        if (fabs(step) <= 1e-16 * bm) break;
    }
    return b0 > bm ? b0 : bm;
}

static double microimpact_adh_unloading_radius_b(double bs, double Ps, double E, double R, double s)
{
    double b3 = bs * bs * bs;
    (void)R;
    return (4.0 * E * b3 * b3 / 3.0) / (Ps + 4.0 * E * s * b3);
}

/* _unloading_state: R_p and alpha_p of the unloading from alpha_max */
static void microimpact_adh_unloading_state(const microimpact_adh_pair *t, double alpha_max, double *Rp, double *ap)
{
    double bs = microimpact_adh_b_of_alpha(alpha_max, t->E, t->R, t->s), Ps, bs2;
    if (bs <= t->bY) {
        *Rp = t->R;
        *ap = 0.0;
        return;
    }
    Ps = microimpact_adh_plastic_force_b(bs, t->bY, t->PY, t->K, t->p_y);
    *Rp = microimpact_adh_unloading_radius_b(bs, Ps, t->E, t->R, t->s);
    bs2 = bs * bs;
    *ap = bs2 * bs2 * (*Rp - t->R) / (t->R * *Rp);
}

static double microimpact_adh_separation_approach_after(const microimpact_adh_pair *t, double alpha_max)
{
    double Rp, ap, G = t->G, E = t->E;
    microimpact_adh_unloading_state(t, alpha_max, &Rp, &ap);
    return ap - 0.75 * pow(MICROIMPACT_PI * MICROIMPACT_PI * G * G * Rp / (E * E), MICROIMPACT_ADH_THIRD);
}

/* force (= signed_force) with G > 0 */
static double microimpact_adh_force(const microimpact_adh_pair *t, double alpha, double alpha_max)
{
    double Rp, ap, x, bf, s = t->s;
    if (alpha_max <= 0.0 && alpha < 0.0) return 0.0;
    if (alpha >= alpha_max) return microimpact_adh_loading_force_b(t, microimpact_adh_b_of_alpha(alpha, t->E, t->R, s));
    microimpact_adh_unloading_state(t, alpha_max, &Rp, &ap);
    x = alpha - ap;
    bf = pow(0.5 * Rp * s, MICROIMPACT_ADH_THIRD);
    if (x < bf * bf * bf * bf / Rp - 2.0 * s * bf) return 0.0;
    return microimpact_adh_force_b(microimpact_adh_b_of_alpha(x, t->E, Rp, s), t->E, Rp, s);
}

/* tangential_contact_radius with G > 0 */
static double microimpact_adh_radius(const microimpact_adh_pair *t, double alpha, double alpha_max)
{
    double Rp, ap, b;
    if (alpha >= alpha_max) {
        b = microimpact_adh_b_of_alpha(alpha, t->E, t->R, t->s);
        return b * b;
    }
    microimpact_adh_unloading_state(t, alpha_max, &Rp, &ap);
    b = microimpact_adh_b_of_alpha(alpha - ap, t->E, Rp, t->s);
    return b * b;
}

/* outcome: the fields restitution, max_approach and loading_time (with G > 0) */
static void microimpact_adh_outcome(const microimpact_adh_pair *t, double V, double *e, double *a_max, double *tL)
{
    double E = t->E, R = t->R, m = t->m, s = t->s, b0 = t->b0, bY = t->bY;
    double bF = pow(0.5 * R * s, 1.0 / 3.0), Kin = 0.5 * m * V * V, KY, Wl, bm;
    double bs, Ps, Rp, bs2, bf, Wr, t1, W, total, w, b, q;
    int i;
    KY = bY == INFINITY ? INFINITY : (bY - b0) * microimpact_adh_work_difference(bY, b0, E, R, s);
    if (Kin <= KY) {  /* the elastic adhesive impact (_jkr.impact) */
        Wl = microimpact_adh_work_integral(bF, E, R, s) - microimpact_adh_work_integral(b0, E, R, s);
        bm = microimpact_adh_jkr_turning_point(Kin, b0, E, R, s);
        *a_max = (bm * bm) * (bm * bm) / R - 2.0 * s * bm;
        *tL = bm > b0 ? microimpact_adh_time_to_top(b0, bm, E, R, m, s) : 0.0;
        *e = Kin <= Wl ? 0.0 : sqrt(1.0 - Wl / Kin);
        return;
    }
    bs = microimpact_adh_plastic_turning_point(t, Kin - KY);
    Ps = microimpact_adh_plastic_force_b(bs, bY, t->PY, t->K, t->p_y);
    Rp = microimpact_adh_unloading_radius_b(bs, Ps, E, R, s);
    bs2 = bs * bs;
    *a_max = bs2 * bs2 / R - 2.0 * s * bs;
    bf = pow(0.5 * Rp * s, MICROIMPACT_ADH_THIRD);
    Wr = (bs - bf) * microimpact_adh_work_difference(bs, bf, E, Rp, s);
    if (bY > b0) {
        bm = microimpact_adh_jkr_turning_point(Kin, b0, E, R, s);
        t1 = microimpact_adh_time_to_top(b0, bm, E, R, m, s) - microimpact_adh_time_to_top(bY, bm, E, R, m, s);
    } else {
        t1 = 0.0;
    }
    W = sqrt(bs - bY);
    total = 0.0;
    for (i = 0; i < @NGL@; i++) {
        w = 0.5 * W * (microimpact_adh_gx[i] + 1.0);
        b = bs - w * w;
        q = microimpact_adh_plastic_work_quotient(t, bs, b);
        total += microimpact_adh_gw[i] * 2.0 * (4.0 * b * b * b / R - 2.0 * s) / sqrt(2.0 * q / m);
    }
    *tL = t1 + 0.5 * W * total;
    *e = Wr <= 0.0 ? 0.0 : sqrt(Wr / Kin);
}

/* hertz.contact_time */
static double microimpact_adh_hertz_time(double V, double E, double R, double m)
{
    double ts = !(V > 0.0) ? INFINITY : pow(15.0 * m / (16.0 * E * sqrt(R)), 0.4) * pow(V, -0.2);
    return 2.0 * (0.4 * MICROIMPACT_ADH_BETA * ts);
}

/* _pulloff: F_c = -min force on the unloading branch from alpha_max (401 samples as numpy's linspace,
   then golden section on the bracket of the sampled minimum) */
static double microimpact_adh_pulloff(const microimpact_adh_pair *t, double alpha_max)
{
    double xs[401], f[401], a_sep, lo, hi, delta, step, a, b, c1, c2, f1, f2, fmin, fm;
    int k, i;
    a_sep = microimpact_adh_separation_approach_after(t, alpha_max);
    lo = alpha_max < a_sep ? alpha_max : a_sep;
    hi = alpha_max;
    delta = hi - lo;
    step = delta / 400.0;
    for (k = 0; k < 401; k++) xs[k] = (step == 0.0 ? (k / 400.0) * delta : k * step) + lo;
    xs[400] = hi;
    i = 0;
    for (k = 0; k < 401; k++) {
        f[k] = microimpact_adh_force(t, xs[k], alpha_max);
        if (f[k] < f[i]) i = k;
    }
    a = xs[i > 0 ? i - 1 : 0];
    b = xs[i < 400 ? i + 1 : 400];
    for (k = 0; k < 60; k++) {
        c1 = b - 0.618 * (b - a);
        c2 = a + 0.618 * (b - a);
        f1 = microimpact_adh_force(t, c1, alpha_max);
        f2 = microimpact_adh_force(t, c2, alpha_max);
        if (f1 < f2) b = c2;
        else a = c1;
    }
    fmin = f[i];
    fm = microimpact_adh_force(t, 0.5 * (a + b), alpha_max);
    if (fm < fmin) fmin = fm;
    return 0.0 > -fmin ? 0.0 : -fmin;
}

/* _integrator's run (end_time None): the last normal speed ratio is not needed; v, w (rim speed R omega)
   and whether the contact slid at its last step */
static void microimpact_adh_run(const microimpact_adh_pair *t, double Vn, double v0, double w0, double mu, double kG,
                                double k_lin, double Fc, double a_sep, double dt, double *v_out, double *w_out,
                                int *sliding_out)
{
    const double c_load = microimpact_adh_law[0], c_unload = microimpact_adh_law[1];
    const double lin = microimpact_adh_law[3], lam = microimpact_adh_law[4], limit_mode = microimpact_adh_law[5];
    double R = t->R, m = t->m;
    double alpha = 0.0, adot = Vn, amax = 0.0, v = v0, w = w0, T = 0.0, a_old = 0.0, F, acc, arm, a, u, c, kt, crit;
    int sliding = 0, unloading = 0;
    long n = 0;
    F = microimpact_adh_force(t, 0.0, 0.0);
    acc = -F / m;
    while (n < MICROIMPACT_ADH_MAX_STEPS) {
        n += 1;
        arm = R - lam * alpha;
        adot += 0.5 * dt * acc;
        v += 0.5 * dt * T / m;
        w += 0.5 * dt * 2.5 * T * arm / (m * R);
        alpha += dt * adot;
        if (alpha > amax) amax = alpha;
        if (adot < 0.0) unloading = 1;
        if (unloading && alpha < a_sep) {
            T = 0.0;
            break;
        }
        F = microimpact_adh_force(t, alpha, amax);
        a = microimpact_adh_radius(t, alpha, amax);
        arm = R - lam * alpha;
        u = v + arm * w / R;
        if (a_old > 0.0 && a > 0.0) {
            c = a >= a_old ? c_load : c_unload;
            if (c == 1.0) T *= a / a_old;
            else if (c == 2.0) T *= (a / a_old) * (a / a_old);
        } else if (a <= 0.0) {
            T = 0.0;
        }
        kt = lin != 0.0 ? k_lin : kG * a;
        T -= kt * u * dt;
        crit = limit_mode == 0.0 ? mu * fabs(F + 2.0 * Fc) : mu * fabs(F);
        if (fabs(T) > crit) {
            T = T > 0.0 ? crit : -crit;
            sliding = 1;
        } else {
            sliding = 0;
        }
        a_old = a;
        acc = -F / m;
        adot += 0.5 * dt * acc;
        v += 0.5 * dt * T / m;
        w += 0.5 * dt * 2.5 * T * arm / (m * R);
        if (unloading && adot > 0.0) break;  /* pulled back before leaving: captured */
    }
    *v_out = v;
    *w_out = w;
    *sliding_out = sliding;
}

/* One adhesive particle at the wall (microimpact.wall._adhesive_oblique with adhesive_oblique_impact):
   n the unit normal, vn = v.n < 0, r and m the sphere's. Returns 1 captured, 0 bounced. */
static int microimpact__adhesive_wall(const double v_in[3], const double n[3], const double w[3], double vn, double r,
                                      double m, const microimpact_wall_params *params, double v_out[3],
                                      double omega_out[3], double *e_n)
{
    microimpact_adh_pair t;
    double V = -vn, E = params->effective_modulus, mu = params->friction;
    double tv[3], sv[3], ev[3], bv[3], slip, tmag, den, v_e, w_b, sgn, speed, angle, rad, Vn, vt, w0;
    double e, a_max, tL, scale, kG, k_lin, Fc, a_sep, th, dt, v, wr, roll_v, v1, w1, eV;
    int i, captured, sliding;

    /* the slip direction e (that of v_t where nothing slips), b = e x n, the parts along them */
    for (i = 0; i < 3; i++) tv[i] = v_in[i] - vn * n[i];
    sv[0] = tv[0] + r * (n[1] * w[2] - n[2] * w[1]);
    sv[1] = tv[1] + r * (n[2] * w[0] - n[0] * w[2]);
    sv[2] = tv[2] + r * (n[0] * w[1] - n[1] * w[0]);
    slip = sqrt(sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]);
    tmag = sqrt(tv[0] * tv[0] + tv[1] * tv[1] + tv[2] * tv[2]);
    den = slip > 0.0 ? slip : (tmag > 0.0 ? tmag : 1.0);
    for (i = 0; i < 3; i++) ev[i] = (slip > 0.0 ? sv[i] : tv[i]) / den;
    bv[0] = ev[1] * n[2] - ev[2] * n[1];
    bv[1] = ev[2] * n[0] - ev[0] * n[2];
    bv[2] = ev[0] * n[1] - ev[1] * n[0];
    v_e = tv[0] * ev[0] + tv[1] * ev[1] + tv[2] * ev[2];
    w_b = w[0] * bv[0] + w[1] * bv[1] + w[2] * bv[2];
    sgn = v_e < 0.0 ? -1.0 : 1.0;
    speed = hypot(V, v_e);
    angle = atan2(fabs(v_e), V) * (180.0 / MICROIMPACT_PI);
    if (!(angle < MICROIMPACT_ADH_ANGLE_MAX)) angle = MICROIMPACT_ADH_ANGLE_MAX;

    /* adhesive_oblique_impact at that speed and angle */
    rad = angle * (MICROIMPACT_PI / 180.0);
    Vn = speed * cos(rad);
    vt = speed * sin(rad);
    w0 = r * (sgn * w_b);
    microimpact_adh_setup(&t, E, r, m, params->limiting_pressure, params->work_of_adhesion);
    microimpact_adh_outcome(&t, Vn, &e, &a_max, &tL);
    scale = 2.0 * tL;
    if (!(isfinite(scale) && scale > 0.0)) scale = INFINITY;
    captured = !(e > 0.0);
    kG = microimpact_adh_law[2] * 2.0 * MICROIMPACT_KAPPA * E;
    k_lin = microimpact_adh_law[3] != 0.0  /* 8 G* a_m of the elastic impact at V */
                ? 2.0 * MICROIMPACT_KAPPA * E * sqrt(r * pow(15.0 * m * (V * V) / (16.0 * E * sqrt(r)), 0.4))
                : 0.0;
    Fc = microimpact_adh_pulloff(&t, a_max);
    a_sep = microimpact_adh_separation_approach_after(&t, a_max);
    th = microimpact_adh_hertz_time(Vn, E, r, m);
    dt = (scale < th ? scale : th) / MICROIMPACT_ADH_STEPS;
    microimpact_adh_run(&t, Vn, vt, w0, mu, kG, k_lin, Fc, a_sep, dt, &v, &wr, &sliding);

    /* a captured contact that sticks keeps the rolling motion */
    roll_v = (5.0 * v - 2.0 * wr) / 7.0;
    if (captured && !sliding) {
        v = roll_v;
        wr = -roll_v;
    }
    v1 = sgn * v;
    w1 = sgn * (wr / r);
    eV = captured ? 0.0 : e * V;
    for (i = 0; i < 3; i++) v_out[i] = (tv[i] - v_e * ev[i]) + v1 * ev[i] + eV * n[i];
    if (omega_out)
        for (i = 0; i < 3; i++) omega_out[i] = (w[i] - w_b * bv[i]) + w1 * bv[i];
    if (e_n) *e_n = captured ? 0.0 : e;
    return captured ? 1 : 0;
}

"""
