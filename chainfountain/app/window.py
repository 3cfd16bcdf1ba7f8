"""The window: pygame-ce drawing, pygame_gui controls, keys and mouse.

:class:`App` reads a :class:`~chainfountain.app.session.Session` (the model side) and
sends it commands; pixels are made in :mod:`chainfountain.app.draw` and the views it
calls. The physics runs at its fixed step inside :meth:`Session.tick`, with a per-frame
time budget so drawing stays at the frame rate; when the machine cannot keep up, the
window first draws fewer frames and then the fountain slows down (the real-time factor
is shown).

The layout (:mod:`chainfountain.app.layout`) gives the scene most of the window at every
size: a panel with the readout and the sliders beside it (under it in a portrait window),
the graphs under it when shown (V), and with Tab the scene alone. The student view shows
a level's two to four sliders and plain words; E shows every field and the paper's
symbols. Projector mode (P, ``--projector``) makes text and parts larger and keeps the
window's size.
"""

from __future__ import annotations

import copy
import gc
import os
import threading
import time
from pathlib import Path

import numpy as np
import pygame
import pygame_gui
from pygame_gui.elements import UIButton, UILabel, UIScrollingContainer, UITextEntryLine, UIWindow

from chainfountain.app import layout, panel, paths, spans, text
from chainfountain.app.camera import Camera
from chainfountain.app.capture import BackgroundSaver, ClipRecorder, mp4_available, timestamp
from chainfountain.app.capture import unique_path as _unique
from chainfountain.app.controls import control_fields, spec_for, student_paths
from chainfountain.app.draw import DrawMixin
from chainfountain.app.input import InputMixin
from chainfountain.app.layout import DEFAULT_SIZE, MIN_SIZE
from chainfountain.app.panel import ControlRow, tooltip
from chainfountain.app.picker import LevelPicker
from chainfountain.app.scene_view import SceneView, scene_bounds
from chainfountain.app.session import Session
from chainfountain.app.timebar import TimeBar
from chainfountain.app.tools import Ruler, Stopwatch
from chainfountain.level import library
from chainfountain.level.io import Level, LevelError
from chainfountain.sim.kinds import kind_of
from chainfountain.sim.stiff_reference import stiff_applies

FRAMEBUFFER_HINT = "SDL_FRAMEBUFFER_ACCELERATION"
"""SDL's hint for how a window's pixels reach the screen; the window sets it to "0" unless
the environment sets it: through the display's own framebuffer (X11: shared memory), not
SDL's OpenGL texture, which without GPU drivers (Mesa's llvmpipe; Xvfb) runs two
rendering threads beside the physics on the same cores. Set
``SDL_FRAMEBUFFER_ACCELERATION=1`` to use it."""
MIN_FPS = 30
"""The frame rate may drop to this before the simulation runs slower than requested."""
HEADROOM = 0.9
"""Share of one core the window's own work (the physics of real time and the drawing of
every frame) may take before it draws fewer frames (:meth:`App.target_fps`)."""
DRAW_SHARE = 1.0 / 3.0
"""The most of a frame the drawing may take (:meth:`App.target_fps`)."""
FOLLOW_EVERY = 30
"""Frames between checks that the view still shows the fountain (0.5 s at 60 frames/s)."""
REBUILD_DELAY = 0.35
"""Seconds a restarting slider must rest before the scene is rebuilt."""
QUIT_WINDOW = 3.0
"""Seconds after a first Esc in which a second one quits."""
NO_LIKE_TWIN = "No ideal machine runs this very fountain"
"""How M's message starts when the ideal twin is the shipped preset, not the same
fountain."""
AUTOSAVES_KEPT = 10
"""Autosaves kept in the user's level folder (the oldest beyond this are removed)."""


def _move_window_to_origin() -> None:
    try:
        pygame.Window.from_display_module().position = (0, 0)
    except (AttributeError, pygame.error):
        pass


def theory_by_default(level: Level) -> bool:
    """Whether the paper's curve is on when a level opens: where the paper predicts the
    fountain (fed levels and machines), not over a beaker's chain, whose fountain is its
    own (T shows it)."""
    return kind_of(level.sim).paper_curve


class App(InputMixin, DrawMixin):
    """The interactive front end for one session.

    Parameters
    ----------
    session:
        The running level.
    size:
        Window size in pixels.
    offscreen:
        Deterministic frames: each frame advances exactly ``1/fps`` s of simulated time
        (times the slow-motion factor), independent of wall time (``--frames`` runs and
        tests).
    fps:
        Target frame rate.
    projector:
        Projector mode from the start (as P).
    """

    def __init__(self, session: Session, size: tuple[int, int] = DEFAULT_SIZE,
                 offscreen: bool = False, fps: int = 60, projector: bool = False) -> None:
        os.environ.setdefault(FRAMEBUFFER_HINT, "0")
        pygame.display.init()
        pygame.font.init()
        flags = 0 if offscreen else pygame.RESIZABLE
        size = (max(MIN_SIZE[0], int(size[0])), max(MIN_SIZE[1], int(size[1])))
        self.screen = pygame.display.set_mode(size, flags)
        pygame.display.set_caption("chainfountain")
        pygame.key.set_repeat(350, 60)
        self.size = self.screen.get_size()
        self.session = session
        self.offscreen = offscreen
        self.fps = fps
        self.running = True
        self.show_help = False
        self.show_about = True
        """The level's card on the view (I); shown whenever a level opens, for its first
        :data:`~chainfountain.app.draw.ABOUT_SECONDS` unless I pinned it."""
        self.about_pinned = False
        self.show_theory = theory_by_default(session.level)
        self.expert = False
        """The expert view (E): every field, the paper's symbols, the graphs."""
        self.show_panel = True
        """The panel beside the scene (Tab hides it: the scene fills the window)."""
        self.show_plots = False
        """The graphs under the scene (V); the expert view turns them on."""
        self._plots_before = False
        self.projector = projector
        self.frame = 0
        self.draw_time = 0.004
        """Smoothed wall time of drawing a frame (s); :attr:`draw_last`, the last one's."""
        self.draw_last = 0.0
        self.overhead = 0.006
        """Smoothed wall time of a frame before its physics (events, GUI, drawing)."""
        self.physics_time = 0.0
        self.physics_cost = 0.0
        """Smoothed wall seconds the physics takes per simulated second (window only)."""
        self.work_time = 0.0
        self.fps_measured = float(fps)
        self.clip: ClipRecorder | None = None
        self._still_rect: pygame.Rect | None = None
        self._still: pygame.Surface | None = None
        self.finishing_clips: list[ClipRecorder] = []
        self.saver = BackgroundSaver()
        self.last_capture: Path | None = None
        self._pending: dict[str, tuple[float, float]] = {}
        self._drag_mode: str | None = None
        self._last_mouse = (0, 0)
        self._plot_cache: pygame.Surface | None = None
        self._plot_key: tuple = ()
        self._plot_frame = -1
        self._ro = None
        self._ro_frame = -1
        self._ro_sim = None
        self.save_window: UIWindow | None = None
        self.save_entry: UITextEntryLine | None = None
        self.picker: LevelPicker | None = None
        self.follow = True
        """The view follows the fountain until the user pans or zooms (F follows again)."""
        self.quit_asked: float | None = None
        """When a first Esc asked to quit (a second within :data:`QUIT_WINDOW` quits)."""
        self.came_from: list[tuple[Level, Path | None, Level, bool]] = []
        """The levels M left for their twin (M on the twin goes back)."""
        self.camera: Camera | None = None
        self.scene_view = SceneView()
        self.timebar = TimeBar()
        self.ruler = Ruler()
        self.stopwatch = Stopwatch()
        self.rows: list[ControlRow] = []
        self._specs_cache: dict[tuple, list] = {}
        """:meth:`shown_specs`' last results, keyed by the view, the level and the level
        as loaded."""
        self._events = 0
        """Events the present frame handled (the whole window is copied to the screen)."""
        self._gc_at = time.perf_counter()
        self._layout()
        self.fit_view()
        settle_garbage()

    # ------------------------------------------------------------------ layout
    def _layout(self) -> None:
        """Lay the window out for its size and modes; rebuild the panel's widgets."""
        if getattr(self, "clip", None) is not None:  # a clip's frames keep one size
            self.toggle_clip()
            self.session.say("the window changed size: the clip is finished (G starts another)")
        text.set_text_scale(layout.text_scale(self.size, self.projector))
        self.lay = layout.compute(self.size, text.text_scale(), self.show_panel,
                                  self.show_plots)
        self.scene_rect = self.lay.scene
        self.ui = pygame_gui.UIManager(self.size, panel.gui_theme(text.text_scale()))
        if self.camera is None:
            self.camera = Camera(self.scene_rect)
        self.camera.rect = self.scene_rect
        self.timebar.place(self.scene_rect)
        self.stopwatch.place((self.scene_rect.right - text.px(10),
                              self.scene_rect.y + text.px(40)))
        if self.picker is not None:
            self.picker.place(self.size)
        self._plot_cache = None
        self._build_panel()

    @property
    def panel_rect(self) -> pygame.Rect | None:
        return self.lay.panel

    @property
    def plots_rect(self) -> pygame.Rect | None:
        return self.lay.plots

    def _panel_columns(self) -> tuple[pygame.Rect, pygame.Rect]:
        """The panel's two parts: the title, buttons and readout; the sliders. One above
        the other beside the scene, side by side under it (portrait)."""
        p = self.lay.panel
        if self.lay.portrait:
            half = p.w // 2
            return pygame.Rect(p.x, p.y, half, p.h), pygame.Rect(p.x + half, p.y, p.w - half,
                                                                 p.h)
        top = self._readout_bottom(p)
        return pygame.Rect(p.x, p.y, p.w, top - p.y), pygame.Rect(p.x, top, p.w, p.bottom - top)

    def _readout_bottom(self, p: pygame.Rect) -> int:
        """Where the readout ends and the sliders start in a landscape panel: room for the
        title, the buttons and the readout's rows of this level and view at the panel's
        width (:meth:`readout_lines`)."""
        from chainfountain.app.draw import TITLE_LINES, readout_font, title_font

        lines = self.readout_lines(p.w)
        return p.y + text.px(12) + TITLE_LINES * title_font().get_linesize() \
            + 2 * text.px(34) + text.px(8) \
            + lines * (readout_font(self.expert).get_linesize() + 1) + text.px(10)

    def readout_lines(self, width: int) -> int:
        """Lines the readout takes at most in a panel ``width`` wide: its rows with every
        number there, wrapped as :meth:`_draw_rows` wraps them."""
        from chainfountain.app.draw import readout_font
        from chainfountain.app.readout import Readout
        from chainfountain.app.readout_text import readout_rows

        s = self.session
        stiff = getattr(s.sim.reference, "theory", "") == "stiff"
        full = Readout(v=9.99, k=0.999, q=9.99, h=9.99, l=9.99, H=9.99, T0_bar=0.999,
                       TE_bar=0.999, T0_theory=0.999, TE_theory=0.999, measured=True,
                       paper_h=9.99 if s.sim.reference is not None else float("nan"),
                       theory="stiff" if stiff else "catenary",
                       theory_label=s.sim.reference.label if stiff else "paper",
                       joints="c = 9.99 N*m/rad, d = 9.99 N*m*s/rad",
                       theory_note="" if s.sim.catenary is None or not stiff_applies(
                           s.sim.config) else "no steady stiff fountain at c = 9.99 "
                       "N*m/rad, d = 9.99 N*m*s/rad",
                       origin="pick-up" if s.sim.beaker is not None else "launch")
        rows = readout_rows(full, s.sim.config.chain.linear_density, self.expert)
        f = readout_font(self.expert)
        room = width - text.px(16) - (text.px(60) if self.expert else 0)
        lines = sum(len(text.wrap(f, r.text, room)) for r in rows)
        from chainfountain.app.draw import EXTRA_LINES

        return lines + (3 * EXTRA_LINES if self.expert else 0)  # machine, bars, note

    def _build_panel(self) -> None:
        self.buttons: dict[str, UIButton] = {}
        self.rows = []
        self.title_rect = None
        self.controls_box = None
        if self.lay.panel is None:
            return
        head, sliders = self._panel_columns()
        px = text.px
        from chainfountain.app.draw import TITLE_LINES, title_font

        self.title_rect = pygame.Rect(head.x + px(8), head.y + px(6), head.w - px(16),
                                      TITLE_LINES * title_font().get_linesize())
        self.buttons, y = panel.build_buttons(self.ui, head, self.title_rect.bottom + px(6))
        self.readout_top = y + px(4)
        self.readout_rect = pygame.Rect(head.x, self.readout_top, head.w,
                                        head.bottom - self.readout_top)
        self.controls_box = UIScrollingContainer(sliders, self.ui, allow_scroll_x=False)
        self._build_controls()

    def _set_title(self) -> None:
        """The title is drawn with the panel (:meth:`_draw_panel`); nothing to set."""

    def _title_text(self) -> str:
        s = self.session
        return f"{s.level.meta.shown_title}{' *' if s.dirty else ''}"

    def shown_specs(self) -> list:
        """The fields the panel shows: every control field (expert view), else the
        level's student sliders; each spanning where its machine runs. The spans' search
        (about 0.5 s on a machine) is kept until the level or the view changes: a resize
        or projector mode rebuilds the panel with the same spans."""
        level = self.session.level
        key = (self.expert, repr(level), repr(self.session.origin))
        cache = self._specs_cache
        if key in cache:
            return list(cache[key])
        specs = control_fields(level.sim)
        if not self.expert:
            wanted = student_paths(level)
            specs = sorted((s for s in specs if s.path in wanted),
                           key=lambda s: wanted.index(s.path))
        shown = [spans.narrowed(level, s, self.session.origin) for s in specs]
        if len(cache) >= 4:  # both views of the level as it is, and of the one before
            cache.pop(next(iter(cache)))
        cache[key] = shown
        return list(shown)

    def _build_controls(self) -> None:
        for row in self.rows:
            for el in (row.label, row.slider, row.entry):
                el.kill()
        self.rows = []
        if self.controls_box is None:
            return
        width = self.controls_box.get_container().get_rect().w
        self.rows = panel.build_rows(self.ui, self.controls_box, width, self.shown_specs(),
                                     self.expert)
        for row in self.rows:
            self._show_value(row)
        for key, on in (("plots", self.show_plots), ("expert", self.expert)):
            b = self.buttons.get(key)
            if b is not None:
                (b.select if on else b.unselect)()

    def _row(self, path: str) -> ControlRow | None:
        for r in self.rows:
            if r.spec.path == path:
                return r
        return None

    def _show_value(self, row: ControlRow, value: float | None = None,
                    slider: bool = True) -> None:
        v = self.session.value(row.spec.path) if value is None else value
        if slider:
            row.slider.set_current_value(row.spec.to_slider(v), warn=False)
            fixed = row.spec.narrowed and row.spec.slider_lo == row.spec.slider_hi
            (row.slider.disable if fixed else row.slider.enable)()  # nothing to drag
            if fixed != row.fixed:  # and the label says so
                row.fixed = fixed
                panel.fit_label(row.label, panel.row_label(row.spec, self.expert, fixed))
        row.entry.set_text(row.spec.fmt(row.spec.to_display(v)))

    # ------------------------------------------------------------------ the view
    def fit_view(self) -> None:
        """Fit the camera to the scene, below the level's card while it shows and above
        the time controls, and follow the fountain from now on."""
        box = self.about_box() if self.about_visible else None
        top = box.bottom - self.scene_rect.top if box is not None else text.px(36)
        bottom = self.scene_rect.bottom - self.timebar.rect.top + text.px(6)
        ro = self.session.readout()
        self.camera.fit(*scene_bounds(self.session.sim, ro), top=top, bottom=bottom)
        # the parts' least sizes in pixels at that scale, then the fit again
        self.camera.fit(*scene_bounds(self.session.sim, ro, self.camera.scale), top=top,
                        bottom=bottom)
        self._fit_top = top
        self.follow = True

    def follow_view(self) -> None:
        """While following: refit when part of the scene has left the view, or when the
        scene fills less than a fifth of it (a fountain that shrank or settled)."""
        c = self.camera
        x0, y0, x1, y1 = scene_bounds(self.session.sim, None, c.scale)
        (ax, ay), (bx, by) = c.to_screen(np.array([[x0, y0], [x1, y1]]))
        r = self.scene_rect
        left, right = min(ax, bx), max(ax, bx)
        top, bottom = min(ay, by), max(ay, by)
        out = left < r.left - 2 or right > r.right + 2 or top < r.top - 2 or bottom > r.bottom + 2
        small = (right - left) * (bottom - top) < 0.2 * r.w * r.h
        if out or small:
            self.fit_view()

    def fit_view_if_lost(self) -> None:
        """Refit when the fountain would be mostly outside the view."""
        x0, y0, x1, y1 = scene_bounds(self.session.sim, None)
        a = self.camera.to_screen(np.array([[x0, y0], [x1, y1]]))
        if not (self.scene_rect.collidepoint(a[0]) or self.scene_rect.collidepoint(a[1])):
            self.fit_view()

    def relayout(self) -> None:
        """Lay out again (a mode changed) and fit the view."""
        self.close_dialogs()
        self._layout()
        self.fit_view()

    def toggle_projector(self) -> None:
        """Projector mode on or off: larger text and parts; the window keeps its size."""
        self.projector = not self.projector
        self.relayout()
        scale = text.text_scale()
        self.session.say(f"projector mode: text x{scale:.2f} (P: back)" if self.projector
                         else f"projector mode off: text x{scale:.2f}")

    def toggle_expert(self) -> None:
        """The expert view (every field, the paper's symbols, the graphs) or the student
        view (the level's sliders, plain words)."""
        self.expert = not self.expert
        if self.expert:  # the expert view shows the graphs; leaving it restores them
            self._plots_before, self.show_plots = self.show_plots, True
        else:
            self.show_plots = self._plots_before
        self.relayout()
        self.session.say("expert view: every field and the paper's symbols (E: student view)"
                         if self.expert else "student view: plain words (E: expert view)")

    def toggle_panel(self) -> None:
        """Hide the panel (the scene fills the window, the readout over it) or show it."""
        self.show_panel = not self.show_panel
        self.relayout()
        self.session.say("full view: Tab shows the panel" if not self.show_panel
                         else "panel shown")

    def toggle_plots(self) -> None:
        """The graphs under the scene on or off (V), in either view."""
        self.show_plots = not self.show_plots
        self.relayout()

    def toggle_ruler(self) -> None:
        if self.ruler.on:
            self.ruler.on = False
        else:
            self.ruler.show(self.camera)
            self.session.say("ruler: drag its ends (U hides it)")

    def toggle_stopwatch(self) -> None:
        self.stopwatch.on = not self.stopwatch.on
        if self.stopwatch.on:
            self.session.say("stopwatch: counts simulated seconds (W hides it)")

    # ------------------------------------------------------------------ commands
    def set_field(self, path: str, value: float) -> None:
        """Set a field from the GUI (clamped, live or rebuilt) and refresh its row."""
        res = self.session.set_field(path, value)
        level = self.session.level
        for row in self.rows:  # a change can move other fields and their spans
            if row.spec.path in spans.NARROWED_FIELDS:
                row.spec = spans.narrowed(level, spec_for(level.sim, row.spec.path),
                                          self.session.origin)
                for el in (row.label, row.entry):
                    el.set_tooltip(tooltip(row.spec, self.expert),
                                   wrap_width=panel.TOOLTIP_WIDTH)
                row.slider.value_range = (0.0, float(max(1, row.spec.positions)))
            self._show_value(row)
        if res.ok and not res.live:
            self.fit_view_if_lost()
        self._set_title()

    def reset(self) -> None:
        """Restart the scene with the current settings (R)."""
        self.session.reset()
        self._pending.clear()
        self.fit_view()

    def reset_all(self) -> None:
        """The level as it was opened: every setting back, the scene restarted (Shift+R,
        Reset all); changed settings are kept in an autosave first."""
        s = self.session
        kept = self.autosave("reset all") if s.dirty else None
        s.load_level(copy.deepcopy(s.opened), s.source)
        self._after_open()
        s.say("reset all: the level as opened" + (f" (your settings are kept as {kept.name})"
                                                   if kept else ""))

    def toggle_pause(self) -> None:
        self.session.toggle_pause()

    def step(self, physics: bool = False) -> None:
        s = self.session
        if not s.paused:
            s.toggle_pause()
        if physics:
            s.step_physics()
        else:
            s.step_frame(1.0 / 60.0)

    def set_speed(self, index: int) -> None:
        s = self.session
        while s.slow_index != index:
            s.cycle_slow()

    # ------------------------------------------------------------------ levels
    def autosave(self, why: str) -> Path | None:
        """Keep the present setup as an autosave in the user's folder (``why``: what is
        about to replace it); the path, or ``None`` when nothing was written."""
        if os.environ.get("CHAINFOUNTAIN_NO_AUTOSAVE"):
            return None
        p = self.session.keep_copy(f"autosave-{timestamp()}")
        if p is not None:
            _prune_autosaves(p.parent)
        return p

    def _keep_changes(self) -> str:
        """Before another level opens: unsaved changes go to an autosave; what to say."""
        if not self.session.dirty:
            return ""
        p = self.autosave("another level")
        return f"; your changes to the last level are kept as {p.name} (L lists it)" if p \
            else ""

    def load_path(self, path: Path, back: bool = False) -> bool:
        """Open a level file (errors are shown, never raised); unsaved changes are kept in
        an autosave and the window says so."""
        kept = self._keep_changes()
        ok = self.session.load_path(path)
        if ok:
            if not back:
                self.came_from.clear()
            self._after_open()
            if kept:
                self.session.say(f"opened {self.session.level.meta.shown_title}{kept}")
        return ok

    def open_level(self, level: Level, source: Path | None) -> bool:
        """Open ``level`` (a twin made here, or one M goes back to)."""
        kept = self._keep_changes()
        ok = self.session.load_level(level, source)
        if ok:
            self._after_open()
            if kept:
                self.session.say(f"opened {level.meta.shown_title}{kept}")
        return ok

    def _after_open(self) -> None:
        self.close_dialogs()
        self._pending.clear()
        self.show_theory = theory_by_default(self.session.level)
        self.show_about, self.about_pinned = True, False
        self.scene_view = SceneView()
        self._layout()
        self.fit_view()
        settle_garbage()

    def open_twin(self) -> bool:
        """M: open the machine's twin in the other machine, or go back to the level M came
        from (:func:`twin_of`); say so when there is none."""
        s = self.session
        if self.came_from:
            level, source, opened, dirty = self.came_from.pop()
            kept = self._keep_changes()
            ok = s.restore(level, source, opened, dirty)
            if ok:
                self._after_open()
                s.say(f"M: back to {level.meta.shown_title}" + kept)
            return ok
        twin = twin_of(s.level)
        if twin is None:
            s.say("M: this level has no twin (the machine levels each have one: the same "
                  "machine with the paper's ideal rollers, or with contact rollers)")
            return False
        here = (copy.deepcopy(s.level), s.source, copy.deepcopy(s.opened), s.dirty)
        level, source, why = twin
        if why.startswith(NO_LIKE_TWIN) and not self.expert:  # the short reason for a class
            why = (f"{NO_LIKE_TWIN}: the paper's rollers need carts that push here; this is "
                   "the same arrangement at its own drop and speed (E: why)")
        if self.open_level(level, source):
            self.came_from.append(here)
            s.say(f"M: {level.meta.shown_title} (M goes back)" + (f". {why}" if why else ""))
            return True
        return False

    def open_picker(self) -> None:
        self.close_dialogs()
        self.picker = LevelPicker(self.session.source)
        self.picker.place(self.size)

    def close_picker(self) -> None:
        self.picker = None

    def open_chosen(self) -> bool:
        """Open the picker's chosen level."""
        e = self.picker.chosen if self.picker is not None else None
        if e is None or e.path is None:
            self.session.say("pick a level first")
            return False
        self.picker = None
        return self.load_path(e.path)

    # ------------------------------------------------------------------ quitting
    def request_quit(self) -> None:
        """Esc: ask first (a second Esc within :data:`QUIT_WINDOW` quits; unsaved changes
        are kept in an autosave then)."""
        now = time.monotonic()
        if self.quit_asked is not None and now - self.quit_asked < QUIT_WINDOW:
            self.running = False
            return
        self.quit_asked = now

    @property
    def quit_prompt(self) -> str | None:
        """What the window says while a quit is asked, or ``None``."""
        if self.quit_asked is None or time.monotonic() - self.quit_asked >= QUIT_WINDOW:
            return None
        kept = " Your changes will be kept as an autosave." if self.session.dirty else ""
        return f"Quit chainfountain? Press Esc again to quit, any other key to stay.{kept}"

    # ------------------------------------------------------------------ pictures
    def capture_rect(self, with_plots: bool = False) -> pygame.Rect:
        """What pictures and clips take: the scene, or the scene and the graphs."""
        if with_plots and self.plots_rect is not None:
            return self.scene_rect.union(self.plots_rect)
        return self.scene_rect.copy()

    def screenshot(self, path: Path | None = None, background: bool = True,
                   with_plots: bool = False) -> Path:
        """Save a picture of the scene (with the graphs: ``with_plots``) as PNG, at full
        resolution and without the window's overlays (default: the captures folder)."""
        if path is None:
            path = _unique(paths.captures_dir(create=True), f"chainfountain-{timestamp()}",
                           ".png")
        self._still_rect = self.capture_rect(with_plots)
        try:
            self.draw()
        finally:
            self._still_rect = None
        still, self._still = self._still, None
        if background:
            self.saver.save(still, path)
        else:
            from chainfountain.app.capture import save_png

            save_png(still, path)
        self.last_capture = path
        self.session.say(f"picture: {path}")
        return path

    def toggle_clip(self, path: Path | None = None, with_plots: bool = False) -> Path | None:
        """Start or stop recording a clip of the scene (with the graphs: ``with_plots``)
        in simulated time; returns the clip path when starting."""
        if self.clip is not None and self.clip.recording:
            self.clip.stop()
            self.finishing_clips.append(self.clip)
            self.session.say(f"writing clip ({self.clip.seconds:.1f} s of simulated time) "
                             f"to {self.clip.path} ...")
            self.clip = None
            return None
        if path is None:
            ext = ".mp4" if mp4_available() else ".gif"
            path = _unique(paths.captures_dir(create=True), f"chainfountain-{timestamp()}", ext)
        fps = 30.0 if path.suffix.lower() == ".mp4" else 20.0  # a GIF counts in 10 ms
        self.clip = ClipRecorder(path, fps=fps, crop=self.capture_rect(with_plots))
        self.session.say(f"recording {'the scene and graphs' if with_plots else 'the scene'} "
                         f"in simulated time to {path} (G stops; up to "
                         f"{self.clip.max_frames / fps:.0f} s)")
        return path

    # ------------------------------------------------------------------ dialogs
    def open_save_dialog(self) -> None:
        self.close_dialogs()
        px = text.px
        r = pygame.Rect(0, 0, min(px(440), self.size[0] - 20), px(156))
        r.center = self.scene_rect.center
        win = UIWindow(r, self.ui, window_display_title="Save the setup as a level",
                       always_on_top=True)
        inner = r.w - px(36)
        folder = str(paths.user_levels_dir())
        if len(folder) > 40:
            folder = "..." + folder[-37:]
        label = UILabel(pygame.Rect(8, px(6), inner, px(22)), "", self.ui, container=win)
        panel.fit_label(label, f"Name (into {folder})")
        entry = UITextEntryLine(pygame.Rect(8, px(32), inner, px(30)), self.ui, container=win)
        entry.set_text(self.session.name)
        entry.focus()
        UIButton(pygame.Rect(inner - px(184), px(68), px(90), px(28)), "Save", self.ui,
                 container=win, object_id="#save_ok")
        UIButton(pygame.Rect(inner - px(88), px(68), px(90), px(28)), "Cancel", self.ui,
                 container=win, object_id="#dialog_cancel")
        self.save_window, self.save_entry = win, entry

    def close_dialogs(self) -> bool:
        closed = False
        if self.save_window is not None:
            self.save_window.kill()
            self.save_window = None
            closed = True
        if self.picker is not None:
            self.picker = None
            closed = True
        self.save_entry = None
        return closed

    def do_save(self, name: str) -> Path | None:
        path = self.session.save(name)
        if path is not None:
            self.close_dialogs()
            self._set_title()
        return path

    # ------------------------------------------------------------------ events
    def resize(self, size: tuple[int, int]) -> None:
        """Resize the window (at least :data:`~chainfountain.app.layout.MIN_SIZE`)."""
        size = (max(MIN_SIZE[0], int(size[0])), max(MIN_SIZE[1], int(size[1])))
        picker = self.picker
        self.close_dialogs()
        self.picker = picker
        if not self.offscreen:
            self.screen = pygame.display.set_mode(size, pygame.RESIZABLE)
        else:
            self.screen = pygame.display.set_mode(size)
        self.size = self.screen.get_size()
        self._layout()
        self.fit_view()

    # ------------------------------------------------------------------ frame
    def update(self, wall_dt: float) -> None:
        """Apply debounced rebuilds, run the physics for one frame, follow the fountain."""
        if self.follow and self._fit_top > text.px(40) and not self.about_visible:
            self.fit_view()  # the card has gone: the scene takes the whole view again
        if self.follow and self.frame % FOLLOW_EVERY == 0 and self._drag_mode is None:
            self.follow_view()
        now = time.perf_counter()
        for path, (v, t0) in list(self._pending.items()):
            if now - t0 >= REBUILD_DELAY or self.offscreen:
                del self._pending[path]
                self.set_field(path, v)
        s = self.session
        if self.offscreen:
            self.physics(wall_dt)
        self.stopwatch.tick(s.sim.time)
        self.ui.update(wall_dt)
        for err in self.saver.errors:
            s.say(err)
        self.saver.errors.clear()
        for clip in list(self.finishing_clips):
            if not clip.busy:
                self.finishing_clips.remove(clip)
                s.say(clip.error or f"clip saved: {clip.path}")
        if self.clip is not None and not self.clip.recording:  # stopped itself when full
            self.finishing_clips.append(self.clip)
            s.say(f"clip full, writing {self.clip.path} ...")
            self.clip = None

    def physics(self, wall_dt: float) -> None:
        """The physics of one frame: off-screen exactly one frame of simulated time, in a
        window what real time asks for within :meth:`physics_budget`."""
        s = self.session
        t0 = time.perf_counter()
        steps = 0
        if self.offscreen:
            if not s.paused:
                s.advance(s.speed_factor / self.fps)
                s.rtf = s.speed_factor
        else:
            steps = s.tick(wall_dt, self.physics_budget())
        self.physics_time = time.perf_counter() - t0
        if steps:
            cost = self.physics_time / (steps * s.sim.dt)
            self.physics_cost += 0.1 * (cost - self.physics_cost)

    def target_fps(self) -> float:
        """The frame rate to aim for: :attr:`fps` while the physics leaves room, fewer
        frames (down to :data:`MIN_FPS`) when the physics of real time and the drawing of
        every frame would take more than :data:`HEADROOM` of the core, and never so many
        that drawing takes more than :data:`DRAW_SHARE` of a frame (fewer frames are the
        first way the window draws less before the physics falls behind)."""
        s = self.session
        if s.paused or self.offscreen:
            return float(self.fps)
        spare = HEADROOM - self.physics_cost * s.speed_factor
        by_physics = spare / max(self.overhead, 1e-4)
        by_drawing = DRAW_SHARE / max(self.draw_time, 1e-4)
        return max(float(MIN_FPS), min(float(self.fps), by_physics, by_drawing))

    def _physics_during_flip(self, wall_dt: float) -> None:
        """Run :meth:`physics` while the drawn frame goes to the screen (the copy waits on
        the display with Python's lock released); the next frame draws its result."""
        failure: list[BaseException] = []

        def work() -> None:
            try:
                self.physics(wall_dt)
            except BaseException as exc:  # noqa: BLE001 - raised again below
                failure.append(exc)

        worker = threading.Thread(target=work, name="chainfountain-physics")
        worker.start()
        try:
            self._present()
        finally:
            worker.join()
        if failure:
            raise failure[0]

    def _present(self) -> None:
        """Copy the frame to the screen: the whole window when the panel may have changed
        (its readout is redrawn every :data:`~chainfountain.app.draw.PLOT_EVERY` frames, an
        event may have moved a widget, a card may be over it), else only the scene (and the
        graphs): under an X server that copies every pixel, a third fewer to copy."""
        from chainfountain.app.draw import PLOT_EVERY

        whole = (self._events or self.panel_rect is None or self.frame % PLOT_EVERY == 0
                 or self.picker is not None or self.show_help or self.save_window is not None
                 or self.quit_prompt is not None)
        if whole:
            pygame.display.flip()
        elif self.plots_rect is not None:
            pygame.display.update([self.scene_rect, self.plots_rect])
        else:
            pygame.display.update(self.scene_rect)

    def collect(self) -> None:
        """A full garbage collection every :data:`GC_EVERY` s of wall time, a second's
        garbage at a time (a few ms), instead of Python's own every few seconds."""
        now = time.perf_counter()
        if now - self._gc_at >= GC_EVERY:
            self._gc_at = now
            gc.collect(2)

    def physics_budget(self) -> float:
        """Wall seconds the physics may use this frame: what is left of a frame at
        :data:`MIN_FPS` (the frame rate gives way before the simulation slows down)."""
        return max(0.002, 1.0 / MIN_FPS - self.overhead - 0.001)

    def run_frame(self, wall_dt: float = 1.0 / 60.0) -> None:
        """One frame: queued events, physics, drawing, clip capture, flip."""
        t0 = time.perf_counter()
        self.physics_time = 0.0
        events = pygame.event.get()
        self._events = len(events)
        for ev in events:
            self.handle(ev)
        self.update(wall_dt)
        self.draw()
        self.collect()
        work = self.work_time = time.perf_counter() - t0 - self.physics_time
        if not self.offscreen:
            self._physics_during_flip(wall_dt)
        self.frame += 1
        self.overhead += 0.1 * (work - self.overhead)

    def run(self, frames: int | None = None, screenshot: Path | None = None) -> int:
        """Run until quit (or for ``frames`` frames); save ``screenshot`` of the last frame."""
        clock = pygame.time.Clock()
        try:
            while self.running and (frames is None or self.frame < frames):
                if self.offscreen:
                    clock.tick()
                    wall_dt = 1.0 / self.fps
                else:
                    wall_dt = clock.tick(self.target_fps()) / 1000.0
                if wall_dt > 0:
                    self.fps_measured += 0.05 * (1.0 / max(wall_dt, 1e-3) - self.fps_measured)
                self.run_frame(wall_dt)
            if screenshot is not None:
                self._plot_cache = self._ro = None  # fresh plots in the saved frame
                self.draw()
                from chainfountain.app.capture import save_png

                save_png(self.screen, Path(screenshot))
        finally:
            self.finish()
        return 0

    def finish(self) -> list[str]:
        """Quit without losing data: finish clips and pictures, keep unsaved changes."""
        notes: list[str] = []
        if self.clip is not None:
            self.clip.stop()
            self.finishing_clips.append(self.clip)
            self.clip = None
        for clip in self.finishing_clips:
            clip.wait()
            notes.append(clip.error or f"clip saved: {clip.path}")
        self.finishing_clips.clear()
        self.saver.wait()
        s = self.session
        if s.dirty and not self.offscreen:
            p = self.autosave("quit")
            if p is not None:
                notes.append(f"unsaved setup kept as {p}")
        for n in notes:
            print(f"chainfountain: {n}")
        pygame.display.quit()
        restore_garbage()
        return notes


def twin_of(level: Level) -> tuple[Level, Path | None, str] | None:
    """What M opens from ``level``, with a sentence on what it is: a contact machine's
    like-for-like ideal twin (the same drop, offsets and speed,
    :func:`chainfountain.level.twins.ideal_twin`); where the paper's rollers cannot run
    that fountain (they pick the chain up with ``lambda v^2/2``, about twice the contact
    rollers' pull, so most contact presets would need carts that push), the shipped ideal
    preset of the same arrangement, and why; for an ideal preset its contact preset.
    ``None`` when the level has no twin."""
    from chainfountain.level import io, twins

    if kind_of(level.sim) is twins.APPARATUS:
        try:
            twin = twins.ideal_twin(level)
        except LevelError as exc:
            other = library.twin(level.meta.name)
            if other is None:
                return None
            path = library.resolve(other)
            why = str(exc).split(": ", 1)[-1]
            return io.load(path), path, (f"{NO_LIKE_TWIN}: {why}; this is the same "
                                         "arrangement at its own drop and speed")
        return (twin, None, "the same drop, offsets and speed") if twin is not None else None
    twin = twins.contact_twin(level)
    if twin is None:
        return None
    return twin, library.resolve(twin.meta.name), "the same arrangement with contact rollers"


GC_THRESHOLDS = gc.get_threshold()
"""Python's garbage-collection thresholds as the window found them."""
GC_EVERY = 1.0
"""Wall seconds between the window's own full garbage collections (:meth:`App.collect`)."""


def settle_garbage() -> None:
    """Collect once and freeze what is left (the level, the window's widgets and caches)
    out of the garbage collector's sight, and leave the full collections to the window
    (:meth:`App.collect`): left to Python they came every few seconds and took 40-100 ms
    in one frame (the beaker at 1920x1080, where the links the floor takes are pymunk
    objects held in cycles by their C handles, freed only by a full collection), time the
    physics could not make up."""
    gc.collect()
    gc.freeze()
    young, middle, _ = gc.get_threshold()
    gc.set_threshold(young, middle, 1_000_000)


def restore_garbage() -> None:
    """Python's own garbage collection again (the window has closed)."""
    gc.unfreeze()
    gc.set_threshold(*GC_THRESHOLDS)
    gc.collect()


def _prune_autosaves(folder: Path) -> None:
    """Remove all but the newest :data:`AUTOSAVES_KEPT` ``autosave-*.toml`` in ``folder``."""
    for old in sorted(folder.glob("autosave-*.toml"))[:-AUTOSAVES_KEPT]:
        try:
            old.unlink()
        except OSError:
            pass
