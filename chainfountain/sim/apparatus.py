"""The paper's pulley apparatus (section "Generating Steady-State Chain Fountains").

Built by :class:`~chainfountain.sim.world.Simulation` for ``kind = "apparatus"``
(:class:`~chainfountain.sim.config.ApparatusConfig`). Frame: the fountain start
(exit of the upper guide channel) is the origin, ``y`` up, the chain flies in
``+x``; the fountain end is ``H`` below the start.

Path of the chain, upstream to downstream (chain order is the reverse: index 0
is the downstream end, as for the feed):

1. **Upper table** (rough, friction ``table_friction``), the chain resting on
   it in ``-x`` direction toward the pick-up roller. Only ``pickup_rest_links``
   (or ``rest_links``) links ahead of the roller are in the solver; further links
   are added at rest at the upstream end as the roller approaches (they carry no
   force: the tension of the unfolding goes into the table through friction right
   at the roller).
2. **Pick-up roller** (alpha = 0, as ``docs/apparatus.md`` recommends): a
   dynamic disc resting on the chain under its weight, on a carriage that
   slides on a horizontal groove (vertical play through a slot). The chain
   comes off the table at the bottom contact, wraps around the back of the
   roller and leaves on top in ``+x``, the roller following at ``v/2``
   (paper: ``v_R = v/(1 + cos alpha)``). The upper cart is the rope-tied
   weight of :mod:`chainfountain.sim.pickup`: a constant force
   ``m*g*sin(beta)`` on the carriage against its motion, the cart mass added to
   the carriage (an ideal rope over an ideal pulley to a cart on an incline).
3. **Upper plate**: a frictionless static segment at the roller-top height
   carrying the strand from the roller to the channel (without it the strand,
   at ``T < lambda*v**2``, would sag onto the resting chain). Its roller end
   follows the roller every step.
4. **Upper channel**: frictionless two-sided guide (static segment walls with
   a small clearance), horizontal, then a bend of radius ``channel_radius`` up
   to ``alpha0`` and straight to the start: rise ``xi2*H`` from the roller top.
5. **Fountain**: free flight.
6. By variant: ``floor``: a solid floor at the end height (the chain centre
   line lying on it is at ``-H``), the chain piles and the oldest lying links
   leave the solver; ``fold``: an end channel whose mouth sits on the predicted
   fountain end, aligned with the landing tangent, turns the chain and lifts it
   ``xi3*H`` onto the lower plate; the folding roller (mirror image of the
   pick-up: moving in ``+x`` at ``v/2``, the chain wraps around its front) lays
   it onto the lower table, pushed forward by the lower cart; ``open``: the end
   channel turns the chain horizontal and it slides away on a long
   frictionless plate (with ``plate = "groove"``: a frictionless joint guide,
   slide joints to the bend centre then plate grooves, the tail beyond 30
   links lumped into the end link; the moving mass grows at ``lambda*v/2``).

Heights: ``y_up = -xi2*H`` (chain centre line on top of the upper roller),
``y_lo = -H + xi3*H`` (same for the lower roller): the paper's "beaker" and
"bottom". Link radius ``rho``, roller radius ``r``: the table top lies
``3*rho + 2*r`` below the roller-top centre line.

The channels' centre lines and the joint-guide pieces are in
:mod:`chainfountain.sim.guide`; measuring a run (tensions along the path,
``summary.json``'s ``apparatus`` object) is in :mod:`chainfountain.sim.apparatus_report`.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

import numpy as np
import pymunk

from chainfountain.errors import RunEnded
from chainfountain.sim import fastbody
from chainfountain.sim.bodies import SCENERY_CATEGORY
from chainfountain.sim.chain import CHAIN_CATEGORY, Chain, Link
from chainfountain.sim.config import CartConfig, SimConfig
from chainfountain.sim.fastbody import pos
from chainfountain.sim.guide import (
    GUIDE_BIAS,
    PLAY,
    Channel,
    GuideElement,
    end_channel,
    end_channel_bends,
    resample,
    upper_channel,
    upper_guide,
)

PICKUP_BAR = 0.27
"""Measured pick-up force at alpha = 0 over ``lambda*v**2`` (``docs/apparatus.md``;
paper: 1/2, loss-free energy balance 1/4)."""
PUTDOWN_BAR = 0.24
"""Measured put-down force at alpha = 0 over ``lambda*v**2`` with a forward push,
extrapolated to no push (``docs/apparatus.md``; by pivots 0.244 + 0.50*Fbar_c, the
loss-free 1/4 + Fbar_c/2; paper: 1/2 + Fbar_c)."""

PICKUP_RIG_2CM = (0.266, 0.0230)
"""Pick-up (unfolding) exit tension at alpha = 0 with the apparatus presets' chain (2 cm
rod links, ``lambda`` = :data:`RIG_2CM_LAMBDA`, friction 0.6, 20 g roller, dt 0.5 ms, 10
iterations), ``(p_inf, R)`` of ``Tbar = p_inf + R/(lambda*v**2) + G*Fbar_c`` with ``R``
in N: a loss-free unfolding (1/4) with a little discretisation excess, a
speed-independent rolling resistance ``R`` and the cart term (:data:`CART_GAIN_2CM`).
Weighted fit to 19 rig runs of 6 s at 2.6-5.1 m/s and ``Fbar_c`` 0-0.5
(``research/pickup_study.py --pickup-2cm-law``; ``docs/apparatus.md``), read through the
contacts with pymunk's stale impulses of re-touching contacts taken out
(:meth:`~chainfountain.sim.measure.ChainReader.arm`)."""
RIG_2CM_LAMBDA = 0.05
"""Linear density (kg/m) of the chain :data:`PICKUP_RIG_2CM` was measured with."""
PICKUP_RIG_2CM_ERR = 0.002
"""Standard uncertainty of :func:`pickup_rig_2cm` at 2.6-3.2 m/s (0.003 at 5.1 m/s), from
the fit's covariance scaled by its chi2/dof of 6.5 (the single runs scatter by 0.0065)."""
CART_GAIN_2CM = 0.526
"""Rise of the pick-up exit tension per unit cart force in the same fit (the paper: 1;
the loss-free power balance ``F_c v_R/v``: 1/2). No curvature: a ``sqrt(Fbar_c)`` or
``Fbar_c**2`` term fits as 0.014 +- 0.018 and -0.04 +- 0.06."""
CART_GAIN_2CM_ERR = 0.010

PUTDOWN_RIG_2CM = (0.172, 0.618)
"""Put-down (folding) entry tension at alpha = 0 with 2 cm links: ``Tbar = d + G_d*Fbar_c``
(intercept ``d``, cart gain ``G_d``), fitted to rig runs at 3 m/s, dt 0.5 ms, 10
iterations, ``Fbar_c = 0.3, 0.4, 0.5`` (3-s averages, about +-0.02 each; the strand
tension from the pivot forces, ``research/pickup_study.py --putdown-2cm``;
``docs/apparatus.md``). Below ``Fbar_c`` of about 0.25 the roller falls behind and the
chain piles up (not steady). Read through the rig's contacts with pymunk's stale
impulses taken out, the same runs give 0.354 / 0.419 / 0.472 against the pivots' 0.357 /
0.422 / 0.481; with the stale impulses left in, the contacts overstate the tension
under a cart."""


def pickup_rig_2cm(v: float) -> float:
    """:data:`PICKUP_RIG_2CM` at chain speed ``v`` (m/s), no cart: ``p_inf + R/(lambda
    v**2)``."""
    p_inf, R = PICKUP_RIG_2CM
    return p_inf + R / (RIG_2CM_LAMBDA * v * v)


def pickup_rig_2cm_drag(v: float, lam: float) -> float:
    """``d(p(v)*lambda*v**2)/dv`` of :data:`PICKUP_RIG_2CM` at speed ``v`` (N s/m): how
    fast the pick-up's exit tension rises with the chain speed, the cart aside. The
    rolling resistance does not depend on the speed, so this is ``2*p_inf*lambda*v``."""
    return 2.0 * PICKUP_RIG_2CM[0] * lam * v


def rig_exit_tension(v: float, lam: float, F_uc: float) -> float:
    """Pick-up exit tension (N) the 2 cm rig law gives at chain speed ``v`` (m/s), linear
    density ``lam`` and cart force ``F_uc`` (N): ``p(v) lambda v**2 + G F_uc``
    (:func:`pickup_rig_2cm`, :data:`CART_GAIN_2CM`; paper ``(1/2 + Tbar_uc) lambda v**2``)."""
    return pickup_rig_2cm(v) * lam * v * v + CART_GAIN_2CM * F_uc


def selected_speed(g: float, H: float, xi2: float, F_uc: float, lam: float,
                   p: float | None = None, gain: float = 1.0, dp: float = 0.0) -> float:
    """Speed a free-ended ('floor', Tbar_E = 0) apparatus selects.

    Steady state needs the fountain's ``Tbar_0 = Tbar_E + k*H = k*H`` (paper: along
    the catenary ``Tbar_0 - Tbar_E = k*H``) to equal the mechanism's
    ``Tbar_0 = p + G*Tbar_uc + xi2*k*H`` (paper, apparatus section, with the pick-up
    intercept ``p`` and cart gain ``G``; paper ``p = 1/2``, ``G = 1``), so
    ``v**2 = (g*H*(1 - xi2) - G*F_uc/lambda)/p``. With ``p=None`` the rig law
    :func:`pickup_rig_2cm` ``+ dp`` is used, ``p_inf + dp + R/(lambda_rig v**2)``:
    ``v**2 = (g*H*(1 - xi2) - G*F_uc/lambda - R/lambda_rig)/(p_inf + dp)``. nan if
    there is no positive root.
    """
    num = g * H * (1.0 - xi2) - gain * F_uc / lam
    if p is None:
        p_inf, R = PICKUP_RIG_2CM
        num -= R / RIG_2CM_LAMBDA
        p = p_inf + dp
    if num <= 0 or p <= 0:
        return math.nan
    return math.sqrt(num / p)


_WALL_R = 0.002
"""Radius of channel wall segments (m)."""
_FUNNEL = (0.06, 0.02)
"""Length and half-opening (m) of the funnel before the end channel's mouth."""
_CATCH = (0.05, 0.0)
"""Length along the landing tangent and outward flare (m) by which the 'open' variant's
one-sided catch wall reaches up above the end channel's mouth (the fountain above its
end lies outside the tangent, on the catenary's convex side)."""
_CAPTURE = (0.02, math.radians(3.0))
"""'open' joint guide: capture band (m) around the turn's radius and angular margin
before the mouth (rad) within which a falling link is taken into the guide."""
_CLOSE_RATE = 0.2
"""Speed (m/s) at which the outer limit of a link captured outside the 'open' guide's
radius closes in to it."""
_FOLD_CAPTURE = (0.06, math.radians(3.0))
"""'fold' joint guide: capture band (m) and angular margin (rad) of the first turn.
Wider than 'open''s: the fountain's landing point wanders by several centimetres
(docs/apparatus.md), and a link captured off the radius
is held there (its limits close in at :data:`_FOLD_CLOSE_RATE`), so a wide band costs
nothing while the chain lands on the radius."""
_FOLD_CLOSE_RATE = 5.0
"""Speed (m/s) at which the limits of a link captured off the 'fold' turn's radius
close in to ``R -+ PLAY``: a 6-cm offset closes in 12 ms, while the link moves
about two link lengths, so the catch acts as a stiff funnel at the mouth. Measured
(docs/apparatus.md): at a close rate of 0.5 m/s the landing point's oscillation grew
until the catch was lost at about 4.3 s (both treadmills on); at 2, 5 and 20 m/s the
run held to 8 s, at 5 m/s to about 13 s."""
_TAIL_KEEP = 30
"""'open': links kept in the lower plate grooves; the tail beyond is lumped into the
end link (:meth:`Apparatus._lump_tail`)."""
_LO_START = 0.15
"""'fold': start distance (m) of the folding roller from the end channel's exit."""
_COLLAPSE_TIME = 0.05
"""'fold': the run ends (:class:`FoldCollapsed`) once the folding roller has rolled
backwards for this long (s). In the shipped fold presets it never does (it rolls
forward at about ``v/2`` throughout); without a forward push it falls behind at once
and rolls back within about 1 s (``apparatus_limit``, docs/apparatus.md)."""
_FOLD_RELEASE = 0.5
"""'fold' with grooves: a lower-plate link leaves its groove (and gets its collision shape
back) once its centre is this many link lengths before the folding roller's top."""
_FOLD_DT_MIN = 3.5e-4
"""'fold': smallest solver step (s) at which this model's fold was measured to hold.
The fold is not converged in the step: ``apparatus_fold`` and ``apparatus_special``
hold for 3 s at dt 0.35-0.5 ms, lose their folding roller at about 2.1 s at 0.25 ms
(``apparatus_special`` with its joint guide: at 0.65 s) and within 0.2 s at 0.1 ms
(docs/apparatus.md); the put-down rig alone is converged down to 0.03 ms. With
``fold_clearance = 0`` only: the cause is the folding roller locking between the plate
grooves and the table."""
_HELD = 0.1
"""'fold': the folding roller counts as holding the chain while ``|v_R/v - 1/2|`` is at
most this (the collapse message tells a fold that never held from one that held and was
then lost)."""
_SWING_EVERY, _SWING_SAMPLES = 0.05, 100
"""'fold': sampling interval (s) and count of the speed history the collapse message
reads the speed swing from (the last 5 s in which the fold held)."""
_LATE_COLLAPSE = 2.0
"""'fold': a collapse after the folding roller has held the chain this long (s) is
reported as the landing swing's, not as a missing push (docs/apparatus.md)."""
_CATCH_LOST = 0.1
"""'fold': a collapse this long (s) or longer after the last link entered the end guide
through its mouth (normally one does every ``L/v``, about 7 ms) was preceded by a lost
catch, and the collapse message says so (docs/apparatus.md)."""
_PRELOAD_STEPS = 40
"""Treadmill: a joint made in the tensioned plate strand starts with the tension of the
joint it replaces as an internal force pair, faded out over this many steps (the
solver's warm start then carries it; in 'fold' trials a cold joint in a plate strand
every 13 steps made the lower turn yield sooner)."""
_UP_RELEASE = 0.5
"""Upper joint guide: a link leaves the guide's straight once its centre is this many
link lengths short of the fountain start, i.e. once its front joint has left the guide,
so the free fountain starts at ``(0, 0)`` as with the channel's walls. Measured
(``apparatus_floor``, 2-6 s; docs/apparatus.md): the vertex is
+5.4 % off the catenary through the ends when links leave at their centre (0), +0.1 %
at 0.5, -1.6 % at 0.6, -6.0 % at 1 (the walls: +1.7 %)."""
_CLEAR = 0.0008
"""Clearance between a link capsule and each channel wall (m)."""
_ONLY_CHAIN = pymunk.ShapeFilter(categories=SCENERY_CATEGORY, mask=CHAIN_CATEGORY)


class TableUsedUp(RunEnded):
    """The pick-up roller has reached the upper channel: the run has outgrown the
    upper table (raised by :meth:`Apparatus.after_step`; the app pauses on it, the
    CLI writes what was simulated and says so)."""


class FoldCollapsed(RunEnded):
    """'fold': the folding roller has rolled backwards for :data:`_COLLAPSE_TIME`: the
    put-down has failed, the chain piles up in the lower guide and the fountain falls
    out of its catch (raised by :meth:`Apparatus.after_step`)."""


# ----------------------------------------------------------------------------- bodies
@dataclass(eq=False)
class RollerUnit:
    """A roller on a carriage (horizontal groove, vertical slot) pushed by a cart force."""

    roller: pymunk.Body
    carriage: pymunk.Body
    shape: pymunk.Circle
    direction: float
    """Force direction on the carriage: -1 holds back (pick-up), +1 pushes (fold)."""
    cart: CartConfig | None
    g: float
    yc: float
    """Height of the roller centre at rest on the chain (m)."""

    @property
    def force(self) -> float:
        """Cart force ``m*g*sin(beta)`` (N), >= 0 along :attr:`direction`."""
        c = self.cart
        return 0.0 if c is None else c.mass * self.g * math.sin(c.incline)

    def set_cart_mass(self, m: float, base: float) -> None:
        """Change the cart mass live (the carriage carries it)."""
        if self.cart is not None:
            self.cart.mass = float(m)
        self.carriage.mass = base + (0.0 if self.cart is None else self.cart.mass)

    @property
    def x(self) -> float:
        return pos(self.roller).x

    @property
    def speed(self) -> float:
        """Carriage velocity along ``x`` (m/s; read every step by the fold's collapse check)."""
        return float(fastbody.get_velocity(fastbody.handle(self.carriage)).x)


def _add_roller(space: pymunk.Space, x: float, y_table: float, rho: float, r: float,
                m_roller: float, m_carriage: float, cart: CartConfig | None, direction: float,
                g: float, error_bias: float, vx: float, omega: float) -> RollerUnit:
    yc = y_table + 2.0 * rho + r
    m_c = m_carriage + (cart.mass if cart is not None else 0.0)
    carriage = pymunk.Body(m_c, float("inf"))
    carriage.position = (x, yc)
    groove = pymunk.GrooveJoint(space.static_body, carriage, (x - 1e3, yc), (x + 1e3, yc),
                                (0.0, 0.0))
    roller = pymunk.Body(m_roller, 0.5 * m_roller * r * r)
    roller.position = (x, yc)
    slot = pymunk.GrooveJoint(carriage, roller, (0.0, -0.5 * r), (0.0, 0.5 * r), (0.0, 0.0))
    for j in (groove, slot):
        j.error_bias = error_bias
    circ = pymunk.Circle(roller, r)
    circ.friction = 1.0
    circ.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
    carriage.velocity = (vx, 0.0)
    roller.velocity = (vx, 0.0)
    roller.angular_velocity = omega
    space.add(carriage, groove, roller, slot, circ)
    return RollerUnit(roller=roller, carriage=carriage, shape=circ, direction=direction,
                      cart=cart, g=g, yc=yc)


def _static_polyline(space: pymunk.Space, pts: np.ndarray, radius: float,
                     friction: float = 0.0, add: bool = True) -> list[pymunk.Segment]:
    out = []
    b = space.static_body
    for i in range(len(pts) - 1):
        s = pymunk.Segment(b, tuple(pts[i]), tuple(pts[i + 1]), radius)
        s.friction = friction
        s.filter = _ONLY_CHAIN
        out.append(s)
    for i, s in enumerate(out):
        prev = pts[i - 1] if i > 0 else pts[i]
        nxt = pts[i + 2] if i + 2 < len(pts) else pts[i + 1]
        s.set_neighbors(tuple(prev), tuple(nxt))
    if add:
        space.add(*out)
    return out


# ----------------------------------------------------------------------------- apparatus
class Apparatus:
    """Builds the apparatus into a space and keeps its bookkeeping (duck-types the
    :class:`~chainfountain.sim.feed.Feed` interface the simulation uses).

    Attributes give the geometry for views and measurements: ``upper``/``lower``
    (:class:`RollerUnit`), ``y_up``/``y_lo`` (roller-top centre lines), ``end``
    (fountain end point), ``launch_u`` (unit launch direction), ``walls``
    (static segments), ``fountain`` (the predicted fountain used for the layout).
    """

    def __init__(self, space: pymunk.Space, chain: Chain, cfg: SimConfig) -> None:
        from chainfountain.theory import Fountain

        self.space = space
        self.chain = chain
        self.sim_cfg = cfg
        a = self.cfg = cfg.apparatus
        self.g = float(cfg.gravity)
        L = chain.L
        self.L = L
        rho = self.rho = float(cfg.chain.link_radius)
        r = self.r = float(a.roller_radius)
        H = self.H = float(a.drop)
        v0 = float(a.speed)
        self.alpha0 = float(a.launch_angle)
        self.launch_u = (math.cos(self.alpha0), math.sin(self.alpha0))
        self.variant = a.variant
        self.n_ahead = int(a.pickup_rest_links or a.rest_links)
        """Resting links kept in the solver ahead of the pick-up roller."""
        step = 0.5 * L
        eb = cfg.solver.joint_error_bias
        carts = list(cfg.carts)
        self.absorbed = 0
        self.added = 0
        self.floor_depth = float(a.floor_depth) if self.variant == "floor" else 0.0
        """Depth (m) of the absorbing floor below the fountain end ('floor' variant)."""
        # predicted fountain (layout, aiming the end channel); a floor ``d`` below the
        # end adds the hanging strand's weight: Tbar_E = g*d/v**2
        TE_lay = float(a.end_tension) + self.g * self.floor_depth / v0**2
        self.fountain = Fountain.from_launch(v=v0, alpha0=self.alpha0, H=H,
                                             TE_bar=TE_lay, g=self.g)
        f = self.fountain
        x_rise = math.acosh(1.0 + f.q * f.h) / f.q
        self.vertex_pred = (x_rise, f.h)
        self.end = (x_rise + math.acosh(1.0 + f.q * (f.h + H)) / f.q, -H)
        self.x_floor = x_rise + math.acosh(1.0 + f.q * (f.h + H + self.floor_depth)) / f.q
        """x where the catenary, continued below the end, meets the floor ('floor')."""
        # ---- upper part
        self.y_up = -a.xi2 * H
        y_tab = self.y_up - 3.0 * rho - 2.0 * r
        self.y_table_up = y_tab
        ch_pts, self.R_up = upper_channel(H, a.xi2, self.alpha0, a.channel_radius, 0.1, step)
        self.x_plate_up_end = float(ch_pts[0, 0])
        self.treadmill = a.plate_links > 0 and a.plate == "groove"
        """The upper plate strand is held at about ``plate_links`` links
        (:meth:`_treadmill_upper`)."""
        travel_lo = travel = 0.5 * v0 * a.duration + 0.15
        if self.treadmill:  # at least 15 cm: the table check below keeps a 5-cm margin
            travel = max((int(a.plate_links) + 2) * L, 0.15)
        x_R = self.x_plate_up_end - travel
        vR = 0.5 * v0
        R = r + rho
        self.upper = _add_roller(space, x_R, y_tab, rho, r, a.roller_mass, a.carriage_mass,
                                 carts[0] if carts else None, -1.0, self.g, eb, vR, -vR / R)
        self.table_up = pymunk.Segment(space.static_body, (x_R - 1.0, y_tab - 0.01),
                                       (self.x_plate_up_end, y_tab - 0.01), 0.01)
        self.table_up.friction = a.table_friction
        self.table_up.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
        space.add(self.table_up)
        self.plate_up = pymunk.Segment(space.static_body, (x_R + 0.5 * L, self.y_up - rho - 0.002),
                                       (self.x_plate_up_end, self.y_up - rho - 0.002), 0.002)
        self.plate_up.friction = 0.0
        self.plate_up.filter = _ONLY_CHAIN
        self.plate_mode = a.plate
        if self.plate_mode == "contact":
            space.add(self.plate_up)
        self._grooves: deque[tuple[Link, pymunk.GrooveJoint]] = deque()
        self._g_next = -1
        """Chain index of the next link to put into a plate groove (``plate = "groove"``)."""
        self.walls: list[pymunk.Segment] = []
        off = rho + _CLEAR + _WALL_R
        ch = Channel(ch_pts)
        self.upper_guided = a.upper_guide == "joints"
        """The upper channel is a frictionless joint guide (:attr:`up_guide`); its walls
        are drawn only."""
        if self.upper_guided and a.plate != "groove":  # the level check says so too
            raise ValueError("apparatus.upper_guide: 'joints' needs apparatus.plate = 'groove' "
                             f"(it is {a.plate!r}); allowed: 'walls' with a 'contact' plate")
        for w in ch.walls(off):
            self.walls += _static_polyline(space, w, _WALL_R, add=not self.upper_guided)
        self.channel_up = ch_pts
        self.up_guide: list[GuideElement] = (
            upper_guide(H, a.xi2, self.alpha0, a.channel_radius, 0.1) if self.upper_guided
            else [])
        self._uq: list[deque[tuple[Link, pymunk.Constraint]]] = [
            deque() for _ in self.up_guide]
        """Upper joint guide: links held by each element (most downstream first)."""
        # ---- path (upstream -> downstream) with per-point speed tags
        yc = self.upper.yc
        n_rest = self.n_ahead
        rest_end = x_R + n_rest * L
        parts: list[np.ndarray] = [np.array([[rest_end, y_tab + rho], [x_R, y_tab + rho]])]
        th = np.linspace(1.5 * math.pi, 0.5 * math.pi, 60)[1:]
        parts.append(np.column_stack((x_R + R * np.cos(th), yc + R * np.sin(th))))
        parts.append(np.array([[self.x_plate_up_end, self.y_up]]))
        parts.append(ch_pts[1:])
        s_wrap0 = n_rest * L
        s_wrap1 = s_wrap0 + math.pi * R
        # fountain
        ex, ey = self.end
        xs = np.linspace(0.0, self.x_floor, 400)[1:]  # x_floor = ex without a floor_depth
        parts.append(np.column_stack((xs, f.h + f.y_of_x(xs - x_rise))))
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
        self.guide_centre = (math.nan, math.nan)
        self.guide_radius = math.nan
        alphaE = math.atan(math.sinh(f.q * (ex - x_rise)))
        self.alphaE = alphaE
        s_lo_wrap = math.inf
        self.end_mode = a.end if self.variant == "floor" else "channel"
        if self.end_mode == "absorbing":
            w = a.floor_width
            self.floor_span = (self.x_floor - 0.3 * w, self.x_floor + 0.7 * w)
        elif self.variant == "floor":
            w = a.floor_width
            self.floor_span = (ex - 0.3 * w, ex + 0.7 * w)
            self.floor = pymunk.Segment(space.static_body, (ex - 0.3 * w, -H - rho - 0.005),
                                        (ex + 0.7 * w, -H - rho - 0.005), 0.005)
            self.floor.friction = cfg.chain.friction
            self.floor.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
            space.add(self.floor)
        else:
            rise = a.xi3 * H if self.variant == "fold" else 0.0
            lead = 0.1
            cp, self.i_end = end_channel(ex, -H, alphaE, rise, a.channel_radius, lead, step)
            self.channel_lo = cp
            # funnel before the mouth: the landing angle wanders by a few degrees and a
            # link arriving on a blunt wall end jams the chain (seen in 'open' runs)
            t0 = (cp[1] - cp[0]) / np.linalg.norm(cp[1] - cp[0])
            n0 = np.array([-t0[1], t0[0]])
            # 'open' with grooves: the turn is a frictionless circular guide of joints
            # (centre of the end channel's bend, radius channel_radius), see _update_guide
            Rc = a.channel_radius
            self.guide_centre = (ex + Rc * math.sin(alphaE), -H + Rc * math.cos(alphaE))
            self.guide_radius = Rc
            self.guided = self.variant == "open" and a.plate == "groove"
            if self.variant == "open":
                # one-sided catch: only the outer wall of the turn (the chain, at
                # T < lambda*v**2, presses on it), flared up and out above the mouth;
                # no inner wall and no mouth lip the falling chain could hook on
                # (drawn only when the joint guide is used)
                outer = Channel(cp).walls(off)[1]
                top = outer[0] - _CATCH[0] * t0 - _CATCH[1] * n0
                self.walls += _static_polyline(space, np.vstack((top, outer)), _WALL_R,
                                               add=not self.guided)
            else:
                # with grooves: the lower channel is a frictionless joint guide
                # (GuideElement); its walls are drawn only
                self.fold_guided = a.plate == "groove"
                for wl, side in zip(Channel(cp).walls(off), (1.0, -1.0), strict=True):
                    flare = wl[0] - _FUNNEL[0] * t0 + side * _FUNNEL[1] * n0
                    self.walls += _static_polyline(space, np.vstack((flare, wl)), _WALL_R,
                                                   add=not self.fold_guided)
            self.y_lo = float(cp[-1, 1])
            xl = float(cp[-1, 0])
            self.x_plate_lo_start = self.guide_centre[0] if self.guided else xl
            parts.append(cp[self.i_end + 1:])
            if self.variant == "open":
                far = xl + v0 * a.duration * 1.5 + 1.0
                self.plate_lo = pymunk.Segment(space.static_body, (xl, self.y_lo - rho - 0.002),
                                               (far, self.y_lo - rho - 0.002), 0.002)
                self.plate_lo.friction = 0.0
                self.plate_lo.filter = _ONLY_CHAIN
                self.far_lo = far
                if a.plate == "contact":
                    space.add(self.plate_lo)
                parts.append(np.array([[xl + 0.2, self.y_lo]]))
            else:
                x_lo = xl + (max(_LO_START, (a.plate_links + 2) * L) if self.treadmill
                             else _LO_START)
                ylt = self.y_lo - 3.0 * rho - 2.0 * r
                if a.plate == "groove":
                    ylt -= a.fold_clearance
                self.y_table_lo = ylt
                self.lower = _add_roller(space, x_lo, ylt, rho, r, a.roller_mass,
                                         a.carriage_mass, carts[1] if len(carts) > 1 else None,
                                         1.0, self.g, eb, vR, -vR / R)
                self.table_lo = pymunk.Segment(
                    space.static_body, (xl - 0.5, ylt - 0.01),
                    (x_lo + travel_lo + 1.0, ylt - 0.01), 0.01)
                self.table_lo.friction = a.table_friction
                self.table_lo.filter = pymunk.ShapeFilter(categories=SCENERY_CATEGORY)
                space.add(self.table_lo)
                self.plate_lo = pymunk.Segment(
                    space.static_body, (xl, self.y_lo - rho - 0.002),
                    (x_lo - 0.5 * L, self.y_lo - rho - 0.002), 0.002)
                self.plate_lo.friction = 0.0
                self.plate_lo.filter = _ONLY_CHAIN
                if not self.fold_guided:
                    space.add(self.plate_lo)
                if self.fold_guided:
                    self.guide = self._fold_guide(ex, alphaE, rise, a.channel_radius,
                                                  x_lo + travel_lo + 1.0)
                ycl = self.lower.yc
                parts.append(np.array([[x_lo, self.y_lo]]))
                th = np.linspace(0.5 * math.pi, -0.5 * math.pi, 60)[1:]
                parts.append(np.column_stack((x_lo + R * np.cos(th), ycl + R * np.sin(th))))
                parts.append(np.array([[x_lo - 0.3, ylt + rho]]))
        path = np.vstack(parts)
        seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
        s_all = np.concatenate([[0.0], np.cumsum(seg)])
        if self.lower is not None:
            # arc length where the lower wrap starts: the point (x_lo, y_lo)
            idx = int(np.flatnonzero(np.isclose(path[:, 0], self.lower.x)
                                     & np.isclose(path[:, 1], self.y_lo))[0])
            s_lo_wrap = float(s_all[idx])
        pts, s = resample(path, L)
        self._lay(pts, s, s_wrap0, s_wrap1, s_lo_wrap, v0, vR, R)
        self.start_x = (self.upper.x, self.lower.x if self.lower is not None else 0.0)
        self.moved_back = 0
        """Treadmill: links added to the upper plate strand."""
        self.shifted = 0.0
        """Treadmill: distance (m) the pick-up roller unit was moved back."""
        self.cut = 0
        """'fold' treadmill: links taken out of the lower plate strand."""
        self.shifted_lo = 0.0
        """'fold' treadmill: distance (m) the folding roller unit was moved back."""
        self._preload: list[list] = []
        """Treadmill: ``[down, up, force N, steps left]`` of joints made in the strand."""
        self._plate_ends = [float(self.plate_up.a.x), float(self.plate_lo.b.x)
                            if self.plate_lo is not None else 0.0]
        """x of the upper plate's start and the lower plate's end (m)."""
        self._sync_plates()
        self._lo_n = 0
        """'open' with ``plate = "groove"``: links ``0 .. _lo_n-1`` (the tail on the lower
        plate) run in frictionless groove joints on the line ``y = y_lo``."""
        self._lo_joints: list[pymunk.GrooveJoint] = []
        self.tail_mass = 0.0
        """'open': mass (kg) of the tail links lumped into the end link (see _lump_tail)."""
        self._t = 0.0
        self._back_t = 0.0
        """How long (s) the folding roller has been rolling backwards without a break."""
        self._held_t = 0.0
        """How long (s) the folding roller has rolled at ``v/2`` (within :data:`_HELD`),
        sampled every :data:`_SWING_EVERY` s."""
        self._held_v: deque[float] = deque(maxlen=_SWING_SAMPLES)
        """Chain speed (m/s) every :data:`_SWING_EVERY` s while the fold held: the speed
        swing the collapse message reports."""
        self._swing_next = 0.0
        self._arc: deque[tuple[Link, pymunk.SlideJoint]] = deque()
        """'open' guide: links ``_lo_n .. _lo_n + len(_arc) - 1`` held on the turn."""
        self._gq: list[deque[tuple[Link, pymunk.Constraint]]] = [deque() for _ in self.guide]
        """'fold' guide: links held by each element (most downstream first)."""
        self._cap_next = -1
        """'fold' guide: chain index of the next link to capture at the mouth."""
        self._mouth_t: float | None = None
        self._mouth_dr = 0.0
        """'fold' guide: time (s) of the last capture through the mouth (at or before its
        angle; later captures take links falling into the turn from the side; None before
        the first) and that link's offset from the turn's radius (m; > 0 outside: the
        fountain landed short). The collapse message says when the catch was lost."""
        self.released = 0
        """'fold' guide: links handed from the lower plate to the folding roller."""
        if self.plate_mode == "groove":
            self._init_grooves()
            self._update_lo_grooves()
        if self.upper_guided:
            self._init_upper_guide()
        self._fly_next = -1
        """'fold' guide: chain index of the next link to leave the upper channel."""
        if self.fold_guided:
            self._init_fold_guide()
            self._fly_next = self._cap_next
            self._update_flight(0)

    # ------------------------------------------------------------------ layout
    def _lay(self, pts: np.ndarray, s: np.ndarray, s_w0: float, s_w1: float, s_lw: float,
             v0: float, vR: float, R: float) -> None:
        """Create the links along the resampled path (``pts[i]`` to ``pts[i+1]``)."""
        up, lo = self.upper, self.lower
        om = -vR / R
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
            elif lo is not None and mid >= s_lw + math.pi * R:
                vel, w = (0.0, 0.0), 0.0
            elif lo is not None and mid >= s_lw:
                c = lo.roller.position
                vel, w = (vR - om * (cy - c.y), om * (cx - c.x)), om
            else:
                vel, w = (v0 * math.cos(ang), v0 * math.sin(ang)), 0.0
            links.append(self.chain.make_body((cx, cy), ang, velocity=vel, angular_velocity=w))
        for link in reversed(links):  # chain order: downstream end first
            self.chain.append(link)
        self.added = len(links)

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

    @property
    def strand_speed(self) -> float:
        """Mean speed of the links in the plate grooves (m/s): the straight strand moves
        rigidly, so this is the cleanest reading of the chain speed (nan without grooves)."""
        g = self._grooves
        if not g:
            return math.nan
        return float(sum(lk.body.velocity.x for lk, _ in g) / len(g))

    @property
    def plate_grooves(self) -> deque[tuple[Link, pymunk.GrooveJoint]]:
        """``plate = "groove"``: the upper plate strand's links with their groove joints,
        most downstream first (the newest, at the pick-up roller, last). Read only."""
        return self._grooves

    @property
    def upper_held(self) -> list[deque[tuple[Link, pymunk.Constraint]]]:
        """Upper joint guide: the links (with their joints) each element of
        :attr:`up_guide` holds, most downstream first. Read only."""
        return self._uq

    @property
    def fold_held(self) -> list[deque[tuple[Link, pymunk.Constraint]]]:
        """'fold' guide: the links (with their joints) each element of :attr:`guide`
        holds, most downstream first (``[-1]``: the lower plate strand). Read only."""
        return self._gq

    @property
    def tail_grooved(self) -> int:
        """'open' with ``plate = "groove"``: how many links (chain indices ``0 ..
        tail_grooved-1``, the tail) run in the lower plate's grooves."""
        return self._lo_n

    @property
    def turn_held(self) -> deque[tuple[Link, pymunk.SlideJoint]]:
        """'open' guide: the links held on the turn (chain indices from
        :attr:`tail_grooved` on) with their slide joints. Read only."""
        return self._arc

    @property
    def last_mouth_entry(self) -> float:
        """'fold': time (s) at which the last link entered the end guide through its
        mouth (nan before any did)."""
        return math.nan if self._mouth_t is None else self._mouth_t

    @property
    def last_mouth_offset(self) -> float:
        """'fold': that link's offset from the first turn's radius at capture (m; > 0
        outside: the fountain landed short; nan before any)."""
        return math.nan if self._mouth_t is None else self._mouth_dr

    def moving_mass(self, v_min: float = 1.0) -> float:
        """Mass of the links moving faster than ``v_min`` (kg), the lumped tail included."""
        n = sum(1 for lk in self.chain.links if lk.body.velocity.length > v_min)
        return n * self.chain.mass + self.tail_mass

    def _lump_tail(self) -> int:
        """'open' with the joint guide: keep at most ``_TAIL_KEEP`` links in the plate
        grooves; the far end link beyond is removed and its mass added to the next one
        (the tail is straight, horizontal and frictionless, so it moves as one body
        and the lumped mass is exact for the chain's motion along the path, while the
        solver keeps a short chain of grooves: a tail of hundreds of grooved links made
        the turn's slide joints yield). Returns the number of links removed."""
        if not self.guided:
            return 0
        links = self.chain.links
        n = 0
        while self._lo_n > _TAIL_KEEP and len(links) > 2:
            j = self._lo_joints.pop(0)
            self.space.remove(j)
            end, nxt = links[0], links[1].body
            if end.shape is not None and end.shape.space is None:
                self.space.add(end.shape)  # so the chain can remove it
            m_end = end.body.mass
            nxt.mass = nxt.mass + m_end
            nxt.moment = nxt.moment + m_end * self.L**2 / 12.0
            self.chain.pop_front()
            self._lo_n -= 1
            self.tail_mass = nxt.mass - self.chain.mass
            n += 1
        return n

    def set_speed(self, v: float) -> None:
        raise KeyError("the apparatus has no feed speed: its speed follows from the carts")

    # ------------------------------------------------------------------ stepping
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

    def before_step(self) -> None:
        """Apply the cart forces (constant, along the track, on the carriage) and the
        end pull ('open')."""
        for unit in (self.upper, self.lower):
            if unit is not None and unit.force:
                fastbody.apply_force_at_local_point(fastbody.handle(unit.carriage),
                                                    (unit.direction * unit.force, 0.0),
                                                    (0.0, 0.0))
        if self.end_pull:
            self.chain.links[0].body.apply_force_at_world_point(
                (self.end_pull, 0.0), self.chain.links[0].body.position)
        if self._preload:
            self._apply_preload()

    def _apply_preload(self) -> None:
        """Treadmill: the internal force pair ``F`` (tension: pulls ``down`` back along
        its axis, ``up`` forward) on each new strand joint, fading linearly. Equal and
        opposite at the joint, so it changes no physics; it stands in for the solver's
        warm start, which a new pymunk joint lacks."""
        h = 0.5 * self.L
        keep = []
        handle, force = fastbody.handle, fastbody.apply_force_at_world_point
        for item in self._preload:
            down, up, F, n = item
            if down.up_joint is None or down.body.space is None or up.body.space is None:
                continue
            f = F * n / _PRELOAD_STEPS
            hd = handle(down.body)
            a = fastbody.get_angle(hd)
            fx, fy = f * math.cos(a), f * math.sin(a)
            p = fastbody.local_to_world(hd, (-h, 0.0))
            force(hd, (-fx, -fy), p)
            force(handle(up.body), (fx, fy), p)
            item[3] = n - 1
            if n > 1:
                keep.append(item)
        self._preload = keep

    def after_step(self, dt: float) -> None:
        """Move the plate ends with the rollers; add resting links ahead of the pick-up
        roller; take resting links out of the solver behind the folding roller / on
        the floor."""
        self._sync_plates()
        chain = self.chain
        links = chain.links
        L, n_keep = self.L, self.cfg.rest_links
        x_R = self.upper.x
        if x_R > self.x_plate_up_end - 0.05:
            if self.treadmill:
                raise TableUsedUp(
                    f"t = {self._t:.2f} s: the pick-up roller has reached the channel although "
                    "the treadmill should hold it (the upper strand has left its plate "
                    "grooves); reset the level")
            raise TableUsedUp(
                f"t = {self._t:.2f} s: the pick-up roller has reached the channel: the upper "
                f"table is used up (apparatus.duration = {self.cfg.duration:g} s sizes it for "
                f"the start speed; raise it, or set apparatus.plate_links > 0 for a treadmill)")
        last = links[-1].body
        while pos(last).x < x_R + self.n_ahead * L:
            c = last.position
            new = chain.make_body((c.x + L, self.y_table_up + self.rho), math.pi)
            chain.append(new)
            self.added += 1
            last = new.body
        # downstream end: absorb at the floor height / drop links that lie at rest
        self._t += dt
        popped = self._lump_tail()
        if self.treadmill:
            self._treadmill_upper()
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
        elif self.lower is not None:
            x_lim = self.lower.x - 2.0 * self.r - n_keep * L
            y_rest = self.y_table_lo + 2.0 * self.rho
            while len(links) > n_keep + 10:
                p = pos(links[0].body)
                if not (p.x < x_lim and p.y < y_rest):
                    break
                chain.pop_front()
                self.absorbed += 1
                popped += 1
        if self.plate_mode == "groove":
            self._update_grooves(popped)
            self._update_lo_grooves()
        if self.upper_guided:
            self._update_upper_guide()
        if self.fold_guided:
            self._update_flight(popped)
            self._update_fold_guide(popped)
            if self.treadmill:
                self._treadmill_lower()
        if self.lower is not None:
            self._check_fold(dt)

    def _check_fold(self, dt: float) -> None:
        """Raise :class:`FoldCollapsed` once the folding roller has rolled backwards for
        :data:`_COLLAPSE_TIME` (a chain that keeps running into a stopped fold only piles
        up; nothing after that is the apparatus any more)."""
        v_R = self.lower.speed
        if v_R >= 0.0:
            self._back_t = 0.0
            if self._t >= self._swing_next:  # the hold is sampled, not read every step
                self._swing_next = self._t + _SWING_EVERY
                v = self.speed
                if v > 0.0 and abs(v_R / v - 0.5) <= _HELD:
                    self._held_t += _SWING_EVERY
                    self._held_v.append(v)
            return
        self._back_t += dt
        if self._back_t < _COLLAPSE_TIME:
            return
        clamped = dt < _FOLD_DT_MIN and not self.cfg.fold_clearance
        if self._held_t >= _LATE_COLLAPSE and not clamped:
            raise FoldCollapsed(self._late_collapse_message(v_R))
        push = self.lower.force
        lam, v = self.sim_cfg.chain.linear_density, self.speed
        pushed = (f"a push of {push / (lam * v * v):.2f} lambda*v^2" if push
                  else "no lower cart (Tbar_lc = 0)")
        head = (f"t = {self._t:.2f} s: the folding roller rolls backwards (v_R = {v_R:.2f} "
                f"m/s, steady is about +{0.5 * v:.2f}) with {pushed}: the put-down has failed "
                "and the chain piles up in the lower guide. ")
        if clamped:
            raise FoldCollapsed(
                head + f"solver.dt = {dt:g} s is below {_FOLD_DT_MIN:g} s, where the folding "
                "roller locks between the lower plate's grooves and the table (with "
                "apparatus.fold_clearance = 0 the fold only holds at dt 0.35-0.5 ms; "
                "docs/apparatus.md): set apparatus.fold_clearance = "
                "0.002 (with a lighter lower cart) or solver.dt = 0.0005")
        raise FoldCollapsed(
            head + "This model's put-down needs a forward push of about 0.3 lambda*v^2 or "
            "more (docs/apparatus.md); "
            + ("raise the lower cart mass" if push else
               "give the level a second [[carts]] entry (the lower cart)") + "."
            + self._catch_note())

    def _catch_note(self) -> str:
        """'fold': a sentence for the collapse message if the chain had stopped entering
        the end guide through its mouth :data:`_CATCH_LOST` s or more before the collapse
        (the fountain landed outside the catch's band and fell into the turn from the
        side), '' otherwise (or before any link entered: nothing to compare). It states
        the order, not a cause. Measured (docs/apparatus.md): the
        catch is lost 1.0-1.3 s before the folding roller rolls back in
        ``apparatus_special`` (starts 2.97-3.06 m/s, the channel's walls; 1.13 s with the
        joint guide from 3.0 m/s), 0.47 s before in ``apparatus_limit``."""
        if (not self.fold_guided or self._mouth_t is None
                or self._t - self._mouth_t < _CATCH_LOST):
            return ""
        dr = self._mouth_dr
        where, shape = ("outside", "narrowed") if dr > 0 else ("inside", "widened")
        return (f" The end guide's catch had been lost before that: the chain last entered "
                f"the guide through its mouth at t = {self._mouth_t:.2f} s, "
                f"{100.0 * abs(dr):.1f} cm {where} the first turn's radius (the catch takes "
                f"links within {100.0 * _FOLD_CAPTURE[0]:.0f} cm); the fountain had {shape} "
                "and after that the chain fell into the turn from the side.")

    def _late_collapse_message(self, v_R: float) -> str:
        """The collapse of a fold that had held the chain for at least
        :data:`_LATE_COLLAPSE` s: the chain speed swings with a period of 2-3 s and a
        growing amplitude (the landing swing) until the folding roller loses the chain.
        The push read at this moment (the chain has run away) says nothing about the
        balance, so the message gives the speed the fold held and its swing instead."""
        hv = self._held_v
        lam = self.sim_cfg.chain.linear_density
        v_held = sum(hv) / len(hv) if hv else self.speed
        swing = 0.5 * (max(hv) - min(hv)) if hv else math.nan
        push = self.lower.force / (lam * v_held * v_held)
        return (f"t = {self._t:.2f} s: the folding roller lost the chain (v_R = {v_R:.2f} m/s) "
                f"after holding it at v/2 for {self._held_t:.1f} s in all. In its last "
                f"{len(hv) * _SWING_EVERY:.0f} s of holding, the chain speed was "
                f"{v_held:.2f} m/s swinging by +-{swing:.2f} m/s (lower cart push "
                f"{push:.2f} lambda*v^2 at that speed): in this model the landing swing "
                "(period 2-3 s) grows until the fold fails. A lower cart a few grams "
                "lighter or heavier, a start 2 % faster or slower, a stiffer catch or longer "
                "strands only move the failure (5.5-18.3 s for apparatus_special at "
                "solver.dt 0.5 ms, 6.7-22.5 s with the upper channel's walls; "
                "docs/apparatus.md)."
                + self._catch_note())

    # ------------------------------------------------------------------ treadmill
    def travel(self, i: int) -> float:
        """Distance (m) roller ``i`` (0 upper, 1 lower) has rolled since the start,
        the treadmills' moves back included."""
        u = (self.upper, self.lower)[i]
        if u is None:
            return 0.0
        return abs(u.x - self.start_x[i] + (self.shifted, self.shifted_lo)[i])

    def _shift_back(self, bodies: list[pymunk.Body], dx: float) -> None:
        """Move ``bodies`` by ``dx`` (m) in ``-x`` (velocities unchanged)."""
        get_p, set_p, handle = fastbody.get_position, fastbody.set_position, fastbody.handle
        for b in bodies:
            h = handle(b)
            p = get_p(h)
            set_p(h, (p.x - dx, p.y))

    def _treadmill_upper(self) -> None:
        """Keep the upper plate strand from shrinking: once the pick-up roller has moved
        half a link length past its start, insert a link into the middle of the grooved
        strand and move everything upstream of it (strand, wrap, resting chain, roller
        and carriage) back by one link length. The strand is straight, horizontal and
        frictionless and all its links move at the chain speed, so the new link (the
        mean velocity of its neighbours, laid exactly into the gap) changes nothing but
        the strand's length; the pick-up (roller on the resting chain) is moved rigidly
        and is untouched."""
        up = self.upper
        L = self.L
        g = self._grooves
        if up.x - self.start_x[0] < 0.5 * L or len(g) < 4:
            return
        chain = self.chain
        links = chain.links
        m = len(g) // 2
        a_link = g[m][0]
        i = chain.ids.index(a_link.id)
        b_link = links[i + 1]
        if g[m + 1][0] is not b_link:
            return  # not a contiguous strand (should not happen): skip this step
        h = 0.5 * L
        pa = a_link.body.local_to_world((-h, 0.0))
        pb = b_link.body.local_to_world((h, 0.0))
        dy = pa.y - pb.y
        dx = math.sqrt(max(L * L - dy * dy, 0.0)) - (pa.x - pb.x)
        self._shift_back([lk.body for lk in links[i + 1:]] + [up.roller, up.carriage], dx)
        self.shifted += dx
        pb = pymunk.Vec2d(pb.x - dx, pb.y)
        ab = a_link.body
        F = a_link.up_joint.impulse / self.sim_cfg.solver.dt if a_link.up_joint else 0.0
        vel = 0.5 * (ab.velocity + b_link.body.velocity)
        new = chain.make_body((0.5 * (pa.x + pb.x), 0.5 * (pa.y + pb.y)),
                              math.atan2(pa.y - pb.y, pa.x - pb.x), velocity=tuple(vel))
        chain.insert(i + 1, new, with_shape=False)  # grooved: out of the broadphase
        self._preload += [[a_link, new, F, _PRELOAD_STEPS], [new, b_link, F, _PRELOAD_STEPS]]
        g.insert(m + 1, (new, self._groove_joint(new.body)))
        self._g_next += 1
        self.added += 1
        self.moved_back += 1

    def _treadmill_lower(self) -> None:
        """'fold': keep the lower plate strand from growing, the mirror of
        :meth:`_treadmill_upper`. Once the folding roller has moved one link length past
        its start, take two neighbouring links out of the middle of the grooved strand
        and move everything downstream of them (strand, wrap, laid chain, roller and
        carriage) back by the gap, so the roller stays within about a link of its start.

        Two, not one: the grooves hold the link centres on the line and leave the angles
        free, and the strand settles into a regular zigzag (angles alternating by about
        +-0.07 rad). Cutting one link leaves its neighbours' free ends 1.3 mm apart in
        ``y``, which the joints close only slowly; cutting two keeps the zigzag's phase
        and the ends meet. Of the pairs near the middle, the one whose ends meet best in
        ``y`` is cut. The strand is straight, horizontal, frictionless and moves as one,
        so the cut changes only its length."""
        lo = self.lower
        L = self.L
        q = self._gq[-1]
        if lo.x - self.start_x[1] < L or len(q) < 10:
            return
        chain = self.chain
        links = chain.links
        h = 0.5 * L
        best = None
        for m in range(len(q) // 2 - 3, len(q) // 2 + 3):
            dn, up = q[m - 1][0], q[m + 2][0]
            i = chain.ids.index(q[m][0].id)
            if links[i - 1] is not dn or links[i + 1] is not q[m + 1][0] or \
                    links[i + 2] is not up:
                continue  # not contiguous (should not happen)
            pd = dn.body.local_to_world((-h, 0.0))
            pu = up.body.local_to_world((h, 0.0))
            if best is None or abs(pd.y - pu.y) < best[0]:
                best = (abs(pd.y - pu.y), m, i, pd.x - pu.x)
        if best is None:
            return
        _, m, i, dx = best
        c = links[i + 1]
        F = c.up_joint.impulse / self.sim_cfg.solver.dt if c.up_joint else 0.0
        self._shift_back([lk.body for lk in links[:i]] + [lo.roller, lo.carriage], dx)
        self.shifted_lo += dx
        for k in (m + 1, m):
            self.space.remove(q[k][1])
            del q[k]
        chain.remove(i + 1)
        chain.remove(i)
        self._preload.append([links[i - 1], links[i], F, _PRELOAD_STEPS])
        self._cap_next -= 2
        self._fly_next -= 2
        self._g_next -= 2
        self.cut += 2

    def _update_lo_grooves(self) -> None:
        """'open': the tail leaving the end channel runs in a frictionless groove joint per
        link on the lower plate line (as the upper plate; no plate contacts, no waves on
        the tail). The tail only grows at its upstream side, so the grooved links are
        always the first ``_lo_n`` of the chain."""
        if self.variant != "open":
            return
        links = self.chain.links
        xl, y = self.x_plate_lo_start, self.y_lo
        space = self.space
        if self.guided:
            # the turn: a link whose centre comes within the capture band of the circle
            # (past the mouth, before the bottom) gets a slide joint to the centre
            # (distance limits around R: a frictionless two-sided circular groove with a
            # little play); past the bottom it moves to the plate groove
            cx, cy = self.guide_centre
            Rc = self.guide_radius
            th_mouth = math.atan2(-math.cos(self.alphaE), -math.sin(self.alphaE))
            while not self._arc and self._lo_n < len(links):  # the tail laid out on the plate
                b = links[self._lo_n].body
                if not (b.position.x > xl and abs(b.position.y - y) < 2.0 * self.rho):
                    break
                self._groove_lo(links[self._lo_n])
            while True:
                i = self._lo_n + len(self._arc)
                if i >= len(links):
                    break
                link = links[i]
                p = link.body.position
                d = math.hypot(p.x - cx, p.y - cy)
                th = math.atan2(p.y - cy, p.x - cx)
                if not (th_mouth - _CAPTURE[1] <= th <= -0.5 * math.pi + 0.05
                        and abs(d - Rc) < _CAPTURE[0]):
                    break
                # the limit starts where the link is (no position kick: a stiff
                # correction would feed energy into the chain) and closes in to R + play
                j = pymunk.SlideJoint(space.static_body, link.body, (cx, cy), (0.0, 0.0),
                                      Rc - _CAPTURE[0], max(Rc + PLAY, d))
                j.error_bias = GUIDE_BIAS
                space.add(j)
                if link.shape is not None and link.shape.space is not None:
                    space.remove(link.shape)
                self._arc.append((link, j))
            close = _CLOSE_RATE * self.sim_cfg.solver.dt
            for link, j in self._arc:
                if j.max > Rc + PLAY:
                    j.max = max(Rc + PLAY, min(j.max - close, math.hypot(
                        link.body.position.x - cx, link.body.position.y - cy)))
            while self._arc and self._arc[0][0].body.position.x > cx:
                link, j = self._arc.popleft()
                space.remove(j)
                self._groove_lo(link)
            return
        while self._lo_n < len(links):
            b = links[self._lo_n].body
            if not (b.position.x > xl and abs(b.position.y - y) < 2.0 * self.rho):
                break
            self._groove_lo(links[self._lo_n])

    def _groove_lo(self, link: Link) -> None:
        """Put ``links[_lo_n]`` into a frictionless groove on the lower plate line."""
        y = self.y_lo
        j = pymunk.GrooveJoint(self.space.static_body, link.body,
                               (self.x_plate_lo_start - 0.05, y), (self.far_lo, y), (0.0, 0.0))
        j.error_bias = self.sim_cfg.solver.joint_error_bias
        self.space.add(j)
        if link.shape is not None and link.shape.space is not None:
            self.space.remove(link.shape)
        self._lo_joints.append(j)
        self._lo_n += 1

    # ------------------------------------------------------------------ fold guide
    def _fold_guide(self, xE: float, alphaE: float, rise: float, R: float,
                    far: float) -> list[GuideElement]:
        """Elements of the 'fold' joint guide, along the end channel's centre line:
        turn from the landing heading ``-alphaE`` (centre :attr:`guide_centre`) up to
        60 deg, straight rise, turn back to horizontal, lower plate line to ``far``."""
        up = math.radians(60.0) if rise > 1e-9 else 0.0
        H = self.H
        out: list[GuideElement] = []
        if rise > 1e-9:
            R, S = end_channel_bends(alphaE, rise, R, up)
        else:
            S = 0.0
        c1 = (xE + R * math.sin(alphaE), -H + R * math.cos(alphaE))
        self.guide_centre, self.guide_radius = c1, R
        th0 = math.atan2(-math.cos(alphaE), -math.sin(alphaE))
        th1 = up - 0.5 * math.pi
        out.append(GuideElement("arc", c1, c1, R, th0, th1))
        p1 = (c1[0] + R * math.cos(th1), c1[1] + R * math.sin(th1))
        p2 = p1
        if S > 1e-6:
            p2 = (p1[0] + S * math.cos(up), p1[1] + S * math.sin(up))
            out.append(GuideElement("line", p1, p2))
        if rise > 1e-9:
            c2 = (p2[0] + R * math.sin(up), p2[1] - R * math.cos(up))
            out.append(GuideElement("arc", c2, c2, R, up + 0.5 * math.pi, 0.5 * math.pi))
            p3 = (c2[0], c2[1] + R)
        else:
            p3 = (c1[0], c1[1] - R)
        out.append(GuideElement("line", p3, (far, p3[1])))
        self.x_plate_lo_start = p3[0]
        return out

    def _init_fold_guide(self) -> None:
        """Put the links laid along the lower channel and plate into their elements."""
        links = self.chain.links
        P = np.array([[lk.body.position.x, lk.body.position.y] for lk in links])
        x_rel = self.lower.x - _FOLD_RELEASE * self.L
        last = -1
        order = list(range(len(self.guide) - 1, -1, -1))  # plate first (downstream)
        cur = 0
        for i, lk in enumerate(links):
            p = P[i:i + 1]
            for jj in order[cur:]:
                el = self.guide[jj]
                if el is self.guide[-1] and p[0, 0] >= x_rel:
                    continue
                if el.on(p, 0.003)[0]:
                    cur = order.index(jj)
                    self._hold(jj, lk)
                    last = i
                    break
            else:
                if last >= 0:
                    break
        self._cap_next = last + 1

    def _hold(self, k: int, link: Link) -> None:
        """Hold ``link`` in guide element ``k`` (out of the collision broadphase)."""
        j = self.guide[k].joint(self.space, link.body, self.sim_cfg.solver.joint_error_bias)
        if link.shape is not None and link.shape.space is not None:
            self.space.remove(link.shape)
        self._gq[k].append((link, j))

    def _update_flight(self, popped: int) -> None:
        """'fold': a link more than a link length past the upper channel's exit flies
        freely until the guide catches it; nothing is left for it to touch (the lower
        channel is a joint guide, links do not collide with each other), so its shape
        leaves the collision broadphase. It comes back when the folding roller takes
        the link (:meth:`_update_fold_guide`). This changes no result (the fold preset
        gives the same numbers to the last digit) and saves about a third of the
        shapes."""
        links = self.chain.links
        self._fly_next -= popped
        x_out = float(self.channel_up[-1, 0]) + self.L
        space = self.space
        while 0 <= self._fly_next < len(links):
            link = links[self._fly_next]
            if pos(link.body).x <= x_out:
                break
            if link.shape is not None and link.shape.space is not None:
                space.remove(link.shape)
            self._fly_next += 1

    def _update_fold_guide(self, popped: int) -> None:
        """'fold': capture links landing at the mouth into the first turn, move links
        from element to element as they pass each end, and hand them to the folding
        roller (shape back in the space) when they reach its top."""
        links = self.chain.links
        self._cap_next -= popped
        el0 = self.guide[0]
        cx, cy = el0.a
        Rc = el0.R
        lim = -0.5 * math.pi + 0.05
        while 0 <= self._cap_next < len(links):
            p = pos(links[self._cap_next].body)
            d = math.hypot(p.x - cx, p.y - cy)
            th = math.atan2(p.y - cy, p.x - cx)
            if not (el0.th0 - _FOLD_CAPTURE[1] <= th <= max(lim, el0.th1)
                    and abs(d - Rc) < _FOLD_CAPTURE[0]):
                break
            if th <= el0.th0:  # through the mouth, not into the turn from the side
                self._mouth_t, self._mouth_dr = self._t, d - Rc
            self._hold(0, links[self._cap_next])
            self._cap_next += 1
        space = self.space
        n_el = len(self.guide)
        for k in range(n_el - 1, -1, -1):  # downstream elements first
            q = self._gq[k]
            el = self.guide[k]
            if k == n_el - 1:  # the lower plate: hand links to the folding roller
                x_rel = self.lower.x - _FOLD_RELEASE * self.L
                while q and pos(q[0][0].body).x > x_rel:
                    link, j = q.popleft()
                    space.remove(j)
                    if link.shape is not None:
                        space.add(link.shape)
                    self.released += 1
                continue
            while q:
                p = pos(q[0][0].body)
                if not el.passed(p.x, p.y):
                    break
                link, j = q.popleft()
                space.remove(j)
                self._hold(k + 1, link)
        self._keep_on_arcs(self.guide, self._gq)

    # ------------------------------------------------------------------ upper guide
    def _init_upper_guide(self) -> None:
        """Put the links laid along the upper channel (downstream of the plate's grooved
        strand) into the upper guide's elements."""
        links = self.chain.links
        i_g = self.chain.ids.index(self._grooves[0][0].id) if self._grooves else len(links)
        found: list[tuple[int, int]] = []
        for i in range(i_g - 1, -1, -1):  # upstream to downstream
            p = pos(links[i].body)
            P = np.array([[p.x, p.y]])
            for k, el in enumerate(self.up_guide):
                if el.on(P, 0.003)[0] and not el.passed(p.x, p.y):
                    found.append((i, k))
                    break
            else:
                if found:
                    break  # past the exit: the fountain
        for i, k in sorted(found):  # downstream first in each queue
            self._hold_up(k, links[i])

    def _hold_up(self, k: int, link: Link) -> None:
        """Hold ``link`` in upper guide element ``k`` (out of the collision broadphase)."""
        j = self.up_guide[k].joint(self.space, link.body, self.sim_cfg.solver.joint_error_bias)
        if link.shape is not None and link.shape.space is not None:
            self.space.remove(link.shape)
        self._uq[k].append((link, j))

    def _update_upper_guide(self) -> None:
        """Upper joint guide: move links from element to element as they pass each end
        (downstream elements first, so a link moves at most one element per step) and
        release them into flight past the fountain start. A released link stays out of
        the broadphase in 'fold' (nothing to touch in flight, :meth:`_update_flight`)
        and gets its shape back otherwise (the floor variants need it)."""
        space = self.space
        els, qs = self.up_guide, self._uq
        last = len(els) - 1
        for k in range(last, -1, -1):
            q, el = qs[k], els[k]
            before = _UP_RELEASE * self.L if k == last else 0.0
            while q:
                p = pos(q[0][0].body)
                if not el.passed(p.x, p.y, before):
                    break
                link, j = q.popleft()
                space.remove(j)
                if k < last:
                    self._hold_up(k + 1, link)
                elif not self.fold_guided and link.shape is not None \
                        and link.shape.space is None:
                    space.add(link.shape)
        self._keep_on_arcs(els, qs)

    def _keep_on_arcs(self, guide: list[GuideElement],
                      queues: list[deque[tuple[Link, pymunk.Constraint]]]) -> None:
        """Joint guides: for each link held on an arc of ``guide``, close its slide joint's
        limits in toward ``R -+ PLAY`` at :data:`_FOLD_CLOSE_RATE` (a link captured off
        the radius), then put it back onto the nearest limit if it has left them and take
        away its velocity across it.

        A frictionless wall does exactly this (it stops the motion into it); the
        slide joint alone corrects a position error only slowly (error bias), while
        the discrete step moves a link in a turn outward by ``(v dt)^2/(2 R)`` every
        step, so without the projection the turn's links sit 1-2 mm beyond the limit.
        Measured on the fold test: with the projection they stay on it to the step, and
        the turn does not drift outward as the lower plate strand grows. (A
        :mod:`pymunk.batch` version, one read and one write of all bodies per step with
        the projection in numpy, is slower: numpy's per-call cost on a few dozen links is
        more than this loop's; docs/apparatus.md.)"""
        close = _FOLD_CLOSE_RATE * self.sim_cfg.solver.dt
        get_p, set_p = fastbody.get_position, fastbody.set_position
        get_v, set_v = fastbody.get_velocity, fastbody.set_velocity
        for el, q in zip(guide, queues, strict=True):
            if el.kind != "arc":
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

    def fold_guided_range(self, position: np.ndarray, x_lower: float) -> tuple[int, int]:
        """'fold' guide, from a recorded state: index ``i_p`` of the lower-plate link
        about 6 links before the folding roller (its horizontal joint force is the
        tension: the grooves add none) and ``k``, one past the last guided link
        (the mouth). ``(-1, 0)`` if the plate is empty."""
        L = self.L
        el = self.guide[-1]
        y = el.a[1]
        on_plate = (np.abs(position[:, 1] - y) < 2.0 * self.rho) & \
            (position[:, 0] > el.a[0] - 0.01) & (position[:, 0] < x_lower - 3.0 * L)
        idx = np.flatnonzero(on_plate)
        if not len(idx):
            return -1, 0
        ip = int(idx[np.argmin(np.abs(position[idx, 0] - (x_lower - 6.0 * L)))])
        on = np.zeros(len(position), dtype=bool)
        for e in self.guide[:-1]:
            on |= e.on(position, 0.004)
        e0 = self.guide[0]
        on |= e0.on(position, _FOLD_CAPTURE[0])
        on |= (np.abs(position[:, 1] - y) < 2.0 * self.rho) & (position[:, 0] > el.a[0] - 0.01)
        off = np.flatnonzero(~on[ip:])
        k = ip + int(off[0]) if len(off) else len(position)
        return ip, k

    # ------------------------------------------------------------------ plate grooves
    def _on_plate(self, body: pymunk.Body) -> bool:
        """Is a link centre on the upper plate line, clear of the roller wrap?"""
        p = pos(body)
        return (self.upper.x + self.L < p.x < self.x_plate_up_end
                and abs(p.y - self.y_up) < 0.5 * self.rho)

    def _groove_joint(self, body: pymunk.Body) -> pymunk.GrooveJoint:
        """A frictionless groove on the upper plate line for ``body``'s centre (added)."""
        j = pymunk.GrooveJoint(self.space.static_body, body,
                               (self.upper.x - 1.0, self.y_up),
                               (self.x_plate_up_end + 0.2, self.y_up), (0.0, 0.0))
        j.error_bias = self.sim_cfg.solver.joint_error_bias
        self.space.add(j)
        return j

    def _groove(self, link: Link) -> None:
        j = self._groove_joint(link.body)
        if link.shape is not None:  # nothing to touch on the plate: out of the broadphase
            self.space.remove(link.shape)
        self._grooves.append((link, j))

    def _init_grooves(self) -> None:
        links = self.chain.links
        on = [i for i, lk in enumerate(links) if self._on_plate(lk.body)]
        if on:
            i0, i1 = on[0], on[-1]
            for i in range(i0, i1 + 1):
                self._groove(links[i])
            self._g_next = i1 + 1
        else:  # nothing on the plate yet: the first link off the roller's top comes next
            self._g_next = max(i for i, lk in enumerate(links)
                               if lk.body.position.x > self.upper.x) + 1

    def _update_grooves(self, popped: int) -> None:
        """``plate = "groove"``: the strand on the upper plate runs in a frictionless
        groove joint per link (link centre on the line ``y = y_up``) instead of one
        contact per link: same normal force (the strand is straight and horizontal,
        the plate carries its weight), two-sided, and much cheaper. A link gets its
        groove when it leaves the roller's wrap onto the plate line and loses it in
        the horizontal lead of the upper channel. Grooved links leave the collision
        broadphase (their shapes are removed and put back)."""
        links = self.chain.links
        self._g_next -= popped
        g = self._grooves
        lim = self.x_plate_up_end + 0.02
        while g and pos(g[0][0].body).x > lim:
            link, j = g.popleft()
            self.space.remove(j)
            if self.upper_guided:  # on into the upper joint guide's lead, still shapeless
                self._hold_up(0, link)
            elif link.shape is not None:
                self.space.add(link.shape)
        while 0 <= self._g_next < len(links) and self._on_plate(links[self._g_next].body):
            self._groove(links[self._g_next])
            self._g_next += 1

    def _sync_plates(self) -> None:
        """Keep the plates' ends under the rollers (the moving ends are mirrored in
        :attr:`_plate_ends`, so that the usual step reads only the rollers)."""
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
        """Scaled cart forces ``(Tbar_uc, Tbar_lc)`` at chain speed ``v``."""
        s = lam * v * v
        lo = self.lower.force if self.lower is not None else 0.0
        return self.upper.force / s, lo / s
