"""Benchmark of the physics core: speed of each shipped feed level, cost of recording.

Usage: ``.venv/bin/python benchmarks/bench_sim.py [--seconds 6] [level ...]``

For each level (default: every shipped ``levels/*.toml`` of kind "feed") prints: links
in flight, simulated seconds, wall seconds, real-time factor (simulated / wall),
time per physics step, and the recording overhead (``Simulation.step`` with a
:class:`Recorder` attached against bare ``space.step`` plus feed bookkeeping).
Single process, one core.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from chainfountain.level import io, library
from chainfountain.sim import Recorder, Simulation


def _time_steps(sim: Simulation, seconds: float, *, bare: bool) -> float:
    n = int(round(seconds / sim.dt))
    dt = sim.dt
    t0 = time.perf_counter()
    if bare:
        space_step, after = sim.space.step, sim.ends.after_step
        for _ in range(n):
            space_step(dt)
            after(dt)
    else:
        step = sim.step
        for _ in range(n):
            step()
    return time.perf_counter() - t0


def bench(name: str, seconds: float, chunk: float = 0.25,
          iterations: int | None = None) -> dict[str, float]:
    """Time ``seconds`` of each mode in interleaved chunks (the machine is shared).

    Modes: bare (``space.step`` + feed bookkeeping), ``Simulation.step`` without
    and with a :class:`Recorder`. Overheads are medians of per-round ratios, so
    load changes between rounds cancel.
    """
    cfg = io.load(library.resolve(name)).sim
    if iterations is not None:
        cfg.solver.iterations = iterations
    sim = Simulation(cfg)
    sim.advance(0.5)
    rec = Recorder(sim, profiles=True)
    rounds = max(1, int(round(seconds / chunk)))
    bare, plain, recd = [], [], []
    for _ in range(rounds):
        sim.recorder = None
        bare.append(_time_steps(sim, chunk, bare=True))
        plain.append(_time_steps(sim, chunk, bare=False))
        sim.recorder = rec
        recd.append(_time_steps(sim, chunk, bare=False))
    bare_a, plain_a, rec_a = (np.array(x) for x in (bare, plain, recd))
    steps = int(round(chunk / sim.dt))
    return {
        "links": sim.n_free,
        "sim_s": rounds * chunk,
        "wall_s": float(rec_a.sum()),
        "rtf": rounds * chunk / float(rec_a.sum()),
        "rtf_bare": rounds * chunk / float(bare_a.sum()),
        "us_per_step": float(np.median(rec_a)) / steps * 1e6,
        "overhead_step": float(np.median(plain_a / bare_a)) - 1.0,
        "overhead_rec": float(np.median(rec_a / bare_a)) - 1.0,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("levels", nargs="*",
                    help="level names (default: every shipped level of kind 'feed')")
    ap.add_argument("--seconds", type=float, default=6.0, help="simulated seconds per preset")
    ap.add_argument("--iterations", type=int, default=None,
                    help="override the solver iterations (default: the preset's)")
    args = ap.parse_args()
    if not args.levels:
        args.levels = [p.stem for p in sorted(library.shipped_dir().glob("*.toml"))
                       if io.load(p).sim.kind == "feed"]
    print(f"{'level':<16} {'links':>5} {'sim s':>6} {'wall s':>7} {'RTF':>5} {'RTF bare':>8} "
          f"{'us/step':>8} {'step ovh':>8} {'rec ovh':>8}")
    for name in args.levels:
        r = bench(name, args.seconds, iterations=args.iterations)
        print(f"{name:<16} {r['links']:>5d} {r['sim_s']:>6.1f} {r['wall_s']:>7.2f} "
              f"{r['rtf']:>5.2f} {r['rtf_bare']:>8.2f} {r['us_per_step']:>8.1f} "
              f"{100 * r['overhead_step']:>7.1f}% {100 * r['overhead_rec']:>7.1f}%")


if __name__ == "__main__":
    main()
