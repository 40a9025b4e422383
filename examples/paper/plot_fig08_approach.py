"""
Fig. 8: maximum approach and plastic share
==========================================

The maximum approach ``alpha*`` (seed eq. 22) and the ratio
``alpha_p / alpha*`` (eq. 11) against the impact speed.
"""

from microimpact.figures import plot_approach

ax = plot_approach()
