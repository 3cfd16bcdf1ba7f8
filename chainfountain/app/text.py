"""Text in the window: the text scale, fonts, a cache of rendered texts, wrapping, and
the check that no text runs out of its box.

The whole layout is measured in pixels of the default layout (:func:`px`) times the text
scale, which grows with the window and more in projector mode
(:func:`chainfountain.app.layout.text_scale`). Text drawn into a box goes through
:func:`blit_in`; while :data:`OVERFLOWS` is a list (the tests set it), every text that
does not fit its box is recorded there.
"""

from __future__ import annotations

from collections import OrderedDict

import pygame

_SCALE = [1.0]
"""The text scale (:func:`set_text_scale`): 1 at the default window size."""


def set_text_scale(scale: float) -> None:
    """Scale all text and the layout measures around it (:func:`px`) by ``scale``."""
    _SCALE[0] = float(scale)


def text_scale() -> float:
    """The current text scale (1 at the default window size)."""
    return _SCALE[0]


def px(n: float) -> int:
    """``n`` pixels of the default layout at the current text scale."""
    return int(round(n * _SCALE[0]))


_FONTS: dict[tuple[int, bool], pygame.font.Font] = {}


def font(size: int, bold: bool = False) -> pygame.font.Font:
    """pygame's bundled font at ``size`` px of the default layout, scaled by the text scale
    (cached)."""
    key = (px(size), bold)
    f = _FONTS.get(key)
    if f is None:
        f = pygame.font.Font(None, key[0])
        f.bold = bold
        _FONTS[key] = f
    return f


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
    if SEEN is not None:
        SEEN.add(s)
    key = (f, s, antialias, tuple(colour))  # the font itself: its id could be reused
    img = _TEXTS.get(key)
    if img is None:
        img = f.render(s, antialias, colour)
        _remember(_TEXTS, key, img)
    else:
        _TEXTS.move_to_end(key)
    return img


def wrap(f: pygame.font.Font, s: str, width: int) -> list[str]:
    """``s`` split at spaces into lines no wider than ``width`` pixels in font ``f`` (a
    single word wider than that gets a line of its own; kept like :func:`text`)."""
    key = (f, s, width)
    rows = _WRAPS.get(key)
    if rows is None:
        rows = _wrap(f, s, width)
        _remember(_WRAPS, key, rows)
    else:
        _WRAPS.move_to_end(key)
    return list(rows)


def _wrap(f: pygame.font.Font, s: str, width: int) -> list[str]:
    lines: list[str] = []
    cur = ""
    for word in s.split():
        trial = f"{cur} {word}" if cur else word
        if cur and f.size(trial)[0] > width:
            lines.append(cur)
            cur = word
        else:
            cur = trial
    return lines + [cur] if cur else lines


def fit_text(f: pygame.font.Font, s: str, width: int) -> str:
    """``s``, or as much of it as fits in ``width`` pixels in font ``f`` with "..." after
    it."""
    if f.size(s)[0] <= width:
        return s
    while s and f.size(s + "...")[0] > width:
        s = s[:-1]
    return s.rstrip() + "..."


SEEN: set[str] | None = None
"""While a set: every text :func:`text` rendered or took from its cache (the tests read
what the window says)."""

OVERFLOWS: list[tuple[str, tuple[int, int, int, int], tuple[int, int, int, int]]] | None = None
"""While a list: every text :func:`blit_in` drew outside its box, as ``(text, text rect,
box)`` (the tests set it; ``None`` in the window, where nothing is recorded)."""


def blit_in(surf: pygame.Surface, img: pygame.Surface, pos: tuple[int, int],
            box: pygame.Rect, what: str = "") -> pygame.Rect:
    """Blit ``img`` at ``pos``, the text ``what`` of a box ``box`` it must stay inside
    (recorded in :data:`OVERFLOWS` when it does not)."""
    r = surf.blit(img, pos)
    if OVERFLOWS is not None:
        drawn = pygame.Rect(pos, img.get_size())
        if not box.contains(drawn):
            OVERFLOWS.append((what, tuple(drawn), tuple(box)))
    return r
