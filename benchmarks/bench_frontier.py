"""Accuracy against cost for the kinds without the fed error model: a scene and the beaker.

Usage::

    .venv/bin/python benchmarks/bench_frontier.py [--only scene|beaker] [--beaker-seconds 4]

- **Scene** (``falling_chain``, 0.4 s from rest, the whole fall): the free end's speed
  against Calkin and March at 25 / 50 / 75 % of the fall, and CPU seconds per simulated
  second, at a 250-us step over pymunk sub-steps and iterations, and at the shipped 8 x 2
  with the step halved. ``*`` marks a scene's defaults
  (:data:`chainfountain.sim.kinds.scene.SOLVER_DEFAULTS`, the shipped table).
- **Beaker** (``beaker``, ``--beaker-seconds`` from rest): CPU seconds per simulated second
  at the steps its accuracy chooses between, beside the step model's shortfall of the
  speed and the top (:func:`chainfountain.sim.beaker_error.shortfalls`, measured by
  refinement). ``*`` marks the shipped step.

CPU time is the process's (one core). Prints only; nothing is asserted.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

SCENE_SETTINGS = [  # (dt, substeps, iterations)
    (2.5e-4, 1, 10), (2.5e-4, 1, 25), (2.5e-4, 2, 5), (2.5e-4, 4, 2), (2.5e-4, 4, 4),
    (2.5e-4, 8, 1), (2.5e-4, 8, 2), (2.5e-4, 8, 4), (2.5e-4, 16, 1), (2.5e-4, 16, 2),
    (1.25e-4, 8, 2), (6.25e-5, 8, 2),
]
BEAKER_STEPS = [2.5e-4, 1.19e-4, 6.25e-5]


def _run(name: str, changes: dict, seconds: float | None) -> tuple[dict, float]:
    """The run's summary and its CPU seconds per simulated second."""
    from chainfountain.headless import run_and_record
    from chainfountain.level import io, library
    from chainfountain.study import with_changes

    level = with_changes(io.load(library.resolve(name)), changes)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.process_time()
        path, _ = run_and_record(level, Path(tmp), seconds, progress=False, snapshot=False)
        cpu = time.process_time() - t0
        import json

        s = json.loads(path.read_text())
    return s, cpu / s["duration_s"]


def scene() -> None:
    from chainfountain.sim.kinds.scene import SOLVER_DEFAULTS

    print("falling_chain, 0.4 s from rest: free end's speed against Calkin and March")
    print(f"{'dt us':>6s} {'sub':>4s} {'it':>3s} {'25 %':>8s} {'50 %':>8s} {'75 %':>8s} "
          f"{'CPU s/s':>8s}")
    for dt, sub, it in SCENE_SETTINGS:
        s, cost = _run("falling_chain", {"solver.dt": dt, "solver.substeps": sub,
                                         "solver.iterations": it}, None)
        err = s["closed_form"]["speed_rel_error"]
        mark = "*" if (dt == 2.5e-4 and sub == SOLVER_DEFAULTS["substeps"]
                       and it == SOLVER_DEFAULTS["iterations"]) else " "
        cells = " ".join("     n/a" if e is None else f"{100 * e:+7.2f}%" for e in err)
        print(f"{1e6 * dt:6.1f} {sub:4d} {it:3d} {cells} {cost:8.2f} {mark}", flush=True)


def beaker(seconds: float) -> None:
    from chainfountain.level import io, library
    from chainfountain.sim import beaker_error

    shipped = io.load(library.resolve("beaker")).sim.solver.dt
    print(f"\nbeaker, {seconds:g} s from rest: CPU cost against the step model's shortfall")
    print(f"{'dt us':>6s} {'speed':>7s} {'top':>7s} {'CPU s/s':>8s}")
    for dt in BEAKER_STEPS:
        _, cost = _run("beaker", {"solver.dt": dt}, seconds)
        low = beaker_error.shortfalls(dt)
        mark = "*" if abs(dt - shipped) < 1e-12 else " "
        print(f"{1e6 * dt:6.1f} {100 * low['speed']:6.1f}% {100 * low['rise_above_rim']:6.1f}% "
              f"{cost:8.2f} {mark}", flush=True)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", choices=("scene", "beaker"))
    ap.add_argument("--beaker-seconds", type=float, default=4.0)
    a = ap.parse_args(argv)
    if a.only in (None, "scene"):
        scene()
    if a.only in (None, "beaker"):
        beaker(a.beaker_seconds)
    return 0


if __name__ == "__main__":
    sys.exit(main())
