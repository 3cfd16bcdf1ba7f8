"""The window's speed on the demonstration levels: real-time factor, frames per second and
the share of a frame spent drawing.

Usage::

    .venv/bin/python benchmarks/bench_app.py                  # every demo level, a window
    .venv/bin/python benchmarks/bench_app.py --level beaker --seconds 20
    .venv/bin/python benchmarks/bench_app.py --offscreen      # no display: drawing only

With a display (Xvfb: ``xvfb-run -s "-screen 0 1920x1080x24"``) it opens the real window,
1920x1080 in projector mode by default, on each level the picker lists as forming from rest
(or ``--level``), lets it run ``--warmup`` seconds from its start, then times ``--seconds``
of the window's own loop (the frame rate it chooses, the physics overlapping the copy to
the screen) and prints, per level: the real-time factor reached, the frames per second,
the wall time a frame spends drawing (the scene, the panel, the GUI) and its share of the
frame, the physics' cost per simulated second, and the share of the CPU the host took
from this virtual machine meanwhile (its "steal": a busy host slows everything down).
``--offscreen`` (SDL's dummy driver) times the drawing of one frame at the same size
instead, with no physics in real time.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path


def demo_levels() -> list[str]:
    """The levels the picker lists as the demonstrations (they form from rest)."""
    from chainfountain.app import paths

    rows = paths.list_levels()
    out = []
    for _label, path in rows[1:]:
        if path is None:
            break
        out.append(path.stem)
    return out


def cpu_steal() -> tuple[int, int]:
    """The host's stolen and all CPU time so far (jiffies, /proc/stat; zeros elsewhere): a
    virtual machine whose host is busy runs everything slower, and says so here."""
    try:
        fields = [int(x) for x in Path("/proc/stat").read_text().split("\n")[0].split()[1:]]
    except (OSError, ValueError):
        return 0, 0
    return (fields[7] if len(fields) > 7 else 0), sum(fields)


def time_window(name: str, size: tuple[int, int], projector: bool, warmup: float,
                seconds: float, offscreen: bool) -> dict:
    """Run ``name`` in the window and time it (see the module docstring)."""
    import pygame

    from chainfountain.app.session import Session
    from chainfountain.app.window import App
    from chainfountain.level import io, library

    path = library.resolve(name)
    app = App(Session(io.load(path), path), size=size, offscreen=offscreen,
              projector=projector)
    try:
        if offscreen:
            for _ in range(int(warmup * 60)):
                app.run_frame()
            draws = []
            for _ in range(int(seconds * 60)):
                t0 = time.perf_counter()
                app.draw()
                draws.append(time.perf_counter() - t0)
                app.run_frame()
            return {"draw_ms": 1e3 * statistics.median(draws)}
        clock = pygame.time.Clock()
        t_start = time.perf_counter()
        while time.perf_counter() - t_start < warmup:
            app.run_frame(clock.tick(app.target_fps()) / 1000.0)
        sim0, frames, draw, phys = app.session.sim.time, 0, 0.0, 0.0
        t0 = time.perf_counter()
        while time.perf_counter() - t0 < seconds and app.running:
            app.run_frame(clock.tick(app.target_fps()) / 1000.0)
            frames += 1
            draw += app.draw_last
            phys += app.physics_time
        wall = time.perf_counter() - t0
        simulated = app.session.sim.time - sim0
        fps = frames / wall
        return {"rtf": simulated / wall, "fps": fps, "draw_ms": 1e3 * draw / frames,
                "draw_share": (draw / frames) * fps,
                "physics_cost": phys / max(simulated, 1e-9),
                "stopped": app.session.stopped}
    finally:
        app.finish()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", action="append", help="a level (default: every demo level)")
    ap.add_argument("--seconds", type=float, default=10.0, help="wall seconds timed")
    ap.add_argument("--warmup", type=float, default=10.0,
                    help="wall seconds run first (the fountain forms)")
    ap.add_argument("--size", default="1920x1080", help="window size WxH")
    ap.add_argument("--no-projector", action="store_true", help="without projector mode")
    ap.add_argument("--offscreen", action="store_true", help="time the drawing only")
    args = ap.parse_args()
    if args.offscreen:
        os.environ["SDL_VIDEODRIVER"] = "dummy"
    elif not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY"):
        print("no display: run under xvfb-run, or with --offscreen", file=sys.stderr)
        return 2
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    os.environ.setdefault("CHAINFOUNTAIN_HOME", str(Path("/tmp/chainfountain-bench")))
    os.environ["CHAINFOUNTAIN_NO_AUTOSAVE"] = "1"
    w, h = (int(v) for v in args.size.lower().split("x"))
    names = args.level or demo_levels()
    mode = "off-screen, drawing only" if args.offscreen else "a window"
    print(f"{w}x{h}{'' if args.no_projector else ', projector mode'}, {mode}; "
          f"{args.warmup:g} s from each level's start, then {args.seconds:g} s timed")
    for name in names:
        steal0, all0 = cpu_steal()
        r = time_window(name, (w, h), not args.no_projector, args.warmup, args.seconds,
                        args.offscreen)
        steal1, all1 = cpu_steal()
        stolen = 100.0 * (steal1 - steal0) / max(all1 - all0, 1)
        if args.offscreen:
            print(f"  {name:28s} drawing {r['draw_ms']:5.1f} ms a frame")
            continue
        note = f"  (stopped: {r['stopped'][:60]})" if r["stopped"] else ""
        print(f"  {name:28s} real-time x{r['rtf']:.2f}  {r['fps']:5.1f} frames/s  drawing "
              f"{r['draw_ms']:5.1f} ms = {100 * r['draw_share']:3.0f} % of a frame  physics "
              f"{r['physics_cost']:.2f} s per simulated s  host steal {stolen:.0f} %{note}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
