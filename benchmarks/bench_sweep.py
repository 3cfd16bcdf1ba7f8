"""Speed of ``chainfountain sweep``: a 64-point sweep of a fed level on 1 and 2 processes.

Usage::

    .venv/bin/python benchmarks/bench_sweep.py [--points 64] [--duration 0.5] [--level wide_low]

The sweep varies ``feed.speed`` and ``feed.launch_angle`` of ``--level`` on an 8 x 8 grid
(``--points`` rounds to a square), each point ``--duration`` simulated seconds from the
level's own start. It runs once with ``--jobs 1``, once with ``--jobs 2`` and once on a
Dask ``LocalCluster`` of two worker processes (``--dask``; the cluster is started before
the clock) into fresh folders and prints the wall time of each, the speed-up, and the
share of the wall time spent outside the points' simulations (imports, start-up,
writing, the table). First it times the machine's own ceiling: the same busy loop in one
process and in two at once (a shared or throttled host gives two processes less than
2x, and no sweep can do better than that).
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

_BUSY = "s = 0\nfor i in range(20_000_000):\n    s += i * i\n"


def ceiling(processes: int = 2) -> float:
    """Speed-up of ``processes`` copies of a pure-Python busy loop run at once against one
    run alone (the wall times of one, and of all together)."""
    def wall(n: int) -> float:
        t0 = time.perf_counter()
        procs = [subprocess.Popen([sys.executable, "-c", _BUSY]) for _ in range(n)]
        for p in procs:
            p.wait()
        return time.perf_counter() - t0

    return processes * wall(1) / wall(processes)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, default=64)
    ap.add_argument("--duration", type=float, default=0.5)
    ap.add_argument("--level", default="wide_low")
    a = ap.parse_args(argv)
    side = max(1, round(math.sqrt(a.points)))
    speeds = ", ".join(f"{v:.3f}" for v in np.linspace(3.8, 4.6, side))
    angles = ", ".join(f"{v:.4f}" for v in np.radians(np.linspace(55.0, 65.0, side)))
    text = (f'base = "{a.level}"\nduration = {a.duration}\n[grid]\n'
            f'"feed.speed" = [{speeds}]\n"feed.launch_angle" = [{angles}]\n')
    import pyarrow.parquet as pq

    print(f"this machine: 2 busy loops at once run {ceiling():.2f}x one alone")
    print(f"{side * side}-point sweep of {a.level}, {a.duration:g} s per point")
    walls = {}
    with tempfile.TemporaryDirectory() as tmp:
        sweep = Path(tmp) / "bench.toml"
        sweep.write_text(text)
        for jobs in (1, 2):
            out = Path(tmp) / f"out{jobs}"
            t0 = time.perf_counter()
            r = subprocess.run([sys.executable, "-m", "chainfountain", "sweep", str(sweep),
                                "--jobs", str(jobs), "--out", str(out), "--quiet"],
                               capture_output=True, text=True)
            wall = time.perf_counter() - t0
            if r.returncode != 0:
                print(r.stderr)
                return 1
            t = pq.read_table(out / "results.parquet").to_pydict()
            sim_wall = float(np.nansum(np.array(t["wall_s"], dtype=float)))
            walls[jobs] = wall
            outside = 1.0 - sim_wall / (wall * jobs)
            print(f"  --jobs {jobs}: {wall:6.1f} s wall, simulations {sim_wall:6.1f} s of "
                  f"process time; outside the simulations {outside:.0%}")
        try:
            from distributed import LocalCluster
        except ImportError:
            print("  LocalCluster: skipped (pip install 'chainfountain[cluster]')")
        else:
            with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                              dashboard_address=None) as cluster:
                out = Path(tmp) / "outdask"
                t0 = time.perf_counter()
                r = subprocess.run([sys.executable, "-m", "chainfountain", "sweep",
                                    str(sweep), "--dask", cluster.scheduler_address, "--out",
                                    str(out), "--quiet"], capture_output=True, text=True)
                wall = time.perf_counter() - t0
            if r.returncode != 0:
                print(r.stderr)
                return 1
            walls["dask"] = wall
            print(f"  LocalCluster of 2 workers: {wall:6.1f} s wall")
    print(f"  speed-up 2 processes / 1: {walls[1] / walls[2]:.2f}x"
          + (f"; LocalCluster / 1: {walls[1] / walls['dask']:.2f}x" if "dask" in walls
             else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
