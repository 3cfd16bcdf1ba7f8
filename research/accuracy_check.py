"""Check the error model's promise: fountains run at the settings it chooses land within its bounds.

For each fountain (the seven of ``research/error_model.py`` and ``--random`` admissible
launches drawn with ``--seed``: speed 3.5-8 m/s, launch angle 55-82 deg, drop 0.5-3 m, floor
pull ``Tbar_E`` 0-0.25, kept when inside the model's domain and at most 10 m in flight),
:func:`chainfountain.sim.accuracy.choose` picks link length, step and iterations for each
``--accuracy``; the fountain is run from the catenary (settled ``--settle`` s, averaged
``--window`` s) and every figure's measured error is compared with its bound.

Usage::

    python -m research.accuracy_check --accuracy 0.01 0.005 --random 8 --jobs 2
    python -m research.accuracy_check --only-random --seed 2 --random 12   # fresh launches
"""

from __future__ import annotations

import argparse
import json
import math
import random
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from research import error_model

KEYS = {"vertex_y": "h", "vertex_x": "vertex_x", "landing_x": "l"}


def launches(n: int, seed: int) -> dict[str, tuple[float, float, float, float]]:
    from chainfountain.sim import accuracy
    from chainfountain.sim.reference import LaunchReference

    rng = random.Random(seed)
    out: dict[str, tuple[float, float, float, float]] = {}
    while len(out) < n:
        v, a = rng.uniform(3.5, 8.0), rng.uniform(55.0, 82.0)
        H, te = rng.uniform(0.5, 3.0), rng.uniform(0.0, 0.25)
        try:
            ref = LaunchReference.from_launch(v, math.radians(a), H, TE_bar=te)
        except (ValueError, ZeroDivisionError):
            continue
        if not (ref.q > 0 and ref.h > 0) or accuracy.in_domain(ref) is not None:
            continue
        if accuracy.flight_length(ref) > 10.0:
            continue
        out[f"rand{len(out)}"] = (round(v, 2), round(a, 1), round(H, 2), round(te, 3))
    return out


def one(job: tuple) -> dict:
    name, acc, settle, window = job
    from chainfountain.refine import measure
    from chainfountain.sim import accuracy

    f = error_model.fountain(name)
    from chainfountain.sim.reference import LaunchReference

    ref = LaunchReference.from_launch(f.v, f.alpha0, f.H, TE_bar=max(0.0, f.TE_bar))
    est = accuracy.choose(ref, acc)
    s = est.settings
    r = measure(error_model.config(name, s.link_length, s.dt, s.iterations),
                settle=settle, window=window)
    return {"name": name, "acc": acc, "settings": s, "links": r.links, "bounds": est.bounds,
            "measured": {k: r.errors[v] for k, v in KEYS.items()}, "spread": r.spread,
            "rtf": r.realtime_factor, "cost": est.cost,
            # the run as a row of research/error_model.py's grid (to refit on)
            "row": {"fountain": name, "L": s.link_length, "dt": s.dt,
                    "iterations": s.iterations, "links": r.links, "q": f.q, "k": f.k,
                    "v": f.v, "h": f.h, "TE_bar": f.TE_bar, "errors": r.errors,
                    "stat": r.stat, "stretch": r.stretch, "spread": r.spread,
                    "rtf": r.realtime_factor}}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--accuracy", type=float, nargs="+", default=[0.01, 0.005])
    ap.add_argument("--random", type=int, default=8)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--settle", type=float, default=1.5)
    ap.add_argument("--window", type=float, default=3.0)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--json", type=Path, help="write the runs as error_model.py grid rows")
    ap.add_argument("--only-random", action="store_true",
                    help="only the random launches (fountains the model was not fitted on)")
    a = ap.parse_args(argv)
    if a.only_random:
        error_model.FOUNTAINS.clear()
    for name, spec in launches(a.random, a.seed).items():
        error_model.FOUNTAINS[f"s{a.seed}{name}"] = {"launch": spec}
    jobs = [(n, acc, a.settle, a.window) for acc in a.accuracy for n in error_model.FOUNTAINS]
    misses = 0
    rows = []
    with ProcessPoolExecutor(max_workers=a.jobs) as ex:
        for r in ex.map(one, jobs):
            rows.append(r["row"])
            s = r["settings"]
            over = [k for k in KEYS if abs(r["measured"][k]) > r["bounds"][k]]
            misses += bool(over)
            spec = error_model.FOUNTAINS[r["name"]]
            print(f"{r['name']:10s} {str(spec.get('launch', spec.get('target'))):28s} "
                  f"acc {r['acc']:.1%}: L {s.link_length * 1e3:4.0f} mm dt {s.dt * 1e6:6.2f} us "
                  f"it {s.iterations:2d} n {r['links']:4d} | "
                  + " ".join(f"{k[:8]} {r['measured'][k]:+.2%}/{r['bounds'][k]:.2%}" for k in KEYS)
                  + f" | spread {r['spread']:.2%} RTF {r['rtf']:.2f} (model {1 / r['cost']:.2f})"
                  + (f"  OVER: {', '.join(over)}" if over else ""), flush=True)
    print(f"{misses} of {len(jobs)} runs beyond a bound")
    if a.json:
        a.json.write_text(json.dumps(rows, indent=1))
    return 0 if misses == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
