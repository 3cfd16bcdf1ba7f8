"""``chain.bend_limit``: a rotary limit on every joint, given once the joint is bent less
than 90 % of the limit (a pile's U-turns start free and are limited once straightened)."""

from __future__ import annotations

import math

import pymunk
import pytest

from chainfountain.sim.chain import Chain
from chainfountain.sim.config import ChainConfig, SolverConfig


def _chain(angles, limit):
    space = pymunk.Space()
    cfg = ChainConfig(link_length=0.02, bend_limit=limit)
    ch = Chain(space, cfg, SolverConfig(), shapes=False)
    for i, a in enumerate(angles):  # centres along x, each link turned by its angle
        ch.append(ch.make_body((-0.02 * i, 0.0), a))
    return space, ch


def test_straight_joints_get_their_limit():
    space, ch = _chain([0.0, 0.1, 0.2], limit=0.5)
    lims = [lk.up_limit for lk in ch.links[:-1]]
    assert all(isinstance(j, pymunk.RotaryLimitJoint) for j in lims)
    assert lims[0].min == pytest.approx(-0.5) and lims[0].max == pytest.approx(0.5)
    assert not ch.bend_pending


def test_a_sharp_bend_waits_until_it_straightens():
    space, ch = _chain([0.0, math.pi - 0.2, math.pi - 0.2], limit=0.5)
    assert ch.links[0].up_limit is None and ch.bend_pending == [ch.links[0]]
    assert ch.links[1].up_limit is not None
    assert ch.tighten_bends() == 1  # still bent
    ch.links[1].body.angle = 0.3
    ch.links[2].body.angle = 0.3
    assert ch.tighten_bends() == 0
    lim = ch.links[0].up_limit
    assert isinstance(lim, pymunk.RotaryLimitJoint) and lim in space.constraints


def test_no_limit_by_default():
    _, ch = _chain([0.0, 1.0], limit=0.0)
    assert ch.links[0].up_limit is None and not ch.bend_pending


def test_removing_a_link_removes_its_limit():
    space, ch = _chain([0.0, 0.1, 0.2], limit=0.5)
    ch.pop_front()
    assert sum(isinstance(c, pymunk.RotaryLimitJoint) for c in space.constraints) == 1
