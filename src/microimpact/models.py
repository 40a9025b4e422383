"""Impact models by name: ``microimpact.models.available()`` and what each one takes.

Each model is one file in :mod:`microimpact.core.models`; pick one with
``pair.impact(V, model=NAME)`` (the default is the seed's, ``"thornton_ning_2016"``).
"""

from __future__ import annotations

from .core.models import DEFAULT, available, get, parameters

__all__ = ["available", "get", "parameters", "DEFAULT"]
