"""Guide geometry of the pulley apparatus (:mod:`chainfountain.sim.apparatus`).

Centre lines of the guide channels (polylines: straight leads and circular bends)
and the pieces of the frictionless joint guides: a link held on a circular arc by
a slide joint to the arc's centre (:class:`ArcJoint`) or on a straight line by a
groove joint (:class:`GuideElement`). Lengths in m, angles in rad, in the
apparatus frame (fountain start at the origin, ``y`` up).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pymunk

from chainfountain.sim import fastbody

PLAY = 0.001
"""Outward play (m) of the 'open' joint guide beyond its radius."""
GUIDE_BIAS = 0.0018
"""Joint error bias of the 'open' turn's slide joints (pymunk's default)."""


def _bend(x: float, y: float, phi0: float, phi1: float, R: float,
          step: float) -> tuple[np.ndarray, float, float]:
    """Centre-line points of a circular bend from heading ``phi0`` to ``phi1`` (rad)
    starting at ``(x, y)``; counter-clockwise when ``phi1 > phi0``. Returns points
    (without the start) and the end point."""
    s = 1.0 if phi1 > phi0 else -1.0
    # centre to the left (CCW) or right (CW) of the heading
    cx, cy = x - s * R * math.sin(phi0), y + s * R * math.cos(phi0)
    n = max(2, int(math.ceil(abs(phi1 - phi0) * R / step)))
    ph = phi0 + (phi1 - phi0) * np.arange(1, n + 1) / n
    px = cx + s * R * np.sin(ph)
    py = cy - s * R * np.cos(ph)
    return np.column_stack((px, py)), float(px[-1]), float(py[-1])


def _line(x: float, y: float, phi: float, length: float,
          step: float) -> tuple[np.ndarray, float, float]:
    n = max(1, int(math.ceil(length / step)))
    d = length * np.arange(1, n + 1) / n
    px, py = x + d * math.cos(phi), y + d * math.sin(phi)
    return np.column_stack((px, py)), float(px[-1]), float(py[-1])


@dataclass
class Channel:
    """Centre line of a guide channel (polyline, chain direction) and its walls."""

    points: np.ndarray
    shapes: list = field(default_factory=list)

    def walls(self, offset: float) -> tuple[np.ndarray, np.ndarray]:
        """Left and right wall polylines at ``offset`` from the centre line."""
        p = self.points
        # points closer than a nanometre (a vanishing rise, e.g. xi2 -> 0) have no
        # direction between them: keep the first of each run
        keep = np.ones(len(p), dtype=bool)
        keep[1:] = np.hypot(*np.diff(p, axis=0).T) > 1e-9
        p = p[keep]
        if len(p) < 2:
            return p.copy(), p.copy()
        t = np.gradient(p, axis=0)
        t /= np.linalg.norm(t, axis=1)[:, None]
        nrm = np.column_stack((-t[:, 1], t[:, 0]))
        return p + offset * nrm, p - offset * nrm


def _upper_bend(H: float, xi2: float, alpha0: float,
                R: float) -> tuple[float, float, float, float]:
    """The upper channel's rise, bend radius actually used (at most ``R``), straight
    length and horizontal run from the bend's start to the fountain start (m)."""
    rise = xi2 * H
    R = min(R, rise / (1.0 - math.cos(alpha0))) if rise > 0 else 0.0
    S = (rise - R * (1.0 - math.cos(alpha0))) / math.sin(alpha0)
    return rise, R, S, R * math.sin(alpha0) + S * math.cos(alpha0)


def upper_channel(H: float, xi2: float, alpha0: float, R: float, lead: float,
                  step: float) -> tuple[np.ndarray, float]:
    """Centre line from the plate end to the start (0, 0): horizontal lead, bend up to
    ``alpha0``, straight. Returns the points and the bend radius actually used."""
    rise, R, S, run = _upper_bend(H, xi2, alpha0, R)
    x0 = -run - lead
    pts = [np.array([[x0, -rise]])]
    p, x, y = _line(x0, -rise, 0.0, lead, step)
    pts.append(p)
    if R > 0:
        p, x, y = _bend(x, y, 0.0, alpha0, R, step)
        pts.append(p)
    if S > 1e-9:
        p, x, y = _line(x, y, alpha0, S, step)
        pts.append(p)
    out = np.vstack(pts)
    out[-1] = (0.0, 0.0)
    return out, R


def upper_guide(H: float, xi2: float, alpha0: float, R: float,
                lead: float) -> list[GuideElement]:
    """The pieces of the upper channel's centre line (:func:`upper_channel` with the
    same arguments) as joint-guide elements, chain direction: the horizontal lead, the
    bend up to ``alpha0`` (centre above the lead) and the straight to the fountain
    start ``(0, 0)``."""
    rise, R, S, run = _upper_bend(H, xi2, alpha0, R)
    xb = -run
    out = [GuideElement("line", (xb - lead, -rise), (xb, -rise))]
    if R > 0:
        c = (xb, -rise + R)
        out.append(GuideElement("arc", c, c, R, -0.5 * math.pi, alpha0 - 0.5 * math.pi))
    if S > 1e-9:
        p = (xb + R * math.sin(alpha0), -rise + R * (1.0 - math.cos(alpha0)))
        out.append(GuideElement("line", p, (0.0, 0.0)))
    return out


def end_channel_bends(alphaE: float, rise: float, R: float,
                      up: float = math.radians(60.0)) -> tuple[float, float]:
    """Bend radius and straight length of a rising end channel (:func:`end_channel`):
    bend from the landing heading ``-alphaE`` up to ``up``, straight ``S``, bend back to
    horizontal, total rise ``rise``; the radius shrinks (by 0.8) until ``S >= 0``."""
    phi = -alphaE

    def straight(R: float) -> float:
        # the first bend (counter-clockwise, heading phi -> up) changes the height by
        # R (cos(phi) - cos(up)) (it dips for a steep landing), the second (clockwise,
        # up -> 0) by R (1 - cos(up)); the straight makes up the rest of the rise
        return (rise - R * (math.cos(phi) - math.cos(up)) - R * (1 - math.cos(up))) / \
            math.sin(up)

    S = straight(R)
    while S < 0 and R > 0.02:
        R *= 0.8
        S = straight(R)
    if S < 0:
        raise ValueError(f"end channel cannot rise only {rise:.3g} m")
    return R, S


def end_channel_min_rise(alphaE: float, R: float, up: float = math.radians(60.0)) -> float:
    """The least rise above zero a rising end channel can make: its two bends at the
    smallest radius :func:`end_channel_bends` shrinks ``R`` to (a factor 0.8 at a time,
    down to 0.02 m), with no straight between them."""
    while R > 0.02:
        R *= 0.8
    return R * (math.cos(alphaE) - math.cos(up)) + R * (1.0 - math.cos(up))


def end_channel(xE: float, yE: float, alphaE: float, rise: float, R: float, lead: float,
                step: float, *, up: float = math.radians(60.0),
                mouth: float = 0.06) -> tuple[np.ndarray, int]:
    """Centre line from a mouth on the landing tangent through the fountain end
    ``(xE, yE)`` (heading ``-alphaE``), bending up and lifting the chain by ``rise``
    to a horizontal exit. Returns the points and the index of the fountain end."""
    phi = -alphaE
    x0, y0 = xE - mouth * math.cos(phi), yE - mouth * math.sin(phi)
    pts = [np.array([[x0, y0]])]
    p, x, y = _line(x0, y0, phi, mouth, step)
    pts.append(p)
    i_end = sum(len(a) for a in pts) - 1
    if rise <= 1e-9:
        p, x, y = _bend(x, y, phi, 0.0, R, step)
        pts.append(p)
    else:
        R, S = end_channel_bends(alphaE, rise, R, up)
        p, x, y = _bend(x, y, phi, up, R, step)
        pts.append(p)
        if S > 1e-9:
            p, x, y = _line(x, y, up, S, step)
            pts.append(p)
        p, x, y = _bend(x, y, up, 0.0, R, step)
        pts.append(p)
    p, x, y = _line(x, y, 0.0, lead, step)
    pts.append(p)
    return np.vstack(pts), i_end


def resample(path: np.ndarray, L: float) -> tuple[np.ndarray, np.ndarray]:
    """Points at arc-length spacing ``L`` along a polyline and their arc lengths."""
    seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
    keep = np.concatenate([[True], seg > 1e-12])
    path = path[keep]
    seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    n = int(s[-1] // L)
    q = np.arange(n + 1) * L
    return np.column_stack((np.interp(q, s, path[:, 0]), np.interp(q, s, path[:, 1]))), q


class ArcJoint(pymunk.SlideJoint):
    """A slide joint that mirrors its limits in Python (:attr:`lim`): the fold guide
    reads them for every held link every step, and each read of ``min``/``max`` is a
    call into chipmunk."""

    def __init__(self, a: pymunk.Body, b: pymunk.Body, anchor_a: tuple[float, float],
                 anchor_b: tuple[float, float], lo: float, hi: float) -> None:
        super().__init__(a, b, anchor_a, anchor_b, lo, hi)
        self.lim = (lo, hi)
        self.handle = fastbody.handle(b)
        """The held body's chipmunk handle (:mod:`chainfountain.sim.fastbody`)."""

    def set_limits(self, lo: float, hi: float) -> None:
        self.min, self.max = lo, hi
        self.lim = (lo, hi)


@dataclass
class GuideElement:
    """One piece of a frictionless joint guide (the 'fold' lower channel; the upper
    channel with ``upper_guide = "joints"``): a circular arc
    (links held by a :class:`pymunk.SlideJoint` to its centre) or a straight line (a
    :class:`pymunk.GrooveJoint`). The chain moves along it from ``start`` to ``end``."""

    form: str
    """'arc' or 'line'."""
    a: tuple[float, float]
    """Arc: centre; line: start point."""
    b: tuple[float, float]
    """Line: end point (unused for an arc)."""
    R: float = 0.0
    """Arc radius (m)."""
    th0: float = 0.0
    th1: float = 0.0
    """Arc: polar angle (rad, about the centre) of the start and end points."""
    carrier: pymunk.Body | None = field(default=None, repr=False)
    """A kinematic body the element rides on (a following end guide,
    :mod:`chainfountain.sim.apparatus.follow`): its joints are anchored on it and move
    with it inside pymunk's step. ``a`` and ``b`` are the element's world coordinates,
    kept by the owner; ``None``: fixed, its joints on the space's static body."""

    @property
    def ccw(self) -> bool:
        return self.th1 > self.th0

    def passed(self, x: float, y: float, before: float = 0.0) -> bool:
        """Has a link centre at ``(x, y)`` gone past the element's end (a line's: past
        ``before`` m short of it)?"""
        if self.form == "arc":
            th = math.atan2(y - self.a[1], x - self.a[0])
            return th > self.th1 if self.ccw else th < self.th1
        (ax, ay), (bx, by) = self.a, self.b
        tx, ty = bx - ax, by - ay
        if not before:
            return (x - ax) * tx + (y - ay) * ty > tx * tx + ty * ty
        ln = math.hypot(tx, ty)
        return (x - ax) * tx + (y - ay) * ty > ln * (ln - before)

    def on(self, P: np.ndarray, tol: float) -> np.ndarray:
        """Which of the points ``P`` (n, 2) lie on the element within ``tol`` (m)."""
        if self.form == "arc":
            d = np.hypot(P[:, 0] - self.a[0], P[:, 1] - self.a[1])
            th = np.arctan2(P[:, 1] - self.a[1], P[:, 0] - self.a[0])
            lo, hi = min(self.th0, self.th1), max(self.th0, self.th1)
            return (np.abs(d - self.R) < tol) & (th >= lo - 0.05) & (th <= hi + 0.05)
        (ax, ay), (bx, by) = self.a, self.b
        t = np.array([bx - ax, by - ay])
        ln = float(np.hypot(*t))
        t /= ln
        rel = P - np.array([ax, ay])
        s = rel @ t
        d = np.abs(rel @ np.array([-t[1], t[0]]))
        return (d < tol) & (s >= -0.01) & (s <= ln + 0.01)

    def groove_ends(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """A line's groove: from 5 cm before its start to 5 cm past its end."""
        (ax, ay), (bx, by) = self.a, self.b
        ln = math.hypot(bx - ax, by - ay)
        tx, ty = (bx - ax) / ln, (by - ay) / ln
        return (ax - 0.05 * tx, ay - 0.05 * ty), (bx + 0.05 * tx, by + 0.05 * ty)

    def joint(self, space: pymunk.Space, body: pymunk.Body, error_bias: float) -> \
            pymunk.Constraint:
        """A frictionless constraint holding the link centre on the element; an arc's
        limits start where the link is (no position kick) and close in later."""
        base, ox, oy = space.static_body, 0.0, 0.0
        if self.carrier is not None:
            base = self.carrier
            o = fastbody.pos(base)
            ox, oy = o.x, o.y
        if self.form == "arc":
            p = fastbody.pos(body)
            d = math.hypot(p.x - self.a[0], p.y - self.a[1])
            j: pymunk.Constraint = ArcJoint(
                base, body, (self.a[0] - ox, self.a[1] - oy), (0.0, 0.0),
                min(self.R - PLAY, d), max(self.R + PLAY, d))
            j.error_bias = GUIDE_BIAS
        else:
            (ax, ay), (bx, by) = self.groove_ends()
            j = pymunk.GrooveJoint(base, body, (ax - ox, ay - oy), (bx - ox, by - oy),
                                   (0.0, 0.0))
            j.error_bias = error_bias
        space.add(j)
        return j
