"""Random input for the window: keys, typing, clicks, drags, wheel turns, resizes.

:func:`play` drives an :class:`~chainfountain.app.window.App` with a seeded random
stream of pygame events for a number of frames and reports the frames run and the
process's peak resident memory. The suite runs a short stretch of it
(``tests/app/test_monkey.py``); ``benchmarks/bench_monkey.py`` runs it for minutes.
The events are seeded, so every machine sends the same input; the window runs as on a
screen (under ``SDL_VIDEODRIVER=dummy``), spending at most its frame budget on physics, so
how far the simulation gets between two events depends on the machine's speed.
"""

from __future__ import annotations

import math
import random
import resource
from dataclasses import dataclass

import pygame

KEYS = (pygame.K_SPACE, pygame.K_RIGHT, pygame.K_PERIOD, pygame.K_s, pygame.K_r, pygame.K_f,
        pygame.K_t, pygame.K_h, pygame.K_i, pygame.K_F1, pygame.K_l, pygame.K_g, pygame.K_F12,
        pygame.K_RETURN, pygame.K_BACKSPACE, pygame.K_TAB, pygame.K_a, pygame.K_0,
        pygame.K_MINUS, pygame.K_ESCAPE, pygame.K_LEFT, pygame.K_DELETE, pygame.K_e,
        pygame.K_v, pygame.K_u, pygame.K_w, pygame.K_p, pygame.K_m, pygame.K_UP, pygame.K_DOWN)
"""Keys pressed at random (with Shift or Ctrl now and then)."""

TEXTS = ("1e9", "-3", "nan", "0", "abc", "2.5", "1e-300", ".", "inf", "30", "0.001")
"""Text typed at random into whatever has the focus."""


@dataclass
class Report:
    """What a stretch of random input did."""

    frames: int
    peak_rss_mb: float
    """Peak resident memory of this process so far (MB)."""


def peak_rss_mb() -> float:
    """Peak resident memory of this process (MB; Linux reports kB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _post(kind: int, **attrs: object) -> None:
    pygame.event.post(pygame.event.Event(kind, **attrs))


def events(rng: random.Random, size: tuple[int, int], held: list) -> None:
    """Post zero to four random events (``held``: the pressed mouse position, or empty)."""
    w, h = size
    for _ in range(rng.randint(0, 4)):
        r = rng.random()
        if r < 0.3:
            k = rng.choice(KEYS)
            mod = rng.choice((0, 0, 0, pygame.KMOD_SHIFT, pygame.KMOD_CTRL))
            uni = chr(k) if 32 <= k < 127 else ""
            _post(pygame.KEYDOWN, key=k, mod=mod, unicode=uni, scancode=0)
            if uni:
                _post(pygame.TEXTINPUT, text=uni)
            _post(pygame.KEYUP, key=k, mod=mod, unicode=uni, scancode=0)
        elif r < 0.4:
            _post(pygame.TEXTINPUT, text=rng.choice(TEXTS))
        elif r < 0.7:
            pos = (rng.randrange(w), rng.randrange(h))
            _post(pygame.MOUSEBUTTONDOWN, pos=pos, button=rng.choice((1, 1, 1, 2, 3)))
            held[:] = [pos]
        elif r < 0.85 and held:
            p0 = held[0]
            pos = (p0[0] + rng.randint(-60, 60), p0[1] + rng.randint(-60, 60))
            _post(pygame.MOUSEMOTION, pos=pos, rel=(pos[0] - p0[0], pos[1] - p0[1]),
                  buttons=(1, 0, 0))
            held[:] = [pos]
        elif r < 0.93:
            pos = held[0] if held else (rng.randrange(w), rng.randrange(h))
            _post(pygame.MOUSEBUTTONUP, pos=pos, button=rng.choice((1, 2, 3)))
            held.clear()
        else:
            _post(pygame.MOUSEWHEEL, x=0, y=rng.choice((-3, -1, 1, 2)), flipped=False)


def play(app, frames: int, seed: int = 1234, check=None) -> Report:
    """Drive ``app`` (an :class:`~chainfountain.app.window.App`) with random input
    for ``frames`` frames. Now and then a rebuild-only field gets an extreme value and the
    window is resized. ``check(app)`` runs after every frame (assertions of the caller)."""
    rng = random.Random(seed)
    held: list = []
    for _ in range(frames):
        events(rng, app.size, held)
        r = rng.random()
        if r < 0.01:
            app.set_field("chain.link_length", rng.choice((-1.0, 0.5, 1e-9, 0.02, 0.001)))
        elif r < 0.015:
            app.set_field("solver.dt", rng.choice((0.02, 1e-3, 2.5e-4, 1e9, math.nan)))
        elif r < 0.018:
            app.resize(rng.choice(((1280, 760), (900, 600), (1600, 1000), (400, 300))))
        app.running = True  # Esc may ask to quit; keep going
        app.run_frame()
        if check is not None:
            check(app)
    return Report(frames=frames, peak_rss_mb=peak_rss_mb())
