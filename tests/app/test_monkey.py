"""Random input (keys, typing, clicks, drags, wheel, extreme field values, resizes) for a
fixed number of frames raises nothing, keeps every field inside its schema range and
keeps the process's memory bounded (``chainfountain.app.monkey``; the input is seeded,
so every machine sends the same events)."""

from __future__ import annotations

import math
import os

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import pytest  # noqa: E402

from chainfountain.app import monkey  # noqa: E402
from chainfountain.app.session import Session  # noqa: E402
from chainfountain.app.window import App  # noqa: E402
from chainfountain.level import io  # noqa: E402
from chainfountain.sim.config import SimConfig  # noqa: E402

FRAMES = 600
MEMORY_MB = 2048
"""No process of the project may grow past 2 GB."""


def _invariants(app: App) -> None:
    s = app.session
    assert math.isfinite(s.sim.time)
    for spec in (r.spec for r in app.rows):
        v = s.value(spec.path)
        assert spec.clamp(v)[0] == v  # every value stays inside the schema


@pytest.mark.slow
@pytest.mark.parametrize("seed", [1234, 99])
def test_monkey(tmp_path, monkeypatch, seed):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    cfg = SimConfig()
    cfg.feed.drop = 0.5
    cfg.feed.speed = 4.0
    cfg.chain.link_length = 0.03
    io.save(io.make_level("monkey level", "", cfg), tmp_path / "home" / "levels" / "m.toml")
    app = App(Session(io.make_level("monkey", "", cfg)), size=(1280, 760), offscreen=False)
    try:
        report = monkey.play(app, FRAMES, seed=seed, check=_invariants)
    finally:
        app.finish()
    assert report.frames == FRAMES
    assert report.peak_rss_mb < MEMORY_MB
