"""
Fig. 7: force against time, elastic-plastic and equivalent elastic
==================================================================

At 70 m/s, the elastic-plastic impact against the same pair without yielding
(:meth:`ContactPair.elastic_equivalent
<microimpact.pair.ContactPair.elastic_equivalent>`): the elastic-plastic force
is asymmetric and its contact lasts longer.
"""

from microimpact.figures import plot_force_time

ax = plot_force_time(70.0)
