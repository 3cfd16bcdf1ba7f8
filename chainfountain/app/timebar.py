"""Time controls at the foot of the scene, in PhET's manner: a big play/pause button, a
step button, restart, the speed as a choice of normal / slow / slower, and Reset all (the
level as it was opened) at the bottom right. Keys do the same: Space, Right, R, S,
Shift+R."""

from __future__ import annotations

import pygame

from chainfountain.app.palette import BUTTON, PLAY, RESET_ALL, TEXT
from chainfountain.app.text import px
from chainfountain.app.widgets import RoundButton, TextButton, text_button_width

SPEEDS = ("normal", "slow", "slower")
"""The speed choice, in the order of :data:`chainfountain.app.session.SLOW_FACTORS`."""
SPEED_LABELS = {"normal": "normal", "slow": "slow 1/2", "slower": "slower 1/4"}


class TimeBar:
    """The scene's time controls: their places for a scene rectangle, drawing, hits."""

    def __init__(self) -> None:
        self.round: list[RoundButton] = []
        self.speeds: list[TextButton] = []
        self.rect = pygame.Rect(0, 0, 0, 0)
        """The box the controls take (labels and the fitted view keep clear of it)."""
        self.reset_rect = pygame.Rect(0, 0, 0, 0)

    def place(self, scene: pygame.Rect) -> None:
        """Put the controls at the foot of ``scene``."""
        big, small = px(30), px(20)
        cy = scene.bottom - big - px(12)
        cx = scene.centerx
        self.round = [
            RoundButton("restart", (cx - big - small - px(14), cy), small, "restart", BUTTON),
            RoundButton("play", (cx, cy), big, "play", PLAY),
            RoundButton("step", (cx + big + small + px(14), cy), small, "step", BUTTON),
        ]
        x = cx + big + 2 * small + px(30)
        h = px(26)
        self.speeds = []
        for key in SPEEDS:
            w = text_button_width(SPEED_LABELS[key], 15)
            self.speeds.append(TextButton(key, pygame.Rect(x, cy - h // 2, w, h),
                                          SPEED_LABELS[key]))
            x += w + px(4)
        r = px(26)
        reset = RoundButton("reset_all", (scene.right - r - px(18), cy), r, "reset",
                            RESET_ALL, "Reset all")
        self.round.append(reset)
        self.reset_rect = reset.rect
        left = min(b.rect.left for b in self.round[:3])
        self.rect = pygame.Rect(left, cy - big - px(4), x - left, 2 * big + px(8))
        if self.speeds and self.speeds[-1].rect.right > reset.rect.left - px(8):
            # a narrow scene: the speed choice goes above the round buttons
            y = cy - big - px(10) - h
            x = cx - sum(b.rect.w + px(4) for b in self.speeds) // 2
            for b in self.speeds:
                b.rect.topleft = (x, y)
                x += b.rect.w + px(4)
            self.rect = pygame.Rect(min(left, self.speeds[0].rect.left), y,
                                    max(self.rect.right, x) - min(left, self.speeds[0].rect.left),
                                    cy + big + px(4) - y)

    def keep_clear(self) -> list[pygame.Rect]:
        """Boxes nothing else in the scene may cover."""
        return [self.rect, self.reset_rect]

    def draw(self, surf: pygame.Surface, paused: bool, speed: int,
             mouse: tuple[int, int] | None = None) -> None:
        """Draw the controls: play shows pause while running; the speed choice marks
        ``speed`` (an index into :data:`SPEEDS`)."""
        for b in self.round:
            if b.key == "play":
                b.icon = "play" if paused else "pause"
            b.draw(surf, hover=mouse is not None and b.hit(mouse),
                   glyph=(20, 24, 32) if b.key in ("play", "reset_all") else TEXT)
        for i, b in enumerate(self.speeds):
            b.on = i == speed
            b.draw(surf, hover=mouse is not None and b.hit(mouse), size=15)

    def hit(self, pos: tuple[int, int]) -> str | None:
        """The control at ``pos`` (``play``, ``step``, ``restart``, ``reset_all``,
        ``normal``, ``slow``, ``slower``), or ``None``."""
        for b in self.round:
            if b.hit(pos):
                return b.key
        for b in self.speeds:
            if b.hit(pos):
                return b.key
        return None
