"""The upper joint guide (``upper_guide = "joints"``): the upper channel as a
frictionless guide of joints along its centre line (elements of
:func:`chainfountain.sim.guide.upper_guide`) instead of static walls."""

from __future__ import annotations

from collections import deque

import numpy as np
import pymunk

from chainfountain.sim.apparatus.joints import hold, keep_on_arcs
from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.tuning import UP_RELEASE
from chainfountain.sim.apparatus.upper import UpperPart
from chainfountain.sim.chain import Chain, Link
from chainfountain.sim.fastbody import pos
from chainfountain.sim.guide import GuideElement


class UpperJointGuide:
    """Links held in the upper joint guide's elements (:attr:`UpperPart.up_guide
    <.upper.UpperPart.up_guide>`)."""

    def __init__(self, space: pymunk.Space, chain: Chain, layout: Layout, upper: UpperPart,
                 close_rate: float) -> None:
        self.space = space
        self.chain = chain
        self.layout = layout
        self.elements: list[GuideElement] = upper.up_guide
        self.close_rate = close_rate
        """Speed (m/s) at which the limits of a link captured off a bend's radius close
        in (:meth:`Tuning.close_rate <.tuning.Tuning.close_rate>`)."""
        self.held: list[deque[tuple[Link, pymunk.Constraint]]] = [
            deque() for _ in self.elements]
        """The links (with their joints) each element holds, most downstream first."""

    def take_in(self, first_grooved: Link | None) -> None:
        """Put the links laid along the upper channel (downstream of the plate's grooved
        strand, whose most downstream link is ``first_grooved``) into the guide's
        elements."""
        links = self.chain.links
        i_g = self.chain.ids.index(first_grooved.id) if first_grooved is not None else len(links)
        found: list[tuple[int, int]] = []
        for i in range(i_g - 1, -1, -1):  # upstream to downstream
            p = pos(links[i].body)
            P = np.array([[p.x, p.y]])
            for k, el in enumerate(self.elements):
                if el.on(P, 0.003)[0] and not el.passed(p.x, p.y):
                    found.append((i, k))
                    break
            else:
                if found:
                    break  # past the exit: the fountain
        for i, k in sorted(found):  # downstream first in each queue
            self.hold(k, links[i])

    def hold(self, k: int, link: Link) -> None:
        """Hold ``link`` in element ``k`` (out of the collision broadphase)."""
        hold(self.space, self.elements[k], self.held[k], link,
             self.layout.sim_cfg.solver.joint_error_bias)

    def update(self) -> None:
        """Move links from element to element as they pass each end (downstream elements
        first, so a link moves at most one element per step) and release them into
        flight past the fountain start. A released link stays out of the broadphase in
        'fold' (nothing to touch in flight, :meth:`~.fold.FoldPart.update_flight`) and
        gets its shape back otherwise (the floor variants need it)."""
        els, qs = self.elements, self.held
        last = len(els) - 1
        self.release()
        for k in range(last - 1, -1, -1):
            q, el = qs[k], els[k]
            while q:
                p = pos(q[0][0].body)
                if not el.passed(p.x, p.y):
                    break
                link, j = q.popleft()
                self.space.remove(j)
                self.hold(k + 1, link)
        keep_on_arcs(els, qs, self.close_rate * self.layout.sim_cfg.solver.dt)

    def release(self) -> None:
        """Release into flight the links whose front joint has left the upper guide (its
        centre :data:`~.tuning.UP_RELEASE` link lengths short of the start). Run in every
        pymunk step (:meth:`~.core.Apparatus.before_step` with ``substeps > 1``), not only
        with the bookkeeping: the fountain is sensitive to where its links leave the
        guide, so it does not move with the bookkeeping's cadence."""
        el, q = self.elements[-1], self.held[-1]
        before = UP_RELEASE * self.layout.L
        space = self.space
        fold_guided = self.layout.fold_guided
        while q:
            p = pos(q[0][0].body)
            if not el.passed(p.x, p.y, before):
                break
            link, j = q.popleft()
            space.remove(j)
            if not fold_guided and link.shape is not None and link.shape.space is None:
                space.add(link.shape)
