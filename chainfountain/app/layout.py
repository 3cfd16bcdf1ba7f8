"""Where the window's parts go at any size: the scene takes most of the window, the panel
(readout, sliders, buttons) a column beside it in a landscape window or a strip under it
in a portrait one, the graphs (when shown) a strip under the scene; with the panel
hidden (Tab) the scene fills the window. The text scale grows with the window and more in
projector mode (P or ``--projector``, which keep the window's size).
"""

from __future__ import annotations

from dataclasses import dataclass

import pygame

DEFAULT_SIZE = (1280, 760)
"""The window's default size; text scale 1 there."""
MIN_SIZE = (720, 540)
"""The smallest window the layout supports (a resize below it is raised to it)."""
PROJECTOR = 1.5
"""Projector mode makes the text and every part's least size this much larger."""
PANEL_W = 300
"""The panel's width in a landscape window (px at text scale 1)."""
PANEL_SHARE = 0.30
"""The panel takes at most this share of the window's width (landscape) or height
(portrait); the text scale is capped so that its rows fit."""
PORTRAIT_PANEL = 0.34
"""Share of a portrait window's height the panel takes (at least 250 px at text
scale 1)."""
PLOTS_SHARE = 0.30
"""Share of the scene's column the graphs strip takes when shown."""


def text_scale(size: tuple[int, int], projector: bool) -> float:
    """1 at :data:`DEFAULT_SIZE`, growing with the window, times :data:`PROJECTOR` in
    projector mode; capped so that the panel's column (:data:`PANEL_W` at this scale)
    stays within :data:`PANEL_SHARE` of a landscape window's width, or half a portrait
    window's."""
    w, h = size
    s = max(1.0, min(w / DEFAULT_SIZE[0], h / DEFAULT_SIZE[1]))
    if projector:
        s *= PROJECTOR
    room = 0.5 * w if portrait(size) else PANEL_SHARE * w
    return max(1.0, min(s, room / PANEL_W))


def portrait(size: tuple[int, int]) -> bool:
    """A window taller than about its width lays the panel out under the scene."""
    return size[0] < 1.05 * size[1]


@dataclass(frozen=True)
class Layout:
    """The window's rectangles: the scene, the panel (``None`` when hidden), the graphs
    (``None`` when hidden)."""

    scene: pygame.Rect
    panel: pygame.Rect | None
    plots: pygame.Rect | None
    portrait: bool

    def scene_share(self, size: tuple[int, int]) -> float:
        """Share of the window's area the scene takes."""
        return self.scene.w * self.scene.h / float(size[0] * size[1])


def compute(size: tuple[int, int], scale: float, panel: bool = True,
            plots: bool = False) -> Layout:
    """The layout of a window of ``size`` at text scale ``scale``."""
    w, h = size
    tall = portrait(size)
    if not panel:
        prect = None
        col = pygame.Rect(0, 0, w, h)
    elif tall:
        ph = int(min(max(250 * scale, PORTRAIT_PANEL * h), 0.45 * h))
        prect = pygame.Rect(0, h - ph, w, ph)
        col = pygame.Rect(0, 0, w, h - ph)
    else:
        pw = int(min(PANEL_W * scale, PANEL_SHARE * w))
        prect = pygame.Rect(w - pw, 0, pw, h)
        col = pygame.Rect(0, 0, w - pw, h)
    if plots:
        gh = int(max(PLOTS_SHARE * col.h, min(170 * scale, 0.45 * col.h)))
        grect = pygame.Rect(col.x, col.bottom - gh, col.w, gh)
        scene = pygame.Rect(col.x, col.y, col.w, col.h - gh)
    else:
        grect = None
        scene = col
    return Layout(scene=scene, panel=prect, plots=grect, portrait=tall)
