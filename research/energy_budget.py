"""Energy budget of the floor presets: where the chain loses the tension the rig law lacks.

    .venv/bin/python -m research.energy_budget                      # both presets, ~20 s
    .venv/bin/python -m research.energy_budget --radius 0.075 0.15 0.25 --only 9g
    .venv/bin/python -m research.energy_budget --only open          # 'open', ~6 s

Runs each preset (optionally with other upper-guide radii, ``apparatus.channel_radius``)
and sums the losses between the plate's upstream end and the free end with
:class:`chainfountain.sim.budget.EnergyBudget` (an exact impulse sweep; no single
joint's tension is read). Prints them by region in ``lambda v**3`` and the speed the rig
law selects without and with them (``selected_speed(..., dp=loss)``).
docs/apparatus.md, "Energy budget".

``open``: the floor preset's chain and cart in the non-stationary 'open' arrangement
(joint guides; ``xi2 = 0.546`` so that the drop equals the floor preset's). In windows of
``--width`` s it prints the losses and the chain's acceleration against the momentum law
``M dv/dt = F_drive - T_exit(v) - D/v`` with and without the loss ``D``
(:func:`chainfountain.sim.budget.open_windows`; docs/apparatus.md, "Open variant: where
the drive goes").
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time

from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Simulation
from chainfountain.sim.budget import REGIONS, EnergyBudget, open_windows, rig_law_speed
from chainfountain.study.changes import laid_on_path

LEVELS = shipped_dir()
PRESETS = {"9g": "apparatus_floor", "15g": "apparatus_floor_heavy"}
OPEN_WINDOW = (0.2, 2.2)
"""Default window (s) of the 'open' run: the fountain leaves the catch at about 2 s."""


def budget(name: str, radius: float | None, start: float, end: float, every: int) -> None:
    cfg = laid_on_path(io.load(LEVELS / f"{name}.toml")).sim
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
                      for reg in REGIONS if reg not in ("turn", "tail"))  # 'open' only
    print(f"{name} R = {a.channel_radius:.3f} m, {start:.1f}-{end:.1f} s "
          f"({time.perf_counter() - t0:.0f} s wall): v {r.v:.4f} m/s")
    print(f"  loss (guide/groove + pivots, lambda v^3): {parts}  total {r.total:.4f}")
    print(f"  rig law {v_law:.4f} m/s ({100 * (r.v / v_law - 1):+.2f} %), with the loss "
          f"{v_loss:.4f} m/s ({100 * (r.v / v_loss - 1):+.2f} %); sweep check "
          f"{r.rotation_residual:.1e} N m s")
    if not r.exact:
        print("  WARNING: the sweep did not close (a free link touched something the "
              "sweep does not know); the losses above are not exact")


def open_budget(start: float, end: float, width: float, every: int) -> None:
    cfg = laid_on_path(io.load(LEVELS / "apparatus_floor.toml")).sim
    a = dataclasses.replace(cfg.apparatus, variant="open", xi2=0.546, end_tension=0.144,
                            plate_links=0, upper_guide="joints", speed=2.92,
                            duration=end + 0.4)
    sim = Simulation(dataclasses.replace(cfg, apparatus=a))
    t0 = time.perf_counter()
    print(f"open (floor preset's chain and cart, xi2 0.546, joint guides), {start:.1f}-"
          f"{end:.1f} s; losses in lambda v^3, accelerations in m/s^2 (law: rig exit "
          "tension; law+loss: and the budget's loss)")
    regs = [r for r in REGIONS if r not in ("line",)]
    print("  window     v      M     " + " ".join(f"{r:>7s}" for r in regs)
          + "   total  a_meas  a_law  a_law+loss  sweep")
    for w in open_windows(sim, start, end, width, every):
        b = w.budget
        print(f"  {w.t0:.1f}-{w.t1:.1f}  {w.v:.3f}  {w.mass:.3f} "
              + " ".join(f"{b.region(r):7.4f}" for r in regs)
              + f"  {b.total:6.4f}  {w.a_measured:+.3f}  {w.a_law:+.3f}  {w.a_law_loss:+.3f}"
              f"      {'exact' if b.exact else 'NOT EXACT'}")
    print(f"  ({time.perf_counter() - t0:.0f} s wall)")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", choices=[*sorted(PRESETS), "open"], nargs="+",
                    default=sorted(PRESETS))
    ap.add_argument("--radius", type=float, nargs="+", default=[None],
                    help="upper guide radii (m; default: the level's)")
    ap.add_argument("--start", type=float, default=None,
                    help="window start (s; default 3, open: 0.2)")
    ap.add_argument("--end", type=float, default=None,
                    help="window end (s; default 6, open: 2.2)")
    ap.add_argument("--width", type=float, default=0.4,
                    help="open: width of each window (s)")
    ap.add_argument("--every", type=int, default=1, help="sample every n-th step")
    args = ap.parse_args(argv)
    for r in args.radius:
        if r is not None and not 0.03 <= r <= 0.3:
            ap.error(f"--radius: {r} m is outside 0.03-0.3 m (the guide must fit the rise)")
    if args.every < 1:
        ap.error(f"--every: {args.every}; allowed: an integer >= 1")
    if not 0 < args.width <= 2:
        ap.error(f"--width: {args.width} s; allowed: 0 < width <= 2 s")
    for key in args.only:
        start, end = (args.start, args.end)
        if key == "open":
            start = OPEN_WINDOW[0] if start is None else start
            end = OPEN_WINDOW[1] if end is None else end
            if not 0 <= start < end <= 2.4:
                ap.error(f"--start {start} / --end {end}: open needs 0 <= start < end <= "
                         "2.4 s (its fountain leaves the catch at about 2 s)")
            open_budget(start, end, args.width, args.every)
            continue
        start = 3.0 if start is None else start
        end = 6.0 if end is None else end
        if not 0 <= start < end:
            ap.error(f"--start {start} / --end {end}: need 0 <= start < end")
        for r in args.radius:
            budget(PRESETS[key], r, start, end, args.every)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
