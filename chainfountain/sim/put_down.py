"""The ideal full machine's lower half as the floor's pull on the chain end.

With ``feed.drive = "ideal_fold"`` the chain that lands on the absorbing floor is taken
by the paper's lower half (section "Generating Steady-State Chain Fountains"): it is
lifted ``xi3 H`` to the raised bottom and put down at rest by a massless roller at the
loss-free rate ``lambda v^2/2``, with a lower cart adding ``F_lc``. The pull on the end
is then

    T_E = lambda v^2/2 + F_lc - c v/2 - lambda g xi3 H,  i.e.  Tbar_E = 1/2 + Tbar_lc - xi3 k H

at the chain's present speed ``v``, where the folding roller's bearing drag ``c v/2``
(``feed.bearing_drag = c``, 0 in the paper) counts as part of the lower cart. A strand
cannot push: below :func:`~chainfountain.theory.apparatus.ideal_fold_slack_speed` it goes
slack and the end is free. The upper half is the :class:`~chainfountain.sim.piston.Piston`.
"""

from __future__ import annotations

from typing import Any


class PutDown:
    """The lower half's law as the floor's pull on the chain end (:meth:`pull`, the feed's
    ``end_pull``)."""

    def __init__(self, sim: Any) -> None:
        """``sim``: the :class:`~chainfountain.sim.world.Simulation` being built."""
        self.sim = sim

    def pull(self, v: float) -> float:
        """The pull ``T_E`` (N, at least 0) on the chain end at speed ``v`` (m/s)."""
        f = self.sim.config.feed
        lam = self.sim.chain.cfg.linear_density
        drag = 0.5 * f.bearing_drag * v  # the folding roller's bearing
        return max(0.0, 0.5 * lam * v * v + f.lower_cart_force - drag
                   - lam * self.sim.g * f.xi3 * f.drop)
