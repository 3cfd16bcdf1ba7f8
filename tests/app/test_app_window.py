"""The window under the SDL dummy driver: scripted events change the model as asked."""

from __future__ import annotations

import os

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import numpy as np  # noqa: E402
import pygame  # noqa: E402
import pygame_gui  # noqa: E402
import pytest  # noqa: E402

from chainfountain.app import render  # noqa: E402
from chainfountain.app.draw import (  # noqa: E402
    ABOUT_MORE,
    ABOUT_SECONDS,
    STOP_ROWS,
    status_rows,
)
from chainfountain.app.session import Session, paused_message  # noqa: E402
from chainfountain.app.window import App  # noqa: E402
from chainfountain.level import io, library  # noqa: E402
from chainfountain.sim.config import SimConfig  # noqa: E402


def small_level() -> io.Level:
    cfg = SimConfig()
    cfg.feed.drop = 0.5
    cfg.feed.speed = 4.0
    cfg.chain.link_length = 0.03
    return io.make_level("small", "test level", cfg)


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
    pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=pos, rel=(0, 0), buttons=(0,
                                         0, 0)))
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
    key(app, pygame.K_ESCAPE)
    assert not app.running


def test_slider_arrow_moves_the_live_value(app):
    row = app._row("feed.speed")
    before = app.session.sim.feed.speed
    right = row.slider.right_button
    for _ in range(3):
        click(app, right.rect.center)
    after = app.session.sim.feed.speed
    assert after > before
    assert app.session.value("feed.speed") == after
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


def test_save_and_load_through_the_dialogs(app, tmp_path):
    app.session.set_field("feed.speed", 4.4)
    key(app, pygame.K_s, mod=pygame.KMOD_CTRL)
    assert app.save_window is not None
    app.save_entry.set_text("classroom demo")
    ok = [b for b in app.save_window.get_container().elements
          if "#save_ok" in getattr(b, "object_ids", [])][0]
    click(app, ok.rect.center)
    path = tmp_path / "home" / "levels" / "classroom_demo.toml"
    assert path.exists() and app.save_window is None
    assert io.load(path).sim.feed.speed == 4.4
    # change the setup, then load the saved level back through the picker
    app.session.set_field("feed.speed", 5.0)
    key(app, pygame.K_l)
    assert app.load_window is not None
    label = "saved/classroom_demo.toml"
    assert label in app._load_items
    app.do_load(label)
    assert app.session.value("feed.speed") == 4.4 and app.load_window is None
    assert app.session.name == "classroom demo"


def test_screenshot_clip_zoom_pan_drag(app, tmp_path):
    for _ in range(10):
        app.run_frame()
    key(app, pygame.K_F12)  # the scene alone, full resolution
    key(app, pygame.K_F12, mod=pygame.KMOD_SHIFT)  # the scene and the plots
    app.saver.wait()
    shots = sorted((tmp_path / "home" / "captures").glob("*.png"), key=lambda p: p.name)
    assert len(shots) == 2 and all(p.stat().st_size > 10_000 for p in shots)
    sizes = sorted(pygame.image.load(str(p)).get_size() for p in shots)
    assert sizes == sorted([app.scene_rect.size, app.scene_rect.union(app.right_rect).size])
    key(app, pygame.K_g)
    assert app.clip is not None and app.clip.crop == app.scene_rect
    t0 = app.session.sim.time
    for _ in range(30):
        app.run_frame()
    clip = app.clip
    # one frame per 1/fps of simulated time (offscreen: 1/60 s of it per window frame)
    assert clip.frames == int((app.session.sim.time - t0) * clip.fps + 1e-6) + 1
    key(app, pygame.K_g)
    assert app.clip is None and app.finishing_clips
    app.finishing_clips[0].wait()
    clips = [p for p in (tmp_path / "home" / "captures").iterdir()
             if p.suffix in (".gif", ".mp4")]  # MP4 when imageio-ffmpeg is installed
    assert len(clips) == 1 and clips[0].stat().st_size > 1000
    # zoom and pan
    cam = app.camera
    scale = cam.scale
    pos = app.scene_rect.center
    pygame.mouse.set_pos(pos)
    pygame.event.post(pygame.event.Event(pygame.MOUSEWHEEL, x=0, y=2, flipped=False))
    app.run_frame()
    assert cam.scale > scale or pygame.mouse.get_pos() != pos  # dummy driver may ignore set_pos
    empty = (app.scene_rect.right - 20, 120)
    cx = cam.cx
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=empty, button=3))
    pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=(empty[0] - 50, 120),
                                         rel=(-50, 0), buttons=(0, 0, 1)))
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONUP, pos=(empty[0] - 50, 120),
                                         button=3))
    app.run_frame()
    assert cam.cx > cx
    # drag a link of the chain
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
    arr = pygame.surfarray.array3d(img)
    assert arr.std() > 10  # not blank
    # chain-coloured pixels inside the scene
    x0 = 300
    scene = arr[x0:x0 + 590, :, :].astype(int)
    near = (abs(scene - render.CHAIN).sum(axis=2) < 60).sum()
    assert near > 150


def test_rollers_carts_and_their_controls(tmp_path, monkeypatch):
    """Apparatus building blocks are drawn and get controls generated from the schema."""
    import math

    from chainfountain.sim.config import CartConfig, RollerConfig

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    lvl = small_level()
    lvl.sim.feed.floor = "solid"
    lvl.sim.rollers = (RollerConfig(x=0.8, y=-0.3, radius=0.05, angular_speed=3.0),)
    lvl.sim.carts = (CartConfig(x=0.4, y=-0.4, incline=math.radians(20), track_length=0.4),)
    app = App(Session(lvl), offscreen=True)
    try:
        paths = [r.spec.path for r in app.rows]
        assert {"carts[0].mass", "carts[0].incline", "rollers[0].angular_speed"} <= set(paths)
        for _ in range(5):
            app.run_frame()
        row = app._row("rollers[0].angular_speed")
        pygame.event.post(pygame.event.Event(pygame_gui.UI_TEXT_ENTRY_FINISHED,
                                             ui_element=row.entry, text="-2"))
        app.run_frame()
        assert app.session.value("rollers[0].angular_speed") == -2.0
        row = app._row("carts[0].mass")
        pygame.event.post(pygame.event.Event(pygame_gui.UI_TEXT_ENTRY_FINISHED,
                                             ui_element=row.entry, text="0.3"))
        app.run_frame()
        assert app.session.sim.config.carts[0].mass == 0.3
    finally:
        app.finish()


def test_quit_keeps_the_clip_and_the_changed_setup(tmp_path, monkeypatch):
    """Esc while recording with unsaved changes: the clip is finished, the setup kept."""
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    app = App(Session(small_level()), offscreen=True)
    app.offscreen = False  # behave like a window on quit (autosave) ...
    app.session.set_field("feed.speed", 4.3)
    key(app, pygame.K_g)
    for _ in range(3):
        app.run_frame()
    key(app, pygame.K_ESCAPE)
    assert not app.running
    notes = app.finish()
    assert any(n.startswith("clip saved") for n in notes), notes
    saved = list((tmp_path / "home" / "levels").glob("autosave-*.toml"))
    assert len(saved) == 1 and io.load(saved[0]).sim.feed.speed == 4.3


def test_each_quit_keeps_its_own_autosave_up_to_ten(tmp_path):
    """Autosaves are named by time (a quit does not overwrite the last one) and only the
    newest ten are kept."""
    from chainfountain.app.window import AUTOSAVES_KEPT, _prune_autosaves

    for k in range(AUTOSAVES_KEPT + 3):
        (tmp_path / f"autosave-20261124-1200{k:02d}.toml").write_text("x")
    (tmp_path / "mine.toml").write_text("x")
    _prune_autosaves(tmp_path)
    left = sorted(p.name for p in tmp_path.glob("autosave-*.toml"))
    assert len(left) == AUTOSAVES_KEPT and left[0] == "autosave-20261124-120003.toml"
    assert (tmp_path / "mine.toml").exists()


def test_status_keeps_a_long_stop_reason_from_its_head():
    """A fold's collapse message runs to 8-10 rows in the view; the status keeps its head,
    which says what failed, rather than the last 6 rows of all messages, which cut it off."""
    import textwrap

    reason = "t = 15.53 s: the folding roller lost the chain. " + "Why it did. " * 80 + "End."
    msgs = [paused_message(reason), "running", "paused"]

    def wrap(m: str) -> list[str]:
        return textwrap.wrap(m, 70)

    rows = status_rows(msgs, reason, wrap)
    assert rows[0].startswith("t = 15.53 s: the folding roller lost the chain")
    assert len(wrap(reason)) > STOP_ROWS and len(rows) == STOP_ROWS + 1
    assert rows[-1] == "paused"  # the newest other message, once
    short = "t = 1.00 s: the table is used up."
    rows = status_rows([paused_message(short)], short, wrap)
    assert rows == ["t = 1.00 s: the table is used up; paused: press R to start again"]
    # not stopped: the newest messages' last 6 rows, as before
    rows = status_rows(["a " * 200, "b"], None, wrap)
    assert len(rows) == 6 and rows[-1] == "b"


def _assert_reaction_plot(app: App) -> None:
    """The window's third plot is the lower plate's reaction, growing, drawn measured
    (chain colour) beside the paper's rate (theory colour)."""
    import numpy as np

    hist = app.session.history.arrays()
    r = hist["reaction"][np.isfinite(hist["reaction"])]
    assert len(r) > 10 and r[-5:].mean() > 2.0 * r[:5].mean() > 0.0
    surf = app._render_plots(app.session.readout(), pygame.Rect(0, 0, 380, 600))
    third = pygame.surfarray.array3d(surf).astype(int)[:, 2 * 600 // 3:, :]
    for colour in (render.CHAIN, render.THEORY):
        assert (abs(third - colour).sum(axis=2) < 30).sum() > 40, colour


def test_open_arrangement_plots_the_plate_reaction(tmp_path, monkeypatch):
    """'open' (the paper's non-stationary arrangement): the third plot is the lower
    plate's reaction force, growing, with the paper's rate drawn beside it."""
    import numpy as np

    from chainfountain.level import library

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    app = App(Session(io.load(library.resolve("apparatus_open"))), offscreen=True)
    try:
        for _ in range(20):
            app.run_frame()
        _assert_reaction_plot(app)
    finally:
        app.finish()
    # a level with a fold has no reaction series: its third plot stays the end tensions
    s = Session(io.load(library.resolve("apparatus_special")))
    s.advance(0.05)
    assert len(s.history.t) > 0 and not np.isfinite(s.history.arrays()["reaction"]).any()


def test_ideal_open_plots_the_plate_reaction_and_switches_to_its_contact_twin(tmp_path,
                                                                          monkeypatch):
    """The open arrangement with ideal rollers: the third plot is the plate's reaction
    with the paper's rate, the turn's height has a slider, and M opens apparatus_open."""

    from chainfountain.level import library

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    lvl = io.load(library.resolve("ideal_open"))
    lvl.sim.initial.mode, lvl.sim.feed.starter = "catenary", 0.0  # landed from the start
    app = App(Session(lvl), offscreen=True)
    try:
        for _ in range(30):
            app.run_frame()
        _assert_reaction_plot(app)
        assert any(row.spec.path == "feed.turn_drop" for row in app.rows)
        # the chain sliding away is drawn on the plate below the floor line
        path, slid = app.session.sim.slide_geometry()
        scr = pygame.Surface(app.screen.get_size())
        render.draw_scene(scr, app.camera, app.session.sim, app.session.readout())
        x0, y_plate = app.camera.point(float(path[-2, 0]) + 0.02, float(path[-1, 1]))
        row = pygame.surfarray.array3d(scr)[x0:x0 + 40, y_plate - 3:y_plate + 4].astype(int)
        assert (abs(row - render.CHAIN).sum(axis=2) < 30).sum() > 20
        key(app, pygame.K_m)
        assert app.session.level.meta.name == "apparatus_open"
    finally:
        app.finish()


def _type_into(app: App, row, text: str, end: int) -> None:
    """Click a field, replace its text by ``text`` as a person types, end with ``end``."""
    click(app, row.entry.rect.center)
    assert app._text_focused()
    for _ in range(12):
        key(app, pygame.K_BACKSPACE)
    for ch in text:
        pygame.event.post(pygame.event.Event(pygame.TEXTINPUT, text=ch))
        app.run_frame()
    key(app, end, unicode="\r" if end == pygame.K_RETURN else "")
    app.run_frame()  # the field's own event (entry finished) arrives one frame later


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
        key(app, pygame.K_SPACE)  # paused, so that a step is one step
    t = s.sim.time
    key(app, pygame.K_RIGHT)
    chk("Right  or  .", "Right", s.sim.time > t)
    t = s.sim.time
    key(app, pygame.K_PERIOD, unicode=".")
    chk("Right  or  .", ".", s.sim.time > t)
    t = s.sim.time
    key(app, pygame.K_RIGHT, mod=pygame.KMOD_SHIFT)
    chk("Shift+Right", "Shift+Right", abs(s.sim.time - t - s.sim.dt) < 1e-9)
    i = s.slow_index
    key(app, pygame.K_s, unicode="s")
    chk("S", "S", s.slow_index != i)
    key(app, pygame.K_r, unicode="r")
    chk("R", "R", s.sim.time == 0.0)
    app.camera.zoom(3.0, app.scene_rect.center)
    app.follow = False
    scale = app.camera.scale
    key(app, pygame.K_f, unicode="f")
    chk("F", "F", app.follow and app.camera.scale != scale)
    theory = app.show_theory
    key(app, pygame.K_t, unicode="t")
    chk("T", "T", app.show_theory != theory)
    key(app, pygame.K_t, unicode="t")
    key(app, pygame.K_h, unicode="h")
    chk("H  or  F1", "H", app.show_help)
    key(app, pygame.K_ESCAPE)
    chk("Esc", "Esc closes the help", not app.show_help and app.running)
    key(app, pygame.K_F1)
    chk("H  or  F1", "F1", app.show_help)
    key(app, pygame.K_F1)
    about = app.about_visible
    key(app, pygame.K_i, unicode="i")
    chk("I", "I", app.about_visible != about)
    key(app, pygame.K_p, unicode="p")
    chk("P", "P", app.projector)
    key(app, pygame.K_p, unicode="p")
    key(app, pygame.K_e, unicode="e")
    chk("E", "E", app.expert)
    key(app, pygame.K_e, unicode="e")
    key(app, pygame.K_g, unicode="g")
    chk("G  (Shift: with the plots)", "G", app.clip is not None)
    key(app, pygame.K_g, unicode="g")
    chk("G  (Shift: with the plots)", "G again", app.clip is None)
    key(app, pygame.K_m, unicode="m")  # this level has no twin: it says so
    chk("M", "M", "twin" in _last(app))
    key(app, pygame.K_l, unicode="l")
    chk("Ctrl+O  or  L", "L", app.load_window is not None)
    key(app, pygame.K_ESCAPE)
    chk("Esc", "Esc closes the picker", app.load_window is None and app.running)
    key(app, pygame.K_o, mod=pygame.KMOD_CTRL)
    chk("Ctrl+O  or  L", "Ctrl+O", app.load_window is not None)
    key(app, pygame.K_ESCAPE)
    key(app, pygame.K_s, mod=pygame.KMOD_CTRL)
    chk("Ctrl+S", "Ctrl+S", app.save_window is not None)
    key(app, pygame.K_ESCAPE)
    chk("Esc", "Esc closes the save prompt", app.save_window is None and app.running)
    before = app.last_capture
    key(app, pygame.K_F12)
    app.saver.wait()
    chk("F12  (Shift: with the plots)", "F12",
        app.last_capture is not None and app.last_capture != before
        and app.last_capture.exists())
    return fails, pressed


@pytest.mark.parametrize("end", [pygame.K_RETURN, pygame.K_ESCAPE], ids=["enter", "esc"])
def test_every_key_works_after_typing_in_any_field(app, end):
    """Enter or Esc in a field gives the keys back to the scene: after each field of the
    panel is typed into, every key of the help acts at once (no click on the scene
    needed), and Esc, with no dialog open, then quits."""
    from chainfountain.app.draw import KEYS

    mouse = {"Mouse wheel", "Drag (empty space)", "Drag (on the chain)", "Enter (in a field)"}
    for row in app.rows:
        _type_into(app, row, row.entry.get_text() or "1", end)
        assert not app._text_focused(), row.spec.path
        fails, pressed = _press_every_key(app)
        assert not fails, (row.spec.path, fails)
    assert pressed | mouse == {k for k, _ in KEYS}  # every key of the help was pressed
    assert app.running  # Esc in a field released it and did not quit
    key(app, pygame.K_ESCAPE)
    assert not app.running


def test_esc_in_a_field_drops_what_was_typed_and_shows_the_value_again(app):
    """Esc leaves the field without applying it, so the field must not keep showing a
    number that is not the value."""
    row = next(r for r in app.rows if r.spec.path == "feed.speed")
    before = app.session.value("feed.speed")
    shown = row.entry.get_text()
    _type_into(app, row, "3.3", pygame.K_ESCAPE)
    assert app.session.value("feed.speed") == before
    assert row.entry.get_text() == shown


def test_play_button_says_what_it_does(app):
    button = app.buttons["play"]
    app.run_frame()
    assert not app.session.paused and button.text == "Pause"
    key(app, pygame.K_SPACE)
    assert app.session.paused and button.text == "Play"
    click(app, button.rect.center)
    assert not app.session.paused and button.text == "Pause"


def test_a_run_that_stopped_itself_says_press_r(app, monkeypatch):
    from chainfountain.errors import UserError

    def used_up() -> None:
        raise UserError("t = 0.10 s: the table is used up.")

    monkeypatch.setattr(app.session.sim, "step", used_up)
    app.run_frame()
    s = app.session
    assert s.paused and s.stopped and app.buttons["play"].text == "Play"
    key(app, pygame.K_SPACE)  # Space cannot run a stopped run: it says what to do
    assert s.paused and "press R to start again" in s.messages[-1][1]
    from chainfountain.app import draw  # the readout's status line says so, too

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
    x0, y0, x1, y1 = render.scene_bounds(app.session.sim, None)
    (ax, ay), (bx, by) = app.camera.to_screen(np.array([[x0, y0], [x1, y1]]))
    r = app.scene_rect.inflate(4, 4)
    return r.collidepoint(ax, ay) and r.collidepoint(bx, by)


def test_view_follows_the_fountain_until_the_user_pans(app):
    """The view refits when the fountain leaves it; after the user pans it stays where
    the user put it, until F."""
    from chainfountain.app.window import FOLLOW_EVERY

    app.run_frame()
    app.camera.fit(10.0, 10.0, 10.1, 10.1)  # the view somewhere else (as after a change)
    assert not _scene_in_view(app)
    for _ in range(FOLLOW_EVERY + 1):
        app.run_frame()
    assert app.follow and _scene_in_view(app)
    # the user pans with the right button on empty space
    start = (app.scene_rect.right - 20, app.scene_rect.bottom - 20)
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
    assert not _scene_in_view(app)  # left where the user put it
    key(app, pygame.K_f)
    assert app.follow and _scene_in_view(app)


def test_m_switches_a_machine_preset_to_its_twin_and_back(tmp_path, monkeypatch):
    """M opens the ideal twin of a contact-machine preset, and M again the contact one; a
    level without a twin says so."""
    from chainfountain.level import library

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    a = App(Session(io.load(library.resolve("ideal_special"))), size=(1280, 760),
            offscreen=True)
    try:
        a.run_frame()
        key(a, pygame.K_m)
        assert a.session.level.meta.name == "apparatus_special"
        assert any(r.spec.path.startswith("carts[") for r in a.rows)
        key(a, pygame.K_m)
        assert a.session.level.meta.name == "ideal_special"
        assert any(r.spec.path == "feed.xi3" for r in a.rows)
    finally:
        a.finish()


def test_m_on_a_level_without_twin_says_so(app):
    key(app, pygame.K_m)
    assert app.session.level.meta.name == "small"
    assert "no twin" in app.session.messages[-1][1]


def test_the_level_says_what_to_watch_until_i_hides_it(app, tmp_path):
    """The description of the level is on the view when it opens and for its first
    ABOUT_SECONDS (then it makes room for the fountain); I hides it and shows it, and shown
    by I it stays; opening another level shows that one's."""
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
    app.run_frame()  # draws the card
    app.session.sim.advance(ABOUT_SECONDS)
    assert not app.about_visible  # it made room for the fountain


def test_the_scene_opens_below_the_card_and_takes_the_view_when_it_goes(tmp_path, monkeypatch):
    """The beaker's pot sits at the top of its scene: the first fit keeps the card's band
    free, so the card covers none of the scene; once the card has gone the view refits to
    the whole view."""
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    a = App(Session(io.load(library.resolve("beaker"))), size=(1280, 760), offscreen=True)
    try:
        box = a.about_box()
        x0, y0, x1, y1 = render.scene_bounds(a.session.sim, a.session.readout())
        (_, top), (_, bottom) = a.camera.to_screen(np.array([[x0, y1], [x1, y0]]))
        assert a.about_visible and top > box.bottom and bottom <= a.scene_rect.bottom + 1
        scale = a.camera.scale
        a.session.sim.advance(ABOUT_SECONDS)
        a.run_frame()
        assert not a.about_visible and a.camera.scale > 1.05 * scale
    finally:
        a.finish()


def test_every_shipped_level_says_all_of_what_to_watch_at_the_default_size(app):
    """At 1280x760 every shipped level's description fits its card whole; a longer one
    is cut to the card's share of the view and says where the rest is."""
    for path in sorted(library.shipped_dir().glob("*.toml")):
        rows = app.about_rows(io.load(path).meta.description.strip())
        assert rows[-1] != ABOUT_MORE, f"{path.stem}: {len(rows)} rows do not fit"
    rows = app.about_rows("a long description " * 300)
    assert rows[-1] == ABOUT_MORE and 4 < len(rows) < 30


def test_the_picker_shows_what_each_level_shows(app):
    key(app, pygame.K_l)
    assert app.load_window is not None and app.load_about is not None
    label = next(lb for lb in app._load_items if lb.endswith("/classroom.toml"))
    app.describe_choice(label)
    app.run_frame()
    assert "A big chain fountain" in app.load_about.html_text
    assert "falling_chain" not in " ".join(app._load_items)  # scenes run headless only
    key(app, pygame.K_ESCAPE)
    assert app.load_window is None and app.load_about is None


def test_the_picker_lists_the_levels_that_form_first_under_headings(app):
    """A teacher picks a demonstration: the shipped levels that start at rest and form come
    first (the default at their head), then those that start on their path; a heading
    says what its group is, and each level says how it starts."""
    from chainfountain.app import paths

    key(app, pygame.K_l)
    assert app.load_list is not None
    rows = [label for label, _ in paths.list_levels()]
    assert rows[0] == paths.FORMING and rows[1] == "levels/beaker.toml"
    laid = rows.index(paths.LAID)
    assert all(paths.forms_from_rest(app._load_items[r]) for r in rows[1:laid])
    assert not any(paths.forms_from_rest(app._load_items[r]) for r in rows[laid + 1:])
    assert "levels/apparatus_fold_gripped.toml" in rows[1:laid]
    assert "levels/apparatus_fold.toml" in rows[laid + 1:]
    for r in rows[laid + 1:]:  # each says so, and why
        text = paths.level_description(app._load_items[r])
        assert "starts laid on its path" in text.lower() or "starts on the predicted curve" \
            in text.lower(), r
    app.describe_choice(paths.LAID)
    app.run_frame()
    assert "already moving" in app.load_about.html_text
    app.describe_choice("levels/apparatus_special.toml")
    app.run_frame()
    assert "Starts laid on its path" in app.load_about.html_text
    app.describe_choice("levels/beaker.toml")
    app.run_frame()
    assert "Starts at rest and forms" in app.load_about.html_text
    assert not app.do_load(paths.FORMING)  # a heading opens nothing
    assert app.session.messages[-1][1] == "pick a level first"


def test_e_switches_the_readout_between_plain_words_and_symbols(app):
    assert not app.expert  # a class first: plain words
    key(app, pygame.K_e)
    assert app.expert and "paper's symbols" in app.session.messages[-1][1]
    app.run_frame()
    key(app, pygame.K_e)
    assert not app.expert


def test_text_grows_with_the_window_and_more_in_projector_mode() -> None:
    from chainfountain.app.window import DEFAULT_SIZE, PANEL_SHARE, PROJECTOR, text_scale

    assert text_scale(DEFAULT_SIZE, False) == 1.0
    assert text_scale((900, 560), False) == 1.0  # never smaller than the default
    assert text_scale((1920, 1080), False) == pytest.approx(1080 / 760)
    big = text_scale((2560, 1440), True)
    assert big == pytest.approx(min(1440 / 760 * PROJECTOR, PANEL_SHARE * 2560 / 690))
    for size in ((1280, 760), (1920, 1080), (3840, 2160)):  # the scene keeps its share
        assert text_scale(size, True) * 690 <= PANEL_SHARE * size[0] + 1e-9


def test_p_switches_projector_mode_and_everything_grows_with_it(app):
    small = render.font(19).get_linesize()
    key(app, pygame.K_p)
    assert app.projector and "projector mode" in app.session.messages[-1][1]
    app.resize((1920, 1080))
    scale = render.text_scale()
    assert scale > 1.4
    assert render.font(19).get_linesize() > 1.3 * small
    assert app.left_w == render.px(300) and app.scene_rect.w >= 0.45 * 1920
    for row in app.rows:  # every control stays inside the panel
        assert row.entry.get_relative_rect().right <= app.left_w
    key(app, pygame.K_h)  # the help draws at this size
    app.run_frame()
    key(app, pygame.K_h)
    key(app, pygame.K_p)
    assert not app.projector and render.text_scale() == pytest.approx(1080 / 760)


def test_rendered_text_is_kept_and_bounded(app):
    """A frame's labels are rendered once and drawn again from the cache; the cache keeps
    at most TEXT_CACHE texts however many different ones a long run draws (the time
    line's text changes every frame)."""
    f = render.font(18)
    first = render.text(f, "speed 3.00 m/s", True, render.TEXT)
    assert render.text(f, "speed 3.00 m/s", True, render.TEXT) is first
    assert render.text(f, "speed 3.00 m/s", True, render.DIM) is not first
    for i in range(render.TEXT_CACHE + 50):
        render.text(f, f"t = {i * 0.01:7.2f} s", True, render.TEXT)
        render.wrap(f, f"a long paragraph number {i} " * 4, 120)
    assert len(render._TEXTS) <= render.TEXT_CACHE
    assert len(render._WRAPS) <= render.TEXT_CACHE
    assert render.wrap(f, "one two three", 10_000) == ["one two three"]


def test_a_window_steps_its_physics_while_the_frame_goes_to_the_screen(tmp_path, monkeypatch):
    """With a display (here SDL's dummy one) each frame's physics runs in a worker while
    the drawn frame is copied to the screen; the next frame draws its result, and a failure
    in the worker reaches the caller of the frame as it would without the worker."""
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
    """The frame rate gives way to the physics: a light physics keeps the full rate, a
    heavy one (the gripped folds) sinks it toward MIN_FPS so that drawing does not take
    the time real time needs; the physics' cost is measured from the frames it ran."""
    from chainfountain.app.window import HEADROOM, MIN_FPS

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    a = App(Session(small_level()), size=(1280, 760), offscreen=False, fps=60)
    try:
        for _ in range(5):
            a.run_frame(1.0 / 60.0)
        assert a.physics_cost > 0.0  # measured from the frames' steps
        a.overhead = 0.005
        a.physics_cost = 0.2
        assert a.target_fps() == 60.0
        a.physics_cost = HEADROOM - 40 * 0.005
        assert a.target_fps() == pytest.approx(40.0)
        a.physics_cost = 0.95
        assert a.target_fps() == MIN_FPS
        a.session.paused = True
        assert a.target_fps() == 60.0
    finally:
        a.finish()


@pytest.mark.parametrize("preset, want", [(None, "0"), ("1", "1")])
def test_the_window_uses_the_displays_framebuffer_unless_told_otherwise(
        tmp_path, monkeypatch, preset, want) -> None:
    """Without GPU drivers SDL's OpenGL path costs the physics two threads' worth of CPU
    (window.FRAMEBUFFER_HINT): the window asks for the display's own framebuffer, and an
    environment that says otherwise is obeyed."""
    from chainfountain.app.window import FRAMEBUFFER_HINT

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    monkeypatch.delenv(FRAMEBUFFER_HINT, raising=False)
    if preset is not None:
        monkeypatch.setenv(FRAMEBUFFER_HINT, preset)
    a = App(Session(small_level()), size=(640, 480), offscreen=True)
    try:
        assert os.environ[FRAMEBUFFER_HINT] == want
    finally:
        a.finish()


def test_a_readout_row_too_long_for_the_panel_wraps_instead_of_running_off(app):
    """In projector mode the expert readout's first row is wider than the panel: it goes
    on onto a second line; a row that fits is drawn as written."""
    from chainfountain.app.readout_text import Row

    key(app, pygame.K_p, unicode="p")
    f = render.font(19)
    long = Row("Readout (measured); theory: catenary through the ends   (E: plain words)",
               "dim")
    assert f.size(long.text)[0] > app.right_rect.w - 18
    one = app._draw_rows([Row("v  3.0 m/s")], app.right_rect)
    two = app._draw_rows([long], app.right_rect)
    top = render.px(8)
    assert two - top == 2 * (one - top)


def test_part_labels_at_one_place_do_not_cover_each_other(app) -> None:
    """Two names at one point on one side (as the starter's label lands on the pick-up
    roller's in apparatus_fold_gripped) go a row apart: no two boxes overlap."""
    from types import SimpleNamespace

    from chainfountain.sim.part_labels import PartLabel

    labels = [PartLabel("pick-up roller", 0.0, 0.0, side) for side in
              ("above", "above", "left", "left", "below", "below", "right", "right")]
    sim = SimpleNamespace(part_labels=lambda: labels)
    surf = pygame.Surface((800, 600))
    cam = render.Camera(pygame.Rect(0, 0, 800, 600))
    boxes = render._part_labels(surf, cam, sim)
    assert len(boxes) == len(labels)
    for i, a in enumerate(boxes):
        assert a.collidelist(boxes[i + 1:]) < 0, (i, a)


def test_a_plot_title_never_runs_under_its_legend(app) -> None:
    """A title too long for the room left of the legend ends in "..." (the fed levels'
    end-tension plot once ran its title under "launch")."""
    f = render.font(16)
    long = "pull at the ends / (lambda v^2), and a great deal more said about it"
    short = render.fit_text(f, long, 200)
    assert short.endswith("...") and f.size(short)[0] <= 200
    assert render.fit_text(f, "speed (m/s)", 200) == "speed (m/s)"
