"""Rigid-body building blocks besides the chain: floor, rollers, carts on inclined tracks.

These are what the later "apparatus" level kind (paper section "Generating
Steady-State Chain Fountains": pulleys and carts on inclined tracks) is built
from. All positions are in the launch frame (launch point at the origin, y up).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pymunk

from chainfountain.sim.config import CartConfig, RollerConfig

SCENERY_CATEGORY = 0b01
"""Collision category bit of floor, rollers and carts."""


@dataclass(eq=False)
class Floor:
    """A static floor segment links can land and pile on."""

    shape: pymunk.Segment
    y: float
    x0: float
    x1: float

    @classmethod
    def add(cls, space: pymunk.Space, y: float, x0: float, x1: float, *,
            friction: float = 0.6, radius: float = 0.005) -> Floor:
        """Add a static segment from ``(x0, y)`` to ``(x1, y)`` (top surface at ``y``)."""
        shape = pymunk.Segment(space.static_body, (x0, y - radius), (x1, y - radius), radius)
        shape.friction = friction
        shape.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
        space.add(shape)
        return cls(shape=shape, y=y, x0=x0, x1=x1)


@dataclass(eq=False)
class Roller:
    """A kinematic circle spinning at a set angular speed (counter-clockwise positive)."""

    body: pymunk.Body
    shape: pymunk.Circle
    cfg: RollerConfig

    @classmethod
    def add(cls, space: pymunk.Space, cfg: RollerConfig) -> Roller:
        body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        body.position = (cfg.x, cfg.y)
        body.angular_velocity = cfg.angular_speed
        shape = pymunk.Circle(body, cfg.radius)
        shape.friction = cfg.friction
        shape.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
        space.add(body, shape)
        return cls(body=body, shape=shape, cfg=cfg)

    def set_angular_speed(self, w: float) -> None:
        """Change the spin rate live (rad/s)."""
        self.cfg.angular_speed = float(w)
        self.body.angular_velocity = float(w)

    @property
    def surface_speed(self) -> float:
        """Rim speed ``|omega|*r`` (m/s)."""
        return abs(self.body.angular_velocity) * self.cfg.radius


@dataclass(eq=False)
class Cart:
    """A dynamic box sliding without friction along a straight inclined track (GrooveJoint).

    The track makes the angle ``incline`` (beta) with the horizontal; under
    gravity alone the cart accelerates downhill at ``g*sin(beta)``.
    """

    body: pymunk.Body
    shape: pymunk.Poly
    groove: pymunk.GrooveJoint
    cfg: CartConfig
    track_start: tuple[float, float]
    track_end: tuple[float, float]

    @classmethod
    def add(cls, space: pymunk.Space, cfg: CartConfig, *, error_bias: float = 1e-100) -> Cart:
        moment = pymunk.moment_for_box(cfg.mass, (cfg.width, cfg.height))
        body = pymunk.Body(cfg.mass, moment)
        body.position = (cfg.x, cfg.y)
        body.angle = cfg.incline
        shape = pymunk.Poly.create_box(body, (cfg.width, cfg.height))
        shape.friction = 0.6
        shape.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
        half = 0.5 * cfg.track_length
        ux, uy = math.cos(cfg.incline), math.sin(cfg.incline)
        a = (cfg.x - half * ux, cfg.y - half * uy)
        b = (cfg.x + half * ux, cfg.y + half * uy)
        groove = pymunk.GrooveJoint(space.static_body, body, a, b, (0.0, 0.0))
        groove.error_bias = error_bias
        # keep the cart aligned with its track (no rotation)
        lock = pymunk.RotaryLimitJoint(space.static_body, body, cfg.incline, cfg.incline)
        lock.error_bias = error_bias
        space.add(body, shape, groove, lock)
        return cls(body=body, shape=shape, groove=groove, cfg=cfg, track_start=a, track_end=b)

    @property
    def track_position(self) -> float:
        """Signed distance of the cart centre along the track from its centre (+ = uphill end)."""
        ux, uy = math.cos(self.cfg.incline), math.sin(self.cfg.incline)
        p = self.body.position
        return (p.x - self.cfg.x) * ux + (p.y - self.cfg.y) * uy

    @property
    def track_speed(self) -> float:
        """Velocity component along the track (m/s)."""
        ux, uy = math.cos(self.cfg.incline), math.sin(self.cfg.incline)
        v = self.body.velocity
        return v.x * ux + v.y * uy


def nudge_bodies(space: pymunk.Space, seed: int | tuple[int, ...], rel: float = 1e-12) -> None:
    """Change every dynamic body's velocity by about ``rel`` of itself (of 1 mm/s at
    rest), seeded: far below anything physical, as another machine or library build
    changes the last bits of a run."""
    rng = np.random.default_rng(seed)
    for body in space.bodies:
        if body.body_type == pymunk.Body.DYNAMIC:
            vx, vy = body.velocity
            scale = rel * (abs(vx) + abs(vy) + 1e-3)
            body.velocity = (vx + scale * rng.standard_normal(),
                             vy + scale * rng.standard_normal())
