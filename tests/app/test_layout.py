"""The window's layout at every supported size: the scene takes most of the window, the
panel moves under it in a portrait window, projector mode keeps the window's size, and no
text the window draws runs out of its box."""

from __future__ import annotations

import os

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import pygame  # noqa: E402
import pytest  # noqa: E402

from chainfountain.app import layout, text  # noqa: E402
from chainfountain.app.session import Session  # noqa: E402
from chainfountain.app.window import App  # noqa: E402
from tests import shipped
from tests.app.offscreen import shipped_app

SIZES = ((720, 540), (900, 600), (1280, 760), (1920, 1080), (800, 1100), (1080, 1920))
"""The smallest supported window, a small laptop's, the default, a projector's, and two
portrait windows."""


@pytest.mark.parametrize("size", SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("projector", [False, True], ids=["plain", "projector"])
def test_the_scene_takes_most_of_the_window(size, projector) -> None:
    """The student view: the scene takes at least 60 % of the window (with the graphs
    shown, at least 40 %), the panel at most 30 % of a landscape window's width."""
    scale = layout.text_scale(size, projector)
    lay = layout.compute(size, scale)
    assert lay.scene_share(size) >= 0.6
    assert lay.portrait == (size[0] < size[1])
    if not lay.portrait:
        assert lay.panel.w <= layout.PANEL_SHARE * size[0] + 1
    with_plots = layout.compute(size, scale, plots=True)
    assert with_plots.scene_share(size) >= 0.4
    full = layout.compute(size, scale, panel=False)
    assert full.scene.size == size and full.panel is None


def test_text_grows_with_the_window_and_more_in_projector_mode() -> None:
    assert layout.text_scale(layout.DEFAULT_SIZE, False) == 1.0
    assert layout.text_scale((900, 600), False) == 1.0  # never smaller than the default
    assert layout.text_scale((1920, 1080), False) == pytest.approx(1080 / 760)
    assert layout.text_scale((1920, 1080), True) > 1.3 * layout.text_scale((1920, 1080), False)
    for size in SIZES:  # grown text never makes the panel wider than its share
        s = layout.text_scale(size, True)
        room = 0.5 * size[0] if layout.portrait(size) else layout.PANEL_SHARE * size[0]
        assert s == 1.0 or s * layout.PANEL_W <= room + 1e-9


@pytest.fixture
def beaker_app(tmp_path, monkeypatch):
    with shipped_app("beaker", tmp_path / "home", monkeypatch) as a:
        yield a


def test_projector_mode_keeps_the_windows_size_whichever_way_it_starts(tmp_path,
                                                                       monkeypatch) -> None:
    """P and ``--projector`` give the same text scale and layout, and the window keeps its
    size either way (leaving P does not snap it back to another size)."""
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    level = shipped.level("ideal_fold")
    a = App(Session(level), size=(1600, 900), offscreen=True, projector=True)
    try:
        started = (text.text_scale(), a.scene_rect.copy(), a.size)
    finally:
        a.finish()
    b = App(Session(level), size=(1600, 900), offscreen=True)
    try:
        plain = text.text_scale()
        pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_p, mod=0,
                                             unicode="p", scancode=0))
        b.run_frame()
        assert (text.text_scale(), b.scene_rect, b.size) == started
        assert text.text_scale() > plain
        pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_p, mod=0,
                                             unicode="p", scancode=0))
        b.run_frame()
        assert b.size == (1600, 900) and text.text_scale() == plain
    finally:
        b.finish()


DEMOS = ("beaker", "apparatus_fold_gripped", "ideal_fold", "classroom")


@pytest.mark.slow
@pytest.mark.parametrize("name", DEMOS)
def test_no_text_runs_out_of_its_box_at_any_size(level, name, tmp_path, monkeypatch) -> None:
    """Every text the window draws into a box (the readout, the card, the help, the
    picker, the scene's controls, the messages) stays inside it, in both views, at every
    supported size, with and without projector mode."""
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    monkeypatch.setattr(text, "OVERFLOWS", [])
    a = App(Session(level(name)), size=(1280, 760), offscreen=True)
    try:
        for _ in range(90):
            a.run_frame()
        for size in SIZES:
            a.resize(size)
            for projector in (False, True):
                if a.projector != projector:
                    a.toggle_projector()
                for expert in (False, True):
                    if a.expert != expert:
                        a.toggle_expert()
                    a.show_help = True
                    a.draw()
                    a.show_help = False
                    a.open_picker()
                    a.draw()
                    a.close_picker()
                    a.about_pinned = a.show_about = True
                    a.draw()
        assert text.OVERFLOWS == []
        for row in a.rows:  # the panel's widgets stay inside its column
            assert a.controls_box.get_container().get_rect().w >= \
                row.entry.get_relative_rect().right
    finally:
        a.finish()
