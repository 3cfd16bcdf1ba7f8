"""The ideal floor machine across settings: does the speed it selects match the paper?

Runs ``levels/ideal_floor.toml`` (``feed.drive = "ideal_floor"``, the paper's idealized
beaker with a real floor; ``chainfountain.sim.piston``) with the given drop, offset
``xi2``, cart force and start speed, and prints the chain's speed against the paper's

    v^2 = 2 g (H (1 - xi2) - F_uc/(lambda g))

(:func:`chainfountain.theory.apparatus.ideal_floor_speed`), with the mean and scatter over
the run's second half. The level starts on the predicted catenary at ``--v0``.

Usage::

    python -m research.ideal_floor                       # H 1 m, xi2 0.3, no cart, from 3.5 m/s
    python -m research.ideal_floor --xi2 0.1 --seconds 10
    python -m research.ideal_floor --xi2 0.3 --cart 0.05 --v0 3.7 --seconds 10
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from chainfountain.level.library import shipped_dir

LEVEL = shipped_dir() / "ideal_floor.toml"


def main(argv: list[str] | None = None) -> int:
    from chainfountain.level import io
    from chainfountain.sim import Simulation
    from chainfountain.theory.apparatus import ideal_floor_speed

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--H", type=float, default=1.0)
    ap.add_argument("--xi2", type=float, default=0.3)
    ap.add_argument("--cart", type=float, default=0.0, help="F_uc (N)")
    ap.add_argument("--mass", type=float, default=0.05, help="M, cart + upstream strand (kg)")
    ap.add_argument("--v0", type=float, default=3.5)
    ap.add_argument("--angle", type=float, default=60.0, help="launch angle (deg)")
    ap.add_argument("--seconds", type=float, default=15.0)
    a = ap.parse_args(argv)
    lvl = io.load(LEVEL)
    f = lvl.sim.feed
    f.drop, f.xi2, f.cart_force, f.machine_mass = a.H, a.xi2, a.cart, a.mass
    f.speed, f.launch_angle = a.v0, math.radians(a.angle)
    lvl = io.loads(io.dumps(lvl), "ideal_floor (changed)")  # the level checks, as a file
    v_pred = ideal_floor_speed(a.H, a.xi2, a.cart, lvl.sim.chain.linear_density,
                               lvl.sim.gravity)
    sim = Simulation(lvl.sim)
    print(f"predicted v = {v_pred:.4f} m/s")
    vs, ts = [], []
    while sim.time < a.seconds:
        sim.advance(0.05)
        vs.append(sim.piston.speed)
        ts.append(sim.time)
        if abs(sim.time - round(sim.time)) < 1e-6:
            print(f"t = {sim.time:5.2f} s  v = {vs[-1]:.4f} ({vs[-1] / v_pred - 1:+.2%})  "
                  f"free links {sim.n_free}", flush=True)
    vs, ts = np.array(vs), np.array(ts)
    late = ts >= a.seconds / 2
    print(f"mean speed over the second half {vs[late].mean():.4f} m/s "
          f"({vs[late].mean() / v_pred - 1:+.2%} against the paper), sd {vs[late].std():.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
