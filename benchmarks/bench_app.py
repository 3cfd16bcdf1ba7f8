"""Frame rate and real-time factor of the app on the default level (one core).

Usage::

    .venv/bin/python benchmarks/bench_app.py [--seconds 5] [--level LEVEL] [--links N]
    .venv/bin/python benchmarks/bench_app.py --window      # real window (needs a display)

Off-screen (default, SDL dummy driver) it runs the app's frame loop with each
frame advancing 1/60 s of simulated time and times the physics and the rest of
the frame (events, GUI, drawing) separately, then prints the frame rate the
app could hold in real time and the real-time factor it reaches at 60 frames
per second. The flip to a real screen is not included (about 1 ms on a desktop;
far more under Xvfb). ``--window`` runs the real loop on the display and
prints the measured frame rate and real-time factor.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=5.0, help="simulated seconds to time")
    ap.add_argument("--warmup", type=float, default=1.0, help="simulated seconds not timed")
    ap.add_argument("--level", help="level file or name (default: the built-in default)")
    ap.add_argument("--links", type=int, help="override the link length to get about N links")
    ap.add_argument("--window", action="store_true", help="time the real window loop")
    args = ap.parse_args()
    if not args.window:
        os.environ["SDL_VIDEODRIVER"] = "dummy"
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    os.environ.setdefault("CHAINFOUNTAIN_HOME", str(Path("/tmp/chainfountain-bench")))

    from chainfountain.app.session import Session, default_level
    from chainfountain.app.window import App
    from chainfountain.level import io, library

    level = io.load(library.resolve(args.level)) if args.level else default_level()
    if args.links:
        sess = Session(level)
        ref = sess.sim.reference
        if ref is None:
            print("no reference fountain: --links needs a tensile feed", file=sys.stderr)
            return 2
        level.sim.chain.link_length = ref.arc_length / args.links
    sess = Session(level)
    app = App(sess, offscreen=not args.window)
    links = sess.sim.n_links
    fps = 60
    if args.window:
        app.run_frame()
        frames = 0
        clock_t0 = time.perf_counter()
        sim0 = sess.sim.time
        import pygame

        clock = pygame.time.Clock()
        work = phys = 0.0
        while time.perf_counter() - clock_t0 < args.seconds:
            app.run_frame(clock.tick(app.target_fps()) / 1000.0)
            frames += 1
            work += app.work_time
            phys += app.physics_time
        wall = time.perf_counter() - clock_t0
        app.finish()
        print(f"level {level.meta.name}: {links} links, dt {sess.sim.dt * 1e3:g} ms (window)")
        simulated = sess.sim.time - sim0
        print(f"  {frames / wall:.1f} frames/s, real-time factor {simulated / wall:.2f}")
        print(f"  per frame: events, GUI and drawing {work / frames * 1e3:.1f} ms, physics "
              f"{phys / frames * 1e3:.1f} ms (during the copy to the screen); the physics "
              f"costs {phys / max(simulated, 1e-9):.2f} s per simulated second")
        return 0

    warm = int(args.warmup * fps)
    for _ in range(warm):
        app.run_frame()
    phys: list[float] = []
    other: list[float] = []
    n = int(args.seconds * fps)
    for _ in range(n):
        t0 = time.perf_counter()
        app.run_frame()
        total = time.perf_counter() - t0
        phys.append(app.physics_time)
        other.append(total - app.physics_time)
    app.finish()
    p = statistics.mean(phys)
    o = statistics.mean(other)
    frame = p + o
    rt_fps = 1.0 / frame
    rtf60 = min(1.0, max(0.0, (1.0 / fps - o)) / p) if p > 0 else 1.0
    print(f"level {level.meta.name}: {links} links, dt {sess.sim.dt * 1e3:g} ms, "
          f"{round(1 / fps / sess.sim.dt)} steps per frame (off-screen, one core)")
    print(f"  physics {p * 1e3:.2f} ms per 1/60 s simulated, "
          f"drawing+GUI {o * 1e3:.2f} ms per frame")
    print(f"  {rt_fps:.1f} frames/s in real time (physics + drawing, no flip)")
    print(f"  real-time factor at 60 frames/s: {rtf60:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
