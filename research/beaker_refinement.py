"""The beaker level against Biggins and Warner, with its error bars: nudged starts (the
pile is chaotic), half the time step and twice the solver iterations.

    .venv/bin/python -m research.beaker_refinement [--level beaker] [--seconds 30]
        [--seeds 0 1 2] [--jobs 2] [--set beaker.drop=1.5 ...]

Each run starts from rest and is averaged over its last ``--window`` seconds (the fountain
forms in about 4 s). It prints one row per run and then, per setting, the mean over the
seeds with their spread: the chain speed (links the floor took), the top above the rim,
the pick-up's depth and the pile's push ``alpha`` read off the speed
(``1 - g H/v^2``), off the rise of a zero-width fountain (``h/(H + h)``) and off the
paper's catenary through the measured ends (``1 - Tbar_0``). About 20 s of wall time per
run of 30 s on one core.
"""

from __future__ import annotations

import argparse
import json
import statistics
import tempfile
from pathlib import Path

from joblib import Parallel, delayed

from chainfountain.headless import run_and_record
from chainfountain.level import io, library
from chainfountain.study import with_changes

SETTINGS = {
    "level": {},
    "dt/2": {"solver.dt": 0.5},
    "dt/4": {"solver.dt": 0.25},
    "2x iterations": {"solver.iterations": 2.0},
}
"""Refinements: factors applied to the level's own values."""


def _number(text: str):
    try:
        return int(text)
    except ValueError:
        try:
            return float(text)
        except ValueError:
            return {"true": True, "false": False}.get(text, text)


def one(level_text: str, name: str, factors: dict, seed: int, seconds: float,
        window: float) -> dict:
    """One run: the level with ``factors`` applied and ``seed``; its ``beaker`` figures."""
    import tomllib

    lv = io.parse_level(tomllib.loads(level_text), "level")
    changes = {}
    for path, f in factors.items():
        sec, field = path.split(".")
        v = getattr(getattr(lv.sim, sec), field)
        changes[path] = type(v)(v * f)
    changes["initial.seed"] = seed
    changes["recording.window"] = window
    lv = with_changes(lv, changes)
    with tempfile.TemporaryDirectory() as d:
        path, _ = run_and_record(lv, Path(d), seconds, progress=False, snapshot=False)
        s = json.loads(path.read_text())
    b = s["beaker"]
    a = b["alpha"]
    return {"setting": name, "seed": seed, "steady_since": s["steady_since_s"],
            "window": b["window_s"], "v": b["speed"], "rise_rim": b["rise_above_rim"],
            "pickup_y": b["pickup"][1], "H": b["drop_from_pickup"],
            "a_speed": a["from_speed"], "a_rise": a["from_rise"],
            "a_paper": a.get("from_paper_catenary"), "rtf": s["realtime_factor"]}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="beaker")
    ap.add_argument("--seconds", type=float, default=30.0)
    ap.add_argument("--window", type=float, default=10.0, help="averaged last seconds")
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2])
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", nargs="+", default=["level", "dt/2", "2x iterations"],
                    choices=list(SETTINGS))
    ap.add_argument("--set", nargs="+", default=[], metavar="FIELD=VALUE",
                    help="change the level first (e.g. chain.bend_limit=0)")
    a = ap.parse_args()
    lv = io.load(library.resolve(a.level))
    if a.set:
        lv = with_changes(lv, {k: _number(v) for k, v in (s.split("=", 1) for s in a.set)})
    text = io.dumps(lv)
    jobs = [(name, SETTINGS[name], seed) for name in a.only for seed in a.seeds]
    rows = Parallel(n_jobs=a.jobs)(delayed(one)(text, n, f, s, a.seconds, a.window)
                                  for n, f, s in jobs)
    print(f"{lv.meta.name}{' ' + ' '.join(a.set) if a.set else ''}: {a.seconds:g} s from "
          f"rest, the last {a.window:g} s averaged")
    print("| setting | seed | steady since (s) | v (m/s) | top above rim (m) | pick-up y (m) "
          "| alpha: speed | rise | paper's curve | real time |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        ap_ = "n/a" if r["a_paper"] is None else f"{r['a_paper']:.3f}"
        print(f"| {r['setting']} | {r['seed']} | {r['steady_since']} | {r['v']:.3f} | "
              f"{r['rise_rim']:.3f} | {r['pickup_y']:.4f} | {r['a_speed']:.3f} | "
              f"{r['a_rise']:.3f} | {ap_} | {r['rtf']:.2f}x |")
    print("\nmeans over the seeds (+- their standard deviation):")
    for name in a.only:
        sel = [r for r in rows if r["setting"] == name]

        def ms(key: str, fmt: str = ".3f", sel=sel) -> str:
            xs = [r[key] for r in sel if r[key] is not None]
            sd = statistics.stdev(xs) if len(xs) > 1 else float("nan")
            return f"{statistics.mean(xs):{fmt}} +- {sd:{fmt}}"

        print(f"  {name}: v {ms('v')} m/s, top {ms('rise_rim')} m above the rim, alpha "
              f"{ms('a_speed')} (speed), {ms('a_rise')} (rise), {ms('a_paper')} (paper's "
              "curve)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
