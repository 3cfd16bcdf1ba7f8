"""The level picker (L, Ctrl+O): a card over the window listing the levels by title under
headings (the demonstrations that form from rest first), each with a thumbnail of its
machine and the fountain the paper predicts, and beside the list the chosen level's card.
Up/Down (PageUp/PageDown, Home/End) choose, Return or a double click opens, Esc closes;
while it is open it takes every key, so Space does not run the scene behind it."""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pygame

from chainfountain.app import paths, text
from chainfountain.app.camera import Camera
from chainfountain.app.palette import BG, DIM, PANEL, SCENE_BG, SPEED_COL, TEXT
from chainfountain.app.readout import Readout
from chainfountain.app.text import blit_in, font, px
from chainfountain.app.widgets import TextButton

HEADINGS = {paths.FORMING: "Demonstrations: they form their fountain from rest",
            paths.LAID: "Studies: they start already running, or run slower than real time",
            paths.SAVED: "Your saved levels"}
DOUBLE_CLICK = 0.4
"""Seconds between two clicks on a row that open it."""
THUMB = (120, 68)
"""A row's thumbnail (px at text scale 1)."""


@dataclass(frozen=True)
class Entry:
    """A row of the picker: a heading (``path`` None) or a level."""

    title: str
    path: Path | None
    description: str = ""
    forms: bool = False


def entries() -> list[Entry]:
    """The picker's rows from :func:`chainfountain.app.paths.list_levels`."""
    out: list[Entry] = []
    for label, path in paths.list_levels():
        if path is None:
            out.append(Entry(HEADINGS.get(label, label), None))
        else:
            out.append(Entry(paths.level_title(path), path, paths.level_description(path),
                             paths.forms_from_rest(path)))
    return out


def predicted_curve(sim) -> np.ndarray | None:
    """The fountain the paper predicts for a level at its start (launch frame), or
    ``None`` (a beaker: its fountain is the chain's own)."""
    from chainfountain.theory import Fountain

    app = sim.apparatus
    if app is not None:
        f = app.fountain
        x_rise = app.vertex_pred[0]
        xs = np.linspace(0.0, app.end[0], 80)
        return np.column_stack([xs, f.h + f.y_of_x(xs - x_rise)])
    ref = sim.reference
    if ref is None:
        return None
    if ref.theory == "stiff":
        return ref.curve(80)
    f = Fountain.from_launch(v=ref.v, alpha0=ref.alpha0, H=ref.H, TE_bar=ref.TE_bar, g=ref.g)
    sx, sy = f.start
    xs, ys = f.curve(80)
    return np.column_stack([np.asarray(xs) - sx, np.asarray(ys) - sy])


def thumbnail(path: Path, size: tuple[int, int]) -> pygame.Surface:
    """A picture of the level at ``path``: its machine at the start and the paper's
    fountain (dashed); a line saying why when it cannot be opened."""
    from chainfountain.app.scene_view import SceneView, scene_bounds
    from chainfountain.level import io
    from chainfountain.sim.world import Simulation

    surf = pygame.Surface(size)
    surf.fill(SCENE_BG)
    scale = text.text_scale()
    try:
        level = io.load(path)
        sim = Simulation(level.sim)
        ro = Readout(curve=predicted_curve(sim))
        cam = Camera(pygame.Rect(0, 0, *size))
        cam.fit(*scene_bounds(sim, ro), margin=0.04)
        text.set_text_scale(max(0.25, 0.5 * size[1] / 300.0))
        SceneView().draw(surf, cam, sim, ro, show_theory=True, small=True)
    except Exception as exc:  # noqa: BLE001 - a picture of what is wrong instead
        text.set_text_scale(scale)
        msg = str(exc).split(":")[-1].strip()[:60] or type(exc).__name__
        img = text.text(font(14), f"cannot open: {msg}", True, DIM)
        surf.blit(img, (4, size[1] // 2 - img.get_height() // 2))
    finally:
        text.set_text_scale(scale)
    return surf


_KEPT: dict[tuple, pygame.Surface] = {}
"""Thumbnails already drawn in this program (:func:`_kept_thumbnail`)."""
KEPT_MAX = 128
"""At most this many kept (about 30 levels at two sizes and two text scales)."""


def _kept_thumbnail(path: Path, size: tuple[int, int]) -> pygame.Surface:
    """:func:`thumbnail`, drawn once per file state, size and text scale in this program:
    each takes about 25 ms (a level loaded and built), and the picker draws every
    visible one each time it opens."""
    try:
        stamp = path.stat().st_mtime_ns
    except OSError:
        stamp = None
    key = (path, stamp, size, text.text_scale())
    img = _KEPT.get(key)
    if img is None:
        img = thumbnail(path, size)
        if len(_KEPT) >= KEPT_MAX:
            _KEPT.pop(next(iter(_KEPT)))
        _KEPT[key] = img
    return img


class LevelPicker:
    """The picker's state (rows, choice, scroll) and drawing."""

    def __init__(self, current: Path | None = None) -> None:
        self.rows = entries()
        levels = [i for i, e in enumerate(self.rows) if e.path is not None]
        self.sel = levels[0] if levels else -1
        if current is not None:
            for i in levels:
                if self.rows[i].path == current:
                    self.sel = i
        self.top = 0
        self.rect = pygame.Rect(0, 0, 0, 0)
        self.list_rect = pygame.Rect(0, 0, 0, 0)
        self.buttons: list[TextButton] = []
        self._thumbs: dict[tuple[Path, tuple[int, int]], pygame.Surface] = {}
        self._last_click = (-1, 0.0)

    # ------------------------------------------------------------------ geometry
    def place(self, size: tuple[int, int]) -> None:
        w, h = size
        self.rect = pygame.Rect(0, 0, int(min(w - px(20), max(0.8 * w, px(640)))),
                                int(min(h - px(20), max(0.84 * h, px(420)))))
        self.rect.center = (w // 2, h // 2)
        r = self.rect
        self.list_rect = pygame.Rect(r.x + px(10), r.y + px(44), int(0.52 * r.w),
                                     r.h - px(54))
        bw = px(96)
        y = r.bottom - px(40)
        self.buttons = [TextButton("open", pygame.Rect(r.right - 2 * bw - px(20), y, bw, px(30)),
                                   "Open"),
                        TextButton("close", pygame.Rect(r.right - bw - px(12), y, bw, px(30)),
                                   "Cancel")]
        self._keep_visible()

    @property
    def row_h(self) -> int:
        return max(px(THUMB[1]) + px(8), font(19).get_linesize() * 2 + px(10))

    def _heading_h(self) -> int:
        return font(17).get_linesize() + px(10)

    def _row_heights(self) -> list[int]:
        return [self._heading_h() if e.path is None else self.row_h for e in self.rows]

    def _keep_visible(self) -> None:
        hs = self._row_heights()
        if self.sel < 0:
            return
        self.top = min(self.top, self.sel)
        while sum(hs[self.top:self.sel + 1]) > self.list_rect.h and self.top < self.sel:
            self.top += 1
        if self.top > 0 and self.rows[self.top - 1].path is None and \
                sum(hs[self.top - 1:self.sel + 1]) <= self.list_rect.h:
            self.top -= 1  # show the heading above the first row

    def _visible(self) -> list[tuple[int, pygame.Rect]]:
        out = []
        y = self.list_rect.y
        for i, hgt in enumerate(self._row_heights()[self.top:], start=self.top):
            if y + hgt > self.list_rect.bottom:
                break
            out.append((i, pygame.Rect(self.list_rect.x, y, self.list_rect.w, hgt)))
            y += hgt
        return out

    # ------------------------------------------------------------------ input
    @property
    def chosen(self) -> Entry | None:
        return self.rows[self.sel] if 0 <= self.sel < len(self.rows) else None

    def move(self, step: int) -> None:
        """Choose the level ``step`` rows on (headings skipped), stopping at the ends."""
        levels = [i for i, e in enumerate(self.rows) if e.path is not None]
        if not levels:
            return
        k = levels.index(self.sel) if self.sel in levels else 0
        self.sel = levels[min(max(k + step, 0), len(levels) - 1)]
        self._keep_visible()

    def key(self, key: int) -> str | None:
        """A key while open: ``open``, ``close`` or ``None`` (the picker used it)."""
        if key in (pygame.K_ESCAPE,):
            return "close"
        if key in (pygame.K_RETURN, pygame.K_KP_ENTER):
            return "open"
        steps = {pygame.K_UP: -1, pygame.K_DOWN: 1, pygame.K_PAGEUP: -5,
                 pygame.K_PAGEDOWN: 5, pygame.K_HOME: -10_000, pygame.K_END: 10_000}
        if key in steps:
            self.move(steps[key])
        return None

    def click(self, pos: tuple[int, int], now: float | None = None) -> str | None:
        """A click: on a button its action; on a row, choose it (twice quickly: open);
        outside the card: close."""
        now = time.monotonic() if now is None else now
        for b in self.buttons:
            if b.hit(pos):
                return b.key
        if not self.rect.collidepoint(pos):
            return "close"
        for i, r in self._visible():
            if r.collidepoint(pos) and self.rows[i].path is not None:
                last_i, last_t = self._last_click
                self.sel = i
                self._last_click = (i, now)
                if last_i == i and now - last_t < DOUBLE_CLICK:
                    return "open"
        return None

    def wheel(self, dy: int) -> None:
        self.move(-dy)

    # ------------------------------------------------------------------ drawing
    def _thumb(self, path: Path, size: tuple[int, int]) -> pygame.Surface:
        key = (path, size)
        img = self._thumbs.get(key)
        if img is None:
            img = self._thumbs[key] = _kept_thumbnail(path, size)
        return img

    def draw(self, surf: pygame.Surface, mouse: tuple[int, int] | None = None) -> None:
        r = self.rect
        shade = pygame.Surface(surf.get_size(), pygame.SRCALPHA)
        shade.fill((0, 0, 0, 150))
        surf.blit(shade, (0, 0))
        pygame.draw.rect(surf, BG, r, 0, px(8))
        pygame.draw.rect(surf, DIM, r, 1, px(8))
        head = text.text(font(24, bold=True), "Open a level", True, TEXT)
        blit_in(surf, head, (r.x + px(12), r.y + px(10)), r, "picker title")
        hint = text.text(font(16), "Up/Down choose, Return opens, Esc closes", True, DIM)
        if head.get_width() + hint.get_width() + px(40) < r.w:
            blit_in(surf, hint, (r.right - hint.get_width() - px(12), r.y + px(14)), r, "hint")
        tw, th = px(THUMB[0]), px(THUMB[1])
        for i, row in self._visible():
            e = self.rows[i]
            if e.path is None:
                img = text.text(font(17, bold=True), text.fit_text(font(17, bold=True), e.title,
                                                                    row.w - px(8)), True,
                                SPEED_COL)
                blit_in(surf, img, (row.x + px(4), row.y + px(6)), row, e.title)
                continue
            if i == self.sel:
                pygame.draw.rect(surf, (52, 66, 96), row, 0, px(5))
            surf.blit(self._thumb(e.path, (tw, th)), (row.x + px(4), row.y + px(4)))
            f = font(19)
            room = row.w - tw - px(16)
            lines = text.wrap(f, e.title, room)[:2]
            y = row.y + px(6)
            for ln in lines:
                img = text.text(f, text.fit_text(f, ln, room), True, TEXT)
                blit_in(surf, img, (row.x + tw + px(12), y), row, e.title)
                y += f.get_linesize()
        self._draw_card(surf)
        for b in self.buttons:
            b.draw(surf, hover=mouse is not None and b.hit(mouse))

    def _draw_card(self, surf: pygame.Surface) -> None:
        """The chosen level's picture and card beside the list."""
        e = self.chosen
        r = self.rect
        box = pygame.Rect(self.list_rect.right + px(12), self.list_rect.y,
                          r.right - self.list_rect.right - px(24), r.h - px(100))
        pygame.draw.rect(surf, PANEL, box, 0, px(6))
        if e is None or e.path is None:
            return
        pw = box.w - px(16)
        ph = min(int(pw * 0.56), box.h // 2)
        surf.blit(self._thumb(e.path, (pw, ph)), (box.x + px(8), box.y + px(8)))
        y = box.y + ph + px(16)
        f_t, f = font(21, bold=True), font(18)
        for ln in text.wrap(f_t, e.title, pw):
            blit_in(surf, text.text(f_t, ln, True, TEXT), (box.x + px(8), y), box, e.title)
            y += f_t.get_linesize()
        start = ("Starts at rest and forms its fountain." if e.forms else
                 "Starts already running, laid along its path.")
        for para, colour in ((start, SPEED_COL), (e.description, TEXT)):
            for ln in text.wrap(f, para, pw):
                if y + f.get_linesize() > box.bottom - px(4):
                    return
                blit_in(surf, text.text(f, ln, True, colour), (box.x + px(8), y), box, ln)
                y += f.get_linesize()
            y += px(6)
