"""The live plots: small line and point plots with axes, ticks, a legend and shaded
bands, drawn into a surface (the window caches it between redraws)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pygame

from chainfountain.app.camera import nice_step
from chainfountain.app.palette import BG, DIM, GRID, TEXT
from chainfountain.app.shade import shade as _shade
from chainfountain.app.text import fit_text, font, px, text


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
