"""Where the scene's labels go: a layout pass that puts every label beside its part, clear
of the other labels, of the machine's parts and of the chain, and keeps it where it was
while that stays clear (so labels do not jump from frame to frame).

:meth:`LabelLayout.place` tries positions around each anchor (its preferred side first,
then the others, a little further out each round); a label that finds no clear place is
left out of the frame rather than drawn over something.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
import pygame

from chainfountain.app.text import px

SIDES = ("above", "below", "left", "right")
DISTANCES = (12, 24, 38, 56, 78, 104, 136)
"""How far (px at text scale 1) from its anchor a label may go, tried in this order."""
RETRY_FRAMES = 10
"""Frames a label that found no clear place waits before it tries again."""
CHAIN_CLEARANCE = 3
"""Pixels (at text scale 1) a label keeps clear of the chain's drawn edge."""


@dataclass(frozen=True)
class Request:
    """A label to place: ``key`` names it (it keeps its place by it), ``size`` is its
    rendered size (px), ``anchor`` the screen point it labels, ``side`` where it prefers
    to go."""

    key: str
    size: tuple[int, int]
    anchor: tuple[int, int]
    side: str = "above"


@dataclass(frozen=True)
class Placed:
    """Where a label went: its box and the anchor it is drawn to."""

    key: str
    rect: pygame.Rect
    anchor: tuple[int, int]


def _box(side: str, d: int, anchor: tuple[int, int], size: tuple[int, int],
         slide: int = 0) -> pygame.Rect:
    ax, ay = anchor
    w, h = size
    if side == "above":
        return pygame.Rect(ax - w // 2 + slide, ay - d - h, w, h)
    if side == "below":
        return pygame.Rect(ax - w // 2 + slide, ay + d, w, h)
    if side == "left":
        return pygame.Rect(ax - d - w, ay - h // 2 + slide, w, h)
    return pygame.Rect(ax + d, ay - h // 2 + slide, w, h)


def candidates(req: Request) -> Iterator[tuple[str, int, int]]:
    """``(side, distance, slide)`` to try for ``req``: its own side first, then the
    others, at growing distances; above and below also slid sideways by half the label."""
    order = [req.side] + [s for s in SIDES if s != req.side]
    w, h = req.size
    for d in (px(d) for d in DISTANCES):
        for side in order:
            slides = (0, -w // 2, w // 2) if side in ("above", "below") else (0, -h, h)
            for s in slides:
                yield side, d, s


def chain_points(polylines: list[np.ndarray], spacing: float = 4.0) -> np.ndarray:
    """Screen points along ``polylines`` (each ``(n, 2)``) at most ``spacing`` px apart:
    what a label must not cover."""
    out = []
    for line in polylines:
        if len(line) < 2:
            out.append(np.asarray(line, dtype=float).reshape(-1, 2))
            continue
        seg = np.hypot(*np.diff(line, axis=0).T)
        s = np.concatenate([[0.0], np.cumsum(seg)])
        n = max(2, int(s[-1] / spacing) + 2)
        t = np.linspace(0.0, s[-1], n)
        out.append(np.column_stack([np.interp(t, s, line[:, 0]), np.interp(t, s, line[:, 1])]))
    return np.vstack(out) if out else np.zeros((0, 2))


def _hits(rect: pygame.Rect, pts: np.ndarray, pad: int) -> bool:
    if len(pts) == 0:
        return False
    x, y = pts[:, 0], pts[:, 1]
    return bool(np.any((x >= rect.left - pad) & (x <= rect.right + pad)
                       & (y >= rect.top - pad) & (y <= rect.bottom + pad)))


class LabelLayout:
    """Places a frame's labels; remembers where each went for the next frame."""

    def __init__(self) -> None:
        self._last: dict[str, tuple[str, int, int, bool]] = {}
        self._failed: dict[str, int] = {}
        """Labels that found no place, and how many frames until they try again."""

    def clear(self) -> None:
        self._last.clear()
        self._failed.clear()

    def place(self, requests: list[Request], view: pygame.Rect,
              obstacles: list[pygame.Rect], chain: np.ndarray,
              chain_width: int = 6, keep_clear: list[pygame.Rect] | None = None
              ) -> list[Placed]:
        """Boxes for ``requests`` (in order: earlier ones get the better places) inside
        ``view``, overlapping no other label, no box of ``obstacles`` and no point of
        ``chain`` (screen points, :func:`chain_points`; kept ``chain_width / 2`` plus
        :data:`CHAIN_CLEARANCE` clear). A label goes over a part's box when it finds no
        place beside one, never over ``keep_clear`` (the window's controls). Requests
        without a clear place are left out."""
        inner = view.inflate(-4, -4)
        placed: list[Placed] = []
        taken: list[pygame.Rect] = list(keep_clear or [])
        pad = chain_width // 2 + px(CHAIN_CLEARANCE)
        reach = px(DISTANCES[-1]) + 2 * max((r.size[0] for r in requests), default=0)
        for req in requests:
            ax, ay = req.anchor
            near = chain[(np.abs(chain[:, 0] - ax) < reach) & (np.abs(chain[:, 1] - ay) < reach)] \
                if len(chain) else chain
            wait = self._failed.get(req.key, 0)
            if wait > 0:  # no place last time: try again in a few frames
                self._failed[req.key] = wait - 1
                continue
            found = None
            last = self._last.get(req.key)
            if last is not None:  # where it was, if that is still as clear as it was
                side, d, slide, parts = last
                rect = _box(side, d, req.anchor, req.size, slide)
                if _clear(rect, inner, taken, obstacles if parts else [], near, pad):
                    found = last, rect
            for parts in (True, False):  # beside the parts if it can, else over one
                if found is not None:
                    break
                for side, d, slide in candidates(req):
                    rect = _box(side, d, req.anchor, req.size, slide)
                    if _clear(rect, inner, taken, obstacles if parts else [], near, pad):
                        found = (side, d, slide, parts), rect
                        break
            if found is None:
                self._last.pop(req.key, None)
                self._failed[req.key] = RETRY_FRAMES
                continue
            self._last[req.key] = found[0]
            taken.append(found[1])
            placed.append(Placed(req.key, found[1], req.anchor))
        return placed


def _clear(rect: pygame.Rect, inner: pygame.Rect, taken: list[pygame.Rect],
           obstacles: list[pygame.Rect], chain: np.ndarray, pad: int) -> bool:
    """``rect`` is inside ``inner`` and clear of the labels ``taken`` (by a small gap), the
    ``obstacles`` and the ``chain`` points (by ``pad``)."""
    if not inner.contains(rect):
        return False
    gap = px(3)
    if rect.inflate(2 * gap, 2 * gap).collidelist(taken) >= 0:
        return False
    if obstacles and rect.collidelist(obstacles) >= 0:
        return False
    return not _hits(rect, chain, pad)


def leader_end(rect: pygame.Rect, anchor: tuple[int, int]) -> tuple[int, int]:
    """The point of ``rect``'s edge nearest to ``anchor`` (where a leader line ends)."""
    x = min(max(anchor[0], rect.left), rect.right)
    y = min(max(anchor[1], rect.top), rect.bottom)
    return int(x), int(y)
