"""Drawing the window (:class:`DrawMixin`, part of :class:`chainfountain.app.window.App`):
the scene with the theory overlaid, the readout, the plots and the help; it only reads the
session."""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np
import pygame

from chainfountain.app import render
from chainfountain.app.readout_text import Row, readout_rows
from chainfountain.app.session import paused_message
from chainfountain.theory.apparatus import plate_reaction
from chainfountain.theory.tension import tension_bar

ROW_COLOURS = {"text": render.TEXT, "dim": render.DIM, "t0": render.T0_COL,
               "te": render.TE_COL, "ok": render.OK, "warn": render.WARN}
"""Colours of the readout rows' colour names (:class:`~chainfountain.app.readout_text.Row`)."""
PLOT_EVERY = 4
"""Redraw the live plots every this many frames (15 Hz at 60 frames/s)."""
ABOUT_SHARE = 0.45
"""Largest share of the view's height the level's description card takes
(:meth:`DrawMixin._draw_about`); a longer description ends with :data:`ABOUT_MORE`."""
ABOUT_MORE = "... the rest: the level picker (L) shows it all"
"""Last row of a description card cut to fit the view."""
ABOUT_SWITCH = 5
"""Link ends the level's card must hide fewer of at the other end of the view to move
there (so that it does not flicker between the top and the bottom)."""
ABOUT_SECONDS = 6.0
"""Simulated seconds the level's description stays on the view unless I pins it."""
STOP_ROWS = 12
"""Rows of the view kept for why a run stopped (the status text over the chain)."""


def status_rows(msgs: list[str], stopped: str | None,
                wrap: Callable[[str], list[str]]) -> list[str]:
    """Rows of status text over the view: the newest messages' last 6 rows; or, while a
    run that stopped itself is paused (``stopped``: why), that reason whole from its head
    (up to :data:`STOP_ROWS`; a fold's collapse runs to 8-10 rows) and the newest other
    message's first 2 rows below it."""
    if not stopped:
        return [ln for m in msgs for ln in wrap(m)][-6:]
    others = [m for m in msgs if not m.startswith(stopped.rstrip("."))][-1:]
    rows = wrap(paused_message(stopped))[:STOP_ROWS]
    return rows + [ln for m in others for ln in wrap(m)][:2]


KEYS: tuple[tuple[str, str], ...] = (
    ("Space", "play / pause"),
    ("Right  or  .", "single step (1/60 s of simulated time)"),
    ("Shift+Right", "one physics step dt"),
    ("S", "slow motion: 1 -> 1/2 -> 1/4 -> 1"),
    ("R", "reset the scene (t = 0)"),
    ("F", "fit the view to the fountain and follow it again"),
    ("T", "theory overlay on / off"),
    ("Mouse wheel", "zoom about the pointer"),
    ("Drag (empty space)", "pan; right or middle drag also pans"),
    ("Drag (on the chain)", "pull a link"),
    ("Ctrl+S", "save the setup as a level (name prompt)"),
    ("Ctrl+O  or  L", "open a level (picker)"),
    ("M", "switch a machine preset between the contact and the ideal machine"),
    ("F12  (Shift: with the plots)", "picture of the scene (PNG, full resolution)"),
    ("G  (Shift: with the plots)", "start / stop a clip of the scene, in simulated time"),
    ("I", "what this level shows and what to watch (on / off; shown as a level opens)"),
    ("E", "readout in plain words / in the paper's symbols"),
    ("P", "projector mode: larger text (it also grows with the window)"),
    ("H  or  F1", "this help"),
    ("Enter (in a field)", "apply the typed value (clamped to the level schema)"),
    ("Esc", "close a dialog; else quit (clips and changes are kept)"),
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


def card_rows(font: pygame.font.Font, text: str, width: int, height: int) -> list[str]:
    """``text`` wrapped to ``width`` pixels in ``font``, as many rows as fit ``height``
    pixels; when it does not all fit, the last row is :data:`ABOUT_MORE`."""
    rows = render.wrap(font, text, width)
    n = max(2, height // font.get_linesize())
    return rows if len(rows) <= n else [*rows[:n - 1], ABOUT_MORE]


class DrawMixin:
    """Drawing of :class:`~chainfountain.app.window.App` (reads its own state and the session)."""

    def draw(self) -> None:
        """Draw the whole window into ``self.screen``."""
        t0 = time.perf_counter()
        scr = self.screen
        scr.fill(render.BG, pygame.Rect(0, 0, self.scene_rect.x, self.size[1]))
        s = self.session
        if (self._ro is None or self.frame - self._ro_frame >= PLOT_EVERY
                or self._ro_sim is not s.sim or s.paused):
            self._ro, self._ro_frame, self._ro_sim = s.readout(), self.frame, s.sim
        ro = self._ro
        render.draw_scene(scr, self.camera, s.sim, ro, self.show_theory)
        self._draw_right(ro)
        # the scene and the plots are drawn, nothing over them yet: what clips and stills
        # take (no time line, messages, card, REC counter or controls)
        if self.clip is not None and self.clip.recording:
            self.clip.offer(scr, s.sim.time)
        if self._still_rect is not None:
            self._still = scr.subsurface(self._still_rect).copy()
        self._draw_overlay(ro)
        if self.about_visible:
            self._draw_about()
        self.ui.draw_ui(scr)
        if self.show_help:
            self._draw_help()
        self.draw_time += 0.1 * ((time.perf_counter() - t0) - self.draw_time)

    @property
    def about_visible(self) -> bool:
        """The level's description is on the view: from the level's start for
        :data:`ABOUT_SECONDS` of simulated time (so it does not hide the fountain as it
        forms), or while I keeps it."""
        return self.show_about and (self.about_pinned
                                    or self.session.sim.time < ABOUT_SECONDS)

    def _about_width(self) -> int:
        """Width (px) of the description card in the present view."""
        return min(self.scene_rect.w - 20, render.px(640))

    def about_rows(self, text: str) -> list[str]:
        """``text`` as the description card shows it in the present view
        (:func:`card_rows`)."""
        return card_rows(render.font(18), text, self._about_width() - 20,
                         int(self.scene_rect.h * ABOUT_SHARE) - render.px(34))

    def _about_card(self) -> tuple[pygame.Rect, list[str]] | None:
        """The level's description card at the top of the view: its box and its rows
        (``None``: the level has no description)."""
        text = self.session.level.meta.description.strip()
        if not text:
            return None
        rows = self.about_rows(text)
        lh = render.font(18).get_linesize()
        return pygame.Rect(self.scene_rect.x + 10, render.px(72), self._about_width(),
                           render.px(34) + lh * len(rows)), rows

    def about_box(self) -> pygame.Rect | None:
        """Where the level's description card goes at the top of the view (``None``: the
        level has no description)."""
        card = self._about_card()
        return None if card is None else card[0]

    def _draw_about(self) -> None:
        """The level's description (what it shows and what to watch) on a card at the top
        of the view, under the time line, or at its bottom when that hides less of the
        chain (a fountain forming rises into the top); I hides it."""
        card = self._about_card()
        if card is None:
            return
        box, rows = card
        rect = self.scene_rect
        head, body = render.font(19), render.font(18)
        lh = body.get_linesize()
        low = box.move(0, rect.bottom - render.px(40) - box.bottom)
        if low.top > box.bottom:  # room for both: the one hiding less, without flicker
            at_top, at_low = self._chain_under((box, low))
            hidden, other = (at_low, at_top) if self._about_low else (at_top, at_low)
            if other + ABOUT_SWITCH < hidden:
                self._about_low = not self._about_low
            box = low if self._about_low else box
        shade = pygame.Surface(box.size, pygame.SRCALPHA)
        shade.fill((10, 12, 18, 215))
        self.screen.blit(shade, box.topleft)
        pygame.draw.rect(self.screen, render.DIM, box, 1, 6)
        self.screen.blit(render.text(head, f"{self.session.name}: what to watch   (I hides this)",
                                     True, render.SPEED_COL), (box.x + 10, box.y + render.px(8)))
        y = box.y + render.px(30)
        for row in rows:
            self.screen.blit(render.text(body, row, True, render.TEXT), (box.x + 10, y))
            y += lh

    def _chain_under(self, boxes: tuple[pygame.Rect, ...]) -> list[int]:
        """How many of the chain's link ends a card at each of ``boxes`` would hide."""
        poly = self.session.sim.chain_polyline()
        if len(poly) == 0:
            return [0] * len(boxes)
        x, y = self.camera.to_screen(poly).T
        return [int(np.count_nonzero((x >= b.left) & (x <= b.right) & (y >= b.top)
                                     & (y <= b.bottom))) for b in boxes]

    def _draw_overlay(self, ro) -> None:
        s = self.session
        rect = self.scene_rect
        state = []
        if s.paused:
            state.append(("PAUSED", render.WARN))
        if s.speed_factor != 1:
            state.append((f"slow motion 1/{round(1 / s.speed_factor)}", render.SPEED_COL))
        if self.clip is not None and self.clip.recording:
            state.append((f"REC {self.clip.seconds:4.1f} s of simulated time", render.WARN))
        if s.dragging:
            state.append(("holding a link", render.VERTEX))
        f = render.font(20)
        x = rect.x + 10
        head = f"t = {s.sim.time:7.2f} s   links {s.sim.n_free} free"
        scr = self.screen
        scr.blit(render.text(f, head, True, render.TEXT), (x, render.px(8)))
        rtf_col = render.WARN if s.behind else render.DIM
        speed = (f"off-screen: {s.speed_factor / self.fps * 1e3:.1f} ms simulated per frame"
                 if self.offscreen else
                 f"real-time factor {s.rtf:4.2f}  ({self.fps_measured:4.1f} fps)")
        scr.blit(render.text(render.font(18), speed, True, rtf_col), (x, render.px(28)))
        xx = x
        for txt, col in state:
            surf = render.text(f, txt, True, col)
            scr.blit(surf, (xx, render.px(48)))
            xx += surf.get_width() + 14
        # status messages (newest last), shown for 6 s, wrapped to the view's width; why
        # the run stopped stays whole while paused (its head says what failed: a fold's
        # collapse runs to 8-10 rows), with the newest other message below it
        now = s.clock()
        small = render.font(17)
        msgs = [m for t, m in s.messages if now - t < 6.0][-3:]
        rows = status_rows(msgs, s.stopped if s.paused else None,
                           lambda m: render.wrap(small, m, rect.w - 20))
        lh = small.get_linesize()
        y = rect.bottom - render.px(44) - lh * len(rows)
        for m in rows:
            img = render.text(small, m, True, render.TEXT)
            bg = pygame.Surface((img.get_width() + 8, img.get_height() + 2), pygame.SRCALPHA)
            bg.fill((0, 0, 0, 150))
            scr.blit(bg, (rect.x + 6, y - 1))
            scr.blit(img, (rect.x + 10, y))
            y += lh
        hint = render.text(render.font(16), "H: help", True, render.DIM)
        scr.blit(hint, (rect.right - hint.get_width() - 8, render.px(8)))

    def _draw_right(self, ro) -> None:
        rect = self.right_rect
        scr = self.screen
        pygame.draw.rect(scr, render.BG, rect)
        s = self.session

        rows = readout_rows(ro, s.sim.config.chain.linear_density, self.expert,
                            stopped=s.stopped is not None)
        width = rect.w - 18  # the rows' font, measured: no line runs off the panel
        if ro.machine:
            rows += [Row(part) for part in render.wrap(render.font(19), ro.machine, width)[:2]]
        if ro.note:
            rows += [Row(part, "dim") for part in render.wrap(render.font(19), ro.note, width)[:2]]
        y = self._draw_rows(rows, rect)
        top = y + 6
        key = (top, rect.size, id(s.sim))
        if (self._plot_cache is None or key != self._plot_key
                or self.frame - self._plot_frame >= PLOT_EVERY):
            self._plot_cache = self._render_plots(ro, pygame.Rect(0, 0, rect.w, rect.h - top))
            self._plot_key = key
            self._plot_frame = self.frame
        scr.blit(self._plot_cache, (rect.x, top))

    def _draw_rows(self, rows: list[Row], rect: pygame.Rect) -> int:
        """The readout's rows at the top of ``rect``, each symbol right-aligned in dim, a
        row too long for the panel (large text, projector mode) wrapped onto the next
        line; returns the y below them."""
        f, sym_f = render.font(19), render.font(17)
        y = render.px(8)
        for row in rows:
            room = rect.w - 18
            if row.symbol:
                img = render.text(sym_f, row.symbol, True, render.DIM)
                self.screen.blit(img, (rect.right - img.get_width() - 10, y + 1))
                room -= img.get_width() + 10
            fits = f.size(row.text)[0] <= room  # as written: its spacing kept
            for part in [row.text] if fits else render.wrap(f, row.text, max(room, 40)):
                self.screen.blit(render.text(f, part, True, ROW_COLOURS[row.colour]),
                                 (rect.x + 8, y))
                y += f.get_linesize() + 1
        return y

    def _render_plots(self, ro, area: pygame.Rect) -> pygame.Surface:
        surf = pygame.Surface(area.size)
        surf.fill(render.BG)
        ph = (area.h - 8) // 3
        w = area.w - 12
        s = self.session
        hist = s.history.arrays()
        r1 = pygame.Rect(6, 0, w, ph - 4)
        r2 = pygame.Rect(6, ph, w, ph - 4)
        r3 = pygame.Rect(6, 2 * ph, w, ph - 4)
        # 1. tension along the chain against height (plain words unless E: expert)
        ex = self.expert
        series = []
        ys = ro.tension_y
        if len(ys):
            series.append(render.Series(ys, ro.tension_bar, render.CHAIN, "measured",
                                        points=True))
        if math.isfinite(ro.q) and math.isfinite(ro.h):
            top = ro.vertex[1] if ro.vertex is not None else ro.h  # the scene's frame
            lo = min(float(ys.min()) if len(ys) else top - ro.H - ro.h, top - ro.H - ro.h)
            hi = max(float(ys.max()) if len(ys) else top, top)
            yy = np.linspace(lo, hi, 50)
            tb = tension_bar(yy - top, ro.q, ro.k)
            series.append(render.Series(yy, tb, render.THEORY,
                                        "1 - k/q + k*y" if ex else "paper"))
        render.draw_plot(surf, r1, "Tbar along the chain" if ex else
                         "pull along the chain / (lambda v^2)", f"height above {ro.origin} (m)",
                         series, ylim=(-0.1, 1.05))
        # 2. speed against time
        t = hist["t"]
        span = 20.0
        t1 = float(t[-1]) if len(t) else s.sim.time
        t0 = max(0.0, t1 - span)
        sel = t >= t0
        fs = s.sim.feed.speed
        sp = [render.Series(t[sel], hist["speed"][sel], render.SPEED_COL, "mean link speed")]
        # apparatus: the chain speed at each roller (twice its speed) shows the slow swing
        # of the stored length, which the fountain's mean link speed averages away
        extra = [(k, col, label) for k, col, label in (
            ("speed_in", render.T0_COL, "pick-up 2 v_R" if ex else "at pick-up"),
            ("speed_out", render.TE_COL, "fold 2 v_R" if ex else "at fold"))
            if np.isfinite(hist[k][sel]).any()]
        n_sm = max(1, round(0.05 / s.recorder.cfg.sample_interval))  # rollers jitter
        rollers = [render.Series(t[sel], _smooth(hist[k][sel], n_sm), col, label, width=1)
                   for k, col, label in extra]
        sp += rollers
        sp.append(render.Series(np.array([t0, max(t1, t0 + 1)]), np.array([fs, fs]),
                                render.DIM, "floor's take" if s.sim.beaker else "feed",
                                width=1))
        vals = np.concatenate([hist["speed"][sel]] + [r.y for r in rollers])
        vals = vals[np.isfinite(vals)]
        lo = min(float(vals.min()) if len(vals) else fs, fs) * 0.97
        hi = max(float(vals.max()) if len(vals) else fs, fs) * 1.03
        render.draw_plot(surf, r2, "speed (m/s)", "time (s)", sp, xlim=(t0, max(t1, t0 + 1)),
                         ylim=(lo, hi))
        # 3. end tensions against time with the paper's ranges; the 'open' arrangement's
        # point is its lower plate's reaction force instead (paper: "exactly known over time")
        n = max(1, round(0.1 / s.recorder.cfg.sample_interval))
        if np.isfinite(hist["reaction"][sel]).any():
            self._reaction_plot(surf, r3, t[sel], hist["reaction"][sel], hist["speed"][sel],
                                (t0, max(t1, t0 + 1)), n)
            return surf
        if s.sim.beaker is not None:
            # a beaker's end tensions are not the paper's machine's: how high it rises is
            top = _smooth(hist["vertex_y"][sel], n)
            fin = top[np.isfinite(top)]
            render.draw_plot(surf, r3, "top of the chain above the rim (m)", "time (s)",
                             [render.Series(t[sel], top, render.VERTEX, "top")],
                             xlim=(t0, max(t1, t0 + 1)),
                             ylim=(min(0.0, float(fin.min()) if len(fin) else 0.0),
                                   max(0.1, 1.1 * float(fin.max()) if len(fin) else 0.1)))
            return surf
        ts = [render.Series(t[sel], _smooth(hist["T0"][sel], n), render.T0_COL,
                            "Tbar_0" if ex else "launch"),
              render.Series(t[sel], _smooth(hist["TE"][sel], n), render.TE_COL,
                            "Tbar_E" if ex else "landing")]
        # the paper's ranges are what its pulley machine delivers; a motor's guide is not
        # that machine, so a fed fountain may sit outside them
        motor = s.sim.config.kind == "feed" and s.sim.config.feed.drive == "motor"
        what = "end tensions" if ex else "pull at the ends / (lambda v^2)"
        title = f"{what}, motor-fed" if motor else f"{what} (0.1 s mean)"
        bands = (((0.5, 1.0, render.T0_COL, "paper's machine: Tbar_0 in (1/2, 1)"),
                  (0.0, 0.5, render.TE_COL, "paper's machine: Tbar_E in [0, 1/2)")) if ex else
                 ((0.5, 1.0, render.T0_COL, "the paper's machine: launch 1/2 to 1"),
                  (0.0, 0.5, render.TE_COL, "landing 0 to 1/2")))
        render.draw_plot(surf, r3, title, "time (s)", ts,
                         xlim=(t0, max(t1, t0 + 1)), ylim=(-0.1, 1.05), bands=bands)
        return surf

    def _reaction_plot(self, surf: pygame.Surface, rect: pygame.Rect, t: np.ndarray,
                       reaction: np.ndarray, speed: np.ndarray, xlim: tuple[float, float],
                       n: int) -> None:
        """The lower plate's reaction force against time, with the paper's rate: it carries
        the chain sliding away, so it grows at ``lambda*g*v`` (drawn from the first
        plotted sample, integrating the measured speed)."""
        ok = np.isfinite(reaction) & np.isfinite(speed)
        t, reaction, speed = t[ok], reaction[ok], speed[ok]
        cfg = self.session.sim.config
        lam, g = cfg.chain.linear_density, cfg.gravity
        series = []
        hi = 1.0
        if len(t):
            measured = _smooth(reaction, n)
            predicted = plate_reaction(t, speed, float(reaction[0]), lam, g)
            series = [render.Series(t, measured, render.CHAIN, "measured"),
                      render.Series(t, predicted, render.THEORY, "lambda g v (paper)",
                                    width=1, dashed=True)]
            hi = max(hi, 1.1 * float(max(measured.max(), predicted.max())))
        render.draw_plot(surf, rect, "lower plate reaction (N, 0.1 s mean)", "time (s)",
                         series, xlim=xlim, ylim=(0.0, hi))

    def _draw_help(self) -> None:
        scr = self.screen
        size = 19  # as large as fits the window's height
        while size > 11 and (render.px(60) + (render.font(size).get_linesize() + 2) * len(KEYS)
                             > self.size[1] - 20):
            size -= 1
        small = render.font(size)
        lh = small.get_linesize() + 2
        w = min(self.size[0] - 20, render.px(700))
        h = render.px(60) + lh * len(KEYS)
        box = pygame.Rect(0, 0, w, h)
        box.center = (self.size[0] // 2, self.size[1] // 2)
        shade = pygame.Surface(box.size, pygame.SRCALPHA)
        shade.fill((10, 12, 18, 235))
        scr.blit(shade, box.topleft)
        pygame.draw.rect(scr, render.DIM, box, 1, 6)
        f = render.font(22)
        scr.blit(render.text(f, "Keys and mouse  (H, F1 or Esc closes)", True, render.TEXT),
                 (box.x + 16, box.y + render.px(14)))
        y = box.y + render.px(46)
        for key, what in KEYS:
            scr.blit(render.text(small, key, True, render.SPEED_COL), (box.x + 20, y))
            scr.blit(render.text(small, what, True, render.TEXT), (box.x + render.px(210), y))
            y += lh

    # ------------------------------------------------------------------ main loop
