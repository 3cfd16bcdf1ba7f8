"""Treadmills (``plate_links > 0`` with ``plate = "groove"``): the upper plate strand is
kept from shrinking and ('fold') the lower one from growing, by putting links into or
taking them out of the middle of the grooved strand and moving the roller's side back,
so the rollers stay near their starts and a run may last any time.

A joint made in the tensioned strand starts warm: it gets the accumulated impulse of the
joint it replaces (:func:`~chainfountain.sim.fastbody.set_pivot_impulse`), which pymunk
applies as the warm start of its next step, as it would have for the old joint. A cold
joint starts from no force and lets the strand stretch for a few steps (in 'fold' trials
a cold joint in a plate strand every 13 steps made the lower turn yield sooner)."""

from __future__ import annotations

import math

import pymunk

from chainfountain.sim import fastbody
from chainfountain.sim.apparatus.fold import FoldPart
from chainfountain.sim.apparatus.grip import GrippedFold
from chainfountain.sim.apparatus.grooves import PlateGrooves
from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.parts import RollerUnit
from chainfountain.sim.chain import Chain

MAX_INSERTS = 8
"""Most links the upper treadmill puts in per bookkeeping step (1-mm links at 3 m/s with
the bookkeeping every 1 ms need 2: the roller rolls 1.5 mm a step)."""


class Treadmills:
    """The plate treadmills, and how far each roller has rolled."""

    def __init__(self, space: pymunk.Space, chain: Chain, layout: Layout, upper: RollerUnit,
                 grooves: PlateGrooves, fold: FoldPart | None,
                 grip: GrippedFold | None) -> None:
        self.space = space
        self.chain = chain
        self.layout = layout
        self.upper = upper
        self.lower = fold.lower if fold is not None else None
        self.grooves = grooves
        self.fold = fold
        self.grip = grip
        self.start_x = (upper.x, self.lower.x if self.lower is not None else 0.0)
        """The rollers' start x (m; 0 for a missing folding roller)."""
        self.moved_back = 0
        """Treadmill: links added to the upper plate strand."""
        self.shifted = 0.0
        """Treadmill: distance (m) the pick-up roller unit was moved back."""
        self.cut = 0
        """'fold' treadmill: links taken out of the lower plate strand."""
        self.shifted_lo = 0.0
        """'fold' treadmill: distance (m) the folding roller unit was moved back."""

    def travel(self, i: int) -> float:
        """Distance (m) roller ``i`` (0 upper, 1 lower) has rolled since the start,
        the treadmills' moves back included."""
        u = (self.upper, self.lower)[i]
        if u is None:
            return 0.0
        return abs(u.x - self.start_x[i] + (self.shifted, self.shifted_lo)[i])

    def _shift_back(self, bodies: list[pymunk.Body], dx: float) -> None:
        """Move ``bodies`` by ``dx`` (m) in ``-x`` (velocities unchanged)."""
        get_p, set_p, handle = fastbody.get_position, fastbody.set_position, fastbody.handle
        for b in bodies:
            h = handle(b)
            p = get_p(h)
            set_p(h, (p.x - dx, p.y))

    def treadmill_upper(self) -> int:
        """Keep the upper plate strand from shrinking: once the pick-up roller has moved
        half a link length past its start, insert a link into the middle of the grooved
        strand and move everything upstream of it (strand, wrap, resting chain, roller
        and carriage) back by one link length; as many links as the roller has rolled
        since the last bookkeeping step (more than one only for links shorter than the
        roller's roll per step, ``v dt / 2``). The strand is straight, horizontal and
        frictionless and all its links move at the chain speed, so the new link (the
        mean velocity of its neighbours, laid exactly into the gap) changes nothing but
        the strand's length; the pick-up (roller on the resting chain) is moved rigidly
        and is untouched. Returns how many links went in."""
        n = 0
        for _ in range(MAX_INSERTS):
            if not self._insert_upper():
                break
            n += 1
        return n

    def _insert_upper(self) -> bool:
        """One link into the upper strand (:meth:`treadmill_upper`); whether it went in."""
        up = self.upper
        L = self.layout.L
        g = self.grooves.held
        if up.x - self.start_x[0] < 0.5 * L or len(g) < 4:
            return False
        chain = self.chain
        links = chain.links
        m = len(g) // 2
        a_link = g[m][0]
        i = chain.ids.index(a_link.id)
        b_link = links[i + 1]
        if g[m + 1][0] is not b_link:
            return False  # not a contiguous strand (should not happen): skip this step
        h = 0.5 * L
        pa = a_link.body.local_to_world((-h, 0.0))
        pb = b_link.body.local_to_world((h, 0.0))
        dy = pa.y - pb.y
        dx = math.sqrt(max(L * L - dy * dy, 0.0)) - (pa.x - pb.x)
        self._shift_back([lk.body for lk in links[i + 1:]] + [up.roller, up.carriage], dx)
        self.shifted += dx
        pb = pymunk.Vec2d(pb.x - dx, pb.y)
        ab = a_link.body
        j = fastbody.pivot_impulse(a_link.up_joint) if a_link.up_joint else (0.0, 0.0)
        vel = 0.5 * (ab.velocity + b_link.body.velocity)
        new = chain.make_body((0.5 * (pa.x + pb.x), 0.5 * (pa.y + pb.y)),
                              math.atan2(pa.y - pb.y, pa.x - pb.x), velocity=tuple(vel))
        chain.insert(i + 1, new, with_shape=False)  # grooved: out of the broadphase
        for lk in (a_link, new):
            if lk.up_joint is not None:
                fastbody.set_pivot_impulse(lk.up_joint, j)
        g.insert(m + 1, (new, self.grooves.groove_joint(new.body)))
        self.grooves.next_index += 1
        self.moved_back += 1
        return True

    def treadmill_lower(self) -> None:
        """'fold': keep the lower plate strand from growing, the mirror of
        :meth:`treadmill_upper`. Once the folding roller has moved one link length past
        its start, take two neighbouring links out of the middle of the grooved strand
        and move everything downstream of them (strand, wrap, laid chain, roller and
        carriage) back by the gap, so the roller stays within about a link of its start.

        Two, not one: the grooves hold the link centres on the line and leave the angles
        free, and the strand settles into a regular zigzag (angles alternating by about
        +-0.07 rad). Cutting one link leaves its neighbours' free ends 1.3 mm apart in
        ``y``, which the joints close only slowly; cutting two keeps the zigzag's phase
        and the ends meet. Of the pairs near the middle, the one whose ends meet best in
        ``y`` is cut. The strand is straight, horizontal, frictionless and moves as one,
        so the cut changes only its length."""
        lo, fold = self.lower, self.fold
        if lo is None or fold is None:
            return
        L = self.layout.L
        q = fold.held[-1]
        if lo.x - self.start_x[1] < L or len(q) < 10:
            return
        chain = self.chain
        links = chain.links
        h = 0.5 * L
        best = None
        for m in range(len(q) // 2 - 3, len(q) // 2 + 3):
            dn, up = q[m - 1][0], q[m + 2][0]
            i = chain.ids.index(q[m][0].id)
            if links[i - 1] is not dn or links[i + 1] is not q[m + 1][0] or \
                    links[i + 2] is not up:
                continue  # not contiguous (should not happen)
            pd = dn.body.local_to_world((-h, 0.0))
            pu = up.body.local_to_world((h, 0.0))
            if best is None or abs(pd.y - pu.y) < best[0]:
                best = (abs(pd.y - pu.y), m, i, pd.x - pu.x)
        if best is None:
            return
        _, m, i, dx = best
        c = links[i + 1]
        j = fastbody.pivot_impulse(c.up_joint) if c.up_joint else (0.0, 0.0)
        self._shift_back([lk.body for lk in links[:i]] + [lo.roller, lo.carriage], dx)
        if self.grip is not None:
            self.grip.shift_pin(dx)
        self.shifted_lo += dx
        for k in (m + 1, m):
            self.space.remove(q[k][1])
            del q[k]
        chain.remove(i + 1)
        chain.remove(i)
        if links[i - 1].up_joint is not None:
            fastbody.set_pivot_impulse(links[i - 1].up_joint, j)
        fold.reindex(2)
        self.grooves.next_index -= 2
        self.cut += 2
