"""Accuracy per CPU-second of the shipped fed levels: error against wall time.

Usage::

    .venv/bin/python benchmarks/bench_accuracy.py [level ...] [--settle 1.5] [--window 3]

Each ordinary fed level runs from the predicted catenary (settled ``--settle`` s,
averaged ``--window`` s; :func:`chainfountain.refine.measure`) at each of its settings in
:data:`SETTINGS`: the ones the level runs (from ``solver.accuracy`` or set by hand)
and hand-set ones (2-cm links at 10 iterations; 1 cm at 24 for ``paper_tall_fine``),
where the solver does not converge. It prints vertex height,
vertex x and landing error against the paper, the link-speed spread, the wall time per
simulated second and the error model's bound for the settings (``-`` when the solver
does not converge at them). One run at a time, so the timings are one core's.
"""

from __future__ import annotations

import argparse
import copy
import math
import sys

from chainfountain.level.library import shipped_dir

LEVELS = shipped_dir()
SETTINGS: dict[str, list[tuple[str, float, float, int]]] = {
    # level: (label, link length m, step s, iterations); the level's own are read from it
    "classroom": [("hand-set", 0.02, 2.5e-4, 10)],
    "paper_tall": [("hand-set", 0.02, 2.5e-4, 10)],
    "paper_tall_fine": [("hand-set", 0.01, 2.5e-4, 24)],
    "wide_low": [],
}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("levels", nargs="*", default=list(SETTINGS))
    ap.add_argument("--settle", type=float, default=1.5)
    ap.add_argument("--window", type=float, default=3.0)
    a = ap.parse_args(argv)

    from chainfountain.level import io
    from chainfountain.refine import measure
    from chainfountain.sim import accuracy
    from chainfountain.sim.reference import LaunchReference

    print(f"from the catenary, settled {a.settle:g} s, averaged {a.window:g} s; errors "
          "against the paper's catenary; bound: the error model's (vertex y / x / landing)")
    print(f"{'level':16s} {'settings':16s} {'L mm':>5s} {'dt us':>6s} {'it':>3s} "
          f"{'links':>5s} {'vertex y':>9s} {'vertex x':>9s} {'landing':>9s} {'spread':>7s} "
          f"{'wall s/s':>8s}  bound")
    for name in a.levels:
        cfg = io.load(LEVELS / f"{name}.toml").sim
        f = cfg.feed
        ref = LaunchReference.of_feed(f, cfg.gravity)
        rows = [("level", cfg.chain.link_length, cfg.solver.dt, cfg.solver.iterations)]
        rows += SETTINGS.get(name, [])
        for label, L, dt, it in rows:
            c = copy.deepcopy(cfg)
            c.chain.link_length, c.solver.dt, c.solver.iterations = L, dt, it
            c.solver.accuracy = 0.0
            c.initial.mode = "catenary"
            r = measure(c, settle=a.settle, window=a.window)
            est = accuracy.estimate(ref, accuracy.Settings(L, dt, it))
            bound = ("-" if not math.isfinite(est.worst) else
                     " / ".join(f"{100 * est.bounds[k]:.2f}" for k in accuracy.FIGURES) + " %")
            e = r.errors
            print(f"{name:16s} {label:16s} {L * 1e3:5.1f} {dt * 1e6:6.1f} {it:3d} {r.links:5d} "
                  f"{e['h']:+9.2%} {e['vertex_x']:+9.2%} {e['l']:+9.2%} {r.spread:7.2%} "
                  f"{1 / r.realtime_factor:8.2f}  {bound}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
