"""The apparatus as one object: :class:`Apparatus` builds the parts (in the order the
solver sees them) and steps them; each part's code is in its own module, composed here
as a mixin.

Build steps, upstream to downstream (:meth:`Apparatus.__init__`): the predicted
fountain (layout), the upper part (:mod:`.upper`), the end by variant (:mod:`.ends`;
the open tail's plate, :mod:`.open_tail`; the folding roller and lower guide,
:mod:`.fold`), the chain laid along the path, then the links taken into their grooves
and joint guides (:mod:`.grooves`, :mod:`.upper_guide`, :mod:`.fold`). Each step adds
its bodies, shapes and joints to the space in the order the single constructor did
(the solver's results depend on it).
"""

from __future__ import annotations

import math

import numpy as np
import pymunk

from chainfountain.errors import RunEnded
from chainfountain.sim.apparatus.ends import EndPart
from chainfountain.sim.apparatus.fold import FoldPart
from chainfountain.sim.apparatus.fold_watch import FoldWatch
from chainfountain.sim.apparatus.follow import FollowingEnd
from chainfountain.sim.apparatus.grip import GrippedFold
from chainfountain.sim.apparatus.grooves import PlateGrooves
from chainfountain.sim.apparatus.open_tail import OpenTail
from chainfountain.sim.apparatus.parts import DRIVE_REACH
from chainfountain.sim.apparatus.stall_watch import StallWatch
from chainfountain.sim.apparatus.starter import StarterPart
from chainfountain.sim.apparatus.treadmill import Treadmills
from chainfountain.sim.apparatus.tuning import (
    FOLD_CAPTURE,
    FOLD_CLOSE_RATE,
    FOLLOW_CAPTURE,
    FOLLOW_CLOSE_RATE,
)
from chainfountain.sim.apparatus.upper import UpperPart
from chainfountain.sim.apparatus.upper_guide import UpperJointGuide
from chainfountain.sim.chain import Chain, Link
from chainfountain.sim.config import SimConfig
from chainfountain.sim.fastbody import pos
from chainfountain.sim.guide import resample

HEAD_BACK = 0.1
"""'fold' from rest: how far (m) inside the upper guide the chain's head waits, so that
the starter has it at its launch speed before it leaves (a head that leaves slowly
droops and falls short)."""


class TableUsedUp(RunEnded):
    """The pick-up roller has reached the upper channel: the run has outgrown the
    upper table (raised by :meth:`Apparatus.after_step`; the app pauses on it, the
    CLI writes what was simulated and says so)."""


class Apparatus(UpperPart, EndPart, PlateGrooves, UpperJointGuide, FoldPart, GrippedFold,
                FoldWatch, FollowingEnd, StallWatch, Treadmills, OpenTail, StarterPart):
    """Builds the apparatus into a space and keeps its bookkeeping (duck-types the
    :class:`~chainfountain.sim.feed.Feed` interface the simulation uses).

    Attributes give the geometry for views and measurements: ``upper``/``lower``
    (:class:`~chainfountain.sim.apparatus.parts.RollerUnit`), ``y_up``/``y_lo``
    (roller-top centre lines), ``end`` (fountain end point), ``launch_u`` (unit launch
    direction), ``walls`` (static segments), ``fountain`` (the predicted fountain used
    for the layout).

    The parts (mixins, one module each) share this object's state: each builds its
    attributes in its build step and its bookkeeping in its ``_init_*_state``.
    """

    fold_capture: tuple[float, float] = FOLD_CAPTURE
    """'fold' joint guide: capture band (m) and angular margin (rad) of the first turn
    (:data:`~.tuning.FOLD_CAPTURE`). A class attribute so that a study can vary it
    (``research/swing_study.py`` sets it on the class)."""
    fold_close_rate: float = FOLD_CLOSE_RATE
    """Joint guides: speed (m/s) at which the limits of a link captured off a turn's
    radius close in (:data:`~.tuning.FOLD_CLOSE_RATE`); a class attribute as
    :attr:`fold_capture`."""

    def __init__(self, space: pymunk.Space, chain: Chain, cfg: SimConfig) -> None:
        """Build the apparatus into ``space`` and lay ``chain`` along it, part by part in
        the order the solver sees them (module docstring)."""
        self._read_config(space, chain, cfg)
        self._predict_fountain()
        path = self._build_upper()
        path.append(self._fountain_path())
        beyond = self._build_end()
        if not self.threads:  # else the starter threads the head through later
            path += beyond
        self._lay_along(path)
        self._init_state()
        self._add_swing_damper()
        self.sync_plates()
        if self.gripped and not self.threads:
            self._init_grip()
        self._take_in_held_links()

    # ------------------------------------------------------------------ build steps
    def _read_config(self, space: pymunk.Space, chain: Chain, cfg: SimConfig) -> None:
        """The space, the chain and the level's figures the parts share."""
        self.space = space
        self.chain = chain
        self.sim_cfg = cfg
        a = self.cfg = cfg.apparatus
        self.g = float(cfg.gravity)
        if a.variant == "fold" and a.plate == "groove" and a.end_follow > 0.0:
            # a following end guide's wide mouth (unless a study has set the class's)
            if type(self).fold_capture == FOLD_CAPTURE:
                self.fold_capture = FOLLOW_CAPTURE
            if type(self).fold_close_rate == FOLD_CLOSE_RATE:
                self.fold_close_rate = FOLLOW_CLOSE_RATE
        self.h = float(cfg.solver.dt) / int(cfg.solver.substeps)
        """pymunk's step (s): ``solver.dt / solver.substeps``. The bookkeeping
        (:meth:`after_step`) runs once per ``solver.dt``; forces apply in every pymunk step."""
        self._release_every_step = int(cfg.solver.substeps) > 1 and a.upper_guide == "joints"
        """Whether the upper joint guide lets links go in every pymunk step as well
        (:meth:`~.upper_guide.UpperJointGuide._release_upper`)."""
        self.L = chain.L
        self.rho = float(cfg.chain.link_radius)
        self.r = float(a.roller_radius)
        self.r_lo = float(a.fold_roller_radius) or self.r
        """Radius (m) of the folding roller ('fold'; ``apparatus.fold_roller_radius``)."""
        self.R_lo = self.r_lo + self.rho
        """Radius (m) of the chain's centre line on the folding roller."""
        self.gripped = a.variant == "fold" and a.fold_roller == "gripped"
        """The folding roller holds the chain by joints (:mod:`.grip`), not by contact."""
        self.H = float(a.drop)
        self.alpha0 = float(a.launch_angle)
        self.launch_u = (math.cos(self.alpha0), math.sin(self.alpha0))
        self.variant = a.variant
        self.n_ahead = int(a.pickup_rest_links or a.rest_links)
        """Resting links kept in the solver ahead of the pick-up roller."""
        self.absorbed = 0
        self.added = 0
        self.floor_depth = float(a.floor_depth) if self.variant == "floor" else 0.0
        """Depth (m) of the absorbing floor below the fountain end ('floor' variant)."""
        self.from_rest = cfg.initial.mode == "stub"
        """The chain starts at rest with a stub at the start, run up by the starter
        (:mod:`.starter`); else it starts laid along its path, moving."""
        self.threads = self.from_rest and a.variant == "fold"
        """From rest in 'fold': the chain ends inside the upper guide, and the starter
        threads its head through the end guide and round the folding roller."""
        self.stub_length = float(cfg.initial.stub_length)
        self.v_lay = 0.0 if self.from_rest else float(a.speed)
        """The speed (m/s) the chain is laid moving at."""

    def _predict_fountain(self) -> None:
        """The predicted fountain (the layout; it aims the end channel). A floor ``d``
        below the end adds the hanging strand's weight: ``Tbar_E = g*d/v**2``."""
        from chainfountain.theory import Fountain

        a, H = self.cfg, self.H
        v0 = float(a.speed)
        TE_lay = float(a.end_tension) + self.g * self.floor_depth / v0**2
        self.fountain = Fountain.from_launch(v=v0, alpha0=self.alpha0, H=H,
                                             TE_bar=TE_lay, g=self.g)
        f = self.fountain
        x_rise = math.acosh(1.0 + f.q * f.h) / f.q
        self.vertex_pred = (x_rise, f.h)
        self.end = (x_rise + math.acosh(1.0 + f.q * (f.h + H)) / f.q, -H)
        self.x_floor = x_rise + math.acosh(1.0 + f.q * (f.h + H + self.floor_depth)) / f.q
        """x where the catenary, continued below the end, meets the floor ('floor')."""

    def _fountain_path(self) -> np.ndarray:
        """The chain's path through the predicted fountain (to ``x_floor``, the end's x
        without a ``floor_depth``); from rest, a straight stub along the launch line, and
        in 'fold' none (the starter threads the head through, :mod:`.starter`)."""
        if self.threads:
            return np.empty((0, 2))  # the head waits inside the upper guide (_lay_along)
        if self.from_rest:
            s = np.linspace(0.0, self.stub_length, 8)[1:]
            return np.column_stack((s * self.launch_u[0], s * self.launch_u[1]))
        f = self.fountain
        x_rise = self.vertex_pred[0]
        xs = np.linspace(0.0, self.x_floor, 400)[1:]  # x_floor = ex without a floor_depth
        return np.column_stack((xs, f.h + f.y_of_x(xs - x_rise)))

    def _lay_along(self, parts: list[np.ndarray]) -> None:
        """Lay the chain along the path (upstream to downstream), one link per link
        length, moving as the steady state would: at rest on the tables, rolling with
        the rollers on their wraps, at the start speed elsewhere."""
        L = self.L
        v0 = self.v_lay
        vR = 0.5 * v0
        R = self.r + self.rho
        s_wrap0 = self.n_ahead * L
        s_wrap1 = s_wrap0 + math.pi * R
        s_lo_wrap = math.inf
        path = np.vstack(parts)
        seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
        s_all = np.concatenate([[0.0], np.cumsum(seg)])
        if self.lower is not None and not self.threads:
            # arc length where the lower wrap starts: the point (x_lo, y_lo)
            idx = int(np.flatnonzero(np.isclose(path[:, 0], self.lower.x)
                                     & np.isclose(path[:, 1], self.y_lo))[0])
            s_lo_wrap = float(s_all[idx])
        pts, s = resample(path, L)
        if self.threads:
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

    def _init_state(self) -> None:
        """The bookkeeping of every part (before any link is taken into a guide)."""
        self.start_x = (self.upper.x, self.lower.x if self.lower is not None else 0.0)
        self._plate_ends = [float(self.plate_up.a.x), float(self.plate_lo.b.x)
                            if self.plate_lo is not None else 0.0]
        """x of the upper plate's start and the lower plate's end (m)."""
        self._plates_collide = self.plate_up.space is not None or (
            self.plate_lo is not None and self.plate_lo.space is not None)
        """Whether a plate is a collision shape (``plate = "contact"``): its ends then
        follow the rollers every step; with grooves the plates are only drawn, and their
        ends follow when read (:meth:`sync_plates`)."""
        self._t = 0.0
        self._init_groove_state()
        self._init_upper_guide_state()
        self._init_treadmill_state()
        self._init_open_state()
        self._init_fold_state()
        self._init_grip_state()
        self._init_follow_state()
        self._init_watch_state()
        self._init_stall_state()
        self._init_starter_state()

    def _take_in_held_links(self) -> None:
        """Put the links laid on the plates and along the joint guides into their grooves
        and joints."""
        if self.plate_mode == "groove":
            self._init_grooves()
            self._update_lo_grooves()
        if self.upper_guided:
            self._init_upper_guide()
        if self.fold_guided:
            self._init_fold_guide()
            self._fly_next = self._cap_next
            self._update_flight(0)

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
        if self.starting:
            self._drive_starter()
        elif self.fading:
            self._fade_starter()
        if self._release_every_step:
            self._release_upper()

    def _add_swing_damper(self) -> None:
        """The swing damper (``apparatus.swing_damper`` c, 'fold'): ``-c*(u_up - u_lo)`` on
        the upper carriage and its opposite on the lower, zero while both roll at one
        speed; a pymunk damped spring without stiffness between the carriages, its axis
        horizontal (the lower carriage's anchor :data:`~.parts.DRIVE_REACH` behind it)."""
        self.swing_spring: pymunk.DampedSpring | None = None
        if self.lower is None:
            return
        s = pymunk.DampedSpring(self.upper.carriage, self.lower.carriage, (0.0, 0.0),
                                (-DRIVE_REACH, 0.0), DRIVE_REACH, 0.0,
                                float(self.cfg.swing_damper))
        self.space.add(s)
        self.swing_spring = s

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
        if self._plates_collide:
            self.sync_plates()
        if self.end_carrier is not None:
            self._sync_end_guide()
        self._check_table()
        self._feed_resting_links()
        # downstream end: absorb at the floor height / drop links that lie at rest
        self._t += dt
        popped = self._lump_tail()
        if self.treadmill:
            self._treadmill_upper()
        popped += self._absorb_end()
        if self.plate_mode == "groove":
            self._update_grooves(popped)
            self._update_lo_grooves()
        if self.upper_guided:
            self._update_upper_guide()
        if self.fold_guided:
            self._update_flight(popped)
            self._update_fold_guide(popped)
            if self.gripped:
                self._grip_arriving()
            if self.treadmill:
                self._treadmill_lower()
            self._track_landing()
            if self.end_follow and not self.starting:  # the starter sets the length
                self._follow_landing(dt)
        if self.lower is not None:
            self._check_fold(dt)
        if self.starting:
            self._check_starter()
        else:
            self._check_stall(dt)

    def _check_table(self) -> None:
        """Raise :class:`TableUsedUp` once the pick-up roller is within 5 cm of the upper
        channel."""
        x_R = self.upper.x
        if x_R > self.x_plate_up_end - 0.05:
            if self.treadmill:
                raise TableUsedUp(
                    f"t = {self._t:.2f} s: the pick-up roller has reached the channel although "
                    "the treadmill should hold it (the upper strand has left its plate "
                    "grooves); reset the level",
                    plain=f"At {self._t:.1f} s the chain left the upper treadmill's grooves "
                    "and the pick-up roller reached the channel")
            raise TableUsedUp(
                f"t = {self._t:.2f} s: the pick-up roller has reached the channel: the upper "
                f"table is used up (apparatus.duration = {self.cfg.duration:g} s sizes it for "
                f"the start speed; raise it, or set apparatus.plate_links > 0 for a treadmill)",
                plain=f"At {self._t:.1f} s the upper table ran out of chain: this level's "
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
        while pos(last).x < x_R + self.n_ahead * L:
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
        elif self.gripped:
            popped = self._land_gripped()
        elif self.lower is not None:
            x_lim = self.lower.x - 2.0 * self.r_lo - n_keep * L
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
