"""The upper plate's grooves (``plate = "groove"``): the strand from the pick-up roller
to the upper channel runs in one frictionless groove joint per link instead of on a
contact plate."""

from __future__ import annotations

import math
from collections import deque

import pymunk

from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.upper import UpperPart
from chainfountain.sim.apparatus.upper_guide import UpperJointGuide
from chainfountain.sim.chain import Chain, Link
from chainfountain.sim.fastbody import pos


class PlateGrooves:
    """The upper plate strand's grooves: one frictionless groove joint per link on the
    line ``y = y_up`` from the pick-up roller to the upper channel."""

    def __init__(self, space: pymunk.Space, chain: Chain, layout: Layout, upper: UpperPart,
                 upper_guide: UpperJointGuide | None) -> None:
        self.space = space
        self.chain = chain
        self.layout = layout
        self.pickup = upper.upper
        """The pick-up roller (the grooves start at it)."""
        self.upper_guide = upper_guide
        """Where a link leaving the grooves goes on to (the upper joint guide's lead),
        ``None`` with the channel's walls."""
        self.held: deque[tuple[Link, pymunk.GrooveJoint]] = deque()
        """The strand's links with their groove joints, most downstream first (the newest,
        at the pick-up roller, last)."""
        self.next_index = -1
        """Chain index of the next link to put into a groove."""

    @property
    def strand_speed(self) -> float:
        """Mean speed of the links in the plate grooves (m/s): the straight strand moves
        rigidly, so this is the cleanest reading of the chain speed (nan without grooves)."""
        g = self.held
        if not g:
            return math.nan
        return float(sum(lk.body.velocity.x for lk, _ in g) / len(g))

    def _on_plate(self, body: pymunk.Body) -> bool:
        """Is a link centre on the upper plate line, clear of the roller wrap?"""
        lay = self.layout
        p = pos(body)
        return (self.pickup.x + lay.L < p.x < lay.x_plate_up_end
                and abs(p.y - lay.y_up) < 0.5 * lay.rho)

    def groove_joint(self, body: pymunk.Body) -> pymunk.GrooveJoint:
        """A frictionless groove on the upper plate line for ``body``'s centre (added)."""
        lay = self.layout
        j = pymunk.GrooveJoint(self.space.static_body, body,
                               (self.pickup.x - 1.0, lay.y_up),
                               (lay.x_plate_up_end + 0.2, lay.y_up), (0.0, 0.0))
        j.error_bias = lay.sim_cfg.solver.joint_error_bias
        self.space.add(j)
        return j

    def _groove(self, link: Link) -> None:
        j = self.groove_joint(link.body)
        if link.shape is not None:  # nothing to touch on the plate: out of the broadphase
            self.space.remove(link.shape)
        self.held.append((link, j))

    def take_in(self) -> None:
        """Put the links laid on the plate into their grooves."""
        links = self.chain.links
        on = [i for i, lk in enumerate(links) if self._on_plate(lk.body)]
        if on:
            i0, i1 = on[0], on[-1]
            for i in range(i0, i1 + 1):
                self._groove(links[i])
            self.next_index = i1 + 1
        else:  # nothing on the plate yet: the first link off the roller's top comes next
            self.next_index = max(i for i, lk in enumerate(links)
                                  if lk.body.position.x > self.pickup.x) + 1

    def update(self, popped: int) -> None:
        """The strand on the upper plate runs in a frictionless groove joint per link
        (link centre on the line ``y = y_up``) instead of one contact per link: same
        normal force (the strand is straight and horizontal, the plate carries its
        weight), two-sided, and much cheaper. A link gets its groove when it leaves the
        roller's wrap onto the plate line and loses it in the horizontal lead of the
        upper channel. Grooved links leave the collision broadphase (their shapes are
        removed and put back). ``popped`` links have left the chain's downstream end
        since the last call."""
        links = self.chain.links
        self.next_index -= popped
        g = self.held
        lim = self.layout.x_plate_up_end + 0.02
        while g and pos(g[0][0].body).x > lim:
            link, j = g.popleft()
            self.space.remove(j)
            if self.upper_guide is not None:  # on into its lead, still shapeless
                self.upper_guide.hold(0, link)
            elif link.shape is not None:
                self.space.add(link.shape)
        while 0 <= self.next_index < len(links) and self._on_plate(links[self.next_index].body):
            self._groove(links[self.next_index])
            self.next_index += 1
