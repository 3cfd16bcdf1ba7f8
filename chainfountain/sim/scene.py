"""A free chain laid along a polyline: the public API for scenes without a feed.

:class:`ChainScene` builds the project's chain (rod links, pivot joints, see
:mod:`chainfountain.sim.chain`) along a polyline, pins and releases its points, adds a
floor, steps in pymunk sub-steps and reads positions, speeds, tensions, pin forces and
the floor's force. Scene levels (``kind = "scene"``) run on it
(:mod:`chainfountain.sim.scene_sim`), among them the validation problems with closed
forms: the folded chain falling with one end fixed and the chain dropped onto a scale
(``chainfountain/levels/falling_chain.toml``, ``chainfountain/levels/chain_on_scale.toml``,
``tests/sim/test_scene_levels.py``).

Its default solver (:data:`SCENE_SOLVER`) keeps the energy of fast folds: the energy a
fold loses is set by how far the links rounding it turn in one pymunk step,
``h*v/w`` (``w`` the fold's width); it must stay below about 0.015 for the free end of
a folded chain to keep within 2 % of the energy-conserving speed (``research/`` and
``docs/convergence.md``). A 250-us step in 8 sub-steps (31 us) does that up to 6 m/s
for a fold 1.4 cm wide.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
import pymunk

from chainfountain.sim.bodies import SCENERY_CATEGORY, Floor
from chainfountain.sim.chain import Chain
from chainfountain.sim.config import ChainConfig, SolverConfig
from chainfountain.sim.measure import ChainReader, joint_forces, signed_tension

TIGHTEN_EVERY = 40
"""A joint waiting for its bend limit (``chain.bend_limit``) is tried every this many steps."""
SCENE_SOLVER = SolverConfig(dt=2.5e-4, substeps=8, iterations=2)
"""Solver of a scene unless told otherwise: 31-us pymunk steps, 2 iterations each."""


@dataclass(eq=False)
class Pin:
    """A point of the chain held in place (returned by :meth:`ChainScene.pin`)."""

    point: int
    joint: pymunk.PivotJoint
    released: bool = False


class ChainScene:
    """A chain along ``points`` (``(N + 1, 2)`` m, every segment one link of the same
    length), at rest, under gravity ``g`` pointing down (-y).

    Points are numbered along the polyline, ``0 .. N``; link ``i`` joins points ``i`` and
    ``i + 1``. With ``collide`` the links get capsule shapes (radius
    ``chain.link_radius``) so they can land on a floor; they never collide with each
    other.
    """

    def __init__(self, points, *, linear_density: float = 0.05, gravity: float = 9.81,
                 solver: SolverConfig | None = None, collide: bool = False,
                 bending_damping: float = 0.0, friction: float = 0.6,
                 chain: ChainConfig | None = None) -> None:
        pts = np.asarray(points, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 3 or not np.isfinite(pts).all():
            raise ValueError("points: a finite (N + 1, 2) polyline with at least 2 links "
                             f"is needed, got shape {pts.shape}")
        seg = np.hypot(*np.diff(pts, axis=0).T)
        L = float(seg.mean())
        if not L > 0.0 or np.abs(seg / L - 1.0).max() > 1e-6:
            raise ValueError(f"points: every segment must be one link of the same length; "
                             f"lengths are {seg.min():.6g} ... {seg.max():.6g} m")
        if not (linear_density > 0.0 and gravity >= 0.0):
            raise ValueError(f"linear_density {linear_density} and gravity {gravity}: "
                             "allowed: linear_density > 0, gravity >= 0")
        self.solver = solver or SCENE_SOLVER
        self.g = float(gravity)
        self.space = pymunk.Space()
        self.space.gravity = (0.0, -self.g)
        self.space.iterations = self.solver.iterations
        self.space.collision_slop = self.solver.collision_slop
        if chain is not None:  # a level's chain: its every setting, at the points' spacing
            cfg = dataclasses.replace(chain, link_length=L)
        else:
            cfg = ChainConfig(link_length=L, linear_density=float(linear_density),
                              bending_damping=float(bending_damping), friction=float(friction))
        self.chain = Chain(self.space, cfg, self.solver, shapes=collide)
        n = len(pts) - 1
        self.n = n
        self.L = L
        # chain order runs downstream from point N back to point 0 (links[0] is link N-1)
        for i in reversed(range(n)):
            (x0, y0), (x1, y1) = pts[i], pts[i + 1]
            link = self.chain.make_body((0.5 * (x0 + x1), 0.5 * (y0 + y1)),
                                        math.atan2(y1 - y0, x1 - x0))
            self.chain.append(link)
        self.floor: Floor | None = None
        self.time = 0.0
        self._steps = 0
        self._reader = ChainReader(self.space, self.chain)
        self._last: tuple | None = None  # (pre, post, contacts) of the last pymunk step
        self._floor_impulse = np.zeros(2)
        self._pins: list[Pin] = []
        self._held = np.zeros(0)  # pin impulses summed since the last take_means()
        self._landed = np.zeros(2)  # floor impulse summed since the last take_means()
        self._since = 0.0

    # ------------------------------------------------------------------ set-up
    def _link(self, i: int):
        return self.chain.links[self.n - 1 - i]

    def _point_anchor(self, point: int) -> tuple[pymunk.Body, tuple[float, float]]:
        """A link holding ``point`` and the point in that link's frame."""
        if not 0 <= point <= self.n:
            raise ValueError(f"point {point}: allowed: 0 .. {self.n}")
        h = 0.5 * self.L
        if point < self.n:
            return self._link(point).body, (-h, 0.0)
        return self._link(self.n - 1).body, (h, 0.0)

    def pin(self, point: int) -> Pin:
        """Hold ``point`` where it is now (a pivot to the static world)."""
        body, local = self._point_anchor(point)
        world = body.local_to_world(local)
        joint = pymunk.PivotJoint(self.space.static_body, body, world, local)
        joint.error_bias = self.solver.joint_error_bias
        joint.collide_bodies = False
        self.space.add(joint)
        pin = Pin(point=point, joint=joint)
        self._pins.append(pin)
        self._held = np.append(self._held, 0.0)
        return pin

    def release(self, pin: Pin) -> None:
        """Let a pinned point go."""
        if not pin.released:
            self.space.remove(pin.joint)
            pin.released = True

    def set_velocity(self, vx: float, vy: float) -> None:
        """Give every link the velocity ``(vx, vy)`` (m/s), without spin."""
        for lk in self.chain.links:
            lk.body.velocity = (vx, vy)
            lk.body.angular_velocity = 0.0

    def add_floor(self, y: float, x0: float = -10.0, x1: float = 10.0, *,
                  friction: float = 0.6) -> Floor:
        """A static floor with its top surface at ``y`` (needs ``collide=True``)."""
        if not self.chain.shapes:
            raise ValueError("add_floor: the chain was built with collide=False; links "
                             "without shapes pass through floors")
        self.floor = Floor.add(self.space, y, x0, x1, friction=friction)
        return self.floor

    def add_wall(self, a: tuple[float, float], b: tuple[float, float], radius: float, *,
                 friction: float = 0.6) -> pymunk.Segment:
        """A static segment from ``a`` to ``b``, its surface ``radius`` from that line
        (needs ``collide=True``). Its contacts are not part of :meth:`floor_force`."""
        if not self.chain.shapes:
            raise ValueError("add_wall: the chain was built with collide=False; links "
                             "without shapes pass through walls")
        shape = pymunk.Segment(self.space.static_body, a, b, radius)
        shape.friction = friction
        shape.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
        self.space.add(shape)
        return shape

    # ------------------------------------------------------------------ stepping
    @property
    def h(self) -> float:
        """The pymunk step (s): ``solver.dt / solver.substeps``."""
        return self.solver.dt / self.solver.substeps

    def step(self) -> None:
        """Advance one time step ``solver.dt`` (``substeps`` pymunk steps). Joint, pin and
        tension readings are those of the last pymunk step; the floor's force is the mean
        over the step (impacts are short)."""
        h = self.h
        floor_imp = np.zeros(2)
        held = self._held
        for k in range(self.solver.substeps):
            last = k == self.solver.substeps - 1
            pre = self._reader.read() if last else None
            self.space.step(h)
            if last:
                self._last = (pre, self._reader.read(), self._reader.contact_impulses())
            if self.floor is not None:
                floor_imp += self._impulse_on_floor()
            for i, pin in enumerate(self._pins):
                if not pin.released:
                    held[i] += pin.joint.impulse
        self.time += self.solver.dt
        self._steps += 1
        if self.chain.bend_pending and self._steps % TIGHTEN_EVERY == 0:
            self.chain.tighten_bends()  # joints bent too far at the start get their limit
        self._floor_impulse = floor_imp
        self._landed += floor_imp
        self._since += self.solver.dt

    def _impulse_on_floor(self) -> np.ndarray:
        static = self.space.static_body
        floor = self.floor.shape
        imp = np.zeros(2)

        def add(arb: pymunk.Arbiter) -> None:
            a, b = arb.shapes
            if a is not floor and b is not floor:
                return  # a wall's contact
            # the impulse on the arbiter's first body is +total_impulse
            sign = 1.0 if arb.bodies[0] is static else -1.0
            imp[:] += (sign * arb.total_impulse.x, sign * arb.total_impulse.y)

        static.each_arbiter(add)
        return imp

    def advance(self, seconds: float) -> None:
        """Step for ``seconds`` (rounded to whole steps)."""
        for _ in range(int(round(seconds / self.solver.dt))):
            self.step()

    # ------------------------------------------------------------------ readings
    def points(self) -> np.ndarray:
        """Link ends ``(N + 1, 2)`` in polyline order (m)."""
        h = 0.5 * self.L
        out = np.empty((self.n + 1, 2))
        for i in range(self.n):
            out[i] = self._link(i).body.local_to_world((-h, 0.0))
        out[self.n] = self._link(self.n - 1).body.local_to_world((h, 0.0))
        return out

    def point_velocity(self, point: int) -> np.ndarray:
        """Velocity (m/s) of polyline point ``point``."""
        body, local = self._point_anchor(point)
        return np.array(body.velocity_at_local_point(local))

    def velocities(self) -> np.ndarray:
        """Velocities of the link centres ``(N, 2)`` in polyline order (m/s)."""
        return np.array([self._link(i).body.velocity for i in range(self.n)])

    def pin_force(self, pin: Pin) -> float:
        """Magnitude of the force (N) the pin exerts in the last pymunk step."""
        return float(pin.joint.impulse) / self.h

    def tensions(self) -> np.ndarray:
        """Tension (N, + = pull) at the interior points ``1 .. N-1`` in polyline order,
        from the momentum balance of the last pymunk step summed from point ``N``
        (:func:`chainfountain.sim.measure.joint_forces`): exact while point ``N`` is free
        and no pin holds a point between it and the joint."""
        if self._last is None:
            raise RuntimeError("tensions: step the scene first")
        pre, post, contacts = self._last
        f = joint_forces(pre, post, self.chain.mass, self.h, self.g, self.n, contacts)
        t, _ = signed_tension(f, post, self.n)
        return t[: self.n - 1][::-1].copy()

    def take_means(self) -> tuple[np.ndarray, np.ndarray]:
        """Mean forces (N) since the last call (or the start): each pin's, in the order
        pinned (0 while released), and the chain's on the floor ``(fx, fy)``; then starts
        the next interval. Impacts and a pin's step-to-step ringing average out."""
        span = self._since or math.inf
        out = (self._held / span, self._landed / span)
        self._held = np.zeros_like(self._held)
        self._landed = np.zeros(2)
        self._since = 0.0
        return out

    def floor_force(self) -> np.ndarray:
        """Mean force (N) the chain exerts on the floor over the last step (a chain at rest
        on it pushes down: ``(0, -weight)``)."""
        return self._floor_impulse / self.solver.dt

    def kinetic_energy(self) -> float:
        """Translational and rotational kinetic energy of the links (J)."""
        # pymunk's Body.kinetic_energy is m*v**2 + I*w**2, twice the energy
        return 0.5 * float(sum(lk.body.kinetic_energy for lk in self.chain.links))
