"""Keys, mouse and the controls' events of the window (:class:`InputMixin`, part of
:class:`chainfountain.app.window.App`): each event becomes a command to the session or a
change of the view. While the level picker is open it takes every key and click."""

from __future__ import annotations

import time

import pygame
import pygame_gui
from pygame_gui.elements import UITextEntryLine

from chainfountain.app.timebar import SPEEDS

TOGGLE_KEYS = {pygame.K_t: "theory", pygame.K_e: "expert", pygame.K_p: "projector",
               pygame.K_v: "plots", pygame.K_TAB: "panel", pygame.K_u: "ruler",
               pygame.K_w: "stopwatch"}


class InputMixin:
    """Event handling of :class:`~chainfountain.app.window.App` (uses its state)."""

    def _text_focused(self) -> bool:
        """A text field has the keyboard."""
        return any(isinstance(e, UITextEntryLine) and e.is_focused
                   for e in self.ui.get_focus_set() or ())

    def release_keyboard(self) -> None:
        """Give the keys back to the scene: no text field keeps the focus."""
        self.ui.set_focus_set(None)

    def handle(self, ev: pygame.event.Event) -> None:
        """Process one pygame event."""
        if ev.type == pygame.QUIT:
            self.running = False  # the window's close button: quit (changes are kept)
            return
        if ev.type == pygame.VIDEORESIZE and not self.offscreen:
            self.resize((ev.w, ev.h))
            return
        if self.picker is not None:
            self._on_picker(ev)
            return
        if ev.type == pygame.KEYDOWN and self.quit_asked is not None \
                and ev.key != pygame.K_ESCAPE:
            self.quit_asked = None  # any other key: stay
        consumed = self.ui.process_events(ev)
        t = ev.type
        if t == pygame_gui.UI_BUTTON_PRESSED:
            self._on_button(ev.ui_element)
        elif t == pygame_gui.UI_HORIZONTAL_SLIDER_MOVED:
            self._on_slider(ev.ui_element, ev.value)
        elif t == pygame_gui.UI_TEXT_ENTRY_FINISHED:
            self._on_entry(ev.ui_element, ev.text)
        elif t == pygame_gui.UI_WINDOW_CLOSE:
            if ev.ui_element is self.save_window:
                self.save_window = self.save_entry = None
        elif t == pygame.KEYDOWN:
            self._on_key(ev)
        elif t in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP, pygame.MOUSEMOTION,
                   pygame.MOUSEWHEEL):
            self._on_mouse(ev, consumed)

    # ------------------------------------------------------------------ the picker
    def _on_picker(self, ev: pygame.event.Event) -> None:
        """The picker is open: its keys and clicks, nothing reaches the scene."""
        p = self.picker
        what = None
        if ev.type == pygame.KEYDOWN:
            what = p.key(ev.key)
        elif ev.type == pygame.MOUSEBUTTONDOWN and ev.button == 1:
            what = p.click(ev.pos)
        elif ev.type == pygame.MOUSEWHEEL:
            p.wheel(ev.y)
        if what == "close":
            self.close_picker()
        elif what == "open":
            self.open_chosen()

    # ------------------------------------------------------------------ widgets
    def _on_button(self, el) -> None:
        b = self.buttons
        actions = {"levels": self.open_picker, "save": self.open_save_dialog,
                   "shot": self.screenshot, "rec": self.toggle_clip,
                   "plots": self.toggle_plots, "expert": self.toggle_expert,
                   "full": self.toggle_panel, "help": self._toggle_help}
        for key, act in actions.items():
            if el is b.get(key):
                act()
                return
        ids = getattr(el, "object_ids", None) or []
        if "#save_ok" in ids and self.save_entry is not None:
            self.do_save(self.save_entry.get_text())
        elif "#dialog_cancel" in ids:
            self.close_dialogs()

    def _toggle_help(self) -> None:
        self.show_help = not self.show_help

    def _on_slider(self, el, pos: float) -> None:
        for row in self.rows:
            if row.slider is el:
                v = row.spec.from_slider(pos)
                if row.spec.live:
                    res = self.session.set_field(row.spec.path, v)
                    self._show_value(row, slider=not res.ok)
                    self._set_title()
                else:
                    self._pending[row.spec.path] = (v, time.perf_counter())
                    self._show_value(row, v, slider=False)
                return

    def _on_entry(self, el, typed: str) -> None:
        if el is self.save_entry:
            self.do_save(typed)
            return
        for row in self.rows:
            if row.entry is el:
                try:
                    v = row.spec.from_display(float(typed))
                except ValueError:
                    self.session.say(f"{row.spec.label}: {typed!r} is not a number; "
                                     f"allowed: {row.spec.allowed()}")
                    self._show_value(row)
                    self.release_keyboard()
                    return
                self._pending.pop(row.spec.path, None)
                self.set_field(row.spec.path, v)
                self.release_keyboard()
                return

    # ------------------------------------------------------------------ keys
    def _on_key(self, ev: pygame.event.Event) -> None:
        k = ev.key
        mods = ev.mod
        ctrl = bool(mods & (pygame.KMOD_CTRL | pygame.KMOD_META))
        shift = bool(mods & pygame.KMOD_SHIFT)
        if k == pygame.K_ESCAPE:
            self._on_escape()
            return
        if k == pygame.K_F1:
            self._toggle_help()
            return
        if k == pygame.K_F12:
            self.screenshot(with_plots=shift)
            return
        if self._text_focused() or self.save_window is not None:
            return
        if ctrl and k == pygame.K_s:
            self.open_save_dialog()
        elif (ctrl and k == pygame.K_o) or (k == pygame.K_l and not ctrl):
            self.open_picker()
        elif ctrl:
            return
        elif k == pygame.K_SPACE:
            self.toggle_pause()
        elif k in (pygame.K_RIGHT, pygame.K_PERIOD, pygame.K_KP_PERIOD):
            self.step(physics=shift)
        elif k == pygame.K_s:
            self.session.cycle_slow()
        elif k == pygame.K_r:
            self.reset_all() if shift else self.reset()
        elif k == pygame.K_f:
            self.fit_view()
        elif k == pygame.K_h:
            self._toggle_help()
        elif k == pygame.K_i:
            self.show_about = self.about_pinned = not self.about_visible
        elif k == pygame.K_g:
            self.toggle_clip(with_plots=shift)
        elif k == pygame.K_m:
            self.open_twin()
        elif k in TOGGLE_KEYS:
            self._toggle(TOGGLE_KEYS[k])

    def _toggle(self, what: str) -> None:
        if what == "theory":
            self.show_theory = not self.show_theory
            self.session.say("the paper's curve: " + ("shown" if self.show_theory else
                                                      "hidden (T shows it)"))
        else:
            {"expert": self.toggle_expert, "projector": self.toggle_projector,
             "plots": self.toggle_plots, "panel": self.toggle_panel,
             "ruler": self.toggle_ruler, "stopwatch": self.toggle_stopwatch}[what]()

    def _on_escape(self) -> None:
        """Esc closes the help, a dialog or a field's typing; else it asks to quit (twice
        quits)."""
        if self.show_help:
            self.show_help = False
        elif self.close_dialogs():
            pass
        elif self._text_focused():
            for row in self.rows:  # Esc drops the typed text: show the value again
                if row.entry.is_focused:
                    self._show_value(row, slider=False)
            self.release_keyboard()
        else:
            self.request_quit()

    # ------------------------------------------------------------------ mouse
    def _over_ui(self, pos: tuple[int, int]) -> bool:
        if not self.scene_rect.collidepoint(pos):
            return True
        return self.save_window is not None and self.save_window.rect.collidepoint(pos)

    def _scene_control(self, pos: tuple[int, int]) -> bool:
        """A click on the scene's own controls (time, tools, the stopwatch) does what they
        do; whether it hit one."""
        hit = self.timebar.hit(pos)
        if hit is not None:
            if hit == "play":
                self.toggle_pause()
            elif hit == "step":
                self.step()
            elif hit == "restart":
                self.reset()
            elif hit == "reset_all":
                self.reset_all()
            elif hit in SPEEDS:
                self.set_speed(SPEEDS.index(hit))
            return True
        for b in self._tool_buttons():
            if b.hit(pos):
                self._toggle(b.key)
                return True
        sw = self.stopwatch.hit(pos)
        if sw is not None:
            if sw != "body":
                self.stopwatch.press(sw)
            return True
        return False

    def _on_mouse(self, ev: pygame.event.Event, consumed: bool) -> None:
        cam = self.camera
        s = self.session
        if ev.type == pygame.MOUSEWHEEL:
            pos = pygame.mouse.get_pos()
            if not self._over_ui(pos) and ev.y:
                cam.zoom(1.15 ** max(-5, min(5, ev.y)), pos)
                self.follow = False  # the user's view now (F follows again)
            return
        if ev.type == pygame.MOUSEBUTTONDOWN:
            if consumed or self._over_ui(ev.pos) or ev.button not in (1, 2, 3):
                return
            if ev.button == 1 and self._scene_control(ev.pos):
                return
            self._last_mouse = ev.pos
            if ev.button == 1 and self.ruler.grab(cam, ev.pos):
                self._drag_mode = "ruler"
            elif ev.button == 1 and s.grab(cam.to_world(*ev.pos), 14.0 / cam.scale):
                self._drag_mode = "link"
            else:
                self._drag_mode = "pan"
        elif ev.type == pygame.MOUSEMOTION:
            if self._drag_mode == "link":
                s.drag_to(cam.to_world(*ev.pos))
            elif self._drag_mode == "ruler":
                self.ruler.drag(cam, ev.pos)
            elif self._drag_mode == "pan":
                cam.pan(ev.pos[0] - self._last_mouse[0], ev.pos[1] - self._last_mouse[1])
                self.follow = False
            self._last_mouse = ev.pos
        elif ev.type == pygame.MOUSEBUTTONUP:
            if self._drag_mode == "link":
                s.release()
            elif self._drag_mode == "ruler":
                self.ruler.release()
            self._drag_mode = None
