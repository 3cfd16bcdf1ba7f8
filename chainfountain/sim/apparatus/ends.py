"""The end of the fountain by variant: the floor ('floor': absorbing or solid), or the
end channel ('fold', 'open'), whose mouth sits on the predicted fountain end aligned
with the landing tangent (with 'open''s one-sided catch wall, or the 'fold' channel's
funnel); beyond it the open tail's plate (:mod:`.open_tail`) or the folding roller
(:mod:`.fold`)."""

from __future__ import annotations

import math

import numpy as np
import pymunk

from chainfountain.sim.apparatus.layout import Layout
from chainfountain.sim.apparatus.parts import SCENERY, static_polyline, static_segment
from chainfountain.sim.apparatus.tuning import CATCH, CLEAR, FUNNEL, WALL_R
from chainfountain.sim.guide import Channel, end_channel


class EndPart:
    """The fountain's end by variant: the floor ('floor'), or the end channel ('fold',
    'open'; its walls, drawn only with a joint guide). What follows the end channel is
    another part's (:class:`~.open_tail.OpenTail`, :class:`~.fold.FoldPart`)."""

    def __init__(self, space: pymunk.Space, layout: Layout) -> None:
        self.space = space
        self.layout = layout
        ex = layout.end[0]
        self.end = layout.end
        """The fountain end (m): the predicted one, moved along x with a following end
        guide (:meth:`shift`)."""
        self.floor: pymunk.Segment | None = None
        """'floor' with ``end = "solid"``: the floor the chain piles on."""
        self.floor_span = (ex - 0.1, ex + 0.1)
        """x range of the floor (drawing; 'floor' variant)."""
        self.channel_lo: np.ndarray | None = None
        """The end channel's centre line (mouth to exit; ``None`` for 'floor')."""
        self.i_end = 0
        """Index in :attr:`channel_lo` of the predicted fountain end."""
        self.walls: list[pymunk.Segment] = []
        """The end channel's walls: 'open''s catch, 'fold''s channel with its funnel."""
        self.end_walls: list[pymunk.Segment] = []
        """'fold': the end channel's walls (drawn; a following end guide moves them)."""
        self.guide_centre = (math.nan, math.nan)
        """Centre of the end channel's first bend (m)."""
        self.guide_radius = math.nan
        self.y_lo = math.nan
        """Chain centre line at the end channel's exit (m; nan for 'floor'): on top of
        the folding roller ('fold'), on the tail's plate ('open')."""
        self.x_exit = math.nan
        """x of the end channel's exit (m)."""
        self.x_plate_lo_start = math.nan
        """Where the lower plate's grooves start (m; 'open')."""
        self.rise = 0.0
        """'fold': the end channel's rise ``xi3*H`` from the landing to the lower plate."""
        if layout.end_mode == "absorbing":
            w = layout.cfg.floor_width
            self.floor_span = (layout.x_floor - 0.3 * w, layout.x_floor + 0.7 * w)
        elif layout.variant == "floor":
            self._build_floor()
        else:
            self._build_end_channel()

    def _build_floor(self) -> None:
        """'floor' with ``end = "solid"``: a static floor at the end height (the chain's
        centre line lying on it at ``-H``) the chain piles on."""
        lay = self.layout
        H, rho = lay.H, lay.rho
        ex = self.end[0]
        w = lay.cfg.floor_width
        self.floor_span = (ex - 0.3 * w, ex + 0.7 * w)
        self.floor = static_segment(self.space, (ex - 0.3 * w, -H - rho - 0.005),
                                    (ex + 0.7 * w, -H - rho - 0.005), 0.005,
                                    lay.sim_cfg.chain.friction, SCENERY)
        self.space.add(self.floor)

    def _build_end_channel(self) -> None:
        """'fold', 'open': the end channel's centre line and its walls (with grooves a
        joint guide's, drawn only)."""
        lay = self.layout
        a, H = lay.cfg, lay.H
        ex = self.end[0]
        alphaE = lay.alphaE
        rise = a.xi3 * H if lay.variant == "fold" else 0.0
        self.rise = rise
        lead = 0.1
        cp, self.i_end = end_channel(ex, -H, alphaE, rise, a.channel_radius, lead,
                                     0.5 * lay.L)
        self.channel_lo = cp
        # 'open' with grooves: the turn is a frictionless circular guide of joints
        # (centre of the end channel's bend, radius channel_radius), see OpenTail
        Rc = a.channel_radius
        self.guide_centre = (ex + Rc * math.sin(alphaE), -H + Rc * math.cos(alphaE))
        self.guide_radius = Rc
        if lay.variant == "open":
            self._build_catch(cp)
        else:
            self._build_funnel(cp)
        self.y_lo = float(cp[-1, 1])
        self.x_exit = float(cp[-1, 0])
        self.x_plate_lo_start = self.guide_centre[0] if lay.guided else self.x_exit

    def path(self) -> list[np.ndarray]:
        """The chain's path through the end channel from its mouth on (empty for
        'floor')."""
        if self.channel_lo is None:
            return []
        return [self.channel_lo[self.i_end + 1:]]

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
        off = self.layout.rho + CLEAR + WALL_R
        outer = Channel(cp).walls(off)[1]
        top = outer[0] - CATCH[0] * t0 - CATCH[1] * n0
        self.walls += static_polyline(self.space, np.vstack((top, outer)), WALL_R,
                                      add=not self.layout.guided)

    def _build_funnel(self, cp: np.ndarray) -> None:
        """'fold': both walls of the end channel with a funnel before the mouth (the
        landing angle wanders by a few degrees and a link arriving on a blunt wall end
        jams the chain; seen in 'open' runs). With grooves the lower channel is a
        frictionless joint guide (:mod:`.fold`) and its walls are drawn only."""
        t0, n0 = self._mouth_frame(cp)
        off = self.layout.rho + CLEAR + WALL_R
        fold_guided = self.layout.fold_guided
        for wl, side in zip(Channel(cp).walls(off), (1.0, -1.0), strict=True):
            flare = wl[0] - FUNNEL[0] * t0 + side * FUNNEL[1] * n0
            segs = static_polyline(self.space, np.vstack((flare, wl)), WALL_R,
                                   add=not fold_guided)
            self.end_walls += segs
            self.walls += segs

    def shift(self, dx: float) -> None:
        """Move the fountain end and the end channel's centre line by ``dx`` along x (a
        following end guide; its drawn walls follow when read,
        :meth:`~.follow.FollowingEnd.sync_end_walls`)."""
        self.end = (self.end[0] + dx, self.end[1])
        if self.channel_lo is not None:
            self.channel_lo[:, 0] += dx
