"""Measuring tools on the scene: a ruler whose two ends are dragged to measure a length
and a height (in metres, from the camera), and a stopwatch that counts simulated
seconds (it stops when the simulation is paused)."""

from __future__ import annotations

import math

import numpy as np
import pygame

from chainfountain.app.camera import Camera
from chainfountain.app.palette import PANEL, RULER, TEXT
from chainfountain.app.shade import shade
from chainfountain.app.text import blit_in, font, px, text
from chainfountain.app.widgets import TextButton, text_button_width


class Ruler:
    """A measuring tape between two world points, each end dragged on its own."""

    def __init__(self) -> None:
        self.on = False
        self.ends: list[tuple[float, float]] = [(0.0, 0.0), (0.5, 0.0)]
        self.held: int | None = None

    def show(self, cam: Camera) -> None:
        """Turn the ruler on, lying across the middle of the view."""
        r = cam.rect
        self.ends = [cam.to_world(r.x + 0.35 * r.w, r.y + 0.5 * r.h),
                     cam.to_world(r.x + 0.65 * r.w, r.y + 0.5 * r.h)]
        self.on = True

    def grab(self, cam: Camera, pos: tuple[int, int]) -> bool:
        """Take the end near ``pos`` (a click within a handle's reach); whether one was."""
        if not self.on:
            return False
        for i, e in enumerate(self.ends):
            sx, sy = cam.point(*e)
            if math.hypot(pos[0] - sx, pos[1] - sy) <= px(14):
                self.held = i
                return True
        return False

    def drag(self, cam: Camera, pos: tuple[int, int]) -> None:
        if self.held is not None:
            self.ends[self.held] = cam.to_world(*pos)

    def release(self) -> None:
        self.held = None

    def reading(self) -> tuple[float, float]:
        """Length between the ends and how much higher the second is (m)."""
        (x0, y0), (x1, y1) = self.ends
        return math.hypot(x1 - x0, y1 - y0), y1 - y0

    def draw(self, surf: pygame.Surface, cam: Camera) -> pygame.Rect | None:
        if not self.on:
            return None
        a, b = (np.array(cam.point(*e), dtype=float) for e in self.ends)
        pygame.draw.line(surf, (40, 36, 20), a, b, max(4, px(7)))
        pygame.draw.line(surf, RULER, a, b, max(2, px(4)))
        d = b - a
        n = float(np.hypot(*d))
        length, rise = self.reading()
        if n > 1 and length > 0:  # ticks every round length
            from chainfountain.app.camera import nice_step

            step = nice_step(length, 10)
            u, w = d / n, np.array([-d[1], d[0]]) / n
            for k in range(int(length / step) + 1):
                p = a + u * (k * step * cam.scale)
                tick = px(7) if k % 5 == 0 else px(4)
                pygame.draw.line(surf, (40, 36, 20), p - w * tick, p + w * tick, 2)
        for p in (a, b):
            pygame.draw.circle(surf, RULER, p, px(9))
            pygame.draw.circle(surf, (40, 36, 20), p, px(9), 2)
        label = text(font(19, bold=True), f"{length:.2f} m   (height {rise:+.2f} m)", True,
                     RULER)
        mid = (a + b) / 2
        box = pygame.Rect(0, 0, label.get_width() + px(10), label.get_height() + px(4))
        box.midbottom = (int(mid[0]), int(mid[1]) - px(12))
        box.clamp_ip(cam.rect)
        surf.blit(shade(box.size, (0, 0, 0), 170), box.topleft)
        surf.blit(label, (box.x + px(5), box.y + px(2)))
        return box


class Stopwatch:
    """Counts simulated seconds while it runs."""

    def __init__(self) -> None:
        self.on = False
        self.running = False
        self.elapsed = 0.0
        self._t: float | None = None
        self.buttons: list[TextButton] = []
        self.rect = pygame.Rect(0, 0, 0, 0)

    def tick(self, sim_time: float) -> None:
        """Count the simulated time since the last frame (a rebuilt scene's time that
        went back counts nothing)."""
        if self.running and self._t is not None and sim_time >= self._t:
            self.elapsed += sim_time - self._t
        self._t = sim_time

    def press(self, key: str) -> None:
        if key == "start":
            self.running = not self.running
        elif key == "zero":
            self.elapsed = 0.0

    def place(self, topright: tuple[int, int]) -> None:
        f = font(24, bold=True)
        w = max(f.size("00.00 s")[0], text_button_width("start", 15)
                + text_button_width("zero", 15) + px(4)) + px(16)
        h = f.get_linesize() + px(40)
        self.rect = pygame.Rect(topright[0] - w, topright[1], w, h)
        bw = (w - px(12) - px(4)) // 2
        y = self.rect.bottom - px(30)
        self.buttons = [TextButton("start", pygame.Rect(self.rect.x + px(6), y, bw, px(24)),
                                   "start"),
                        TextButton("zero", pygame.Rect(self.rect.x + px(10) + bw, y, bw,
                                                       px(24)), "zero")]

    def hit(self, pos: tuple[int, int]) -> str | None:
        if not self.on:
            return None
        for b in self.buttons:
            if b.hit(pos):
                return b.key
        return "body" if self.rect.collidepoint(pos) else None

    def draw(self, surf: pygame.Surface) -> None:
        if not self.on:
            return
        pygame.draw.rect(surf, PANEL, self.rect, 0, px(6))
        pygame.draw.rect(surf, TEXT, self.rect, 1, px(6))
        img = text(font(24, bold=True), f"{self.elapsed:5.2f} s", True, TEXT)
        blit_in(surf, img, (self.rect.centerx - img.get_width() // 2, self.rect.y + px(5)),
                self.rect, "stopwatch")
        self.buttons[0].label = "stop" if self.running else "start"
        for b in self.buttons:
            b.draw(surf, size=15)
