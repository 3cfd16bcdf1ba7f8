"""Without a display `chainfountain` says so and runs the default level headless."""

from __future__ import annotations

import os

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import json  # noqa: E402

import pytest  # noqa: E402

from chainfountain import cli  # noqa: E402
from chainfountain.app import launch  # noqa: E402


def test_no_display_detected(monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    monkeypatch.delenv("SDL_VIDEODRIVER", raising=False)
    ok, why = launch.display_available()
    assert not ok and "DISPLAY" in why
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    assert launch.display_available() == (False, "SDL_VIDEODRIVER=dummy")


def test_no_display_runs_the_default_level_headless(tmp_path, monkeypatch, capsys):
    from chainfountain.level import io
    from chainfountain.sim.config import SimConfig

    cfg = SimConfig()
    cfg.feed.drop = 0.5
    cfg.feed.speed = 4.0
    cfg.chain.link_length = 0.03
    small = io.make_level("tiny default", "", cfg)
    monkeypatch.setattr("chainfountain.app.session.default_level", lambda: small)
    monkeypatch.setattr("chainfountain.headless.run.DEFAULT_DURATION", 0.3)
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    monkeypatch.delenv("SDL_VIDEODRIVER", raising=False)
    assert cli.main([]) == 0
    err = capsys.readouterr().err
    assert "no display" in err and "headless" in err
    out = tmp_path / "runs" / "tiny_default"
    for name in ("summary.json", "tensions.csv", "speed.csv", "snapshot.png"):
        assert (out / name).exists(), name
    assert json.loads((out / "summary.json").read_text())


def test_play_rejects_bad_arguments(capsys):
    with pytest.raises(SystemExit):
        cli.main(["play", "--frames", "0"])
    assert "out of range" in capsys.readouterr().err
    assert cli.main(["play", "no_such_level_anywhere", "--frames", "1"]) == 2
    assert "no_such_level_anywhere" in capsys.readouterr().err
