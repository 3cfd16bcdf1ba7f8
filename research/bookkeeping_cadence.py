"""How the apparatus's Python bookkeeping cadence moves a floor preset's fountain.

pymunk steps every 0.5 ms in both runs; the bookkeeping (guides, grooves, treadmill,
taking links in and out) runs every pymunk step (``solver.dt = 0.5 ms``, as shipped)
or every second one (``solver.dt = 1 ms``, ``substeps = 2``, as the fold presets run).
Each run is laid along its path and nudged (``Simulation.nudge``); the report is
over 3-6 s. Prints, per run, the mean speed, ``Tbar_0``, ``Tbar_E``, the pick-up's exit
tension and the vertex's offset from the catenary through the measured ends.

Usage::

    python -m research.bookkeeping_cadence [apparatus_floor] [--seeds 1 2 3]

About 20 s for three seeds on one core.
"""

from __future__ import annotations

import argparse

from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus_report import report
from chainfountain.study.changes import laid_on_path, with_changes

LEVELS = shipped_dir()


def one(name: str, substeps: int, seed: int) -> dict:
    """Report of one laid, nudged run with the bookkeeping every ``substeps`` pymunk
    steps (pymunk's step kept at the level's)."""
    lvl = io.load(LEVELS / f"{name}.toml")
    h = lvl.sim.solver.dt / lvl.sim.solver.substeps
    lvl = with_changes(lvl, {"solver.dt": h * substeps, "solver.substeps": substeps})
    sim = Simulation(laid_on_path(lvl).sim)
    sim.nudge(seed)
    rec = Recorder(sim, profiles=False)
    sim.advance(6.0)
    return report(sim, rec, 3.0, 6.0)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("level", nargs="?", default="apparatus_floor",
                    help="a floor preset in levels/ (default apparatus_floor)")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ns = ap.parse_args()
    print("| bookkeeping | seed | speed m/s | Tbar_0 | Tbar_E | exit | vertex off catenary |")
    print("|---|---|---|---|---|---|---|")
    for substeps in (1, 2):
        for seed in ns.seeds:
            r = one(ns.level, substeps, seed)
            m = r["measured"]
            print(f"| every {substeps} pymunk step(s) | {seed} | {m['v']:.4f} | "
                  f"{m['T0_bar']:.4f} | {m['TE_bar']:.4f} | {m['T_pickup_exit_bar']:.4f} | "
                  f"{100 * r['catenary']['vertex_y_rel_error']:+.2f} % |", flush=True)


if __name__ == "__main__":
    main()
