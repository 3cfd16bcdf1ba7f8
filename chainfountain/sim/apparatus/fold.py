"""'fold': the folding roller with the lower table and plate, and (``plate = "groove"``)
the lower joint guide: the end channel's turn, rise and turn and the lower plate as
frictionless joints that catch the landing chain at the mouth and hand it to the
folding roller. The collapse check is in :mod:`.fold_watch`."""

from __future__ import annotations

import math
from collections import deque

import numpy as np
import pymunk

from chainfountain.sim.apparatus.ends import EndPart
from chainfountain.sim.apparatus.joints import hold, keep_on_arcs
from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.parts import (
    ONLY_CHAIN,
    SCENERY,
    Clock,
    RollerUnit,
    add_roller,
    static_segment,
)
from chainfountain.sim.apparatus.tuning import FOLD_RELEASE, LO_START
from chainfountain.sim.chain import Chain, Link
from chainfountain.sim.fastbody import pos
from chainfountain.sim.guide import GuideElement, end_channel_bends


class FoldPart:
    """The folding roller on the lower table, the lower plate and (``plate = "groove"``)
    the lower joint guide, built into the space after the end channel's walls; and the
    guide's bookkeeping."""

    def __init__(self, space: pymunk.Space, chain: Chain, layout: Layout, end: EndPart,
                 clock: Clock, capture: tuple[float, float], close_rate: float) -> None:
        self.space = space
        self.chain = chain
        self.layout = layout
        self.clock = clock
        self.capture = capture
        """The first turn's capture band (m) and angular margin (rad)
        (:meth:`Tuning.capture <.tuning.Tuning.capture>`; a study's starter may widen it
        while it runs)."""
        self.close_rate = close_rate
        """Speed (m/s) at which the limits of a link captured off a turn's radius close in
        (:meth:`Tuning.close_rate <.tuning.Tuning.close_rate>`)."""
        self.guide_centre: tuple[float, float] = end.guide_centre
        """Centre of the first turn (m; with grooves the joint guide's, moved by a
        following end guide)."""
        self.guide_radius: float = end.guide_radius
        self.x_plate_lo_start: float = end.x_exit
        """Where the lower plate starts (m): the end channel's exit, with grooves the
        guide's last turn's end."""
        self.guide: list[GuideElement] = []
        """With grooves, the lower joint guide's elements: turn, rise, turn, lower plate."""
        self.y_lo = end.y_lo
        self.y_table_lo = 0.0
        """Height of the lower table's top (m)."""
        self.lower: RollerUnit = self._build(end.x_exit, end.rise, end.end[0])
        """The folding roller on its carriage."""
        self.held: list[deque[tuple[Link, pymunk.Constraint]]] = [deque() for _ in self.guide]
        """With grooves, the links (with their joints) each element of :attr:`guide`
        holds, most downstream first (``[-1]``: the lower plate strand)."""
        self.cap_next = -1
        """Chain index of the next link to capture at the mouth."""
        self.mouth_t: float | None = None
        self.mouth_dr = 0.0
        """Time (s) of the last capture through the mouth (at or before its angle; later
        captures take links falling into the turn from the side; None before the first)
        and that link's offset from the turn's radius (m; > 0 outside: the fountain
        landed short). The collapse message says when the catch was lost."""
        self.released = 0
        """Links handed from the lower plate to the folding roller."""
        self.fly_next = -1
        """Chain index of the next link to leave the upper channel."""

    @property
    def last_mouth_entry(self) -> float:
        """Time (s) at which the last link entered the end guide through its mouth (nan
        before any did)."""
        return math.nan if self.mouth_t is None else self.mouth_t

    @property
    def last_mouth_offset(self) -> float:
        """That link's offset from the first turn's radius at capture (m; > 0 outside:
        the fountain landed short; nan before any)."""
        return math.nan if self.mouth_t is None else self.mouth_dr

    # ------------------------------------------------------------------ build
    def _build(self, xl: float, rise: float, xE: float) -> RollerUnit:
        """The folding roller (mirror image of the pick-up: it moves in ``+x`` at ``v/2``
        and the chain wraps around its front) on the lower table, the lower plate from
        the end channel's exit ``xl`` to the roller, and with grooves the joint guide's
        elements; returns the roller."""
        lay = self.layout
        a, L, rho, r = lay.cfg, lay.L, lay.rho, lay.r_lo
        space = self.space
        carts = list(lay.sim_cfg.carts)
        travel_lo = lay.table_travel()
        vR = 0.5 * float(a.speed)
        R = r + rho
        x_lo = xl + (max(LO_START, (a.plate_links + 2) * L) if lay.treadmill
                     else LO_START)
        ylt = self.y_lo - 3.0 * rho - 2.0 * r
        if a.plate == "groove":
            ylt -= a.fold_clearance
        self.y_table_lo = ylt
        lower = add_roller(space, x_lo, ylt, rho, r, a.roller_mass,
                           a.carriage_mass, carts[1] if len(carts) > 1 else None,
                           1.0, lay.g, lay.sim_cfg.solver.joint_error_bias, vR, -vR / R,
                           drag=a.bearing_drag + a.fold_brake,
                           fixed_axle=lay.gripped)
        self.table_lo: pymunk.Segment = static_segment(
            space, (xl - 0.5, ylt - 0.01), (x_lo + travel_lo + 1.0, ylt - 0.01), 0.01,
            a.table_friction, SCENERY)
        """The lower table."""
        space.add(self.table_lo)
        self.plate_lo: pymunk.Segment = static_segment(
            space, (xl, self.y_lo - rho - 0.002), (x_lo - 0.5 * L, self.y_lo - rho - 0.002),
            0.002, 0.0, ONLY_CHAIN)
        """The lower plate (a collision shape without grooves; its end follows the
        folding roller)."""
        if not lay.fold_guided:
            space.add(self.plate_lo)
        if lay.fold_guided:
            self.guide = self._fold_guide(xE, lay.alphaE, rise, a.channel_radius,
                                          x_lo + travel_lo + 1.0)
        return lower

    def path(self) -> list[np.ndarray]:
        """The chain's path from the plate over the roller's wrap onto the table."""
        lay = self.layout
        R = lay.r_lo + lay.rho
        x_lo = self.lower.x
        ycl = self.lower.yc
        parts = [np.array([[x_lo, self.y_lo]])]
        th = np.linspace(0.5 * math.pi, -0.5 * math.pi, 60)[1:]
        parts.append(np.column_stack((x_lo + R * np.cos(th), ycl + R * np.sin(th))))
        parts.append(np.array([[x_lo - 0.3, self.y_table_lo + lay.rho]]))
        return parts

    def _fold_guide(self, xE: float, alphaE: float, rise: float, R: float,
                    far: float) -> list[GuideElement]:
        """Elements of the 'fold' joint guide, along the end channel's centre line:
        turn from the landing heading ``-alphaE`` (centre :attr:`guide_centre`) up to
        60 deg, straight rise, turn back to horizontal, lower plate line to ``far``."""
        up = math.radians(60.0) if rise > 1e-9 else 0.0
        H = self.layout.H
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

    def take_in(self) -> None:
        """With grooves: put the links laid along the lower channel and plate into their
        elements, and the links past the upper channel out of the broadphase."""
        links = self.chain.links
        P = np.array([[lk.body.position.x, lk.body.position.y] for lk in links])
        x_rel = self.lower.x - FOLD_RELEASE * self.layout.L
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
        self.cap_next = last + 1
        self.fly_next = self.cap_next
        self.update_flight(0)

    def _hold(self, k: int, link: Link) -> None:
        """Hold ``link`` in guide element ``k`` (out of the collision broadphase)."""
        hold(self.space, self.guide[k], self.held[k], link,
             self.layout.sim_cfg.solver.joint_error_bias)

    # ------------------------------------------------------------------ stepping
    def reindex(self, removed: int) -> None:
        """``removed`` links have left the chain downstream of the links this part counts
        by chain index (the bookkeeping's ``popped``, a treadmill's cut)."""
        self.cap_next -= removed
        self.fly_next -= removed

    def update_flight(self, popped: int) -> None:
        """A link more than a link length past the upper channel's exit flies freely
        until the guide catches it; nothing is left for it to touch (the lower channel is
        a joint guide, links do not collide with each other), so its shape leaves the
        collision broadphase. It comes back when the folding roller takes the link
        (:meth:`update_guide`). This changes no result (the fold preset gives the same
        numbers to the last digit) and saves about a third of the shapes."""
        links = self.chain.links
        self.fly_next -= popped
        x_out = float(self.layout.channel_up[-1, 0]) + self.layout.L
        space = self.space
        while 0 <= self.fly_next < len(links):
            link = links[self.fly_next]
            if pos(link.body).x <= x_out:
                break
            if link.shape is not None and link.shape.space is not None:
                space.remove(link.shape)
            self.fly_next += 1

    def update_guide(self, popped: int) -> None:
        """Capture links landing at the mouth into the first turn, move links from element
        to element as they pass each end, and hand them to the folding roller (shape back
        in the space) when they reach its top."""
        self.capture_at_mouth(popped)
        self._pass_along()
        keep_on_arcs(self.guide, self.held, self.close_rate * self.layout.sim_cfg.solver.dt)

    def capture_at_mouth(self, popped: int) -> None:
        """Take the links that have landed within the capture band (:attr:`capture`) into
        the first turn; note the time and offset of each that came through the mouth."""
        links = self.chain.links
        self.cap_next -= popped
        el0 = self.guide[0]
        cx, cy = el0.a
        Rc = el0.R
        lim = -0.5 * math.pi + 0.05
        following = self.layout.end_follow
        while 0 <= self.cap_next < len(links):
            p = pos(links[self.cap_next].body)
            d = math.hypot(p.x - cx, p.y - cy)
            th = math.atan2(p.y - cy, p.x - cx)
            if not (el0.th0 - self.capture[1] <= th <= max(lim, el0.th1)
                    and abs(d - Rc) < self.capture[0]):
                break
            if th <= el0.th0 or following:  # through the mouth, not from the side
                # (a following end guide's wide mouth takes both: it follows either)
                self.mouth_t, self.mouth_dr = self.clock.t, d - Rc
            self._hold(0, links[self.cap_next])
            self.cap_next += 1

    def _pass_along(self) -> None:
        """Move held links on to the next element as they pass each end (downstream
        elements first); release lower-plate links onto the folding roller."""
        space = self.space
        n_el = len(self.guide)
        gripped = self.layout.gripped
        for k in range(n_el - 1, -1, -1):  # downstream elements first
            q = self.held[k]
            el = self.guide[k]
            if k == n_el - 1:  # the lower plate: hand links to the folding roller
                x_rel = self.lower.x - FOLD_RELEASE * self.layout.L
                while q and pos(q[0][0].body).x > x_rel:
                    link, j = q.popleft()
                    space.remove(j)
                    if link.shape is not None and not gripped:  # gripped: no contact
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

    def shift_guide(self, dx: float) -> None:
        """Move the guide's turn, rise and second turn, the lower plate's start and the
        first turn's centre by ``dx`` along x (a following end guide: their joints ride on
        its slide)."""
        els = self.guide
        for el in els[:-1]:
            el.a = (el.a[0] + dx, el.a[1])
            el.b = (el.b[0] + dx, el.b[1])
        last = els[-1]  # the lower plate: only its start moves (its grooves are along it)
        last.a = (last.a[0] + dx, last.a[1])
        cx, cy = self.guide_centre
        self.guide_centre = (cx + dx, cy)
        self.x_plate_lo_start += dx
        a, b = self.plate_lo.a, self.plate_lo.b
        self.plate_lo.unsafe_set_endpoints((a.x + dx, a.y), b)

    def fold_guided_range(self, position: np.ndarray, x_lower: float,
                          mouth: int | None = None) -> tuple[int, int]:
        """'fold' guide, from a recorded state: index ``i_p`` of the lower-plate link
        about 6 links before the folding roller (its horizontal joint force is the
        tension: the grooves add none) and ``k``, one past the last guided link
        (the mouth). ``(-1, 0)`` if the plate is empty.

        ``mouth``: :attr:`cap_next` as it was during the recorded step, the exact ``k``.
        Without it ``k`` is found from the positions (the first link from ``i_p`` on
        more than 4 mm off the guide), which misreads a guided link that its slide
        joint lets stand off the rise as the mouth."""
        L = self.layout.L
        el = self.guide[-1]
        y = el.a[1]
        rho = self.layout.rho
        on_plate = (np.abs(position[:, 1] - y) < 2.0 * rho) & \
            (position[:, 0] > el.a[0] - 0.01) & (position[:, 0] < x_lower - 3.0 * L)
        idx = np.flatnonzero(on_plate)
        if not len(idx):
            return -1, 0
        ip = int(idx[np.argmin(np.abs(position[idx, 0] - (x_lower - 6.0 * L)))])
        if mouth is not None and ip < mouth <= len(position):
            return ip, mouth
        on = np.zeros(len(position), dtype=bool)
        for e in self.guide[:-1]:
            on |= e.on(position, 0.004)
        e0 = self.guide[0]
        on |= e0.on(position, self.capture[0])
        on |= (np.abs(position[:, 1] - y) < 2.0 * rho) & \
            (position[:, 0] > el.a[0] - 0.01)
        off = np.flatnonzero(~on[ip:])
        k = ip + int(off[0]) if len(off) else len(position)
        return ip, k
