"""Random input to the window for minutes: frames run, peak memory, exceptions (none).

Usage::

    .venv/bin/python benchmarks/bench_monkey.py [--minutes 10] [--seed 1234] [--level NAME]

Drives the window (``SDL_VIDEODRIVER=dummy``, as on a screen) with
:func:`chainfountain.app.monkey.play`: random keys, typing, clicks, drags, wheel turns,
extreme field values, resizes, level loads (L), saves (Ctrl+S), clips (G) and
screenshots (F12), in chunks of 500 frames until the time is up, and prints frames,
frames per second and the peak resident memory after each chunk. An exception ends
the script with a traceback (exit status 1). The suite runs 600 frames of the same
(``tests/app/test_monkey.py``).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
os.environ["CHAINFOUNTAIN_NO_AUTOSAVE"] = "1"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--minutes", type=float, default=10.0)
    ap.add_argument("--seed", type=int, default=1234)
    ap.add_argument("--level", default="classroom")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as home:
        os.environ["CHAINFOUNTAIN_HOME"] = home  # saves, clips, screenshots go here
        from chainfountain.app import monkey
        from chainfountain.app.session import Session
        from chainfountain.app.window import App
        from chainfountain.level import io, library

        app = App(Session(io.load(library.resolve(args.level))), size=(1280, 760))
        t0 = time.perf_counter()
        frames, chunk = 0, 0
        try:
            while time.perf_counter() - t0 < 60.0 * args.minutes:
                r = monkey.play(app, 500, seed=args.seed + chunk)
                frames += r.frames
                chunk += 1
                el = time.perf_counter() - t0
                print(f"{el:7.0f} s: {frames} frames ({frames / el:.0f} per s), peak RSS "
                      f"{r.peak_rss_mb:.0f} MB, level {app.session.level.meta.name}",
                      flush=True)
        finally:
            app.finish()
    print(f"{args.minutes:g} min of random input: {frames} frames, no exception, peak RSS "
          f"{monkey.peak_rss_mb():.0f} MB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
