"""The upper part: the pick-up roller on the upper table, the upper plate and the upper
channel (its walls, or the joint guide's elements: :mod:`.upper_guide`)."""

from __future__ import annotations

import math

import numpy as np
import pymunk

from chainfountain.sim.apparatus.parts import (
    ONLY_CHAIN,
    SCENERY,
    add_roller,
    static_polyline,
    static_segment,
)
from chainfountain.sim.apparatus.tuning import CLEAR, WALL_R
from chainfountain.sim.guide import Channel, GuideElement, upper_channel, upper_guide


class UpperPart:
    """Builds the upper part (a mixin of :class:`~chainfountain.sim.apparatus.Apparatus`)."""

    def _build_upper(self) -> list[np.ndarray]:
        """Pick-up roller, upper table, upper plate and upper channel, in this order;
        returns the chain's path along them (upstream to downstream: resting chain, the
        roller's wrap, the plate, the channel)."""
        ch_pts = self._upper_channel_points()
        x_R = self._build_pickup()
        self._build_upper_channel(ch_pts)
        return self._upper_path(x_R, ch_pts)

    def _upper_channel_points(self) -> np.ndarray:
        """Heights of the upper part and the upper channel's centre line; whether the
        upper plate is a treadmill."""
        a, H = self.cfg, self.H
        self.y_up = -a.xi2 * H
        self.y_table_up = self.y_up - 3.0 * self.rho - 2.0 * self.r
        ch_pts, self.R_up = upper_channel(H, a.xi2, self.alpha0, a.channel_radius, 0.1,
                                          0.5 * self.L)
        self.x_plate_up_end = float(ch_pts[0, 0])
        self.treadmill = a.plate_links > 0 and a.plate == "groove"
        """The upper plate strand is held at about ``plate_links`` links
        (:meth:`~.treadmill.Treadmills._treadmill_upper`)."""
        return ch_pts

    def _table_travel(self) -> float:
        """Distance (m) a roller rolls in ``apparatus.duration`` at the start speed, with
        15 cm to spare: the length of table a run needs without a treadmill."""
        a = self.cfg
        v0 = float(a.speed)
        return 0.5 * v0 * a.duration + 0.15

    def _build_pickup(self) -> float:
        """The pick-up roller (rolling at ``v/2``), the upper table and the upper plate;
        returns the roller's start x."""
        a, L, rho, r = self.cfg, self.L, self.rho, self.r
        space = self.space
        carts = list(self.sim_cfg.carts)
        y_tab = self.y_table_up
        travel = self._table_travel()
        if self.treadmill:  # at least 15 cm: the table check keeps a 5-cm margin
            travel = max((int(a.plate_links) + 2) * L, 0.15)
        x_R = self.x_plate_up_end - travel
        vR = 0.5 * self.v_lay
        R = r + rho
        self.upper = add_roller(space, x_R, y_tab, rho, r, a.roller_mass, a.carriage_mass,
                                carts[0] if carts else None, -1.0, self.g,
                                self.sim_cfg.solver.joint_error_bias, vR, -vR / R,
                                drag=a.bearing_drag)
        self.table_up = static_segment(space, (x_R - 1.0, y_tab - 0.01),
                                       (self.x_plate_up_end, y_tab - 0.01), 0.01,
                                       a.table_friction, SCENERY)
        space.add(self.table_up)
        self.plate_up = static_segment(space, (x_R + 0.5 * L, self.y_up - rho - 0.002),
                                       (self.x_plate_up_end, self.y_up - rho - 0.002), 0.002,
                                       0.0, ONLY_CHAIN)
        self.plate_mode = a.plate
        if self.plate_mode == "contact":
            space.add(self.plate_up)
        return x_R

    def _build_upper_channel(self, ch_pts: np.ndarray) -> None:
        """The upper channel: static walls, or (``upper_guide = "joints"``) the joint
        guide's elements with the walls drawn only."""
        a = self.cfg
        self.walls: list[pymunk.Segment] = []
        off = self.rho + CLEAR + WALL_R
        ch = Channel(ch_pts)
        self.upper_guided = a.upper_guide == "joints"
        """The upper channel is a frictionless joint guide (:attr:`up_guide`); its walls
        are drawn only."""
        if self.upper_guided and a.plate != "groove":  # the level check says so too
            raise ValueError("apparatus.upper_guide: 'joints' needs apparatus.plate = 'groove' "
                             f"(it is {a.plate!r}); allowed: 'walls' with a 'contact' plate")
        for w in ch.walls(off):
            self.walls += static_polyline(self.space, w, WALL_R, add=not self.upper_guided)
        self.channel_up = ch_pts
        self.up_guide: list[GuideElement] = (
            upper_guide(self.H, a.xi2, self.alpha0, a.channel_radius, 0.1)
            if self.upper_guided else [])

    def _upper_path(self, x_R: float, ch_pts: np.ndarray) -> list[np.ndarray]:
        """The chain's path from the resting chain's end to the fountain start."""
        L, rho = self.L, self.rho
        R = self.r + rho
        y_tab = self.y_table_up
        yc = self.upper.yc
        rest_end = x_R + self.n_ahead * L
        parts: list[np.ndarray] = [np.array([[rest_end, y_tab + rho], [x_R, y_tab + rho]])]
        th = np.linspace(1.5 * math.pi, 0.5 * math.pi, 60)[1:]
        parts.append(np.column_stack((x_R + R * np.cos(th), yc + R * np.sin(th))))
        parts.append(np.array([[self.x_plate_up_end, self.y_up]]))
        parts.append(ch_pts[1:])
        return parts
