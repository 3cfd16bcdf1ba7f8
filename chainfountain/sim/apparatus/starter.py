"""Starting the machine from rest (``initial.mode = "stub"``, ``apparatus.starter > 0``).

A real chain-fountain machine is started by hand: at rest its carts hold the chain and
nothing falls. The starter is that hand, a motor in the upper joint guide: it runs the
links held there along the guide, from rest up to ``apparatus.speed`` over
:data:`RAMP` s, and holds that speed until the chain has landed and ``apparatus.starter``
seconds after. Then it lets go, and the carts and the fall alone drive the chain, which
settles at the speed the machine selects (a mixin of
:class:`~chainfountain.sim.apparatus.Apparatus`).
"""

from __future__ import annotations

import math

from chainfountain.errors import RunEnded

RAMP = 0.5
"""Time (s) over which the starter runs the chain up from rest to ``apparatus.speed``."""
LAND_WITHIN = 10.0
"""Time (s) by which a started chain must have reached the floor (it takes about 1 s)."""


def run_along(guide: list, queues: list, v: float) -> None:
    """Set the links held in a joint guide (``guide``'s elements, ``queues`` their held
    ``(link, joint)`` pairs) moving along it at ``v``: along a straight's line, on a bend
    along its tangent."""
    for el, q in zip(guide, queues, strict=True):
        if el.kind == "line":
            (ax, ay), (bx, by) = el.a, el.b
            ln = math.hypot(bx - ax, by - ay)
            vel = (v * (bx - ax) / ln, v * (by - ay) / ln)
            for link, _ in q:
                link.body.velocity = vel
            continue
        cx, cy = el.a
        turn = 1.0 if el.ccw else -1.0
        for link, _ in q:
            p = link.body.position
            dx, dy = p.x - cx, p.y - cy
            d = math.hypot(dx, dy) or 1.0
            link.body.velocity = (-turn * v * dy / d, turn * v * dx / d)


class StarterFailed(RunEnded):
    """The starter could not run the chain up to the floor (raised by
    :meth:`StarterPart._check_starter`)."""


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
        """Set the links held in the upper guide moving along it at :attr:`starter_speed`
        (before each step; the solver passes the pull on): along a straight's line, on a
        bend along its tangent. (The last straight alone holds one link when the rise
        ``xi2*H`` is short, too little to pull the chain.)"""
        run_along(self.up_guide, self._uq, self.starter_speed)

    def _check_starter(self) -> None:
        """Let go :attr:`~chainfountain.sim.config.ApparatusConfig.starter` seconds after
        the first link has reached the floor; end the run with one sentence if the chain
        has not landed within :data:`LAND_WITHIN` s (the starter could not run it up)."""
        if self._hand_over is None and self.absorbed > 0:
            self._hand_over = self._t + float(self.cfg.starter)
        if self._hand_over is not None and self._t >= self._hand_over:
            self.starting = False
        elif self._hand_over is None and self._t > LAND_WITHIN:
            raise StarterFailed(
                f"t = {self._t:.2f} s: the starter could not run the chain up (it moves at "
                f"{self.speed:.2g} m/s and has not reached the floor): the carts hold it "
                "harder than the starter pulls; make the upper cart lighter (carts[0].mass) "
                "or lift the chain less (a smaller apparatus.xi2)")
