"""The window: pygame-ce drawing, pygame_gui controls, keys and mouse.

:class:`App` reads a :class:`~chainfountain.app.session.Session` (the model
side) and sends it commands; all pixels are made here and in
:mod:`chainfountain.app.render`. The physics runs at its fixed step inside
:meth:`Session.tick`, with a per-frame time budget so drawing stays at the
frame rate; when the machine cannot keep up the fountain slows down and the
real-time factor is shown.
"""

from __future__ import annotations

import html
import os
import threading
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pygame
import pygame_gui
from pygame_gui.elements import (
    UIButton,
    UIHorizontalSlider,
    UILabel,
    UIScrollingContainer,
    UISelectionList,
    UITextBox,
    UITextEntryLine,
    UIWindow,
)

from chainfountain.app import paths, render, spans
from chainfountain.app.capture import BackgroundSaver, ClipRecorder, mp4_available, timestamp
from chainfountain.app.capture import unique_path as _unique
from chainfountain.app.controls import SLIDER_STEPS, FieldSpec, control_fields, spec_for
from chainfountain.app.draw import DrawMixin
from chainfountain.app.input import InputMixin
from chainfountain.app.session import Session
from chainfountain.level import library

LEFT_W = 300
RIGHT_W = 390
"""Widths of the control panel and of the readout (pixels at text scale 1)."""
DEFAULT_SIZE = (1280, 760)
PROJECTOR = 1.4
"""Projector mode (P, ``play --projector``) makes the text this much larger."""
PANEL_SHARE = 0.55
"""The control panel and the readout take at most this share of the window's width (the
text scale is capped for it)."""
GUI_FONT = 14
"""pygame_gui's text size (pixels at text scale 1)."""
FRAMEBUFFER_HINT = "SDL_FRAMEBUFFER_ACCELERATION"
"""SDL's hint for how a window's pixels reach the screen; the window sets it to "0" unless
the environment sets it: through the display's own framebuffer (X11: shared memory), not
SDL's OpenGL texture. Without GPU drivers (Mesa's llvmpipe; Xvfb) the OpenGL path runs two
rendering threads beside the physics on the same cores: ``apparatus_fold_gripped`` in a
1280x760 window under Xvfb ran at 0.89-0.91x real time and 30-31 frames/s with it,
0.97-0.98x and 42-44 frames/s without (``benchmarks/bench_app.py --window``, two runs
each; docs/apparatus.md). Set ``SDL_FRAMEBUFFER_ACCELERATION=1`` to use it."""
MIN_FPS = 30
"""The frame rate may drop to this before the simulation runs slower than requested."""
HEADROOM = 0.9
"""Share of one core the window's own work (the physics of real time and the drawing of
every frame) may take before it draws fewer frames (:meth:`App.target_fps`); the rest is
for the display and the system."""
FOLLOW_EVERY = 30
"""Frames between checks that the view still shows the fountain (0.5 s at 60 frames/s)."""
REBUILD_DELAY = 0.35
"""Seconds a rebuild-only slider must rest before the scene is rebuilt."""


@dataclass
class ControlRow:
    """The widgets of one schema field."""

    spec: FieldSpec
    label: UILabel
    slider: UIHorizontalSlider
    entry: UITextEntryLine


def text_scale(size: tuple[int, int], projector: bool) -> float:
    """The window's text scale: 1 at :data:`DEFAULT_SIZE`, growing with the window, times
    :data:`PROJECTOR` in projector mode; capped so that the control panel and the readout
    leave the scene :data:`PANEL_SHARE` of the width."""
    w, h = size
    s = max(1.0, min(w / DEFAULT_SIZE[0], h / DEFAULT_SIZE[1]))
    if projector:
        s *= PROJECTOR
    return max(1.0, min(s, PANEL_SHARE * w / (LEFT_W + RIGHT_W)))


def _move_window_to_origin() -> None:
    """Put the window at the screen's top left corner (projector mode fills the screen)."""
    try:
        pygame.Window.from_display_module().position = (0, 0)
    except (AttributeError, pygame.error):  # an SDL without windows to move: leave it
        pass


def gui_theme(scale: float) -> dict:
    """pygame_gui's theme at text scale ``scale``: its font for every element the window
    uses."""
    size = str(round(GUI_FONT * scale))
    font = {"font": {"name": "noto_sans", "size": size}}
    return {t: font for t in ("label", "button", "text_entry_line", "text_box",
                              "selection_list", "tool_tip", "window", "horizontal_slider")}


TOOLTIP_WIDTH = 420
"""Width (px) a field's tooltip wraps at: the longest dotted path (``chain.bending_stiffness:``)
fits on a line, so the wrap never breaks a word (pygame_gui hyphenates one that does not fit)."""


def _tooltip(spec: FieldSpec) -> str:
    how = "applies live" if spec.live else "rebuilds the scene"
    span = ""
    if spec.narrowed:
        lo, hi = spec.slider_lo, spec.slider_hi
        span = (f" The slider spans {lo:.4g}-{hi:.4g}{spec.shown_unit}, where this machine "
                "keeps running; a value typed beyond runs as a real machine would.")
    return html.escape(f"{spec.path}: {spec.doc}. Allowed: {spec.allowed()}. Changing it "
                       f"{how}.{span}")


class App(InputMixin, DrawMixin):
    """The interactive front end for one session.

    Parameters
    ----------
    session:
        The running level.
    size:
        Window size in pixels.
    offscreen:
        Deterministic frames: each frame advances exactly ``1/fps`` s of
        simulated time (times the slow-motion factor), independent of wall
        time (``--frames`` runs and tests).
    fps:
        Target frame rate.
    """

    def __init__(self, session: Session, size: tuple[int, int] = DEFAULT_SIZE,
                 offscreen: bool = False, fps: int = 60, projector: bool = False) -> None:
        os.environ.setdefault(FRAMEBUFFER_HINT, "0")
        pygame.display.init()
        pygame.font.init()
        flags = 0 if offscreen else pygame.RESIZABLE
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
        """The level's description on the view (I); shown again whenever a level opens,
        for its first :data:`~chainfountain.app.draw.ABOUT_SECONDS` of simulated time
        unless I pinned it."""
        self._about_low = False
        """The level's card is at the bottom of the view (:meth:`_draw_about`)."""
        self._fit_top = 0
        """Pixels the last fit kept free at the view's top for the description card."""
        self.about_pinned = False
        """I showed the description: it stays until I hides it."""
        self.show_theory = True
        self.expert = False
        """The readout in the paper's symbols (E) instead of plain words."""
        self.frame = 0
        self.draw_time = 0.004
        self.overhead = 0.006
        """Smoothed wall time of a frame before its physics (events, GUI, drawing; the flip to
        the screen overlaps the physics)."""
        self.physics_time = 0.0
        """Wall time of the last frame's physics (s)."""
        self.physics_cost = 0.0
        """Smoothed wall seconds the physics takes per simulated second (window only)."""
        self.work_time = 0.0
        """Wall time of the last frame before its physics (s; :attr:`overhead` unsmoothed)."""
        self.fps_measured = float(fps)
        self.clip: ClipRecorder | None = None
        self._still_rect: pygame.Rect | None = None
        """While a picture is taken: the part of the window it takes."""
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
        self.load_window: UIWindow | None = None
        self.load_list: UISelectionList | None = None
        self.load_about: UITextBox | None = None
        self._load_items: dict[str, Path] = {}
        self.follow = True
        """The view follows the fountain until the user pans or zooms (F follows again)."""
        self.projector = projector
        """Projector mode (P): larger text everywhere (:func:`text_scale`); a window
        smaller than the screen grows to it."""
        self._size_before: tuple[int, int] | None = None
        """The window's size before projector mode grew it (restored when it ends)."""
        self._layout()
        self.fit_view()

    # ------------------------------------------------------------------ layout
    def _layout(self) -> None:
        if getattr(self, "clip", None) is not None:  # a clip's frames keep one size
            self.toggle_clip()
            self.session.say("the window changed size: the clip is finished (G starts another)")
        w, h = self.size
        render.set_text_scale(text_scale(self.size, self.projector))
        px = render.px
        self.left_w, right_w = px(LEFT_W), px(RIGHT_W)
        self.scene_rect = pygame.Rect(self.left_w, 0, max(100, w - self.left_w - right_w), h)
        self.right_rect = pygame.Rect(w - right_w, 0, right_w, h)
        self.ui = pygame_gui.UIManager((w, h), gui_theme(render.text_scale()))
        self.camera = getattr(self, "camera", None) or render.Camera(self.scene_rect)
        self.camera.rect = self.scene_rect
        self._build_panel()

    def _build_panel(self) -> None:
        ui = self.ui
        px, lw = render.px, self.left_w
        self.buttons: dict[str, UIButton] = {}
        self.title = UILabel(pygame.Rect(8, px(4), lw - 16, px(24)), self._title_text(), ui)
        row1 = (("play", "Pause", "Play / pause (Space)"), ("step", "Step", "Single step (Right)"),
                ("slow", "Slow", "Slow motion 1/2, 1/4 (S)"), ("reset", "Reset", "Reset (R)"))
        row2 = (("save", "Save", "Save the setup as a level (Ctrl+S)"),
                ("load", "Load", "Open a level (Ctrl+O)"), ("shot", "Shot", "Screenshot (F12)"),
                ("rec", "Rec", "Record a clip (G)"), ("help", "?", "Keys (H, F1)"))
        for y, row in ((px(32), row1), (px(64), row2)):
            bw = (lw - 16) // len(row)
            for i, (key, text, tip) in enumerate(row):
                self.buttons[key] = UIButton(pygame.Rect(8 + i * bw, y, bw - 4, px(28)), text,
                                             ui, tool_tip_text=tip)
        top = px(100)
        self.controls_box = UIScrollingContainer(
            pygame.Rect(0, top, lw, self.size[1] - top), ui, allow_scroll_x=False)
        self._build_controls()

    def _title_text(self) -> str:
        s = self.session
        return f"{s.name}{' *' if s.dirty else ''}  ({s.level.sim.kind})"

    def _build_controls(self) -> None:
        box = self.controls_box
        for row in getattr(self, "rows", []):
            for el in (row.label, row.slider, row.entry):
                el.kill()
        self.rows: list[ControlRow] = []
        level = self.session.level
        origin = self.session.origin
        specs = [spans.narrowed(level, s, origin) for s in control_fields(level.sim)]
        px, lw = render.px, self.left_w
        y = px(4)
        for spec in specs:
            tag = "live" if spec.live else "rebuild"
            unit = f" ({spec.unit})" if spec.unit and spec.unit != "1" else ""
            label = UILabel(pygame.Rect(8, y, lw - 30, px(20)), f"{spec.label}{unit}  [{tag}]",
                            self.ui, container=box, object_id="#field_label")
            label.set_tooltip(_tooltip(spec), wrap_width=TOOLTIP_WIDTH)
            slider = UIHorizontalSlider(pygame.Rect(8, y + px(21), px(180), px(24)), 0,
                                        (0, SLIDER_STEPS),
                                        self.ui, container=box, click_increment=1)
            entry = UITextEntryLine(pygame.Rect(px(192), y + px(20), lw - px(222), px(26)),
                                    self.ui,
                                    container=box)
            entry.set_allowed_characters(list("0123456789.-+eE"))
            entry.set_tooltip(_tooltip(spec), wrap_width=TOOLTIP_WIDTH)
            row = ControlRow(spec, label, slider, entry)
            self.rows.append(row)
            self._show_value(row)
            y += px(52)
        box.set_scrollable_area_dimensions((lw - 20, y + 8))

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
        row.entry.set_text(row.spec.fmt(row.spec.to_display(v)))

    def fit_view(self) -> None:
        """Fit the camera to the scene, below the level's description card while it shows,
        and follow the fountain from now on."""
        box = self.about_box() if self.about_visible else None
        top = box.bottom - self.scene_rect.top if box is not None else 0
        self.camera.fit(*render.scene_bounds(self.session.sim, self.session.readout()),
                        top=top)
        self._fit_top = top
        self.follow = True

    def follow_view(self) -> None:
        """While following: refit when part of the scene has left the view, or when the
        scene fills less than a fifth of it (a fountain that shrank or settled)."""
        x0, y0, x1, y1 = render.scene_bounds(self.session.sim, None)
        c = self.camera
        (ax, ay), (bx, by) = c.to_screen(np.array([[x0, y0], [x1, y1]]))
        r = self.scene_rect
        left, right = min(ax, bx), max(ax, bx)
        top, bottom = min(ay, by), max(ay, by)
        out = left < r.left - 2 or right > r.right + 2 or top < r.top - 2 or bottom > r.bottom + 2
        small = (right - left) * (bottom - top) < 0.2 * r.w * r.h
        if out or small:
            self.fit_view()

    # ------------------------------------------------------------------ commands
    def set_field(self, path: str, value: float) -> None:
        """Set a schema field from the GUI (clamped, live or rebuilt) and refresh its row."""
        res = self.session.set_field(path, value)
        level = self.session.level
        # a change can move other fields (a cart that follows the balance) and the spans
        for row in self.rows:
            if row.spec.path in spans.NARROWED_FIELDS:
                row.spec = spans.narrowed(level, spec_for(level.sim, row.spec.path),
                                          self.session.origin)
                for el in (row.label, row.entry):
                    el.set_tooltip(_tooltip(row.spec), wrap_width=TOOLTIP_WIDTH)
            self._show_value(row)
        if res.ok and not res.live:
            self.fit_view_if_lost()
        self.title.set_text(self._title_text())

    def fit_view_if_lost(self) -> None:
        """Refit when the fountain would be mostly outside the view."""
        x0, y0, x1, y1 = render.scene_bounds(self.session.sim, None)
        c = self.camera
        a = c.to_screen(np.array([[x0, y0], [x1, y1]]))
        if not (self.scene_rect.collidepoint(a[0]) or self.scene_rect.collidepoint(a[1])):
            self.fit_view()

    def reset(self) -> None:
        self.session.reset()
        self._pending.clear()
        self.fit_view()

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

    def capture_rect(self, with_plots: bool = False) -> pygame.Rect:
        """What pictures and clips take: the scene, or the scene and the plots beside it."""
        return self.scene_rect.union(self.right_rect) if with_plots else self.scene_rect.copy()

    def screenshot(self, path: Path | None = None, background: bool = True,
                   with_plots: bool = False) -> Path:
        """Save a picture of the scene (with the plots: ``with_plots``) as PNG, at full
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
        """Start or stop recording a clip of the scene (with the plots: ``with_plots``) in
        simulated time; returns the clip path when starting."""
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
        self.session.say(f"recording {'the scene and plots' if with_plots else 'the scene'} "
                         f"in simulated time to {path} (G stops; up to "
                         f"{self.clip.max_frames / fps:.0f} s)")
        return path

    def open_save_dialog(self) -> None:
        self.close_dialogs()
        px = render.px
        r = pygame.Rect(0, 0, px(420), px(150))
        r.center = self.scene_rect.center
        win = UIWindow(r, self.ui, window_display_title="Save level as", always_on_top=True)
        folder = str(paths.user_levels_dir())
        if len(folder) > 40:
            folder = "..." + folder[-37:]
        UILabel(pygame.Rect(8, px(6), px(390), px(22)), f"Name (into {folder})", self.ui,
                container=win)
        entry = UITextEntryLine(pygame.Rect(8, px(32), px(390), px(30)), self.ui, container=win)
        entry.set_text(self.session.name)
        entry.focus()
        UIButton(pygame.Rect(px(218), px(68), px(90), px(28)), "Save", self.ui, container=win,
                 object_id="#save_ok")
        UIButton(pygame.Rect(px(310), px(68), px(90), px(28)), "Cancel", self.ui, container=win,
                 object_id="#dialog_cancel")
        self.save_window, self.save_entry = win, entry

    def open_load_dialog(self) -> None:
        self.close_dialogs()
        items = paths.list_levels()
        self._load_items = {label: p for label, p in items if p is not None}
        px = render.px
        w = min(px(780), self.size[0] - 20)
        r = pygame.Rect(0, 0, w, min(px(400), self.size[1] - 20))
        r.center = (self.size[0] // 2, self.size[1] // 2)
        win = UIWindow(r, self.ui, window_display_title="Open a level", always_on_top=True)
        labels = [label for label, _ in items] or ["(no level files found)"]
        list_w, list_h = px(300), r.h - px(100)
        self.load_list = UISelectionList(pygame.Rect(8, 6, list_w, list_h), labels, self.ui,
                                         container=win)
        self.load_about = UITextBox("Click a level to read what it shows and what to watch; "
                                    "double-click or Open to open it.",
                                    pygame.Rect(list_w + 16, 6, w - list_w - 56, list_h),
                                    self.ui, container=win)
        UIButton(pygame.Rect(w - px(232), list_h + 14, px(90), px(28)), "Open", self.ui,
                 container=win, object_id="#load_ok")
        UIButton(pygame.Rect(w - px(140), list_h + 14, px(90), px(28)), "Cancel", self.ui,
                 container=win,
                 object_id="#dialog_cancel")
        self.load_window = win

    def describe_choice(self, label: str | None) -> None:
        """Show the picked level's description beside the picker's list."""
        if self.load_about is None:
            return
        if label in paths.HEADING_TEXT:
            self.load_about.set_text(html.escape(paths.HEADING_TEXT[label]))
            return
        path = self._load_items.get(label or "")
        if path is None:
            return
        start = ("Starts at rest and forms its fountain." if paths.forms_from_rest(path)
                 else "Starts laid on its path, already moving.")
        self.load_about.set_text(f"{html.escape(path.stem)}: {start}<br>"
                                 + html.escape(paths.level_description(path)))

    def close_dialogs(self) -> bool:
        closed = False
        for attr in ("save_window", "load_window"):
            win = getattr(self, attr)
            if win is not None:
                win.kill()
                setattr(self, attr, None)
                closed = True
        self.save_entry = None
        self.load_list = None
        self.load_about = None
        return closed

    def do_save(self, name: str) -> Path | None:
        path = self.session.save(name)
        if path is not None:
            self.close_dialogs()
            self.title.set_text(self._title_text())
        return path

    def do_load(self, label: str | None) -> bool:
        if not label or label not in self._load_items:
            self.session.say("pick a level first")
            return False
        return self.load_path(self._load_items[label])

    def load_path(self, path: Path) -> bool:
        """Open a level file (errors are shown, never raised)."""
        ok = self.session.load_path(path)
        if ok:
            self.close_dialogs()
            self._pending.clear()
            self._build_controls()
            self.title.set_text(self._title_text())
            self.fit_view()
            self.show_about, self.about_pinned = True, False
        return ok

    def open_twin(self) -> bool:
        """Open the current machine preset in the other machine (contact or ideal;
        :func:`chainfountain.level.library.twin`), or say there is none."""
        other = library.twin(self.session.level.meta.name)
        if other is None:
            self.session.say("M: this level has no twin (the machine presets apparatus_floor, "
                             "_fold, _special, _limit and _open each have an ideal one)")
            return False
        return self.load_path(library.resolve(other))

    def toggle_projector(self) -> None:
        """Projector mode on or off: the text, panels and controls grow (or shrink back), a
        window smaller than the screen grows to fill it (and returns to its size after),
        the view is fitted again."""
        self.projector = not self.projector
        size = self.size
        if not self.offscreen:  # a projector shows the whole screen: grow to it, and back
            if self.projector:
                self._size_before = self.size
                desk = pygame.display.get_desktop_sizes()
                if desk and desk[0][0] > size[0] and desk[0][1] > size[1]:
                    size = desk[0]
            elif self._size_before is not None:
                size, self._size_before = self._size_before, None
        if size != self.size:
            self.resize(size)
            if self.projector:
                _move_window_to_origin()
        else:
            self.close_dialogs()
            self._layout()
            self.fit_view()
        self._plot_cache = None
        scale = render.text_scale()
        self.session.say(f"projector mode: text x{scale:.2f} (P: back)" if self.projector
                         else f"projector mode off: text x{scale:.2f}")

    def request_quit(self) -> None:
        self.running = False

    # ------------------------------------------------------------------ events
    def resize(self, size: tuple[int, int]) -> None:
        """Resize the window (at least 900 x 560 pixels) and refit the view."""
        size = (max(900, int(size[0])), max(560, int(size[1])))
        self.close_dialogs()
        self.screen = pygame.display.set_mode(size, pygame.RESIZABLE)
        self.size = self.screen.get_size()
        self._layout()
        self.fit_view()

    # ------------------------------------------------------------------ frame
    def update(self, wall_dt: float) -> None:
        """Apply debounced rebuilds, run the physics for one frame, follow the fountain."""
        if self.follow and self._fit_top and not self.about_visible:
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
        play = "Play" if s.paused else "Pause"
        if self.buttons["play"].text != play:
            self.buttons["play"].set_text(play)
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
        steps = 0  # real-time steps (window only): they measure the physics' cost
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
        frames (down to :data:`MIN_FPS`) when the physics of real time and the drawing
        of every frame would take more than :data:`HEADROOM` of the core. Every frame
        drawn costs :attr:`overhead` (5-7 ms), time the physics needs: at 0.7 s of
        physics per simulated second (``apparatus_fold_gripped``) 60 frames/s would
        leave too little for real time, 40 leave enough."""
        s = self.session
        if s.paused or self.offscreen:
            return float(self.fps)
        spare = HEADROOM - self.physics_cost * s.speed_factor
        return max(float(MIN_FPS), min(float(self.fps), spare / max(self.overhead, 1e-4)))

    def _physics_during_flip(self, wall_dt: float) -> None:
        """Run :meth:`physics` while the drawn frame goes to the screen. Copying a frame
        to the screen waits on the display (about 10 ms at 1280x760 under a software X
        server, Xvfb) with Python's lock released, so the physics runs in that wait
        instead of after it; the next frame draws its result. Nothing else touches the
        model meanwhile (events are handled before the frame is drawn)."""
        failure: list[BaseException] = []

        def work() -> None:
            try:
                self.physics(wall_dt)
            except BaseException as exc:  # noqa: BLE001 - raised again below
                failure.append(exc)

        worker = threading.Thread(target=work, name="chainfountain-physics")
        worker.start()
        try:
            pygame.display.flip()
        finally:  # Ctrl-C in the flip: the model is left alone before anything else runs
            worker.join()
        if failure:
            raise failure[0]

    def physics_budget(self) -> float:
        """Wall seconds the physics may use this frame.

        First what is left of a frame at the target rate; when that is not
        enough for real time, the frame rate may sink towards :data:`MIN_FPS`
        before the simulation itself slows down (then the real-time factor
        shown drops below the requested speed).
        """
        # Session.tick only takes the steps real time asks for, so when they fit in
        # a 1/fps frame the frame rate stays; only the cap is at MIN_FPS.
        return max(0.002, 1.0 / MIN_FPS - self.overhead - 0.001)

    def run_frame(self, wall_dt: float = 1.0 / 60.0) -> None:
        """One frame: queued events, physics, drawing, clip capture, flip."""
        t0 = time.perf_counter()
        self.physics_time = 0.0
        for ev in pygame.event.get():
            self.handle(ev)
        self.update(wall_dt)
        self.draw()  # the clip takes its frame while drawing
        work = self.work_time = time.perf_counter() - t0 - self.physics_time
        if not self.offscreen:
            self._physics_during_flip(wall_dt)  # the flip overlaps the physics
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
        """Quit without losing data: finish clips and screenshots, keep unsaved changes."""
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
        if s.dirty and not self.offscreen and not os.environ.get("CHAINFOUNTAIN_NO_AUTOSAVE"):
            p = s.save(f"autosave-{timestamp()}")
            if p is not None:
                notes.append(f"unsaved setup kept as {p}")
                _prune_autosaves(p.parent)
        for n in notes:
            print(f"chainfountain: {n}")
        pygame.display.quit()
        return notes



AUTOSAVES_KEPT = 10
"""Autosaves kept in the user's level folder (one per quit with unsaved changes, named
by time; the oldest beyond this are removed)."""


def _prune_autosaves(folder: Path) -> None:
    """Remove all but the newest :data:`AUTOSAVES_KEPT` ``autosave-*.toml`` in ``folder``."""
    for old in sorted(folder.glob("autosave-*.toml"))[:-AUTOSAVES_KEPT]:
        try:
            old.unlink()
        except OSError:
            pass
