"""An offscreen window on a shipped level for the app tests (SDL's dummy driver is set by
the tests that import pygame)."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

from chainfountain.app.session import Session
from chainfountain.app.window import App
from tests import shipped


@contextmanager
def shipped_app(name: str, home: Path, monkeypatch: pytest.MonkeyPatch,
                size: tuple[int, int] = (1280, 760)) -> Iterator[App]:
    """The window on shipped level ``name``, its settings kept under ``home``."""
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(home))
    a = App(Session(shipped.level(name)), size=size, offscreen=True)
    try:
        yield a
    finally:
        a.finish()
