"""Bodies and static shapes the apparatus is built from: a roller on its cart-pushed
carriage (:class:`RollerUnit`), static segments (tables, plates, the floor) and the
channels' wall polylines."""

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

    @property
    def force(self) -> float:
        """Cart force ``m*g*sin(beta)`` (N), >= 0 along :attr:`direction`."""
        c = self.cart
        return 0.0 if c is None else c.mass * self.g * math.sin(c.incline)

    def set_cart_mass(self, m: float, base: float) -> None:
        """Change the cart mass live (the carriage carries it)."""
        if self.cart is not None:
            self.cart.mass = float(m)
        self.carriage.mass = base + (0.0 if self.cart is None else self.cart.mass)

    @property
    def x(self) -> float:
        return pos(self.roller).x

    @property
    def speed(self) -> float:
        """Carriage velocity along ``x`` (m/s; read every step by the fold's collapse check)."""
        return float(fastbody.get_velocity(fastbody.handle(self.carriage)).x)


def add_roller(space: pymunk.Space, x: float, y_table: float, rho: float, r: float,
                m_roller: float, m_carriage: float, cart: CartConfig | None, direction: float,
                g: float, error_bias: float, vx: float, omega: float) -> RollerUnit:
    yc = y_table + 2.0 * rho + r
    m_c = m_carriage + (cart.mass if cart is not None else 0.0)
    carriage = pymunk.Body(m_c, float("inf"))
    carriage.position = (x, yc)
    groove = pymunk.GrooveJoint(space.static_body, carriage, (x - 1e3, yc), (x + 1e3, yc),
                                (0.0, 0.0))
    roller = pymunk.Body(m_roller, 0.5 * m_roller * r * r)
    roller.position = (x, yc)
    slot = pymunk.GrooveJoint(carriage, roller, (0.0, -0.5 * r), (0.0, 0.5 * r), (0.0, 0.0))
    for j in (groove, slot):
        j.error_bias = error_bias
    circ = pymunk.Circle(roller, r)
    circ.friction = 1.0
    circ.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
    carriage.velocity = (vx, 0.0)
    roller.velocity = (vx, 0.0)
    roller.angular_velocity = omega
    space.add(carriage, groove, roller, slot, circ)
    return RollerUnit(roller=roller, carriage=carriage, shape=circ, direction=direction,
                      cart=cart, g=g, yc=yc)


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
