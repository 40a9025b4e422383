"""
Fig. 9: contact times against impact speed
==========================================

``t1, t2, t_L, t_U, t_c`` from the closed forms of :ref:`theory-times`, with
Deresiewicz's elastic contact time (seed eq. 30) and Ning's high-speed loading
time (eq. 31).
"""

from microimpact.figures import plot_contact_times

ax = plot_contact_times()
