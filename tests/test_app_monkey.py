"""Monkey test: 20 s of random keys, clicks, drags, wheel turns and typing raise nothing."""

from __future__ import annotations

import os

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import math  # noqa: E402
import random  # noqa: E402
import time  # noqa: E402

import pygame  # noqa: E402

from chainfountain.app.session import Session  # noqa: E402
from chainfountain.app.window import App  # noqa: E402
from chainfountain.level import io  # noqa: E402
from chainfountain.sim.config import SimConfig  # noqa: E402

DURATION = 20.0

KEYS = [pygame.K_SPACE, pygame.K_RIGHT, pygame.K_PERIOD, pygame.K_s, pygame.K_r, pygame.K_f,
        pygame.K_t, pygame.K_h, pygame.K_F1, pygame.K_l, pygame.K_g, pygame.K_F12,
        pygame.K_RETURN, pygame.K_BACKSPACE, pygame.K_TAB, pygame.K_a, pygame.K_0,
        pygame.K_MINUS, pygame.K_ESCAPE, pygame.K_LEFT, pygame.K_DELETE]


def test_monkey(tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))
    cfg = SimConfig()
    cfg.feed.drop = 0.5
    cfg.feed.speed = 4.0
    cfg.chain.link_length = 0.03
    io.save(io.make_level("monkey level", "", cfg), tmp_path / "home" / "levels" / "m.toml")
    app = App(Session(io.make_level("monkey", "", cfg)), size=(1280, 760), offscreen=True)
    rng = random.Random(1234)
    w, h = app.size
    end = time.perf_counter() + DURATION
    frames = 0
    held: tuple[int, int] | None = None
    try:
        while time.perf_counter() < end:
            for _ in range(rng.randint(0, 4)):
                r = rng.random()
                if r < 0.3:
                    k = rng.choice(KEYS)
                    mod = rng.choice([0, 0, 0, pygame.KMOD_SHIFT, pygame.KMOD_CTRL])
                    uni = chr(k) if 32 <= k < 127 else ""
                    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=k, mod=mod,
                                                         unicode=uni, scancode=0))
                    if uni:
                        pygame.event.post(pygame.event.Event(pygame.TEXTINPUT, text=uni))
                    pygame.event.post(pygame.event.Event(pygame.KEYUP, key=k, mod=mod,
                                                         unicode=uni, scancode=0))
                elif r < 0.4:
                    text = rng.choice(["1e9", "-3", "nan", "0", "abc", "2.5", "1e-300", "."])
                    pygame.event.post(pygame.event.Event(pygame.TEXTINPUT, text=text))
                elif r < 0.7:
                    pos = (rng.randrange(w), rng.randrange(h))
                    btn = rng.choice([1, 1, 1, 2, 3])
                    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=pos,
                                                         button=btn))
                    held = pos
                elif r < 0.85 and held is not None:
                    pos = (held[0] + rng.randint(-60, 60), held[1] + rng.randint(-60, 60))
                    pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=pos,
                                                         rel=(pos[0] - held[0], pos[1] - held[1]),
                                                         buttons=(1, 0, 0)))
                    held = pos
                elif r < 0.93:
                    pos = held or (rng.randrange(w), rng.randrange(h))
                    pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONUP, pos=pos,
                                                         button=rng.choice([1, 2, 3])))
                    held = None
                else:
                    pygame.event.post(pygame.event.Event(pygame.MOUSEWHEEL, x=0,
                                                         y=rng.choice([-3, -1, 1, 2]),
                                                         flipped=False))
            if rng.random() < 0.01:  # a rebuild-only slider value far out of range
                app.set_field("chain.link_length", rng.choice([-1.0, 0.5, 1e-9, 0.02]))
            app.running = True  # Esc may ask to quit; keep going
            app.run_frame()
            frames += 1
            s = app.session
            assert math.isfinite(s.sim.time)
            for spec in (r.spec for r in app.rows):
                v = s.value(spec.path)
                assert spec.clamp(v)[0] == v  # every value stays inside the schema
    finally:
        app.finish()
    assert frames > 100
