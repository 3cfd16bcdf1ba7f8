"""Every control of the window, given a bad number or a bad text, keeps a value in its range.

For each field :func:`chainfountain.app.controls.control_fields` builds a row for (a fed
level and an apparatus level), the window's setter, its text entry handler and its slider
get non-finite, huge, zero, negative and out-of-range values and texts that are not
numbers. Nothing raises, the field's value stays finite and inside the range its
:class:`~chainfountain.app.controls.FieldSpec` declares, and the session says what it did
with the value (clamped, refused, applied) instead of crashing; the window still draws
frames afterwards.

Setting a field can rebuild the simulation (0.1-0.5 s), so each field gets NaN and a
rotating share of the other values (:func:`share`): every value reaches several fields,
and the suite stays within a minute. Texts and slider positions reach a field through the
same setter as numbers, so they run on the fed level only (an apparatus level rebuilds
its scene for most fields, about a second each).
"""

from __future__ import annotations

import math
import os

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import pytest  # noqa: E402

from chainfountain.app.controls import FieldSpec  # noqa: E402
from chainfountain.app.session import Session  # noqa: E402
from chainfountain.app.window import App  # noqa: E402
from tests import shipped

NUMBERS = [math.nan, math.inf, -math.inf, 1e308, -1e308, 0.0, -0.0, -1.0, -1e-9, 5e-324,
           1e-300, 1e9]
"""Values given to every field's setter (schema units)."""

TEXTS = ["nan", "abc", "1e999", "-1e999", "", " ", "--1", "1,5", "inf", "-inf", "1e308",
         "-0.0", "0", "-5", "0x10", "1e-320", "e", ".", "+"]
"""Texts typed into every field's entry (display units)."""

SLIDER = [math.nan, -1e9, -1.0, 0.0, 0.4, 1.0, 500.0, 999.6, 1000.0, 1e9, math.inf]
"""Slider positions (0 .. 1000 are the slider's own)."""


def share(pool: list, i: int, n: int = 4) -> list:
    """``pool[0]`` and ``n - 1`` more of ``pool``, rotating with the field's index ``i``."""
    rest = pool[1:]
    return [pool[0]] + [rest[(i * (n - 1) + j) % len(rest)] for j in range(n - 1)]


def in_range(spec: FieldSpec, v: float) -> bool:
    if not math.isfinite(v):
        return False
    if spec.lo is not None and (v < spec.lo or (v == spec.lo and not spec.lo_incl)):
        return False
    if spec.hi is not None and (v > spec.hi or (v == spec.hi and not spec.hi_incl)):
        return False
    return True


@pytest.fixture(params=["classroom", "apparatus_floor"])
def app(request, tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    a = App(Session(shipped.level(request.param)), size=(1280, 760),
            offscreen=True)
    yield a
    a.finish()


@pytest.fixture(autouse=True)
def said(app, monkeypatch) -> list[str]:
    """Every message the session says (its own list keeps only the newest)."""
    out: list[str] = []
    say = app.session.say

    def record(text: str) -> str:
        out.append(text)
        return say(text)

    monkeypatch.setattr(app.session, "say", record)
    return out


def test_every_field_keeps_a_value_in_range(app, said):
    rows = list(app.rows)
    assert rows, "the window builds controls"
    for i, row in enumerate(rows):
        path = row.spec.path
        for value in share(NUMBERS, i):
            row = app._row(path)
            assert row is not None, path  # the row survives rebuilds of the panel
            n = len(said)
            old = app.session.value(path)
            app.set_field(path, value)
            now = app.session.value(path)
            assert in_range(row.spec, now), (path, value, now)
            if not in_range(row.spec, value) or (value != old and now == old):
                assert said[n:], (path, value)  # clamped or refused: said so
            shown = app._row(path).entry.get_text()
            assert math.isfinite(float(shown)), (path, value, shown)
        app.run_frame()


@pytest.mark.parametrize("app", ["classroom"], indirect=True)
def test_every_entry_takes_any_text(app, said):
    for i, path in enumerate([r.spec.path for r in app.rows]):
        for text in share(TEXTS, i):
            row = app._row(path)
            n = len(said)
            app._on_entry(row.entry, text)
            now = app.session.value(path)
            assert in_range(row.spec, now), (path, text, now)
            try:
                typed = float(text)
            except ValueError:
                typed = math.nan
            if not math.isfinite(typed):
                assert said[n:], (path, text)
            assert math.isfinite(float(app._row(path).entry.get_text())), (path, text)
        app.run_frame()


@pytest.mark.parametrize("app", ["classroom"], indirect=True)
def test_every_slider_takes_any_position(app):
    for i, path in enumerate([r.spec.path for r in app.rows]):
        for pos in share(SLIDER, i, 3):
            row = app._row(path)
            app._on_slider(row.slider, pos)
            app.update(1 / 60)  # applies a pending rebuild-only value
            assert in_range(app._row(path).spec, app.session.value(path)), (path, pos)
    for _ in range(3):
        app.run_frame()
    assert app.session.sim.time >= 0.0
