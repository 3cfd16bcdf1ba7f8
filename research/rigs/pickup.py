"""Pick-up (unfolding) and put-down (folding) of a chain by a roller rolling on it.

Paper, section "Pick-Up and Pull-Down Forces" (Fig. schematic_pick_up): a
roller of radius ``r`` rolls without slip on chain lying at rest on a table.
The chain wraps from the bottom contact around the back of the roller and
leaves at the angle ``alpha`` (above the roller's direction of motion). With
``v`` the speed of the leaving chain along its own direction the paper finds

    v_R = v/(1 + cos(alpha))          (roller speed, no slip at the contact)
    F   = lambda*v**2/(1 + cos(alpha)) (pulling force, momentum balance)

and for the mirror image (folding, "put-down") ``F = lambda*v**2/2``.

:class:`RollerRig` builds exactly that in pymunk: a static table with
friction, a chain of rod links lying on it, a dynamic roller that rests on the
chain under its own weight and slides along the table on a carriage (a
dynamic body on a horizontal groove, rotation free, vertical play through a
second groove), and at the far end of the leaving strand a *port* of
kinematic links: for pick-up a drain that pulls the chain out at speed ``v``
along ``e = (cos alpha, sin alpha)``, for put-down a source that pushes it in
at ``v`` along ``-e`` (the time-reversed motion, same geometry). The port
translates with the roller's measured speed so that the strand keeps its
angle, which is the paper's geometry (the velocity of the exit point ``P`` is
``(v_R, 0) + v_R*(cos alpha, sin alpha)``).

A constant force ``cart_force`` can pull the carriage backwards along the
table (the weight component ``m*g*sin(beta)`` of a cart on an incline coupled
to the roller by an ideal rope; its mass adds to the carriage).

The strand tension comes from the exact momentum balance of
:mod:`chainfountain.sim.measure`, summed from the free end of the resting
chain with all contact impulses subtracted. In the moving strand
``dT = lambda*g*dy`` (paper: ``Tbar' = k*sin(alpha)``), so the force at the
exit point is ``T_j - lambda*g*(y_j - y_P)`` averaged over strand joints.
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque
from dataclasses import dataclass, field

import numpy as np
import pymunk

from chainfountain.sim.bodies import SCENERY_CATEGORY
from chainfountain.sim.chain import Chain, Link
from chainfountain.sim.config import ChainConfig, SolverConfig
from chainfountain.sim.measure import ChainReader, joint_forces, signed_tension


@dataclass
class RigConfig:
    """One pick-up or put-down experiment (SI units)."""

    mode: str = "pickup"
    """'pickup' (unfolding) or 'putdown' (folding)."""
    speed: float = 5.0
    """Chain speed ``v`` along the strand direction (m/s)."""
    angle: float = 0.0
    """Strand angle ``alpha`` above the roller's direction of motion (rad)."""
    radius: float = 0.03
    roller_mass: float = 0.02
    carriage_mass: float = 0.02
    cart_force: float = 0.0
    """Constant force on the carriage along ``-x`` (N): against the roller's motion for
    pick-up, with it for put-down; in both cases it raises the strand tension."""
    strand: float = 0.12
    """Length of the free strand from the exit point to the port (m)."""
    rest_length: float = 1.2
    """Length of chain lying on the table (pick-up: ahead of the roller)."""
    table_friction: float = 5.0
    roller_friction: float = 1.0
    gravity: float = 9.81
    chain: ChainConfig = field(default_factory=lambda: ChainConfig(
        link_length=0.01, linear_density=0.05, friction=1.0, link_radius=0.002))
    solver: SolverConfig = field(default_factory=SolverConfig)
    port_links: int = 3
    feed: str = "free"
    """Put-down only, ``angle = 0``: 'free' (the strand flies freely from the port to the
    roller) or 'groove' (as in the apparatus's lower plate: each strand link's centre runs
    in a frictionless groove joint on a horizontal line until it is ``release`` link
    lengths from the roller's top, and has no collision shape while grooved)."""
    release: float = 0.5
    """'groove' feed: a link leaves its groove once its centre is this many link lengths
    (ahead of the roller, along the chain's motion) from the roller's top."""
    clearance: float = 0.0
    """'groove' feed: height (m) of the groove line above the chain centre line on the
    roller's top (the apparatus: 0)."""


def _no_gravity(body: pymunk.Body, gravity: tuple[float, float], damping: float,
                dt: float) -> None:
    pymunk.Body.update_velocity(body, (0.0, 0.0), damping, dt)


class RollerRig:
    """A roller unfolding (or folding) a resting chain, driven by a kinematic port.

    Frame: table top at ``y = 0``, roller initially above ``x = 0``; for
    pick-up the roller moves in ``+x`` onto the resting chain that lies ahead
    of it, for put-down it moves in ``-x`` and lays the chain down behind it
    (at ``x > 0``). Chain order: index 0 is the free end of the resting chain,
    the last links are the port's kinematic links.
    """

    def __init__(self, cfg: RigConfig) -> None:
        if cfg.mode not in ("pickup", "putdown"):
            raise ValueError(f"mode {cfg.mode!r}: allowed 'pickup' or 'putdown'")
        if cfg.feed not in ("free", "groove"):
            raise ValueError(f"feed {cfg.feed!r}: allowed 'free' or 'groove'")
        if cfg.feed == "groove" and (cfg.mode != "putdown" or cfg.angle != 0.0):
            raise ValueError("feed 'groove' needs mode 'putdown' and angle 0")
        self.cfg = cfg
        space = pymunk.Space()
        space.gravity = (0.0, -cfg.gravity)
        space.iterations = cfg.solver.iterations
        space.collision_slop = cfg.solver.collision_slop
        self.space = space
        self.dt = float(cfg.solver.dt)
        self.g = float(cfg.gravity)
        ch = cfg.chain
        self.rho = ch.link_radius
        self.chain = Chain(space, ch, cfg.solver, shapes=True)
        self.L = self.chain.L
        self.sign = 1.0 if cfg.mode == "pickup" else -1.0
        # table
        tab = pymunk.Segment(space.static_body, (-20.0, -0.01), (20.0, -0.01), 0.01)
        tab.friction = cfg.table_friction
        tab.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
        space.add(tab)
        # carriage on a horizontal groove, roller on a vertical groove on the carriage
        r = cfg.radius
        yc = 2.0 * self.rho + r
        self.carriage = pymunk.Body(cfg.carriage_mass, float("inf"))
        self.carriage.position = (0.0, yc)
        groove = pymunk.GrooveJoint(space.static_body, self.carriage, (-20.0, yc), (20.0, yc),
                                    (0.0, 0.0))
        self.roller = pymunk.Body(cfg.roller_mass, 0.5 * cfg.roller_mass * r * r)
        self.roller.position = (0.0, yc)
        slot = pymunk.GrooveJoint(self.carriage, self.roller, (0.0, -0.5 * r), (0.0, 0.5 * r),
                                  (0.0, 0.0))
        for j in (groove, slot):
            j.error_bias = cfg.solver.joint_error_bias
        circ = pymunk.Circle(self.roller, r)
        circ.friction = cfg.roller_friction
        circ.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
        space.add(self.carriage, groove, self.roller, slot, circ)
        self.e = (math.cos(cfg.angle), math.sin(cfg.angle))
        self._lay_chain()
        self._fed: deque[tuple[Link, pymunk.GrooveJoint]] = deque()
        if cfg.feed == "groove":
            y_mid = 2.0 * self.rho + cfg.radius  # the strand, not the chain on the table
            for link in self.chain.links[:self.n_free]:
                if link.body.position.y > y_mid and self._feeds(link):
                    self._groove(link)
        self.reader = ChainReader(space, self.chain)
        self.time = 0.0
        self.steps = 0
        self.vR_pred = cfg.speed / (1.0 + math.cos(cfg.angle))
        self._samples: list[tuple[float, float, float, float, float, float]] = []

    # ------------------------------------------------------------------ layout
    def exit_point(self) -> tuple[float, float]:
        """Chain centreline point where the strand leaves the roller."""
        a = self.cfg.angle
        R = self.cfg.radius + self.rho
        c = self.roller.position
        return (c.x - R * math.sin(a), c.y + R * math.cos(a))

    def _lay_chain(self) -> None:
        cfg = self.cfg
        L, rho, r = self.L, self.rho, cfg.radius
        R = r + rho
        yc = 2.0 * rho + r
        s = self.sign
        vR = cfg.speed / (1.0 + math.cos(cfg.angle))
        pts: list[tuple[float, float]] = []
        # resting chain: free end at x = rest_length, up to the bottom contact (0, rho)
        n_rest = int(round(cfg.rest_length / L))
        for i in range(n_rest + 1):
            pts.append((cfg.rest_length - i * L, rho))
        # wrap: clockwise from the bottom (270 deg) via the back to the exit (90 deg + alpha)
        th0, th1 = 1.5 * math.pi, 0.5 * math.pi + cfg.angle
        arc = R * (th0 - th1)
        n_arc = max(2, int(math.ceil(arc / (0.25 * L))))
        for i in range(1, n_arc + 1):
            th = th0 - (th0 - th1) * i / n_arc
            pts.append((R * math.cos(th), yc + R * math.sin(th)))
        px, py = pts[-1]
        if cfg.feed == "groove":  # the strand and the port run on the groove line
            py += cfg.clearance
        ex, ey = self.e
        n_str = int(round(cfg.strand / L)) + cfg.port_links + 2
        for i in range(1, n_str + 1):
            pts.append((px + i * L * ex, py + i * L * ey))
        P = np.array(pts)
        seg = np.linalg.norm(np.diff(P, axis=0), axis=1)
        sarc = np.concatenate([[0.0], np.cumsum(seg)])
        n = int(sarc[-1] // L)
        q = np.arange(n + 1) * L
        X = np.interp(q, sarc, P[:, 0])
        Y = np.interp(q, sarc, P[:, 1])
        s_exit = n_rest * L + arc
        n_port = cfg.port_links
        # links between the first n_dyn links (up to strand + exit) are dynamic
        n_dyn = int((s_exit + cfg.strand) // L)
        n = min(n, n_dyn + n_port)
        port_vel = self._port_velocity(s * vR)
        om = -s * vR / R
        for i in range(n):
            x0, y0, x1, y1 = X[i], Y[i], X[i + 1], Y[i + 1]
            cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
            ang = math.atan2(y0 - y1, x0 - x1)  # local +x points toward index 0
            kin = i >= n_dyn
            mid = q[i] + 0.5 * L
            if mid < n_rest * L:
                vel, w = (0.0, 0.0), 0.0
            elif kin or mid > s_exit:
                vel, w = port_vel, 0.0
            else:  # on the roller, rolling without slip at centre speed s*vR
                vel, w = (s * vR - om * (cy - yc), om * cx), om
            link = self.chain.make_body((cx, cy), ang, kinematic=kin, velocity=vel,
                                        angular_velocity=w)
            if kin and i > n_dyn:
                self.chain.append_unjoined(link)
            else:
                self.chain.append(link)
        self.n_port = n_port
        self._i_strand = len(self.chain.links) - n_port
        self.carriage.velocity = (s * vR, 0.0)
        self.roller.velocity = (s * vR, 0.0)
        self.roller.angular_velocity = om

    def _port_velocity(self, u: float) -> tuple[float, float]:
        """Port links translate with the roller (``u`` along x) and move along ``e`` so that
        their velocity component along ``e`` is ``+v`` (pick-up) or ``-v`` (put-down)."""
        ex, ey = self.e
        w = self.sign * self.cfg.speed - u * ex
        return (u + w * ex, w * ey)

    # ------------------------------------------------------------------ grooved feed
    def _feeds(self, link: Link) -> bool:
        """'groove' feed: is ``link`` (dynamic, in the strand) still held by the grooves?"""
        return link.body.position.x - self.roller.position.x > self.cfg.release * self.L

    def _groove(self, link: Link) -> None:
        """Hold ``link``'s centre on the feed line (a frictionless groove joint), out of the
        collision broadphase: the apparatus's lower plate (``apparatus.joints.hold``)."""
        y = 3.0 * self.rho + 2.0 * self.cfg.radius + self.cfg.clearance
        j = pymunk.GrooveJoint(self.space.static_body, link.body, (-20.0, y), (20.0, y),
                               (0.0, 0.0))
        j.error_bias = self.cfg.solver.joint_error_bias
        self.space.add(j)
        if link.shape is not None and link.shape.space is not None:
            self.space.remove(link.shape)
        self._fed.append((link, j))

    def _update_feed(self) -> None:
        """Release the grooved links that have reached the roller (shape back in the space)."""
        fed = self._fed
        while fed and not self._feeds(fed[0][0]):
            link, j = fed.popleft()
            self.space.remove(j)
            if link.shape is not None:
                self.space.add(link.shape)

    # ------------------------------------------------------------------ stepping
    @property
    def n_free(self) -> int:
        """Dynamic links, counted from the free end of the resting chain."""
        return len(self.chain.links) - self.n_port

    def _exit_distance(self, p: pymunk.Vec2d) -> float:
        px, py = self.exit_point()
        return (p.x - px) * self.e[0] + (p.y - py) * self.e[1]

    def step(self) -> None:
        """One physics step (port velocities follow the carriage), then the bookkeeping."""
        self._physics_step()
        self._bookkeeping()

    def _physics_step(self) -> None:
        cfg = self.cfg
        if cfg.cart_force:
            # pick-up: against the roller's motion (+x); put-down: with it (-x)
            self.carriage.apply_force_at_local_point((-cfg.cart_force, 0.0))
        vel = self._port_velocity(float(self.carriage.velocity.x))
        for link in self.chain.links[-self.n_port:]:
            link.body.velocity = vel
        self.space.step(self.dt)
        self.steps += 1
        self.time = self.steps * self.dt

    def _bookkeeping(self) -> None:
        self._update_port()
        self._update_strand()
        if self.cfg.feed == "groove":
            self._update_feed()

    def _update_strand(self) -> None:
        """Links beyond the exit point fly without gravity (the paper's mechanism is
        analysed without gravity; with it the free strand would be a short inverted
        catenary that the straight port cannot follow)."""
        links = self.chain.links
        n_dyn = self.n_free
        self._i_strand = min(self._i_strand, n_dyn)
        while self._i_strand > 0 and \
                self._exit_distance(links[self._i_strand - 1].body.position) > 0.0:
            self._i_strand -= 1
            links[self._i_strand].body.velocity_func = _no_gravity
        while self._i_strand < n_dyn and \
                self._exit_distance(links[self._i_strand].body.position) <= 0.0:
            links[self._i_strand].body.velocity_func = pymunk.Body.update_velocity
            self._i_strand += 1

    def _update_port(self) -> None:
        chain = self.chain
        L = self.L
        ex, ey = self.e
        links = chain.links
        n = len(links)
        strand = self.cfg.strand
        if self.sign > 0:  # drain: the dynamic link next to the port becomes kinematic
            cand = links[n - self.n_port - 1]
            if self._exit_distance(cand.body.position) >= strand:
                first = links[n - self.n_port]
                fe = first.body.local_to_world((0.5 * L, 0.0))  # its end toward the roller
                # replace it by a kinematic link on the port line (pymunk cannot turn a
                # jointed body kinematic), re-joined to its dynamic neighbour
                i_c = n - self.n_port - 1
                if i_c < 2:
                    raise RuntimeError(
                        f"t = {self.time:.3f} s: the resting chain is used up; make "
                        f"rest_length longer than v_R*duration ({self.vR_pred:.3g} m/s)")
                prev = links[i_c - 1]
                objs = [cand.body] + [c for c in (cand.shape, cand.up_joint, cand.up_spring,
                                                  prev.up_joint, prev.up_spring) if c is not None]
                self.space.remove(*objs)
                prev.up_joint = prev.up_spring = None
                new = chain.make_body((fe.x - 0.5 * L * ex, fe.y - 0.5 * L * ey),
                                      self.cfg.angle + math.pi, kinematic=True,
                                      velocity=first.body.velocity)
                if new.shape is not None:
                    self.space.add(new.body, new.shape)
                else:
                    self.space.add(new.body)
                links[i_c] = new
                chain.ids[i_c] = new.id
                chain._connect(prev, new)
                self.n_port += 1
                chain.version += 1
                while self.n_port > self.cfg.port_links:
                    self._pop_back()
        else:  # source: the port link next to the chain is released once inside the strand
            i_front = n - self.n_port
            front = links[i_front]
            if self._exit_distance(front.body.position) <= strand:
                chain.make_dynamic(front)
                self.n_port -= 1
                if self.n_port > 0:
                    chain.join(i_front)
                if self.cfg.feed == "groove":
                    self._groove(front)
                last = links[-1]
                c = last.body.position
                new = chain.make_body((c.x + L * ex, c.y + L * ey), self.cfg.angle + math.pi,
                                      kinematic=True, velocity=last.body.velocity)
                chain.append_unjoined(new)
                self.n_port += 1

    def _pop_back(self) -> None:
        chain = self.chain
        link = chain.links.pop()
        chain.ids.pop()
        objs: list = [link.body]
        if link.shape is not None:
            objs.append(link.shape)
        self.space.remove(*objs)
        self.n_port -= 1
        chain.version += 1

    # ------------------------------------------------------------------ measuring
    def run(self, duration: float, *, settle: float, every: int = 7) -> RigResult:
        """Run ``duration`` s; measure after ``settle`` s every ``every`` steps."""
        n_steps = int(round(duration / self.dt))
        m = self.chain.mass
        ex, ey = self.e
        F, V, VR, ALPHA, T, PIV = [], [], [], [], [], []
        links = self.chain.links
        for _ in range(n_steps):
            sample = self.time >= settle and (self.steps + 1) % every == 0
            if sample:
                pre = self.reader.read()
                self.reader.arm()
            self._physics_step()
            if not sample:
                self._bookkeeping()
                continue
            post = self.reader.read()
            nd = self.n_free
            contacts = self.reader.contact_impulses()
            forces = joint_forces(pre, post, m, self.dt, self.g, nd, contacts)
            # links of the strand felt no gravity: take their weight back out
            ns = max(nd - self._i_strand, 0)
            if ns:
                corr = np.zeros(nd)
                corr[self._i_strand:] = m * self.g
                forces[:, 1] -= np.cumsum(corr)
            ten, _ = signed_tension(forces, post, nd)
            # joint j sits at link j's back end
            c = post.position[:nd]
            ang = post.angle[:nd]
            jx = c[:, 0] - 0.5 * self.L * np.cos(ang)
            jy = c[:, 1] - 0.5 * self.L * np.sin(ang)
            px, py = self.exit_point()
            d = (jx - px) * ex + (jy - py) * ey
            instrand = np.arange(nd) >= self._i_strand
            sel = instrand & (d > 0.25 * self.cfg.strand) & (d < 0.75 * self.cfg.strand)
            if not np.any(sel):
                self._bookkeeping()
                continue
            F.append(float(np.mean(ten[sel])))
            # the same joints' force from the solver's pivot impulses (no contact in between)
            PIV.append(float(np.mean([abs(links[j].up_joint.impulse)
                                      for j in np.flatnonzero(sel)
                                      if links[j].up_joint is not None])) / self.dt)
            lsel = instrand & (d > 0.2 * self.cfg.strand) & (d < 0.8 * self.cfg.strand)
            vel = post.velocity[:nd][lsel]
            V.append(float(np.mean(vel[:, 0] * ex + vel[:, 1] * ey)))
            VR.append(float(self.carriage.velocity.x))
            # strand angle from the link directions (links point toward the roller)
            a = ang[lsel]
            ALPHA.append(float(math.atan2(-np.mean(np.sin(a)), -np.mean(np.cos(a)))))
            T.append(self.time)
            self._bookkeeping()
        return RigResult(cfg=self.cfg, t=np.array(T), force=np.array(F), v=np.array(V),
                         v_roller=np.array(VR), alpha=np.array(ALPHA),
                         pivot_force=np.array(PIV))


@dataclass
class RigResult:
    """Time series of one rig run and its time averages against the paper."""

    cfg: RigConfig
    t: np.ndarray
    force: np.ndarray
    """Strand tension at the exit point (N)."""
    v: np.ndarray
    """Chain speed along the strand (signed: + leaving, - arriving)."""
    v_roller: np.ndarray
    alpha: np.ndarray
    pivot_force: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """The size of the same joints' force from the solver's pivot impulses (N). It
    involves no contact impulse. :attr:`force` is summed through the contacts, with the
    stale impulses of contacts that touch again taken out (:meth:`ChainReader.arm`; left
    in, they bias it when a cart presses the roller, ``docs/apparatus.md``); it is the
    component along the chain, so where the strand goes slack for a moment it is below
    this size."""

    @property
    def speed(self) -> float:
        return float(abs(np.mean(self.v)))

    @property
    def force_bar(self) -> float:
        """Mean exit force over ``lambda*v**2`` (v: measured mean chain speed)."""
        lam = self.cfg.chain.linear_density
        return float(np.mean(self.force)) / (lam * self.speed**2)

    @property
    def pivot_bar(self) -> float:
        """Mean of :attr:`pivot_force` over ``lambda*v**2``."""
        lam = self.cfg.chain.linear_density
        return float(np.mean(self.pivot_force)) / (lam * self.speed**2)

    @property
    def roller_ratio(self) -> float:
        """Measured roller speed over ``v``; paper ``1/(1 + cos(alpha))``."""
        return float(abs(np.mean(self.v_roller))) / self.speed

    @property
    def paper_bar(self) -> float:
        """The paper's scaled force: ``1/(1 + cos(alpha))`` (pick-up) or ``1/2`` (put-down)."""
        if self.cfg.mode == "pickup":
            return 1.0 / (1.0 + math.cos(self.cfg.angle))
        return 0.5


def run_rig(cfg: RigConfig, duration: float = 0.6, settle: float = 0.25) -> RigResult:
    """Build and run one rig (the resting chain is made long enough for ``duration``)."""
    if cfg.mode == "pickup":
        need = cfg.speed / (1.0 + math.cos(cfg.angle)) * duration * 1.3 + 0.2
        cfg = dataclasses.replace(cfg, rest_length=max(cfg.rest_length, need))
    return RollerRig(cfg).run(duration, settle=settle)


def lossless_bar(mode: str, alpha: float, cart_bar: float = 0.0) -> float:
    """Strand tension over ``lambda*v**2`` if the mechanism lost no energy.

    In the rig's geometry (strand translating with the roller, chain speed
    ``v`` along the strand, roller speed ``v_R = v/(1 + cos(alpha))``) the chain
    leaves with the full speed ``|V|**2 = v**2 + v_R**2*sin(alpha)**2``; a
    power balance ``T*v = lambda*v_R*|V|**2/2 + F_c*v_R`` (pick-up; the same
    for the time-reversed put-down) gives
    ``Tbar = (v_R/v)*(1 + (v_R/v)**2*sin(alpha)**2)/2 + Fbar_c*v_R/v``.
    The paper's ``1/(1 + cos(alpha))`` is twice the first term at ``alpha = 0``:
    its momentum balance leaves out the table's reaction, so it implies that half
    the work is dissipated.
    """
    if mode not in ("pickup", "putdown"):
        raise ValueError(mode)
    ratio = 1.0 / (1.0 + math.cos(alpha))
    return 0.5 * ratio * (1.0 + ratio**2 * math.sin(alpha) ** 2) + cart_bar * ratio
