"""The apparatus's layout: the level's figures every part reads and the positions
derived from them before anything is built (the predicted fountain, the heights of the
upper part and the upper channel's centre line), as one frozen :class:`Layout`."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from chainfountain.sim.apparatus.tuning import Tuning
from chainfountain.sim.config import ApparatusConfig, SimConfig
from chainfountain.sim.guide import upper_channel

if TYPE_CHECKING:
    from chainfountain.theory import Fountain


@dataclass(frozen=True, eq=False)
class Layout:
    """What the parts share: the level's figures (SI units) and the positions the build
    starts from. Frame as in :mod:`chainfountain.sim.apparatus`: the fountain start is
    the origin, ``y`` up, the chain flies in ``+x``."""

    sim_cfg: SimConfig
    cfg: ApparatusConfig
    """The level's ``apparatus`` table (the live setters change its losses in place)."""
    g: float
    h: float
    """pymunk's step (s): ``solver.dt / solver.substeps``. The bookkeeping runs once per
    ``solver.dt``; forces apply in every pymunk step."""
    release_every_step: bool
    """Whether the upper joint guide lets links go in every pymunk step as well
    (:meth:`~.upper_guide.UpperJointGuide.release`)."""
    L: float
    rho: float
    r: float
    r_lo: float
    """Radius (m) of the folding roller ('fold'; ``apparatus.fold_roller_radius``)."""
    R_lo: float
    """Radius (m) of the chain's centre line on the folding roller."""
    gripped: bool
    """The folding roller holds the chain by joints (:mod:`.grip`), not by contact."""
    H: float
    alpha0: float
    launch_u: tuple[float, float]
    variant: str
    n_ahead: int
    """Resting links kept in the solver ahead of the pick-up roller."""
    floor_depth: float
    """Depth (m) of the absorbing floor below the fountain end ('floor' variant)."""
    from_rest: bool
    """The chain starts at rest with a stub at the start, run up by the starter
    (:mod:`.starter`); else it starts laid along its path, moving."""
    threads: bool
    """From rest in 'fold': the chain ends inside the upper guide, and the starter
    threads its head through the end guide and round the folding roller."""
    stub_length: float
    v_lay: float
    """The speed (m/s) the chain is laid moving at."""
    fountain: Fountain
    """The predicted fountain (the layout; it aims the end channel)."""
    vertex_pred: tuple[float, float]
    end: tuple[float, float]
    """The predicted fountain end (m), where the level puts the end channel's mouth."""
    x_floor: float
    """x where the catenary, continued below the end, meets the floor ('floor')."""
    alphaE: float
    """Landing angle (rad) of the predicted fountain at its end."""
    y_up: float
    """Chain centre line on top of the pick-up roller (m): ``-xi2*H``."""
    y_table_up: float
    channel_up: np.ndarray
    """The upper channel's centre line (plate end to the start)."""
    R_up: float
    x_plate_up_end: float
    treadmill: bool
    """The plate strands are held at about ``plate_links`` links (:mod:`.treadmill`)."""
    plate_mode: str
    upper_guided: bool
    """The upper channel is a frictionless joint guide; its walls are drawn only."""
    end_mode: str
    """``apparatus.end`` for 'floor' ('absorbing' or 'solid'), else 'channel'."""
    guided: bool
    """'open' with ``plate = "groove"``: the turn after landing is a joint guide."""
    fold_guided: bool
    """'fold' with ``plate = "groove"``: the lower channel (turn, rise, turn) and the
    lower plate are a frictionless joint guide."""
    end_follow: float
    """Rate (1/s) at which the end guide follows the landing; 0: it stays put."""

    @classmethod
    def of(cls, chain_L: float, cfg: SimConfig, tuning: Tuning) -> Layout:
        """The layout of ``cfg``'s apparatus for a chain of link length ``chain_L``. A
        floor ``d`` below the end adds the hanging strand's weight to the predicted
        fountain: ``Tbar_E = g*d/v**2``."""
        from chainfountain.theory import Fountain

        a = cfg.apparatus
        g = float(cfg.gravity)
        rho = float(cfg.chain.link_radius)
        r = float(a.roller_radius)
        r_lo = float(a.fold_roller_radius) or r
        H = float(a.drop)
        alpha0 = float(a.launch_angle)
        variant = a.variant
        floor_depth = float(a.floor_depth) if variant == "floor" else 0.0
        from_rest = cfg.initial.mode == "stub"
        v_lay = 0.0 if from_rest or tuning.lay_at_rest else float(a.speed)
        # the predicted fountain
        v0 = float(a.speed)
        TE_lay = float(a.end_tension) + g * floor_depth / v0**2
        f = Fountain.from_launch(v=v0, alpha0=alpha0, H=H, TE_bar=TE_lay, g=g)
        x_rise = math.acosh(1.0 + f.q * f.h) / f.q
        end = (x_rise + math.acosh(1.0 + f.q * (f.h + H)) / f.q, -H)
        x_floor = x_rise + math.acosh(1.0 + f.q * (f.h + H + floor_depth)) / f.q
        # the upper part's heights and channel
        y_up = -a.xi2 * H
        ch_pts, R_up = upper_channel(H, a.xi2, alpha0, a.channel_radius, 0.1, 0.5 * chain_L)
        fold_guided = variant == "fold" and a.plate == "groove"
        return cls(
            sim_cfg=cfg, cfg=a, g=g,
            h=float(cfg.solver.dt) / int(cfg.solver.substeps),
            release_every_step=int(cfg.solver.substeps) > 1 and a.upper_guide == "joints",
            L=chain_L, rho=rho, r=r, r_lo=r_lo, R_lo=r_lo + rho,
            gripped=variant == "fold" and a.fold_roller == "gripped",
            H=H, alpha0=alpha0, launch_u=(math.cos(alpha0), math.sin(alpha0)),
            variant=variant, n_ahead=int(a.pickup_rest_links or a.rest_links),
            floor_depth=floor_depth, from_rest=from_rest,
            threads=from_rest and variant == "fold",
            stub_length=float(cfg.initial.stub_length), v_lay=v_lay,
            fountain=f, vertex_pred=(x_rise, f.h), end=end, x_floor=x_floor,
            alphaE=math.atan(math.sinh(f.q * (end[0] - x_rise))),
            y_up=y_up, y_table_up=y_up - 3.0 * rho - 2.0 * r,
            channel_up=ch_pts, R_up=R_up, x_plate_up_end=float(ch_pts[0, 0]),
            treadmill=a.plate_links > 0 and a.plate == "groove",
            plate_mode=a.plate, upper_guided=a.upper_guide == "joints",
            end_mode=a.end if variant == "floor" else "channel",
            guided=variant == "open" and a.plate == "groove",
            fold_guided=fold_guided,
            end_follow=float(a.end_follow) if fold_guided else 0.0)

    def table_travel(self) -> float:
        """Distance (m) a roller rolls in ``apparatus.duration`` at the start speed, with
        15 cm to spare: the length of table a run needs without a treadmill."""
        a = self.cfg
        v0 = float(a.speed)
        return 0.5 * v0 * a.duration + 0.15
