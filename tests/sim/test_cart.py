"""Cart on a frictionless inclined track (GrooveJoint): acceleration g*sin(beta)."""

from __future__ import annotations

import math

import pymunk
import pytest

from chainfountain.sim.bodies import Cart
from chainfountain.sim.config import CartConfig, SolverConfig

G = 9.81


@pytest.mark.parametrize("beta_deg", [10.0, 30.0, 60.0, -25.0])
def test_cart_accelerates_at_g_sin_beta(beta_deg: float) -> None:
    beta = math.radians(beta_deg)
    space = pymunk.Space()
    space.gravity = (0.0, -G)
    solver = SolverConfig()
    space.iterations = solver.iterations
    cart = Cart.add(space, CartConfig(incline=beta, track_length=10.0, mass=0.2),
                    error_bias=solver.joint_error_bias)
    dt = solver.dt
    steps = int(round(0.5 / dt))
    s0 = cart.track_position
    for _ in range(steps):
        space.step(dt)
    t = steps * dt
    a_speed = cart.track_speed / t
    a_dist = 2.0 * (cart.track_position - s0) / t**2
    expected = -G * math.sin(beta)  # + is uphill along the track direction
    assert a_speed == pytest.approx(expected, rel=0.005)
    # semi-implicit Euler overshoots distance by a*dt*t/2: far below 0.5 %
    assert a_dist == pytest.approx(expected, rel=0.005)
