"""Bodies and static shapes the apparatus is built from: a roller on its cart-pushed
carriage (:class:`RollerUnit`), static segments (tables, plates, the floor) and the
channels' wall polylines; and the run's :class:`Clock` the parts read."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pymunk

from chainfountain.sim import fastbody
from chainfountain.sim.bodies import SCENERY_CATEGORY
from chainfountain.sim.chain import CHAIN_CATEGORY
from chainfountain.sim.config import CartConfig
from chainfountain.sim.fastbody import pos

ONLY_CHAIN = pymunk.ShapeFilter(categories=SCENERY_CATEGORY, mask=CHAIN_CATEGORY)
"""Filter of the plates and channel walls: they touch the chain only (not the rollers)."""
SCENERY = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
"""Filter of the tables and the floor (the rollers roll on the chain lying on them)."""

DRIVE_REACH = 1.0e3
"""Distance (m) from a carriage to the static anchor of its drive spring
(:meth:`RollerUnit.set_drive`), on the carriage's own line."""
DRIVE_STIFFNESS = 1.0e-6
"""Stiffness (N/m) of a drive spring: so soft that its force changes by 1e-6 N per metre
the carriage rolls (a cart's force is 0.04-0.3 N), i.e. a constant force."""


@dataclass(eq=False)
class Clock:
    """The apparatus's time (s): advanced by the bookkeeping
    (:meth:`~chainfountain.sim.apparatus.Apparatus.after_step`), read by the parts that
    time what they watch."""

    t: float = 0.0


@dataclass(eq=False)
class RollerUnit:
    """A roller on a carriage (horizontal groove, vertical slot) pushed by a cart force."""

    roller: pymunk.Body
    carriage: pymunk.Body
    shape: pymunk.Circle
    direction: float
    """Force direction on the carriage: -1 holds back (pick-up), +1 pushes (fold)."""
    cart: CartConfig | None
    g: float
    yc: float
    """Height of the roller centre at rest on the chain (m)."""
    drive: pymunk.DampedSpring
    """The cart's force and the bearing drag on the carriage, applied by pymunk in every
    step (:meth:`set_drive`)."""
    radius: float = 0.0
    """Roller radius r (m)."""

    @property
    def force(self) -> float:
        """Cart force ``m*g*sin(beta)`` (N), >= 0 along :attr:`direction`."""
        c = self.cart
        return 0.0 if c is None else c.mass * self.g * math.sin(c.incline)

    def set_cart_mass(self, m: float, base: float) -> None:
        """Change the cart mass live (the carriage carries it, and it pulls harder)."""
        if self.cart is not None:
            self.cart.mass = float(m)
        self.carriage.mass = base + (0.0 if self.cart is None else self.cart.mass)
        self.set_drive(self.drive.damping)

    def set_drive(self, drag: float) -> None:
        """The carriage's drive: the cart force :attr:`force` along :attr:`direction` and a
        bearing drag ``-drag*u`` (N s/m) on its velocity ``u``, as one pymunk damped spring
        from a static anchor :data:`DRIVE_REACH` behind the carriage on its line. The
        spring's stiffness is :data:`DRIVE_STIFFNESS`, so its force is constant to 1e-6 N
        per metre of travel; its damper is the drag (pymunk integrates it exactly over
        the step). Native, the drive costs no Python in the step."""
        s = self.drive
        s.stiffness = DRIVE_STIFFNESS
        s.rest_length = DRIVE_REACH + self.force / DRIVE_STIFFNESS
        s.damping = float(drag)

    @property
    def x(self) -> float:
        return pos(self.roller).x

    @property
    def speed(self) -> float:
        """Carriage velocity along ``x`` (m/s; read every step by the fold's collapse check)."""
        return float(fastbody.get_velocity(fastbody.handle(self.carriage)).x)


def add_roller(space: pymunk.Space, x: float, y_table: float, rho: float, r: float,
                m_roller: float, m_carriage: float, cart: CartConfig | None, direction: float,
                g: float, error_bias: float, vx: float, omega: float,
                drag: float = 0.0, fixed_axle: bool = False) -> RollerUnit:
    """A roller on its carriage at ``x`` on a table at ``y_table``, moving at ``vx`` and
    turning at ``omega``, its carriage driven by ``cart`` along ``direction`` with a
    bearing drag ``drag`` (N s/m; :meth:`RollerUnit.set_drive`).

    The roller turns on an axle in a vertical slot of the carriage, so it rests on the
    chain it rolls on; with ``fixed_axle`` (the gripped folding roller,
    :mod:`~chainfountain.sim.apparatus.grip`) the axle is pinned to the carriage and the
    roller's circle touches nothing (the chain is held by joints, not contact)."""
    yc = y_table + 2.0 * rho + r
    m_c = m_carriage + (cart.mass if cart is not None else 0.0)
    carriage = pymunk.Body(m_c, float("inf"))
    carriage.position = (x, yc)
    groove = pymunk.GrooveJoint(space.static_body, carriage, (x - 1e3, yc), (x + 1e3, yc),
                                (0.0, 0.0))
    roller = pymunk.Body(m_roller, 0.5 * m_roller * r * r)
    roller.position = (x, yc)
    slot: pymunk.Constraint
    if fixed_axle:
        slot = pymunk.PivotJoint(carriage, roller, (0.0, 0.0), (0.0, 0.0))
    else:
        slot = pymunk.GrooveJoint(carriage, roller, (0.0, -0.5 * r), (0.0, 0.5 * r),
                                  (0.0, 0.0))
    for j in (groove, slot):
        j.error_bias = error_bias
    circ = pymunk.Circle(roller, r)
    circ.friction = 1.0
    circ.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY,
                                     mask=0 if fixed_axle else pymunk.ShapeFilter.ALL_MASKS())
    carriage.velocity = (vx, 0.0)
    roller.velocity = (vx, 0.0)
    roller.angular_velocity = omega
    # the drive pushes away from its anchor: behind the carriage for its direction
    drive = pymunk.DampedSpring(space.static_body, carriage, (x - direction * DRIVE_REACH, yc),
                                (0.0, 0.0), DRIVE_REACH, 0.0, 0.0)
    space.add(carriage, groove, roller, slot, circ, drive)
    unit = RollerUnit(roller=roller, carriage=carriage, shape=circ, direction=direction,
                      cart=cart, g=g, yc=yc, drive=drive, radius=float(r))
    unit.set_drive(drag)
    return unit


def static_segment(space: pymunk.Space, a: tuple[float, float], b: tuple[float, float],
                   radius: float, friction: float, shape_filter: pymunk.ShapeFilter
                   ) -> pymunk.Segment:
    """A static segment from ``a`` to ``b`` (a table, plate or floor), not yet added."""
    s = pymunk.Segment(space.static_body, a, b, radius)
    s.friction = friction
    s.filter = shape_filter
    return s


def static_polyline(space: pymunk.Space, pts: np.ndarray, radius: float,
                     friction: float = 0.0, add: bool = True) -> list[pymunk.Segment]:
    out = []
    b = space.static_body
    for i in range(len(pts) - 1):
        s = pymunk.Segment(b, tuple(pts[i]), tuple(pts[i + 1]), radius)
        s.friction = friction
        s.filter = ONLY_CHAIN
        out.append(s)
    for i, s in enumerate(out):
        prev = pts[i - 1] if i > 0 else pts[i]
        nxt = pts[i + 2] if i + 2 < len(pts) else pts[i + 1]
        s.set_neighbors(tuple(prev), tuple(nxt))
    if add:
        space.add(*out)
    return out
