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
    """The physics core's scalar ``outcome`` of the default model, or None where it has not landed.

    Returns
    -------
    callable or None
        ``outcome(V, E, R, m, p_y, params)`` -> tuple of floats (plain Python with ``math``), with
        the model's default parameters bound as ``params``.
    """
    try:
        from microimpact.core import models
    except ImportError:
        return None
    get = getattr(models, "get", None)
    if get is None:
        return None
    try:
        model = get()
    except ValueError:  # the registry is there, the model file not yet
        return None
    outcome = getattr(model, "outcome", None)
    if outcome is None:
        return None
    params = tuple(getattr(model, "DEFAULTS", ()))
    py = getattr(outcome, "py_func", outcome)  # the plain-Python function, never a compiled one
    return lambda V, E, R, m, p_y: py(V, E, R, m, p_y, params)
