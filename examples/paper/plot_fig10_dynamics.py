"""
Fig. 10: one impact in time
===========================

Velocity, force and approach during an impact at 50 m/s, evaluated from the
closed-form history (no ODE).
"""

from microimpact.figures import plot_dynamics

ax = plot_dynamics(50.0)

# %%
# The same history with the stages shaded, from any pair's
# :meth:`ContactPair.history <microimpact.pair.ContactPair.history>`:

import microimpact as mi
from microimpact.figures import plot_history

history = mi.ContactPair.paper_case("silicon").history(50.0)
axes = plot_history(history)
