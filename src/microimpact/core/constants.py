"""Model constants, each named once (seed paper and the sources cited beside each)."""

from __future__ import annotations

import sys

__all__ = ["LARGE_STRAIN_RATIO", "DEFAULT_K", "TINY_NORMAL", "UNIT_ROUNDOFF"]

#: Contact radius over effective radius above which the small-strain assumption of Hertz's theory
#: is no longer good (seed, Section 2; Johnson, *Contact Mechanics*, 1985, §4.2); results beyond it
#: are flagged (``large_strain``), not refused.
LARGE_STRAIN_RATIO = 0.3

#: Default ratio ``k = p_y / Y`` of limiting contact pressure to yield strength. The seed takes ``k``
#: "in the range of 2.1-2.3" (after Hardy et al. 1971); its two cases give 156/74 = 2.11 (silicon)
#: and 158/68 = 2.32 (mica). We take the middle of the stated range, 2.2.
DEFAULT_K = 2.2

#: The smallest normal double: below it a number has lost precision (subnormal) and its reciprocal
#: overflows; a quantity of a formula that falls below it gets the formula's limit or a NaN.
TINY_NORMAL = sys.float_info.min

#: The unit roundoff of doubles, ``2^-53``: a term below this fraction of another is lost in their sum.
UNIT_ROUNDOFF = 2.0**-53
