"""The scene as a class sees it: a chain whose marks travel with it, a machine whose parts
move with its sliders and turn with the chain, labels that never cover each other, the
chain or the controls, and the paper's curve behind the chain."""

from __future__ import annotations

import math
import os

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import numpy as np  # noqa: E402
import pygame  # noqa: E402
import pytest  # noqa: E402

from chainfountain.app import chain_view, palette  # noqa: E402
from chainfountain.app.camera import Camera  # noqa: E402
from chainfountain.app.labels import LabelLayout, Request  # noqa: E402
from chainfountain.app.machine_view import MachineView, ideal_parts  # noqa: E402
from chainfountain.app.session import Session  # noqa: E402
from chainfountain.app.window import App  # noqa: E402
from chainfountain.level import io  # noqa: E402
from chainfountain.sim import placement
from chainfountain.sim.world import Simulation  # noqa: E402
from tests import shipped

pygame.font.init()


def _speed(level: io.Level) -> float:
    sim = level.sim
    if sim.kind == "beaker":
        return math.sqrt(2.0 * sim.gravity * sim.beaker.drop)
    return sim.apparatus.speed if sim.kind == "apparatus" else sim.feed.speed


def test_the_marks_never_strobe_on_any_shipped_level() -> None:
    """At the window's lowest frame rate a mark moves at most a third of the marks'
    spacing in a frame (a mark that jumps more than half of it is seen moving backwards),
    and there are at least ten links between two marks."""
    for path in shipped.PATHS:
        level = io.load(path)
        if level.sim.kind == "scene":
            continue
        v, L = _speed(level), level.sim.chain.link_length
        n = chain_view.mark_spacing(v, L)
        assert n >= 10 and n % 5 == 0
        assert v / chain_view.SLOWEST_FPS <= n * L / 3.0 + 1e-12, path.stem


def test_the_marks_travel_with_the_links() -> None:
    """A link keeps its number while it exists, whatever enters or leaves the chain, so a
    marked link stays marked as it moves from the guide to the floor."""
    level = shipped.level("wide_low")
    sim = Simulation(level.sim)
    serials = chain_view.LinkSerials()
    sim.advance(0.5)
    first = dict(zip(map(id, sim.chain.links), serials.of(sim.chain.links).tolist(),
                     strict=True))
    links = list(sim.chain.links)
    sim.advance(0.3)  # links leave at the floor and enter at the guide
    now = serials.of(sim.chain.links)
    assert len(set(map(id, sim.chain.links)) - set(first)) > 0  # new links came in
    for link, s in zip(sim.chain.links, now.tolist(), strict=True):
        if id(link) in first and link in links:
            assert s == first[id(link)]
    assert np.all(np.diff(now) == -1)  # numbered in order along the chain


def _app(tmp_path, monkeypatch, name: str, size=(1920, 1080), projector=False) -> App:
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    return App(Session(shipped.level(name)), size=size, offscreen=True,
               projector=projector)


def _assert_labels_clear(app: App, where: str) -> None:
    """The scene's labels lie inside the view, clear of each other, of the chain's drawn
    points and of the time controls."""
    placed = app.scene_view.placed
    rects = [p.rect for p in placed]
    pts = app.scene_view.chain_screen
    for i, r in enumerate(rects):
        assert app.scene_rect.contains(r), (where, placed[i].key)
        assert r.collidelist(rects[i + 1:]) < 0, (where, placed[i].key)
        inside = (pts[:, 0] >= r.left) & (pts[:, 0] <= r.right) & (pts[:, 1] >= r.top) & \
            (pts[:, 1] <= r.bottom)
        assert not inside.any(), (where, placed[i].key)
        assert r.collidelist(app.timebar.keep_clear()) < 0, (where, placed[i].key)


MACHINES = sorted(p.stem for p in shipped.PATHS
                  if p.stem.startswith(("apparatus_", "ideal_")) or p.stem == "beaker")


SLOW = ("apparatus_fountain_d", "apparatus_fountain_d_kmax")
"""Study levels at 0.04-0.05x real time: looked at as they start only (their machine is
the floor machine's, looked at for 2 s as apparatus_floor)."""


@pytest.mark.slow
@pytest.mark.parametrize("name", MACHINES)
def test_labels_never_cover_each_other_the_chain_or_the_controls(name, tmp_path,
                                                                 monkeypatch) -> None:
    """Every machine level, at a projector's 1920x1080 in projector mode and at 900x600,
    as it starts and 2 s on: its parts' labels are laid out clear (and most of them are
    shown)."""
    app = _app(tmp_path, monkeypatch, name, projector=True)
    try:
        for size, projector in (((1920, 1080), True), ((900, 600), False)):
            app.resize(size)
            if app.projector != projector:
                app.toggle_projector()
            for frames in (2, 6) if name in SLOW else (2, 120):
                for _ in range(frames):
                    app.run_frame()
                    if app.session.stopped:  # the limit case ends early: it says why
                        break
                app.draw()
                _assert_labels_clear(app, f"{name} {size} t={app.session.sim.time:.2f}")
                assert len(app.scene_view.placed) >= 3
            app.session.reset()
    finally:
        app.finish()


def test_the_layout_keeps_a_label_where_it_was_while_it_stays_clear() -> None:
    view = pygame.Rect(0, 0, 800, 600)
    lay = LabelLayout()
    reqs = [Request("a", (120, 24), (400, 300), "above"), Request("b", (120, 24), (400, 300),
                                                                 "above")]
    first = lay.place(reqs, view, [], np.zeros((0, 2)))
    assert [p.key for p in first] == ["a", "b"] and not first[0].rect.colliderect(first[1].rect)
    chain = np.array([[x, float(first[1].rect.centery)] for x in range(0, 800, 3)])
    again = lay.place(reqs, view, [], chain)  # the chain moved over b: b moves, a stays
    assert again[0].rect == first[0].rect and again[1].rect != first[1].rect
    # a label with no clear place anywhere is left out, not drawn over something
    full = [pygame.Rect(0, 0, 800, 600)]
    assert lay.place([Request("c", (120, 24), (400, 300))], view, [], np.zeros((0, 2))) != []
    assert LabelLayout().place([Request("c", (120, 24), (400, 300))], view, [],
                               np.array([[x, y] for x in range(0, 800, 4)
                                         for y in range(0, 600, 4)], float)) == []
    del full


def test_every_slider_of_an_ideal_machine_moves_something_drawn(tmp_path, monkeypatch) -> None:
    """The ideal full machine is drawn as the contact machine's parts at the paper's
    geometry: the upper table sits ``xi2*H`` below the start and the lower table ``xi3*H``
    above the end, so each offset's slider moves its table; each cart's slider changes
    what the cart says and how big it is drawn."""
    level = shipped.level("ideal_fold")
    sim = Simulation(level.sim)
    base = ideal_parts(sim)
    H = level.sim.feed.drop
    assert base.upper.table[0][1] == pytest.approx(-level.sim.feed.xi2 * H, abs=0.08)
    for path, attr in (("xi2", "upper"), ("xi3", "lower")):
        moved = shipped.level("ideal_fold")
        setattr(moved.sim.feed, path, getattr(moved.sim.feed, path) + 0.1)
        parts = ideal_parts(Simulation(moved.sim))
        dy = getattr(parts, attr).table[0][1] - getattr(base, attr).table[0][1]
        assert dy == pytest.approx(-0.1 * H if path == "xi2" else 0.1 * H, abs=1e-3), path
    app = _app(tmp_path, monkeypatch, "ideal_fold")
    try:
        app.run_frame()
        before = pygame.surfarray.array3d(app.screen).copy()
        app.set_field("feed.lower_cart_force", 0.35)
        app.run_frame()
        after = pygame.surfarray.array3d(app.screen)
        near = app.scene_view.machine.draw(app.screen, app.camera, app.session.sim).boxes
        changed = np.abs(after.astype(int) - before).sum(axis=2) > 60
        assert any(changed[b.left:b.right, b.top:b.bottom].sum() > 50 for b in near)
    finally:
        app.finish()


def test_the_rollers_turn_with_the_chain(tmp_path, monkeypatch) -> None:
    """A roller's white spoke turns between frames as the chain runs over it (and not
    when it stands still)."""
    app = _app(tmp_path, monkeypatch, "apparatus_special_gripped")
    try:
        for _ in range(240):
            app.run_frame()
        view = app.scene_view.machine
        before = dict(view._angles)
        app.run_frame()
        turned = {k: view._angles[k] - before[k] for k in before}
        assert all(abs(a) > 1e-3 for a in turned.values()), turned
        app.toggle_pause()
        app.run_frame()
        still = dict(view._angles)
        app.run_frame()
        assert view._angles == still
    finally:
        app.finish()


@pytest.mark.slow
def test_the_chain_is_drawn_over_the_papers_curve_and_stands_out(tmp_path, monkeypatch) -> None:
    """Where the chain lies on the paper's curve the class sees the chain: its pixels are
    the chain's colour (or its marks'), never the curve's; the curve is a thin dashed
    line, so most pixels along it away from the chain are the background."""
    app = _app(tmp_path, monkeypatch, "ideal_fold")
    try:
        for _ in range(600):
            app.run_frame()
        app.draw()
        arr = pygame.surfarray.array3d(app.screen).astype(int)
        pts = app.camera.to_screen(app.session.sim.chain_polyline()).astype(int)
        pts = pts[(pts[:, 0] > app.scene_rect.left) & (pts[:, 0] < app.scene_rect.right - 1)
                  & (pts[:, 1] > 0) & (pts[:, 1] < app.scene_rect.bottom - 1)]
        colours = arr[pts[:, 0], pts[:, 1]]
        chain = np.abs(colours - palette.CHAIN).sum(axis=1) < 60
        mark = np.abs(colours - palette.MARK).sum(axis=1) < 60
        theory = np.abs(colours - palette.THEORY).sum(axis=1) < 40
        assert (chain | mark).mean() > 0.9 and theory.mean() < 0.02
        assert chain_view.chain_width(app.camera, 0.002) >= 6
    finally:
        app.finish()


def test_the_beakers_pile_is_drawn_as_chain(tmp_path, monkeypatch) -> None:
    """The part of the pile the solver does not hold is drawn as rows of links in the pot
    (chain-coloured pixels below its plate)."""
    level = shipped.level("beaker")
    sim = Simulation(level.sim)
    surf = pygame.Surface((800, 800))
    cam = Camera(pygame.Rect(0, 0, 800, 800), scale=900.0, cx=-0.1, cy=-0.1)
    MachineView().draw(surf, cam, sim)
    outline, plate = placement.vessel(sim)
    (x0, y0), (x1, _) = cam.point(*plate[0]), cam.point(*plate[1])
    bottom = cam.point(0.0, float(outline[1, 1]))[1]
    arr = pygame.surfarray.array3d(surf)[x0 + 4:x1 - 4, y0 + 4:bottom - 4].astype(int)
    chainy = (np.abs(arr - palette.CHAIN).sum(axis=2) < 60).mean()
    assert chainy > 0.2
