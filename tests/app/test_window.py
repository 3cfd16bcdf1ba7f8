"""The window under the SDL dummy driver: scripted events change the model as asked."""

from __future__ import annotations

import os

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import numpy as np  # noqa: E402
import pygame  # noqa: E402
import pygame_gui  # noqa: E402
import pytest  # noqa: E402

from chainfountain.app import palette, panel, text  # noqa: E402
from chainfountain.app.draw import ABOUT_SECONDS, STOP_ROWS, status_rows  # noqa: E402
from chainfountain.app.scene_view import scene_bounds  # noqa: E402
from chainfountain.app.session import Session, paused_message  # noqa: E402
from chainfountain.app.window import App  # noqa: E402
from chainfountain.level import io  # noqa: E402
from chainfountain.sim import placement
from chainfountain.sim.config import SimConfig  # noqa: E402
from tests import shipped  # noqa: E402


def small_level() -> io.Level:
    cfg = SimConfig()
    cfg.feed.drop = 0.5
    cfg.feed.speed = 4.0
    cfg.chain.link_length = 0.03
    level = io.make_level("small", "test level", cfg)
    level.meta.controls = "feed.speed, chain.link_length"
    return level


@pytest.fixture
def app(tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    a = App(Session(small_level()), size=(1280, 760), offscreen=True)
    yield a
    a.finish()


def key(app: App, k: int, mod: int = 0, unicode: str = "") -> None:
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=k, mod=mod, unicode=unicode,
                                         scancode=0))
    pygame.event.post(pygame.event.Event(pygame.KEYUP, key=k, mod=mod, unicode=unicode,
                                         scancode=0))
    app.run_frame()


def click(app: App, pos: tuple[int, int], button: int = 1) -> None:
    pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=pos, rel=(0, 0),
                                         buttons=(0, 0, 0)))
    app.run_frame()
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=pos, button=button))
    app.run_frame()
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONUP, pos=pos, button=button))
    app.run_frame()
    app.run_frame()  # the GUI's own events (button pressed) arrive one frame later


def test_pause_step_reset_keys(app):
    app.run_frame()
    assert app.session.sim.time > 0
    key(app, pygame.K_SPACE)
    assert app.session.paused
    t = app.session.sim.time
    app.run_frame()
    assert app.session.sim.time == t
    key(app, pygame.K_RIGHT)
    assert app.session.sim.time == pytest.approx(t + 1 / 60, abs=app.session.sim.dt)
    key(app, pygame.K_PERIOD)
    assert app.session.sim.time == pytest.approx(t + 2 / 60, abs=2 * app.session.sim.dt)
    steps = app.session.sim.steps
    key(app, pygame.K_RIGHT, mod=pygame.KMOD_SHIFT)
    assert app.session.sim.steps == steps + 1
    key(app, pygame.K_r)
    assert app.session.sim.time == 0
    key(app, pygame.K_s)
    assert app.session.speed_factor == 0.5
    key(app, pygame.K_h)
    assert app.show_help
    key(app, pygame.K_ESCAPE)  # closes the help first
    assert not app.show_help and app.running


def test_the_time_controls_do_what_their_keys_do(app):
    """PhET's controls at the foot of the scene: the big button pauses and plays, the step
    button steps, the speed choice sets the speed, restart restarts."""
    bar = app.timebar
    centre = {b.key: b.centre for b in bar.round}
    app.run_frame()
    click(app, centre["play"])
    assert app.session.paused
    t = app.session.sim.time
    click(app, centre["step"])
    assert app.session.sim.time == pytest.approx(t + 1 / 60, abs=app.session.sim.dt)
    slower = next(b for b in bar.speeds if b.key == "slower")
    click(app, slower.rect.center)
    assert app.session.speed_factor == 0.25
    click(app, next(b for b in bar.speeds if b.key == "normal").rect.center)
    assert app.session.speed_factor == 1.0
    click(app, centre["restart"])
    assert app.session.sim.time == 0.0
    click(app, centre["play"])
    assert not app.session.paused


def test_slider_arrow_moves_the_live_value_one_round_step(app):
    row = app._row("feed.speed")
    before = app.session.value("feed.speed")
    right = row.slider.right_button
    for _ in range(2):
        click(app, right.rect.center)
    app.run_frame()  # the slider's own event (moved) arrives a frame after the press
    after = app.session.value("feed.speed")
    step = row.spec.ladder()[2] - row.spec.ladder()[1]
    assert after == pytest.approx(before + 2 * step)
    assert app.session.sim.feed.speed == after
    assert float(row.entry.get_text()) == pytest.approx(after, rel=1e-3)


def test_entry_clamps_and_rebuilds(app):
    row = app._row("chain.link_length")
    sim = app.session.sim
    pygame.event.post(pygame.event.Event(pygame_gui.UI_TEXT_ENTRY_FINISHED,
                                         ui_element=row.entry, text="0.025"))
    app.run_frame()
    assert app.session.sim is not sim and app.session.value("chain.link_length") == 0.025
    # outside the schema: clamped to the limit, then to what the window runs at real time,
    # and said so; the field shows the value set
    row = app._row("feed.speed")
    pygame.event.post(pygame.event.Event(pygame_gui.UI_TEXT_ENTRY_FINISHED,
                                         ui_element=row.entry, text="1e6"))
    app.run_frame()
    v = app.session.value("feed.speed")
    assert 4.0 < v < 30.0  # above its 4 m/s, below the schema's 30
    assert row.entry.get_text() == app.session.spec("feed.speed").fmt(v)
    assert any("outside the allowed range" in m and "too slow for the window" in m
               for _, m in app.session.messages)


def test_save_and_load_through_the_dialog_and_the_picker(app, tmp_path):
    app.session.set_field("feed.speed", 4.4)
    key(app, pygame.K_s, mod=pygame.KMOD_CTRL)
    assert app.save_window is not None
    app.save_entry.set_text("classroom demo")
    ok = [b for b in app.save_window.get_container().elements
          if "#save_ok" in getattr(b, "object_ids", [])][0]
    click(app, ok.rect.center)
    path = tmp_path / "home" / "levels" / "classroom_demo.toml"
    assert path.exists() and app.save_window is None
    saved = io.load(path)
    assert saved.sim.feed.speed == 4.4 and saved.meta.controls == app.session.opened.meta.controls
    # change the setup, then open the saved level back through the picker
    app.session.set_field("feed.speed", 5.0)
    key(app, pygame.K_l)
    assert app.picker is not None
    rows = [e.path for e in app.picker.rows]
    app.picker.sel = rows.index(path)
    key(app, pygame.K_RETURN)
    assert app.picker is None and app.session.value("feed.speed") == 4.4
    assert app.session.name == "classroom demo"
    # the changes the picker replaced were kept, and the window said so
    kept = list((tmp_path / "home" / "levels").glob("autosave-*.toml"))
    assert len(kept) == 1 and io.load(kept[0]).sim.feed.speed == 5.0
    assert any(kept[0].name in m for _, m in app.session.messages)


def test_screenshot_clip_zoom_pan_drag(app, tmp_path):
    for _ in range(10):
        app.run_frame()
    key(app, pygame.K_v)  # the graphs, for the picture with them
    key(app, pygame.K_F12)  # the scene alone, full resolution
    key(app, pygame.K_F12, mod=pygame.KMOD_SHIFT)  # the scene and the graphs
    app.saver.wait()
    shots = sorted((tmp_path / "home" / "captures").glob("*.png"), key=lambda p: p.name)
    assert len(shots) == 2 and all(p.stat().st_size > 10_000 for p in shots)
    sizes = sorted(pygame.image.load(str(p)).get_size() for p in shots)
    assert sizes == sorted([app.scene_rect.size, app.scene_rect.union(app.plots_rect).size])
    key(app, pygame.K_g)
    assert app.clip is not None and app.clip.crop == app.scene_rect
    t0 = app.session.sim.time
    for _ in range(30):
        app.run_frame()
    clip = app.clip
    assert clip.frames == int((app.session.sim.time - t0) * clip.fps + 1e-6) + 1
    key(app, pygame.K_g)
    assert app.clip is None and app.finishing_clips
    app.finishing_clips[0].wait()
    clips = [p for p in (tmp_path / "home" / "captures").iterdir()
             if p.suffix in (".gif", ".mp4")]
    assert len(clips) == 1 and clips[0].stat().st_size > 1000
    cam = app.camera
    scale = cam.scale
    pos = app.scene_rect.center
    pygame.mouse.set_pos(pos)
    pygame.event.post(pygame.event.Event(pygame.MOUSEWHEEL, x=0, y=2, flipped=False))
    app.run_frame()
    assert cam.scale > scale or pygame.mouse.get_pos() != pos  # dummy driver may ignore set_pos
    empty = (app.scene_rect.right - 20, app.scene_rect.centery)
    cx = cam.cx
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=empty, button=3))
    pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=(empty[0] - 50, empty[1]),
                                         rel=(-50, 0), buttons=(0, 0, 1)))
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONUP, pos=(empty[0] - 50, empty[1]),
                                         button=3))
    app.run_frame()
    assert cam.cx > cx
    s = app.session
    p = s.sim.state().position[s.sim.n_free // 2]
    sp = tuple(int(v) for v in cam.to_screen(p)[0])
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=sp, button=1))
    app.run_frame()
    assert s.dragging
    pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=(sp[0] + 40, sp[1] + 40),
                                         rel=(40, 40), buttons=(1, 0, 0)))
    app.run_frame()
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONUP, pos=(sp[0] + 40, sp[1] + 40),
                                         button=1))
    app.run_frame()
    assert not s.dragging


def test_offscreen_screenshot_shows_the_chain(tmp_path, monkeypatch):
    from chainfountain import cli

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    lvl = tmp_path / "small.toml"
    io.save(small_level(), lvl)
    shot = tmp_path / "shot.png"
    assert cli.main(["play", str(lvl), "--frames", "20", "--screenshot", str(shot)]) == 0
    img = pygame.image.load(str(shot))
    assert img.get_size() == (1280, 760)
    arr = pygame.surfarray.array3d(img).astype(int)
    assert arr.std() > 10  # not blank
    scene = arr[:890, :, :]  # the scene: the window left of the panel
    assert (abs(scene - palette.CHAIN).sum(axis=2) < 60).sum() > 500


def test_rollers_carts_and_their_controls(tmp_path, monkeypatch):
    """A fed level's rollers and carts are drawn and get controls generated from the
    schema (the expert view shows every field)."""
    import math

    from chainfountain.sim.config import CartConfig, RollerConfig

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    lvl = small_level()
    lvl.sim.feed.floor = "solid"
    lvl.sim.rollers = (RollerConfig(x=0.8, y=-0.3, radius=0.05, angular_speed=3.0),)
    lvl.sim.carts = (CartConfig(x=0.4, y=-0.4, incline=math.radians(20), track_length=0.4),)
    app = App(Session(lvl), offscreen=True)
    try:
        key(app, pygame.K_e)
        paths = [r.spec.path for r in app.rows]
        assert {"carts[0].mass", "carts[0].incline", "rollers[0].angular_speed"} <= set(paths)
        for _ in range(5):
            app.run_frame()
        row = app._row("rollers[0].angular_speed")
        pygame.event.post(pygame.event.Event(pygame_gui.UI_TEXT_ENTRY_FINISHED,
                                             ui_element=row.entry, text="-2"))
        app.run_frame()
        assert app.session.value("rollers[0].angular_speed") == -2.0
        row = app._row("carts[0].mass")  # shown in grams
        pygame.event.post(pygame.event.Event(pygame_gui.UI_TEXT_ENTRY_FINISHED,
                                             ui_element=row.entry, text="300"))
        app.run_frame()
        assert app.session.sim.config.carts[0].mass == 0.3
        boxes = app.scene_view.machine.draw(app.screen, app.camera, app.session.sim).boxes
        assert len(boxes) >= 2  # the roller's wheel and the cart
    finally:
        app.finish()


def test_esc_asks_before_it_quits_and_the_changes_are_kept(tmp_path, monkeypatch):
    """One Esc asks (any other key stays); a second quits, keeping the clip and the
    changed setup."""
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    app = App(Session(small_level()), offscreen=True)
    app.offscreen = False  # behave like a window on quit (autosave) ...
    app.session.set_field("feed.speed", 4.3)
    key(app, pygame.K_g)
    for _ in range(3):
        app.run_frame()
    key(app, pygame.K_ESCAPE)
    assert app.running and "Press Esc again to quit" in app.quit_prompt
    assert "kept as an autosave" in app.quit_prompt
    key(app, pygame.K_SPACE)  # any other key: stay
    assert app.running and app.quit_prompt is None
    key(app, pygame.K_ESCAPE)
    key(app, pygame.K_ESCAPE)
    assert not app.running
    notes = app.finish()
    assert any(n.startswith("clip saved") for n in notes), notes
    saved = list((tmp_path / "home" / "levels").glob("autosave-*.toml"))
    assert len(saved) == 1 and io.load(saved[0]).sim.feed.speed == 4.3


def test_each_quit_keeps_its_own_autosave_up_to_ten(tmp_path):
    from chainfountain.app.window import AUTOSAVES_KEPT, _prune_autosaves

    for k in range(AUTOSAVES_KEPT + 3):
        (tmp_path / f"autosave-20261124-1200{k:02d}.toml").write_text("x")
    (tmp_path / "mine.toml").write_text("x")
    _prune_autosaves(tmp_path)
    left = sorted(p.name for p in tmp_path.glob("autosave-*.toml"))
    assert len(left) == AUTOSAVES_KEPT and left[0] == "autosave-20261124-120003.toml"
    assert (tmp_path / "mine.toml").exists()


def test_status_keeps_a_long_stop_reason_from_its_head():
    import textwrap

    reason = "t = 15.53 s: the folding roller lost the chain. " + "Why it did. " * 80 + "End."
    msgs = [paused_message(reason), "running", "paused"]

    def wrap(m: str) -> list[str]:
        return textwrap.wrap(m, 70)

    rows = status_rows(msgs, reason, wrap)
    assert rows[0].startswith("t = 15.53 s: the folding roller lost the chain")
    assert len(wrap(reason)) > STOP_ROWS and len(rows) == STOP_ROWS + 1
    assert rows[-1] == "paused"
    short = "t = 1.00 s: the table is used up."
    rows = status_rows([paused_message(short)], short, wrap)
    assert rows == ["t = 1.00 s: the table is used up; paused: press R to start again"]
    rows = status_rows(["a " * 200, "b"], None, wrap)
    assert len(rows) == 4 and rows[-1] == "b"


def _assert_reaction_plot(app: App) -> None:
    """The third graph is the lower plate's reaction, growing, drawn measured (chain
    colour) beside the paper's rate (theory colour)."""
    hist = app.session.history.arrays()
    r = hist["reaction"][np.isfinite(hist["reaction"])]
    assert len(r) > 10 and r[-5:].mean() > 2.0 * r[:5].mean() > 0.0
    surf = app._render_plots(app.session.readout(), pygame.Rect(0, 0, 1200, 300))
    third = pygame.surfarray.array3d(surf).astype(int)[2 * 1200 // 3:, :, :]
    for colour in (palette.CHAIN, palette.THEORY):
        assert (abs(third - colour).sum(axis=2) < 30).sum() > 40, colour


def test_open_arrangement_plots_the_plate_reaction(level, tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    app = App(Session(level("apparatus_open")), offscreen=True)
    try:
        for _ in range(40):  # 0.67 s: 16 samples at the window's 25 a second
            app.run_frame()
        _assert_reaction_plot(app)
    finally:
        app.finish()
    s = Session(level("apparatus_special"))
    s.advance(0.05)
    assert len(s.history.t) > 0 and not np.isfinite(s.history.arrays()["reaction"]).any()


def test_ideal_open_plots_the_plate_reaction_and_draws_the_chain_sliding_away(level, tmp_path,
                                                                              monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    lvl = level("ideal_open")
    lvl.sim.initial.mode, lvl.sim.feed.starter = "catenary", 0.0  # landed from the start
    app = App(Session(lvl), offscreen=True)
    try:
        for _ in range(30):
            app.run_frame()
        _assert_reaction_plot(app)
        key(app, pygame.K_e)
        assert any(row.spec.path == "feed.turn_drop" for row in app.rows)
        path, slid = placement.slide(app.session.sim)
        app.draw()
        x0, y_plate = app.camera.point(float(path[-2, 0]) + 0.02, float(path[-1, 1]))
        row = pygame.surfarray.array3d(app.screen)[x0:x0 + 40, y_plate - 5:y_plate + 6]
        assert (abs(row.astype(int) - palette.CHAIN).sum(axis=2) < 40).sum() > 20
    finally:
        app.finish()


def _type_into(app: App, row, typed: str, end: int) -> None:
    """Click a field, replace its text by ``typed`` as a person types, end with ``end``."""
    click(app, row.entry.rect.center)
    assert app._text_focused()
    for _ in range(12):
        key(app, pygame.K_BACKSPACE)
    for ch in typed:
        pygame.event.post(pygame.event.Event(pygame.TEXTINPUT, text=ch))
        app.run_frame()
    key(app, end, unicode="\r" if end == pygame.K_RETURN else "")
    app.run_frame()


def _last(app: App) -> str:
    return app.session.messages[-1][1] if app.session.messages else ""


def _press_every_key(app: App) -> tuple[list[str], set[str]]:
    """Press every key of the help (:data:`chainfountain.app.draw.KEYS`) and check that each
    acted; returns the keys that did not, and the help rows pressed."""
    s = app.session
    fails: list[str] = []
    pressed: set[str] = set()

    def chk(row: str, name: str, ok: bool) -> None:
        pressed.add(row)
        if not ok:
            fails.append(name)

    p = s.paused
    key(app, pygame.K_SPACE)
    chk("Space", "Space", s.paused != p)
    if not s.paused:
        key(app, pygame.K_SPACE)
    t = s.sim.time
    key(app, pygame.K_RIGHT)
    chk("Right  or  .", "Right", s.sim.time > t)
    t = s.sim.time
    key(app, pygame.K_PERIOD, unicode=".")
    chk("Right  or  .", ".", s.sim.time > t)
    t = s.sim.time
    key(app, pygame.K_RIGHT, mod=pygame.KMOD_SHIFT)
    chk("Right  or  .", "Shift+Right", abs(s.sim.time - t - s.sim.dt) < 1e-9)
    i = s.slow_index
    key(app, pygame.K_s, unicode="s")
    chk("S", "S", s.slow_index != i)
    key(app, pygame.K_r, unicode="r")
    chk("R", "R", s.sim.time == 0.0)
    s.set_field("feed.speed", 4.5)
    key(app, pygame.K_r, mod=pygame.KMOD_SHIFT)
    chk("Shift+R", "Shift+R", s.value("feed.speed") == s.opened.sim.feed.speed and not s.dirty)
    app.camera.zoom(3.0, app.scene_rect.center)
    app.follow = False
    scale = app.camera.scale
    key(app, pygame.K_f, unicode="f")
    chk("F", "F", app.follow and app.camera.scale != scale)
    theory = app.show_theory
    key(app, pygame.K_t, unicode="t")
    chk("T", "T", app.show_theory != theory)
    key(app, pygame.K_t, unicode="t")
    chk("Wheel, drag", "(mouse: test_screenshot_clip_zoom_pan_drag)", True)
    key(app, pygame.K_u, unicode="u")
    ruler = app.ruler.on
    key(app, pygame.K_w, unicode="w")
    chk("U, W", "U, W", ruler and app.stopwatch.on)
    key(app, pygame.K_u, unicode="u")
    key(app, pygame.K_w, unicode="w")
    key(app, pygame.K_l, unicode="l")
    chk("L  or  Ctrl+O", "L", app.picker is not None)
    key(app, pygame.K_ESCAPE)
    chk("Esc", "Esc closes the picker", app.picker is None and app.running
        and app.quit_prompt is None)
    key(app, pygame.K_o, mod=pygame.KMOD_CTRL)
    chk("L  or  Ctrl+O", "Ctrl+O", app.picker is not None)
    key(app, pygame.K_ESCAPE)
    key(app, pygame.K_m, unicode="m")  # this level has no twin: it says so
    chk("M", "M", "no twin" in _last(app))
    key(app, pygame.K_s, mod=pygame.KMOD_CTRL)
    chk("Ctrl+S", "Ctrl+S", app.save_window is not None)
    key(app, pygame.K_ESCAPE)
    chk("Esc", "Esc closes the save prompt", app.save_window is None and app.running)
    before = app.last_capture
    key(app, pygame.K_F12)
    app.saver.wait()
    key(app, pygame.K_g, unicode="g")
    recording = app.clip is not None
    key(app, pygame.K_g, unicode="g")
    chk("F12, G", "F12, G", app.last_capture is not None and app.last_capture != before
        and recording and app.clip is None)
    about = app.about_visible
    key(app, pygame.K_i, unicode="i")
    chk("I", "I", app.about_visible != about)
    key(app, pygame.K_e, unicode="e")
    chk("E", "E", app.expert)
    key(app, pygame.K_e, unicode="e")
    plots = app.plots_rect is not None
    key(app, pygame.K_v, unicode="v")
    chk("V", "V", (app.plots_rect is not None) != plots)
    key(app, pygame.K_v, unicode="v")
    key(app, pygame.K_TAB)
    chk("Tab", "Tab", app.panel_rect is None)
    key(app, pygame.K_TAB)
    key(app, pygame.K_p, unicode="p")
    chk("P", "P", app.projector)
    key(app, pygame.K_p, unicode="p")
    key(app, pygame.K_h, unicode="h")
    chk("H  or  F1", "H", app.show_help)
    key(app, pygame.K_ESCAPE)
    chk("Esc", "Esc closes the help", not app.show_help and app.running)
    key(app, pygame.K_F1)
    chk("H  or  F1", "F1", app.show_help)
    key(app, pygame.K_F1)
    return fails, pressed


@pytest.mark.parametrize("end", [pytest.param(pygame.K_RETURN, id="enter", marks=pytest.mark.slow),
                                 pytest.param(pygame.K_ESCAPE, id="esc")])
def test_every_key_works_after_typing_in_any_field(app, end):
    """Enter or Esc in a field gives the keys back to the scene: after each field of the
    panel is typed into, every key of the help acts at once, and Esc (twice) quits."""
    from chainfountain.app.draw import KEYS

    for row in app.rows:
        _type_into(app, row, row.entry.get_text() or "1", end)
        assert not app._text_focused(), row.spec.path
        fails, pressed = _press_every_key(app)
        assert not fails, (row.spec.path, fails)
    assert pressed == {k for k, _ in KEYS}  # every key of the help was pressed
    assert app.running
    key(app, pygame.K_ESCAPE)
    key(app, pygame.K_ESCAPE)
    assert not app.running


def test_esc_in_a_field_drops_what_was_typed_and_shows_the_value_again(app):
    row = next(r for r in app.rows if r.spec.path == "feed.speed")
    before = app.session.value("feed.speed")
    shown = row.entry.get_text()
    _type_into(app, row, "3.3", pygame.K_ESCAPE)
    assert app.session.value("feed.speed") == before
    assert row.entry.get_text() == shown


def test_a_run_that_stopped_itself_says_press_r(app, monkeypatch):
    from chainfountain.errors import UserError

    def used_up() -> None:
        raise UserError("t = 0.10 s: the table is used up.")

    monkeypatch.setattr(app.session.sim, "step", used_up)
    app.run_frame()
    s = app.session
    assert s.paused and s.stopped
    key(app, pygame.K_SPACE)  # Space cannot run a stopped run: it says what to do
    assert s.paused and "press R to start again" in s.messages[-1][1]
    from chainfountain.app import draw

    real, shown = draw.readout_rows, []
    monkeypatch.setattr(draw, "readout_rows",
                        lambda *a, **k: shown.append(real(*a, **k)) or shown[-1])
    app.run_frame()
    texts = [r.text for r in shown[-1]]
    assert "the run has stopped (R starts it again)" in texts
    assert not any("steady" in t for t in texts)
    key(app, pygame.K_r)
    app.run_frame()
    assert s.stopped is None and not s.paused and s.sim.time > 0


def _scene_in_view(app: App) -> bool:
    x0, y0, x1, y1 = scene_bounds(app.session.sim, None)
    (ax, ay), (bx, by) = app.camera.to_screen(np.array([[x0, y0], [x1, y1]]))
    r = app.scene_rect.inflate(4, 4)
    return r.collidepoint(ax, ay) and r.collidepoint(bx, by)


def test_view_follows_the_fountain_until_the_user_pans(app):
    from chainfountain.app.window import FOLLOW_EVERY

    app.run_frame()
    app.camera.fit(10.0, 10.0, 10.1, 10.1)
    assert not _scene_in_view(app)
    for _ in range(FOLLOW_EVERY + 1):
        app.run_frame()
    assert app.follow and _scene_in_view(app)
    start = (app.scene_rect.right - 20, app.scene_rect.centery)
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=start, button=3))
    pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=(start[0] - 300, start[1]),
                                         rel=(-300, 0), buttons=(0, 0, 1)))
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONUP, pos=(start[0] - 300, start[1]),
                                         button=3))
    app.run_frame()
    assert not app.follow
    app.camera.fit(10.0, 10.0, 10.1, 10.1)
    for _ in range(FOLLOW_EVERY + 1):
        app.run_frame()
    assert not _scene_in_view(app)
    key(app, pygame.K_f)
    assert app.follow and _scene_in_view(app)


def test_m_on_a_level_without_twin_says_so(app):
    key(app, pygame.K_m)
    assert app.session.level.meta.name == "small"
    assert "no twin" in app.session.messages[-1][1]


def test_the_level_says_what_to_watch_until_i_hides_it(app, tmp_path):
    assert app.about_visible
    app.run_frame()
    key(app, pygame.K_i)
    assert not app.about_visible
    key(app, pygame.K_i)
    assert app.about_visible
    app.session.sim.advance(ABOUT_SECONDS)
    assert app.about_visible  # pinned by I
    key(app, pygame.K_i)
    assert not app.about_visible
    path = tmp_path / "other.toml"
    io.save(io.make_level("other", "Watch the chain climb.", small_level().sim), path)
    assert app.load_path(path) and app.about_visible
    app.run_frame()
    app.session.sim.advance(ABOUT_SECONDS)
    assert not app.about_visible


@pytest.mark.slow
def test_the_scene_opens_below_the_card_and_takes_the_view_when_it_goes(level, tmp_path,
                                                                        monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    a = App(Session(level("beaker")), size=(1280, 760), offscreen=True)
    try:
        box = a.about_box()
        x0, y0, x1, y1 = scene_bounds(a.session.sim, a.session.readout(), a.camera.scale)
        (_, top), (_, bottom) = a.camera.to_screen(np.array([[x0, y1], [x1, y0]]))
        assert a.about_visible and top > box.bottom and bottom <= a.timebar.rect.top + 1
        scale = a.camera.scale
        a.session.sim.advance(ABOUT_SECONDS)
        a.run_frame()
        assert not a.about_visible and a.camera.scale > 1.05 * scale
    finally:
        a.finish()


def test_e_switches_between_the_student_and_the_expert_view(app):
    """A class first: the level's sliders in plain words; E shows every field with the
    paper's symbols and whether it applies live, and the graphs."""
    student = [r.spec.path for r in app.rows]
    assert student == ["feed.speed", "chain.link_length"] and not app.expert
    assert app.plots_rect is None
    key(app, pygame.K_e)
    assert app.expert and "paper's symbols" in app.session.messages[-1][1]
    expert = [r.spec.path for r in app.rows]
    assert set(student) < set(expert) and app.plots_rect is not None
    assert "[live]" in app._row("feed.speed").label.text
    key(app, pygame.K_e)
    assert not app.expert and [r.spec.path for r in app.rows] == student


def test_rendered_text_is_kept_and_bounded(app):
    f = text.font(18)
    first = text.text(f, "speed 3.00 m/s", True, palette.TEXT)
    assert text.text(f, "speed 3.00 m/s", True, palette.TEXT) is first
    assert text.text(f, "speed 3.00 m/s", True, palette.DIM) is not first
    for i in range(text.TEXT_CACHE + 50):
        text.text(f, f"t = {i * 0.01:7.2f} s", True, palette.TEXT)
        text.wrap(f, f"a long paragraph number {i} " * 4, 120)
    assert len(text._TEXTS) <= text.TEXT_CACHE
    assert len(text._WRAPS) <= text.TEXT_CACHE
    assert text.wrap(f, "one two three", 10_000) == ["one two three"]


def test_a_window_steps_its_physics_while_the_frame_goes_to_the_screen(tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    a = App(Session(small_level()), size=(1280, 760), offscreen=False)
    try:
        t0 = a.session.sim.time
        for _ in range(5):
            a.run_frame(1.0 / 60.0)
        assert a.session.sim.time > t0 and a.physics_time > 0.0

        def broken(*args, **kwargs):
            raise RuntimeError("broken tick")

        monkeypatch.setattr(a.session, "tick", broken)
        with pytest.raises(RuntimeError, match="broken tick"):
            a.run_frame(1.0 / 60.0)
    finally:
        a.finish()


def test_a_window_draws_fewer_frames_when_its_physics_needs_the_core(tmp_path, monkeypatch):
    from chainfountain.app.window import HEADROOM, MIN_FPS

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    a = App(Session(small_level()), size=(1280, 760), offscreen=False, fps=60)
    try:
        for _ in range(5):
            a.run_frame(1.0 / 60.0)
        assert a.physics_cost > 0.0
        a.overhead, a.draw_time = 0.005, 0.004
        a.physics_cost = 0.2
        assert a.target_fps() == 60.0
        a.physics_cost = HEADROOM - 40 * 0.005
        assert a.target_fps() == pytest.approx(40.0)
        a.physics_cost = 0.95
        assert a.target_fps() == MIN_FPS
        # and never so many frames that drawing takes more than a third of each
        a.physics_cost, a.draw_time = 0.2, 0.008
        assert a.target_fps() == pytest.approx(1.0 / (3 * 0.008))
        a.session.paused = True
        assert a.target_fps() == 60.0
    finally:
        a.finish()


@pytest.mark.parametrize("preset, want", [(None, "0"), ("1", "1")])
def test_the_window_uses_the_displays_framebuffer_unless_told_otherwise(
        tmp_path, monkeypatch, preset, want) -> None:
    from chainfountain.app.window import FRAMEBUFFER_HINT

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    monkeypatch.delenv(FRAMEBUFFER_HINT, raising=False)
    if preset is not None:
        monkeypatch.setenv(FRAMEBUFFER_HINT, preset)
    a = App(Session(small_level()), size=(720, 540), offscreen=True)
    try:
        assert os.environ[FRAMEBUFFER_HINT] == want
    finally:
        a.finish()


def test_a_plot_title_never_runs_under_its_legend(app) -> None:
    f = text.font(16)
    long = "pull at the ends, and a great deal more said about it than fits"
    short = text.fit_text(f, long, 200)
    assert short.endswith("...") and f.size(short)[0] <= 200
    assert text.fit_text(f, "speed (m/s)", 200) == "speed (m/s)"


def test_a_refusal_stays_on_screen_as_long_as_a_class_takes_to_read_it(tmp_path, monkeypatch):
    """A typed value the level check refuses (a gripped fold's drop beyond its start region)
    is said in one message naming the field, the value and what is allowed, held for its
    words at a class's reading pace (3 words a second, at least 6 s, at most 20 s); a
    short message keeps the 6 s."""
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    now = [0.0]
    s = Session(io.load(shipped.path("apparatus_fold_gripped")), clock=lambda: now[0])
    a = App(s, size=(1280, 760), offscreen=True)
    try:
        r = s.set_field("apparatus.drop", 0.6)
        assert not r.ok and "apparatus.drop" in r.message and "allowed:" in r.message
        words = len(r.message.split())
        assert words > 30  # long enough that 6 s would not do
        now[0] = 0.99 * words / 3.0
        assert any("apparatus.drop" in row for row in a._message_rows())
        now[0] = 20.5
        assert not any("apparatus.drop" in row for row in a._message_rows())
        s.say("reset: t = 0")
        now[0] += 5.9
        assert any("reset" in row for row in a._message_rows())
        now[0] += 0.2
        assert not any("reset" in row for row in a._message_rows())
    finally:
        a.finish()


def test_a_slider_with_one_admissible_value_is_greyed_out_and_its_label_says_so(
        tmp_path, monkeypatch):
    """The gripped fold's offsets are balanced as built (a one-value span): their sliders
    do not move, and their rows say "fixed here" (the tooltip says why); the others
    move and say whether they act live."""
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    a = App(Session(io.load(shipped.path("apparatus_fold_gripped"))), size=(1280, 760),
            offscreen=True)
    try:
        a.toggle_expert()
        rows = {r.spec.path: r for r in a.rows}
        for path in ("apparatus.xi2", "apparatus.xi3"):
            r = rows[path]
            assert not r.slider.is_enabled and "[fixed here]" in r.label.text
            assert "Fixed here" in panel.tooltip(r.spec, True)
        r = rows["carts[1].mass"]
        assert r.slider.is_enabled and "fixed" not in r.label.text
    finally:
        a.finish()
