"""The scene's own buttons, drawn in pygame (PhET's manner: round buttons with icons for
time, a segmented choice for the speed, toggles for the tools): what each looks like and
whether a click hits it. The window decides what a hit does."""

from __future__ import annotations

import math
from dataclasses import dataclass

import pygame

from chainfountain.app.palette import BUTTON, BUTTON_HOVER, DIM, SCENE_BG, TEXT
from chainfountain.app.text import blit_in, font, px, text


def icon(surf: pygame.Surface, name: str, c: tuple[int, int], s: int, colour) -> None:
    """Draw icon ``name`` (``play``, ``pause``, ``step``, ``restart``, ``reset``) centred
    at ``c`` in a square of ``s`` px."""
    x, y = c
    h = s // 2
    if name == "play":
        pygame.draw.polygon(surf, colour, [(x - h * 0.45, y - h * 0.6), (x - h * 0.45, y + h * 0.6),
                                           (x + h * 0.65, y)])
    elif name == "pause":
        w = max(2, int(s * 0.16))
        for dx in (-h * 0.32, h * 0.32):
            pygame.draw.rect(surf, colour, (x + dx - w / 2, y - h * 0.55, w, h * 1.1))
    elif name == "step":
        w = max(2, int(s * 0.12))
        pygame.draw.polygon(surf, colour, [(x - h * 0.55, y - h * 0.55),
                                           (x - h * 0.55, y + h * 0.55), (x + h * 0.3, y)])
        pygame.draw.rect(surf, colour, (x + h * 0.35, y - h * 0.55, w, h * 1.1))
    elif name in ("restart", "reset"):
        r = int(h * 0.6)
        rect = pygame.Rect(x - r, y - r, 2 * r, 2 * r)
        pygame.draw.arc(surf, colour, rect, math.radians(60), math.radians(360), max(2, s // 9))
        a = math.radians(60)
        tip = (x + r * math.cos(a), y - r * math.sin(a))
        k = max(3, s // 6)
        pygame.draw.polygon(surf, colour, [(tip[0] - k, tip[1] - k * 0.9),
                                           (tip[0] + k * 0.9, tip[1] - k * 0.2),
                                           (tip[0] - k * 0.1, tip[1] + k)])


@dataclass
class RoundButton:
    """A round button with an icon (and a caption under it)."""

    key: str
    centre: tuple[int, int]
    radius: int
    icon: str
    fill: tuple[int, int, int]
    caption: str = ""

    def hit(self, pos: tuple[int, int]) -> bool:
        return math.hypot(pos[0] - self.centre[0], pos[1] - self.centre[1]) <= self.radius

    @property
    def rect(self) -> pygame.Rect:
        r = self.radius
        out = pygame.Rect(self.centre[0] - r, self.centre[1] - r, 2 * r, 2 * r)
        if self.caption:
            out.height += px(20)
        return out

    def draw(self, surf: pygame.Surface, hover: bool = False, glyph=SCENE_BG) -> None:
        fill = tuple(min(255, int(c * 1.12)) for c in self.fill) if hover else self.fill
        pygame.draw.circle(surf, (0, 0, 0), (self.centre[0], self.centre[1] + 2), self.radius)
        pygame.draw.circle(surf, fill, self.centre, self.radius)
        pygame.draw.circle(surf, (250, 250, 250), self.centre, self.radius, 1)
        icon(surf, self.icon, self.centre, int(self.radius * 1.5), glyph)
        if self.caption:
            img = text(font(15), self.caption, True, TEXT)
            surf.blit(img, (self.centre[0] - img.get_width() // 2,
                            self.centre[1] + self.radius + px(3)))


@dataclass
class TextButton:
    """A rectangular button with a text; ``on`` draws it pressed (a toggle, a choice)."""

    key: str
    rect: pygame.Rect
    label: str
    on: bool = False

    def hit(self, pos: tuple[int, int]) -> bool:
        return self.rect.collidepoint(pos)

    def draw(self, surf: pygame.Surface, hover: bool = False, size: int = 16) -> None:
        fill = (92, 110, 150) if self.on else (BUTTON_HOVER if hover else BUTTON)
        pygame.draw.rect(surf, fill, self.rect, 0, px(5))
        pygame.draw.rect(surf, TEXT if self.on else DIM, self.rect, 1, px(5))
        f = font(size, bold=self.on)
        img = text(f, self.label, True, TEXT)
        blit_in(surf, img, (self.rect.centerx - img.get_width() // 2,
                            self.rect.centery - img.get_height() // 2), self.rect, self.label)


def text_button_width(label: str, size: int = 16) -> int:
    """The width a :class:`TextButton` needs for ``label``."""
    return font(size, bold=True).size(label)[0] + px(16)
