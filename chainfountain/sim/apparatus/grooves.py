"""The upper plate's grooves (``plate = "groove"``): the strand from the pick-up roller
to the upper channel runs in one frictionless groove joint per link instead of on a
contact plate."""

from __future__ import annotations

import math
from collections import deque

import pymunk

from chainfountain.sim.chain import Link
from chainfountain.sim.fastbody import pos


class PlateGrooves:
    """The upper plate strand's grooves (a mixin of
    :class:`~chainfountain.sim.apparatus.Apparatus`)."""

    def _init_groove_state(self) -> None:
        self._grooves: deque[tuple[Link, pymunk.GrooveJoint]] = deque()
        self._g_next = -1
        """Chain index of the next link to put into a plate groove (``plate = "groove"``)."""

    @property
    def plate_grooves(self) -> deque[tuple[Link, pymunk.GrooveJoint]]:
        """``plate = "groove"``: the upper plate strand's links with their groove joints,
        most downstream first (the newest, at the pick-up roller, last). Read only."""
        return self._grooves

    @property
    def strand_speed(self) -> float:
        """Mean speed of the links in the plate grooves (m/s): the straight strand moves
        rigidly, so this is the cleanest reading of the chain speed (nan without grooves)."""
        g = self._grooves
        if not g:
            return math.nan
        return float(sum(lk.body.velocity.x for lk, _ in g) / len(g))

    def _on_plate(self, body: pymunk.Body) -> bool:
        """Is a link centre on the upper plate line, clear of the roller wrap?"""
        p = pos(body)
        return (self.upper.x + self.L < p.x < self.x_plate_up_end
                and abs(p.y - self.y_up) < 0.5 * self.rho)

    def _groove_joint(self, body: pymunk.Body) -> pymunk.GrooveJoint:
        """A frictionless groove on the upper plate line for ``body``'s centre (added)."""
        j = pymunk.GrooveJoint(self.space.static_body, body,
                               (self.upper.x - 1.0, self.y_up),
                               (self.x_plate_up_end + 0.2, self.y_up), (0.0, 0.0))
        j.error_bias = self.sim_cfg.solver.joint_error_bias
        self.space.add(j)
        return j

    def _groove(self, link: Link) -> None:
        j = self._groove_joint(link.body)
        if link.shape is not None:  # nothing to touch on the plate: out of the broadphase
            self.space.remove(link.shape)
        self._grooves.append((link, j))

    def _init_grooves(self) -> None:
        links = self.chain.links
        on = [i for i, lk in enumerate(links) if self._on_plate(lk.body)]
        if on:
            i0, i1 = on[0], on[-1]
            for i in range(i0, i1 + 1):
                self._groove(links[i])
            self._g_next = i1 + 1
        else:  # nothing on the plate yet: the first link off the roller's top comes next
            self._g_next = max(i for i, lk in enumerate(links)
                               if lk.body.position.x > self.upper.x) + 1

    def _update_grooves(self, popped: int) -> None:
        """``plate = "groove"``: the strand on the upper plate runs in a frictionless
        groove joint per link (link centre on the line ``y = y_up``) instead of one
        contact per link: same normal force (the strand is straight and horizontal,
        the plate carries its weight), two-sided, and much cheaper. A link gets its
        groove when it leaves the roller's wrap onto the plate line and loses it in
        the horizontal lead of the upper channel. Grooved links leave the collision
        broadphase (their shapes are removed and put back)."""
        links = self.chain.links
        self._g_next -= popped
        g = self._grooves
        lim = self.x_plate_up_end + 0.02
        while g and pos(g[0][0].body).x > lim:
            link, j = g.popleft()
            self.space.remove(j)
            if self.upper_guided:  # on into the upper joint guide's lead, still shapeless
                self._hold_up(0, link)
            elif link.shape is not None:
                self.space.add(link.shape)
        while 0 <= self._g_next < len(links) and self._on_plate(links[self._g_next].body):
            self._groove(links[self._g_next])
            self._g_next += 1
