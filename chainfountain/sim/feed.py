"""The motor-driven beaker: a straight guide feeding the chain at speed ``v``, angle ``alpha0``.

Scheme (validated against the paper's catenary, see ``docs/convergence.md``):
the last ``guide_links`` links of the chain are KINEMATIC bodies moving at ``v``
along the launch line ``u = (cos alpha0, sin alpha0)`` through the launch
point (the origin). Only the front guide link is pinned to the free chain.
When the back end of the front guide link passes the launch point, that link
becomes DYNAMIC (it keeps its velocity ``v*u``), the next guide link is pinned
to it and a new kinematic link is spawned at the back of the guide. Because
both transverse wave speeds ``v +- sqrt(T/lambda)`` point downstream when
``Tbar < 1``, the free chain leaves the guide tangentially, as the paper's
boundary condition ``alpha(0) = alpha0`` assumes.

Link-length bias: the first free joint (front end of the front guide link)
sits between ``L/2`` before and ``L/2`` beyond the launch point, so on average
the chain leaves exactly at the launch point. Likewise the absorbing floor
``H`` below the launch point removes the downstream end link when its *centre*
reaches the floor, so the free end (zero tension, ``Tbar_E = 0``) is on average
exactly at the floor. Triggering on a link end instead shifts ``Tbar_0`` by
``k*L/2`` (measured, see ``docs/convergence.md``). A solid floor is a static segment instead (see
:mod:`chainfountain.sim.bodies`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from chainfountain.sim.chain import Chain
from chainfountain.sim.config import FeedConfig, InitialConfig
from chainfountain.sim.reference import LaunchReference

PULL_REACH = 1.5
"""The floor pulls on the chain's end only while the end link's centre is within this many
link lengths of the floor: a landed end (its links are taken at the floor) always is, the
end of a chain still forming from its stub is not."""


class Feed:
    """Guide (kinematic links) at the launch point plus the absorbing floor bookkeeping."""

    def __init__(self, chain: Chain, cfg: FeedConfig,
                 end_pull: Callable[[float], float] | None = None) -> None:
        self.chain = chain
        self.cfg = cfg
        self.u = (math.cos(cfg.launch_angle), math.sin(cfg.launch_angle))
        self.offset = 0.0
        """Distance of the front guide link's front end beyond the launch point, in [-L/2, L/2)."""
        self.n_guide = 0
        """Number of kinematic guide links at the upstream end of the chain."""
        self.fed_links = 0
        """Links created so far (for a finite ``chain_length``)."""
        self.absorbed = 0
        """Links removed by the absorbing floor so far."""
        self.floor_y = -float(cfg.drop)
        self.end_dir: tuple[float, float] = (0.0, -1.0)
        """Unit direction of the floor's pull (the predicted landing tangent)."""
        self.end_force: tuple[float, float] | None = None
        """World force the floor applied to the end link (link 0) in the last step."""
        self.end_pull = end_pull
        """The floor's pull (N) as a function of the chain's speed, when a machine sets it
        (:class:`chainfountain.sim.put_down.PutDown`); ``None``: ``end_tension*lambda*v^2``."""
        self.launch_omega = 0.0
        """Angular velocity (rad/s) a link gets when it leaves the guide: the catenary's
        ``alpha' * v = -q v cos(alpha0)**2`` at the launch point, so the released link turns
        with the curve it enters instead of being bent into it by its neighbours."""

    # ------------------------------------------------------------------ geometry
    @property
    def speed(self) -> float:
        return float(self.cfg.speed)

    def _max_links(self) -> int | None:
        if self.cfg.chain_length <= 0.0:
            return None
        return max(1, int(round(self.cfg.chain_length / self.chain.L)))

    def _can_feed(self) -> bool:
        m = self._max_links()
        return m is None or self.fed_links < m

    def _guide_link(self, j: int):
        """Kinematic link ``j`` places behind the front guide link (``j = 0`` is the front)."""
        L = self.chain.L
        ux, uy = self.u
        d = self.offset - (j + 0.5) * L  # centre's signed distance along the launch line
        v = self.speed
        return self.chain.make_body((d * ux, d * uy), self.cfg.launch_angle, kinematic=True,
                                    velocity=(v * ux, v * uy))

    # ------------------------------------------------------------------ initial state
    def initialise(self, initial: InitialConfig, ref: LaunchReference | None) -> None:
        """Lay out the free chain (stub or predicted catenary) and the guide links."""
        L = self.chain.L
        rng = np.random.default_rng(initial.seed)
        v = self.speed
        a0 = self.cfg.launch_angle
        if initial.mode == "catenary" and ref is not None:
            n = int(math.floor(ref.arc_length / L))
            s = np.arange(n + 1) * L
            x, y, _ = ref.points_at_arc(s)
            keep = y > self.floor_y
            keep[0] = True
            x, y = x[keep], y[keep]
            angles = np.arctan2(np.diff(y), np.diff(x))
            omega = -v * ref.q * np.cos(angles) ** 2  # alpha' * ds/dt, alpha' = -q cos^2 alpha
        else:
            n = int(round(initial.stub_length / L)) if initial.mode == "stub" else 0
            angles = np.full(n, a0)
            omega = np.zeros(n)
        if len(angles):
            angles = angles + initial.jitter * rng.standard_normal(len(angles))
            # never exactly straight: at least a tiny bend even with jitter = 0
            if initial.jitter == 0.0 and initial.mode == "stub":
                angles = angles + 1e-4 * np.sin(np.arange(len(angles)))
        # walk from the launch point downstream, link k spans [k*L, (k+1)*L] of arc
        links = []
        px, py = 0.0, 0.0
        for ang, w in zip(angles, omega, strict=True):
            cx, cy = math.cos(ang), math.sin(ang)
            centre = (px + 0.5 * L * cx, py + 0.5 * L * cy)
            links.append(self.chain.make_body(centre, float(ang), velocity=(v * cx, v * cy),
                                              angular_velocity=float(w)))
            px, py = px + L * cx, py + L * cy
        links.reverse()  # chain order: downstream end first
        self.offset = 0.0
        for link in links:
            self.chain.append(link)
            self.fed_links += 1
        for j in range(self.cfg.guide_links):
            if not self._can_feed():
                break
            guide = self._guide_link(j)
            if j == 0 and links:
                self.chain.append(guide)
            else:
                self.chain.append_unjoined(guide)
            self.n_guide += 1
            self.fed_links += 1

    # ------------------------------------------------------------------ stepping
    def set_speed(self, v: float) -> None:
        """Change the feed speed live: all guide links move at ``v`` from now on."""
        self.cfg.speed = float(v)
        ux, uy = self.u
        for link in self.chain.links[len(self.chain.links) - self.n_guide:]:
            link.body.velocity = (v * ux, v * uy)

    def after_step(self, dt: float) -> None:
        """Advance the guide bookkeeping by one step and absorb links at the floor."""
        chain = self.chain
        L = chain.L
        self.offset += self.speed * dt
        while self.n_guide > 0 and self.offset >= 0.5 * L:
            self.offset -= L
            n = len(chain.links)
            i_front = n - self.n_guide
            front = chain.links[i_front]
            chain.make_dynamic(front)
            front.body.angular_velocity = self.launch_omega
            chain.refit_spring(i_front - 1)
            self.n_guide -= 1
            if self.n_guide > 0:
                chain.join(i_front)
            if self._can_feed():
                new = self._guide_link(self.n_guide)
                if self.n_guide == 0:
                    chain.append(new)
                else:
                    chain.append_unjoined(new)
                self.n_guide += 1
                self.fed_links += 1
            if self.n_guide > 0:
                self._resync_guide()
        if self.cfg.floor == "absorbing":
            self._absorb()

    def _resync_guide(self) -> None:
        """Put guide links exactly on the launch line (removes round-off drift)."""
        L = self.chain.L
        ux, uy = self.u
        links = self.chain.links
        n = len(links)
        for j in range(self.n_guide):
            d = self.offset - (j + 0.5) * L
            links[n - self.n_guide + j].body.position = (d * ux, d * uy)

    def set_reference(self, ref: LaunchReference | None) -> None:
        """Take the predicted fountain ``ref``: it aims the floor's pull and sets the
        released links' turning rate (:attr:`launch_omega`).

        The pull is a dead load along the predicted landing tangent: a force that turned
        with the end link (a follower force) destabilises narrow fountains (the paper's
        fountain D flew apart with one), while in the steady state both coincide.
        """
        if ref is None:
            self.end_dir = (0.0, -1.0)
            self.launch_omega = 0.0
            return
        c = 1.0 / (1.0 + ref.q * (ref.h + ref.H))  # cos(alpha_E), section "Inverted Catenary"
        self.end_dir = (c, -math.sqrt(max(0.0, 1.0 - c * c)))
        self.launch_omega = -ref.v * ref.q * math.cos(ref.alpha0) ** 2

    def before_step(self) -> None:
        """Apply the floor's pull ``Tbar_E*lambda*v^2`` to the chain end (absorbing floor only).

        The force acts at the downstream end of the end link, along the
        predicted landing direction (see :meth:`set_reference`): the end
        tension of the paper's string model.
        """
        self.end_force = None
        if self.cfg.floor != "absorbing" or self.n_free < 1:
            return
        if self.end_pull is not None:
            F = self.end_pull(self.speed)
        else:
            F = self.cfg.end_tension * self.chain.cfg.linear_density * self.speed**2
        if F <= 0.0:
            return
        body = self.chain.links[0].body
        if body.position.y > self.floor_y + PULL_REACH * self.chain.L:
            return  # the end has not landed yet (a chain forming from its stub)
        fx, fy = F * self.end_dir[0], F * self.end_dir[1]
        body.apply_force_at_world_point((fx, fy), body.local_to_world((0.5 * self.chain.L, 0.0)))
        self.end_force = (fx, fy)

    def _absorb(self) -> None:
        chain = self.chain
        while len(chain.links) - self.n_guide > 0:
            if chain.links[0].body.position.y > self.floor_y:
                break
            chain.pop_front()
            self.absorbed += 1

    @property
    def n_free(self) -> int:
        """Number of dynamic (free) links."""
        return len(self.chain.links) - self.n_guide
