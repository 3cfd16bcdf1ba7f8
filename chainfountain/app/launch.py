"""Opening the window, or running headless when there is no display."""

from __future__ import annotations

import os
import sys
from pathlib import Path

from chainfountain.level.io import Level

OFFSCREEN_DRIVERS = ("dummy", "offscreen")

os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")


def display_available() -> tuple[bool, str]:
    """Whether a window can be opened here, and why not.

    ``SDL_VIDEODRIVER=dummy`` (or ``offscreen``) counts as no display. On
    Linux and the BSDs a display needs ``DISPLAY`` or ``WAYLAND_DISPLAY``
    unless ``SDL_VIDEODRIVER`` names another driver. Finally SDL must start.
    """
    drv = os.environ.get("SDL_VIDEODRIVER", "")
    if drv in OFFSCREEN_DRIVERS:
        return False, f"SDL_VIDEODRIVER={drv}"
    if (sys.platform.startswith(("linux", "freebsd", "openbsd", "netbsd")) and not drv
            and not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY")):
        return False, "neither DISPLAY nor WAYLAND_DISPLAY is set"
    try:
        import pygame

        pygame.display.init()
        driver = pygame.display.get_driver()
    except Exception as exc:  # noqa: BLE001 - any SDL failure means: no window
        return False, f"SDL cannot start a display ({exc})"
    if driver in OFFSCREEN_DRIVERS:
        return False, f"SDL chose the {driver} driver"
    return True, driver


def _load_or_default(level: Level | None) -> Level:
    if level is not None:
        return level
    from chainfountain.app.session import default_level

    return default_level()


def open_app(level: Level | None = None, source: Path | None = None, *,
             frames: int | None = None, screenshot: Path | None = None,
             size: tuple[int, int] | None = None, offscreen: bool = False,
             paused: bool = False, projector: bool = False, notice: str | None = None) -> int:
    """Open the window on ``level`` (default level when ``None``).

    With ``offscreen`` the SDL dummy driver is used and every frame advances
    exactly 1/60 s of simulated time (``--frames``/``--screenshot`` runs). ``notice``:
    the window opens paused, saying it over the scene until R starts the level.
    """
    if offscreen:
        os.environ["SDL_VIDEODRIVER"] = "dummy"
    from chainfountain.app.session import Session
    from chainfountain.app.window import DEFAULT_SIZE, App

    lvl = _load_or_default(level)
    try:
        session = Session(lvl, source)
    except ValueError as exc:  # e.g. a level kind this simulator cannot build yet
        from chainfountain.errors import UserError

        raise UserError(f"cannot open level {lvl.meta.name!r}: {exc}") from None
    if paused:
        session.paused = True
    if notice is not None:
        session.hold(notice)
    app = App(session, size=size or DEFAULT_SIZE, offscreen=offscreen, projector=projector)
    return app.run(frames=frames, screenshot=screenshot)


def run_headless(level: Level, reason: str, out_dir: Path | None = None,
                 duration: float | None = None) -> int:
    """No display: say so and run ``level`` headless (outputs and a snapshot)."""
    from chainfountain.headless import default_out_dir

    out = out_dir or default_out_dir(level)
    print(f"chainfountain: no display ({reason}); running level {level.meta.name!r} "
          f"headless, writing to {out}", file=sys.stderr)
    from chainfountain.headless import RunSummary, describe_outputs, exit_status, run_level

    path = run_level(level, out, duration=duration, progress=True)
    summary = RunSummary.load(path)
    print(describe_outputs(path, summary))
    return exit_status(summary)


def run_default(level: Level | None = None, source: Path | None = None,
                size: tuple[int, int] | None = None) -> int:
    """Open the window on ``level``; without a display run it headless instead."""
    ok, why = display_available()
    lvl = _load_or_default(level)
    if not ok:
        return run_headless(lvl, why)
    return open_app(lvl, source, size=size)
