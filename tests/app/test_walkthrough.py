"""A teacher's walkthrough of the window, scripted: what a class saw go wrong must no
longer happen.

A teacher opens the default level, picks a machine from the picker with the arrow keys,
tunes a cart with the slider's arrows, resizes the window to a small laptop's and to a
portrait screen, switches to projector mode, looks at the twin machine and comes back,
measures with the ruler and the stopwatch, and quits with unsaved changes. Each step
asserts one line of the classroom review (issue 59): a steady fountain that looks
frozen, a chain that loses to the theory band, a machine drawn as lines, a scene that is
the smallest thing on screen, researcher language, a demo easy to lose, controls that do
not work by hand.
"""

from __future__ import annotations

import os
import re

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import numpy as np  # noqa: E402
import pygame  # noqa: E402
import pytest  # noqa: E402

from chainfountain.app import chain_view, text  # noqa: E402
from chainfountain.app.session import Session  # noqa: E402
from chainfountain.app.window import App  # noqa: E402
from chainfountain.level import library  # noqa: E402
from tests import shipped

RESEARCHER = re.compile(r"lambda|Tbar|\bxi[23]\b|links \d+ free|N\*s/m|\[live\]|\[rebuild\]|"
                        r"docs/|\.md\b|real-time factor")
"""Words of the expert view (and of the model's notes) a class should not meet."""


def key(app: App, k: int, mod: int = 0, unicode: str = "") -> None:
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=k, mod=mod, unicode=unicode,
                                         scancode=0))
    pygame.event.post(pygame.event.Event(pygame.KEYUP, key=k, mod=mod, unicode=unicode,
                                         scancode=0))
    app.run_frame()


def click(app: App, pos: tuple[int, int]) -> None:
    for kind in (pygame.MOUSEBUTTONDOWN, pygame.MOUSEBUTTONUP):
        pygame.event.post(pygame.event.Event(kind, pos=pos, button=1))
        app.run_frame()
    app.run_frame()
    app.run_frame()  # the GUI's own events arrive a frame or two later


def frames(app: App, n: int) -> None:
    for _ in range(n):
        app.run_frame()


def marked_links(app: App) -> np.ndarray:
    """Screen centres of the links the scene draws white (the travelling marks)."""
    sim = app.session.sim
    serial = app.scene_view.serials.of(sim.chain.links)
    front, back = sim.link_endpoints()
    keep = serial % app.scene_view.marks_every == 0
    return app.camera.to_screen(0.5 * (front[keep] + back[keep]))


@pytest.fixture
def teacher(tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    monkeypatch.setattr(text, "SEEN", set())
    monkeypatch.setattr(text, "OVERFLOWS", [])
    app = App(Session(library.default_level(), shipped.path("beaker")),
              size=(1920, 1080), offscreen=True)
    yield app
    app.finish()


@pytest.mark.slow
@pytest.mark.xdist_group("walkthrough")
def test_a_teacher_prepares_a_demo(teacher, tmp_path) -> None:
    app = teacher
    s = app.session
    # the default level: the beaker, its own fountain, no theory band over it
    assert s.level.sim.kind == "beaker" and not app.show_theory
    frames(app, 60)
    # -- the picker: titles and thumbnails, the arrow keys, Space does not run the scene
    key(app, pygame.K_l)
    assert app.picker is not None
    titles = [e.title for e in app.picker.rows if e.path is not None]
    assert "Chain leaping out of a pot" in titles and not any(t.endswith(".toml")
                                                              for t in titles)
    while app.picker.chosen.path.stem != "apparatus_special_gripped":
        before = app.picker.sel
        key(app, pygame.K_DOWN)
        assert app.picker.sel != before
    paused = s.paused
    key(app, pygame.K_SPACE)
    assert app.picker is not None and s.paused == paused  # Space is the picker's
    app.draw()
    assert app.picker._thumbs  # it drew the levels' pictures
    key(app, pygame.K_RETURN)
    assert app.picker is None and s.level.meta.name == "apparatus_special_gripped"
    # -- the student view: the level's own sliders, plain words
    assert [r.spec.path for r in app.rows] == s.level.meta.control_paths()
    for r in app.rows:
        assert not RESEARCHER.search(r.label.text), r.label.text
    frames(app, 8 * 60)  # the fountain forms from rest
    app.draw()
    drawn = " | ".join(sorted(text.SEEN))
    assert not RESEARCHER.search(drawn), RESEARCHER.search(drawn).group(0)
    # -- a steady fountain does not look frozen: the marks move along the chain
    a = marked_links(app)
    app.run_frame()
    b = marked_links(app)
    assert len(a) >= 3
    n = min(len(a), len(b))
    assert np.median(np.hypot(*(b[:n] - a[:n]).T)) > 1.0  # px a frame
    # -- the chain reads on a projector and wins over the paper's curve
    assert chain_view.chain_width(app.camera, s.level.sim.chain.link_radius) >= 6
    # -- the machine as a machine: wheels, carts with their masses, tables, labels clear
    labels = {p.key for p in app.scene_view.placed}
    assert {"pickup", "fold", "upper_cart", "lower_cart"} <= labels
    assert any(f"{s.value('carts[1].mass') * 1e3:.3g} g" in t for t in text.SEEN)
    # -- a cart tuned by the slider's arrow: one round step a click
    row = app._row("carts[1].mass")
    before = s.value("carts[1].mass")
    click(app, row.slider.left_button.rect.center)
    step = before - s.value("carts[1].mass")
    assert step > 0 and round(step * 1e3, 9) in (0.1, 0.2, 0.5, 1.0, 2.0)
    assert s.dirty
    # -- the scene is the biggest thing on screen at any size, text never spills
    for size in ((900, 600), (800, 1100), (1920, 1080)):
        app.resize(size)
        frames(app, 3)
        assert app.lay.scene_share(app.size) >= 0.6, size
    key(app, pygame.K_p)
    assert app.projector and app.size == (1920, 1080)  # P keeps the window's size
    frames(app, 3)
    assert text.OVERFLOWS == []
    # -- the measuring tools
    key(app, pygame.K_u)
    key(app, pygame.K_w)
    assert app.ruler.on and app.stopwatch.on
    click(app, next(b for b in app.stopwatch.buttons if b.key == "start").rect.center)
    assert app.stopwatch.running
    e0, t0 = app.stopwatch.elapsed, s.sim.time
    frames(app, 30)
    assert s.sim.time - t0 > 0.4  # simulated seconds, counted as they pass
    assert app.stopwatch.elapsed - e0 == pytest.approx(s.sim.time - t0)
    end = app.camera.point(*app.ruler.ends[1])
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=end, button=1))
    pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=(end[0], end[1] - 100),
                                         rel=(0, -100), buttons=(1, 0, 0)))
    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONUP, pos=(end[0], end[1] - 100),
                                         button=1))
    app.run_frame()
    assert app.ruler.reading()[1] == pytest.approx(100 / app.camera.scale, rel=0.02)
    # -- M: the twin, and M again: back where we were, with the tuned cart
    key(app, pygame.K_m)
    assert s.level.sim.kind == "feed" and "M goes back" in s.messages[-1][1]
    autosaves = list((tmp_path / "home" / "levels").glob("autosave-*.toml"))
    assert len(autosaves) == 1  # the tuned setup was kept, and the window said so
    assert any(autosaves[0].name in m for _, m in s.messages)
    key(app, pygame.K_m)
    assert s.level.meta.name == "apparatus_special_gripped"
    assert s.value("carts[1].mass") == pytest.approx(before - step)
    # -- Reset all: the level as it was opened
    key(app, pygame.K_r, mod=pygame.KMOD_SHIFT)
    assert s.value("carts[1].mass") == pytest.approx(before) and not s.dirty
    # -- quitting: one Esc asks, the second quits, the changes are kept
    s.set_field("carts[1].mass", before + 0.001)
    app.offscreen = False  # quit as a window does
    key(app, pygame.K_ESCAPE)
    assert app.running and app.quit_prompt and "autosave" in app.quit_prompt
    key(app, pygame.K_ESCAPE)
    assert not app.running


def test_the_picker_takes_every_key_while_it_is_open(level, tmp_path, monkeypatch) -> None:
    """Up/Down choose (headings skipped), Esc closes without opening, and no key reaches
    the scene behind it."""
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    app = App(Session(level("classroom")), size=(1280, 760),
              offscreen=True)
    try:
        key(app, pygame.K_l)
        p = app.picker
        first = p.sel
        key(app, pygame.K_UP)  # at the top: stays
        assert p.sel == first and p.rows[p.sel].path is not None
        for _ in range(40):
            key(app, pygame.K_DOWN)
            assert p.rows[p.sel].path is not None
        key(app, pygame.K_END)
        last = p.sel
        key(app, pygame.K_HOME)
        assert p.sel == first != last
        for k in (pygame.K_r, pygame.K_t, pygame.K_e, pygame.K_m):
            key(app, k)
        assert app.show_theory and not app.expert and app.session.sim.time > 0
        key(app, pygame.K_ESCAPE)
        assert app.picker is None and app.running and app.quit_prompt is None
        assert app.session.level.meta.name == "classroom"
    finally:
        app.finish()


def test_the_theory_is_on_where_the_paper_predicts_the_fountain(level, tmp_path,
                                                                monkeypatch) -> None:
    """The paper's curve is shown over the machines and fed fountains, not over the
    beaker's chain (its fountain is the chain's own; T shows the fit)."""
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    for name, shown in (("beaker", False), ("ideal_fold", True), ("classroom", True),
                        ("apparatus_special_gripped", True)):
        app = App(Session(level(name)), size=(900, 600), offscreen=True)
        try:
            assert app.show_theory is shown, name
        finally:
            app.finish()
