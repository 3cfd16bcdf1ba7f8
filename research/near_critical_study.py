"""Vertex creep of a near-critical fountain against the time step (not a test).

Usage: ``.venv/bin/python -m research.near_critical_study [--seconds 0.9]``

The paper's fountain D (``l = 0.33``, ``h = 0.28``, ``H = 2`` m, ``k = 0.377``)
has ``1 - Tbar = k/q = 0.017`` at its vertex: close to the critical tension
``lambda v^2`` at which any shape is steady. The script designs it with
``chainfountain design`` (4 mm links), runs it from the predicted catenary at
several time steps and prints the vertex height against the design's at a few
times, the creep rate (least-squares slope) and the ratio
``q v dt / (k/q)`` that :func:`chainfountain.design_level.time_step_for` keeps
at 0.1 or below. Takes about a minute on one core.
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import numpy as np

from chainfountain.design_level import design_sim_config
from chainfountain.sim import Recorder, Simulation
from chainfountain.theory.design import design
from chainfountain.theory.fountain import Fountain

STEPS_US = (250.0, 125.0, 62.5, 15.625)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=0.9, help="simulated seconds per run")
    args = ap.parse_args()
    f = Fountain.from_geometry(l=0.33, h=0.28, H=2.0, k=0.377)
    base = design_sim_config(design(f, 0.05))
    print(f"fountain D: q = {f.q:.2f} 1/m, k/q = {f.k / f.q:.4f}, "
          f"L = {base.chain.link_length * 1e3:.0f} mm, designed dt = {base.solver.dt * 1e6:.0f} us")
    marks = np.linspace(args.seconds / 3, args.seconds, 3)
    print("| dt us | iterations | q v dt/(k/q) | " + " | ".join(f"h/h0 at {m:.2f} s" for m in marks)
          + " | creep %/s | stretch | wall s |")
    print("|---" * (6 + len(marks)) + "|")
    for dt_us in STEPS_US:
        for it in (10, 24):
            cfg = dataclasses.replace(base, solver=dataclasses.replace(
                base.solver, dt=dt_us * 1e-6, iterations=it))
            sim = Simulation(cfg)
            rec = Recorder(sim, profiles=False)
            t0 = time.perf_counter()
            sim.advance(args.seconds)
            wall = time.perf_counter() - t0
            t = rec.series("t")
            h = rec.series("vertex_y") / f.h
            at = [float(np.interp(m, t, h)) for m in marks]
            creep = float(np.polyfit(t, h, 1)[0]) * 100.0
            ratio = f.q * f.v * dt_us * 1e-6 / (f.k / f.q)
            print(f"| {dt_us:g} | {it} | {ratio:.3f} | " + " | ".join(f"{a:.3f}" for a in at)
                  + f" | {creep:+.2f} | {rec.series('stretch').max():.4f} | {wall:.1f} |",
                  flush=True)


if __name__ == "__main__":
    main()
