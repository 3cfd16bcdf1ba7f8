"""Starting the machine from rest (``initial.mode = "stub"``, ``apparatus.starter > 0``).

A real chain-fountain machine is started by hand: at rest its carts hold the chain and
nothing falls. The starter is that hand, a motor in the upper joint guide's last straight:
it runs the links there along the launch line, from rest up to ``apparatus.speed`` over
:data:`RAMP` s, and holds that speed until the chain has landed and ``apparatus.starter``
seconds after. Then it lets go, and the carts and the fall alone drive the chain, which
settles at the speed the machine selects (a mixin of
:class:`~chainfountain.sim.apparatus.Apparatus`).
"""

from __future__ import annotations

RAMP = 0.5
"""Time (s) over which the starter runs the chain up from rest to ``apparatus.speed``."""


class StarterPart:
    """The starter motor (a mixin of :class:`~chainfountain.sim.apparatus.Apparatus`)."""

    def _init_starter_state(self) -> None:
        self.starting = self.from_rest
        """True while the starter drives the chain."""
        self._hand_over: float | None = None
        """When the starter lets go (s): set once the first link reaches the floor."""

    @property
    def starter_speed(self) -> float:
        """The speed (m/s) the starter runs the chain at now."""
        return float(self.cfg.speed) * min(1.0, self._t / RAMP)

    def _drive_starter(self) -> None:
        """Set the links in the upper guide's last straight moving along the launch line
        at :attr:`starter_speed` (before each step; the solver passes the pull on)."""
        v = self.starter_speed
        vx, vy = v * self.launch_u[0], v * self.launch_u[1]
        for link, _ in self._uq[-1]:
            link.body.velocity = (vx, vy)

    def _check_starter(self) -> None:
        """Let go :attr:`~chainfountain.sim.config.ApparatusConfig.starter` seconds after
        the first link has reached the floor."""
        if self._hand_over is None and self.absorbed > 0:
            self._hand_over = self._t + float(self.cfg.starter)
        if self._hand_over is not None and self._t >= self._hand_over:
            self.starting = False
