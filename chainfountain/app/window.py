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
import math
import os
import textwrap
import time
from collections.abc import Callable
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
    UITextEntryLine,
    UIWindow,
)

from chainfountain.app import paths, render
from chainfountain.app.capture import BackgroundSaver, ClipRecorder, mp4_available, timestamp
from chainfountain.app.capture import unique_path as _unique
from chainfountain.app.controls import SLIDER_STEPS, FieldSpec, control_fields
from chainfountain.app.session import Session, paused_message
from chainfountain.theory.apparatus import plate_reaction

LEFT_W = 300
RIGHT_W = 390
DEFAULT_SIZE = (1280, 760)
MIN_FPS = 30
"""The frame rate may drop to this before the simulation runs slower than requested."""
PLOT_EVERY = 4
"""Redraw the live plots every this many frames (15 Hz at 60 frames/s)."""
REBUILD_DELAY = 0.35
"""Seconds a rebuild-only slider must rest before the scene is rebuilt."""
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
    ("F", "fit the view to the fountain"),
    ("T", "theory overlay on / off"),
    ("Mouse wheel", "zoom about the pointer"),
    ("Drag (empty space)", "pan; right or middle drag also pans"),
    ("Drag (on the chain)", "pull a link"),
    ("Ctrl+S", "save the setup as a level (name prompt)"),
    ("Ctrl+O  or  L", "open a level (picker)"),
    ("F12", "screenshot (PNG)"),
    ("G", "start / stop recording a clip (GIF, or MP4 with imageio-ffmpeg)"),
    ("H  or  F1", "this help"),
    ("Enter (in a field)", "apply the typed value (clamped to the level schema)"),
    ("Esc", "close a dialog; else quit (clips and changes are kept)"),
)


@dataclass
class ControlRow:
    """The widgets of one schema field."""

    spec: FieldSpec
    label: UILabel
    slider: UIHorizontalSlider
    entry: UITextEntryLine


def _tooltip(spec: FieldSpec) -> str:
    how = "applies live" if spec.live else "rebuilds the scene"
    return html.escape(f"{spec.path}: {spec.doc}. Allowed: {spec.allowed()}. Changing it {how}.")


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


class App:
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
                 offscreen: bool = False, fps: int = 60) -> None:
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
        self.show_theory = True
        self.frame = 0
        self.draw_time = 0.004
        self.overhead = 0.006
        """Smoothed wall time of a frame without the physics (events, GUI, drawing, flip)."""
        self.physics_time = 0.0
        self.fps_measured = float(fps)
        self.clip: ClipRecorder | None = None
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
        self._load_items: dict[str, Path] = {}
        self._layout()
        self.fit_view()

    # ------------------------------------------------------------------ layout
    def _layout(self) -> None:
        w, h = self.size
        self.scene_rect = pygame.Rect(LEFT_W, 0, max(100, w - LEFT_W - RIGHT_W), h)
        self.right_rect = pygame.Rect(w - RIGHT_W, 0, RIGHT_W, h)
        self.ui = pygame_gui.UIManager((w, h))
        self.camera = getattr(self, "camera", None) or render.Camera(self.scene_rect)
        self.camera.rect = self.scene_rect
        self._build_panel()

    def _build_panel(self) -> None:
        ui = self.ui
        self.buttons: dict[str, UIButton] = {}
        self.title = UILabel(pygame.Rect(8, 4, LEFT_W - 16, 24), self._title_text(), ui)
        row1 = (("play", "Pause", "Play / pause (Space)"), ("step", "Step", "Single step (Right)"),
                ("slow", "Slow", "Slow motion 1/2, 1/4 (S)"), ("reset", "Reset", "Reset (R)"))
        row2 = (("save", "Save", "Save the setup as a level (Ctrl+S)"),
                ("load", "Load", "Open a level (Ctrl+O)"), ("shot", "Shot", "Screenshot (F12)"),
                ("rec", "Rec", "Record a clip (G)"), ("help", "?", "Keys (H, F1)"))
        for y, row in ((32, row1), (64, row2)):
            bw = (LEFT_W - 16) // len(row)
            for i, (key, text, tip) in enumerate(row):
                self.buttons[key] = UIButton(pygame.Rect(8 + i * bw, y, bw - 4, 28), text, ui,
                                             tool_tip_text=tip)
        top = 100
        self.controls_box = UIScrollingContainer(
            pygame.Rect(0, top, LEFT_W, self.size[1] - top), ui, allow_scroll_x=False)
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
        specs = control_fields(self.session.level.sim)
        y = 4
        for spec in specs:
            tag = "live" if spec.live else "rebuild"
            unit = f" ({spec.unit})" if spec.unit and spec.unit != "1" else ""
            label = UILabel(pygame.Rect(8, y, LEFT_W - 30, 20), f"{spec.label}{unit}  [{tag}]",
                            self.ui, container=box, object_id="#field_label")
            label.set_tooltip(_tooltip(spec))
            slider = UIHorizontalSlider(pygame.Rect(8, y + 21, 180, 24), 0, (0, SLIDER_STEPS),
                                        self.ui, container=box, click_increment=1)
            entry = UITextEntryLine(pygame.Rect(192, y + 20, LEFT_W - 222, 26), self.ui,
                                    container=box)
            entry.set_allowed_characters(list("0123456789.-+eE"))
            entry.set_tooltip(_tooltip(spec))
            row = ControlRow(spec, label, slider, entry)
            self.rows.append(row)
            self._show_value(row)
            y += 52
        box.set_scrollable_area_dimensions((LEFT_W - 20, y + 8))

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
        """Fit the camera to the scene."""
        self.camera.fit(*render.scene_bounds(self.session.sim, self.session.readout()))

    # ------------------------------------------------------------------ commands
    def set_field(self, path: str, value: float) -> None:
        """Set a schema field from the GUI (clamped, live or rebuilt) and refresh its row."""
        res = self.session.set_field(path, value)
        row = self._row(path)
        if row is not None:
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

    def screenshot(self, path: Path | None = None, background: bool = True) -> Path:
        """Save the current window as PNG (default: the user's captures folder)."""
        if path is None:
            path = _unique(paths.captures_dir(create=True), f"chainfountain-{timestamp()}",
                           ".png")
        self.draw()
        if background:
            self.saver.save(self.screen, path)
        else:
            from chainfountain.app.capture import save_png

            save_png(self.screen, path)
        self.last_capture = path
        self.session.say(f"screenshot: {path}")
        return path

    def toggle_clip(self, path: Path | None = None, every_frame: bool = False) -> Path | None:
        """Start or stop recording a clip; returns the clip path when starting."""
        if self.clip is not None and self.clip.recording:
            self.clip.stop()
            self.finishing_clips.append(self.clip)
            self.session.say(f"writing clip ({self.clip.frames} frames) to {self.clip.path} ...")
            self.clip = None
            return None
        if path is None:
            ext = ".mp4" if mp4_available() else ".gif"
            path = _unique(paths.captures_dir(create=True), f"chainfountain-{timestamp()}", ext)
        self.clip = ClipRecorder(path, fps=15.0, scale=0.5, every_call=every_frame or
                                 self.offscreen)
        self.session.say(f"recording clip to {path} (G stops)")
        return path

    def open_save_dialog(self) -> None:
        self.close_dialogs()
        r = pygame.Rect(0, 0, 420, 150)
        r.center = self.scene_rect.center
        win = UIWindow(r, self.ui, window_display_title="Save level as", always_on_top=True)
        folder = str(paths.user_levels_dir())
        if len(folder) > 40:
            folder = "..." + folder[-37:]
        UILabel(pygame.Rect(8, 6, 390, 22), f"Name (into {folder})", self.ui, container=win)
        entry = UITextEntryLine(pygame.Rect(8, 32, 390, 30), self.ui, container=win)
        entry.set_text(self.session.name)
        entry.focus()
        UIButton(pygame.Rect(218, 68, 90, 28), "Save", self.ui, container=win,
                 object_id="#save_ok")
        UIButton(pygame.Rect(310, 68, 90, 28), "Cancel", self.ui, container=win,
                 object_id="#dialog_cancel")
        self.save_window, self.save_entry = win, entry

    def open_load_dialog(self) -> None:
        self.close_dialogs()
        items = paths.list_levels()
        self._load_items = {label: p for label, p in items}
        r = pygame.Rect(0, 0, 440, 380)
        r.center = self.scene_rect.center
        win = UIWindow(r, self.ui, window_display_title="Open a level", always_on_top=True)
        labels = list(self._load_items) or ["(no level files found)"]
        self.load_list = UISelectionList(pygame.Rect(8, 6, 410, 270), labels, self.ui,
                                         container=win)
        UIButton(pygame.Rect(236, 284, 90, 28), "Open", self.ui, container=win,
                 object_id="#load_ok")
        UIButton(pygame.Rect(328, 284, 90, 28), "Cancel", self.ui, container=win,
                 object_id="#dialog_cancel")
        self.load_window = win

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
        return ok

    def request_quit(self) -> None:
        self.running = False

    # ------------------------------------------------------------------ events
    def _text_focused(self) -> bool:
        return any(isinstance(e, UITextEntryLine) for e in self.ui.get_focus_set() or ())

    def handle(self, ev: pygame.event.Event) -> None:
        """Process one pygame event."""
        if ev.type == pygame.QUIT:
            self.request_quit()
            return
        if ev.type == pygame.VIDEORESIZE and not self.offscreen:
            self.resize((ev.w, ev.h))
            return
        consumed = self.ui.process_events(ev)
        t = ev.type
        if t == pygame_gui.UI_BUTTON_PRESSED:
            self._on_button(ev.ui_element)
        elif t == pygame_gui.UI_HORIZONTAL_SLIDER_MOVED:
            self._on_slider(ev.ui_element, ev.value)
        elif t == pygame_gui.UI_TEXT_ENTRY_FINISHED:
            self._on_entry(ev.ui_element, ev.text)
        elif t == pygame_gui.UI_SELECTION_LIST_DOUBLE_CLICKED_SELECTION:
            if ev.ui_element is self.load_list:
                self.do_load(ev.text)
        elif t == pygame_gui.UI_WINDOW_CLOSE:
            if ev.ui_element is self.save_window:
                self.save_window = self.save_entry = None
            elif ev.ui_element is self.load_window:
                self.load_window = self.load_list = None
        elif t == pygame.KEYDOWN:
            self._on_key(ev)
        elif t in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP, pygame.MOUSEMOTION,
                   pygame.MOUSEWHEEL):
            self._on_mouse(ev, consumed)

    def _on_button(self, el) -> None:
        b = self.buttons
        if el is b["play"]:
            self.toggle_pause()
        elif el is b["step"]:
            self.step()
        elif el is b["slow"]:
            self.session.cycle_slow()
        elif el is b["reset"]:
            self.reset()
        elif el is b["save"]:
            self.open_save_dialog()
        elif el is b["load"]:
            self.open_load_dialog()
        elif el is b["shot"]:
            self.screenshot()
        elif el is b["rec"]:
            self.toggle_clip()
        elif el is b["help"]:
            self.show_help = not self.show_help
        else:
            ids = getattr(el, "object_ids", None) or []
            if "#save_ok" in ids and self.save_entry is not None:
                self.do_save(self.save_entry.get_text())
            elif "#load_ok" in ids and self.load_list is not None:
                self.do_load(self.load_list.get_single_selection())
            elif "#dialog_cancel" in ids:
                self.close_dialogs()

    def _on_slider(self, el, pos: float) -> None:
        for row in self.rows:
            if row.slider is el:
                v = row.spec.from_slider(pos)
                if row.spec.live:
                    res = self.session.set_field(row.spec.path, v)
                    self._show_value(row, slider=not res.ok)
                    self.title.set_text(self._title_text())
                else:
                    self._pending[row.spec.path] = (v, time.perf_counter())
                    self._show_value(row, v, slider=False)
                return

    def _on_entry(self, el, text: str) -> None:
        if el is self.save_entry:
            self.do_save(text)
            return
        for row in self.rows:
            if row.entry is el:
                try:
                    v = row.spec.from_display(float(text))
                except ValueError:
                    self.session.say(f"{row.spec.label}: {text!r} is not a number; "
                                     f"allowed: {row.spec.allowed()}")
                    self._show_value(row)
                    return
                self._pending.pop(row.spec.path, None)
                self.set_field(row.spec.path, v)
                row.entry.unfocus()
                return

    def _on_key(self, ev: pygame.event.Event) -> None:
        k = ev.key
        mods = ev.mod
        ctrl = bool(mods & (pygame.KMOD_CTRL | pygame.KMOD_META))
        if k == pygame.K_ESCAPE:
            if self.show_help:
                self.show_help = False
            elif self.close_dialogs():
                pass
            elif self._text_focused():
                for e in list(self.ui.get_focus_set() or ()):
                    if isinstance(e, UITextEntryLine):
                        e.unfocus()
            else:
                self.request_quit()
            return
        if k == pygame.K_F1:
            self.show_help = not self.show_help
            return
        if k == pygame.K_F12:
            self.screenshot()
            return
        if self._text_focused() or self.save_window is not None:
            return
        if ctrl and k == pygame.K_s:
            self.open_save_dialog()
        elif (ctrl and k == pygame.K_o) or (k == pygame.K_l and not ctrl):
            self.open_load_dialog()
        elif ctrl:
            return
        elif k == pygame.K_SPACE:
            self.toggle_pause()
        elif k in (pygame.K_RIGHT, pygame.K_PERIOD, pygame.K_KP_PERIOD):
            self.step(physics=bool(mods & pygame.KMOD_SHIFT))
        elif k == pygame.K_s:
            self.session.cycle_slow()
        elif k == pygame.K_r:
            self.reset()
        elif k == pygame.K_f:
            self.fit_view()
        elif k == pygame.K_t:
            self.show_theory = not self.show_theory
        elif k == pygame.K_h:
            self.show_help = not self.show_help
        elif k == pygame.K_g:
            self.toggle_clip()

    def _over_ui(self, pos: tuple[int, int]) -> bool:
        if not self.scene_rect.collidepoint(pos):
            return True
        for win in (self.save_window, self.load_window):
            if win is not None and win.rect.collidepoint(pos):
                return True
        return False

    def _on_mouse(self, ev: pygame.event.Event, consumed: bool) -> None:
        cam = self.camera
        s = self.session
        if ev.type == pygame.MOUSEWHEEL:
            pos = pygame.mouse.get_pos()
            if not self._over_ui(pos) and ev.y:
                cam.zoom(1.15 ** max(-5, min(5, ev.y)), pos)
            return
        if ev.type == pygame.MOUSEBUTTONDOWN:
            if consumed or self._over_ui(ev.pos) or ev.button not in (1, 2, 3):
                return
            self._last_mouse = ev.pos
            if ev.button == 1 and s.grab(cam.to_world(*ev.pos), 14.0 / cam.scale):
                self._drag_mode = "link"
            else:
                self._drag_mode = "pan"
        elif ev.type == pygame.MOUSEMOTION:
            if self._drag_mode == "link":
                s.drag_to(cam.to_world(*ev.pos))
            elif self._drag_mode == "pan":
                cam.pan(ev.pos[0] - self._last_mouse[0], ev.pos[1] - self._last_mouse[1])
            self._last_mouse = ev.pos
        elif ev.type == pygame.MOUSEBUTTONUP:
            if self._drag_mode == "link":
                s.release()
            self._drag_mode = None

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
        """Apply debounced rebuilds and run the physics for one frame."""
        now = time.perf_counter()
        for path, (v, t0) in list(self._pending.items()):
            if now - t0 >= REBUILD_DELAY or self.offscreen:
                del self._pending[path]
                self.set_field(path, v)
        s = self.session
        if self.offscreen:
            if not s.paused:
                t0 = time.perf_counter()
                s.advance(s.speed_factor / self.fps)
                self.physics_time = time.perf_counter() - t0
                s.rtf = s.speed_factor
        else:
            budget = self.physics_budget()
            t0 = time.perf_counter()
            s.tick(wall_dt, budget)
            self.physics_time = time.perf_counter() - t0
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
        self._draw_overlay(ro)
        self._draw_right(ro)
        self.ui.draw_ui(scr)
        if self.show_help:
            self._draw_help()
        self.draw_time += 0.1 * ((time.perf_counter() - t0) - self.draw_time)

    def _draw_overlay(self, ro) -> None:
        s = self.session
        rect = self.scene_rect
        state = []
        if s.paused:
            state.append(("PAUSED", render.WARN))
        if s.speed_factor != 1:
            state.append((f"slow motion 1/{round(1 / s.speed_factor)}", render.SPEED_COL))
        if self.clip is not None and self.clip.recording:
            state.append((f"REC {self.clip.frames / self.clip.fps:4.1f} s", render.WARN))
        if s.dragging:
            state.append(("holding a link", render.VERTEX))
        f = render.font(20)
        x = rect.x + 10
        head = f"t = {s.sim.time:7.2f} s   links {s.sim.n_free} free"
        scr = self.screen
        scr.blit(f.render(head, True, render.TEXT), (x, 8))
        rtf_col = render.WARN if s.behind else render.DIM
        speed = (f"off-screen: {s.speed_factor / self.fps * 1e3:.1f} ms simulated per frame"
                 if self.offscreen else
                 f"real-time factor {s.rtf:4.2f}  ({self.fps_measured:4.1f} fps)")
        scr.blit(render.font(18).render(speed, True, rtf_col), (x, 28))
        xx = x
        for txt, col in state:
            surf = f.render(txt, True, col)
            scr.blit(surf, (xx, 48))
            xx += surf.get_width() + 14
        # status messages (newest last), shown for 6 s, wrapped to the view's width; why
        # the run stopped stays whole while paused (its head says what failed: a fold's
        # collapse runs to 8-10 rows), with the newest other message below it
        now = s.clock()
        small = render.font(17)
        msgs = [m for t, m in s.messages if now - t < 6.0][-3:]
        rows = status_rows(msgs, s.stopped if s.paused else None,
                           lambda m: render.wrap(small, m, rect.w - 20))
        y = rect.bottom - 44 - 18 * len(rows)
        for m in rows:
            img = small.render(m, True, render.TEXT)
            bg = pygame.Surface((img.get_width() + 8, img.get_height() + 2), pygame.SRCALPHA)
            bg.fill((0, 0, 0, 150))
            scr.blit(bg, (rect.x + 6, y - 1))
            scr.blit(img, (rect.x + 10, y))
            y += 18
        hint = render.font(16).render("H: help", True, render.DIM)
        scr.blit(hint, (rect.right - hint.get_width() - 8, 8))

    def _draw_right(self, ro) -> None:
        rect = self.right_rect
        scr = self.screen
        pygame.draw.rect(scr, render.BG, rect)
        s = self.session

        def num(v: float, fmt: str = ".4g") -> str:
            return "--" if v is None or not math.isfinite(v) else format(v, fmt)

        src = "measured" if ro.measured else "predicted"
        f3 = ".3f"
        lines = [
            (f"Readout ({src}); theory: catenary through the ends", render.DIM),
            (f"v  {num(ro.v, '.3f')} m/s     k = g/v^2  {num(ro.k)} 1/m", render.TEXT),
            (f"q  {num(ro.q)} 1/m     h  {num(ro.h, '.3f')} m", render.TEXT),
            (f"l  {num(ro.l, '.3f')} m     H  {num(ro.H, '.3f')} m", render.TEXT),
            (f"Tbar_0  {num(ro.T0_bar, f3)}  (theory {num(ro.T0_theory, f3)})", render.T0_COL),
            (f"Tbar_E  {num(ro.TE_bar, f3)}  (theory {num(ro.TE_theory, f3)})", render.TE_COL),
            (("off-screen render" if self.offscreen else f"real-time factor {s.rtf:.2f}")
             + f"    t = {s.sim.time:.2f} s", render.TEXT),
            ("steady" if ro.steady else "not steady (yet)",
             render.OK if ro.steady else render.WARN),
        ]
        if ro.note:
            lines += [(part, render.DIM) for part in textwrap.wrap(ro.note, 56)[:2]]
        y = render.text_block(scr, (rect.x + 8, 8), lines, size=18, line_h=19)
        top = y + 6
        key = (top, rect.size, id(s.sim))
        if (self._plot_cache is None or key != self._plot_key
                or self.frame - self._plot_frame >= PLOT_EVERY):
            self._plot_cache = self._render_plots(ro, pygame.Rect(0, 0, rect.w, rect.h - top))
            self._plot_key = key
            self._plot_frame = self.frame
        scr.blit(self._plot_cache, (rect.x, top))

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
        # 1. tension along the chain against height
        series = []
        ys = ro.tension_y
        if len(ys):
            series.append(render.Series(ys, ro.tension_bar, render.CHAIN, "measured",
                                        points=True))
        if math.isfinite(ro.q) and math.isfinite(ro.h):
            lo = min(float(ys.min()) if len(ys) else -ro.H, -ro.H)
            hi = max(float(ys.max()) if len(ys) else ro.h, ro.h)
            yy = np.linspace(lo, hi, 50)
            tb = 1.0 - ro.k / ro.q + ro.k * (yy - ro.h)
            series.append(render.Series(yy, tb, render.THEORY, "1 - k/q + k*y"))
        render.draw_plot(surf, r1, "Tbar along the chain", "height above launch (m)", series,
                         ylim=(-0.1, 1.05))
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
            ("speed_in", render.T0_COL, "pick-up 2 v_R"),
            ("speed_out", render.TE_COL, "fold 2 v_R")) if np.isfinite(hist[k][sel]).any()]
        n_sm = max(1, round(0.05 / s.recorder.cfg.sample_interval))  # rollers jitter
        rollers = [render.Series(t[sel], _smooth(hist[k][sel], n_sm), col, label, width=1)
                   for k, col, label in extra]
        sp += rollers
        sp.append(render.Series(np.array([t0, max(t1, t0 + 1)]), np.array([fs, fs]),
                                render.DIM, "feed", width=1))
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
        ts = [render.Series(t[sel], _smooth(hist["T0"][sel], n), render.T0_COL, "Tbar_0"),
              render.Series(t[sel], _smooth(hist["TE"][sel], n), render.TE_COL, "Tbar_E")]
        render.draw_plot(surf, r3, "end tensions (0.1 s mean)", "time (s)", ts,
                         xlim=(t0, max(t1, t0 + 1)), ylim=(-0.1, 1.05),
                         bands=((0.5, 1.0, render.T0_COL, "paper: Tbar_0 in (1/2, 1)"),
                                (0.0, 0.5, render.TE_COL, "paper: Tbar_E in [0, 1/2)")))
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
        w = 700
        h = 60 + 22 * len(KEYS)
        box = pygame.Rect(0, 0, w, h)
        box.center = (self.size[0] // 2, self.size[1] // 2)
        shade = pygame.Surface(box.size, pygame.SRCALPHA)
        shade.fill((10, 12, 18, 235))
        scr.blit(shade, box.topleft)
        pygame.draw.rect(scr, render.DIM, box, 1, 6)
        f = render.font(22)
        scr.blit(f.render("Keys and mouse  (H, F1 or Esc closes)", True, render.TEXT),
                 (box.x + 16, box.y + 14))
        small = render.font(19)
        y = box.y + 46
        for key, what in KEYS:
            scr.blit(small.render(key, True, render.SPEED_COL), (box.x + 20, y))
            scr.blit(small.render(what, True, render.TEXT), (box.x + 210, y))
            y += 22

    # ------------------------------------------------------------------ main loop
    def run_frame(self, wall_dt: float = 1.0 / 60.0) -> None:
        """One frame: queued events, physics, drawing, clip capture, flip."""
        t0 = time.perf_counter()
        self.physics_time = 0.0
        for ev in pygame.event.get():
            self.handle(ev)
        self.update(wall_dt)
        self.draw()
        if self.clip is not None:
            self.clip.offer(self.screen)
        if not self.offscreen:
            pygame.display.flip()
        self.frame += 1
        work = time.perf_counter() - t0 - self.physics_time
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
                    wall_dt = clock.tick(self.fps) / 1000.0
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
            p = s.save("autosave")
            if p is not None:
                notes.append(f"unsaved setup kept as {p}")
        for n in notes:
            print(f"chainfountain: {n}")
        pygame.display.quit()
        return notes
