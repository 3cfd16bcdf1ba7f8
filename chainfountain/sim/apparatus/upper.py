"""The upper part: the pick-up roller on the upper table, the upper plate and the upper
channel (its walls, or the joint guide's elements: :mod:`.upper_guide`)."""

from __future__ import annotations

import math

import numpy as np
import pymunk

from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.parts import (
    ONLY_CHAIN,
    SCENERY,
    RollerUnit,
    add_roller,
    static_polyline,
    static_segment,
)
from chainfountain.sim.apparatus.tuning import CLEAR, WALL_R
from chainfountain.sim.guide import Channel, GuideElement, upper_guide


class UpperPart:
    """The pick-up roller (rolling at ``v/2``), the upper table, the upper plate and the
    upper channel, built into the space in this order."""

    def __init__(self, space: pymunk.Space, layout: Layout) -> None:
        self.space = space
        self.layout = layout
        x_R = self._roller_x()
        self.upper: RollerUnit = self._add_pickup(x_R)
        """The pick-up roller on its carriage."""
        self.table_up: pymunk.Segment = self._add_table(x_R)
        self.plate_up: pymunk.Segment = self._add_plate(x_R)
        """The upper plate (a collision shape with ``plate = "contact"``, else drawn only:
        the grooves run on its line)."""
        self.walls: list[pymunk.Segment] = self._add_channel_walls()
        """The upper channel's walls (drawn only with the upper joint guide)."""
        lay, a = layout, layout.cfg
        self.up_guide: list[GuideElement] = (
            upper_guide(lay.H, a.xi2, lay.alpha0, a.channel_radius, 0.1)
            if lay.upper_guided else [])
        """The upper joint guide's elements (empty without it)."""
        self.x_start = x_R
        """The pick-up roller's start x (m)."""

    def _roller_x(self) -> float:
        """The pick-up roller's start x: a table's travel before the channel (with a
        treadmill a few strand links' worth, at least 15 cm: the table check keeps a 5-cm
        margin)."""
        lay = self.layout
        travel = lay.table_travel()
        if lay.treadmill:
            travel = max((int(lay.cfg.plate_links) + 2) * lay.L, 0.15)
        return lay.x_plate_up_end - travel

    def _add_pickup(self, x_R: float) -> RollerUnit:
        lay, a = self.layout, self.layout.cfg
        carts = list(lay.sim_cfg.carts)
        vR = 0.5 * lay.v_lay
        R = lay.r + lay.rho
        return add_roller(self.space, x_R, lay.y_table_up, lay.rho, lay.r, a.roller_mass,
                          a.carriage_mass, carts[0] if carts else None, -1.0, lay.g,
                          lay.sim_cfg.solver.joint_error_bias, vR, -vR / R,
                          drag=a.bearing_drag)

    def _add_table(self, x_R: float) -> pymunk.Segment:
        lay = self.layout
        y_tab = lay.y_table_up
        table = static_segment(self.space, (x_R - 1.0, y_tab - 0.01),
                               (lay.x_plate_up_end, y_tab - 0.01), 0.01,
                               lay.cfg.table_friction, SCENERY)
        self.space.add(table)
        return table

    def _add_plate(self, x_R: float) -> pymunk.Segment:
        lay = self.layout
        L, rho = lay.L, lay.rho
        plate = static_segment(self.space, (x_R + 0.5 * L, lay.y_up - rho - 0.002),
                               (lay.x_plate_up_end, lay.y_up - rho - 0.002), 0.002,
                               0.0, ONLY_CHAIN)
        if lay.plate_mode == "contact":
            self.space.add(plate)
        return plate

    def _add_channel_walls(self) -> list[pymunk.Segment]:
        """The upper channel: static walls, or (``upper_guide = "joints"``) walls drawn
        only (the joint guide holds the links)."""
        lay = self.layout
        a = lay.cfg
        walls: list[pymunk.Segment] = []
        off = lay.rho + CLEAR + WALL_R
        ch = Channel(lay.channel_up)
        if lay.upper_guided and a.plate != "groove":  # the level check says so too
            raise ValueError("apparatus.upper_guide: 'joints' needs apparatus.plate = 'groove' "
                             f"(it is {a.plate!r}); allowed: 'walls' with a 'contact' plate")
        for w in ch.walls(off):
            walls += static_polyline(self.space, w, WALL_R, add=not lay.upper_guided)
        return walls

    def path(self) -> list[np.ndarray]:
        """The chain's path from the resting chain's end to the fountain start (upstream
        to downstream: resting chain, the roller's wrap, the plate, the channel)."""
        lay = self.layout
        L, rho = lay.L, lay.rho
        x_R = self.x_start
        R = lay.r + rho
        y_tab = lay.y_table_up
        yc = self.upper.yc
        rest_end = x_R + lay.n_ahead * L
        parts: list[np.ndarray] = [np.array([[rest_end, y_tab + rho], [x_R, y_tab + rho]])]
        th = np.linspace(1.5 * math.pi, 0.5 * math.pi, 60)[1:]
        parts.append(np.column_stack((x_R + R * np.cos(th), yc + R * np.sin(th))))
        parts.append(np.array([[lay.x_plate_up_end, lay.y_up]]))
        parts.append(lay.channel_up[1:])
        return parts
