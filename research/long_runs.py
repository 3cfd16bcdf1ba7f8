"""Self-formed long runs of the fed fountains: the worst window of each figure.

Each fed level starts from rest on its short stub (``initial.mode = "stub"``), forms its
fountain on its own and runs ``--duration`` simulated seconds (default 120) at the
level's own solver settings. The run is cut into ``--window``-second windows (default
10 s); from ``--skip`` seconds on (default 20 s, after every shipped level has formed)
each window's time averages are compared with the paper's inverted catenary
(``docs/convergence.md``). The script prints, per level, when the fountain became steady
and the worst window of each figure:

- vertex y, vertex x, landing: relative error of the window mean against the theory;
- spread: the window mean of the instantaneous link-speed spread (max - min)/mean;
- stretch: the largest total joint gap over the chain length in the window;
- growth: the spread's last window over its first (a growing link-scale mode shows
  as growth well above 1).

Usage::

    python -m research.long_runs                          # every ordinary fed level
    python -m research.long_runs classroom wide_low --duration 60 --jobs 2

Cost: the ordinary levels run at 1-5x real time (2-2.5 min for 120 s of
``paper_tall_fine``); fountain D's presets at about 0.05x (40 min each), so they
are run only when named.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from chainfountain.level.library import shipped_dir

LEVELS = shipped_dir()
ORDINARY = ("classroom", "paper_tall", "paper_tall_fine", "wide_low")
FIGURES = ("vertex_y", "vertex_x", "landing_x", "spread", "stretch")
LIMITS = {"vertex_y": 0.005, "vertex_x": 0.01, "landing_x": 0.01, "spread": 0.002,
          "stretch": 0.001}
"""Issue 35's bounds for any 10-s window up to 120 s."""


def run(name: str, duration: float, window: float, skip: float, seed: int) -> dict:
    """One self-formed run of level ``name``; per-window figures and the steady time."""
    from chainfountain.level import io
    from chainfountain.sim import Recorder, Simulation

    cfg = io.load(LEVELS / f"{name}.toml").sim
    cfg.initial.mode = "stub"
    sim = Simulation(cfg)
    if seed:
        sim.nudge(seed)
    rec = Recorder(sim, profiles=False)
    wall = time.perf_counter()
    windows = []
    t = 0.0
    while t + window <= duration + 1e-9:
        sim.advance(window)
        t += window
        s = rec.summary(window=window)
        e = s.errors(sim.reference)
        windows.append({"t0": round(t - window, 6), "t1": round(t, 6),
                        "vertex_y": e["h"], "vertex_x": e["vertex_x"],
                        "landing_x": e["l"], "spread": s.speed_spread_inst,
                        "stretch": s.stretch_max, "speed": e["v"]})
    steady = rec.steady_from(window=2.0)
    return {"level": name, "seed": seed, "dt": sim.dt, "links": sim.n_links,
            "steady_from": steady, "wall_s": time.perf_counter() - wall,
            "windows": windows, "skip": skip}


def worst(res: dict) -> dict[str, float]:
    """The worst window (largest magnitude) of each figure after ``skip``."""
    ws = [w for w in res["windows"] if w["t0"] >= res["skip"] - 1e-9]
    out = {f: max((w[f] for w in ws), key=abs) if ws else math.nan for f in FIGURES}
    first, last = ws[0]["spread"] if ws else math.nan, ws[-1]["spread"] if ws else math.nan
    out["growth"] = last / first if first else math.nan
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("levels", nargs="*", default=list(ORDINARY))
    ap.add_argument("--duration", type=float, default=120.0)
    ap.add_argument("--window", type=float, default=10.0)
    ap.add_argument("--skip", type=float, default=20.0)
    ap.add_argument("--seed", type=int, default=0, help="nudge of the start (0: none)")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--json", type=Path, help="also write every window here")
    a = ap.parse_args(argv)
    args = [(n, a.duration, a.window, a.skip, a.seed) for n in a.levels]
    with ProcessPoolExecutor(max_workers=a.jobs) as ex:
        results = list(ex.map(run, *zip(*args, strict=True)))
    print(f"self-formed runs from the stub, {a.duration:g} s each, worst {a.window:g}-s "
          f"window from {a.skip:g} s (relative errors against the paper's catenary)")
    print(f"{'level':16s} {'dt us':>6s} {'steady s':>8s} {'vertex y':>9s} {'vertex x':>9s} "
          f"{'landing':>9s} {'spread':>8s} {'stretch':>8s} {'growth':>7s} {'RTF':>5s}")
    ok = True
    for r in results:
        w = worst(r)
        fails = [f for f in FIGURES if not abs(w[f]) <= LIMITS[f]]
        ok &= not fails
        st = "-" if r["steady_from"] is None else f"{r['steady_from']:.1f}"
        print(f"{r['level']:16s} {r['dt'] * 1e6:6.1f} {st:>8s} {w['vertex_y']:+9.2%} "
              f"{w['vertex_x']:+9.2%} {w['landing_x']:+9.2%} {w['spread']:8.3%} "
              f"{w['stretch']:8.3%} {w['growth']:7.2f} {a.duration / r['wall_s']:5.2f}"
              + (f"  beyond the bound: {', '.join(fails)}" if fails else ""))
    print("bounds (issue 35): " + ", ".join(f"{f} {v:.1%}" for f, v in LIMITS.items()))
    if a.json:
        from chainfountain.headless import json_safe

        a.json.write_text(json.dumps(json_safe(results), indent=1))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
