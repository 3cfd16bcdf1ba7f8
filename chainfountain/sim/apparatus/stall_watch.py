"""Watching the chain's speed: a machine whose carts hold the chain back harder than the
falling chain pulls it on stops, as a real one would. The run then ends with
:class:`ChainStalled` and one plain sentence saying what to change."""

from __future__ import annotations

from chainfountain.errors import RunEnded
from chainfountain.sim.apparatus.parts import Clock, RollerUnit
from chainfountain.sim.config import ApparatusConfig

STALL_FRACTION = 0.3
"""The chain counts as stopping below this fraction of the level's start speed."""
STALL_TIME = 0.5
"""... for this long without a break (s)."""
STALL_EVERY = 0.01
"""How often the speed is read (s of simulated time)."""


class ChainStalled(RunEnded):
    """The chain has (nearly) stopped: the carts hold it back harder than the fall pulls
    it on (raised by :meth:`~chainfountain.sim.apparatus.Apparatus.after_step`)."""


class StallWatch:
    """The stall check."""

    def __init__(self, cfg: ApparatusConfig, upper: RollerUnit, lower: RollerUnit | None,
                 clock: Clock) -> None:
        self.cfg = cfg
        self.upper = upper
        self.lower = lower
        self.clock = clock
        self._slow_t = 0.0
        """How long (s) the chain has run below :data:`STALL_FRACTION` of its start speed."""
        self._stall_clock = 0.0

    @property
    def speed(self) -> float:
        """Chain speed: twice the pick-up roller speed."""
        return 2.0 * abs(self.upper.speed)

    def check(self, dt: float) -> None:
        """Raise :class:`ChainStalled` after :data:`STALL_TIME` below
        :data:`STALL_FRACTION` of the start speed (read every :data:`STALL_EVERY` s)."""
        self._stall_clock += dt
        if self._stall_clock < STALL_EVERY:
            return
        elapsed, self._stall_clock = self._stall_clock, 0.0
        if self.speed >= STALL_FRACTION * self.cfg.speed:
            self._slow_t = 0.0
            return
        self._slow_t += elapsed
        if self._slow_t >= STALL_TIME:
            raise ChainStalled(self.stall_message())

    def stall_message(self) -> str:
        """One sentence: what happened and what to change."""
        carts = [(name, unit.cart.mass) for name, unit in (("upper", self.upper),
                                                          ("lower", self.lower))
                 if unit is not None and unit.cart is not None]
        held = ", ".join(f"{name} cart {1000 * m:.3g} g" for name, m in carts) or "the machine"
        return (f"t = {self.clock.t:.2f} s: the chain has stopped: {held} holds it back harder "
                "than the falling chain pulls it on; make the upper cart lighter "
                "(carts[0].mass)")
