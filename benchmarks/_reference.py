"""Plain-Python references the suite times the library against (``math`` only, one float in).

These are the floor of what one Python function call computing the same number costs; the
suite reports how many times that the public API takes.
"""

from __future__ import annotations

import math


def restitution_reference(velocity: float, yield_velocity: float) -> float:
    """Restitution coefficient ``e`` [-] of one impact, in plain Python.

    Thornton & Ning's (1998) closed form as written on the theory page, eq. (D2), with
    ``w = V_y / V``; equal to the seed's eq. 27 (the test-suite checks the identity to 1e-12)::

        e = (6 sqrt(3) / 5)^(1/2) (1 - w^2/6)^(1/2) [w / (w + 2 (6/5 - w^2/5)^(1/2))]^(1/4)

    and ``e = 1`` for ``V <= V_y``.

    Parameters
    ----------
    velocity : float
        Impact speed ``V`` [m/s].
    yield_velocity : float
        Yield velocity ``V_y`` [m/s] (seed eq. 28).

    Returns
    -------
    float
        ``e`` [-].
    """
    if velocity <= yield_velocity:
        return 1.0
    w = yield_velocity / velocity
    return (
        math.sqrt(6.0 * math.sqrt(3.0) / 5.0)
        * math.sqrt(1.0 - w * w / 6.0)
        * (w / (w + 2.0 * math.sqrt(6.0 / 5.0 - w * w / 5.0))) ** 0.25
    )


def core_outcome():
    """The physics core's scalar ``outcome`` of the default model, in plain Python.

    Returns
    -------
    callable
        ``outcome(V, E, R, m, p_y)`` -> tuple of floats (plain Python with ``math``, never a
        compiled function), with the model's default parameters bound.
    """
    from microimpact.core import models

    model = models.get()
    params = tuple(model.DEFAULTS)
    py = getattr(model.outcome, "py_func", model.outcome)
    return lambda V, E, R, m, p_y: py(V, E, R, m, p_y, params)


def outcome_reference(V: float, E: float, R: float, m: float, p_y: float) -> tuple:
    """The seed's full outcome of one plastic impact (``V >= 2 V_y``, finite ``p_y``) as one flat function.

    The closed forms of seed eqs. 5-33 written out in one body, with no function calls but ``math``
    and the scaled Hertz time integral (the core's
    :func:`~microimpact.core.special.hertz_beta_scaled`, itself plain Python): the floor of what one
    Python call returning the 18 numbers costs. Same operations in the same order as the core for
    ``V >= 2 V_y`` (there the core takes no branch this body leaves out), so the numbers are bitwise
    the same (the suite asserts it).

    Returns
    -------
    tuple of float
        In the order of :data:`microimpact.core.quantities.OUTCOME_FIELDS`.
    """
    from microimpact.core.special import BETA_25_12, hertz_beta_scaled

    sqR = math.sqrt(R)
    ac = math.pi * p_y * R / (2.0 * E)
    a_y = ac * ac / R
    P_y = 4.0 / 3.0 * E * sqR * (a_y * math.sqrt(a_y))
    Vy = math.sqrt(0.8 * P_y * a_y / m)
    v = V / Vy
    q = math.sqrt((24.0 - 4.0 / (v * v)) / 5.0)
    A = (1.0 + v * q) / 3.0
    Phat = 0.5 * v * q
    sqA = math.sqrt(A)
    a_p = a_y * max(A - Phat / sqA, 0.0)
    qe = math.sqrt((24.0 - 4.0 / (v * v)) * 0.2)
    e = 0.5 * qe / math.sqrt(math.sqrt((1.0 + v * qe) * (1.0 / 3.0)))
    a_star = a_y * A
    P_star = P_y * Phat
    R_p = R * (A * sqA / Phat)
    V_r = e * V
    a_max = math.sqrt(R * a_star)
    w = Vy / V
    t1 = 0.4 * (a_y / V) * hertz_beta_scaled(w * w)
    omega = math.sqrt(math.pi * p_y * R / m)
    t2 = math.atan2(math.sqrt((V - Vy) * (V + Vy)), 2.0 * omega * a_y / 3.0) / omega
    tU = 0.4 * BETA_25_12 * (a_y * min(Phat / sqA, A)) / V_r
    tL = t1 + t2
    return (V, Vy, v, 0.0, e, V_r, a_star, a_p, P_star, R_p, 1.0 - e * e, a_max,
            1.0 if a_max / R > 0.3 else 0.0, t1, t2, tL, tU, tL + tU)  # fmt: skip
