"""Model constants, each named once (seed paper and the sources cited beside each)."""

from __future__ import annotations

__all__ = ["LARGE_STRAIN_RATIO", "DEFAULT_K"]

#: Contact radius over effective radius above which the small-strain assumption of Hertz's theory
#: is no longer good (seed, Section 2; Johnson, *Contact Mechanics*, 1985, §4.2); results beyond it
#: are flagged (``large_strain``), not refused.
LARGE_STRAIN_RATIO = 0.3

#: Default ratio ``k = p_y / Y`` of limiting contact pressure to yield strength. The seed takes ``k``
#: "in the range of 2.1-2.3" (after Hardy et al. 1971); its two cases give 156/74 = 2.11 (silicon)
#: and 158/68 = 2.32 (mica). We take the middle of the stated range, 2.2.
DEFAULT_K = 2.2
