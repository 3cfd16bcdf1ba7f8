"""'fold': the folding roller with the lower table and plate, and (``plate = "groove"``)
the lower joint guide: the end channel's turn, rise and turn and the lower plate as
frictionless joints that catch the landing chain at the mouth and hand it to the
folding roller. The collapse check is in :mod:`.fold_watch`."""

from __future__ import annotations

import math
from collections import deque

import numpy as np
import pymunk

from chainfountain.sim.apparatus.joints import hold, keep_on_arcs
from chainfountain.sim.apparatus.parts import ONLY_CHAIN, SCENERY, add_roller, static_segment
from chainfountain.sim.apparatus.tuning import FOLD_RELEASE, LO_START
from chainfountain.sim.chain import Link
from chainfountain.sim.fastbody import pos
from chainfountain.sim.guide import GuideElement, end_channel_bends


class FoldPart:
    """The folding roller and the lower joint guide (a mixin of
    :class:`~chainfountain.sim.apparatus.Apparatus`)."""

    def _init_fold_state(self) -> None:
        self._gq: list[deque[tuple[Link, pymunk.Constraint]]] = [deque() for _ in self.guide]
        """'fold' guide: links held by each element (most downstream first)."""
        self._cap_next = -1
        """'fold' guide: chain index of the next link to capture at the mouth."""
        self._mouth_t: float | None = None
        self._mouth_dr = 0.0
        """'fold' guide: time (s) of the last capture through the mouth (at or before its
        angle; later captures take links falling into the turn from the side; None before
        the first) and that link's offset from the turn's radius (m; > 0 outside: the
        fountain landed short). The collapse message says when the catch was lost."""
        self.released = 0
        """'fold' guide: links handed from the lower plate to the folding roller."""
        self._fly_next = -1
        """'fold' guide: chain index of the next link to leave the upper channel."""

    @property
    def fold_held(self) -> list[deque[tuple[Link, pymunk.Constraint]]]:
        """'fold' guide: the links (with their joints) each element of :attr:`guide`
        holds, most downstream first (``[-1]``: the lower plate strand). Read only."""
        return self._gq

    @property
    def last_mouth_entry(self) -> float:
        """'fold': time (s) at which the last link entered the end guide through its
        mouth (nan before any did)."""
        return math.nan if self._mouth_t is None else self._mouth_t

    @property
    def last_mouth_offset(self) -> float:
        """'fold': that link's offset from the first turn's radius at capture (m; > 0
        outside: the fountain landed short; nan before any)."""
        return math.nan if self._mouth_t is None else self._mouth_dr

    # ------------------------------------------------------------------ build
    def _build_fold_lower(self, xl: float, rise: float) -> list[np.ndarray]:
        """The folding roller (mirror image of the pick-up: it moves in ``+x`` at ``v/2``
        and the chain wraps around its front) on the lower table, the lower plate from
        the end channel's exit ``xl`` to the roller, and with grooves the joint guide's
        elements; returns the chain's path from the plate over the roller's wrap onto the
        table."""
        a, L, rho, r = self.cfg, self.L, self.rho, self.r_lo
        space = self.space
        carts = list(self.sim_cfg.carts)
        travel_lo = self._table_travel()
        vR = 0.5 * float(a.speed)
        R = r + rho
        x_lo = xl + (max(LO_START, (a.plate_links + 2) * L) if self.treadmill
                     else LO_START)
        ylt = self.y_lo - 3.0 * rho - 2.0 * r
        if a.plate == "groove":
            ylt -= a.fold_clearance
        self.y_table_lo = ylt
        self.lower = add_roller(space, x_lo, ylt, rho, r, a.roller_mass,
                                a.carriage_mass, carts[1] if len(carts) > 1 else None,
                                1.0, self.g, self.sim_cfg.solver.joint_error_bias, vR, -vR / R,
                                drag=a.bearing_drag + a.fold_brake,
                                fixed_axle=self.gripped)
        self.table_lo = static_segment(space, (xl - 0.5, ylt - 0.01),
                                       (x_lo + travel_lo + 1.0, ylt - 0.01), 0.01,
                                       a.table_friction, SCENERY)
        space.add(self.table_lo)
        self.plate_lo = static_segment(space, (xl, self.y_lo - rho - 0.002),
                                       (x_lo - 0.5 * L, self.y_lo - rho - 0.002), 0.002,
                                       0.0, ONLY_CHAIN)
        if not self.fold_guided:
            space.add(self.plate_lo)
        if self.fold_guided:
            self.guide = self._fold_guide(self.end[0], self.alphaE, rise, a.channel_radius,
                                          x_lo + travel_lo + 1.0)
        ycl = self.lower.yc
        parts = [np.array([[x_lo, self.y_lo]])]
        th = np.linspace(0.5 * math.pi, -0.5 * math.pi, 60)[1:]
        parts.append(np.column_stack((x_lo + R * np.cos(th), ycl + R * np.sin(th))))
        parts.append(np.array([[x_lo - 0.3, ylt + rho]]))
        return parts

    def _fold_guide(self, xE: float, alphaE: float, rise: float, R: float,
                    far: float) -> list[GuideElement]:
        """Elements of the 'fold' joint guide, along the end channel's centre line:
        turn from the landing heading ``-alphaE`` (centre :attr:`guide_centre`) up to
        60 deg, straight rise, turn back to horizontal, lower plate line to ``far``."""
        up = math.radians(60.0) if rise > 1e-9 else 0.0
        H = self.H
        out: list[GuideElement] = []
        if rise > 1e-9:
            R, S = end_channel_bends(alphaE, rise, R, up)
        else:
            S = 0.0
        c1 = (xE + R * math.sin(alphaE), -H + R * math.cos(alphaE))
        self.guide_centre, self.guide_radius = c1, R
        th0 = math.atan2(-math.cos(alphaE), -math.sin(alphaE))
        th1 = up - 0.5 * math.pi
        out.append(GuideElement("arc", c1, c1, R, th0, th1))
        p1 = (c1[0] + R * math.cos(th1), c1[1] + R * math.sin(th1))
        p2 = p1
        if S > 1e-6:
            p2 = (p1[0] + S * math.cos(up), p1[1] + S * math.sin(up))
            out.append(GuideElement("line", p1, p2))
        if rise > 1e-9:
            c2 = (p2[0] + R * math.sin(up), p2[1] - R * math.cos(up))
            out.append(GuideElement("arc", c2, c2, R, up + 0.5 * math.pi, 0.5 * math.pi))
            p3 = (c2[0], c2[1] + R)
        else:
            p3 = (c1[0], c1[1] - R)
        out.append(GuideElement("line", p3, (far, p3[1])))
        self.x_plate_lo_start = p3[0]
        return out

    def _init_fold_guide(self) -> None:
        """Put the links laid along the lower channel and plate into their elements."""
        links = self.chain.links
        P = np.array([[lk.body.position.x, lk.body.position.y] for lk in links])
        x_rel = self.lower.x - FOLD_RELEASE * self.L
        last = -1
        order = list(range(len(self.guide) - 1, -1, -1))  # plate first (downstream)
        cur = 0
        for i, lk in enumerate(links):
            p = P[i:i + 1]
            for jj in order[cur:]:
                el = self.guide[jj]
                if el is self.guide[-1] and p[0, 0] >= x_rel:
                    continue
                if el.on(p, 0.003)[0]:
                    cur = order.index(jj)
                    self._hold(jj, lk)
                    last = i
                    break
            else:
                if last >= 0:
                    break
        self._cap_next = last + 1

    def _hold(self, k: int, link: Link) -> None:
        """Hold ``link`` in guide element ``k`` (out of the collision broadphase)."""
        hold(self.space, self.guide[k], self._gq[k], link, self.sim_cfg.solver.joint_error_bias)

    # ------------------------------------------------------------------ stepping
    def _update_flight(self, popped: int) -> None:
        """'fold': a link more than a link length past the upper channel's exit flies
        freely until the guide catches it; nothing is left for it to touch (the lower
        channel is a joint guide, links do not collide with each other), so its shape
        leaves the collision broadphase. It comes back when the folding roller takes
        the link (:meth:`_update_fold_guide`). This changes no result (the fold preset
        gives the same numbers to the last digit) and saves about a third of the
        shapes."""
        links = self.chain.links
        self._fly_next -= popped
        x_out = float(self.channel_up[-1, 0]) + self.L
        space = self.space
        while 0 <= self._fly_next < len(links):
            link = links[self._fly_next]
            if pos(link.body).x <= x_out:
                break
            if link.shape is not None and link.shape.space is not None:
                space.remove(link.shape)
            self._fly_next += 1

    def _update_fold_guide(self, popped: int) -> None:
        """'fold': capture links landing at the mouth into the first turn, move links
        from element to element as they pass each end, and hand them to the folding
        roller (shape back in the space) when they reach its top."""
        self._capture_at_mouth(popped)
        self._pass_along_fold_guide()
        keep_on_arcs(self.guide, self._gq, self.fold_close_rate * self.sim_cfg.solver.dt)

    def _capture_at_mouth(self, popped: int) -> None:
        """Take the links that have landed within the capture band
        (:attr:`~chainfountain.sim.apparatus.Apparatus.fold_capture`) into the first
        turn; note the time and offset of each that came through the mouth."""
        links = self.chain.links
        self._cap_next -= popped
        el0 = self.guide[0]
        cx, cy = el0.a
        Rc = el0.R
        lim = -0.5 * math.pi + 0.05
        while 0 <= self._cap_next < len(links):
            p = pos(links[self._cap_next].body)
            d = math.hypot(p.x - cx, p.y - cy)
            th = math.atan2(p.y - cy, p.x - cx)
            if not (el0.th0 - self.fold_capture[1] <= th <= max(lim, el0.th1)
                    and abs(d - Rc) < self.fold_capture[0]):
                break
            if th <= el0.th0 or self.end_follow:  # through the mouth, not from the side
                # (a following end guide's wide mouth takes both: it follows either)
                self._mouth_t, self._mouth_dr = self._t, d - Rc
            self._hold(0, links[self._cap_next])
            self._cap_next += 1

    def _pass_along_fold_guide(self) -> None:
        """Move held links on to the next element as they pass each end (downstream
        elements first); release lower-plate links onto the folding roller."""
        space = self.space
        n_el = len(self.guide)
        for k in range(n_el - 1, -1, -1):  # downstream elements first
            q = self._gq[k]
            el = self.guide[k]
            if k == n_el - 1:  # the lower plate: hand links to the folding roller
                x_rel = self.lower.x - FOLD_RELEASE * self.L
                while q and pos(q[0][0].body).x > x_rel:
                    link, j = q.popleft()
                    space.remove(j)
                    if link.shape is not None and not self.gripped:  # gripped: no contact
                        space.add(link.shape)
                    self.released += 1
                continue
            while q:
                p = pos(q[0][0].body)
                if not el.passed(p.x, p.y):
                    break
                link, j = q.popleft()
                space.remove(j)
                self._hold(k + 1, link)

    def fold_guided_range(self, position: np.ndarray, x_lower: float) -> tuple[int, int]:
        """'fold' guide, from a recorded state: index ``i_p`` of the lower-plate link
        about 6 links before the folding roller (its horizontal joint force is the
        tension: the grooves add none) and ``k``, one past the last guided link
        (the mouth). ``(-1, 0)`` if the plate is empty."""
        L = self.L
        el = self.guide[-1]
        y = el.a[1]
        on_plate = (np.abs(position[:, 1] - y) < 2.0 * self.rho) & \
            (position[:, 0] > el.a[0] - 0.01) & (position[:, 0] < x_lower - 3.0 * L)
        idx = np.flatnonzero(on_plate)
        if not len(idx):
            return -1, 0
        ip = int(idx[np.argmin(np.abs(position[idx, 0] - (x_lower - 6.0 * L)))])
        on = np.zeros(len(position), dtype=bool)
        for e in self.guide[:-1]:
            on |= e.on(position, 0.004)
        e0 = self.guide[0]
        on |= e0.on(position, self.fold_capture[0])
        on |= (np.abs(position[:, 1] - y) < 2.0 * self.rho) & (position[:, 0] > el.a[0] - 0.01)
        off = np.flatnonzero(~on[ip:])
        k = ip + int(off[0]) if len(off) else len(position)
        return ip, k
