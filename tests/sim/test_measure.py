"""Signed tension from momentum balance (chainfountain.sim.measure) against exact statics."""

from __future__ import annotations

import math

import numpy as np
import pymunk

from chainfountain.sim.bodies import Floor
from chainfountain.sim.chain import Chain
from chainfountain.sim.config import ChainConfig, SolverConfig
from chainfountain.sim.measure import ChainReader, joint_forces, link_ends, signed_tension

G = 9.81


def _hanging_chain(n: int, *, floor_y: float | None = None, tilt: float = 1e-3,
                   damping: float = 2e-4, solver: SolverConfig | None = None):
    """``n`` links hanging from a static pivot at the origin (chain order: bottom link first)."""
    space = pymunk.Space()
    space.gravity = (0.0, -G)
    solver = solver or SolverConfig()
    space.iterations = solver.iterations
    space.collision_slop = solver.collision_slop
    ccfg = ChainConfig(bending_damping=damping)
    chain = Chain(space, ccfg, solver, shapes=floor_y is not None)
    L = chain.L
    angle = -math.pi / 2 + tilt  # local +x points downstream = down the chain
    u = np.array([math.cos(angle), math.sin(angle)])
    links = [chain.make_body(tuple((k + 0.5) * L * u), angle) for k in range(n)]
    for link in reversed(links):  # bottom first
        chain.append(link)
    top = chain.links[-1]
    hook = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
    anchor = pymunk.PivotJoint(hook, top.body, (0.0, 0.0), (-0.5 * L, 0.0))
    anchor.error_bias = solver.joint_error_bias
    space.add(hook, anchor)
    if floor_y is not None:
        Floor.add(space, floor_y, -1.0, 1.0, friction=0.0)
    return space, chain, hook


def _pymunk_step() -> float:
    """The default solver's pymunk step (a time step ``dt`` is ``substeps`` of them)."""
    solver = SolverConfig()
    return solver.dt / solver.substeps


def _mean_tension(space, chain, dt: float, steps: int, settle: float):
    reader = ChainReader(space, chain)
    for _ in range(int(round(settle / dt))):
        space.step(dt)
    n = len(chain)
    acc = np.zeros(n)
    for _ in range(steps):
        pre = reader.read()
        space.step(dt)
        post = reader.read()
        contacts = reader.contact_impulses()
        f = joint_forces(pre, post, chain.mass, dt, G, n, contacts)
        t, _ = signed_tension(f, post, n)
        acc += t
    return acc / steps, reader.read()


def test_hanging_chain_tension_is_weight_below() -> None:
    """T(s) = lambda*g*(L - s) at every joint, within 1 % (physics.md section 3)."""
    n = 100
    dt = _pymunk_step()
    space, chain, _ = _hanging_chain(n)
    tension, _ = _mean_tension(space, chain, dt, steps=400, settle=2.0)
    expected = chain.mass * G * np.arange(1, n + 1)  # joint j carries links 0..j
    rel = np.abs(tension / expected - 1.0)
    assert rel.max() < 0.01, f"worst joint {rel.argmax()}: {rel.max():.4f}"


def test_contact_impulses_are_subtracted() -> None:
    """A chain hanging onto a frictionless floor: tension rises by lambda*g per metre.

    Checks the sign convention of the arbiter impulses read in batch: without
    subtracting them the 15 links resting on the floor would add their weight
    to every joint above.
    """
    n = 60
    dt = _pymunk_step()
    L = ChainConfig().link_length
    drop = 15 * L
    floor_y = -n * L - 0.005  # just below the hanging chain's lower end
    space, chain, hook = _hanging_chain(n, floor_y=floor_y, tilt=0.02, damping=5e-4)
    hook.velocity = (0.0, -0.1)  # lower the hook: the bottom 15 links pile on the floor
    for _ in range(int(round(drop / 0.1 / dt))):
        space.step(dt)
    hook.velocity = (0.0, 0.0)
    tension, state = _mean_tension(space, chain, dt, steps=400, settle=2.0)
    front, back = link_ends(state, chain.L)
    joint_y = 0.5 * (back[:-1, 1] + front[1:, 1])
    t = tension[:-1]
    weight = chain.mass * G  # of one link
    lying = joint_y < floor_y + 2 * ChainConfig().link_radius
    hanging = joint_y > floor_y + 5 * L
    assert lying.sum() >= 10 and hanging.sum() > 30
    # links resting on the frictionless floor carry (almost) no tension (the last
    # lying joint is in the touch-down bend and is left out)
    flat = np.flatnonzero(lying)[:-1]
    assert np.abs(t[flat]).max() < 0.05 * weight
    # the hanging part: slope lambda*g within 1 %
    slope, offset = np.polyfit(joint_y[hanging] - floor_y, t[hanging], 1)
    assert abs(slope / (chain.mass / chain.L * G) - 1.0) < 0.01
    # and no offset from the resting links' weight (15 link weights if contacts were
    # not subtracted); the touch-down bend may hold up to one link weight
    assert abs(offset) < weight
