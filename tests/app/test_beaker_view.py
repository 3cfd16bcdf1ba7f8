"""The beaker in the window: the default level, its parts named, its readout in words of
the pick-up, and the window's budget for it."""

from __future__ import annotations

import copy
import os

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")

from chainfountain import cli  # noqa: E402
from chainfountain.app import cost as budget  # noqa: E402
from chainfountain.app.readout import Readout  # noqa: E402
from chainfountain.app.readout_text import readout_rows  # noqa: E402
from chainfountain.level import library  # noqa: E402
from chainfountain.sim.world import Simulation  # noqa: E402
from tests import shipped


def _beaker():
    return shipped.level("beaker")


def test_the_default_level_is_the_beaker():
    assert library.default_level().sim.kind == "beaker"


def test_the_beakers_parts_are_named():
    import pygame

    from chainfountain.app.camera import Camera
    from chainfountain.app.machine_view import MachineView

    pygame.font.init()
    sim = Simulation(_beaker().sim)
    cam = Camera(pygame.Rect(0, 0, 800, 600), scale=400.0)
    texts = {lb.text for lb in MachineView().draw(pygame.Surface((800, 600)), cam, sim).labels}
    assert {"pot", "the chain leaves the pile here",
            "pile of chain (topped up from below)"} <= texts


def test_readout_speaks_of_the_pick_up_and_shows_no_machine_pulls():
    ro = Readout(v=4.4, k=9.81 / 4.4**2, q=26.0, h=0.33, l=0.25, H=0.97, T0_bar=0.0,
                 TE_bar=0.1, T0_theory=0.8, TE_theory=0.3, measured=True, origin="pick-up")
    rows = [r.text for r in readout_rows(ro, lam=0.05, expert=False)]
    assert any("0.33 m above the pick-up" in t for t in rows)
    assert not any("pull at" in t for t in rows)


def test_window_budget_refuses_a_beaker_too_tall_to_run():
    origin = _beaker().sim
    tall = copy.deepcopy(origin)
    tall.beaker.drop = 5.0
    why = budget.over_budget(tall, origin)
    assert why is not None and "beaker" in why
    a_bit = copy.deepcopy(origin)
    a_bit.beaker.drop = 1.2
    assert budget.over_budget(a_bit, origin) is None


def test_offscreen_window_draws_the_beaker(tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    shot = tmp_path / "beaker.png"
    assert cli.main(["play", "beaker", "--frames", "20", "--screenshot", str(shot)]) == 0
    assert shot.stat().st_size > 10_000


def test_the_bend_limit_has_a_slider_in_the_beaker_only(level):
    from chainfountain.app.controls import control_fields

    def paths(name):
        return {f.path for f in control_fields(level(name).sim)}

    assert {"beaker.drop", "beaker.pile_depth", "chain.bend_limit"} <= paths("beaker")
    for name in ("classroom", "ideal_fold", "apparatus_floor"):
        assert "chain.bend_limit" not in paths(name)


def test_the_what_to_watch_card_leaves_the_rising_fountain_in_view(tmp_path, monkeypatch):
    """While the beaker forms, its chain rises above the rim: the level's card (at the
    view's top left) hides at most a few of the chain's drawn points (the first fit keeps
    the card's band free)."""
    import numpy as np

    from chainfountain.app.session import Session
    from chainfountain.app.window import App

    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    app = App(Session(_beaker()), size=(1280, 760), offscreen=True)
    try:
        hidden = []
        while app.session.sim.time < 4.0:
            app.run_frame()
            if app.frame % 10 == 0:
                box = app.about_box()
                x, y = app.scene_view.chain_screen.T
                hidden.append(int(np.count_nonzero((x >= box.left) & (x <= box.right)
                                                   & (y >= box.top) & (y <= box.bottom))))
        assert app.about_visible and max(hidden) <= 5
    finally:
        app.finish()


def test_the_piles_push_is_not_read_before_a_fountain_stands():
    """Just after the chain reaches the floor, the floor takes it slowly: Biggins and
    Warner's ``alpha = 1 - gH/v^2`` would read a large negative push, so the line waits."""
    from chainfountain.app.readout import beaker_line

    sim = Simulation(_beaker().sim)
    b = sim.beaker
    b.absorbed, b._speed = 5, 0.04
    assert "alpha" not in beaker_line(sim) and "sqrt(gH)" in beaker_line(sim)
    b._speed = 4.4
    assert "alpha = 1 - gH/v^2 = 0.5" in beaker_line(sim)
