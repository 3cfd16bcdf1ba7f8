"""The upper joint guide (``upper_guide = "joints"``): the upper channel as a
frictionless guide of joints along its centre line (elements of
:func:`chainfountain.sim.guide.upper_guide`) instead of static walls."""

from __future__ import annotations

from collections import deque

import numpy as np
import pymunk

from chainfountain.sim.apparatus.joints import hold, keep_on_arcs
from chainfountain.sim.apparatus.tuning import UP_RELEASE
from chainfountain.sim.chain import Link
from chainfountain.sim.fastbody import pos


class UpperJointGuide:
    """Links held in the upper joint guide (a mixin of
    :class:`~chainfountain.sim.apparatus.Apparatus`)."""

    def _init_upper_guide_state(self) -> None:
        self._uq: list[deque[tuple[Link, pymunk.Constraint]]] = [
            deque() for _ in self.up_guide]
        """Upper joint guide: links held by each element (most downstream first)."""

    @property
    def upper_held(self) -> list[deque[tuple[Link, pymunk.Constraint]]]:
        """Upper joint guide: the links (with their joints) each element of
        :attr:`up_guide` holds, most downstream first. Read only."""
        return self._uq

    def _init_upper_guide(self) -> None:
        """Put the links laid along the upper channel (downstream of the plate's grooved
        strand) into the upper guide's elements."""
        links = self.chain.links
        i_g = self.chain.ids.index(self._grooves[0][0].id) if self._grooves else len(links)
        found: list[tuple[int, int]] = []
        for i in range(i_g - 1, -1, -1):  # upstream to downstream
            p = pos(links[i].body)
            P = np.array([[p.x, p.y]])
            for k, el in enumerate(self.up_guide):
                if el.on(P, 0.003)[0] and not el.passed(p.x, p.y):
                    found.append((i, k))
                    break
            else:
                if found:
                    break  # past the exit: the fountain
        for i, k in sorted(found):  # downstream first in each queue
            self._hold_up(k, links[i])

    def _hold_up(self, k: int, link: Link) -> None:
        """Hold ``link`` in upper guide element ``k`` (out of the collision broadphase)."""
        hold(self.space, self.up_guide[k], self._uq[k], link,
             self.sim_cfg.solver.joint_error_bias)

    def _update_upper_guide(self) -> None:
        """Upper joint guide: move links from element to element as they pass each end
        (downstream elements first, so a link moves at most one element per step) and
        release them into flight past the fountain start. A released link stays out of
        the broadphase in 'fold' (nothing to touch in flight,
        :meth:`~.fold.FoldPart._update_flight`) and gets its shape back otherwise (the floor
        variants need it)."""
        els, qs = self.up_guide, self._uq
        last = len(els) - 1
        self._release_upper()
        for k in range(last - 1, -1, -1):
            q, el = qs[k], els[k]
            while q:
                p = pos(q[0][0].body)
                if not el.passed(p.x, p.y):
                    break
                link, j = q.popleft()
                self.space.remove(j)
                self._hold_up(k + 1, link)
        keep_on_arcs(els, qs, self.fold_close_rate * self.sim_cfg.solver.dt)

    def _release_upper(self) -> None:
        """Release into flight the links whose front joint has left the upper guide (its
        centre :data:`~.tuning.UP_RELEASE` link lengths short of the start). Run in every
        pymunk step (:meth:`~.core.Apparatus.before_step` with ``substeps > 1``), not only
        with the bookkeeping: the fountain is sensitive to where its links leave the
        guide, so it does not move with the bookkeeping's cadence."""
        el, q = self.up_guide[-1], self._uq[-1]
        before = UP_RELEASE * self.L
        space = self.space
        while q:
            p = pos(q[0][0].body)
            if not el.passed(p.x, p.y, before):
                break
            link, j = q.popleft()
            space.remove(j)
            if not self.fold_guided and link.shape is not None and link.shape.space is None:
                space.add(link.shape)
