"""Peak resident memory of long runs: a headless run and the window with a clip recording.

Usage::

    .venv/bin/python benchmarks/bench_memory.py [--headless-seconds 600] [--window-seconds 300]
        [--level classroom] [--only headless|window]

Each part runs in its own subprocess (``/usr/bin/time``-style peak from
``getrusage(RUSAGE_CHILDREN)``) and prints simulated seconds, wall seconds and peak
resident memory (MB):

- *headless*: ``chainfountain run LEVEL --headless --duration S`` (default 600 s
  simulated, the issue's "10-minute headless run");
- *window*: the window under ``SDL_VIDEODRIVER=dummy`` for S wall seconds (default
  300) with a clip being recorded the whole time (a new clip starts whenever one
  fills up) and random input every frame (``chainfountain.app.monkey``).
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time

WINDOW_SCRIPT = r"""
import os, sys, time, random
os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ["CHAINFOUNTAIN_NO_AUTOSAVE"] = "1"
from chainfountain.app import monkey
from chainfountain.app.session import Session
from chainfountain.app.window import App
from chainfountain.level import io, library
seconds, level = float(sys.argv[1]), sys.argv[2]
app = App(Session(io.load(library.resolve(level))), size=(1280, 760))
rng = random.Random(7)
held = []
t_end = time.perf_counter() + seconds
frames = clips = 0
while time.perf_counter() < t_end:
    if app.clip is None:
        app.toggle_clip()
        clips += 1
    monkey.events(rng, app.size, held)
    app.running = True
    app.run_frame()
    frames += 1
app.finish()
print(f"frames {frames}, clips started {clips}, simulated {app.session.sim.time:.1f} s")
"""


def _child(cmd: list[str], env: dict[str, str]) -> tuple[float, float, str]:
    """Run ``cmd``; return wall seconds, the peak RSS of the child (MB) and its stdout."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    t0 = time.perf_counter()
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    if r.returncode not in (0, 3):
        print(r.stderr[-2000:], file=sys.stderr)
        raise SystemExit(f"{cmd[:4]} exited with {r.returncode}")
    if peak <= before:
        print("  (peak below an earlier child's: the figure is an upper bound)")
    return wall, peak / 1024.0, r.stdout


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--headless-seconds", type=float, default=600.0)
    ap.add_argument("--window-seconds", type=float, default=300.0)
    ap.add_argument("--level", default="classroom")
    ap.add_argument("--only", choices=("headless", "window"))
    args = ap.parse_args()
    env = dict(os.environ)
    if args.only in (None, "window"):
        with tempfile.TemporaryDirectory() as home:  # clips go here, not to the user's folder
            env["CHAINFOUNTAIN_HOME"] = home
            wall, peak, out = _child([sys.executable, "-c", WINDOW_SCRIPT,
                                      str(args.window_seconds), args.level], env)
        print(f"window {args.level}, {args.window_seconds:g} s wall with a clip recording "
              f"and random input: peak RSS {peak:.0f} MB ({out.strip()})")
    if args.only in (None, "headless"):
        with tempfile.TemporaryDirectory() as tmp:
            wall, peak, _ = _child([sys.executable, "-m", "chainfountain", "run", args.level,
                                    "--headless", "--quiet", "--duration",
                                    str(args.headless_seconds), "--out", tmp], env)
        print(f"headless {args.level}, {args.headless_seconds:g} s simulated in {wall:.0f} s "
              f"wall: peak RSS {peak:.0f} MB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
