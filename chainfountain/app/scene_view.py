"""The scene: the machine, the paper's curve (thin, dashed, behind the chain), the chain
with its travelling marks, the height marker, the parts' labels (laid out clear of each
other and of the chain) and the scale bar. It only reads the model.
"""

from __future__ import annotations

import math

import numpy as np
import pygame

from chainfountain.app import chain_view, labels
from chainfountain.app.camera import Camera, nice_step
from chainfountain.app.labels import LabelLayout, Placed, Request
from chainfountain.app.machine_view import Drawn, MachineView, machine_bounds
from chainfountain.app.palette import GRID, LABEL, LABEL_BG, SCENE_BG, TEXT, THEORY, VERTEX
from chainfountain.app.readout import Readout
from chainfountain.app.text import font, px, text

DASH = (10, 7)
"""The paper's curve: dash and gap (px at text scale 1)."""


def scene_bounds(sim, readout: Readout | None, scale: float | None = None
                 ) -> tuple[float, float, float, float]:
    """World box that shows the launch point, the fountain, the floor and the machine (its
    parts' least sizes in pixels at ``scale`` px per metre, when given)."""
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
    for x, y in machine_bounds(sim, scale):
        xs.append(x)
        ys.append(y)
    return min(xs), min(ys), max(xs), max(ys)


def dashed_line(surf: pygame.Surface, colour, pts: np.ndarray, dash: float, gap: float,
                width: int) -> None:
    """``pts`` (screen, ``(n, 2)``) as a dashed polyline (each dash drawn straight: dashes
    are a few pixels long)."""
    if len(pts) < 2:
        return
    seg = np.hypot(*np.diff(pts, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    a = np.arange(0.0, s[-1], dash + gap)
    b = np.minimum(a + dash, s[-1])
    xa, ya = np.interp(a, s, pts[:, 0]), np.interp(a, s, pts[:, 1])
    xb, yb = np.interp(b, s, pts[:, 0]), np.interp(b, s, pts[:, 1])
    line = pygame.draw.line
    for x0, y0, x1, y1 in zip(xa.tolist(), ya.tolist(), xb.tolist(), yb.tolist(),
                              strict=True):
        line(surf, colour, (x0, y0), (x1, y1), width)


def grid(surf: pygame.Surface, cam: Camera) -> None:
    """Faint grid lines at a round spacing."""
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


def scale_bar(surf: pygame.Surface, cam: Camera, at: tuple[int, int]) -> pygame.Rect:
    """A scale bar of a round length with its left end at ``at`` (screen); its box."""
    rect = cam.rect
    length = nice_step(rect.w * 0.36 / cam.scale, 2)
    while length * cam.scale > rect.w * 0.3:
        length /= 2
    bar = int(length * cam.scale)
    x0, y0 = at
    w = max(2, px(3))
    pygame.draw.line(surf, TEXT, (x0, y0), (x0 + bar, y0), w)
    for x in (x0, x0 + bar):
        pygame.draw.line(surf, TEXT, (x, y0 - px(6)), (x, y0 + px(6)), w)
    txt = f"{length:g} m" if length >= 0.01 else f"{length * 1000:g} mm"
    lbl = text(font(20), txt, True, TEXT)
    surf.blit(lbl, (x0 + bar // 2 - lbl.get_width() // 2, y0 - px(8) - lbl.get_height()))
    return pygame.Rect(x0, y0 - px(8) - lbl.get_height(), bar, lbl.get_height() + px(14))


class SceneView:
    """Draws the scene of one window; remembers the links' serials, the machine's wheels
    and where the labels went between frames."""

    def __init__(self) -> None:
        self.serials = chain_view.LinkSerials()
        self.machine = MachineView()
        self.layout = LabelLayout()
        self.placed: list[Placed] = []
        """The labels of the last frame and where they went (the tests read them)."""
        self.chain_screen = np.zeros((0, 2))
        """The last frame's chain (and drawn chain), as screen points (:mod:`labels`)."""
        self.marks_every = 10
        self._sim_id = 0

    def _new_sim(self, sim) -> None:
        self._sim_id = id(sim)
        self.serials.clear()
        self.layout.clear()
        cfg = sim.config
        if sim.beaker is not None:
            speed = math.sqrt(2.0 * cfg.gravity * cfg.beaker.drop)
        else:
            speed = float(sim.ends.speed)
        self.marks_every = chain_view.mark_spacing(speed, float(sim.chain.L))

    def draw(self, surf: pygame.Surface, cam: Camera, sim, readout: Readout | None,
             show_theory: bool = True, expert: bool = False,
             keep_clear: list[pygame.Rect] | None = None,
             bar_at: tuple[int, int] | None = None, small: bool = False) -> None:
        """The scene, clipped to the camera's rectangle; ``keep_clear``: boxes of the
        window's own overlays (the time controls) that labels must not cover; ``bar_at``:
        where the scale bar starts (default: the view's bottom left); ``small``: a
        thumbnail (no labels, no scale bar, the chain at its true width or 2 px)."""
        if id(sim) != self._sim_id:
            self._new_sim(sim)
        rect = cam.rect
        old_clip = surf.get_clip()
        surf.set_clip(rect)
        surf.fill(SCENE_BG, rect)
        grid(surf, cam)
        drawn = self.machine.draw(surf, cam, sim, expert, self.marks_every)
        theory = show_theory and readout is not None and readout.curve is not None
        if theory and len(readout.curve) >= 2:
            dashed_line(surf, THEORY, cam.to_screen(readout.curve), px(DASH[0]), px(DASH[1]),
                        max(2, px(2)))
        width = chain_view.chain_width(cam, sim.config.chain.link_radius)
        if small:
            width = max(2, int(round(2.0 * sim.config.chain.link_radius * cam.scale)))
        front, back = sim.link_endpoints()
        serial = self.serials.of(sim.chain.links)
        beads = sim.beaker is not None or sim.config.chain.bend_limit > 0.0
        chain_view.draw_links(surf, cam, front, back, serial, self.marks_every, width, beads)
        if small:
            surf.set_clip(old_clip)
            return
        requests, images = self._requests(drawn, cam, expert)
        marker = self._height_marker(surf, cam, readout, theory, requests, images)
        poly = cam.to_screen(sim.chain_polyline()) if len(front) else np.zeros((0, 2))
        self.chain_screen = labels.chain_points([poly] + self._drawn_chains(cam, sim))
        at = bar_at or (rect.left + px(18), rect.bottom - px(22))
        bar = scale_bar(surf, cam, at)
        self.placed = self.layout.place(requests, rect, drawn.boxes + marker, self.chain_screen,
                                        width, keep_clear=(keep_clear or []) + [bar])
        for p in self.placed:
            self._draw_label(surf, p, images[p.key])
        surf.set_clip(old_clip)

    def _drawn_chains(self, cam: Camera, sim) -> list[np.ndarray]:
        """Screen lines of the chain the machine view draws (an ideal machine's channels)."""
        return [cam.to_screen(p) for p in self.machine.paths]

    def _requests(self, drawn: Drawn, cam: Camera, expert: bool
                  ) -> tuple[list[Request], dict[str, tuple[pygame.Surface, tuple]]]:
        f = font(19)
        reqs: list[Request] = []
        images: dict[str, tuple[pygame.Surface, tuple]] = {}
        for lb in drawn.labels:
            img = text(f, lb.text, True, LABEL)
            images[lb.key] = (img, LABEL)
            size = (img.get_width() + px(8), img.get_height() + px(4))
            reqs.append(Request(lb.key, size, cam.point(lb.x, lb.y), lb.side))
        return reqs, images

    def _height_marker(self, surf: pygame.Surface, cam: Camera, ro: Readout | None,
                       theory: bool, reqs: list[Request], images: dict) -> list[pygame.Rect]:
        """The fountain's top: a dashed level line with an arrow up from the launch (a
        beaker: the pick-up) and its height as a label; with the theory, a tick and label
        at the height the paper predicts. The labels go first in the layout."""
        if ro is None or ro.vertex is None or not math.isfinite(ro.h):
            return []
        vx, vy = cam.point(*ro.vertex)
        x0, y0 = cam.point(ro.vertex[0], ro.vertex[1] - ro.h)
        half = max(px(40), int(0.25 * abs(cam.point(ro.l, 0.0)[0] - cam.point(0.0, 0.0)[0])))
        w = max(1, px(2))
        dashed_line(surf, VERTEX, np.array([[vx - half, vy], [vx + half, vy]], float), px(6),
                    px(5), w)
        if y0 - vy > px(24):
            dashed_line(surf, VERTEX, np.array([[x0, y0], [vx, vy + 2]], float), px(4),
                        px(4), w)
            a = px(5)
            pygame.draw.polygon(surf, VERTEX, [(vx, vy + 1), (vx - a, vy + 2 * a),
                                               (vx + a, vy + 2 * a)])
        f = font(19)
        img = text(f, f"top: {ro.h:.2f} m above the {ro.origin}", True, VERTEX)
        images["top"] = (img, VERTEX)
        size = (img.get_width() + px(8), img.get_height() + px(4))
        reqs.insert(0, Request("top", size, (vx + half, vy), "right"))
        if theory and math.isfinite(ro.paper_h):
            py = cam.point(0.0, ro.paper_h)[1]
            pygame.draw.line(surf, THEORY, (vx - half, py), (vx - half + px(18), py),
                             max(2, px(3)))
            img = text(f, f"{ro.theory_label}: {ro.paper_h:.2f} m", True, THEORY)
            images["paper"] = (img, THEORY)
            size = (img.get_width() + px(8), img.get_height() + px(4))
            reqs.insert(1, Request("paper", size, (vx - half, py), "left"))
        return []

    def _draw_label(self, surf: pygame.Surface, p: Placed, image) -> None:
        img, colour = image
        end = labels.leader_end(p.rect, p.anchor)
        if math.hypot(end[0] - p.anchor[0], end[1] - p.anchor[1]) > px(5):
            pygame.draw.line(surf, colour, p.anchor, end, 1)
            pygame.draw.circle(surf, colour, p.anchor, max(2, px(2)))
        surf.fill(LABEL_BG, p.rect)  # opaque: labels never lie over the chain anyway
        surf.blit(img, (p.rect.x + px(4), p.rect.y + px(2)))
