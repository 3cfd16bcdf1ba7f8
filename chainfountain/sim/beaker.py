"""The beaker: a chain piled in a pot rises over the rim and falls to the floor (the Mould
effect), forming its fountain on its own from rest.

Frame: the exit rim's top is the origin, ``y`` up; the pot lies at ``x < 0`` and the chain
falls at ``x > 0`` onto an absorbing floor ``drop`` below the rim, which takes each link
whose centre reaches it (the chain's end is free there: Biggins and Warner's ``beta = 0``).

The pile is a zig-zag of horizontal rows of links (:func:`next_row`) lying on a plate
inside the pot; the links collide with each other, the pot and the plate, and every joint
can bend at most ``chain.bend_limit`` (a ball chain's largest bend: without it the chain
barely clears the rim, ``docs/beaker.md``). Only ``pile_rows`` rows are simulated:
the plate rises as the chain is drawn off, so the top of the pile, where the chain is
picked up, stays ``pile_depth`` below the rim, and whenever it has risen by one row's
spacing a new row is laid under the pile (out of the solver until then: "the pile refilled
out of sight"). The plate's rise, a few per cent of the chain speed, is the only motion of
the pile that a real, emptying pot would not have; it runs as long as anyone watches.
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np
import pymunk

from chainfountain.errors import RunEnded
from chainfountain.sim.bodies import SCENERY_CATEGORY
from chainfountain.sim.chain import Chain
from chainfountain.sim.config import BeakerConfig
from chainfountain.sim.measure import ChainReader
from chainfountain.sim.scene_layout import along_polyline

WALL_RADIUS = 0.003
"""Radius (m) of the pot's walls, floor and plate (static and kinematic segments)."""
ROW_GAP = 5e-4
"""Extra gap (m) between rows at the start (the links settle onto each other)."""
PLATE_TAU = 0.1
"""Time constant (s) with which the plate makes up a shortfall of links in the pile."""
PLATE_MAX_SPEED = 1.0
"""The plate's largest rise speed (m/s)."""
PICKUP_TAU = 0.2
"""Time constant (s) of the pick-up point's average (:attr:`Beaker.pickup`)."""
SPEED_SPAN = 0.5
"""The chain speed (:attr:`Beaker.speed`) is the floor's take over the last this many s."""
LOG_INTERVAL = 0.05
"""Time (s) between two rows of :attr:`Beaker.log` (doubled whenever it is thinned)."""
MAX_LOG = 20_000
"""Most rows :attr:`Beaker.log` keeps (every other is dropped when it is full)."""
CHECK_EVERY = 16
"""The pile is counted and the plate set every this many steps."""
TIGHTEN_EVERY = 40
"""Waiting bend limits are tried every this many steps (:meth:`Chain.tighten_bends`)."""
HASH_CELL = 2.5
"""Cell size of the space's spatial hash, in links: the beaker (at two sub-steps a step)
stepped in 308 us per step in it against 492 us in pymunk's default tree
(``benchmarks/bench_beaker.py`` times the level)."""


class PotEmpty(RunEnded):
    """The pile is used up (``beaker.refill = false``): the chain's tail has left the pot."""


def row_geometry(cfg: BeakerConfig, L: float, r: float) -> tuple[int, float, float]:
    """Links per row ``m``, row spacing ``s`` and the horizontal reach ``du`` of the
    slanted link joining two rows, for a pot ``cfg.pot_width`` wide."""
    s = 2.0 * r + ROW_GAP
    du = math.sqrt(max(L * L - s * s, 0.0))
    m = int((cfg.pot_width - 2.0 * r - du - 0.002) / L)
    return m, s, du


def next_row(start: np.ndarray, direction: float, m: int, s: float, du: float,
             L: float) -> tuple[np.ndarray, float]:
    """The points of the row below a row that ends (going upstream) at ``start`` heading
    ``direction`` (+1: +x): a slanted link ``du`` on and ``s`` down, then ``m`` links back
    the other way. Returns the ``m + 1`` new points and the new row's direction."""
    x0, y0 = float(start[0]), float(start[1])
    pts = [(x0 + direction * du, y0 - s)]
    d = -direction
    for k in range(1, m + 1):
        pts.append((x0 + direction * du + d * k * L, y0 - s))
    return np.array(pts), d


class Beaker:
    """The pot, the plate, the pile and the absorbing floor around a :class:`Chain`.

    Offers the feed interface :class:`~chainfountain.sim.world.Simulation` steps and reads
    (``speed``, ``n_free``, ``n_guide``, ``floor_y``, ``absorbed``, ``u``,
    ``before_step``, ``after_step``)."""

    def __init__(self, space: pymunk.Space, chain: Chain, cfg: BeakerConfig,
                 friction: float) -> None:
        self.space = space
        self.chain = chain
        self.cfg = cfg
        self.reader = ChainReader(space, chain)
        L, r = chain.L, float(chain.cfg.link_radius)
        space.use_spatial_hash(HASH_CELL * L, 1000)
        self.L, self.r = L, r
        self.m, self.s, self.du = row_geometry(cfg, L, r)
        if self.m < 3:
            raise ValueError(f"beaker.pot_width {cfg.pot_width} m holds fewer than 3 links "
                             f"of {L} m in a row")
        wr = WALL_RADIUS
        self.x_in = (-2.0 * wr - cfg.pot_width, -2.0 * wr)
        """Inner faces of the pot's walls (m)."""
        self.floor_y = -float(cfg.drop)
        self.y_top = -float(cfg.pile_depth)
        """Height of the pile's top row's centre line when the pile is full (m)."""
        self.absorbed = 0
        self.added_rows = 0
        self.n_guide = 0
        self.u = (0.0, 1.0)
        self.end_force: tuple[float, float] | None = None
        """The floor pulls on nothing (an absorbing floor: ``beta = 0``)."""
        self.plate_speed = 0.0
        self._steps = 0
        self._speed = 0.0
        self.time = 0.0
        self._takes: deque[tuple[float, int]] = deque()
        self.log: list[tuple[float, int, float, float]] = []
        """Rows ``(t, links taken by the floor so far, pick-up x, pick-up y)``, one per
        :data:`LOG_INTERVAL` (thinned to at most :data:`MAX_LOG`; see :meth:`window`)."""
        self._log_every = LOG_INTERVAL
        self._next_log = 0.0
        self._n_rest = 0
        self._pickup: tuple[float, float] | None = None
        filt = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
        sb = space.static_body
        xl, xr = self.x_in[0] - wr, self.x_in[1] + wr
        bottom = -float(cfg.pot_depth)
        self.walls = [pymunk.Segment(sb, (xl, bottom), (xl, -wr), wr),
                      pymunk.Segment(sb, (xr, bottom), (xr, -wr), wr),
                      pymunk.Segment(sb, (xl, bottom - wr), (xr, bottom - wr), wr)]
        for w in self.walls:
            w.friction = friction
            w.filter = filt
        space.add(*self.walls)
        self.plate = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        plate_top = self.y_top - (cfg.pile_rows - 1) * self.s - r - ROW_GAP
        self.plate_base = plate_top - wr
        self.plate.position = (0.0, self.plate_base)
        self.plate_shape = pymunk.Segment(self.plate, (self.x_in[0] + wr, 0.0),
                                          (self.x_in[1] - wr, 0.0), wr)
        self.plate_shape.friction = friction
        self.plate_shape.filter = filt
        space.add(self.plate, self.plate_shape)
        if self.plate_base - wr < bottom:
            raise ValueError(f"beaker.pot_depth {cfg.pot_depth} m is too shallow for "
                             f"{cfg.pile_rows} rows {cfg.pile_depth} m below the rim")
        self._lay()
        self.pile_target, self._n_rest = self._count()
        """Links the pile keeps (its count at the start)."""

    # ------------------------------------------------------------------ layout
    def _lay(self) -> None:
        """Lay the chain at rest: the free end ``hang`` below the rim outside the pot, up
        the outer wall, over the rim, down into the pot and along the pile's rows."""
        cfg, L, r = self.cfg, self.L, self.r
        x_hi = self.x_in[1] - r - 0.001
        top_row = [(x_hi - k * L, self.y_top) for k in range(self.m + 1)]
        pts = [np.array(top_row)]
        end, d = np.array(top_row[-1]), -1.0
        for _ in range(cfg.pile_rows - 1):
            row, d = next_row(end, d, self.m, self.s, self.du, L)
            pts.append(row)
            end = row[-1]
        self._tail_dir = d
        pile = np.vstack(pts)  # downstream (top row, at the exit wall) to upstream
        x_out = WALL_RADIUS + r + 0.001  # the falling strand's centre line, outside
        lift = r + 0.0015  # over the rim
        back = np.array([pile[0], (self.x_in[1] - 0.01, lift), (0.0, lift), (x_out, -0.02),
                         (x_out, -cfg.hang)])
        over = along_polyline(back, L)[::-1]  # from the hanging end to the pile's top row
        pts_all = np.vstack((over[:-1], pile))
        for a, b in zip(pts_all[:-1], pts_all[1:], strict=True):
            self._append(a, b, (0.0, 0.0))
        self.chain.tighten_bends()

    def _append(self, a, b, velocity) -> None:
        """Add a link from ``a`` (downstream) to ``b`` (upstream) at the chain's tail."""
        ax, ay = a
        bx, by = b
        link = self.chain.make_body((0.5 * (ax + bx), 0.5 * (ay + by)),
                                    math.atan2(ay - by, ax - bx), velocity=velocity)
        self.chain.append(link)

    def _add_row(self) -> None:
        """Lay one row under the pile at the plate's top and drop the plate by a row."""
        tail = self.chain.links[-1]
        end = np.array(tuple(self.chain.ends(tail)[1]))
        row, d = next_row(end, self._tail_dir, self.m, self.s, self.du, self.L)
        self._tail_dir = d
        v = (0.0, self.plate_speed)
        prev = end
        for p in row:
            self._append(prev, p, v)
            prev = p
        x, y = self.plate.position
        self.plate.position = (x, y - self.s)
        self.added_rows += 1

    # ------------------------------------------------------------------ feed interface
    @property
    def speed(self) -> float:
        """The chain speed (m/s): links taken by the floor per second times ``L``, over the
        last :data:`SPEED_SPAN`."""
        return self._speed

    @property
    def n_free(self) -> int:
        """Links moving: all but those at rest in the pile (the chain's tail)."""
        return len(self.chain.links) - self._n_rest

    def set_speed(self, v: float) -> None:
        """The beaker has no motor: its speed is the chain's own."""

    def set_reference(self, ref) -> None:
        """The beaker has no guide to aim: nothing to do."""

    def before_step(self) -> None:
        """Nothing: the plate moves by its velocity."""

    def after_step(self, dt: float) -> None:
        """Take links at the floor, count the flux; every :data:`CHECK_EVERY` steps set the
        plate's rise, lay a row under the pile when it has risen one, tighten bends."""
        self._steps += 1
        self.time = self._steps * dt
        self._absorb()
        if self._steps % CHECK_EVERY:
            return
        takes = self._takes
        takes.append((self.time, self.absorbed))
        while takes[0][0] < self.time - SPEED_SPAN:
            takes.popleft()
        t0, n0 = takes[0]
        if self.time > t0:
            self._speed = (self.absorbed - n0) * self.L / (self.time - t0)
        n_pot, n_rest = self._count()
        if n_pot == 0 and not self.cfg.refill:
            raise PotEmpty(f"the pot is empty at t = {self.time:.2f} s: the whole chain has "
                           "left it; set beaker.refill = true to keep the pile topped up")
        self._track_pickup(n_rest, CHECK_EVERY * dt)
        if self.cfg.refill:
            short = self.pile_target - n_pot
            feed_rate = self._speed / (self.L * (self.m + 1))  # rows drawn off per second
            u = feed_rate * self.s + max(short, 0) * self.s / ((self.m + 1) * PLATE_TAU)
            self.plate_speed = min(u, PLATE_MAX_SPEED)
            self.plate.velocity = (0.0, self.plate_speed)
            if self.plate.position.y - self.plate_base >= self.s:
                self._add_row()
        if self._steps % TIGHTEN_EVERY == 0:
            self.chain.tighten_bends()
        if self.time >= self._next_log:
            self._record()

    def _record(self) -> None:
        px, py = self.pickup
        self.log.append((self.time, self.absorbed, px, py))
        self._next_log += self._log_every
        if len(self.log) > MAX_LOG:
            del self.log[1::2]
            self._log_every *= 2.0

    def window(self, t0: float, t1: float) -> dict[str, float]:
        """Means over ``t0 .. t1`` (s) from :attr:`log`: the chain speed from the links the
        floor took (``v``, m/s, to one link in the window), the pick-up point (m) and the
        rows of the log used."""
        rows = [r for r in self.log if t0 - 1e-9 <= r[0] <= t1 + 1e-9]
        if len(rows) < 2 or rows[-1][0] <= rows[0][0]:
            return {"v": math.nan, "pickup_x": math.nan, "pickup_y": math.nan, "rows": 0}
        a, b = rows[0], rows[-1]
        return {"v": (b[1] - a[1]) * self.L / (b[0] - a[0]),
                "pickup_x": float(np.mean([r[2] for r in rows])),
                "pickup_y": float(np.mean([r[3] for r in rows])), "rows": len(rows)}

    def _absorb(self) -> None:
        links = self.chain.links
        fy = self.floor_y
        while len(links) > 2 and links[0].body.position.y < fy:
            self.chain.pop_front()
            self.absorbed += 1

    # ------------------------------------------------------------------ reading
    def _count(self) -> tuple[int, int]:
        """Links in the pot below the rim, and links at rest in the pile (slower than a
        tenth of the chain speed or 0.1 m/s, relative to the plate), each counted from the
        chain's tail as far as they go on without a break."""
        st = self.reader.read()
        x, y = st.position[:, 0], st.position[:, 1]
        x0, x1 = self.x_in
        in_pot = (x > x0) & (x < x1) & (y < -self.r)
        vx, vy = st.velocity[:, 0], st.velocity[:, 1] - self.plate_speed
        slow = in_pot & (vx * vx + vy * vy < max(0.1, 0.1 * self._speed) ** 2)
        return _trailing(in_pot), _trailing(slow)

    def _track_pickup(self, n_rest: int, dt: float) -> None:
        """Where the moving chain leaves the resting pile: the front end of the first
        resting link (followed with a time constant of :data:`PICKUP_TAU`)."""
        links = self.chain.links
        self._n_rest = min(n_rest, len(links) - 2)
        if self._n_rest <= 0:
            return
        first = links[len(links) - self._n_rest]
        px, py = first.body.local_to_world((0.5 * self.L, 0.0))
        if self._pickup is None:
            self._pickup = (px, py)
            return
        a = min(1.0, dt / PICKUP_TAU)
        ox, oy = self._pickup
        self._pickup = (ox + a * (px - ox), oy + a * (py - oy))

    @property
    def pickup(self) -> tuple[float, float]:
        """Where the chain leaves the pile (m), averaged over :data:`PICKUP_TAU`: the
        paper's launch point and Biggins and Warner's pick-up."""
        if self._pickup is None:
            return (self.x_in[1] - self.r, self.y_top)
        return self._pickup

    def pot_outline(self) -> np.ndarray:
        """The inner faces of the pot (m): left rim, bottom corners, right rim."""
        (x0, x1), y0 = self.x_in, -float(self.cfg.pot_depth)
        return np.array([(x0, 0.0), (x0, y0), (x1, y0), (x1, 0.0)])

    def plate_segment(self) -> np.ndarray:
        """The plate under the pile (its top face), ``(2, 2)`` m."""
        y = float(self.plate.position.y) + WALL_RADIUS
        return np.array([(self.x_in[0], y), (self.x_in[1], y)])


def _trailing(mask: np.ndarray) -> int:
    """How many of ``mask``'s last entries are True without a break."""
    off = np.flatnonzero(~mask)
    return len(mask) if len(off) == 0 else len(mask) - 1 - int(off[-1])
