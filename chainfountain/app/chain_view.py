"""The chain drawn as a chain: its links (or a ball chain's beads) at their true size but
never thinner than a projector shows, a dark edge that keeps it clear of the lines behind
it, and every n-th link marked in white. The marks belong to the links, so they travel
with the chain: the flow shows in a still and is obvious in motion.

The marks are spaced so that they move at most a third of their spacing in a frame at
the slowest frame rate they are seen at, a GIF clip's 20 frames/s (:func:`mark_spacing`):
closer marks would strobe (a mark jumping more than half the spacing is seen moving
backwards).
"""

from __future__ import annotations

import math
import weakref

import numpy as np
import pygame

from chainfountain.app.camera import Camera
from chainfountain.app.palette import CHAIN, CHAIN_DARK, HALO, MARK
from chainfountain.app.text import px

MIN_WIDTH = 6
"""Thinnest the chain is drawn (px at text scale 1): a 4-mm chain seen from the back of a
classroom."""
MIN_BEAD = 3.5
"""Smallest bead radius (px at text scale 1)."""
STROBE_FRAMES = 3.0
"""A mark moves at most 1/STROBE_FRAMES of the marks' spacing per frame."""
SLOWEST_FPS = 20.0
"""The frame rate the marks' spacing is chosen for: a GIF clip's (the window itself draws
at least 30 frames/s)."""


def mark_spacing(speed: float, link_length: float, fps: float = SLOWEST_FPS) -> int:
    """Links between two marks for a chain at ``speed`` (m/s) of links ``link_length``
    (m): a multiple of 5, at least 10, so that a mark moves at most
    1/:data:`STROBE_FRAMES` of the spacing in a frame at ``fps``."""
    if not (math.isfinite(speed) and speed > 0 and link_length > 0):
        return 10
    n = math.ceil(STROBE_FRAMES * speed / (fps * link_length))
    return max(10, 5 * math.ceil(n / 5))


class LinkSerials:
    """A number for every link that stays with it while it exists (the order in which
    the links entered the chain), so that the marks travel with the material. Links are
    numbered from the downstream end (0) upstream (-1, -2, ...); a new link takes its
    neighbour's number and one more step in its direction."""

    def __init__(self) -> None:
        self._serial: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()

    def clear(self) -> None:
        self._serial = weakref.WeakKeyDictionary()

    def of(self, links: list) -> np.ndarray:
        """The serial of each link in ``links`` (chain order, downstream first)."""
        ser = self._serial
        got = [ser.get(link) for link in links]
        if None in got:
            known = [i for i, s in enumerate(got) if s is not None]
            if not known:
                got = [-i for i in range(len(links))]
            else:
                for i in range(known[0] - 1, -1, -1):  # downstream of the first known
                    got[i] = got[i + 1] + 1
                for i in range(known[0] + 1, len(got)):  # and on upstream
                    if got[i] is None:
                        got[i] = got[i - 1] - 1
            for link, s in zip(links, got, strict=True):
                ser[link] = s
        return np.asarray(got, dtype=np.int64)


def chain_width(cam: Camera, link_radius: float) -> int:
    """The chain's drawn width (px): its true width, at least :data:`MIN_WIDTH`."""
    return max(px(MIN_WIDTH), int(round(2.0 * link_radius * cam.scale)))


def draw_links(surf: pygame.Surface, cam: Camera, front: np.ndarray, back: np.ndarray,
               serials: np.ndarray, every: int, width: int, beads: bool) -> None:
    """Links from ``front`` to ``back`` ends (world, ``(n, 2)``, chain order), each
    ``every``-th serial marked. ``beads``: a ball chain (a bead at each joint)."""
    n = len(front)
    if n == 0:
        return
    f = cam.to_screen(front)
    b = cam.to_screen(back)
    marked = np.flatnonzero(serials % every == 0)
    if beads:
        _draw_beads(surf, cam, f, b, marked, width)
        return
    line = np.vstack([f, b[-1:]])
    pts = line.tolist()
    if len(pts) >= 2:
        pygame.draw.lines(surf, HALO, False, pts, width + px(4))
        pygame.draw.lines(surf, CHAIN, False, pts, width)
    link_px = float(np.median(np.hypot(*(f - b).T)))
    if link_px >= 3.0 * width:  # the links show one by one: mark the joints between them
        r = max(1, width // 3)
        for x, y in f[1:].tolist():
            pygame.draw.circle(surf, CHAIN_DARK, (x, y), r)
    for i in marked.tolist():
        a, c = f[i].tolist(), b[i].tolist()
        if link_px < 1.5 * width:  # too short to see: mark two links' length
            j = min(i + 1, n - 1)
            c = b[j].tolist()
        pygame.draw.line(surf, MARK, a, c, width)


def _draw_beads(surf: pygame.Surface, cam: Camera, f: np.ndarray, b: np.ndarray,
                marked: np.ndarray, width: int) -> None:
    """A ball chain: a bead at each link's front joint, joined by a thin line."""
    link_px = float(np.median(np.hypot(*(f - b).T)))
    r = max(px(MIN_BEAD), min(int(0.42 * link_px), width))
    pts = np.vstack([f, b[-1:]]).tolist()
    if len(pts) >= 2:  # the dark edge: one wide line under the beads, not a ring each
        pygame.draw.lines(surf, HALO, False, pts, 2 * r + px(3))
        pygame.draw.lines(surf, CHAIN_DARK, False, pts, max(2, r // 2))
    circle = pygame.draw.circle
    for x, y in f.tolist():
        circle(surf, CHAIN, (x, y), r)
    for x, y in f[marked].tolist():
        circle(surf, MARK, (x, y), r)


def draw_along(surf: pygame.Surface, cam: Camera, path: np.ndarray, travelled: float,
               link_length: float, every: int, width: int) -> None:
    """A chain running along ``path`` (world, ``(n, 2)``, the way it moves), that has
    moved ``travelled`` metres: the links of a part of the machine that is drawn, not
    simulated (an ideal machine's channels), marked as the simulated chain is."""
    if len(path) < 2 or link_length <= 0:
        return
    seg = np.hypot(*np.diff(path, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    total = float(s[-1])
    if total <= 0:
        return
    phase = travelled % link_length
    joints = np.arange(phase, total, link_length)
    if len(joints) < 2:
        return
    x = np.interp(joints, s, path[:, 0])
    y = np.interp(joints, s, path[:, 1])
    pts = np.column_stack([x, y])
    serial = np.floor((travelled - joints) / link_length).astype(np.int64)
    # downstream first, as the simulated chain's links are
    front, back = pts[1:][::-1], pts[:-1][::-1]
    draw_links(surf, cam, front, back, serial[1:][::-1], every, width, beads=False)


def pile_texture(size: tuple[int, int], link_px: int, width: int) -> pygame.Surface:
    """A pile of chain, as the part of a beaker's pile the solver does not hold is drawn:
    rows of links laid back and forth (a cached texture)."""
    key = (size, link_px, width)
    img = _PILES.get(key)
    if img is not None:
        return img
    if len(_PILES) > 16:
        _PILES.clear()
    w, h = max(1, size[0]), max(1, size[1])
    img = pygame.Surface((w, h), pygame.SRCALPHA)
    img.fill((0, 0, 0, 0))
    step = max(4, link_px)
    row = max(3, int(0.9 * width) + 1)
    for k, y in enumerate(range(row // 2, h, row)):
        x0 = -(k % 2) * step // 2
        for x in range(x0, w, step):
            col = MARK if (x // step + 3 * k) % 17 == 0 else (CHAIN if k % 2 else CHAIN_DARK)
            pygame.draw.line(img, col, (x + 1, y), (x + step - 2, y), max(2, width - 2))
    _PILES[key] = img
    return img


_PILES: dict[tuple, pygame.Surface] = {}
