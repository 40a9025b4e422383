"""The one table of quantities, for the application modules and the command line.

The names of :mod:`microimpact.core.quantities` (name, SI unit, description, equation, symbol,
display unit and scale, format and input check of every number microimpact reports or takes),
re-exported so that code outside the physics core, the CLI above all, reads labels from here.
Its ``__all__`` is the core module's: a name added there is here too.
"""

from __future__ import annotations

from .core import quantities as _core
from .core.quantities import *  # noqa: F403  (every public name of the core's table, no other)

__all__ = list(_core.__all__)
