"""The apparatus as one object: :class:`Apparatus` builds its parts (in the order the
solver sees them), steps them and answers for them; each part is an object of its own
module, given what it reads.

Build steps, upstream to downstream (:meth:`Apparatus.__init__`): the layout
(:mod:`.layout`: the predicted fountain and the upper heights), the upper part
(:mod:`.upper`), the end by variant (:mod:`.ends`; the open tail's plate,
:mod:`.open_tail`; the folding roller and lower guide, :mod:`.fold`), the chain laid
along the path, the bookkeeping parts (:mod:`.upper_guide`, :mod:`.grooves`,
:mod:`.grip`, :mod:`.follow`, :mod:`.treadmill`, :mod:`.fold_watch`,
:mod:`.stall_watch`, :mod:`.starter`), then the links taken into their grooves and
joint guides. Each step adds its bodies, shapes and joints to the space in the order
the single constructor did (the solver's results depend on it).
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
import pymunk

from chainfountain.errors import RunEnded
from chainfountain.sim.apparatus.ends import EndPart
from chainfountain.sim.apparatus.fold import FoldPart
from chainfountain.sim.apparatus.fold_watch import FoldWatch
from chainfountain.sim.apparatus.follow import FollowingEnd
from chainfountain.sim.apparatus.grip import GrippedFold
from chainfountain.sim.apparatus.grooves import PlateGrooves
from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.open_tail import OpenTail
from chainfountain.sim.apparatus.parts import DRIVE_REACH, Clock, RollerUnit
from chainfountain.sim.apparatus.stall_watch import StallWatch
from chainfountain.sim.apparatus.starter import Starter
from chainfountain.sim.apparatus.treadmill import Treadmills
from chainfountain.sim.apparatus.tuning import Tuning
from chainfountain.sim.apparatus.upper import UpperPart
from chainfountain.sim.apparatus.upper_guide import UpperJointGuide
from chainfountain.sim.chain import Chain, Link
from chainfountain.sim.config import ApparatusConfig, SimConfig
from chainfountain.sim.fastbody import pos
from chainfountain.sim.guide import GuideElement, resample

if TYPE_CHECKING:
    pass

HEAD_BACK = 0.1
"""'fold' from rest: how far (m) inside the upper guide the chain's head waits, so that
the starter has it at its launch speed before it leaves (a head that leaves slowly
droops and falls short)."""

FountainPath = Callable[[Layout, np.ndarray], np.ndarray]
"""A study's chain path through the fountain: given the layout and the path the model
lays (:meth:`Apparatus._fountain_path`), the points to lay instead (``research/
hanging_start.py``)."""


class TableUsedUp(RunEnded):
    """The pick-up roller has reached the upper channel: the run has outgrown the
    upper table (raised by :meth:`Apparatus.after_step`; the app pauses on it, the
    CLI writes what was simulated and says so)."""


class _Part:
    """An attribute of one of the apparatus's parts read through the apparatus, read only
    (``app.y_up`` is ``app.layout.y_up``): the names the rest of the code reads."""

    def __init__(self, part: str) -> None:
        self.part = part

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    def __get__(self, obj: Any, owner: type | None = None) -> Any:
        if obj is None:
            return self
        return getattr(getattr(obj, self.part), self.name)

    def __set__(self, obj: Any, value: Any) -> None:
        raise AttributeError(f"{self.name} is {self.part}.{self.name}'s, read only")


class Apparatus:
    """Builds the apparatus into a space and keeps its bookkeeping (duck-types the
    :class:`~chainfountain.sim.feed.Feed` interface the simulation uses).

    Attributes give the geometry for views and measurements: ``upper``/``lower``
    (:class:`~chainfountain.sim.apparatus.parts.RollerUnit`), ``y_up``/``y_lo``
    (roller-top centre lines), ``end`` (fountain end point), ``launch_u`` (unit launch
    direction), ``walls`` (static segments), ``fountain`` (the predicted fountain used
    for the layout); they are read from the parts (:attr:`layout`, :attr:`upper_part`,
    :attr:`end_part`, :attr:`fold`, :attr:`tail`, ...), which hold the state.

    ``tuning`` is what a study may vary (:class:`~.tuning.Tuning`; the shipped model's by
    default), ``starter`` the class of the starter motor (a study's own start subclasses
    :class:`~.starter.Starter`) and ``fountain_path`` a study's path to lay the chain
    along through the fountain (:data:`FountainPath`).
    """

    def __init__(self, space: pymunk.Space, chain: Chain, cfg: SimConfig,
                 tuning: Tuning | None = None, starter: type[Starter] = Starter,
                 fountain_path: FountainPath | None = None) -> None:
        """Build the apparatus into ``space`` and lay ``chain`` along it, part by part in
        the order the solver sees them (module docstring)."""
        self.space = space
        self.chain = chain
        self.sim_cfg = cfg
        self.cfg: ApparatusConfig = cfg.apparatus
        self.tuning = tuning if tuning is not None else Tuning()
        lay = self.layout = Layout.of(chain.L, cfg, self.tuning)
        following = lay.end_follow > 0.0
        close_rate = self.tuning.close_rate(following)
        self.clock = Clock()
        self.absorbed = 0
        """Links taken out at the downstream end (the floor, the lower table)."""
        self.added = 0
        """Links laid and added at the upstream end (and by the upper treadmill)."""
        # the parts built into the space, upstream to downstream
        self.upper_part = UpperPart(space, lay)
        path = self.upper_part.path()
        laid = self._fountain_path()
        path.append(laid if fountain_path is None else fountain_path(lay, laid))
        self.end_part = EndPart(space, lay)
        self.tail: OpenTail | None = (OpenTail(space, chain, lay, self.end_part)
                                      if lay.variant == "open" else None)
        """'open': the tail on the long lower plate."""
        self.fold: FoldPart | None = (
            FoldPart(space, chain, lay, self.end_part, self.clock,
                     self.tuning.capture(following), close_rate)
            if lay.variant == "fold" else None)
        """'fold': the folding roller, the lower plate and the lower joint guide."""
        self.walls: list[pymunk.Segment] = self.upper_part.walls + self.end_part.walls
        """The channels' walls (static segments; drawn only where a joint guide holds the
        chain)."""
        if not lay.threads:  # else the starter threads the head through later
            path += self._path_beyond()
        self._lay_along(path)
        # the bookkeeping parts
        self.upper_guide = UpperJointGuide(space, chain, lay, self.upper_part, close_rate)
        self.grooves = PlateGrooves(space, chain, lay, self.upper_part,
                                    self.upper_guide if lay.upper_guided else None)
        self.grip: GrippedFold | None = (GrippedFold(space, chain, lay, self.fold)
                                         if lay.gripped and self.fold is not None else None)
        """The gripped folding roller's welds ('fold' with ``fold_roller = "gripped"``)."""
        self.follow = FollowingEnd(space, lay, self.end_part, self.fold)
        self.treadmills = Treadmills(space, chain, lay, self.upper, self.grooves, self.fold,
                                     self.grip)
        self.fold_watch: FoldWatch | None = (
            FoldWatch(lay, self.upper, self.fold, self.clock) if self.fold is not None
            else None)
        self.stall_watch = StallWatch(self.cfg, self.upper, self.lower, self.clock)
        self.starter: Starter = starter(lay, self.clock, self.upper, self.upper_guide,
                                        self.end_part, self.fold, self.follow)
        self._plate_ends = [float(self.plate_up.a.x), float(self.plate_lo.b.x)
                            if self.plate_lo is not None else 0.0]
        """x of the upper plate's start and the lower plate's end (m)."""
        self._plates_collide = self.plate_up.space is not None or (
            self.plate_lo is not None and self.plate_lo.space is not None)
        """Whether a plate is a collision shape (``plate = "contact"``): its ends then
        follow the rollers every step; with grooves the plates are only drawn, and their
        ends follow when read (:meth:`sync_plates`)."""
        self.swing_spring: pymunk.DampedSpring | None = self._add_swing_damper()
        self.sync_plates()
        if self.grip is not None and not lay.threads:
            self.absorbed += self.grip.take_in()
        self._take_in_held_links()

    # ------------------------------------------------------------------ build steps
    def _fountain_path(self) -> np.ndarray:
        """The chain's path through the predicted fountain (to ``x_floor``, the end's x
        without a ``floor_depth``); from rest, a straight stub along the launch line, and
        in 'fold' none (the starter threads the head through, :mod:`.starter`)."""
        if self.layout.threads:
            return np.empty((0, 2))  # the head waits inside the upper guide (_lay_along)
        if self.layout.from_rest:
            s = np.linspace(0.0, self.layout.stub_length, 8)[1:]
            return np.column_stack((s * self.launch_u[0], s * self.launch_u[1]))
        f = self.fountain
        x_rise = self.vertex_pred[0]
        xs = np.linspace(0.0, self.layout.x_floor, 400)[1:]  # x_floor = ex without a floor_depth
        return np.column_stack((xs, f.h + f.y_of_x(xs - x_rise)))

    def _path_beyond(self) -> list[np.ndarray]:
        """The chain's path beyond the fountain: through the end channel and onto the
        tail's plate or over the folding roller (none for 'floor')."""
        beyond = self.end_part.path()
        if self.tail is not None:
            beyond += self.tail.path()
        if self.fold is not None:
            beyond += self.fold.path()
        return beyond

    def _lay_along(self, parts: list[np.ndarray]) -> None:
        """Lay the chain along the path (upstream to downstream), one link per link
        length, moving as the steady state would: at rest on the tables, rolling with
        the rollers on their wraps, at the start speed elsewhere."""
        L = self.L
        v0 = self.layout.v_lay
        vR = 0.5 * v0
        R = self.r + self.rho
        s_wrap0 = self.layout.n_ahead * L
        s_wrap1 = s_wrap0 + math.pi * R
        s_lo_wrap = math.inf
        path = np.vstack(parts)
        seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
        s_all = np.concatenate([[0.0], np.cumsum(seg)])
        if self.lower is not None and not self.layout.threads:
            # arc length where the lower wrap starts: the point (x_lo, y_lo)
            idx = int(np.flatnonzero(np.isclose(path[:, 0], self.lower.x)
                                     & np.isclose(path[:, 1], self.y_lo))[0])
            s_lo_wrap = float(s_all[idx])
        pts, s = resample(path, L)
        if self.layout.threads:
            n = int(round(HEAD_BACK / L))
            pts, s = pts[:-n], s[:-n]
        self._lay(pts, s, s_wrap0, s_wrap1, s_lo_wrap, v0, vR, R)

    def _lay(self, pts: np.ndarray, s: np.ndarray, s_w0: float, s_w1: float, s_lw: float,
             v0: float, vR: float, R: float) -> None:
        """Create the links along the resampled path (``pts[i]`` to ``pts[i+1]``)."""
        up, lo = self.upper, self.lower
        om = -vR / R
        R_lo = self.R_lo
        om_lo = -vR / R_lo
        links: list[Link] = []
        for i in range(len(pts) - 1):
            (x0, y0), (x1, y1) = pts[i], pts[i + 1]
            cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
            ang = math.atan2(y1 - y0, x1 - x0)  # local +x points downstream
            mid = s[i] + 0.5 * self.L
            if mid < s_w0:
                vel, w = (0.0, 0.0), 0.0
            elif mid < s_w1:
                c = up.roller.position
                vel, w = (vR - om * (cy - c.y), om * (cx - c.x)), om
            elif lo is not None and mid >= s_lw + math.pi * R_lo:
                vel, w = (0.0, 0.0), 0.0
            elif lo is not None and mid >= s_lw:
                c = lo.roller.position
                vel, w = (vR - om_lo * (cy - c.y), om_lo * (cx - c.x)), om_lo
            else:
                vel, w = (v0 * math.cos(ang), v0 * math.sin(ang)), 0.0
            links.append(self.chain.make_body((cx, cy), ang, velocity=vel, angular_velocity=w))
        for link in reversed(links):  # chain order: downstream end first
            self.chain.append(link)
        self.added = len(links)

    def _take_in_held_links(self) -> None:
        """Put the links laid on the plates and along the joint guides into their grooves
        and joints."""
        lay = self.layout
        if lay.plate_mode == "groove":
            self.grooves.take_in()
            if self.tail is not None:
                self.tail.update()
        if lay.upper_guided:
            g = self.grooves.held
            self.upper_guide.take_in(g[0][0] if g else None)
        if lay.fold_guided and self.fold is not None:
            self.fold.take_in()

    def _add_swing_damper(self) -> pymunk.DampedSpring | None:
        """The swing damper (``apparatus.swing_damper`` c, 'fold'): ``-c*(u_up - u_lo)`` on
        the upper carriage and its opposite on the lower, zero while both roll at one
        speed; a pymunk damped spring without stiffness between the carriages, its axis
        horizontal (the lower carriage's anchor :data:`~.parts.DRIVE_REACH` behind it)."""
        if self.lower is None:
            return None
        s = pymunk.DampedSpring(self.upper.carriage, self.lower.carriage, (0.0, 0.0),
                                (-DRIVE_REACH, 0.0), DRIVE_REACH, 0.0,
                                float(self.cfg.swing_damper))
        self.space.add(s)
        return s

    def retune(self, tuning: Tuning) -> None:
        """Give the built apparatus ``tuning``'s catch and close rate: the parts read them
        only while stepping, so this is as if it had been built with them (for a study
        whose :class:`~chainfountain.sim.Simulation` builds the apparatus).
        ``lay_at_rest`` acts in the build only."""
        if tuning.lay_at_rest != self.tuning.lay_at_rest:
            raise ValueError("Tuning.lay_at_rest acts when the apparatus is built only")
        following = self.layout.end_follow > 0.0
        self.tuning = tuning
        self.upper_guide.close_rate = tuning.close_rate(following)
        if self.fold is not None:
            self.fold.capture = tuning.capture(following)
            self.fold.close_rate = tuning.close_rate(following)

    # ------------------------------------------------------------------ feed interface
    @property
    def n_free(self) -> int:
        return len(self.chain.links)

    @property
    def n_guide(self) -> int:
        return 0

    @property
    def u(self) -> tuple[float, float]:
        return self.launch_u

    @property
    def floor_y(self) -> float:
        """Height of the floor (m): the fountain end, or ``floor_depth`` below it."""
        return -self.H - self.floor_depth

    @property
    def speed(self) -> float:
        """Chain speed: twice the pick-up roller speed (paper: ``v_R = v/2`` at alpha = 0)."""
        return 2.0 * abs(self.upper.speed)

    def moving_mass(self, v_min: float = 1.0) -> float:
        """Mass of the links moving faster than ``v_min`` (kg), the lumped tail included."""
        n = sum(1 for lk in self.chain.links if lk.body.velocity.length > v_min)
        return n * self.chain.mass + self.tail_mass

    def set_speed(self, v: float) -> None:
        raise KeyError("the apparatus has no feed speed: its speed follows from the carts")

    # ------------------------------------------------------------------ stepping
    def before_step(self) -> None:
        """Before each pymunk step: the end pull ('open') and the starter. (The cart
        forces, the bearing drag and the swing damper are pymunk springs,
        :meth:`set_losses`.)"""
        if self.end_pull:
            self.chain.links[0].body.apply_force_at_world_point(
                (self.end_pull, 0.0), self.chain.links[0].body.position)
        self.starter.before_step()
        if self.layout.release_every_step:
            self.upper_guide.release()

    def set_losses(self) -> None:
        """Apply the level's cart forces, ``apparatus.bearing_drag``, ``apparatus.fold_brake``
        and ``apparatus.swing_damper`` (after a live change of any of them)."""
        self.upper.set_drive(self.cfg.bearing_drag)
        if self.lower is not None:
            self.lower.set_drive(self.cfg.bearing_drag + self.cfg.fold_brake)
        if self.swing_spring is not None:
            self.swing_spring.damping = float(self.cfg.swing_damper)

    def after_step(self, dt: float) -> None:
        """Move the plate ends with the rollers; add resting links ahead of the pick-up
        roller; take resting links out of the solver behind the folding roller / on
        the floor; move links along the grooves and joint guides."""
        lay, fold = self.layout, self.fold
        if self._plates_collide:
            self.sync_plates()
        self.follow.sync_end_guide()
        self._check_table()
        self._feed_resting_links()
        # downstream end: absorb at the floor height / drop links that lie at rest
        self.clock.t += dt
        popped = self.tail.lump_tail() if self.tail is not None else 0
        if lay.treadmill:
            self.added += self.treadmills.treadmill_upper()
        popped += self._absorb_end()
        if lay.plate_mode == "groove":
            self.grooves.update(popped)
            if self.tail is not None:
                self.tail.update()
        if lay.upper_guided:
            self.upper_guide.update()
        if lay.fold_guided and fold is not None:
            fold.update_flight(popped)
            fold.update_guide(popped)
            if self.grip is not None:
                self.grip.grip_arriving()
            if lay.treadmill:
                self.treadmills.treadmill_lower()
            self.follow.track_landing()
            if lay.end_follow and not self.starter.starting:  # the starter sets the length
                self.follow.follow_landing(dt)
        if self.fold_watch is not None:
            self.fold_watch.check(dt)
        if self.starter.starting:
            self.starter.check(self.absorbed, self.speed)
        else:
            self.stall_watch.check(dt)

    def _check_table(self) -> None:
        """Raise :class:`TableUsedUp` once the pick-up roller is within 5 cm of the upper
        channel."""
        x_R = self.upper.x
        t = self.clock.t
        if x_R > self.x_plate_up_end - 0.05:
            if self.treadmill:
                raise TableUsedUp(
                    f"t = {t:.2f} s: the pick-up roller has reached the channel although "
                    "the treadmill should hold it (the upper strand has left its plate "
                    "grooves); reset the level",
                    plain=f"At {t:.1f} s the chain left the upper treadmill's grooves "
                    "and the pick-up roller reached the channel")
            raise TableUsedUp(
                f"t = {t:.2f} s: the pick-up roller has reached the channel: the upper "
                f"table is used up (apparatus.duration = {self.cfg.duration:g} s sizes it for "
                f"the start speed; raise it, or set apparatus.plate_links > 0 for a treadmill)",
                plain=f"At {t:.1f} s the upper table ran out of chain: this level's "
                f"table is built for {self.cfg.duration:g} s (a longer one is a level-file "
                "change, apparatus.duration)")

    def _feed_resting_links(self) -> None:
        """Add links at rest on the upper table until ``n_ahead`` lie ahead of the pick-up
        roller."""
        chain = self.chain
        links = chain.links
        L = self.L
        x_R = self.upper.x
        last = links[-1].body
        while pos(last).x < x_R + self.layout.n_ahead * L:
            c = last.position
            new = chain.make_body((c.x + L, self.y_table_up + self.rho), math.pi)
            chain.append(new)
            self.added += 1
            last = new.body

    def _absorb_end(self) -> int:
        """Take links out at the downstream end: at the absorbing floor's height, lying
        on the solid floor, or at rest on the lower table behind the folding roller.
        Returns how many."""
        chain = self.chain
        links = chain.links
        L, n_keep = self.L, self.cfg.rest_links
        popped = 0
        if self.end_mode == "absorbing":
            # as chainfountain.sim.feed: remove the end link when its *centre* reaches the
            # floor, so the free end (Tbar_E = 0) is on average exactly at the floor
            y_floor = self.floor_y
            while len(links) > n_keep + 10 and pos(links[0].body).y <= y_floor:
                chain.pop_front()
                self.absorbed += 1
                popped += 1
        elif self.variant == "floor":
            y_rest = -self.H + 0.02
            while len(links) > n_keep + 10 and links[0].body.position.y < y_rest and \
                    links[n_keep].body.position.y < y_rest:
                chain.pop_front()
                self.absorbed += 1
                popped += 1
        elif self.grip is not None:
            popped = self.grip.land()
            self.absorbed += popped
        elif self.lower is not None:
            x_lim = self.lower.x - 2.0 * self.layout.r_lo - n_keep * L
            y_rest = self.y_table_lo + 2.0 * self.rho
            while len(links) > n_keep + 10:
                p = pos(links[0].body)
                if not (p.x < x_lim and p.y < y_rest):
                    break
                chain.pop_front()
                self.absorbed += 1
                popped += 1
        return popped

    def sync_plates(self) -> None:
        """Put the plates' ends under the rollers (every step for a plate that collides,
        else before the plates' shapes are read; the moving ends are mirrored in
        :attr:`_plate_ends`, so that this reads only the rollers)."""
        L = self.L
        x = self.upper.x + 0.5 * L
        if abs(self._plate_ends[0] - x) > 1e-4:
            a, b = self.plate_up.a, self.plate_up.b
            self.plate_up.unsafe_set_endpoints((x, a.y), b)
            self._plate_ends[0] = x
            if self.plate_up.space is not None:
                self.space.reindex_shape(self.plate_up)
        if self.lower is not None and self.plate_lo is not None:
            x = self.lower.x - 0.5 * L
            if abs(self._plate_ends[1] - x) > 1e-4:
                a, b = self.plate_lo.a, self.plate_lo.b
                self.plate_lo.unsafe_set_endpoints(a, (x, b.y))
                self._plate_ends[1] = x
                if self.plate_lo.space is not None:
                    self.space.reindex_shape(self.plate_lo)

    # ------------------------------------------------------------------ theory
    def cart_bars(self, v: float, lam: float) -> tuple[float, float]:
        """Scaled cart forces ``(Tbar_uc, Tbar_lc)`` at chain speed ``v``, the bearing drag
        counted in (it acts on the carriages like the carts: ``c*v/2`` more holding the
        pick-up back, ``c*v/2`` less pushing the fold on)."""
        s = lam * v * v
        d = 0.5 * self.cfg.bearing_drag * v
        brake = 0.5 * self.cfg.fold_brake * v
        lo = self.lower.force - d - brake if self.lower is not None else 0.0
        return (self.upper.force + d) / s, lo / s

    # ------------------------------------------------------------------ the parts' figures
    @property
    def time(self) -> float:
        """The apparatus's time (s), advanced by the bookkeeping."""
        return self.clock.t

    H = _Part("layout")
    L = _Part("layout")
    rho = _Part("layout")
    r = _Part("layout")
    R_lo = _Part("layout")
    g = _Part("layout")
    h = _Part("layout")
    alpha0 = _Part("layout")
    alphaE = _Part("layout")
    launch_u = _Part("layout")
    variant = _Part("layout")
    gripped = _Part("layout")
    floor_depth = _Part("layout")
    fountain = _Part("layout")
    vertex_pred = _Part("layout")
    y_up = _Part("layout")
    y_table_up = _Part("layout")
    channel_up = _Part("layout")
    x_plate_up_end = _Part("layout")
    treadmill = _Part("layout")
    plate_mode = _Part("layout")
    upper_guided = _Part("layout")
    end_mode = _Part("layout")
    guided = _Part("layout")
    fold_guided = _Part("layout")
    end_follow = _Part("layout")

    # upper part
    upper = _Part("upper_part")
    table_up = _Part("upper_part")
    plate_up = _Part("upper_part")
    up_guide = _Part("upper_part")

    @property
    def upper_held(self) -> list[deque[tuple[Link, pymunk.Constraint]]]:
        """Upper joint guide: the links (with their joints) each element of
        :attr:`up_guide` holds, most downstream first. Read only."""
        return self.upper_guide.held

    @property
    def plate_grooves(self) -> deque[tuple[Link, pymunk.GrooveJoint]]:
        """``plate = "groove"``: the upper plate strand's links with their groove joints,
        most downstream first (the newest, at the pick-up roller, last). Read only."""
        return self.grooves.held

    strand_speed = _Part("grooves")

    # end
    end = _Part("end_part")
    floor = _Part("end_part")
    floor_span = _Part("end_part")
    channel_lo = _Part("end_part")
    end_walls = _Part("end_part")
    y_lo = _Part("end_part")

    @property
    def guide_centre(self) -> tuple[float, float]:
        return self.fold.guide_centre if self.fold is not None else self.end_part.guide_centre

    @property
    def guide_radius(self) -> float:
        return self.fold.guide_radius if self.fold is not None else self.end_part.guide_radius

    @property
    def x_plate_lo_start(self) -> float:
        if self.fold is not None:
            return self.fold.x_plate_lo_start
        return self.end_part.x_plate_lo_start

    # fold
    @property
    def lower(self) -> RollerUnit | None:
        return self.fold.lower if self.fold is not None else None

    @property
    def table_lo(self) -> pymunk.Segment | None:
        return self.fold.table_lo if self.fold is not None else None

    @property
    def plate_lo(self) -> pymunk.Segment | None:
        if self.fold is not None:
            return self.fold.plate_lo
        return self.tail.plate_lo if self.tail is not None else None

    @property
    def y_table_lo(self) -> float:
        return self.fold.y_table_lo if self.fold is not None else math.nan

    @property
    def guide(self) -> list[GuideElement]:
        return self.fold.guide if self.fold is not None else []

    @property
    def fold_held(self) -> list[deque[tuple[Link, pymunk.Constraint]]]:
        """'fold' guide: the links (with their joints) each element of :attr:`guide`
        holds, most downstream first (``[-1]``: the lower plate strand). Read only."""
        return self.fold.held if self.fold is not None else []

    @property
    def released(self) -> int:
        return self.fold.released if self.fold is not None else 0

    @property
    def last_mouth_entry(self) -> float:
        return self.fold.last_mouth_entry if self.fold is not None else math.nan

    @property
    def last_mouth_offset(self) -> float:
        return self.fold.last_mouth_offset if self.fold is not None else math.nan

    def fold_guided_range(self, position: np.ndarray, x_lower: float,
                          mouth: int | None = None) -> tuple[int, int]:
        """:meth:`.fold.FoldPart.fold_guided_range` ('fold' only)."""
        if self.fold is None:
            raise ValueError("fold_guided_range: this apparatus has no fold")
        return self.fold.fold_guided_range(position, x_lower, mouth)

    @property
    def fold_mouth(self) -> int:
        """'fold' guide: chain index of the next link the mouth captures, one past the
        last guided link (read between a step and its bookkeeping, the step's own)."""
        return self.fold.cap_next if self.fold is not None else -1

    # open tail
    @property
    def tail_mass(self) -> float:
        """'open': mass (kg) of the tail links lumped into the end link."""
        return self.tail.tail_mass if self.tail is not None else 0.0

    @property
    def tail_grooved(self) -> int:
        """'open' with ``plate = "groove"``: how many links (chain indices ``0 ..
        tail_grooved-1``, the tail) run in the lower plate's grooves."""
        return self.tail.lo_n if self.tail is not None else 0

    @property
    def turn_held(self) -> deque[tuple[Link, pymunk.SlideJoint]]:
        """'open' guide: the links held on the turn (chain indices from
        :attr:`tail_grooved` on) with their slide joints. Read only."""
        return self.tail.arc if self.tail is not None else deque()

    @property
    def end_pull(self) -> float:
        """Constant pull on the downstream end link in ``+x`` (N; 'open' only)."""
        return float(self.cfg.end_pull) if self.variant == "open" else 0.0

    @property
    def open_drive(self) -> float:
        """'open': the constant force (N) driving the moving chain, the weight of the drop
        from the upper plate to the tail's plate plus the end pull,
        ``lambda g (y_up - y_lo) + F_pull``."""
        lam = self.sim_cfg.chain.linear_density
        return lam * self.g * (self.y_up - self.y_lo) + self.end_pull

    # gripped fold
    @property
    def head_pinned(self) -> bool:
        return self.grip is not None and self.grip.head_pinned

    @property
    def n_welded(self) -> int:
        return self.grip.n_welded if self.grip is not None else 0

    @property
    def gripped_links(self) -> int:
        return self.grip.gripped_links if self.grip is not None else 0

    @property
    def landing_speed(self) -> float:
        return self.grip.landing_speed if self.grip is not None else 0.0

    # following end guide
    end_shift = _Part("follow")
    end_carrier = _Part("follow")
    landing_offset = _Part("follow")

    def sync_end_guide(self) -> None:
        """:meth:`.follow.FollowingEnd.sync_end_guide`."""
        self.follow.sync_end_guide()

    def sync_end_walls(self) -> None:
        """:meth:`.follow.FollowingEnd.sync_end_walls`."""
        self.follow.sync_end_walls()

    # treadmills
    start_x = _Part("treadmills")
    moved_back = _Part("treadmills")
    shifted = _Part("treadmills")
    cut = _Part("treadmills")
    shifted_lo = _Part("treadmills")

    def travel(self, i: int) -> float:
        """:meth:`.treadmill.Treadmills.travel`."""
        return self.treadmills.travel(i)

    # starter
    starting = _Part("starter")
    fading = _Part("starter")

    @property
    def starter_speed(self) -> float:
        return self.starter.speed

    launch_speed = _Part("starter")
    head_caught_at = _Part("starter")

    def stall_message(self) -> str:
        return self.stall_watch.stall_message()

