"""A machine tuned while it runs: one field changed as the window's slider changes it.

Opens LEVEL as the window does (its own start; ``--laid``: laid on its path), runs
``--at`` simulated seconds, sets FIELD to each VALUE (``Session.set_field``, live), runs
``--after`` seconds more and
prints the chain speed every ``--every`` seconds, or when and why the run stopped. One run
per value and change time (``--starts N`` changes at ``--at``, ``--at + 0.7``, ... s:
different phases of the fold's 2.1-s landing swing); a chaotic machine, so near an edge a
single run says "this start held", not "every start holds". With ``--starts`` above 1
a last line per value says how many held.

Usage::

    python -m research.live_tuning apparatus_special 'carts[1].mass' 0.054 0.056 0.059 0.060
    python -m research.live_tuning apparatus_floor 'carts[0].mass' 0.015 0.020 0.025 \\
        --at 8 --after 30
    python -m research.live_tuning apparatus_fold 'carts[1].mass' 0.039 0.043 \\
        --starts 3 --after 40 --every 10
    python -m research.live_tuning apparatus_special 'carts[1].mass' 0.056 0.059 \\
        --also 'carts[0].mass=0.019' --starts 3 --after 40 --every 10

About 50 s of wall time per fold run of 70 simulated seconds, 15 s per floor run.
docs/apparatus.md, "Tuning the damped folds live" and "Tuning the floor machine live".
"""

from __future__ import annotations

import argparse
import os
from concurrent.futures import ProcessPoolExecutor


def run(level: str, field: str, value: float, at: float, after: float, every: float,
        also: tuple[tuple[str, float], ...] = (),
        catch: tuple[float, float, float] | None = None, laid: bool = False) -> str:
    """One run; a line with the speeds after the change, or where it stopped. ``also``:
    more fields set at the same moment, before ``field``; ``catch``: the 'fold' guide's
    capture band (m), margin (deg) and close rate (m/s), given to the apparatus
    (:meth:`~chainfountain.sim.apparatus.Apparatus.retune`; a study of the catch)."""
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    import math

    from chainfountain.app.session import Session
    from chainfountain.level import io, library
    from chainfountain.sim.apparatus import Tuning
    from chainfountain.study.changes import laid_on_path

    lvl = io.load(library.resolve(level))
    s = Session(laid_on_path(lvl) if laid else lvl)
    if catch is not None:  # the catch is read while stepping (a rebuild would drop it)
        s.sim.apparatus.retune(Tuning(fold_capture=(catch[0], math.radians(catch[1])),
                                      fold_close_rate=catch[2]))
    s.advance(at)
    for other, v in also:
        res = s.set_field(other, v)
        if not res.ok:
            return f"{other} = {v:g}: refused ({res.message})"
    res = s.set_field(field, value)
    if not res.ok:
        return f"{field} = {value:g}: refused ({res.message})"
    speeds = []
    for _ in range(int(round(after / every))):
        s.advance(every)
        if s.stopped:
            break
        speeds.append(s.sim.apparatus.speed if s.sim.apparatus is not None else s.sim.feed.speed)
    head = "".join(f"{o} = {v:g}, " for o, v in also)
    line = f"{head}{field} = {value:g} at {at:g} s: speed every {every:g} s: " + \
        " ".join(f"{v:.3f}" for v in speeds)
    if s.stopped:
        line += f"; stopped: {s.stopped}"
    else:
        line += f"; held {after:g} s ({min(speeds):.3f}-{max(speeds):.3f} m/s)"
    return line


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("level")
    ap.add_argument("field", help="a live field, e.g. 'carts[1].mass'")
    ap.add_argument("values", type=float, nargs="+")
    ap.add_argument("--at", type=float, default=10.0, help="simulated s before the change")
    ap.add_argument("--after", type=float, default=60.0, help="simulated s after it")
    ap.add_argument("--every", type=float, default=5.0, help="s between printed speeds")
    ap.add_argument("--starts", type=int, default=1,
                    help="runs per value, changed 0.7 s apart (default 1)")
    ap.add_argument("--also", action="append", default=[], metavar="FIELD=VALUE",
                    help="another field set at the same moment (repeatable)")
    ap.add_argument("--catch", type=float, nargs=3, metavar=("BAND_M", "MARGIN_DEG", "CLOSE"),
                    help="the 'fold' guide's catch: capture band (m), angular margin (deg) "
                    "and close rate (m/s) (default: the package's)")
    ap.add_argument("--laid", action="store_true",
                    help="start laid on its path, moving (as the steady-state studies do), "
                    "not from the level's own start")
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args()
    also = []
    for item in args.also:
        name, _, text = item.partition("=")
        try:
            also.append((name, float(text)))
        except ValueError:
            ap.error(f"--also: {item!r} is not FIELD=NUMBER")
    if args.jobs < 1:
        ap.error(f"--jobs: {args.jobs} is not a number of processes; allowed: 1 or more")
    if args.starts < 1:
        ap.error(f"--starts: {args.starts} is not a number of runs; allowed: 1 or more")
    with ProcessPoolExecutor(args.jobs) as pool:
        futures = {v: [pool.submit(run, args.level, args.field, v, args.at + 0.7 * i,
                                   args.after, args.every, tuple(also),
                                   tuple(args.catch) if args.catch else None, args.laid)
                       for i in range(args.starts)]
                   for v in args.values}
        for v, fs in futures.items():
            lines = [f.result() for f in fs]
            for line in lines:
                print(line, flush=True)
            if args.starts > 1:
                held = sum("; held" in line for line in lines)
                head = "".join(f"{o} = {x:g}, " for o, x in also)
                print(f"{head}{args.field} = {v:g}: held {held} of {args.starts}", flush=True)


if __name__ == "__main__":
    main()
