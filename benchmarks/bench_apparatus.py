"""Speed of the apparatus presets: real-time factor, links, steps per second.

    .venv/bin/python benchmarks/bench_apparatus.py [--seconds 2]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from chainfountain.level import io
from chainfountain.sim import Simulation

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--seconds", type=float, default=2.0, help="simulated seconds per preset")
    args = ap.parse_args()
    print("| preset | links (start/end) | steps/s | real-time factor |")
    print("|---|---|---|---|")
    for path in sorted((ROOT / "levels").glob("apparatus_*.toml")):
        lvl = io.load(path)
        sim = Simulation(lvl.sim)
        n0 = sim.n_links
        t0 = time.perf_counter()
        steps = sim.advance(args.seconds)
        wall = time.perf_counter() - t0
        print(f"| {path.stem} | {n0}/{sim.n_links} | {steps / wall:.0f} | "
              f"{args.seconds / wall:.2f} |")


if __name__ == "__main__":
    main()
