"""Energy budget of the floor presets: where the chain loses the tension the rig law lacks.

    .venv/bin/python benchmarks/energy_budget.py                      # both presets, ~1.5 min
    .venv/bin/python benchmarks/energy_budget.py --radius 0.075 0.15 0.25 --only 9g

Runs each preset (optionally with other upper-guide radii, ``apparatus.channel_radius``)
and sums the losses between the plate's upstream end and the free end with
:class:`chainfountain.sim.budget.EnergyBudget` (an exact impulse sweep; no single
joint's tension is read). Prints them by region in ``lambda v**3`` and the speed the rig
law selects without and with them (``selected_speed(..., dp=loss)``).
docs/apparatus.md, "Energy budget".
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

from chainfountain.level import io
from chainfountain.sim import Simulation
from chainfountain.sim.budget import REGIONS, EnergyBudget, rig_law_speed

LEVELS = Path(__file__).resolve().parents[1] / "levels"
PRESETS = {"9g": "apparatus_floor", "15g": "apparatus_floor_heavy"}


def budget(name: str, radius: float | None, start: float, end: float, every: int) -> None:
    cfg = io.load(LEVELS / f"{name}.toml").sim
    a = dataclasses.replace(cfg.apparatus, duration=max(cfg.apparatus.duration, end + 0.5))
    if radius is not None:
        a = dataclasses.replace(a, channel_radius=radius)
    cfg = dataclasses.replace(cfg, apparatus=a)
    sim = Simulation(cfg)
    eb = EnergyBudget(sim, start=start, every=every)
    t0 = time.perf_counter()
    while sim.time < end - 1e-9:
        sim.advance(min(0.5, end - sim.time))
        print(f"\r  {name}: t = {sim.time:4.1f} / {end:.1f} s", end="", file=sys.stderr)
    print("\r" + " " * 40 + "\r", end="", file=sys.stderr)
    r = eb.result()
    v_law, v_loss = rig_law_speed(cfg), rig_law_speed(cfg, r.total)
    parts = "  ".join(f"{reg} {r.region(reg):.4f} ({r.guides[reg]:.4f} + {r.pivots[reg]:.4f})"
                      for reg in REGIONS)
    print(f"{name} R = {a.channel_radius:.3f} m, {start:.1f}-{end:.1f} s "
          f"({time.perf_counter() - t0:.0f} s wall): v {r.v:.4f} m/s")
    print(f"  loss (guide/groove + pivots, lambda v^3): {parts}  total {r.total:.4f}")
    print(f"  rig law {v_law:.4f} m/s ({100 * (r.v / v_law - 1):+.2f} %), with the loss "
          f"{v_loss:.4f} m/s ({100 * (r.v / v_loss - 1):+.2f} %); sweep check "
          f"{r.rotation_residual:.1e} N m s")
    if not r.exact:
        print("  WARNING: the sweep did not close (a free link touched something the "
              "sweep does not know); the losses above are not exact")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", choices=sorted(PRESETS), nargs="+", default=sorted(PRESETS))
    ap.add_argument("--radius", type=float, nargs="+", default=[None],
                    help="upper guide radii (m; default: the level's)")
    ap.add_argument("--start", type=float, default=3.0, help="window start (s)")
    ap.add_argument("--end", type=float, default=6.0, help="window end (s)")
    ap.add_argument("--every", type=int, default=1, help="sample every n-th step")
    args = ap.parse_args(argv)
    for r in args.radius:
        if r is not None and not 0.03 <= r <= 0.3:
            ap.error(f"--radius: {r} m is outside 0.03-0.3 m (the guide must fit the rise)")
    if not 0 <= args.start < args.end:
        ap.error(f"--start {args.start} / --end {args.end}: need 0 <= start < end")
    if args.every < 1:
        ap.error(f"--every: {args.every}; allowed: an integer >= 1")
    for key in args.only:
        for r in args.radius:
            budget(PRESETS[key], r, args.start, args.end, args.every)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
