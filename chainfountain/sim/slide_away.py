"""The open arrangement's lower half with ideal parts: the landed chain slides away.

With ``feed.drive = "ideal_open"`` (paper, Fig. "pulley_experiment_equiv_ground", right:
"without subsequent deceleration of chain elements as more and more chain elements are in
motion over time") the chain that lands on the absorbing floor runs down a loss-free turn
of height ``d = feed.turn_drop`` onto a long frictionless plate and slides away at the
chain's speed. Three things follow:

- the chain hanging in the turn pulls the end with its weight, ``T_E = lambda g d``
  (``Tbar_E = k d``); the tail on the frictionless plate pulls nothing while the speed
  holds;
- each landed link joins the chain in motion: its mass is added to the machine's inertia
  (:meth:`~chainfountain.sim.piston.Piston.carry`), which keeps the speed and the kinetic
  energy. The chain is inextensible and all of it moves at one speed, so lumping the tail
  at the piston changes only where its inertia is taken up: while the speed changes at
  ``a`` the fountain's tensions sit ``M_tail a`` below those of a tail pulling at the end
  (the headless summary states the largest such offset of a run);
- the plate carries the chain laid on it: its reaction grows by ``lambda g`` per metre
  landed, at ``lambda g v`` (paper: "the reaction force change is exactly known over
  time"). It is counted from the links the floor takes, not simulated as contacts.

The upper half is the :class:`~chainfountain.sim.piston.Piston` of the idealized beaker.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

PLATE_REACH = 50.0
"""Length (m) of the plate drawn beyond the turn: far past any view."""


class SlideAway:
    """The turn's weight as the floor's pull (:meth:`pull`, the feed's ``end_pull``); hands
    the landed chain's mass to the level's piston (:meth:`landed`, called by it)."""

    def __init__(self, sim: Any) -> None:
        """``sim``: the :class:`~chainfountain.sim.world.Simulation` being built (its
        :attr:`~chainfountain.sim.world.Simulation.piston` is in place once it runs)."""
        self.sim = sim
        self.links = 0
        """Links landed on the plate so far (they slide away with the chain)."""

    @property
    def mass(self) -> float:
        """Mass (kg) of the chain sliding on the plate: it moves with the chain."""
        return self.links * self.sim.chain.mass

    @property
    def plate_reaction(self) -> float:
        """The plate's reaction force (N): the weight of the chain lying on it."""
        return self.mass * self.sim.g

    def pull(self, v: float) -> float:
        """The pull ``T_E = lambda g d`` (N) of the turn on the chain end (whatever ``v``)."""
        lam = self.sim.chain.cfg.linear_density
        return lam * self.sim.g * self.sim.config.feed.turn_drop

    def landed(self, absorbed: int) -> None:
        """The floor has now taken ``absorbed`` links in all: the new ones join the
        chain in motion."""
        new = absorbed - self.links
        if new > 0:
            self.links = absorbed
            self.sim.piston.carry(new * self.sim.chain.mass)

    @property
    def slid(self) -> float:
        """Length (m) of chain that has landed and slid onto the plate."""
        return self.links * self.sim.chain.L

    def path(self, x_end: float, y_end: float) -> np.ndarray:
        """The landed chain's path ``(n, 2)`` (m, world): from the fountain's end
        ``(x_end, y_end)`` down a quarter turn of radius ``turn_drop`` onto the plate,
        then along the plate for :data:`PLATE_REACH` (a picture of the parts the model
        replaces by their laws; the view draws it)."""
        d = float(self.sim.config.feed.turn_drop)
        th = np.linspace(math.pi, 1.5 * math.pi, 13) if d > 0.0 else np.array([math.pi])
        turn = np.column_stack([x_end + d + d * np.cos(th), y_end + d * np.sin(th)])
        plate = np.array([[x_end + d + PLATE_REACH, y_end - d]])
        return np.vstack([turn, plate])
