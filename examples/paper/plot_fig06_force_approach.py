"""
Fig. 6: force against approach
==============================

Loading (Hertz, then the common plastic line of seed eq. 8) and elastic
unloading (eq. 10) at 30, 50 and 70 m/s. The unloading curves start steeper the
harder the impact, because the contact has flattened more (``R_p``, eq. 9).
"""

from microimpact.figures import plot_force_displacement

ax = plot_force_displacement([30.0, 50.0, 70.0])
