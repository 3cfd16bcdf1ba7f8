"""The camera: world metres (y up) to screen pixels (y down) within the scene's rectangle,
and the world box a level's scene needs."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pygame


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

    def fit(self, x0: float, y0: float, x1: float, y1: float, margin: float = 0.06,
            top: int = 0, bottom: int = 0) -> None:
        """Show the world box ``[x0, x1] x [y0, y1]`` with a margin, between ``top`` pixels
        kept free at the view's top (a card) and ``bottom`` pixels at its foot (the time
        controls)."""
        w = max(x1 - x0, 1e-3) * (1 + 2 * margin)
        h = max(y1 - y0, 1e-3) * (1 + 2 * margin)
        top = min(max(top, 0), self.rect.h // 2)
        bottom = min(max(bottom, 0), self.rect.h // 3)
        free = max(self.rect.h - top - bottom, 20)
        self.scale = max(1e-3, min(self.rect.w / w, free / h))
        self.cx = 0.5 * (x0 + x1)
        self.cy = 0.5 * (y0 + y1) + 0.5 * (top - bottom) / self.scale

    def zoom(self, factor: float, about: tuple[float, float]) -> None:
        """Zoom by ``factor`` keeping the screen point ``about`` fixed."""
        wx, wy = self.to_world(*about)
        self.scale = min(max(self.scale * factor, 5.0), 50000.0)
        self.cx = wx - (about[0] - self.rect.centerx) / self.scale
        self.cy = wy + (about[1] - self.rect.centery) / self.scale

    def pan(self, dx_px: float, dy_px: float) -> None:
        self.cx -= dx_px / self.scale
        self.cy += dy_px / self.scale
