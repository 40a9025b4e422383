"""Model constants, each named once (seed paper and the sources cited beside each)."""

from __future__ import annotations

__all__ = ["LARGE_STRAIN_RATIO", "DEFAULT_K"]

#: Contact radius over effective radius above which the small-strain assumption of Hertz's theory
#: is no longer good (seed, Section 2; Johnson, *Contact Mechanics*, 1985, §4.2); results beyond it
#: are flagged (``large_strain``), not refused.
LARGE_STRAIN_RATIO = 0.3

#: ``k`` of ``p_y = k Y``: the middle of the seed's range 2.1-2.3 (its own two cases give 2.11 and 2.32).
DEFAULT_K = 2.2
