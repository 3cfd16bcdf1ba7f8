"""Holding links in a joint guide (:class:`~chainfountain.sim.guide.GuideElement`): the
upper joint guide and the 'fold' guide hold each link with one frictionless joint per
element, out of the collision broadphase, and keep the links on their arcs."""

from __future__ import annotations

import math
from collections import deque

import pymunk

from chainfountain.sim import fastbody
from chainfountain.sim.chain import Link
from chainfountain.sim.guide import PLAY, GuideElement


def hold(space: pymunk.Space, element: GuideElement,
         queue: deque[tuple[Link, pymunk.Constraint]], link: Link, error_bias: float) -> None:
    """Hold ``link`` in ``element`` (its joint goes into ``queue``; the link's shape leaves
    the collision broadphase)."""
    j = element.joint(space, link.body, error_bias)
    if link.shape is not None and link.shape.space is not None:
        space.remove(link.shape)
    queue.append((link, j))


def keep_on_arcs(guide: list[GuideElement],
                 queues: list[deque[tuple[Link, pymunk.Constraint]]], close: float) -> None:
    """Joint guides: for each link held on an arc of ``guide``, close its slide joint's
    limits in toward ``R -+ PLAY`` by ``close`` (m per step: the apparatus's
    :meth:`~chainfountain.sim.apparatus.Tuning.close_rate` times the step; a
    link captured off the radius), then put it back onto the nearest limit if it has
    left them and take away its velocity across it.

    A frictionless wall does exactly this (it stops the motion into it); the
    slide joint alone corrects a position error only slowly (error bias), while
    the discrete step moves a link in a turn outward by ``(v dt)^2/(2 R)`` every
    step, so without the projection the turn's links sit 1-2 mm beyond the limit.
    Measured on the fold test: with the projection they stay on it to the step, and
    the turn does not drift outward as the lower plate strand grows. (A
    :mod:`pymunk.batch` version, one read and one write of all bodies per step with
    the projection in numpy, is slower: numpy's per-call cost on a few dozen links is
    more than this loop's; docs/apparatus.md.)"""
    get_p, set_p = fastbody.get_position, fastbody.set_position
    get_v, set_v = fastbody.get_velocity, fastbody.set_velocity
    for el, q in zip(guide, queues, strict=True):
        if el.form != "arc":
            continue
        cx, cy = el.a
        lo, hi = el.R - PLAY, el.R + PLAY
        for _, j in q:
            h = j.handle
            p = get_p(h)
            dx, dy = p.x - cx, p.y - cy
            d = math.hypot(dx, dy)
            j_min, j_max = j.lim
            if j_max > hi or j_min < lo:
                j_max = max(hi, min(j_max - close, d))
                j_min = min(lo, max(j_min + close, d))
                j.set_limits(j_min, j_max)
            if j_min <= d <= j_max or d == 0.0:
                continue
            nx, ny = dx / d, dy / d
            lim, side = (j_max, 1.0) if d > j_max else (j_min, -1.0)
            set_p(h, (cx + nx * lim, cy + ny * lim))
            v = get_v(h)
            vx, vy = v.x, v.y
            vr = vx * nx + vy * ny
            if vr * side > 0.0:
                set_v(h, (vx - vr * nx, vy - vr * ny))
