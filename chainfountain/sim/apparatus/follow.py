"""The end guide that follows the fountain's landing ('fold' with ``apparatus.end_follow``
> 0; a mixin of :class:`~chainfountain.sim.apparatus.Apparatus`).

The paper's carts and offsets choose the fountain, and with it where the fountain lands:
about 2 cm per gram of the upper cart in ``apparatus_fold_gripped``. A fixed end guide
catches the chain only within a few centimetres of its turn's radius, so changing a cart by
more than a few grams lost the chain. Here the end guide's turn, rise and second turn ride
on a horizontal slide: every bookkeeping step they move by ``-end_follow * dr * dt``,
``dr`` being the offset from the first turn's radius of the links it catches (> 0
outside, i.e. landed short), averaged over :data:`FOLLOW_TAU`, at most
:data:`FOLLOW_SPEED` and :data:`FOLLOW_TRAVEL` from where the level put them. The links
held in the moving elements follow their joints' anchors (at most 50 um a step). The
heights do not change, so neither do the paper's laws (``xi3*H`` is the same); only the
fountain's span is free, as it is in the paper's laws.

A following guide also has a wide mouth (:data:`~.tuning.FOLLOW_CAPTURE`, closing in at
:data:`~.tuning.FOLLOW_CLOSE_RATE`): the guide follows the landing's mean, the mouth
takes its swing. Measured (docs/apparatus.md, "An end guide that follows the landing").
"""

from __future__ import annotations

from chainfountain.sim import fastbody
from chainfountain.sim.apparatus.tuning import FOLLOW_SPEED, FOLLOW_TAU, FOLLOW_TRAVEL


class FollowingEnd:
    """The following end guide (a mixin of :class:`~chainfountain.sim.apparatus.Apparatus`)."""

    def _init_follow_state(self) -> None:
        self.end_follow = float(self.cfg.end_follow) if self.fold_guided else 0.0
        """Rate (1/s) at which the end guide follows the landing; 0: it stays put."""
        self.end_shift = 0.0
        """How far (m, along x) the end guide has moved from where the level put it."""
        self._follow_dr = 0.0
        self._follow_seen: float | None = None
        self._walls_shift = 0.0
        """How far the drawn walls have been moved (:meth:`sync_end_walls`)."""

    @property
    def landing_offset(self) -> float:
        """Where the fountain lands (m): the caught links' offset from the first turn's
        radius (> 0 outside: landed short), averaged over :data:`FOLLOW_TAU` by the time
        between catches; 0 before any link was caught."""
        return self._follow_dr

    def _track_landing(self) -> None:
        """Update :attr:`landing_offset` (every bookkeeping step)."""
        t, prev = self._mouth_t, self._follow_seen
        if t is not None and t != prev:  # a link has been caught since: average by time
            w = 1.0 if prev is None else min(1.0, (t - prev) / FOLLOW_TAU)
            self._follow_seen = t
            self._follow_dr += (self._mouth_dr - self._follow_dr) * w

    def _follow_landing(self, dt: float) -> None:
        """Move the end guide toward where the fountain lands (every bookkeeping step)."""
        u = max(-FOLLOW_SPEED, min(FOLLOW_SPEED, -self.end_follow * self._follow_dr))
        dx = max(-FOLLOW_TRAVEL - self.end_shift, min(FOLLOW_TRAVEL - self.end_shift, u * dt))
        if dx:
            self._shift_end_guide(dx)

    def _shift_end_guide(self, dx: float) -> None:
        """Move the end guide's turn, rise and second turn, their held links' joints and
        the lower plate's start by ``dx`` along x (the drawn walls follow when read,
        :meth:`sync_end_walls`)."""
        els, qs = self.guide, self._gq
        last = len(els) - 1
        handle = fastbody.constraint_handle
        set_anchor = fastbody.set_slide_anchor_a
        set_ga, set_gb = fastbody.set_groove_a, fastbody.set_groove_b
        for k, (el, q) in enumerate(zip(els, qs, strict=True)):
            if el.kind == "arc":
                el.a = el.b = c = (el.a[0] + dx, el.a[1])
                for _, j in q:  # every arc joint is anchored at the arc's centre
                    set_anchor(handle(j), c)
                continue
            el.a = (el.a[0] + dx, el.a[1])
            if k == last:  # the lower plate: only its start moves (its grooves are along it)
                continue
            el.b = (el.b[0] + dx, el.b[1])
            ga, gb = el.groove_ends()
            for _, j in q:
                h = handle(j)
                set_ga(h, ga)
                set_gb(h, gb)
        cx, cy = self.guide_centre
        self.guide_centre = (cx + dx, cy)
        self.x_plate_lo_start += dx
        self.end = (self.end[0] + dx, self.end[1])
        if self.channel_lo is not None:
            self.channel_lo[:, 0] += dx
        if self.plate_lo is not None:
            a, b = self.plate_lo.a, self.plate_lo.b
            self.plate_lo.unsafe_set_endpoints((a.x + dx, a.y), b)
        self.end_shift += dx

    def sync_end_walls(self) -> None:
        """Put the end channel's drawn walls (out of the space) where the guide is now."""
        dx = self.end_shift - self._walls_shift
        if dx:
            for s in self.end_walls:
                s.unsafe_set_endpoints((s.a.x + dx, s.a.y), (s.b.x + dx, s.b.y))
            self._walls_shift = self.end_shift
