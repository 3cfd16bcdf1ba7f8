"""chainfountain.sim.fastbody: the direct chipmunk calls give pymunk's own numbers."""

from __future__ import annotations

import math

import pymunk
import pytest

from chainfountain.sim import fastbody


@pytest.fixture
def body() -> pymunk.Body:
    space = pymunk.Space()
    b = pymunk.Body(0.3, 0.01)
    b.position = (0.25, -1.5)
    b.velocity = (3.0, -0.5)
    b.angle = 0.7
    space.add(b)
    b.space_ref = space  # keep the space alive with the body
    return b


def test_reads_match_pymunk(body: pymunk.Body) -> None:
    h = fastbody.handle(body)
    p, v = fastbody.get_position(h), fastbody.get_velocity(h)
    assert (p.x, p.y) == tuple(body.position)
    assert (fastbody.pos(body).x, fastbody.pos(body).y) == tuple(body.position)
    assert (v.x, v.y) == tuple(body.velocity)


def test_writes_match_pymunk(body: pymunk.Body) -> None:
    h = fastbody.handle(body)
    fastbody.set_position(h, (1.0, 2.0))
    fastbody.set_velocity(h, (-4.0, 0.5))
    assert tuple(body.position) == (1.0, 2.0)
    assert tuple(body.velocity) == (-4.0, 0.5)


def test_forces_match_pymunk(body: pymunk.Body) -> None:
    h = fastbody.handle(body)
    fastbody.apply_force_at_local_point(h, (0.05, 0.0), (0.01, 0.0))
    f, t = tuple(body.force), body.torque
    body.force, body.torque = (0.0, 0.0), 0.0
    body.apply_force_at_local_point((0.05, 0.0), (0.01, 0.0))
    assert f == pytest.approx(tuple(body.force), abs=1e-15)
    assert math.isclose(t, body.torque, abs_tol=1e-15)


def test_pivot_impulse_is_the_joint_impulse_as_a_vector() -> None:
    """A weight swinging on a rod from a static pivot: the joint's impulse vector is the
    weight's momentum change less its weight's impulse, and its size is pymunk's
    ``impulse``; a chain joint ``PivotJoint(down, up)`` under tension pulls ``up``
    downstream."""
    assert fastbody.PIVOT_LAYOUT_OK
    space = pymunk.Space()
    space.gravity = (0.0, -9.81)
    ball = pymunk.Body(0.2, 1e-3)
    a, h = math.radians(40.0), 1e-3
    ball.position = (0.5 * math.sin(a), -0.5 * math.cos(a))
    ball.velocity = (1.0 * math.cos(a), 1.0 * math.sin(a))
    pin = pymunk.PivotJoint(space.static_body, ball, (0.0, 0.0),
                            tuple(ball.world_to_local((0.0, 0.0))))
    space.add(ball, pin)
    for _ in range(3):
        v0 = ball.velocity
        space.step(h)
        jx, jy = fastbody.pivot_impulse(pin)
        assert math.hypot(jx, jy) == pytest.approx(pin.impulse, rel=1e-12)
        dv = ball.velocity - v0
        assert jx == pytest.approx(0.2 * dv.x, rel=1e-9)
        assert jy == pytest.approx(0.2 * (dv.y + 9.81 * h), rel=1e-9)
    down, up = pymunk.Body(0.001, 1e-7), pymunk.Body(0.001, 1e-7)
    down.position, up.position = (0.0, 0.0), (-0.02, 0.0)
    joint = pymunk.PivotJoint(down, up, (-0.01, 0.0), (0.01, 0.0))
    space.gravity = (0.0, 0.0)
    space.add(down, up, joint)
    down.velocity = (1.0, 0.0)  # the front link runs away: the joint pulls the back one on
    space.step(h)
    jx, jy = fastbody.pivot_impulse(joint)
    assert jx > 0.0 and abs(jy) < 1e-9 * jx
    assert math.hypot(jx, jy) == pytest.approx(joint.impulse, rel=1e-12)


def test_a_joint_given_its_predecessors_impulse_starts_warm() -> None:
    """A chain hanging at rest (two solver iterations): a joint replaced by a new one
    given the old one's impulse (:func:`fastbody.set_pivot_impulse`) leaves the chain at
    rest, as the old joint does; a cold new joint lets it drop (about 1 cm/s in one
    step), which is what the treadmills' new joints must not do."""
    def replaced_joint_speed(mode: str) -> float:
        space = pymunk.Space()
        space.gravity, space.iterations = (0.0, -9.81), 2
        L, prev, anchor, bodies, joints = 0.02, space.static_body, (0.0, 0.0), [], []
        for i in range(10):
            b = pymunk.Body(0.001, 1e-7)
            b.position, b.angle = (0.0, -(i + 0.5) * L), -0.5 * math.pi
            j = pymunk.PivotJoint(prev, b, anchor, (-0.5 * L, 0.0))
            space.add(b, j)
            bodies.append(b)
            joints.append(j)
            prev, anchor = b, (0.5 * L, 0.0)
        for _ in range(2000):  # settle at rest (the velocities damped away)
            space.step(1e-3)
            for b in bodies:
                b.velocity, b.angular_velocity = 0.99 * b.velocity, 0.99 * b.angular_velocity
        old = joints[5]
        if mode != "old":
            new = pymunk.PivotJoint(old.a, old.b, old.anchor_a, old.anchor_b)
            if mode == "warm":
                fastbody.set_pivot_impulse(new, fastbody.pivot_impulse(old))
            space.remove(old)
            space.add(new)
        space.step(1e-3)
        return max(b.velocity.length for b in bodies)

    old, warm, cold = (replaced_joint_speed(m) for m in ("old", "warm", "cold"))
    assert old < 1e-6
    assert warm == pytest.approx(old, abs=1e-12)
    assert cold > 1e-3
