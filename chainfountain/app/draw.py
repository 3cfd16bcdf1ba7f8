"""Drawing the window (:class:`DrawMixin`, part of :class:`chainfountain.app.window.App`):
the scene and its overlays (time, the level's card, messages, the time controls, the
tools), the panel's readout, the graphs, the picker, the help and the quit prompt. It only
reads the session."""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np
import pygame

from chainfountain.app import palette as pal
from chainfountain.app import plots, text
from chainfountain.app.readout_text import Row, readout_rows
from chainfountain.app.session import paused_message
from chainfountain.app.shade import shade
from chainfountain.app.text import blit_in, font, px
from chainfountain.app.widgets import TextButton, text_button_width
from chainfountain.theory.apparatus import plate_reaction
from chainfountain.theory.tension import tension_bar

ROW_COLOURS = {"text": pal.TEXT, "dim": pal.DIM, "t0": pal.T0_COL, "te": pal.TE_COL,
               "ok": pal.OK, "warn": pal.WARN}
"""Colours of the readout rows' colour names (:class:`~chainfountain.app.readout_text.Row`)."""
PLOT_EVERY = 4
"""Redraw the live plots every this many frames (15 Hz at 60 frames/s)."""
ABOUT_SECONDS = 8.0
"""Simulated seconds the level's card stays on the view unless I pins it."""
STOP_ROWS = 12
"""Rows of the view kept for why a run stopped (the status text over the chain)."""
TOOLS = (("ruler", "ruler (U)"), ("stopwatch", "stopwatch (W)"))


EXTRA_LINES = 3
"""Lines the expert readout gives each of the machine's prediction and the note."""
TITLE_LINES = 2
"""Lines the panel keeps for the level's title."""


def title_font() -> pygame.font.Font:
    """The panel title's font."""
    return font(24, bold=True)


def readout_font(expert: bool) -> pygame.font.Font:
    """The panel readout's font (smaller in the expert view, which has more rows)."""
    return font(18) if expert else font(20)


def status_rows(msgs: list[str], stopped: str | None,
                wrap: Callable[[str], list[str]]) -> list[str]:
    """Rows of status text over the view: the newest messages' last 4 rows; or, while a
    run that stopped itself is paused (``stopped``: why), that reason whole from its head
    (up to :data:`STOP_ROWS`) and the newest other message's first 2 rows below it."""
    if not stopped:
        return [ln for m in msgs for ln in wrap(m)][-4:]
    others = [m for m in msgs if not m.startswith(stopped.rstrip("."))][-1:]
    rows = wrap(paused_message(stopped))[:STOP_ROWS]
    return rows + [ln for m in others for ln in wrap(m)][:2]


KEYS: tuple[tuple[str, str], ...] = (
    ("Space", "play / pause"),
    ("Right  or  .", "one step (1/60 s); Shift+Right: one physics step"),
    ("S", "speed: normal, slow (1/2), slower (1/4)"),
    ("R", "restart the scene with these settings"),
    ("Shift+R", "reset all: the level as it was opened"),
    ("F", "fit the view to the fountain and follow it"),
    ("T", "the paper's curve on / off"),
    ("Wheel, drag", "zoom; pan (on the chain: pull a link)"),
    ("U, W", "ruler (drag its ends), stopwatch"),
    ("L  or  Ctrl+O", "open a level"),
    ("M", "the same machine with ideal or contact rollers (M again: back)"),
    ("Ctrl+S", "save the setup as a level"),
    ("F12, G", "a picture, a clip of the scene (Shift: with the graphs)"),
    ("I", "the level's card: what it shows, what to try"),
    ("E", "expert view: every field and the paper's symbols"),
    ("V", "graphs under the scene on / off"),
    ("Tab", "hide the panel: the scene fills the window"),
    ("P", "projector mode: larger text and parts"),
    ("H  or  F1", "this help"),
    ("Esc", "close; twice: quit (changes are kept)"),
)


def _smooth(y: np.ndarray, n: int) -> np.ndarray:
    """Trailing moving average over ``n`` samples (NaN-free input assumed)."""
    if len(y) < 2 or n <= 1:
        return y
    n = min(n, len(y))
    c = np.cumsum(np.insert(np.nan_to_num(y), 0, 0.0))
    out = np.empty(len(y))
    k = np.arange(1, len(y) + 1)
    lo = np.maximum(k - n, 0)
    out[:] = (c[k] - c[lo]) / (k - lo)
    return out



MESSAGE_WORDS_PER_SECOND = 3.0
"""Reading pace a status message is held for: a class reading a projector, slower than a
reader alone (about 4 words a second)."""


def message_seconds(message: str) -> float:
    """How long the window shows a status message: 6 s, longer for a long one (a refusal
    naming the field, the value and what is allowed) at
    :data:`MESSAGE_WORDS_PER_SECOND`, at most 20 s."""
    return min(max(6.0, len(message.split()) / MESSAGE_WORDS_PER_SECOND), 20.0)

class DrawMixin:
    """Drawing of :class:`~chainfountain.app.window.App` (reads its own state and the
    session)."""

    def draw(self) -> None:
        """Draw the whole window into ``self.screen``."""
        t0 = time.perf_counter()
        scr = self.screen
        s = self.session
        if (self._ro is None or self.frame - self._ro_frame >= PLOT_EVERY
                or self._ro_sim is not s.sim or s.paused):
            self._ro, self._ro_frame, self._ro_sim = s.readout(), self.frame, s.sim
        ro = self._ro
        keep = self.timebar.keep_clear() + self._tool_buttons_rects() + [self._messages_box()]
        card = self._about_card() if self.about_visible else None
        if card is not None:
            keep.append(card[0])
        self.scene_view.draw(scr, self.camera, s.sim, ro, self.show_theory, self.expert,
                             keep_clear=keep, bar_at=self._bar_at())
        scr.set_clip(self.scene_rect)
        self.ruler.draw(scr, self.camera)
        scr.set_clip(None)
        if self.plots_rect is not None:
            self._draw_plots(ro)
        # the scene (and graphs) drawn, no overlay yet: what clips and stills take
        if self.clip is not None and self.clip.recording:
            self.clip.offer(scr, s.sim.time)
        if self._still_rect is not None:
            self._still = scr.subsurface(self._still_rect).copy()
        scr.set_clip(self.scene_rect)
        self._draw_overlay(ro)
        if card is not None:
            self._draw_about(*card)
        if self.panel_rect is None:
            self._draw_big_readout(ro)
        scr.set_clip(None)
        if self.panel_rect is not None:
            self._draw_panel(ro)
        self.ui.draw_ui(scr)
        if self.picker is not None:
            self.picker.draw(scr, pygame.mouse.get_pos() if not self.offscreen else None)
        if self.show_help:
            self._draw_help()
        if self.quit_prompt is not None:
            self._draw_banner(self.quit_prompt)
        self.draw_last = time.perf_counter() - t0
        self.draw_time += 0.1 * (self.draw_last - self.draw_time)

    # ------------------------------------------------------------------ the card
    @property
    def about_visible(self) -> bool:
        """The level's card is on the view: for its first :data:`ABOUT_SECONDS` of
        simulated time, or while I keeps it."""
        return self.show_about and (self.about_pinned
                                    or self.session.sim.time < ABOUT_SECONDS)

    def _about_card(self) -> tuple[pygame.Rect, str, list[str]] | None:
        """The level's card at the view's top left: its box, title and rows (``None``: no
        description)."""
        level = self.session.level
        body = level.meta.description.strip()
        if not body:
            return None
        rect = self.scene_rect
        w = min(rect.w - px(20), px(560))
        f, ft = font(19), font(21, bold=True)
        title = text.fit_text(ft, level.meta.shown_title, w - px(20))
        rows = text.wrap(f, body, w - px(20))
        hint = "I hides this"
        room = int(0.4 * rect.h) - ft.get_linesize() - px(30)
        n = max(1, room // f.get_linesize())
        if len(rows) > n:
            rows = [*rows[:n - 1], text.fit_text(f, rows[n - 1] + " ...", w - px(20))]
        h = px(14) + ft.get_linesize() + f.get_linesize() * (len(rows) + 1) + px(8)
        box = pygame.Rect(rect.x + px(10), rect.y + px(40), w, h)
        return box, title, rows + [hint]

    def about_box(self) -> pygame.Rect | None:
        card = self._about_card()
        return None if card is None else card[0]

    def _draw_about(self, box: pygame.Rect, title: str, rows: list[str]) -> None:
        scr = self.screen
        scr.fill(pal.CARD, box)  # opaque: a translucent card costs a blit of its size
        pygame.draw.rect(scr, pal.DIM, box, 1, px(6))
        ft, f = font(21, bold=True), font(19)
        y = box.y + px(8)
        blit_in(scr, text.text(ft, title, True, pal.SPEED_COL), (box.x + px(10), y), box,
                title)
        y += ft.get_linesize() + px(2)
        for i, row in enumerate(rows):
            colour = pal.DIM if i == len(rows) - 1 else pal.TEXT
            blit_in(scr, text.text(f, row, True, colour), (box.x + px(10), y), box, row)
            y += f.get_linesize()

    # ------------------------------------------------------------------ overlays
    def _bar_at(self) -> tuple[int, int]:
        """Where the scale bar starts: the view's bottom left, level with the time
        controls."""
        return self.scene_rect.x + px(18), self.timebar.rect.centery + px(10)

    def _tool_buttons(self) -> list[TextButton]:
        rect = self.scene_rect
        out = []
        x = rect.right - px(8)
        y = rect.y + px(8)
        for key, label in reversed(TOOLS):
            w = text_button_width(label, 15)
            x -= w
            out.append(TextButton(key, pygame.Rect(x, y, w, px(26)), label,
                                  on=getattr(self, key).on))
            x -= px(4)
        return out

    def _tool_buttons_rects(self) -> list[pygame.Rect]:
        return [b.rect for b in self._tool_buttons()]

    def _draw_overlay(self, ro) -> None:
        s = self.session
        rect = self.scene_rect
        scr = self.screen
        mouse = None if self.offscreen else pygame.mouse.get_pos()
        x = rect.x + px(10)
        head = f"t = {s.sim.time:6.2f} s"
        if self.expert:
            head += f"    links {s.sim.n_free} free"
        img = text.text(font(24, bold=True), head, True, pal.TEXT)
        scr.blit(img, (x, rect.y + px(8)))
        chips = []
        if s.paused:
            chips.append(("PAUSED", pal.WARN))
        if s.speed_factor != 1:
            chips.append((f"slow motion 1/{round(1 / s.speed_factor)}", pal.SPEED_COL))
        if self.clip is not None and self.clip.recording:
            chips.append((f"REC {self.clip.seconds:4.1f} s", pal.WARN))
        if s.dragging:
            chips.append(("holding a link", pal.VERTEX))
        behind = not self.offscreen and (s.behind or s.rtf < 0.95 * s.speed_factor) \
            and not s.paused
        if self.expert:
            speed = (f"off-screen: {s.speed_factor / self.fps * 1e3:.1f} ms per frame"
                     if self.offscreen else
                     f"real-time factor {s.rtf:4.2f}  ({self.fps_measured:4.1f} fps)")
            chips.append((speed, pal.WARN if s.behind else pal.DIM))
        elif behind and s.rtf < 0.9 * s.speed_factor:
            chips.append((f"running slower than real time (x{s.rtf:.2f})", pal.WARN))
        xx = x + img.get_width() + px(16)
        for txt, col in chips:
            surf = text.text(font(19), txt, True, col)
            if xx + surf.get_width() > rect.right - px(260):
                break
            scr.blit(surf, (xx, rect.y + px(12)))
            xx += surf.get_width() + px(14)
        for b in self._tool_buttons():
            b.draw(scr, hover=mouse is not None and b.hit(mouse), size=15)
        self.stopwatch.draw(scr)
        hint = text.text(font(16), "H: help", True, pal.DIM)
        scr.blit(hint, (rect.right - hint.get_width() - px(10), rect.y + px(38)
                        if not self.stopwatch.on else self.stopwatch.rect.bottom + px(4)))
        self.timebar.draw(scr, s.paused, s.slow_index, mouse)
        self._draw_messages()

    def _message_rows(self) -> list[str]:
        s = self.session
        now = s.clock()
        small = font(18)
        msgs = [m for t, m in s.messages if now - t < message_seconds(m)][-3:]
        width = self.scene_rect.w - px(28)
        return status_rows(msgs, s.stopped if s.paused else None,
                           lambda m: text.wrap(small, m, width))

    def _messages_box(self) -> pygame.Rect:
        """Where the status messages go (labels keep clear of it)."""
        rows = self._message_rows()
        lh = font(18).get_linesize()
        bottom = self.timebar.rect.top - px(10)
        w = max((font(18).size(r)[0] for r in rows), default=0) + px(12)
        return pygame.Rect(self.scene_rect.x + px(8), bottom - lh * len(rows), w,
                           lh * len(rows))

    def _draw_messages(self) -> None:
        """Status messages (newest last, each for :func:`message_seconds`) above the time
        controls; why a run stopped stays whole while paused."""
        rect = self.scene_rect
        small = font(18)
        width = rect.w - px(28)
        rows = self._message_rows()
        lh = small.get_linesize()
        y = self.timebar.rect.top - px(10) - lh * len(rows)
        box = rect.inflate(-px(8), 0)
        for m in rows:
            img = text.text(small, text.fit_text(small, m, width), True, pal.TEXT)
            self.screen.fill(pal.CARD, (rect.x + px(8), y, img.get_width() + px(10), lh))
            blit_in(self.screen, img, (rect.x + px(13), y), box, m)
            y += lh

    def _draw_big_readout(self, ro) -> None:
        """With the panel hidden: the chief numbers in large text over the scene."""
        s = self.session
        rows = readout_rows(ro, s.sim.config.chain.linear_density, False,
                            stopped=s.stopped is not None)[:4]
        f = font(26, bold=True)
        w = max(f.size(r.text)[0] for r in rows) + px(24)
        w = min(w, self.scene_rect.w // 2)
        h = f.get_linesize() * len(rows) + px(16)
        y0 = self.scene_rect.y + px(40) + (self.stopwatch.rect.h + px(8)
                                           if self.stopwatch.on else 0)
        box = pygame.Rect(self.scene_rect.right - w - px(10), y0, w, h)
        self.screen.fill(pal.CARD, box)
        y = box.y + px(8)
        for r in rows:
            img = text.text(f, text.fit_text(f, r.text, w - px(20)), True, ROW_COLOURS[r.colour])
            blit_in(self.screen, img, (box.x + px(12), y), box, r.text)
            y += f.get_linesize()

    def _draw_banner(self, message: str) -> None:
        scr = self.screen
        f = font(24, bold=True)
        rows = text.wrap(f, message, min(self.size[0] - px(60), px(700)))
        w = max(f.size(r)[0] for r in rows) + px(40)
        h = f.get_linesize() * len(rows) + px(30)
        box = pygame.Rect(0, 0, w, h)
        box.center = self.scene_rect.center
        scr.blit(shade(box.size, (40, 14, 10), 235), box.topleft)
        pygame.draw.rect(scr, pal.WARN, box, 2, px(8))
        y = box.y + px(15)
        for r in rows:
            img = text.text(f, r, True, pal.TEXT)
            blit_in(scr, img, (box.centerx - img.get_width() // 2, y), box, r)
            y += f.get_linesize()

    # ------------------------------------------------------------------ the panel
    def _draw_panel(self, ro) -> None:
        p = self.panel_rect
        scr = self.screen
        pygame.draw.rect(scr, pal.BG, p)
        pygame.draw.line(scr, pal.GRID, p.topleft, p.bottomleft if not self.lay.portrait
                         else p.topright, 2)
        s = self.session
        tr = self.title_rect
        f = title_font()
        lines = text.wrap(f, self._title_text(), tr.w)
        if len(lines) > TITLE_LINES:
            lines = [*lines[:TITLE_LINES - 1], text.fit_text(f, " ".join(
                lines[TITLE_LINES - 1:]), tr.w)]
        for i, ln in enumerate(lines):
            blit_in(scr, text.text(f, text.fit_text(f, ln, tr.w), True, pal.TEXT),
                    (tr.x, tr.y + i * f.get_linesize()), tr, ln)
        rows = readout_rows(ro, s.sim.config.chain.linear_density, self.expert,
                            stopped=s.stopped is not None)
        if self.expert:
            width = self.readout_rect.w - px(16)
            f = font(18)
            for line, colour in ((ro.machine, "text"), (ro.bars, "dim"), (ro.note, "dim")):
                parts = text.wrap(f, line, width) if line else []
                if len(parts) > EXTRA_LINES:  # the rest of the sentence: cut, never dropped
                    parts = [*parts[:EXTRA_LINES - 1],
                             text.fit_text(f, " ".join(parts[EXTRA_LINES - 1:]), width)]
                rows += [Row(part, colour) for part in parts]
        self._draw_rows(rows, self.readout_rect)

    def _draw_rows(self, rows: list[Row], rect: pygame.Rect) -> int:
        """The readout's rows in ``rect``, each symbol (expert view) right-aligned in
        dim, a row too long wrapped onto the next line, rows that do not fit left out;
        returns the y below them."""
        f = readout_font(self.expert)
        sym_f = font(16)
        y = rect.y + px(4)
        for row in rows:
            room = rect.w - px(16)
            if row.symbol and self.expert:
                img = text.text(sym_f, row.symbol, True, pal.DIM)
                if y + f.get_linesize() <= rect.bottom:
                    blit_in(self.screen, img, (rect.right - img.get_width() - px(8), y + 1),
                            rect, row.symbol)
                room -= img.get_width() + px(10)
            parts = [row.text] if f.size(row.text)[0] <= room else text.wrap(f, row.text,
                                                                           max(room, 40))
            for part in parts:
                if y + f.get_linesize() > rect.bottom:
                    return y
                img = text.text(f, text.fit_text(f, part, room), True, ROW_COLOURS[row.colour])
                blit_in(self.screen, img, (rect.x + px(8), y), rect, part)
                y += f.get_linesize() + 1
        return y

    # ------------------------------------------------------------------ graphs
    def _draw_plots(self, ro) -> None:
        rect = self.plots_rect
        key = (rect.size, id(self.session.sim), self.expert)
        if (self._plot_cache is None or key != self._plot_key
                or self.frame - self._plot_frame >= PLOT_EVERY):
            self._plot_cache = self._render_plots(ro, pygame.Rect(0, 0, rect.w, rect.h))
            self._plot_key = key
            self._plot_frame = self.frame
        self.screen.blit(self._plot_cache, rect.topleft)

    def _render_plots(self, ro, area: pygame.Rect) -> pygame.Surface:
        """The three graphs side by side (in a narrow strip, over each other): the pull
        along the chain against height, the speed, and the pulls at the ends (a beaker:
        how high it rises; the open arrangement: the plate's reaction)."""
        surf = pygame.Surface(area.size)
        surf.fill(pal.BG)
        wide = area.w >= 2.2 * area.h
        if wide:
            pw = (area.w - px(16)) // 3
            boxes = [pygame.Rect(px(4) + i * (pw + px(4)), px(4), pw, area.h - px(8))
                     for i in range(3)]
        else:
            ph = (area.h - px(16)) // 3
            boxes = [pygame.Rect(px(4), px(4) + i * (ph + px(4)), area.w - px(8), ph)
                     for i in range(3)]
        s = self.session
        hist = s.history.arrays()
        ex = self.expert
        self._tension_plot(surf, boxes[0], ro, ex)
        t = hist["t"]
        span = 20.0
        t1 = float(t[-1]) if len(t) else s.sim.time
        t0 = max(0.0, t1 - span)
        sel = t >= t0
        xlim = (t0, max(t1, t0 + 1))
        self._speed_plot(surf, boxes[1], hist, sel, xlim, ex)
        n = max(1, round(0.1 / s.recorder.cfg.sample_interval))
        if np.isfinite(hist["reaction"][sel]).any():
            self._reaction_plot(surf, boxes[2], t[sel], hist["reaction"][sel],
                                hist["speed"][sel], xlim, n)
        elif s.sim.beaker is not None:
            top = _smooth(hist["vertex_y"][sel], n)
            fin = top[np.isfinite(top)]
            plots.draw_plot(surf, boxes[2], "how high it rises above the rim (m)", "time (s)",
                            [plots.Series(t[sel], top, pal.VERTEX, "top")], xlim=xlim,
                            ylim=(min(0.0, float(fin.min()) if len(fin) else 0.0),
                                  max(0.1, 1.1 * float(fin.max()) if len(fin) else 0.1)))
        else:
            self._ends_plot(surf, boxes[2], t[sel], hist, sel, xlim, n, ex)
        return surf

    def _tension_plot(self, surf: pygame.Surface, box: pygame.Rect, ro, ex: bool) -> None:
        series = []
        ys = ro.tension_y
        if len(ys):
            series.append(plots.Series(ys, ro.tension_bar, pal.CHAIN, "measured", points=True))
        if len(ro.tension_theory):
            series.append(plots.Series(ro.tension_theory_y, ro.tension_theory, pal.THEORY,
                                       ro.theory_label))
        elif math.isfinite(ro.q) and math.isfinite(ro.h):
            top = ro.vertex[1] if ro.vertex is not None else ro.h
            lo = min(float(ys.min()) if len(ys) else top - ro.H - ro.h, top - ro.H - ro.h)
            hi = max(float(ys.max()) if len(ys) else top, top)
            yy = np.linspace(lo, hi, 50)
            series.append(plots.Series(yy, tension_bar(yy - top, ro.q, ro.k), pal.THEORY,
                                       "1 - k/q + k*y" if ex else "paper"))
        title = "Tbar along the chain" if ex else "how hard the chain pulls (share of lambda v^2)"
        plots.draw_plot(surf, box, title, f"height above the {ro.origin} (m)", series,
                        ylim=(-0.1, 1.05))

    def _speed_plot(self, surf: pygame.Surface, box: pygame.Rect, hist: dict, sel,
                    xlim: tuple[float, float], ex: bool) -> None:
        s = self.session
        t = hist["t"]
        fs = s.sim.ends.speed
        sp = [plots.Series(t[sel], hist["speed"][sel], pal.SPEED_COL, "chain")]
        extra = [(k, col, label) for k, col, label in (
            ("speed_in", pal.T0_COL, "pick-up 2 v_R" if ex else "at pick-up"),
            ("speed_out", pal.TE_COL, "fold 2 v_R" if ex else "at fold"))
            if np.isfinite(hist[k][sel]).any()]
        n_sm = max(1, round(0.05 / s.recorder.cfg.sample_interval))
        rollers = [plots.Series(t[sel], _smooth(hist[k][sel], n_sm), col, label, width=1)
                   for k, col, label in extra]
        sp += rollers
        sp.append(plots.Series(np.array(xlim), np.array([fs, fs]), pal.DIM,
                               "floor's take" if s.sim.beaker else "set", width=1))
        vals = np.concatenate([hist["speed"][sel]] + [r.y for r in rollers])
        vals = vals[np.isfinite(vals)]
        lo = min(float(vals.min()) if len(vals) else fs, fs) * 0.97
        hi = max(float(vals.max()) if len(vals) else fs, fs) * 1.03
        plots.draw_plot(surf, box, "speed (m/s)", "time (s)", sp, xlim=xlim, ylim=(lo, hi))

    def _ends_plot(self, surf: pygame.Surface, box: pygame.Rect, t: np.ndarray, hist: dict,
                   sel, xlim: tuple[float, float], n: int, ex: bool) -> None:
        s = self.session
        ts = [plots.Series(t, _smooth(hist["T0"][sel], n), pal.T0_COL,
                           "Tbar_0" if ex else "launch"),
              plots.Series(t, _smooth(hist["TE"][sel], n), pal.TE_COL,
                           "Tbar_E" if ex else "landing")]
        motor = s.sim.feed is not None and s.sim.piston is None
        what = "end tensions" if ex else "pull at the ends"
        title = f"{what}, motor-fed" if motor else f"{what} (0.1 s mean)"
        bands = (((0.5, 1.0, pal.T0_COL, "paper's machine: Tbar_0 in (1/2, 1)"),
                  (0.0, 0.5, pal.TE_COL, "Tbar_E in [0, 1/2)")) if ex else
                 ((0.5, 1.0, pal.T0_COL, "the paper's launch: 1/2 to 1"),
                  (0.0, 0.5, pal.TE_COL, "landing: 0 to 1/2")))
        plots.draw_plot(surf, box, title, "time (s)", ts, xlim=xlim, ylim=(-0.1, 1.05),
                        bands=bands)

    def _reaction_plot(self, surf: pygame.Surface, rect: pygame.Rect, t: np.ndarray,
                       reaction: np.ndarray, speed: np.ndarray, xlim: tuple[float, float],
                       n: int) -> None:
        """The lower plate's reaction force against time, with the paper's rate: it carries
        the chain sliding away, so it grows at ``lambda*g*v``."""
        ok = np.isfinite(reaction) & np.isfinite(speed)
        t, reaction, speed = t[ok], reaction[ok], speed[ok]
        cfg = self.session.sim.config
        lam, g = cfg.chain.linear_density, cfg.gravity
        series = []
        hi = 1.0
        if len(t):
            measured = _smooth(reaction, n)
            predicted = plate_reaction(t, speed, float(reaction[0]), lam, g)
            series = [plots.Series(t, measured, pal.CHAIN, "measured"),
                      plots.Series(t, predicted, pal.THEORY, "lambda g v (paper)", width=1,
                                   dashed=True)]
            hi = max(hi, 1.1 * float(max(measured.max(), predicted.max())))
        plots.draw_plot(surf, rect, "lower plate reaction (N, 0.1 s mean)", "time (s)",
                        series, xlim=xlim, ylim=(0.0, hi))

    # ------------------------------------------------------------------ help
    def _draw_help(self) -> None:
        scr = self.screen
        size = 20
        while size > 11 and (px(64) + (font(size).get_linesize() + 2) * len(KEYS)
                             > self.size[1] - px(20)):
            size -= 1
        small = font(size)
        lh = small.get_linesize() + 2
        key_w = max(small.size(k)[0] for k, _ in KEYS) + px(24)
        what_w = max(small.size(w)[0] for _, w in KEYS)
        w = min(self.size[0] - px(20), key_w + what_w + px(40))
        h = px(60) + lh * len(KEYS)
        box = pygame.Rect(0, 0, w, h)
        box.center = (self.size[0] // 2, self.size[1] // 2)
        scr.blit(shade(box.size, (10, 12, 18), 240), box.topleft)
        pygame.draw.rect(scr, pal.DIM, box, 1, px(6))
        f = font(22, bold=True)
        blit_in(scr, text.text(f, "Keys and mouse  (H or Esc closes)", True, pal.TEXT),
                (box.x + px(16), box.y + px(14)), box, "help title")
        y = box.y + px(48)
        room = box.w - key_w - px(28)
        for key, what in KEYS:
            blit_in(scr, text.text(small, key, True, pal.SPEED_COL), (box.x + px(20), y), box,
                    key)
            blit_in(scr, text.text(small, text.fit_text(small, what, room), True, pal.TEXT),
                    (box.x + px(20) + key_w, y), box, what)
            y += lh
