"""Keys, mouse and the controls' events of the window (:class:`InputMixin`, part of
:class:`chainfountain.app.window.App`): each event becomes a command to the session or a
change of the view."""

from __future__ import annotations

import time

import pygame
import pygame_gui
from pygame_gui.elements import UITextEntryLine


class InputMixin:
    """Event handling of :class:`~chainfountain.app.window.App` (uses its state)."""

    def _text_focused(self) -> bool:
        """A text field has the keyboard (pygame_gui keeps an unfocused field in its focus
        set after Enter: only a field that says it is focused counts)."""
        return any(isinstance(e, UITextEntryLine) and e.is_focused
                   for e in self.ui.get_focus_set() or ())

    def release_keyboard(self) -> None:
        """Give the keys back to the scene: no text field keeps the focus (the manager
        unfocuses every element it drops from its focus set)."""
        self.ui.set_focus_set(None)

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
        elif t == pygame_gui.UI_SELECTION_LIST_NEW_SELECTION:
            if ev.ui_element is self.load_list:
                self.describe_choice(ev.text)
        elif t == pygame_gui.UI_WINDOW_CLOSE:
            if ev.ui_element is self.save_window:
                self.save_window = self.save_entry = None
            elif ev.ui_element is self.load_window:
                self.load_window = self.load_list = self.load_about = None
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
                    self.release_keyboard()
                    return
                self._pending.pop(row.spec.path, None)
                self.set_field(row.spec.path, v)
                self.release_keyboard()
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
                for row in self.rows:  # Esc drops the typed text: show the value again
                    if row.entry.is_focused:
                        self._show_value(row, slider=False)
                self.release_keyboard()
            else:
                self.request_quit()
            return
        if k == pygame.K_F1:
            self.show_help = not self.show_help
            return
        if k == pygame.K_F12:
            self.screenshot(with_plots=bool(mods & pygame.KMOD_SHIFT))
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
        elif k == pygame.K_i:
            self.show_about = self.about_pinned = not self.about_visible
        elif k == pygame.K_p:
            self.toggle_projector()
        elif k == pygame.K_e:
            self.expert = not self.expert
            self.session.say("readout: the paper's symbols" if self.expert else
                             "readout: plain words (the paper's symbols at the right)")
        elif k == pygame.K_g:
            self.toggle_clip(with_plots=bool(mods & pygame.KMOD_SHIFT))
        elif k == pygame.K_m:
            self.open_twin()

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
                self.follow = False  # the user's view now (F follows again)
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
                self.follow = False
            self._last_mouse = ev.pos
        elif ev.type == pygame.MOUSEBUTTONUP:
            if self._drag_mode == "link":
                s.release()
            self._drag_mode = None
