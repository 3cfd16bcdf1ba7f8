"""The chain: rigid rod links joined by pivot joints and rotary spring-dampers.

Links are kept in chain order: index 0 is the downstream (free, landing) end,
the last index the upstream end (the feed). Each link body's local ``+x`` axis
points downstream, so its front end is at ``(+L/2, 0)`` and its back end at
``(-L/2, 0)``; link ``i``'s back end is pinned to link ``i+1``'s front end.
The joint and the spring that connect link ``i`` to its upstream neighbour are
stored on link ``i`` (``up_joint``, ``up_spring``), so removing the front link
removes exactly its own constraints.

The rotary spring ``c`` and damper ``d`` are the joint resistance of the
paper's angular momentum balance (section "Equations of Motion"); ``c = d = 0``
gives the string model whose steady solution is the inverted catenary. A joint
between two dynamic links also gets the numerical damper ``wave_damping``
(N*m*s/rad, see :attr:`chainfountain.sim.config.SolverConfig.wave_damping`): it
stops a link-scale bending wave that the discrete chain otherwise grows where the
scaled tension exceeds 1/2, and leaves smooth bending alone.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pymunk

from chainfountain.sim.config import ChainConfig, SolverConfig

LINK_GROUP = 1
"""Shape-filter group of chain links (links do not collide with each other)."""

CHAIN_CATEGORY = 0b10
"""Collision category bit of chain links."""
BEND_CATCH = 0.9
"""A joint gets its bend limit once it is bent less than this share of it
(:meth:`Chain.tighten_bends`): a limit given to a joint bent beyond it would snap it
straight."""



@dataclass(eq=False)
class Link:
    """One rigid rod link and the constraints to its upstream neighbour."""

    body: pymunk.Body
    shape: pymunk.Segment | None = None
    id: int = 0
    """``body.id`` cached (reading it from pymunk is slow)."""
    up_joint: pymunk.PivotJoint | None = None
    up_spring: pymunk.DampedRotarySpring | None = None
    up_limit: pymunk.RotaryLimitJoint | None = None
    """The bend limit to the upstream neighbour (``chain.bend_limit``), once it holds."""


class Chain:
    """A chain of rod links living in a :class:`pymunk.Space`.

    Parameters
    ----------
    space:
        The space to add bodies and constraints to.
    chain:
        Link geometry, density, joint resistance and friction.
    solver:
        Supplies the joint ``error_bias``.
    shapes:
        Give links collision shapes (needed for floors, rollers, carts; costs
        about 70 % more per step, so fountains over an absorbing floor go without).
    wave_damping:
        Numerical damper (N*m*s/rad) on joints between two dynamic links, added to
        ``chain.bending_damping`` (see the module docstring).
    """

    def __init__(
        self, space: pymunk.Space, chain: ChainConfig, solver: SolverConfig, *, shapes: bool,
        wave_damping: float = 0.0,
    ) -> None:
        self.space = space
        self.cfg = chain
        self.solver = solver
        self.shapes = shapes
        self.wave_damping = float(wave_damping)
        self.L = float(chain.link_length)
        self.mass = float(chain.linear_density) * self.L
        self.moment = self.mass * self.L**2 / 12.0
        self.links: list[Link] = []
        self.ids: list[int] = []
        """Body ids in chain order (kept in step with ``links`` for fast batch lookup)."""
        self.version = 0
        """Incremented whenever links are added, removed or change type (cache key)."""
        self.bend_pending: list[Link] = []
        """Links whose joint to the upstream neighbour waits for its bend limit (bent
        beyond 90 % of it when joined); :meth:`tighten_bends` gives it when it can."""
        if chain.self_collision:
            self._filter = pymunk.ShapeFilter(categories=CHAIN_CATEGORY)
        else:
            self._filter = pymunk.ShapeFilter(group=LINK_GROUP, categories=CHAIN_CATEGORY)

    # ------------------------------------------------------------------ creation
    def make_body(self, center: tuple[float, float], angle: float, *,
                  kinematic: bool = False,
                  velocity: tuple[float, float] = (0.0, 0.0),
                  angular_velocity: float = 0.0) -> Link:
        """Create (not yet added) a link centred at ``center`` pointing downstream at ``angle``."""
        if kinematic:
            body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        else:
            body = pymunk.Body(self.mass, self.moment)
        body.position = center
        body.angle = angle
        body.velocity = velocity
        body.angular_velocity = angular_velocity
        shape = None
        if self.shapes:
            h = 0.5 * self.L
            shape = pymunk.Segment(body, (-h, 0.0), (h, 0.0), self.cfg.link_radius)
            shape.friction = self.cfg.friction
            shape.filter = self._filter
        return Link(body=body, shape=shape, id=body.id)

    def _add_link_objects(self, link: Link) -> None:
        if link.shape is not None:
            self.space.add(link.body, link.shape)
        else:
            self.space.add(link.body)

    def _connect(self, down: Link, up: Link) -> None:
        """Pin ``down``'s back end to ``up``'s front end and add the rotary spring."""
        h = 0.5 * self.L
        joint = pymunk.PivotJoint(down.body, up.body, (-h, 0.0), (h, 0.0))
        joint.error_bias = self.solver.joint_error_bias
        joint.collide_bodies = False
        down.up_joint = joint
        self.space.add(joint)
        self._fit_spring(down, up)
        if self.cfg.bend_limit > 0.0:
            self._limit_bend(down, up)

    def _limit_bend(self, down: Link, up: Link) -> bool:
        """Give the joint from ``down`` to ``up`` its bend limit ``+-chain.bend_limit`` if
        it is bent less than 90 % of it (else it waits in :attr:`bend_pending`); True when
        given."""
        lim = self.cfg.bend_limit
        raw = up.body.angle - down.body.angle  # the joint limits this, unwrapped
        turns = 2.0 * math.pi * round(raw / (2.0 * math.pi))
        if abs(raw - turns) > BEND_CATCH * lim:
            if down not in self.bend_pending:
                self.bend_pending.append(down)
            return False
        j = pymunk.RotaryLimitJoint(down.body, up.body, turns - lim, turns + lim)
        j.collide_bodies = False
        down.up_limit = j
        self.space.add(j)
        return True

    def tighten_bends(self) -> int:
        """Give the waiting joints (:attr:`bend_pending`) their bend limit where they have
        straightened within 90 % of it; returns how many still wait. Call it now and then
        (a scene: every few steps)."""
        still = []
        index = {lk.id: i for i, lk in enumerate(self.links)} if self.bend_pending else {}
        for down in self.bend_pending:
            i = index.get(down.id)
            if i is None or i + 1 >= len(self.links) or down.up_joint is None:
                continue  # the link or its joint has gone
            if not self._limit_bend(down, self.links[i + 1]):
                still.append(down)
        self.bend_pending = still
        return len(still)

    def _fit_spring(self, down: Link, up: Link) -> None:
        """Give the joint from ``down`` to ``up`` the spring and damper it needs now:
        ``c`` and ``d`` of the chain, plus :attr:`wave_damping` when both links are
        dynamic; no spring object when both are zero."""
        c = self.cfg.bending_stiffness
        d = self.cfg.bending_damping
        if math.isinf(down.body.moment) and math.isinf(up.body.moment):
            c = d = 0.0  # neither can turn (the ideal machine's guide): nothing to spring
        elif (self.wave_damping > 0.0 and down.body.body_type == pymunk.Body.DYNAMIC
                and up.body.body_type == pymunk.Body.DYNAMIC):
            d += self.wave_damping
        spring = down.up_spring
        if c == 0.0 and d == 0.0:
            if spring is not None:
                self.space.remove(spring)
                down.up_spring = None
            return
        if spring is None:
            spring = pymunk.DampedRotarySpring(down.body, up.body, 0.0, c, d)
            spring.collide_bodies = False
            down.up_spring = spring
            self.space.add(spring)
        else:
            spring.stiffness = c
            spring.damping = d

    def refit_spring(self, i: int) -> None:
        """Refit the spring of the joint from link ``i`` to link ``i + 1`` (after one of them
        changed type, e.g. a guide link released into the fountain)."""
        if 0 <= i < len(self.links) - 1 and self.links[i].up_joint is not None:
            self._fit_spring(self.links[i], self.links[i + 1])

    def append(self, link: Link) -> None:
        """Add ``link`` at the upstream end and connect it to the current last link."""
        self._add_link_objects(link)
        if self.links:
            last = self.links[-1]
            if last.body.body_type != pymunk.Body.DYNAMIC and \
                    link.body.body_type != pymunk.Body.DYNAMIC:
                raise ValueError("cannot join two non-dynamic links")
            self.links.append(link)
            self._connect(last, link)
        else:
            self.links.append(link)
        self.ids.append(link.id)
        self.version += 1

    def insert(self, i: int, link: Link, *, with_shape: bool = True) -> None:
        """Put ``link`` between links ``i - 1`` and ``i`` (``0 < i < len``): the joint
        between them is replaced by one to each side of ``link``. The caller lays
        ``link`` into the gap (``chainfountain.sim.apparatus``: the plate treadmill)."""
        if not 0 < i < len(self.links):
            raise IndexError(f"insert at {i}: needs a neighbour on each side")
        down, up = self.links[i - 1], self.links[i]
        self._disconnect(down)
        if with_shape or link.shape is None:
            self._add_link_objects(link)
        else:
            self.space.add(link.body)
        self.links.insert(i, link)
        self.ids.insert(i, link.id)
        self._connect(down, link)
        self._connect(link, up)
        self.version += 1

    def remove(self, i: int) -> Link:
        """Take link ``i`` (``0 < i < len - 1``) out of the chain with its constraints and
        pin its neighbours to each other: the mirror of :meth:`insert`. The caller first
        closes the gap (``chainfountain.sim.apparatus``: the lower plate treadmill)."""
        if not 0 < i < len(self.links) - 1:
            raise IndexError(f"remove at {i}: needs a neighbour on each side")
        down, link, up = self.links[i - 1], self.links[i], self.links[i + 1]
        self._disconnect(down)
        self._remove_objects(link)
        del self.links[i]
        del self.ids[i]
        self._connect(down, up)
        self.version += 1
        return link

    def append_unjoined(self, link: Link) -> None:
        """Add ``link`` at the upstream end without a joint (for kinematic guide links)."""
        self._add_link_objects(link)
        self.links.append(link)
        self.ids.append(link.id)
        self.version += 1

    def join(self, i: int) -> None:
        """Create the joint between link ``i`` and link ``i+1`` (if it is missing)."""
        down, up = self.links[i], self.links[i + 1]
        if down.up_joint is None:
            self._connect(down, up)
            self.version += 1

    def unjoin(self, i: int) -> None:
        """Remove the joint (with its spring and bend limit) between link ``i`` and link
        ``i+1``: the mirror of :meth:`join` (the gripped folding roller holds both links,
        :mod:`chainfountain.sim.apparatus.grip`)."""
        down = self.links[i]
        if down.up_joint is not None:
            self._disconnect(down)
            self.version += 1

    def pop_front(self) -> Link:
        """Remove the downstream end link (with its constraints) from the space."""
        link = self.links.pop(0)
        self.ids.pop(0)
        self._remove_objects(link)
        self.version += 1
        return link

    def _disconnect(self, down: Link) -> None:
        """Remove the joint, spring and bend limit from ``down`` to its upstream neighbour."""
        for c in (down.up_joint, down.up_spring, down.up_limit):
            if c is not None:
                self.space.remove(c)
        down.up_joint = down.up_spring = down.up_limit = None

    def _remove_objects(self, link: Link) -> None:
        objs: list = [link.body]
        if link.shape is not None and link.shape.space is not None:  # grooved: out already
            objs.append(link.shape)
        if link.up_joint is not None:
            objs.append(link.up_joint)
        if link.up_spring is not None:
            objs.append(link.up_spring)
        if link.up_limit is not None:
            objs.append(link.up_limit)
        self.space.remove(*objs)
        link.up_joint = None
        link.up_spring = None
        link.up_limit = None

    def clear(self) -> None:
        """Remove all links."""
        while self.links:
            self.pop_front()

    def make_dynamic(self, link: Link) -> None:
        """Turn a kinematic link into a dynamic one, keeping its velocity."""
        vel = link.body.velocity
        w = link.body.angular_velocity
        link.body.body_type = pymunk.Body.DYNAMIC
        link.body.mass = self.mass
        link.body.moment = self.moment
        link.body.velocity = vel
        link.body.angular_velocity = w
        self.version += 1

    # ------------------------------------------------------------------ live settings
    def set_bending(self, stiffness: float | None = None, damping: float | None = None) -> None:
        """Change ``c`` and/or ``d`` of all joints live (adds springs that were skipped at zero)."""
        if stiffness is not None:
            self.cfg.bending_stiffness = float(stiffness)
        if damping is not None:
            self.cfg.bending_damping = float(damping)
        for i, link in enumerate(self.links[:-1]):
            if link.up_joint is not None:
                self._fit_spring(link, self.links[i + 1])

    def set_error_bias(self, error_bias: float) -> None:
        """Change the pivot joints' ``error_bias`` live."""
        self.solver.joint_error_bias = float(error_bias)
        for link in self.links:
            if link.up_joint is not None:
                link.up_joint.error_bias = error_bias

    def set_friction(self, friction: float) -> None:
        """Change the links' friction coefficient live."""
        self.cfg.friction = float(friction)
        for link in self.links:
            if link.shape is not None:
                link.shape.friction = friction

    # ------------------------------------------------------------------ helpers
    def ends(self, link: Link) -> tuple[pymunk.Vec2d, pymunk.Vec2d]:
        """World positions ``(front, back)`` of one link."""
        h = 0.5 * self.L
        return link.body.local_to_world((h, 0.0)), link.body.local_to_world((-h, 0.0))

    def __len__(self) -> int:
        return len(self.links)
