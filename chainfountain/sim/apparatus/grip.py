"""'fold' with ``fold_roller = "gripped"``: the folding roller holds the chain by joints.

The contact folding roller grips the chain by friction and is not converged in the step
(``docs/apparatus.md``, "The fold depends on the time step"). The gripped roller puts the
chain down without friction or contact (``research/joint_putdown_weld.py`` is the rig it
was measured in):

* **Grip.** When the back joint of the strand's last link passes over the roller's centre
  (or comes within :data:`GRIP_TOL` of the rim), the link is *welded* to the roller: a
  pivot at its front joint (already on the rim) and a gear holding its angle, both made
  where the link is, so the weld starts without error. The gear's target is the chord
  from the front joint to the rim point one link length on (the *catch*): the link is
  turned onto the rim by the gear's error correction within :data:`CATCH_TIME`, with no
  jump in position. The chain joint between two welded links is removed (it would close
  a loop through the roller).
* **Carry.** The roller turns on an axle pinned to its carriage (fixed height, no
  slot), so with its welded links it is one linkage between the strand and the chain on
  the table, moved by the strand's pull and the lower cart only.
* **Land.** When the lowest welded link's front joint passes under the roller's centre
  (at the bottom of its circle it has no velocity), the link is un-welded and its front
  pinned to the table where it is; the link that landed before it (both ends now down)
  leaves the space. The laid chain is at rest by construction.

Loss-free, the power balance gives the arriving strand the pull
``lambda v^2/4 + F_lc/2 + lambda g R`` at ``alpha = 0`` (``R``: the chain's radius on
the roller, which it descends twice). The paper's put-down, ``lambda v^2/2 + F_lc``, lays
the chain slack and so loses the difference; the gripped roller's laid chain is pinned
and the table takes the rest of the momentum. Measured in the rig (no gravity): converged
in the step with a roller of radius five link lengths (``Tbar`` 0.2490/0.2496/0.2498 at
0.5/0.25/0.125 ms against 0.25); with fewer links a turn each grip is a jolt the step
does not resolve (``docs/apparatus.md``, "The gripped folding roller").
"""

from __future__ import annotations

import math
from collections import deque

import pymunk

from chainfountain.sim.apparatus.fold import FoldPart
from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.chain import Chain, Link

GRIP_TOL = 5e-4
"""A strand link is gripped once its back joint is this near the rim (m), if it has not
passed over the roller's centre before."""
CATCH_TIME = 5e-3
"""Time constant (s) in which a gripped link's gear turns it onto the rim chord."""
ON_WRAP = 1e-3
"""Tolerance (m) by which a joint of the chain laid along the path lies on the roller's
rim (the start: which links are welded)."""


class GrippedFold:
    """The gripped folding roller's welds: chain links ``1 .. n_welded`` are welded to
    the roller (bottom to top), link 0 is the landing link (its front pinned to the
    table)."""

    def __init__(self, space: pymunk.Space, chain: Chain, layout: Layout,
                 fold: FoldPart) -> None:
        self.space = space
        self.chain = chain
        self.layout = layout
        self.fold = fold
        """The fold whose roller grips (its lower plate strand arrives at the roller)."""
        self._welds: deque[tuple[Link, pymunk.PivotJoint, pymunk.GearJoint]] = deque()
        """Welded links, bottom (``chain.links[1]``) to top, with their pivot and gear."""
        self._table_pin: pymunk.PivotJoint | None = None
        """The landing link's front joint, pinned to the table."""
        self.gripped_links = 0
        """Links the folding roller has gripped (the start's welds not counted)."""
        self.landing_speed = 0.0
        """Fastest a joint has moved (m/s) when it was pinned to the table: the chain is
        laid at rest when this is near 0 (at the bottom of its circle a welded joint does
        not move; it is pinned at most one bookkeeping step later)."""

    @property
    def head_pinned(self) -> bool:
        """Whether a link of the chain is pinned to the lower table (from rest: once the
        starter has carried the head round the roller; laid: from the start)."""
        return self._table_pin is not None

    @property
    def n_welded(self) -> int:
        """Links welded to the folding roller now."""
        return len(self._welds)

    # ------------------------------------------------------------------ geometry
    def _ends(self, link: Link) -> tuple[pymunk.Vec2d, pymunk.Vec2d]:
        h = 0.5 * self.layout.L
        b = link.body
        return b.local_to_world((h, 0.0)), b.local_to_world((-h, 0.0))

    # ------------------------------------------------------------------ start
    def take_in(self) -> int:
        """Weld the links laid round the roller's front, pin the landing link's front to
        the table and take the chain laid behind it out of the space; returns how many
        links left."""
        chain, links = self.chain, self.chain.links
        c = self.fold.lower.roller.position
        R = self.layout.R_lo

        def on_wrap(p: pymunk.Vec2d) -> bool:
            return abs((p - c).length - R) < ON_WRAP and p.x >= c.x - 1e-9

        wrap = [i for i, lk in enumerate(links) if all(on_wrap(p) for p in self._ends(lk))]
        if not wrap or wrap != list(range(wrap[0], wrap[-1] + 1)) or wrap[0] < 1:
            raise ValueError("the gripped folding roller found no chain laid round it")
        popped = wrap[0] - 1  # the chain laid behind the landing link leaves
        for _ in range(popped):
            chain.pop_front()
        if links[0].shape is not None and links[0].shape.space is not None:
            self.space.remove(links[0].shape)
        self._pin_front(links[0])
        for k in range(1, 1 + len(wrap)):
            self._weld(links[k])
            if k > 1:
                chain.unjoin(k - 1)
        return popped

    # ------------------------------------------------------------------ stepping
    def _weld(self, link: Link, angle: float | None = None) -> None:
        """Weld ``link`` to the folding roller: a pivot at its front joint and a gear
        holding its angle (its own, or ``angle``, reached in :data:`CATCH_TIME`)."""
        roller = self.fold.lower.roller
        bias = self.layout.sim_cfg.solver.joint_error_bias
        h = 0.5 * self.layout.L
        if link.shape is not None and link.shape.space is not None:
            self.space.remove(link.shape)  # held by joints: nothing to touch
        pf = link.body.local_to_world((h, 0.0))
        pj = pymunk.PivotJoint(roller, link.body, roller.world_to_local(pf), (h, 0.0))
        own = link.body.angle
        target = own if angle is None else own + math.remainder(angle - own, 2.0 * math.pi)
        gj = pymunk.GearJoint(roller, link.body, target - roller.angle, 1.0)
        for j in (pj, gj):
            j.error_bias = bias
            j.collide_bodies = False
        if angle is not None:
            gj.error_bias = math.exp(-1.0 / CATCH_TIME)
        self.space.add(pj, gj)
        self._welds.append((link, pj, gj))

    def _pin_front(self, link: Link) -> None:
        """Pin ``link``'s front joint to the table where it is."""
        p = link.body.local_to_world((0.5 * self.layout.L, 0.0))
        pin = pymunk.PivotJoint(self.space.static_body, link.body, p)
        pin.error_bias = self.layout.sim_cfg.solver.joint_error_bias
        self.space.add(pin)
        self._table_pin = pin

    def land(self) -> int:
        """Land every welded link whose front joint has passed under the roller's centre
        (keeping at least one welded); returns how many links left the space."""
        chain = self.chain
        cx = self.fold.lower.x
        if self._table_pin is None:  # from rest: the head lands first
            self._land_head(cx)
            return 0
        popped = 0
        while len(self._welds) > 1:
            link, pj, gj = self._welds[0]
            front = self._ends(link)[0]
            if front.x > cx:
                break
            self.space.remove(self._table_pin)
            chain.pop_front()  # the landing link, both ends down
            popped += 1
            self._welds.popleft()
            self.space.remove(pj, gj)
            self.landing_speed = max(self.landing_speed,
                                     link.body.velocity_at_world_point(front).length)
            self._pin_front(link)
            chain.join(0)  # its back to the lowest welded link's front
        return popped

    def _land_head(self, cx: float) -> None:
        """From rest: once the threaded head (welded first) has gone round the roller's
        front and its front joint passes under the centre, un-weld it, pin its front to the
        table and join its back to the next welded link: from then on the roller lays the
        chain as in the steady state."""
        if len(self._welds) < 2 or self._welds[0][0] is not self.chain.links[0]:
            return
        link, pj, gj = self._welds[0]
        front = self._ends(link)[0]
        if front.x > cx or front.y > self.fold.lower.roller.position.y:
            return  # not yet under the centre (a head gripped early is still on top)
        self._welds.popleft()
        self.space.remove(pj, gj)
        self._pin_front(link)
        self.chain.join(0)

    def grip_arriving(self) -> None:
        """Weld the strand's last link once its back joint has passed over the roller's
        centre or come within :data:`GRIP_TOL` of the rim, caught onto the rim chord."""
        chain, links = self.chain, self.chain.links
        c = self.fold.lower.roller.position
        R = self.layout.R_lo
        d_ang = 2.0 * math.asin(self.layout.L / (2.0 * R))
        plate = self.fold.held[-1]
        first = 1 if self._table_pin is not None else 0  # 0: the head is threaded
        while True:
            k = first + len(self._welds)
            if k >= len(links):
                return
            link = links[k]
            if plate and plate[0][0] is link:
                return  # still in the plate's groove
            pf, pb = self._ends(link)
            if pb.x < c.x and (pb - c).length > R + GRIP_TOL:
                return
            u = pf - c
            ang = math.atan2(u.y, u.x) + d_ang  # the rim point one link on, upstream
            qx, qy = c.x + R * math.cos(ang), c.y + R * math.sin(ang)
            self._weld(link, math.atan2(pf.y - qy, pf.x - qx))
            if k > 0:
                chain.unjoin(k - 1)
            self.gripped_links += 1

    def shift_pin(self, dx: float) -> None:
        """Treadmill: the table pin moves back with the laid chain by ``dx`` (m)."""
        pin = self._table_pin
        if pin is not None:
            a = pin.anchor_a
            pin.anchor_a = (a.x - dx, a.y)
