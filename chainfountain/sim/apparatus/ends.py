"""The end of the fountain by variant: the floor ('floor': absorbing or solid), or the
end channel ('fold', 'open'), whose mouth sits on the predicted fountain end aligned
with the landing tangent (with 'open''s one-sided catch wall, or the 'fold' channel's
funnel); beyond it the open tail's plate (:mod:`.open_tail`) or the folding roller
(:mod:`.fold`)."""

from __future__ import annotations

import math

import numpy as np
import pymunk

from chainfountain.sim.apparatus.parts import (
    SCENERY,
    RollerUnit,
    static_polyline,
    static_segment,
)
from chainfountain.sim.apparatus.tuning import CATCH, CLEAR, FUNNEL, WALL_R
from chainfountain.sim.guide import Channel, GuideElement, end_channel


class EndPart:
    """Builds the fountain's end (a mixin of :class:`~chainfountain.sim.apparatus.Apparatus`)."""

    def _build_end(self) -> list[np.ndarray]:
        """The floor or the end channel and what follows it; returns the chain's path
        beyond the fountain (empty for the floor variant)."""
        ex = self.end[0]
        f = self.fountain
        x_rise = self.vertex_pred[0]
        a = self.cfg
        self.floor: pymunk.Segment | None = None
        self.floor_span = (ex - 0.1, ex + 0.1)
        """x range of the floor (drawing; 'floor' variant)."""
        self.lower: RollerUnit | None = None
        self.plate_lo: pymunk.Segment | None = None
        self.channel_lo: np.ndarray | None = None
        self.guided = False
        """'open' with ``plate = "groove"``: the turn after landing is a joint guide."""
        self.fold_guided = False
        """'fold' with ``plate = "groove"``: the lower channel (turn, rise, turn) and the
        lower plate are a frictionless joint guide (:attr:`guide`)."""
        self.guide: list[GuideElement] = []
        self.end_walls: list[pymunk.Segment] = []
        """'fold': the end channel's walls (drawn; a following end guide moves them)."""
        self.guide_centre = (math.nan, math.nan)
        self.guide_radius = math.nan
        alphaE = math.atan(math.sinh(f.q * (ex - x_rise)))
        self.alphaE = alphaE
        self.end_mode = a.end if self.variant == "floor" else "channel"
        if self.end_mode == "absorbing":
            w = a.floor_width
            self.floor_span = (self.x_floor - 0.3 * w, self.x_floor + 0.7 * w)
            return []
        if self.variant == "floor":
            self._build_floor()
            return []
        return self._build_end_channel()

    def _build_floor(self) -> None:
        """'floor' with ``end = "solid"``: a static floor at the end height (the chain's
        centre line lying on it at ``-H``) the chain piles on."""
        a, H, rho = self.cfg, self.H, self.rho
        ex = self.end[0]
        w = a.floor_width
        self.floor_span = (ex - 0.3 * w, ex + 0.7 * w)
        self.floor = static_segment(self.space, (ex - 0.3 * w, -H - rho - 0.005),
                                    (ex + 0.7 * w, -H - rho - 0.005), 0.005,
                                    self.sim_cfg.chain.friction, SCENERY)
        self.space.add(self.floor)

    def _build_end_channel(self) -> list[np.ndarray]:
        """'fold', 'open': the end channel (its walls; with grooves a joint guide), then
        the open tail's plate or the folding roller; returns the chain's path from the
        channel's mouth on."""
        a, H = self.cfg, self.H
        ex = self.end[0]
        alphaE = self.alphaE
        rise = a.xi3 * H if self.variant == "fold" else 0.0
        lead = 0.1
        cp, self.i_end = end_channel(ex, -H, alphaE, rise, a.channel_radius, lead,
                                     0.5 * self.L)
        self.channel_lo = cp
        # 'open' with grooves: the turn is a frictionless circular guide of joints
        # (centre of the end channel's bend, radius channel_radius), see _update_lo_grooves
        Rc = a.channel_radius
        self.guide_centre = (ex + Rc * math.sin(alphaE), -H + Rc * math.cos(alphaE))
        self.guide_radius = Rc
        self.guided = self.variant == "open" and a.plate == "groove"
        if self.variant == "open":
            self._build_catch(cp)
        else:
            self._build_funnel(cp)
        self.y_lo = float(cp[-1, 1])
        xl = float(cp[-1, 0])
        self.x_plate_lo_start = self.guide_centre[0] if self.guided else xl
        parts = [cp[self.i_end + 1:]]
        if self.variant == "open":
            parts += self._build_open_plate(xl)
        else:
            parts += self._build_fold_lower(xl, rise)
        return parts

    @staticmethod
    def _mouth_frame(cp: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Unit tangent and normal of the end channel at its mouth."""
        t0 = (cp[1] - cp[0]) / np.linalg.norm(cp[1] - cp[0])
        n0 = np.array([-t0[1], t0[0]])
        return t0, n0

    def _build_catch(self, cp: np.ndarray) -> None:
        """'open': a one-sided catch, only the outer wall of the turn (the chain, at
        ``T < lambda*v**2``, presses on it), flared up and out above the mouth; no inner
        wall and no mouth lip the falling chain could hook on (drawn only when the joint
        guide is used)."""
        t0, n0 = self._mouth_frame(cp)
        off = self.rho + CLEAR + WALL_R
        outer = Channel(cp).walls(off)[1]
        top = outer[0] - CATCH[0] * t0 - CATCH[1] * n0
        self.walls += static_polyline(self.space, np.vstack((top, outer)), WALL_R,
                                      add=not self.guided)

    def _build_funnel(self, cp: np.ndarray) -> None:
        """'fold': both walls of the end channel with a funnel before the mouth (the
        landing angle wanders by a few degrees and a link arriving on a blunt wall end
        jams the chain; seen in 'open' runs). With grooves the lower channel is a
        frictionless joint guide (:mod:`.fold`) and its walls are drawn only."""
        a = self.cfg
        t0, n0 = self._mouth_frame(cp)
        off = self.rho + CLEAR + WALL_R
        self.fold_guided = a.plate == "groove"
        for wl, side in zip(Channel(cp).walls(off), (1.0, -1.0), strict=True):
            flare = wl[0] - FUNNEL[0] * t0 + side * FUNNEL[1] * n0
            segs = static_polyline(self.space, np.vstack((flare, wl)), WALL_R,
                                   add=not self.fold_guided)
            self.end_walls += segs
            self.walls += segs
