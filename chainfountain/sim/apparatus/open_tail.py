"""'open': the tail. The end channel turns the chain horizontal and it slides away on a
long frictionless plate (with ``plate = "groove"``: a joint guide, slide joints to the
turn's centre then one plate groove per link, the tail beyond :data:`~.tuning.TAIL_KEEP`
links lumped into the end link); the moving mass grows at ``lambda*v/2``."""

from __future__ import annotations

import math
from collections import deque

import numpy as np
import pymunk

from chainfountain.sim.apparatus.ends import EndPart
from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.parts import ONLY_CHAIN, static_segment
from chainfountain.sim.apparatus.tuning import OPEN_CAPTURE, OPEN_CLOSE_RATE, TAIL_KEEP
from chainfountain.sim.chain import Chain, Link
from chainfountain.sim.guide import GUIDE_BIAS, PLAY


class OpenTail:
    """The open arrangement's tail: the long lower plate (built into the space after the
    end channel's catch) and the links on it and on the turn."""

    def __init__(self, space: pymunk.Space, chain: Chain, layout: Layout,
                 end: EndPart) -> None:
        self.space = space
        self.chain = chain
        self.layout = layout
        self.y_lo = end.y_lo
        self.x_plate_lo_start = end.x_plate_lo_start
        self.guide_centre = end.guide_centre
        self.guide_radius = end.guide_radius
        xl = end.x_exit
        self.x_exit = xl
        a, rho = layout.cfg, layout.rho
        v0 = float(a.speed)
        far = xl + v0 * a.duration * 1.5 + 1.0
        self.plate_lo: pymunk.Segment = static_segment(
            space, (xl, self.y_lo - rho - 0.002), (far, self.y_lo - rho - 0.002), 0.002, 0.0,
            ONLY_CHAIN)
        """The long frictionless lower plate from the end channel's exit (a static segment
        with ``plate = "contact"``, else drawn only: the tail's grooves run on its line)."""
        self.far_lo = far
        if a.plate == "contact":
            space.add(self.plate_lo)
        self.lo_n = 0
        """With ``plate = "groove"``: links ``0 .. lo_n-1`` (the tail on the lower plate)
        run in frictionless groove joints on the line ``y = y_lo``."""
        self._lo_joints: list[pymunk.GrooveJoint] = []
        self.tail_mass = 0.0
        """Mass (kg) of the tail links lumped into the end link (see :meth:`lump_tail`)."""
        self.arc: deque[tuple[Link, pymunk.SlideJoint]] = deque()
        """The joint guide's turn: links ``lo_n .. lo_n + len(arc) - 1`` held on it with
        their slide joints."""

    def path(self) -> list[np.ndarray]:
        """The chain's path onto the lower plate."""
        return [np.array([[self.x_exit + 0.2, self.y_lo]])]

    def update(self) -> None:
        """The tail leaving the end channel runs in a frictionless groove joint per link
        on the lower plate line (as the upper plate; no plate contacts, no waves on the
        tail). The tail only grows at its upstream side, so the grooved links are always
        the first ``lo_n`` of the chain.

        With the joint guide, the turn: a link whose centre comes within the capture
        band of the circle (past the mouth, before the bottom) gets a slide joint to the
        centre (distance limits around R: a frictionless two-sided circular groove with
        a little play); past the bottom it moves to the plate groove."""
        if not self.layout.guided:
            self._groove_tail()
            return
        if not self.arc:  # the tail laid out on the plate
            self._groove_tail()
        self._capture_on_turn()
        self._close_turn()
        self._turn_to_grooves()

    def _groove_tail(self) -> None:
        """Put the links lying on the lower plate line past its start into grooves."""
        links = self.chain.links
        xl, y = self.x_plate_lo_start, self.y_lo
        while self.lo_n < len(links):
            b = links[self.lo_n].body
            if not (b.position.x > xl and abs(b.position.y - y) < 2.0 * self.layout.rho):
                break
            self._groove_lo(links[self.lo_n])

    def _capture_on_turn(self) -> None:
        """Give each link that has come within the turn's capture band a slide joint to
        the turn's centre."""
        links = self.chain.links
        space = self.space
        cx, cy = self.guide_centre
        Rc = self.guide_radius
        th_mouth = math.atan2(-math.cos(self.layout.alphaE), -math.sin(self.layout.alphaE))
        while True:
            i = self.lo_n + len(self.arc)
            if i >= len(links):
                break
            link = links[i]
            p = link.body.position
            d = math.hypot(p.x - cx, p.y - cy)
            th = math.atan2(p.y - cy, p.x - cx)
            if not (th_mouth - OPEN_CAPTURE[1] <= th <= -0.5 * math.pi + 0.05
                    and abs(d - Rc) < OPEN_CAPTURE[0]):
                break
            # the limit starts where the link is (no position kick: a stiff
            # correction would feed energy into the chain) and closes in to R + play
            j = pymunk.SlideJoint(space.static_body, link.body, (cx, cy), (0.0, 0.0),
                                  Rc - OPEN_CAPTURE[0], max(Rc + PLAY, d))
            j.error_bias = GUIDE_BIAS
            space.add(j)
            if link.shape is not None and link.shape.space is not None:
                space.remove(link.shape)
            self.arc.append((link, j))

    def _close_turn(self) -> None:
        """Close the outer limit of each link on the turn in toward ``R + PLAY`` at
        :data:`~.tuning.OPEN_CLOSE_RATE`."""
        cx, cy = self.guide_centre
        Rc = self.guide_radius
        close = OPEN_CLOSE_RATE * self.layout.sim_cfg.solver.dt
        for link, j in self.arc:
            if j.max > Rc + PLAY:
                j.max = max(Rc + PLAY, min(j.max - close, math.hypot(
                    link.body.position.x - cx, link.body.position.y - cy)))

    def _turn_to_grooves(self) -> None:
        """Move the links past the turn's bottom from their slide joints to plate
        grooves."""
        cx = self.guide_centre[0]
        while self.arc and self.arc[0][0].body.position.x > cx:
            link, j = self.arc.popleft()
            self.space.remove(j)
            self._groove_lo(link)

    def _groove_lo(self, link: Link) -> None:
        """Put ``links[lo_n]`` into a frictionless groove on the lower plate line."""
        y = self.y_lo
        j = pymunk.GrooveJoint(self.space.static_body, link.body,
                               (self.x_plate_lo_start - 0.05, y), (self.far_lo, y), (0.0, 0.0))
        j.error_bias = self.layout.sim_cfg.solver.joint_error_bias
        self.space.add(j)
        if link.shape is not None and link.shape.space is not None:
            self.space.remove(link.shape)
        self._lo_joints.append(j)
        self.lo_n += 1

    def lump_tail(self) -> int:
        """'open' with the joint guide: keep at most ``TAIL_KEEP`` links in the plate
        grooves; the far end link beyond is removed and its mass added to the next one
        (the tail is straight, horizontal and frictionless, so it moves as one body
        and the lumped mass is exact for the chain's motion along the path, while the
        solver keeps a short chain of grooves: a tail of hundreds of grooved links made
        the turn's slide joints yield). Returns the number of links removed."""
        if not self.layout.guided:
            return 0
        links = self.chain.links
        n = 0
        while self.lo_n > TAIL_KEEP and len(links) > 2:
            j = self._lo_joints.pop(0)
            self.space.remove(j)
            end, nxt = links[0], links[1].body
            if end.shape is not None and end.shape.space is None:
                self.space.add(end.shape)  # so the chain can remove it
            m_end = end.body.mass
            nxt.mass = nxt.mass + m_end
            nxt.moment = nxt.moment + m_end * self.layout.L**2 / 12.0
            self.chain.pop_front()
            self.lo_n -= 1
            self.tail_mass = nxt.mass - self.chain.mass
            n += 1
        return n
