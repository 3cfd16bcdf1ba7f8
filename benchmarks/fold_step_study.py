"""Is the fold converged in the time step? The fold presets at several solver steps.

    .venv/bin/python benchmarks/fold_step_study.py                  # ~1.5 min
    .venv/bin/python benchmarks/fold_step_study.py --only special --dt 0.5 0.25
    .venv/bin/python benchmarks/fold_step_study.py --rig            # put-down rig, ~30 s

Runs each 'fold' preset (real geometry or treadmills, as shipped) for ``--seconds`` at
each step of ``--dt`` (ms; the iterations as in the preset) and prints a Markdown row per
run from :func:`chainfountain.sim.apparatus_report.report` over 0.5 s to the end: speed,
drift, the folding roller's ``v_R/v``, ``Tbar_0``, ``Tbar_E``, the vertex against the
catenary through the measured ends, and when the run ended (``FoldCollapsed``).
``--rig`` runs the put-down rig alone (2 cm links, 3 m/s, push 0.4 ``lambda v^2``) at
the same steps. docs/apparatus.md, "Twelfth session".
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

from chainfountain.errors import RunEnded
from chainfountain.level import io
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus_report import report
from chainfountain.sim.config import ChainConfig, SolverConfig
from chainfountain.sim.pickup import RigConfig, run_rig

ROOT = Path(__file__).resolve().parents[1]
FOLD_PRESETS = ("apparatus_fold", "apparatus_special")
WINDOW_START = 0.5


def run_preset(name: str, dt: float, seconds: float) -> str:
    cfg = io.load(ROOT / "levels" / f"{name}.toml").sim
    cfg = dataclasses.replace(cfg, solver=dataclasses.replace(cfg.solver, dt=dt))
    sim = Simulation(cfg)
    rec = Recorder(sim, profiles=False)
    t0 = time.perf_counter()
    end, ended = seconds, "held"
    try:
        sim.advance(seconds)
    except RunEnded:
        end, ended = sim.time, f"ended {sim.time:.2f} s"
    wall = time.perf_counter() - t0
    head = f"| {name} | {dt * 1e3:g} | {cfg.solver.iterations} |"
    if end < WINDOW_START + 0.2:
        return f"{head} | | | | | | {ended} | {wall:.0f} |"
    r = report(sim, rec, WINDOW_START, end)
    m, c = r["measured"], r["catenary"]
    return (f"{head} {m['v']:.3f} | {100 * m['speed_drift_per_s']:+.2f} | "
            f"{m['roller_ratio_lo']:.3f} | {m['T0_bar']:.3f} | {m['TE_bar']:.3f} | "
            f"{100 * c['vertex_y_rel_error']:+.1f} % | {ended} | {wall:.0f} |")


def rig_row(dt: float) -> str:
    lam, v, f = 0.05, 3.0, 0.4
    ch = ChainConfig(link_length=0.02, linear_density=lam, friction=0.6, link_radius=0.002)
    sol = SolverConfig(dt=dt, iterations=10, joint_error_bias=1e-10, collision_slop=1e-4)
    cfg = RigConfig(mode="putdown", speed=v, cart_force=f * lam * v * v, chain=ch, solver=sol)
    r = run_rig(cfg, duration=1.5, settle=0.5)
    return f"| {dt * 1e3:g} | {r.speed:.3f} | {r.roller_ratio:.3f} | {r.force_bar:.3f} |"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dt", type=float, nargs="+", default=[0.5, 0.35, 0.25, 0.1],
                    help="solver steps in ms")
    ap.add_argument("--seconds", type=float, default=3.0)
    ap.add_argument("--only", default="", help="run presets whose name contains this")
    ap.add_argument("--rig", action="store_true", help="the put-down rig alone")
    args = ap.parse_args(argv)
    if args.rig:
        print("| dt ms | chain m/s | v_R/v | entry Tbar |")
        print("|---|---|---|---|")
        for dt in args.dt:
            print(rig_row(dt * 1e-3), flush=True)
        return 0
    print(f"Window {WINDOW_START:g} s to the end of a {args.seconds:g}-s run.\n")
    print("| preset | dt ms | iterations | v m/s | drift %/s | lower v_R/v | Tbar_0 | "
          "Tbar_E | vertex | run | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name in FOLD_PRESETS:
        if args.only not in name:
            continue
        for dt in args.dt:
            print(run_preset(name, dt * 1e-3, args.seconds), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
