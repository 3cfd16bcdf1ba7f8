"""What drives the chain's two ends: the :class:`Ends` protocol.

Every fountain kind builds one object that feeds the chain in at one end and takes it
away at the other, and the :class:`~chainfountain.sim.world.Simulation` steps it around
each physics step: a motor's :class:`~chainfountain.sim.feed.Feed` (guide and floor), an
ideal machine's :class:`~chainfountain.sim.piston.Piston` (which holds a feed), the
:class:`~chainfountain.sim.apparatus.Apparatus` and the :class:`~chainfountain.sim.beaker.Beaker`.
"""

from __future__ import annotations

from typing import Protocol


class Ends(Protocol):
    """The chain's two ends as the simulation steps and reads them."""

    absorbed: int
    """Links taken away at the downstream end so far."""

    @property
    def speed(self) -> float:
        """The chain's speed (m/s) as the ends' bookkeeping runs it."""
        ...

    @property
    def n_free(self) -> int:
        """Dynamic (free) links, counted from the downstream end."""
        ...

    @property
    def floor_y(self) -> float:
        """Height (m) at which the downstream end is taken away."""
        ...

    @property
    def u(self) -> tuple[float, float]:
        """Unit launch direction at the origin."""
        ...

    def before_step(self) -> None:
        """Apply the ends' forces before each pymunk step."""
        ...

    def after_step(self, dt: float) -> None:
        """The ends' bookkeeping after each time step ``dt`` (s): links fed in, released,
        taken away; may raise :class:`~chainfountain.errors.RunEnded`."""
        ...
