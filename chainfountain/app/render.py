"""Pixels: the camera (metres <-> pixels), the scene, the live plots, text panels.

Everything here reads the model (a :class:`~chainfountain.sim.world.Simulation`
and a :class:`~chainfountain.app.readout.Readout`) and draws; nothing here
changes the model.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pygame

from chainfountain.app.readout import Readout
from chainfountain.sim.world import Simulation

# colours (projector friendly: light lines on a dark blue-grey background)
BG = (22, 27, 36)
SCENE_BG = (16, 20, 28)
GRID = (34, 41, 54)
TEXT = (220, 226, 235)
DIM = (140, 150, 165)
CHAIN = (255, 170, 60)
THEORY = (90, 210, 255)
ROPE = (170, 150, 120)
LABEL = (205, 212, 225)
"""Names of the machine's parts."""
THEORY_BAND = (38, 92, 118)
"""The paper's curve, drawn as a band under the chain (THEORY darkened on SCENE_BG)."""
VERTEX = (255, 90, 200)
FLOOR = (150, 160, 175)
ABSORB = (70, 130, 90)
GUIDE = (200, 200, 210)
GLASS = (170, 210, 230)
ROLLER = (180, 190, 255)
CART = (120, 220, 160)
TRACK = (110, 120, 135)
T0_COL = (255, 120, 90)
TE_COL = (120, 200, 255)
SPEED_COL = (255, 210, 90)
WARN = (255, 110, 90)
OK = (120, 220, 140)


_SCALE = [1.0]
"""The text scale (:func:`set_text_scale`): 1 at the default window size."""


def set_text_scale(scale: float) -> None:
    """Scale all text and the layout measures around it (:func:`px`) by ``scale``: the
    window grows its text with its size, and more in projector mode."""
    _SCALE[0] = float(scale)


def text_scale() -> float:
    """The current text scale (1 at the default window size)."""
    return _SCALE[0]


def px(n: float) -> int:
    """``n`` pixels of the default layout at the current text scale."""
    return int(round(n * _SCALE[0]))


def font(size: int) -> pygame.font.Font:
    """pygame's bundled font at ``size`` px of the default layout, scaled by the text scale
    (cached)."""
    key = px(size)
    f = _FONTS.get(key)
    if f is None:
        f = pygame.font.Font(None, key)
        _FONTS[key] = f
    return f


_FONTS: dict[int, pygame.font.Font] = {}

TEXT_CACHE = 1024
"""Most rendered texts (and wrapped paragraphs) kept for the next frames: a frame draws
the same labels again, and rendering and measuring text cost about a third of drawing."""
_TEXTS: OrderedDict[tuple, pygame.Surface] = OrderedDict()
_WRAPS: OrderedDict[tuple, list[str]] = OrderedDict()


def _remember(cache: OrderedDict, key: tuple, value: object) -> None:
    cache[key] = value
    if len(cache) > TEXT_CACHE:
        cache.popitem(last=False)


def text(f: pygame.font.Font, s: str, antialias: bool,
         colour: tuple[int, int, int] | pygame.Color) -> pygame.Surface:
    """``f.render(s, antialias, colour)``, kept for the next frames (at most
    :data:`TEXT_CACHE` texts, the least recently drawn forgotten first). The surface is
    shared: blit it, do not draw on it."""
    key = (f, s, antialias, tuple(colour))  # the font itself: its id could be reused
    img = _TEXTS.get(key)
    if img is None:
        img = f.render(s, antialias, colour)
        _remember(_TEXTS, key, img)
    else:
        _TEXTS.move_to_end(key)
    return img


def wrap(f: pygame.font.Font, text: str, width: int) -> list[str]:
    """``text`` split at spaces into lines no wider than ``width`` pixels in font ``f``
    (a single word wider than that gets a line of its own; kept like :func:`text`)."""
    key = (f, text, width)
    rows = _WRAPS.get(key)
    if rows is None:
        rows = _wrap(f, text, width)
        _remember(_WRAPS, key, rows)
    else:
        _WRAPS.move_to_end(key)
    return list(rows)


def _wrap(f: pygame.font.Font, text: str, width: int) -> list[str]:
    lines: list[str] = []
    cur = ""
    for word in text.split():
        trial = f"{cur} {word}" if cur else word
        if cur and f.size(trial)[0] > width:
            lines.append(cur)
            cur = word
        else:
            cur = trial
    return lines + [cur] if cur else lines


def nice_step(span: float, target: int = 5) -> float:
    """A 1-2-5 step that cuts ``span`` into about ``target`` parts."""
    if not math.isfinite(span) or span <= 0:
        return 1.0
    raw = span / target
    mag = 10 ** math.floor(math.log10(raw))
    for m in (1, 2, 5, 10):
        if m * mag >= raw:
            return m * mag
    return 10 * mag


@dataclass
class Camera:
    """World (m, y up) to screen (px, y down) within a rectangle: ``scale`` px per metre."""

    rect: pygame.Rect
    scale: float = 200.0
    cx: float = 0.0
    cy: float = 0.0

    def to_screen(self, pts: np.ndarray) -> np.ndarray:
        """``(n, 2)`` world points to screen pixels (float)."""
        p = np.asarray(pts, dtype=float).reshape(-1, 2)
        out = np.empty_like(p)
        out[:, 0] = self.rect.centerx + (p[:, 0] - self.cx) * self.scale
        out[:, 1] = self.rect.centery - (p[:, 1] - self.cy) * self.scale
        return out

    def point(self, x: float, y: float) -> tuple[int, int]:
        return (int(round(self.rect.centerx + (x - self.cx) * self.scale)),
                int(round(self.rect.centery - (y - self.cy) * self.scale)))

    def to_world(self, sx: float, sy: float) -> tuple[float, float]:
        return (self.cx + (sx - self.rect.centerx) / self.scale,
                self.cy - (sy - self.rect.centery) / self.scale)

    def fit(self, x0: float, y0: float, x1: float, y1: float, margin: float = 0.08,
            top: int = 0) -> None:
        """Show the world box ``[x0, x1] x [y0, y1]`` with a margin, below the view's top
        ``top`` pixels (kept free for a card over the view)."""
        w = max(x1 - x0, 1e-3) * (1 + 2 * margin)
        h = max(y1 - y0, 1e-3) * (1 + 2 * margin)
        top = min(max(top, 0), self.rect.h // 2)
        self.scale = max(1e-3, min(self.rect.w / w, (self.rect.h - top) / h))
        self.cx, self.cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1) + 0.5 * top / self.scale

    def zoom(self, factor: float, about: tuple[float, float]) -> None:
        """Zoom by ``factor`` keeping the screen point ``about`` fixed."""
        wx, wy = self.to_world(*about)
        self.scale = min(max(self.scale * factor, 5.0), 50000.0)
        self.cx = wx - (about[0] - self.rect.centerx) / self.scale
        self.cy = wy + (about[1] - self.rect.centery) / self.scale

    def pan(self, dx_px: float, dy_px: float) -> None:
        self.cx -= dx_px / self.scale
        self.cy += dy_px / self.scale


def scene_bounds(sim: Simulation, readout: Readout | None) -> tuple[float, float, float, float]:
    """World box that shows launch point, fountain, floor, rollers and carts."""
    H = sim.drop
    xs = [-0.25, 0.3]
    ys = [-H - 0.05, 0.3]
    ref = sim.reference
    if ref is not None:
        xs += [ref.landing_x + 0.2]
        ys += [ref.h + 0.1]
    if readout is not None and readout.curve is not None and len(readout.curve):
        xs += [float(readout.curve[:, 0].max()) + 0.1]
        ys += [float(readout.curve[:, 1].max()) + 0.1]
    pts = sim.chain_polyline()
    if len(pts):
        xs += [float(pts[:, 0].max()) + 0.2]
        ys += [float(pts[:, 1].max()) + 0.15]
    vessel = sim.vessel_geometry()
    if vessel is not None:
        xs += [float(vessel[0][:, 0].min()) - 0.1]
        ys += [float(vessel[0][:, 1].min()) - 0.05]
    for x, y, r, _ in sim.roller_geometry():
        xs += [x - r, x + r]
        ys += [y - r, y + r]
    for (a, b) in sim.track_geometry():
        xs += [a[0], b[0]]
        ys += [a[1], b[1]]
    return min(xs), min(ys), max(xs), max(ys)


_SHADES: dict[tuple, pygame.Surface] = {}


def _shade(size: tuple[int, int], colour: tuple[int, int, int], alpha: int) -> pygame.Surface:
    """A translucent rectangle (cached by size and colour)."""
    key = (size, colour, alpha)
    surf = _SHADES.get(key)
    if surf is None:
        if len(_SHADES) > 64:
            _SHADES.clear()
        surf = pygame.Surface(size, pygame.SRCALPHA)
        surf.fill((*colour, alpha))
        _SHADES[key] = surf
    return surf


def _pile_hatch(size: tuple[int, int]) -> pygame.Surface:
    """The shaded, hatched box of a pot's pile below its plate (cached by size: a few
    hundred dashes a frame cost about 0.5 ms)."""
    key = ("pile", size)
    img = _SHADES.get(key)
    if img is None:
        if len(_SHADES) > 64:
            _SHADES.clear()
        img = _shade(size, CHAIN, 45).copy()
        w, h = size
        for y in range(3, h, 6):
            _dashed(img, (120, 90, 50), (2, y), (w - 2, y), 5.0)
        _SHADES[key] = img
    return img


def _dashed(surf: pygame.Surface, col, a, b, dash: float = 8.0, width: int = 1) -> None:
    ax, ay = a
    bx, by = b
    length = math.hypot(bx - ax, by - ay)
    if length < 1:
        return
    n = int(length // dash)
    for i in range(0, n, 2):
        f0, f1 = i * dash / length, min((i + 1) * dash / length, 1.0)
        pygame.draw.line(surf, col, (ax + f0 * (bx - ax), ay + f0 * (by - ay)),
                         (ax + f1 * (bx - ax), ay + f1 * (by - ay)), width)


def _floor_label(sim: Simulation) -> str:
    """What the absorbing floor stands for: a real floor, or an ideal machine's lower half."""
    cfg = sim.config
    if cfg.kind == "feed" and cfg.feed.drive == "ideal_fold":
        return ("lower half (paper's law): lift xi3*H, put-down at rest, lower cart: pulls "
                f"Tbar_E {sim.reference.TE_bar:.3f}" if sim.reference is not None else
                "lower half (paper's law)")
    if cfg.kind == "feed" and cfg.feed.drive == "ideal_floor":
        return "real floor: takes the chain without pull (Tbar_E = 0)"
    if sim.slide_away is not None:  # feed.drive = "ideal_open"
        return (f"turn {cfg.feed.turn_drop:g} m down onto a frictionless plate: the chain "
                f"slides away ({sim.slide_away.mass:.2f} kg moving), pulling Tbar_E = k d")
    return "absorbing floor"


SLIDE_MARK = 0.1
"""Spacing (m) of the marks on the chain that slides away on the open arrangement's plate:
they move with it, so the eye sees the chain that no longer decelerates."""


def _draw_slide(surf: pygame.Surface, cam: Camera, sim: Simulation, path: np.ndarray,
                slid: float) -> None:
    """The open arrangement with ideal rollers: the turn and the plate the landed chain
    slides away on (``path``, m: :meth:`~chainfountain.sim.world.Simulation.slide_geometry`),
    the chain on them marked every :data:`SLIDE_MARK` as far as it has slid (``slid``, m)."""
    seg = np.hypot(*np.diff(path, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    width = max(3, min(8, int(round(2 * sim.config.chain.link_radius * cam.scale))))
    pts = cam.to_screen(path)
    pygame.draw.lines(surf, FLOOR, False, (pts + [0, width]).tolist(), 2)  # the plate
    # the chain reaches as far as it has slid; drawn to the view's right edge (the path's
    # x only grows: a quarter turn, then the plate)
    x_right = cam.to_world(cam.rect.right, cam.rect.centery)[0]
    end = min(slid, float(np.interp(x_right, path[:, 0], s)) + SLIDE_MARK)
    n = int(np.searchsorted(s, end))
    shown = np.vstack([path[:n], [np.interp(end, s, path[:, 0]), np.interp(end, s, path[:, 1])]])
    if len(shown) > 1:
        pygame.draw.lines(surf, CHAIN, False, cam.to_screen(shown).tolist(), width)
    marks = (slid % SLIDE_MARK) + SLIDE_MARK * np.arange(int(end / SLIDE_MARK) + 1)
    marks = marks[marks <= end]
    mx, my = np.interp(marks, s, path[:, 0]), np.interp(marks, s, path[:, 1])
    for px, py in cam.to_screen(np.column_stack([mx, my])).tolist():
        if cam.rect.left <= px <= cam.rect.right:
            pygame.draw.line(surf, SCENE_BG, (px, py - width), (px, py + width), 2)


def draw_scene(surf: pygame.Surface, cam: Camera, sim: Simulation, readout: Readout | None,
               show_theory: bool = True) -> None:
    """The apparatus, the chain, the theory curve and the scale bar, clipped to the camera rect."""
    rect = cam.rect
    old_clip = surf.get_clip()
    surf.set_clip(rect)
    surf.fill(SCENE_BG, rect)
    _grid(surf, cam)
    # floor
    fy, fx0, fx1, mode = sim.floor_geometry()
    slide = sim.slide_geometry()  # the open arrangement's turn and plate, or None
    if mode == "solid":
        a, b = cam.point(fx0, fy), cam.point(fx1, fy)
        pygame.draw.line(surf, FLOOR, a, b, 3)
        for x in range(a[0], b[0], 12):
            pygame.draw.line(surf, FLOOR, (x, a[1] + 1), (x - 8, a[1] + 9), 1)
    elif mode == "absorbing":  # "none": an apparatus with a catch, no floor to draw
        y = cam.point(0, fy)[1]
        band = pygame.Rect(rect.x, y, rect.w, max(4, rect.bottom - y))
        if band.top < rect.bottom:
            surf.blit(_shade(band.size, ABSORB, 60), band.topleft)
        pygame.draw.line(surf, ABSORB, (rect.x, y), (rect.right, y), 2)
        label = text(font(16), _floor_label(sim), True, ABSORB)
        if slide is not None:  # below the plate the chain slides on, clear of the turn
            y = cam.point(0.0, float(slide[0][-1, 1]))[1] + 8
        surf.blit(label, (rect.x + 8, y + 4))
    if slide is not None:
        _draw_slide(surf, cam, sim, *slide)
    vessel = sim.vessel_geometry()
    if vessel is not None:
        _draw_pot(surf, cam, *vessel)
    # cart tracks and carts
    for a, b in sim.track_geometry():
        pygame.draw.line(surf, TRACK, cam.point(*a), cam.point(*b), 2)
    for rope in getattr(sim, "rope_geometry", list)():
        pygame.draw.lines(surf, ROPE, False, cam.to_screen(rope).tolist(), 1)
        pygame.draw.circle(surf, TRACK, cam.point(*rope[1]), 4, 1)
    for verts in sim.cart_geometry():
        pts = cam.to_screen(verts)
        pygame.draw.polygon(surf, CART, pts.tolist(), 0)
        pygame.draw.polygon(surf, (20, 60, 40), pts.tolist(), 1)
    # rollers: a wheel with spokes that turn with the body
    for x, y, r, ang in sim.roller_geometry():
        c = cam.point(x, y)
        rp = max(2, int(r * cam.scale))
        pygame.draw.circle(surf, ROLLER, c, rp, 2)
        for k in range(3):
            a = ang + k * 2 * math.pi / 3
            pygame.draw.line(surf, ROLLER, c, cam.point(x + r * math.cos(a), y + r * math.sin(a)),
                             1)
    if vessel is None:
        _draw_guide(surf, cam, sim)
    _part_labels(surf, cam, sim)
    width = max(3, min(8, int(round(2 * sim.config.chain.link_radius * cam.scale))))
    theory = show_theory and readout is not None and readout.curve is not None
    if theory:
        # the paper's curve as a wide band under the chain: where the chain lies on it,
        # the band shows on both sides of it; where it does not, the band shows apart
        pts = cam.to_screen(readout.curve)
        if len(pts) >= 2:
            pygame.draw.lines(surf, THEORY_BAND, False, pts.tolist(), width + 10)
    # the chain: one polyline
    poly = sim.chain_polyline()
    if len(poly) >= 2:
        pygame.draw.lines(surf, CHAIN, False, cam.to_screen(poly).tolist(), width)
    if theory:
        _height_marker(surf, cam, readout)
    _scale_bar(surf, cam)
    surf.set_clip(old_clip)


def _draw_pot(surf: pygame.Surface, cam: Camera, outline: np.ndarray,
              plate: np.ndarray) -> None:
    """A beaker level's pot: its walls, and below the plate the part of the pile that is
    out of the solver, shaded."""
    (x0, _), (x1, _) = plate
    bottom = float(outline[1, 1])
    a, b = cam.point(float(x0), float(plate[0, 1])), cam.point(float(x1), bottom)
    hidden = pygame.Rect(a[0], a[1], max(1, b[0] - a[0]), max(1, b[1] - a[1]))
    hidden = hidden.clip(cam.rect)
    if hidden.w > 0 and hidden.h > 0:
        surf.blit(_pile_hatch(hidden.size), hidden.topleft)
    pygame.draw.line(surf, GUIDE, cam.point(*plate[0]), cam.point(*plate[1]), 2)
    pygame.draw.lines(surf, GLASS, False, cam.to_screen(outline).tolist(), 3)


def _part_labels(surf: pygame.Surface, cam: Camera, sim: Simulation) -> list[pygame.Rect]:
    """The machine's parts named beside them (:meth:`Simulation.part_labels`), each with a
    short leader line to the part; a label that would cover one already placed moves a
    row further out (a row down beside the part). Returns the labels' boxes."""
    f = font(16)
    placed: list[pygame.Rect] = []
    for lb in sim.part_labels():
        ax, ay = cam.point(lb.x, lb.y)
        img = text(f, lb.text, True, LABEL)
        w, h = img.get_size()
        tier = lb.tier
        for _ in range(8):
            out = (h + 4) * tier
            if lb.side == "above":
                tx, ty, lx, ly = ax - w // 2, ay - 26 - h - out, ax, ay - 24 - out
            elif lb.side == "below":
                tx, ty, lx, ly = ax - w // 2, ay + 22 + out, ax, ay + 20 + out
            elif lb.side == "left":
                tx, ty, lx, ly = ax - 30 - w, ay - h // 2 + out, ax - 26, ay + out
            else:
                tx, ty, lx, ly = ax + 30, ay - h // 2 + out, ax + 26, ay + out
            tx = max(cam.rect.left + 4, min(tx, cam.rect.right - w - 4))
            box = pygame.Rect(tx - 3, ty - 1, w + 6, h + 2)
            if box.collidelist(placed) < 0:
                break
            tier += 1
        placed.append(box)
        pygame.draw.line(surf, LABEL, (ax, ay), (lx, ly), 1)
        bg = pygame.Surface((w + 6, h + 2), pygame.SRCALPHA)
        bg.fill((0, 0, 0, 140))
        surf.blit(bg, (tx - 3, ty - 1))
        surf.blit(img, (tx, ty))
    return placed


def _height_marker(surf: pygame.Surface, cam: Camera, ro: Readout) -> None:
    """A height marker at the fountain's top: a dashed level line with how high the top
    is above the launch (a beaker: the pick-up), an arrow up from there, and (a fed fountain) a tick
    at the height the paper predicts from the settings."""
    if ro.vertex is None or not math.isfinite(ro.h):
        return
    vx, vy = cam.point(*ro.vertex)
    x0, y0 = cam.point(ro.vertex[0], ro.vertex[1] - ro.h)  # from the launch (or pick-up)
    half = max(40, int(0.25 * abs(cam.point(ro.l, 0.0)[0] - cam.point(0.0, 0.0)[0])))
    _dashed(surf, VERTEX, (vx - half, vy), (vx + half, vy), 6.0, 1)
    if y0 - vy > 24:
        _dashed(surf, VERTEX, (x0, y0), (vx, vy + 2), 4.0, 1)
        pygame.draw.polygon(surf, VERTEX, [(vx, vy + 1), (vx - 4, vy + 9), (vx + 4, vy + 9)])
    f = font(18)
    label = text(f, f"top: {ro.h:.2f} m above the {ro.origin}", True, VERTEX)
    # right of the level line, or left of it when the view ends first (never cut off)
    right = vx + half + 6 + label.get_width() <= cam.rect.right - 4
    lx = vx + half + 6 if right else vx - half - 6 - label.get_width()
    lx = max(cam.rect.left + 4, lx)
    surf.blit(label, (lx, vy - label.get_height() // 2))
    if math.isfinite(ro.paper_h):
        py = cam.point(0.0, ro.paper_h)[1]
        tick = (vx + half - 16, vx + half) if right else (vx - half, vx - half + 16)
        pygame.draw.line(surf, THEORY, (tick[0], py), (tick[1], py), 2)
        txt = text(f, f"paper: {ro.paper_h:.2f} m", True, THEORY)
        dy = txt.get_height() if abs(py - vy) < txt.get_height() else 0
        tx = vx + half + 6 if right else max(cam.rect.left + 4, vx - half - 6 - txt.get_width())
        surf.blit(txt, (tx, py - txt.get_height() // 2 + (dy if py >= vy else -dy)))


def _grid(surf: pygame.Surface, cam: Camera) -> None:
    rect = cam.rect
    x0, y1 = cam.to_world(rect.left, rect.top)
    x1, y0 = cam.to_world(rect.right, rect.bottom)
    step = nice_step(max(x1 - x0, y1 - y0), 8)
    if step * cam.scale < 12:
        return
    x = math.floor(x0 / step) * step
    while x <= x1:
        sx = cam.point(x, 0)[0]
        pygame.draw.line(surf, GRID, (sx, rect.top), (sx, rect.bottom), 1)
        x += step
    y = math.floor(y0 / step) * step
    while y <= y1:
        sy = cam.point(0, y)[1]
        pygame.draw.line(surf, GRID, (rect.left, sy), (rect.right, sy), 1)
        y += step


def _draw_guide(surf: pygame.Surface, cam: Camera, sim: Simulation) -> None:
    (ox, oy), (ux, uy) = sim.guide_geometry()
    length = max(0.15, sim.config.feed.guide_links * sim.chain.L * 1.5)
    nx, ny = -uy, ux
    half = max(3.0 / cam.scale, 2.5 * sim.config.chain.link_radius)
    for s in (-1.0, 1.0):
        a = cam.point(ox + s * half * nx, oy + s * half * ny)
        b = cam.point(ox - length * ux + s * half * nx, oy - length * uy + s * half * ny)
        pygame.draw.line(surf, GUIDE, a, b, 2)
    # the motor box at the back of the guide
    bx, by = ox - length * ux, oy - length * uy
    c = cam.point(bx, by)
    size = max(10, int(0.05 * cam.scale))
    box = pygame.Rect(0, 0, size, size)
    box.center = c
    pygame.draw.rect(surf, (70, 75, 90), box, 0, 3)
    pygame.draw.rect(surf, GUIDE, box, 1, 3)
    what = "start" if getattr(sim, "apparatus", None) is not None else "feed"
    piston = getattr(sim, "piston", None)
    if piston is not None:  # an ideal machine's upper half
        what = ("starter motor (the machine's laws take over once the fountain has formed):"
                if piston.starting else "pick-up (paper's law), lift xi2*H, upper cart:")
    lbl = text(font(16), f"{what} {sim.feed.speed:.2f} m/s", True, GUIDE)
    x = box.left - lbl.get_width() - 4
    if x < cam.rect.left + 2:  # no room on the left: put it below the motor box
        surf.blit(lbl, (box.left, box.bottom + 2))
    else:
        surf.blit(lbl, (x, box.top - 4))


def _scale_bar(surf: pygame.Surface, cam: Camera) -> None:
    rect = cam.rect
    target = rect.w * 0.18 / cam.scale
    length = nice_step(target * 2, 2)
    while length * cam.scale > rect.w * 0.3:
        length /= 2
    bar = int(length * cam.scale)
    x0, y0 = rect.left + 16, rect.bottom - px(18)
    pygame.draw.line(surf, TEXT, (x0, y0), (x0 + bar, y0), 2)
    for x in (x0, x0 + bar):
        pygame.draw.line(surf, TEXT, (x, y0 - 5), (x, y0 + 5), 2)
    txt = f"{length:g} m" if length >= 0.01 else f"{length * 1000:g} mm"
    lbl = text(font(18), txt, True, TEXT)
    surf.blit(lbl, (x0 + bar // 2 - lbl.get_width() // 2, y0 - 6 - lbl.get_height()))


# ----------------------------------------------------------------------------- plots
@dataclass
class Series:
    """One curve of a plot."""

    x: np.ndarray
    y: np.ndarray
    colour: tuple[int, int, int]
    label: str = ""
    points: bool = False
    width: int = 2
    dashed: bool = False


def _downsample(x: np.ndarray, y: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    if len(x) <= n:
        return x, y
    idx = np.linspace(0, len(x) - 1, n).astype(int)
    return x[idx], y[idx]


def fit_text(f: pygame.font.Font, s: str, width: int) -> str:
    """``s``, or as much of it as fits in ``width`` pixels in font ``f`` with "..." after
    it."""
    if f.size(s)[0] <= width:
        return s
    while s and f.size(s + "...")[0] > width:
        s = s[:-1]
    return s.rstrip() + "..."


def draw_plot(surf: pygame.Surface, rect: pygame.Rect, title: str, xlabel: str,
              series: Sequence[Series], *, xlim: tuple[float, float] | None = None,
              ylim: tuple[float, float] | None = None,
              bands: Sequence[tuple] = ()) -> None:
    """A small line/point plot with axes, ticks, a legend and shaded y-bands.

    ``bands`` are ``(lo, hi, colour)`` or ``(lo, hi, colour, label)``.
    """
    pygame.draw.rect(surf, (28, 34, 45), rect, 0, 4)
    f = font(16)
    small = font(14)
    legend = sum(small.size(s.label)[0] + 12 for s in series if s.label)
    title = fit_text(f, title, rect.w - 6 - 8 - legend)  # never under the legend
    surf.blit(text(f, title, True, TEXT), (rect.x + 6, rect.y + px(4)))
    inner = pygame.Rect(rect.x + px(40), rect.y + px(22), rect.w - px(50), rect.h - px(44))
    if inner.w < 20 or inner.h < 20:
        return
    xs = [s.x[np.isfinite(s.x) & np.isfinite(s.y)] for s in series]
    ys = [s.y[np.isfinite(s.x) & np.isfinite(s.y)] for s in series]
    allx = np.concatenate(xs) if xs else np.zeros(0)
    ally = np.concatenate(ys) if ys else np.zeros(0)
    if xlim is None:
        xlim = (float(allx.min()), float(allx.max())) if len(allx) else (0.0, 1.0)
    if ylim is None:
        ylim = (float(ally.min()), float(ally.max())) if len(ally) else (0.0, 1.0)
    x0, x1 = xlim
    y0, y1 = ylim
    if not x1 > x0:
        x0, x1 = x0 - 0.5, x0 + 0.5
    if not y1 > y0:
        y0, y1 = y0 - 0.5, y0 + 0.5

    def sx(v):
        return inner.x + (np.asarray(v) - x0) / (x1 - x0) * inner.w

    def sy(v):
        return inner.bottom - (np.asarray(v) - y0) / (y1 - y0) * inner.h

    old = surf.get_clip()
    band_labels: list[tuple[pygame.Surface, tuple[int, int]]] = []
    for lo, hi, col, *label in bands:
        a, b = max(lo, y0), min(hi, y1)
        if b > a:
            band = pygame.Rect(inner.x, int(sy(b)), inner.w, max(1, int(sy(a) - sy(b))))
            surf.blit(_shade(band.size, col, 45), band.topleft)
            if label:  # written last, over the grid and the curves
                img = text(font(14), label[0], True, col)
                band_labels.append((img, (band.right - img.get_width() - 4, band.y + 3)))
    # axes and ticks
    for val in _ticks(y0, y1, 4):
        yy = int(sy(val))
        pygame.draw.line(surf, GRID, (inner.x, yy), (inner.right, yy), 1)
        lbl = text(small, f"{val:g}", True, DIM)
        surf.blit(lbl, (inner.x - lbl.get_width() - 4, yy - lbl.get_height() // 2))
    for val in _ticks(x0, x1, 5):
        xx = int(sx(val))
        pygame.draw.line(surf, GRID, (xx, inner.y), (xx, inner.bottom), 1)
        lbl = text(small, f"{val:g}", True, DIM)
        surf.blit(lbl, (xx - lbl.get_width() // 2, inner.bottom + 3))
    pygame.draw.rect(surf, DIM, inner, 1)
    xl = text(small, xlabel, True, DIM)
    surf.blit(xl, (inner.right - xl.get_width(), inner.bottom + 3 + small.get_height()))
    surf.set_clip(inner)
    for s in series:
        ok = np.isfinite(s.x) & np.isfinite(s.y)
        x, y = _downsample(s.x[ok], s.y[ok], max(2, inner.w))
        if len(x) == 0:
            continue
        pts = np.column_stack((sx(x), sy(y)))
        if s.points:
            for qx, qy in pts[:: max(1, len(pts) // 120)]:
                surf.fill(s.colour, (int(qx) - 1, int(qy) - 1, 3, 3))
        elif len(pts) >= 2:
            if s.dashed:
                for a, b in zip(pts[:-1:2], pts[1::2], strict=False):
                    pygame.draw.line(surf, s.colour, a, b, s.width)
            else:
                pygame.draw.lines(surf, s.colour, False, pts.tolist(), s.width)
    for img, at in band_labels:  # on a backing, so that no grid line or curve crosses it
        surf.blit(_shade((img.get_width() + 4, img.get_height()), BG, 200),
                  (at[0] - 2, at[1]))
        surf.blit(img, at)
    surf.set_clip(old)
    # legend
    lx = rect.right - 8
    for s in reversed([s for s in series if s.label]):
        lbl = text(small, s.label, True, s.colour)
        lx -= lbl.get_width()
        surf.blit(lbl, (lx, rect.y + 6))
        lx -= 12


def _ticks(lo: float, hi: float, n: int) -> list[float]:
    step = nice_step(hi - lo, n)
    start = math.ceil(lo / step) * step
    out = []
    v = start
    while v <= hi + 1e-9 * step and len(out) < 20:
        out.append(round(v / step) * step + 0.0)
        v += step
    return out


def text_block(surf: pygame.Surface, pos: tuple[int, int], lines: Sequence[tuple[str, tuple]],
               size: int = 18, line_h: int | None = None) -> int:
    """Draw lines of text; returns the y below the last line."""
    f = font(size)
    x, y = pos
    lh = line_h or int(size * 0.95)
    for txt, col in lines:
        surf.blit(text(f, txt, True, col), (x, y))
        y += lh
    return y
