"""Export for CFD codes: restitution tables (CSV) and a self-contained C99 wall function.

Tables of the adhesive restitution (:func:`restitution_table`, :func:`write_tables`) and a
C function computing the same outgoing velocity, spin and stick flag as
:func:`microimpact.wall.wall_interaction` for one particle, for Fluent UDFs and OpenFOAM patch
interaction models (:func:`generate_c_source`), with the rigid or the compliant
(``tangential="mindlin"``) tangential model. :func:`write_band` writes both for a fit's
estimate and the two ends of its confidence band. Sign conventions are those of
:mod:`microimpact.wall`.

One private module a subject: ``_tables`` (CSV tables), ``_csource`` (the C
source), ``_adhesive`` (the C source's adhesive oblique impact, integrated as
:mod:`microimpact.oblique.adhesive` integrates it), ``_band`` (a fit's confidence band); every
name is importable from here.
"""

from __future__ import annotations

from ._band import BAND_ENDS, band_pairs, write_band
from ._csource import generate_c_source, write_c_source
from ._tables import DEFAULT_SPEEDS, DEFAULT_V_OVER_VY, DEFAULT_VS_OVER_VY, restitution_table, write_tables  # noqa: F401  (the defaults, as before)

__all__ = [
    "restitution_table",
    "write_tables",
    "generate_c_source",
    "write_c_source",
    "BAND_ENDS",
    "band_pairs",
    "write_band",
]
