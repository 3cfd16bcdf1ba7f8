"""Which lower carts keep a contact fold running, at which pymunk step.

Runs a fold preset (shipped damper and treadmills) laid along its path, with
``apparatus.fold_clearance`` and each lower cart of ``--lower-carts`` (g), at each pymunk
step of ``--dt`` (ms; the bookkeeping in every step, ``substeps = 1``), over ``--seeds``
starts nudged by 1e-12 (``Simulation.nudge``), for ``--duration`` simulated seconds, and
prints a Markdown table: how many runs held, and when the others ended. A fold whose
holding carts move with the step is not converged in it (docs/apparatus.md, "The fold
depends on the time step").

Usage::

    python -m research.fold_balance apparatus_fold --clearance 0.002 \\
        --lower-carts 20 22 24 26 28 --dt 0.5 0.25 --seeds 3 --duration 30

About 10-50 s of wall time per run (two at once; more at smaller steps).
"""

from __future__ import annotations

import argparse
from concurrent.futures import ProcessPoolExecutor

from chainfountain.level.library import shipped_dir

LEVELS = shipped_dir()


def run(level: str, clearance: float, cart_g: float, dt_ms: float, seed: int,
        duration: float) -> float | None:
    """One run; None if it held ``duration`` s, else the time (s) it ended."""
    from chainfountain.errors import RunEnded
    from chainfountain.level import io
    from chainfountain.sim import Simulation
    from chainfountain.study.changes import laid_on_path, with_changes

    lvl = with_changes(io.load(LEVELS / f"{level}.toml"), {
        "apparatus.fold_clearance": clearance, "carts[1].mass": cart_g * 1e-3,
        "solver.dt": dt_ms * 1e-3, "solver.substeps": 1})
    sim = Simulation(laid_on_path(lvl).sim)
    sim.nudge(seed)
    try:
        sim.advance(duration)
    except RunEnded:
        return sim.time
    return None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("level")
    ap.add_argument("--clearance", type=float, default=0.002)
    ap.add_argument("--lower-carts", type=float, nargs="+", required=True, metavar="G")
    ap.add_argument("--dt", type=float, nargs="+", default=[0.5, 0.25], metavar="MS")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--duration", type=float, default=30.0)
    ap.add_argument("--jobs", type=int, default=2)
    ns = ap.parse_args()
    jobs = [(ns.level, ns.clearance, m, dt, s, ns.duration)
            for dt in ns.dt for m in ns.lower_carts for s in range(1, ns.seeds + 1)]
    with ProcessPoolExecutor(ns.jobs) as ex:
        ends = list(ex.map(run, *zip(*jobs, strict=True)))
    print(f"{ns.level}, fold_clearance {ns.clearance:g} m, {ns.duration:g} s from the laid "
          f"start, {ns.seeds} nudged starts each")
    print("| pymunk step (ms) | lower cart (g) | held | the others ended at (s) |")
    print("|---|---|---|---|")
    for k in range(0, len(jobs), ns.seeds):
        group = ends[k:k + ns.seeds]
        held = sum(e is None for e in group)
        others = ", ".join(f"{e:.1f}" for e in group if e is not None)
        print(f"| {jobs[k][3]:g} | {jobs[k][2]:g} | {held} of {ns.seeds} | {others} |")


if __name__ == "__main__":
    main()
