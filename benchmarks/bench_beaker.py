"""Speed of the beaker level: real-time factor, links and wall time per simulated second.

    .venv/bin/python benchmarks/bench_beaker.py [--level beaker] [--seconds 4] [--repeat 3]

Each run first forms the fountain (``--warmup`` simulated seconds, not timed), then times
``--seconds`` of ``Simulation.step`` (the beaker's bookkeeping included, no recorder).
This machine's speed wanders by 20-40 % between identical runs, so the figure is the
best of ``--repeat`` runs, with the median beside it. (Profiled, pymunk's own step is
about 73 % of it; a bare ``space.step`` loop on the same space is no fair measure here:
without the floor taking links the chain falls on below it, contact-free.)
"""

from __future__ import annotations

import argparse
import statistics
import time

from chainfountain.level import io, library
from chainfountain.sim import Simulation


def one(level, warmup: float, seconds: float) -> tuple[int, float]:
    """Links and wall seconds per simulated second of ``Simulation.step``."""
    sim = Simulation(level.sim)
    sim.advance(warmup)
    t0 = time.perf_counter()
    sim.advance(seconds)
    return sim.n_links, (time.perf_counter() - t0) / seconds


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="beaker", help="a beaker level (name or file)")
    ap.add_argument("--seconds", type=float, default=4.0, help="simulated seconds timed")
    ap.add_argument("--warmup", type=float, default=5.0, help="simulated seconds not timed")
    ap.add_argument("--repeat", type=int, default=3, help="runs per figure")
    a = ap.parse_args()
    level = io.load(library.resolve(a.level))
    s = level.sim.solver
    print(f"{level.meta.name}: dt {s.dt * 1e6:.0f} us x {s.substeps} sub-steps x "
          f"{s.iterations} iterations, after {a.warmup:g} s from rest, {a.seconds:g} s timed")
    runs = [one(level, a.warmup, a.seconds) for _ in range(a.repeat)]
    full = sorted(r[1] for r in runs)
    print(f"  {runs[0][0]} links; real-time factor {1 / full[0]:.2f} best, "
          f"{1 / statistics.median(full):.2f} median ({full[0]:.3f} s per simulated s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
