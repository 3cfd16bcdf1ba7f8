"""'open': the tail. The end channel turns the chain horizontal and it slides away on a
long frictionless plate (with ``plate = "groove"``: a joint guide, slide joints to the
turn's centre then one plate groove per link, the tail beyond :data:`~.tuning.TAIL_KEEP`
links lumped into the end link); the moving mass grows at ``lambda*v/2``."""

from __future__ import annotations

import math
from collections import deque

import numpy as np
import pymunk

from chainfountain.sim.apparatus.parts import ONLY_CHAIN, static_segment
from chainfountain.sim.apparatus.tuning import OPEN_CAPTURE, OPEN_CLOSE_RATE, TAIL_KEEP
from chainfountain.sim.chain import Link
from chainfountain.sim.guide import GUIDE_BIAS, PLAY


class OpenTail:
    """The open arrangement's tail (a mixin of
    :class:`~chainfountain.sim.apparatus.Apparatus`)."""

    def _init_open_state(self) -> None:
        self._lo_n = 0
        """'open' with ``plate = "groove"``: links ``0 .. _lo_n-1`` (the tail on the lower
        plate) run in frictionless groove joints on the line ``y = y_lo``."""
        self._lo_joints: list[pymunk.GrooveJoint] = []
        self.tail_mass = 0.0
        """'open': mass (kg) of the tail links lumped into the end link (see _lump_tail)."""
        self._arc: deque[tuple[Link, pymunk.SlideJoint]] = deque()
        """'open' guide: links ``_lo_n .. _lo_n + len(_arc) - 1`` held on the turn."""

    @property
    def tail_grooved(self) -> int:
        """'open' with ``plate = "groove"``: how many links (chain indices ``0 ..
        tail_grooved-1``, the tail) run in the lower plate's grooves."""
        return self._lo_n

    @property
    def turn_held(self) -> deque[tuple[Link, pymunk.SlideJoint]]:
        """'open' guide: the links held on the turn (chain indices from
        :attr:`tail_grooved` on) with their slide joints. Read only."""
        return self._arc

    @property
    def end_pull(self) -> float:
        """Constant pull on the downstream end link in ``+x`` (N; 'open' only)."""
        return float(self.cfg.end_pull) if self.variant == "open" else 0.0

    @property
    def open_drive(self) -> float:
        """'open': the constant force (N) driving the moving chain, the weight of the drop
        from the upper plate to the tail's plate plus the end pull,
        ``lambda g (y_up - y_lo) + F_pull``."""
        lam = self.sim_cfg.chain.linear_density
        return lam * self.g * (self.y_up - self.y_lo) + self.end_pull

    def _build_open_plate(self, xl: float) -> list[np.ndarray]:
        """The long frictionless lower plate from the end channel's exit ``xl`` (a static
        segment with ``plate = "contact"``, else drawn only: the tail's grooves run on its
        line); returns the chain's path onto it."""
        a, rho = self.cfg, self.rho
        v0 = float(a.speed)
        far = xl + v0 * a.duration * 1.5 + 1.0
        self.plate_lo = static_segment(self.space, (xl, self.y_lo - rho - 0.002),
                                       (far, self.y_lo - rho - 0.002), 0.002, 0.0, ONLY_CHAIN)
        self.far_lo = far
        if a.plate == "contact":
            self.space.add(self.plate_lo)
        return [np.array([[xl + 0.2, self.y_lo]])]

    def _update_lo_grooves(self) -> None:
        """'open': the tail leaving the end channel runs in a frictionless groove joint per
        link on the lower plate line (as the upper plate; no plate contacts, no waves on
        the tail). The tail only grows at its upstream side, so the grooved links are
        always the first ``_lo_n`` of the chain.

        With the joint guide, the turn: a link whose centre comes within the capture
        band of the circle (past the mouth, before the bottom) gets a slide joint to the
        centre (distance limits around R: a frictionless two-sided circular groove with
        a little play); past the bottom it moves to the plate groove."""
        if self.variant != "open":
            return
        if not self.guided:
            self._groove_tail()
            return
        if not self._arc:  # the tail laid out on the plate
            self._groove_tail()
        self._capture_on_turn()
        self._close_turn()
        self._turn_to_grooves()

    def _groove_tail(self) -> None:
        """Put the links lying on the lower plate line past its start into grooves."""
        links = self.chain.links
        xl, y = self.x_plate_lo_start, self.y_lo
        while self._lo_n < len(links):
            b = links[self._lo_n].body
            if not (b.position.x > xl and abs(b.position.y - y) < 2.0 * self.rho):
                break
            self._groove_lo(links[self._lo_n])

    def _capture_on_turn(self) -> None:
        """Give each link that has come within the turn's capture band a slide joint to
        the turn's centre."""
        links = self.chain.links
        space = self.space
        cx, cy = self.guide_centre
        Rc = self.guide_radius
        th_mouth = math.atan2(-math.cos(self.alphaE), -math.sin(self.alphaE))
        while True:
            i = self._lo_n + len(self._arc)
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
            self._arc.append((link, j))

    def _close_turn(self) -> None:
        """Close the outer limit of each link on the turn in toward ``R + PLAY`` at
        :data:`~.tuning.OPEN_CLOSE_RATE`."""
        cx, cy = self.guide_centre
        Rc = self.guide_radius
        close = OPEN_CLOSE_RATE * self.sim_cfg.solver.dt
        for link, j in self._arc:
            if j.max > Rc + PLAY:
                j.max = max(Rc + PLAY, min(j.max - close, math.hypot(
                    link.body.position.x - cx, link.body.position.y - cy)))

    def _turn_to_grooves(self) -> None:
        """Move the links past the turn's bottom from their slide joints to plate
        grooves."""
        cx = self.guide_centre[0]
        while self._arc and self._arc[0][0].body.position.x > cx:
            link, j = self._arc.popleft()
            self.space.remove(j)
            self._groove_lo(link)

    def _groove_lo(self, link: Link) -> None:
        """Put ``links[_lo_n]`` into a frictionless groove on the lower plate line."""
        y = self.y_lo
        j = pymunk.GrooveJoint(self.space.static_body, link.body,
                               (self.x_plate_lo_start - 0.05, y), (self.far_lo, y), (0.0, 0.0))
        j.error_bias = self.sim_cfg.solver.joint_error_bias
        self.space.add(j)
        if link.shape is not None and link.shape.space is not None:
            self.space.remove(link.shape)
        self._lo_joints.append(j)
        self._lo_n += 1

    def _lump_tail(self) -> int:
        """'open' with the joint guide: keep at most ``TAIL_KEEP`` links in the plate
        grooves; the far end link beyond is removed and its mass added to the next one
        (the tail is straight, horizontal and frictionless, so it moves as one body
        and the lumped mass is exact for the chain's motion along the path, while the
        solver keeps a short chain of grooves: a tail of hundreds of grooved links made
        the turn's slide joints yield). Returns the number of links removed."""
        if not self.guided:
            return 0
        links = self.chain.links
        n = 0
        while self._lo_n > TAIL_KEEP and len(links) > 2:
            j = self._lo_joints.pop(0)
            self.space.remove(j)
            end, nxt = links[0], links[1].body
            if end.shape is not None and end.shape.space is None:
                self.space.add(end.shape)  # so the chain can remove it
            m_end = end.body.mass
            nxt.mass = nxt.mass + m_end
            nxt.moment = nxt.moment + m_end * self.L**2 / 12.0
            self.chain.pop_front()
            self._lo_n -= 1
            self.tail_mass = nxt.mass - self.chain.mass
            n += 1
        return n
