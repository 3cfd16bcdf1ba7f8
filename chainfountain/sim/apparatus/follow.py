"""The end guide that follows the fountain's landing ('fold' with ``apparatus.end_follow``
> 0).

The paper's carts and offsets choose the fountain, and with it where the fountain lands:
about 2 cm per gram of the upper cart in ``apparatus_fold_gripped``. A fixed end guide
catches the chain only within a few centimetres of its turn's radius, so changing a cart by
more than a few grams lost the chain. Here the end guide's turn, rise and second turn ride
on a horizontal slide: they move at ``-end_follow * dr``, ``dr`` being the offset from
the first turn's radius of the links it catches (> 0 outside, i.e. landed short),
averaged over :data:`FOLLOW_TAU`, at most :data:`FOLLOW_SPEED` and
:data:`FOLLOW_TRAVEL` from where the level put them. The slide is a kinematic pymunk
body (:attr:`FollowingEnd.end_carrier`) that carries the moving elements' joints, so
pymunk moves them in every step; the bookkeeping sets its velocity and keeps the
elements' coordinates in step with it. The heights do not change, so neither do the
paper's laws (``xi3*H`` is the same); only the fountain's span is free, as it is in the
paper's laws.

A following guide also has a wide mouth (:data:`~.tuning.FOLLOW_CAPTURE`, closing in at
:data:`~.tuning.FOLLOW_CLOSE_RATE`): the guide follows the landing's mean, the mouth
takes its swing. Measured (docs/apparatus.md, "An end guide that follows the landing").
"""

from __future__ import annotations

import pymunk

from chainfountain.sim import fastbody
from chainfountain.sim.apparatus.ends import EndPart
from chainfountain.sim.apparatus.fold import FoldPart
from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.tuning import FOLLOW_SPEED, FOLLOW_TAU, FOLLOW_TRAVEL


class FollowingEnd:
    """The following end guide: the slide that carries the fold's end guide, and where
    the fountain lands."""

    def __init__(self, space: pymunk.Space, layout: Layout, end: EndPart,
                 fold: FoldPart | None) -> None:
        self.end = end
        self.fold = fold
        self.end_follow = layout.end_follow
        """Rate (1/s) at which the end guide follows the landing; 0: it stays put."""
        self.end_shift = 0.0
        """How far (m, along x) the end guide has moved from where the level put it."""
        self._follow_dr = 0.0
        self._follow_seen: float | None = None
        self._walls_shift = 0.0
        """How far the drawn walls have been moved (:meth:`sync_end_walls`)."""
        self.end_carrier: pymunk.Body | None = None
        """The kinematic slide carrying the end guide's turn, rise and second turn (their
        joints are anchored on it); ``None`` when the end guide stays put."""
        if self.end_follow and fold is not None:
            self.end_carrier = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
            space.add(self.end_carrier)
            for el in fold.guide[:-1]:  # the lower plate's grooves run along it: fixed
                el.carrier = self.end_carrier

    @property
    def landing_offset(self) -> float:
        """Where the fountain lands (m): the caught links' offset from the first turn's
        radius (> 0 outside: landed short), averaged over :data:`FOLLOW_TAU` by the time
        between catches; 0 before any link was caught."""
        return self._follow_dr

    def track_landing(self) -> None:
        """Update :attr:`landing_offset` (every bookkeeping step)."""
        if self.fold is None:
            return
        t, prev = self.fold.mouth_t, self._follow_seen
        if t is not None and t != prev:  # a link has been caught since: average by time
            w = 1.0 if prev is None else min(1.0, (t - prev) / FOLLOW_TAU)
            self._follow_seen = t
            self._follow_dr += (self.fold.mouth_dr - self._follow_dr) * w

    def follow_landing(self, dt: float) -> None:
        """Set the slide's velocity toward where the fountain lands, for the next
        bookkeeping step of ``dt`` (every bookkeeping step)."""
        if self.end_carrier is None:
            return
        u = max(-FOLLOW_SPEED, min(FOLLOW_SPEED, -self.end_follow * self._follow_dr))
        dx = max(-FOLLOW_TRAVEL - self.end_shift, min(FOLLOW_TRAVEL - self.end_shift, u * dt))
        self.end_carrier.velocity = (dx / dt, 0.0)

    def sync_end_guide(self) -> None:
        """Bring the end guide's coordinates to where the slide has carried it (first in
        every bookkeeping step)."""
        if self.end_carrier is None:
            return
        dx = fastbody.pos(self.end_carrier).x - self.end_shift
        if dx:
            self._shift_end_guide(dx)

    def _shift_end_guide(self, dx: float) -> None:
        """Move the end guide's coordinates by ``dx`` along x (their joints ride on
        :attr:`end_carrier`; the drawn walls follow when read, :meth:`sync_end_walls`)."""
        if self.fold is not None:
            self.fold.shift_guide(dx)
        self.end.shift(dx)
        self.end_shift += dx

    def sync_end_walls(self) -> None:
        """Put the end channel's drawn walls (out of the space) where the guide is now."""
        dx = self.end_shift - self._walls_shift
        if dx:
            for s in self.end.end_walls:
                s.unsafe_set_endpoints((s.a.x + dx, s.a.y), (s.b.x + dx, s.b.y))
            self._walls_shift = self.end_shift
