"""The gripped fold presets started from rest: does the fountain form, thread and hold?

Runs ``apparatus_fold_gripped`` (or ``--level``) from rest (``initial.mode = "stub"``,
``apparatus.starter``; :mod:`chainfountain.sim.apparatus.starter`) for ``--seconds``,
nudged at 0.1 s by each ``--seeds`` (at rest a nudge of the velocities changes nothing),
at the level's step times ``--dt-factor``. Prints one JSON line per run: when the end
guide caught the head, when the head was pinned to the lower table, when the starter let
go, how it ended, and per ``--window`` s after the hand-over the mean speed, the fountain's
top and the landing's offset from the first turn's radius.

Usage::

    python -m research.fold_from_rest --seconds 40 --seeds 0 1 2 3
    python -m research.fold_from_rest --level apparatus_special_gripped --dt-factor 0.5
"""

from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np

from chainfountain.level.library import shipped_dir

LEVELS = shipped_dir()


def run(name: str, seconds: float, seed: int, dt_factor: float, window: float,
        changes: dict[str, float]) -> dict:
    """One start from rest; its milestones and window means."""
    from chainfountain.errors import RunEnded
    from chainfountain.level import io
    from chainfountain.sim import Simulation
    from chainfountain.study.changes import with_changes

    level = io.load(LEVELS / f"{name}.toml")
    ch = {"initial.mode": "stub", "apparatus.starter": 3.0} \
        if level.sim.initial.mode != "stub" else {}
    ch.update(changes)
    if ch:
        level = with_changes(level, ch)
    level.sim.solver.dt *= dt_factor
    sim = Simulation(level.sim)
    app = sim.apparatus
    out: dict = {"level": name, "seed": seed, "step_ms": sim.apparatus.h * 1e3, "windows": []}
    wall = time.perf_counter()
    rows: list[tuple[float, float, float, float]] = []
    try:
        sim.advance(0.1)
        sim.nudge(seed)
        while sim.time < seconds - 1e-9:
            sim.advance(0.05)
            top = max(lk.body.position.y for lk in sim.chain.links)
            rows.append((sim.time, app.speed, top, app.landing_offset))
            if out.get("caught_s") is None and not math.isnan(app.head_caught_at):
                out["caught_s"] = round(app.head_caught_at, 3)
            if out.get("threaded_s") is None and app.head_pinned:
                out["threaded_s"] = round(sim.time, 2)
            if out.get("hand_over_s") is None and not app.starting:
                out["hand_over_s"] = round(sim.time, 2)
        out["ended"] = ""
    except RunEnded as exc:
        out["ended"] = f"{sim.time:.2f} s: {exc.plain}"
    out["wall_s"] = round(time.perf_counter() - wall, 1)
    r = np.array(rows)
    t0 = out.get("hand_over_s", math.inf)
    t = t0
    while len(r) and t + window <= r[-1, 0] + 1e-9:
        m = (r[:, 0] > t) & (r[:, 0] <= t + window)
        out["windows"].append({"t": round(t + window, 1),
                               "v": round(float(r[m, 1].mean()), 4),
                               "top": round(float(r[m, 2].mean()), 4),
                               "dr_cm": round(100 * float(np.nanmean(r[m, 3])), 2)})
        t += window
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="apparatus_fold_gripped")
    ap.add_argument("--seconds", type=float, default=40.0)
    ap.add_argument("--seeds", type=int, nargs="+", default=[0])
    ap.add_argument("--dt-factor", type=float, default=1.0)
    ap.add_argument("--window", type=float, default=5.0)
    ap.add_argument("--set", nargs="*", default=[], metavar="PATH=NUMBER")
    a = ap.parse_args()
    ch = {k: float(v) for k, v in (x.split("=", 1) for x in a.set)}
    for seed in a.seeds:
        print(json.dumps(run(a.level, a.seconds, seed, a.dt_factor, a.window, ch)), flush=True)


if __name__ == "__main__":
    main()
