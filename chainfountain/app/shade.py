"""Translucent rectangles, cached by size and colour (a card's or a band's backing)."""

from __future__ import annotations

import pygame

_SHADES: dict[tuple, pygame.Surface] = {}
SHADES_KEPT = 64
"""Most cached shades (the window draws a few dozen sizes)."""


def shade(size: tuple[int, int], colour: tuple[int, int, int], alpha: int) -> pygame.Surface:
    """A translucent rectangle of ``size`` (cached by size, colour and alpha)."""
    key = (size, colour, alpha)
    surf = _SHADES.get(key)
    if surf is None:
        if len(_SHADES) > SHADES_KEPT:
            _SHADES.clear()
        surf = pygame.Surface((max(1, size[0]), max(1, size[1])), pygame.SRCALPHA)
        surf.fill((*colour, alpha))
        _SHADES[key] = surf
    return surf
