"""The machine drawn as a machine, from the model's public state: tables with legs, rollers
as wheels that turn with the chain, carts on inclined ramps roped to the rollers'
carriages with their masses written on them, guides, the pot and its pile, the floor and
the motor. The ideal machines (``feed.drive`` ``ideal_*``) are drawn as the same parts at
the paper's geometry (massless rollers, carts by their pull), with the chain running
through the parts that are not simulated, so that every slider moves something visible.

Nothing here changes the model; :meth:`MachineView.draw` returns the parts' names with
where they are (:class:`PartLabel`) and the screen boxes the parts take, for the label
layout (:mod:`chainfountain.app.labels`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pygame

from chainfountain.app import chain_view
from chainfountain.app.camera import Camera
from chainfountain.app.palette import (
    ABSORB,
    CART,
    CART_DARK,
    CHAIN_DARK,
    FLOOR,
    GLASS,
    GUIDE,
    MARK,
    ROLLER,
    ROLLER_FILL,
    ROPE,
    SCENE_BG,
    TABLE,
    TABLE_DARK,
    TRACK,
)
from chainfountain.app.text import font, px, text
from chainfountain.sim import placement
from chainfountain.sim.guide import end_channel, upper_channel

IDEAL_ROLLER = 0.03
"""Radius (m) an ideal machine's massless rollers are drawn with."""
IDEAL_TABLE = 0.8
"""Length (m) of an ideal machine's tables drawn behind (and after) its rollers."""
CHANNEL_R = 0.15
"""Bend radius (m) of an ideal machine's drawn channels (the contact presets' own)."""
RAMP = 0.24
"""Length (m) of a cart's ramp as drawn."""
POST = 0.12
"""Height (m) of the post that carries the rope's second pulley above the carriage."""
CART_REACH = RAMP + 0.12
"""How far (m) a cart's ramp and post reach from its roller (the view's bounds)."""
LANDING_SMOOTHING = 0.5
"""Seconds over which an ideal machine's drawn end guide follows where the chain lands."""
MASS_REF = 0.05
"""A cart of this mass (kg) or pull (N, ideal carts: about its weight on a 30-deg ramp) is
drawn at the reference size; the drawn area grows with it."""


@dataclass(frozen=True)
class PartLabel:
    """A part's name and where it is: ``key`` names the part (the label layout keeps a
    label where it was by it), the anchor ``(x, y)`` is in metres, ``side`` where the text
    prefers to go (``above``, ``below``, ``left``, ``right``)."""

    key: str
    text: str
    x: float
    y: float
    side: str = "above"


@dataclass
class Drawn:
    """What :meth:`MachineView.draw` drew: the parts' labels and the parts' screen boxes."""

    labels: list[PartLabel] = field(default_factory=list)
    boxes: list[pygame.Rect] = field(default_factory=list)


FLOOR_BAND = tuple(int(b + (a - b) * 60 / 255) for a, b in zip(ABSORB, SCENE_BG, strict=True))
"""The absorbing floor's band: its colour over the scene's at a quarter (a fill, not a
translucent blit: the band is a fifth of the view)."""


def _grams(kg: float) -> str:
    return f"{kg * 1e3:.3g} g"


_NORMALS: dict[tuple, np.ndarray] = {}


def _offset(line: np.ndarray, d: float) -> np.ndarray:
    """``line`` (``(n, 2)``) moved ``d`` to its left (its unit normals are kept for the
    next frames: a channel's line is the same array every frame)."""
    key = (id(line), len(line), float(line[0, 0]), float(line[0, 1]), float(line[-1, 0]))
    normals = _NORMALS.get(key)
    if normals is None:
        t = np.gradient(line, axis=0)
        n = np.hypot(t[:, 0], t[:, 1])
        n[n == 0] = 1.0
        normals = np.column_stack([-t[:, 1] / n, t[:, 0] / n])
        if len(_NORMALS) > 32:
            _NORMALS.clear()
        _NORMALS[key] = normals
    return line + d * normals


def landing_angle(q: float, h: float, H: float) -> float:
    """The catenary's angle below the horizontal where it lands ``h + H`` below its
    vertex (``q y = 1 - cosh(q x)``: ``tan(alpha_E) = sinh(q x_E)``)."""
    c = 1.0 + q * (h + H)
    return math.atan(math.sqrt(max(c * c - 1.0, 0.0)))


class MachineView:
    """Draws a level's machine; remembers what it needs between frames (the rollers' last
    angles for their motion blur, how far an ideal machine's drawn chain has run)."""

    def __init__(self) -> None:
        self._angles: dict[str, float] = {}
        self._travelled = 0.0
        self._t_last: float | None = None
        self._sim_id = 0
        self._x_land: float | None = None
        self._parts: tuple[tuple, IdealParts] | None = None
        self.frame_dt = 1.0 / 60.0
        """Simulated seconds since the last frame (the rollers' blur)."""
        self.paths: list[np.ndarray] = []
        """The chain drawn (not simulated) in the last frame, world lines (an ideal
        machine's channels and tables): labels keep clear of it too."""

    # ------------------------------------------------------------------ frame
    def draw(self, surf: pygame.Surface, cam: Camera, sim, expert: bool = False,
             marks_every: int = 10) -> Drawn:
        """Draw ``sim``'s machine (below the chain) and return its labels and boxes."""
        if id(sim) != self._sim_id or self._t_last is None or sim.time < self._t_last:
            self._sim_id, self._angles, self._travelled = id(sim), {}, 0.0
            self._x_land = None
            self._t_last = sim.time
        self.frame_dt = max(0.0, sim.time - self._t_last)
        self._t_last = sim.time
        self._travelled += float(sim.ends.speed) * self.frame_dt
        out = Drawn()
        self.paths = []
        cfg = sim.config
        if sim.beaker is not None:
            self._beaker(surf, cam, sim, out, expert)
        elif sim.apparatus is not None:
            self._apparatus(surf, cam, sim, out, expert)
        elif cfg.feed.drive == "motor":
            self._motor(surf, cam, sim, out, expert)
        else:
            self._ideal(surf, cam, sim, out, expert, marks_every)
        if sim.apparatus is None:
            self._obstacles(surf, cam, sim, out)
        return out

    def _obstacles(self, surf: pygame.Surface, cam: Camera, sim, out: Drawn) -> None:
        """A fed level's own rollers (turning at their set speed) and carts on their
        tracks (``rollers``, ``carts`` of the level)."""
        for i, r in enumerate(sim.rollers):
            pos = r.body.position
            self.wheel(surf, cam, f"roller{i}", float(pos.x), float(pos.y), r.cfg.radius,
                       float(r.body.angle), out)
        for c in sim.carts:
            pygame.draw.line(surf, TRACK, cam.point(*c.track_start), cam.point(*c.track_end),
                             max(3, px(4)))
            verts = [cam.point(*c.body.local_to_world(v)) for v in c.shape.get_vertices()]
            pygame.draw.polygon(surf, CART, verts)
            pygame.draw.polygon(surf, CART_DARK, verts, max(1, px(2)))
            xs, ys = [v[0] for v in verts], [v[1] for v in verts]
            out.boxes.append(pygame.Rect(min(xs), min(ys), max(xs) - min(xs) + 1,
                                         max(ys) - min(ys) + 1))

    def _landing(self, sim, predicted: float) -> float:
        """Where an ideal machine's end guide is drawn: where the chain lands once it has
        (smoothed over :data:`LANDING_SMOOTHING` s of simulated time), else where the
        paper's fountain lands."""
        if sim.ends.absorbed == 0 or not sim.chain.links or self._x_land is None:
            self._x_land = predicted if sim.ends.absorbed == 0 else \
                float(sim.chain.links[0].body.position.x)
            return self._x_land
        x = float(sim.chain.links[0].body.position.x)
        a = min(1.0, self.frame_dt / LANDING_SMOOTHING)
        self._x_land += a * (x - self._x_land)
        return self._x_land

    # ------------------------------------------------------------------ parts
    def _spin(self, key: str, angle: float) -> float:
        """The angle a wheel turned since the last frame (rad, wrapped to +-pi)."""
        last = self._angles.get(key)
        self._angles[key] = angle
        if last is None:
            return 0.0
        return (angle - last + math.pi) % (2.0 * math.pi) - math.pi

    def wheel(self, surf: pygame.Surface, cam: Camera, key: str, x: float, y: float,
              r: float, angle: float, out: Drawn) -> None:
        """A roller: a wheel with a hub, spokes and one white spoke that turns with it (a
        trail behind the white spoke when it turns fast), on a carriage's groove."""
        c = cam.point(x, y)
        rp = max(px(7), int(round(r * cam.scale)))
        turned = self._spin(key, angle)
        pygame.draw.circle(surf, ROLLER_FILL, c, rp)
        for k in range(6):
            a = angle + k * math.pi / 3
            pygame.draw.line(surf, ROLLER, c, (c[0] + rp * math.cos(a),
                                               c[1] - rp * math.sin(a)), 1)
        for k in (3, 2, 1):  # the white spoke's trail over the last frame
            if abs(turned) < 0.25:
                break
            a = angle - turned * k / 3.0
            col = tuple(int(0.35 * m + 0.65 * f) for m, f in zip(MARK, ROLLER_FILL,
                                                                    strict=True))
            pygame.draw.line(surf, col, c, (c[0] + rp * math.cos(a), c[1] - rp * math.sin(a)),
                             max(2, px(2)))
        pygame.draw.line(surf, MARK, c, (c[0] + rp * math.cos(angle),
                                         c[1] - rp * math.sin(angle)), max(2, px(3)))
        pygame.draw.circle(surf, ROLLER, c, rp, max(2, px(3)))
        pygame.draw.circle(surf, GUIDE, c, max(2, rp // 5))
        out.boxes.append(pygame.Rect(c[0] - rp, c[1] - rp, 2 * rp, 2 * rp))

    def table(self, surf: pygame.Surface, cam: Camera, a: tuple[float, float],
              b: tuple[float, float], out: Drawn) -> None:
        """A table: a slab from ``a`` to ``b`` (world, its top) standing on legs."""
        (ax, ay), (bx, by) = cam.point(*a), cam.point(*b)
        x0, x1 = min(ax, bx), max(ax, bx)
        thick = max(px(6), int(0.012 * cam.scale))
        slab = pygame.Rect(x0, min(ay, by), max(1, x1 - x0), thick)
        leg_h = max(px(24), int(0.12 * cam.scale))
        step = max(px(120), int(0.5 * cam.scale))
        for lx in list(range(x0 + px(10), x1 - px(10), step)) + [x1 - px(10)]:
            pygame.draw.line(surf, TABLE_DARK, (lx, slab.bottom), (lx, slab.bottom + leg_h),
                             max(2, px(4)))
        pygame.draw.rect(surf, TABLE, slab)
        pygame.draw.rect(surf, TABLE_DARK, slab, 1)
        out.boxes.append(pygame.Rect(x0, slab.y, x1 - x0, thick + leg_h))

    def channel(self, surf: pygame.Surface, cam: Camera, line: np.ndarray, half: float
                ) -> None:
        """A guide channel along ``line`` (world), its walls ``half`` m either side."""
        for s in (-1.0, 1.0):
            wall = cam.to_screen(_offset(line, s * half))
            if len(wall) >= 2:
                pygame.draw.lines(surf, GUIDE, False, wall.tolist(), max(2, px(2)))

    def cart(self, surf: pygame.Surface, cam: Camera, carriage: tuple[float, float],
             roller_px: int, direction: float, incline: float, size: float,
             writing: str, out: Drawn) -> pygame.Rect:
        """A cart on an inclined ramp, roped to a roller's carriage: the rope runs from the
        carriage ``direction``-wards (-1: back, +1: ahead) over a pulley, up over a second
        one and down the ramp to the cart, which gravity pulls down the ramp; ``size``:
        the cart's mass (kg) or pull (N) (its drawn area grows with it), ``writing``: what
        is written on it. The parts have a size in metres (:data:`RAMP`, :data:`POST`),
        never smaller on screen than a projector shows. Returns the cart's box."""
        cx, cy = cam.point(*carriage)
        d = 1 if direction >= 0 else -1
        ax, ay = cx + d * (roller_px + max(px(26), int(0.05 * cam.scale))), cy
        bx, by = ax, ay - max(px(60), int(POST * cam.scale))
        ramp = max(px(110), int(RAMP * cam.scale))
        beta = min(max(float(incline), math.radians(5.0)), math.radians(75.0))
        top = (bx + d * px(10), by + px(9))
        foot = (top[0] + d * ramp * math.cos(beta), top[1] + ramp * math.sin(beta))
        wedge = [top, foot, (top[0], foot[1])]
        pygame.draw.polygon(surf, TRACK, wedge)
        pygame.draw.polygon(surf, SCENE_BG, wedge, 1)
        pygame.draw.line(surf, TRACK, (ax, ay), (bx, by), max(2, px(3)))  # the post
        # the cart on the ramp, its area growing with its mass or pull
        f = font(18, bold=True)
        label = text(f, writing, True, CART_DARK)
        grow = (max(size, 1e-4) / MASS_REF) ** (1.0 / 3.0)  # its volume grows with it
        bw = int(min(max(px(44) * grow, label.get_width() + px(14)), px(96)))
        bh = int(min(max(px(24) * grow, label.get_height() + px(8)), px(44)))
        ux, uy = d * math.cos(beta), math.sin(beta)  # down the ramp (screen)
        nx, ny = uy * d, -ux * d  # the ramp's normal, up off it
        if ny > 0:
            nx, ny = -nx, -ny
        s = 0.5 * ramp
        lift = bh / 2 + px(5)
        mx, my = top[0] + ux * s + nx * lift, top[1] + uy * s + ny * lift
        corners = [(mx + a * ux * bw / 2 + b * nx * bh / 2, my + a * uy * bw / 2 + b * ny * bh / 2)
                   for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        for a in (-0.6, 0.6):  # wheels on the ramp
            wx = mx + a * ux * bw / 2 - nx * (bh / 2 + px(1))
            wy = my + a * uy * bw / 2 - ny * (bh / 2 + px(1))
            pygame.draw.circle(surf, CART_DARK, (wx, wy), max(3, px(5)))
        pygame.draw.polygon(surf, CART, corners)
        pygame.draw.polygon(surf, CART_DARK, corners, max(1, px(2)))
        # the writing level, on a plate over the cart (a tilted box is too small for it)
        plate = pygame.Rect(0, 0, label.get_width() + px(8), label.get_height() + px(2))
        plate.center = (int(mx), int(my))
        pygame.draw.rect(surf, CART, plate, 0, px(3))
        surf.blit(label, (plate.x + px(4), plate.y + px(1)))
        # the rope: carriage -> pulley A -> pulley B -> the cart's upper end
        hook = (mx - ux * bw / 2, my - uy * bw / 2)
        pygame.draw.lines(surf, ROPE, False, [(cx, cy), (ax, ay), (bx, by), hook], 2)
        for p in ((ax, ay), (bx, by)):
            pygame.draw.circle(surf, ROPE, p, max(3, px(6)), 2)
        xs = [ax, bx, foot[0], top[0], plate.left, plate.right] + [c[0] for c in corners]
        ys = [ay, by - px(6), foot[1], top[1], plate.top, plate.bottom] + [c[1] for c in corners]
        box = pygame.Rect(min(xs), min(ys), max(xs) - min(xs), max(ys) - min(ys))
        out.boxes.append(box)
        return box

    def floor(self, surf: pygame.Surface, cam: Camera, y: float, label: str, out: Drawn,
              absorbing: bool = True) -> None:
        """The floor at height ``y``: an absorbing band (it takes the chain away) or a
        solid floor."""
        rect = cam.rect
        sy = cam.point(0.0, y)[1]
        if absorbing:
            band = pygame.Rect(rect.x, sy, rect.w, max(4, rect.bottom - sy))
            if band.top < rect.bottom:
                surf.fill(FLOOR_BAND, band)
            pygame.draw.line(surf, ABSORB, (rect.x, sy), (rect.right, sy), max(2, px(3)))
        else:
            pygame.draw.line(surf, FLOOR, (rect.x, sy), (rect.right, sy), max(3, px(4)))
            for x in range(rect.x, rect.right, px(14)):
                pygame.draw.line(surf, FLOOR, (x, sy + 2), (x - px(9), sy + px(11)), 1)
        if label:
            x = cam.to_world(rect.x + px(60), sy)[0]
            out.labels.append(PartLabel("floor", label, x, y, "below"))

    # ------------------------------------------------------------------ kinds
    def _beaker(self, surf: pygame.Surface, cam: Camera, sim, out: Drawn, expert: bool
                ) -> None:
        outline, plate = placement.vessel(sim)
        b = sim.beaker
        self.floor(surf, cam, placement.floor(sim)[0],
                   "floor: takes the chain away" if not expert else "absorbing floor", out)
        (x0, _), (x1, _) = plate
        bottom = float(outline[1, 1])
        a, c = cam.point(float(x0), float(plate[0, 1])), cam.point(float(x1), bottom)
        hidden = pygame.Rect(a[0], a[1], max(1, c[0] - a[0]), max(1, c[1] - a[1]))
        if hidden.w > 2 and hidden.h > 2:
            link_px = max(4, int(sim.chain.L * cam.scale))
            width = chain_view.chain_width(cam, sim.config.chain.link_radius)
            surf.blit(pile_surface(hidden.size, link_px, width), hidden.topleft)
        pygame.draw.line(surf, GUIDE, cam.point(*plate[0]), cam.point(*plate[1]), 2)
        pts = cam.to_screen(outline)
        pygame.draw.lines(surf, GLASS, False, pts.tolist(), max(3, px(5)))
        out.boxes.append(pygame.Rect(int(pts[:, 0].min()), int(pts[:, 1].min()),
                                     int(np.ptp(pts[:, 0])) + 1, int(np.ptp(pts[:, 1])) + 1))
        (xi0, xi1), depth = b.x_in, -float(b.cfg.pot_depth)
        px_, py_ = b.pickup
        out.labels += [PartLabel("pot", "pot", xi0, 0.5 * depth, "left"),
                       PartLabel("pile", "pile of chain (topped up from below)"
                                 if not expert else "pile (topped up from below)",
                                 0.5 * (xi0 + xi1), float(plate[0, 1]) - 0.02, "below"),
                       PartLabel("pickup", "the chain leaves the pile here"
                                 if not expert else "pick-up", px_, py_, "left")]

    def _motor(self, surf: pygame.Surface, cam: Camera, sim, out: Drawn, expert: bool
               ) -> None:
        """A motor-fed level: the guide the chain leaves and the motor that drives it."""
        fy, _, _, mode = placement.floor(sim)
        self.floor(surf, cam, fy, "floor: takes the chain away" if mode == "absorbing"
                   else "", out, absorbing=mode == "absorbing")
        (ox, oy), (ux, uy) = placement.launch(sim)
        length = max(0.2, sim.config.feed.guide_links * sim.chain.L * 1.5)
        line = np.array([[ox - length * ux, oy - length * uy], [ox, oy]])
        half = 2.5 * sim.config.chain.link_radius + 3.0 / cam.scale
        self.channel(surf, cam, line, half)
        r = max(0.04, 0.12 * length)
        mx, my = ox - (length + r) * ux, oy - (length + r) * uy
        c = cam.point(mx, my)
        size = max(px(30), int(2.6 * r * cam.scale))
        box = pygame.Rect(0, 0, size, size)
        box.center = c
        pygame.draw.rect(surf, (70, 76, 96), box, 0, px(5))
        pygame.draw.rect(surf, GUIDE, box, max(1, px(2)), px(5))
        self.wheel(surf, cam, "motor", mx, my, 0.8 * size / 2 / cam.scale,
                   -self._travelled / max(r, 1e-3), out)
        out.boxes.append(box)
        v = sim.ends.speed
        out.labels.append(PartLabel("motor", f"motor: feeds the chain at {v:.1f} m/s"
                                    if not expert else f"feed motor {v:.2f} m/s", mx, my,
                                    "below"))

    def _apparatus(self, surf: pygame.Surface, cam: Camera, sim, out: Drawn,
                   expert: bool) -> None:
        """A contact machine (``kind = "apparatus"``): its tables, channels, rollers and
        carts where the model has them."""
        app = sim.apparatus
        a = sim.config.apparatus
        H = app.H
        fy, _, _, mode = placement.floor(sim)
        if mode == "absorbing":
            self.floor(surf, cam, fy, "floor: takes the chain away", out)
        elif mode == "solid":
            self.floor(surf, cam, fy, "floor", out, absorbing=False)
        for tab in (app.table_up, getattr(app, "table_lo", None)):
            if tab is not None:
                top = float(max(tab.a.y, tab.b.y)) + float(tab.radius)
                self.table(surf, cam, (float(tab.a.x), top), (float(tab.b.x), top), out)
        half = (chain_view.chain_width(cam, sim.config.chain.link_radius) / 2 + px(4)) / cam.scale
        self.channel(surf, cam, np.asarray(app.channel_up), half)
        lo = getattr(app, "channel_lo", None)
        if lo is not None:
            self.channel(surf, cam, np.asarray(lo, dtype=float), half)
        units = [("upper", app.upper), ("lower", app.lower)]
        for key, u in units:
            if u is None:
                continue
            x, y = float(u.roller.position.x), float(u.roller.position.y)
            self.wheel(surf, cam, key, x, y, u.radius, float(u.roller.angle), out)
            if u.cart is not None:
                rp = max(px(6), int(round(u.radius * cam.scale)))
                box = self.cart(surf, cam, (x, u.yc), rp, u.direction, u.cart.incline,
                                u.cart.mass, _grams(u.cart.mass), out)
                cx, cy = cam.to_world(*box.midtop)
                name = "upper cart" if key == "upper" else "lower cart"
                out.labels.append(PartLabel(f"{key}_cart", name, cx, cy, "above"))
        x, y = float(app.upper.roller.position.x), float(app.upper.roller.position.y)
        out.labels.append(PartLabel("pickup", "pick-up roller", x, y + app.upper.radius,
                                    "above"))
        tab = app.table_up
        out.labels.append(PartLabel(
            "upper_table", "upper table (the beaker)" if not expert else
            f"beaker: upper table, xi2*H = {a.xi2 * H:.2f} m below the start",
            max(float(tab.a.x), x - 0.3), float(tab.a.y), "below"))
        mid = app.channel_up[len(app.channel_up) // 2]
        out.labels.append(PartLabel(
            "guide_up", f"lifts the chain {a.xi2 * H:.2f} m" if not expert else
            f"guide up xi2*H = {a.xi2 * H:.2f} m", float(mid[0]), float(mid[1]), "right"))
        if app.up_guide and getattr(app, "starting", False):
            what = ("starter motor: letting go" if getattr(app, "fading", False) else
                    "starter motor: runs the chain up")
            (sx, sy), (tx, ty) = app.up_guide[-1].a, app.up_guide[-1].b
            out.labels.append(PartLabel("starter", what, 0.5 * (sx + tx), 0.5 * (sy + ty),
                                        "left"))
        ex, ey = app.end
        if a.variant == "fold":
            follows = ""
            if expert and getattr(app, "end_follow", 0.0):
                follows = f", follows the landing ({100 * app.end_shift:+.0f} cm)"
            out.labels.append(PartLabel(
                "guide_lo", f"end guide: lifts the chain {a.xi3 * H:.2f} m" if not expert
                else f"end guide up xi3*H = {a.xi3 * H:.2f} m{follows}", ex, ey, "below"))
            if app.lower is not None:
                x, y = float(app.lower.roller.position.x), float(app.lower.roller.position.y)
                out.labels.append(PartLabel("fold", "folding roller", x,
                                            y + app.lower.radius, "above"))
                tab = app.table_lo
                out.labels.append(PartLabel(
                    "lower_table", "lower table (the bottom)" if not expert else
                    "bottom: lower table", min(float(tab.b.x), x + 0.35), float(tab.a.y),
                    "below"))
        elif a.variant == "open":
            out.labels.append(PartLabel("plate_lo", "lower plate: the chain slides away",
                                        ex, ey, "below"))

    def _ideal(self, surf: pygame.Surface, cam: Camera, sim, out: Drawn, expert: bool,
               every: int) -> None:
        """An ideal machine (``feed.drive`` ``ideal_*``): the same parts as the contact
        machine at the paper's geometry (:func:`ideal_parts`), the chain drawn running
        through them."""
        cfg = sim.config
        f = cfg.feed
        H, L = float(f.drop), float(sim.chain.L)
        width = chain_view.chain_width(cam, cfg.chain.link_radius)
        g = cfg.gravity
        ref = sim.reference
        land = self._landing(sim, float(ref.landing_x)) if ref is not None else None
        key = (id(sim), f.xi2, f.xi3, H, f.launch_angle, None if ref is None else
               (ref.q, ref.h), None if land is None else round(land, 3))
        if self._parts is None or self._parts[0] != key:
            self._parts = key, ideal_parts(sim, None if land is None else round(land, 3))
        parts = self._parts[1]
        up = parts.upper
        half = (width / 2 + px(4)) / cam.scale
        self.table(surf, cam, up.table[0], up.table[1], out)
        self.channel(surf, cam, up.channel, half)
        chain_view.draw_along(surf, cam, up.resting, 0.0, L, every, width)
        chain_view.draw_along(surf, cam, up.moving, self._travelled, L, every, width)
        self.paths += [up.resting, up.moving]
        R = IDEAL_ROLLER + float(cfg.chain.link_radius)
        self.wheel(surf, cam, "upper", *up.roller, IDEAL_ROLLER, -self._travelled / R, out)
        rp = max(px(7), int(round(IDEAL_ROLLER * cam.scale)))
        box = self.cart(surf, cam, up.roller, rp, -1.0, math.radians(30.0),
                        f.cart_force / (g * 0.5), f"{f.cart_force:.2g} N", out)
        mid = up.channel[len(up.channel) // 2]
        out.labels += [
            PartLabel("pickup", "pick-up roller (ideal)" if not expert else
                      "pick-up (paper's law)", up.roller[0], up.roller[1] + IDEAL_ROLLER,
                      "above"),
            PartLabel("upper_cart", "upper cart" if not expert else "upper cart F_uc",
                      *cam.to_world(*box.midtop), "above"),
            PartLabel("upper_table", "upper table (the beaker)" if not expert else
                      f"beaker: xi2*H = {f.xi2 * H:.2f} m below the start",
                      up.roller[0] - 0.3, up.table[0][1], "below"),
            PartLabel("guide_up", f"lifts the chain {f.xi2 * H:.2f} m" if not expert else
                      f"guide up xi2*H = {f.xi2 * H:.2f} m", float(mid[0]), float(mid[1]),
                      "right")]
        piston = sim.piston
        if piston is not None and piston.starting:
            out.labels.append(PartLabel("starter", f"starter motor: {sim.ends.speed:.1f} m/s "
                                        "until the machine takes over", 0.0, 0.0, "left"))
        if f.drive == "ideal_floor":
            self.floor(surf, cam, -H, "real floor: takes the chain, no pull", out,
                       absorbing=False)
            return
        if f.drive == "ideal_open":
            self._open(surf, cam, sim, out, width, expert)
            return
        lo = parts.lower
        if lo is None:
            self.floor(surf, cam, -H, "lower half (paper's law)", out)
            return
        self.channel(surf, cam, lo.channel, half)
        self.table(surf, cam, lo.table[0], lo.table[1], out)
        chain_view.draw_along(surf, cam, lo.moving, self._travelled, L, every, width)
        chain_view.draw_along(surf, cam, lo.resting, 0.0, L, every, width)
        self.paths += [lo.moving, lo.resting]
        self.wheel(surf, cam, "lower", *lo.roller, IDEAL_ROLLER, -self._travelled / R, out)
        box = self.cart(surf, cam, lo.roller, rp, 1.0, math.radians(30.0),
                        f.lower_cart_force / (g * 0.5), f"{f.lower_cart_force:.2g} N", out)
        rise = f.xi3 * H
        out.labels += [
            PartLabel("fold", "folding roller (ideal)" if not expert else
                      "put-down (paper's law)", lo.roller[0], lo.roller[1] + IDEAL_ROLLER,
                      "above"),
            PartLabel("lower_cart", "lower cart" if not expert else "lower cart F_lc",
                      *cam.to_world(*box.midtop), "above"),
            PartLabel("guide_lo", f"end guide: lifts the chain {rise:.2f} m" if not expert
                      else f"end guide up xi3*H = {rise:.2f} m", float(lo.channel[0, 0]),
                      -H, "below"),
            PartLabel("lower_table", "lower table (the bottom)" if not expert else
                      "bottom: lower table", lo.roller[0] + 0.45, lo.table[0][1], "below")]

    def _open(self, surf: pygame.Surface, cam: Camera, sim, out: Drawn, width: int,
              expert: bool) -> None:
        """The open arrangement with ideal rollers: the turn and the plate the landed chain
        slides away on, the chain on them marked as far as it has slid."""
        geom = placement.slide(sim)
        if geom is None:
            return
        path, slid = geom
        pts = cam.to_screen(path)
        pygame.draw.lines(surf, FLOOR, False, (pts + [0, width]).tolist(), max(2, px(3)))
        seg = np.hypot(*np.diff(path, axis=0).T)
        s = np.concatenate([[0.0], np.cumsum(seg)])
        x_right = cam.to_world(cam.rect.right, cam.rect.centery)[0]
        end = min(slid, float(np.interp(x_right, path[:, 0], s)) + 0.1)
        if end > 0:
            n = int(np.searchsorted(s, end))
            shown = np.vstack([path[:n], [np.interp(end, s, path[:, 0]),
                                          np.interp(end, s, path[:, 1])]])
            every = max(10, int(round(0.1 / sim.chain.L)))
            chain_view.draw_along(surf, cam, shown, slid, sim.chain.L, every, width)
            self.paths.append(shown)
        d = sim.config.feed.turn_drop
        moving = float(sim.slide_away.mass)
        x_turn = float(path[0, 0]) + 0.25  # on the plate, just past the turn
        out.labels.append(PartLabel(
            "plate_lo", f"plate: the chain slides away ({moving:.1f} kg moving)"
            if not expert else f"turn {d:g} m down, frictionless plate: Tbar_E = k d "
            f"({moving:.2f} kg moving)", x_turn, float(path[-1, 1]), "below"))


@dataclass(frozen=True)
class IdealHalf:
    """One half of an ideal machine as drawn (world, m): its table's top from end to end,
    its roller's centre, its channel's centre line, the chain that moves through it (the
    way it moves) and the chain resting on its table."""

    table: tuple[tuple[float, float], tuple[float, float]]
    roller: tuple[float, float]
    channel: np.ndarray
    moving: np.ndarray
    resting: np.ndarray


@dataclass(frozen=True)
class IdealParts:
    """An ideal machine's drawn parts: the upper half, and the lower half of the full
    machine (``ideal_fold``; else ``None``)."""

    upper: IdealHalf
    lower: IdealHalf | None


def ideal_parts(sim, landing_x: float | None = None) -> IdealParts:
    """Where an ideal machine's parts are drawn: the upper table ``xi2*H`` below the
    start with the pick-up roller and the channel up to the launch
    (:func:`~chainfountain.sim.guide.upper_channel`, the contact machine's); for the full
    machine the end guide from the landing (``landing_x``, default where the paper's
    fountain lands) up ``xi3*H`` (:func:`~chainfountain.sim.guide.end_channel`), the
    lower table and the folding roller."""
    cfg = sim.config
    f = cfg.feed
    H, L = float(f.drop), float(sim.chain.L)
    rho = float(cfg.chain.link_radius)
    R = IDEAL_ROLLER + rho
    line, _ = upper_channel(H, f.xi2, f.launch_angle, CHANNEL_R, 0.1, 0.5 * L)
    x0, y_up = float(line[0, 0]), float(line[0, 1])
    xr, yc = x0 - 0.05, y_up - R
    y_tab = yc - R
    th = np.linspace(-0.5 * math.pi, -1.5 * math.pi, 24)
    wrap = np.column_stack([xr + R * np.cos(th), yc + R * np.sin(th)])
    upper = IdealHalf(table=((xr - IDEAL_TABLE, y_tab - rho), (x0, y_tab - rho)),
                      roller=(xr, yc), channel=line, moving=np.vstack([wrap, line]),
                      resting=np.array([[xr - IDEAL_TABLE, y_tab], [xr, y_tab]]))
    ref = sim.reference
    if f.drive != "ideal_fold" or ref is None:
        return IdealParts(upper, None)
    xE = float(ref.landing_x) if landing_x is None else float(landing_x)
    alphaE = landing_angle(ref.q, ref.h, H)
    try:
        cp, i_end = end_channel(xE, -H, alphaE, f.xi3 * H, CHANNEL_R, 0.1, 0.5 * L)
    except ValueError:  # too small a rise to bend up and back: a flat exit
        cp, i_end = end_channel(xE, -H, alphaE, 0.0, CHANNEL_R, 0.1, 0.5 * L)
    xl, y_lo = float(cp[-1, 0]), float(cp[-1, 1])
    xf, ycf = xl + 0.25, y_lo - R
    y_tab_lo = ycf - R
    th = np.linspace(0.5 * math.pi, -0.5 * math.pi, 24)
    wrap = np.column_stack([xf + R * np.cos(th), ycf + R * np.sin(th)])
    lower = IdealHalf(table=((xl - 0.1, y_tab_lo - rho), (xf + IDEAL_TABLE, y_tab_lo - rho)),
                      roller=(xf, ycf), channel=cp,
                      moving=np.vstack([cp[i_end:], [[xf, y_lo]], wrap]),
                      resting=np.array([[xf, y_tab_lo], [xf - 0.35, y_tab_lo]]))
    return IdealParts(upper, lower)


def pile_surface(size: tuple[int, int], link_px: int, width: int) -> pygame.Surface:
    """The hidden part of a beaker's pile: chain laid in rows on a dark backing."""
    key = ("pile-bg", size, link_px, width)
    img = _PILE_BG.get(key)
    if img is None:
        if len(_PILE_BG) > 16:
            _PILE_BG.clear()
        img = pygame.Surface(size)
        img.fill(tuple(int(0.35 * c) for c in CHAIN_DARK))
        img.blit(chain_view.pile_texture(size, link_px, width), (0, 0))
        _PILE_BG[key] = img
    return img


_PILE_BG: dict[tuple, pygame.Surface] = {}


def cart_reach(scale: float | None = None) -> tuple[float, float]:
    """How far (m) a cart's rope, post and ramp reach out from its roller, and how high
    above it, at ``scale`` px per metre (their least sizes in pixels count when the view
    is small; ``None``: their sizes in metres)."""
    if scale is None or scale <= 0:
        return CART_REACH + 0.05, POST + 0.05
    out = max(0.05, px(26) / scale) + max(RAMP, px(110) / scale) + px(30) / scale
    up = max(POST, px(60) / scale) + px(20) / scale
    return out, up


def machine_bounds(sim, scale: float | None = None) -> list[tuple[float, float]]:
    """World points the view must show to show the machine: the rollers with their carts
    (:func:`cart_reach` at ``scale``), a contact machine's end and floor (``floor_depth``
    below the end), the pot, an ideal machine's drawn parts."""
    pts: list[tuple[float, float]] = []
    cfg = sim.config
    reach, high = cart_reach(scale)
    if sim.apparatus is not None:
        for u in (sim.apparatus.upper, sim.apparatus.lower):
            if u is not None:
                x, y = float(u.roller.position.x), float(u.roller.position.y)
                d = 1.0 if u.direction >= 0 else -1.0
                pts += [(x + d * (u.radius + reach), y + high), (x - d * u.radius, y)]
        pts.append(tuple(sim.apparatus.end))
        pts.append((float(sim.apparatus.end[0]), sim.apparatus.floor_y - 0.05))  # the floor
    elif sim.beaker is not None:
        outline = placement.vessel(sim)[0]
        pts += [(float(outline[:, 0].min()) - 0.15, float(outline[:, 1].min()) - 0.05)]
    elif sim.piston is not None:  # an ideal machine: drawn as its parts
        parts = ideal_parts(sim)
        for half, d in ((parts.upper, -1.0), (parts.lower, 1.0)):
            if half is not None:
                x, y = half.roller
                pts += [(x + d * (IDEAL_ROLLER + reach), y + high),
                        (x, half.table[0][1] - 0.15)]
        if parts.lower is not None:
            pts.append((float(parts.lower.channel[:, 0].min()), -cfg.feed.drop - 0.1))
    return pts
