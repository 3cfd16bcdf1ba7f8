"""Is the fold converged in the time step? The fold presets at several solver steps.

    .venv/bin/python -m research.fold_step_study                  # ~1.5 min
    .venv/bin/python -m research.fold_step_study --only special --dt 0.5 0.25
    .venv/bin/python -m research.fold_step_study --rig            # put-down rig, ~30 s
    .venv/bin/python -m research.fold_step_study --only special --clearance 0.002 \
        --lower-cart 0.046                                          # the clamp removed
    .venv/bin/python -m research.fold_step_study --only special --seconds 6 --dt 0.5 \
        --speeds 2.94 2.97 3.0 3.03 3.06                            # perturbed starts
    .venv/bin/python -m research.fold_step_study --rig --feed groove --push 0.632
    .venv/bin/python -m research.fold_step_study --rig --feed groove --push 0.632 \
        --clearance 0.002 --dt 0.5 0.1 0.025 --iterations 10 40

Runs each 'fold' preset (real geometry or treadmills, as shipped) for ``--seconds`` at
each step of ``--dt`` (ms; the iterations as in the preset) and prints a Markdown row
per run from :func:`chainfountain.sim.apparatus_report.report` over 0.5 s to the end:
speed, drift, the folding roller's ``v_R/v``, ``Tbar_0``, ``Tbar_E``, the vertex against
the catenary through the measured ends, when the run ended (``FoldCollapsed``), and the
clamp: the mean vertical contact force (N) between the folding roller and the chain
links above its centre over the first 0.15 s (the roller weighs 0.2 N; a locked roller
sees tens of N). ``--speeds`` runs each step from several start speeds
(``apparatus.speed``; the fold is chaotic, so one run does not say whether a setting
holds), and the last line counts the runs that held cleanly. ``--clearance`` sets
``apparatus.fold_clearance`` (m), ``--lower-cart`` the lower cart's mass (kg). ``--rig``
runs the put-down rig alone (2 cm links, 3 m/s, push ``--push`` ``lambda v^2``; ``--feed
groove``: the strand held on a groove line as on the apparatus's lower plate,
``--clearance`` above the roller's top) at the same steps, with ``--iterations`` (10 by
default; several values give a row each).
docs/apparatus.md, "The fold depends on the time step" and "The landing swing".
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from collections.abc import Callable
from pathlib import Path

from chainfountain.errors import RunEnded
from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus_report import report
from chainfountain.sim.config import ChainConfig, SimConfig, SolverConfig
from research.rigs.pickup import RigConfig, run_rig

ROOT = Path(__file__).resolve().parents[1]
FOLD_PRESETS = ("apparatus_fold", "apparatus_special")
WINDOW_START = 0.5
CLAMP_WINDOW = 0.15


def _clamp_force(sim: Simulation, seconds: float) -> float:
    """Advance ``seconds`` and return the mean vertical contact force (N) that chain links
    above the folding roller's centre exert on it."""
    roller = sim.apparatus.lower.roller
    total = [0.0]

    def add(arb) -> None:
        a, b = arb.shapes
        other = b if a.body is roller else a
        if other.body.position.y > roller.position.y:
            total[0] += abs(arb.total_impulse.y)

    t_end = sim.time + seconds
    while sim.time < t_end - 1e-9:
        sim.step()
        roller.each_arbiter(add)
    return total[0] / seconds


def fold_config(level: str, dt: float, clearance: float | None = None,
                lower_cart: float | None = None, speed: float | None = None,
                damper: float = 0.0) -> SimConfig:
    """A 'fold' level (a name in ``levels/`` or a ``.toml`` path) at pymunk step ``dt`` (s, the
    bookkeeping every step: ``substeps = 1``),
    with the study's changes (``None``: as in the level) and the swing damper ``damper``
    (N s/m; 0 by default: these studies read the fold's own behaviour, not the shipped
    presets' damped one). A missing, bad or non-fold level stops the script with one line."""
    path = Path(level) if level.endswith(".toml") else shipped_dir() / f"{level}.toml"
    try:
        cfg = io.load(path).sim
    except io.LevelError as exc:
        raise SystemExit(str(exc)) from None
    a = cfg.apparatus
    if a is None or a.variant != "fold":
        raise SystemExit(f"{path.name}: not a 'fold' apparatus level")
    a = dataclasses.replace(a, swing_damper=damper)
    if clearance is not None:
        a = dataclasses.replace(a, fold_clearance=clearance)
    if speed is not None:
        a = dataclasses.replace(a, speed=speed)
    carts = list(cfg.carts)
    if lower_cart is not None:
        carts[1] = dataclasses.replace(carts[1], mass=lower_cart)
    return dataclasses.replace(cfg, solver=dataclasses.replace(cfg.solver, dt=dt, substeps=1),
                               apparatus=a, carts=carts)


def run_preset(name: str, dt: float, seconds: float, clearance: float | None = None,
               lower_cart: float | None = None, speed: float | None = None) -> tuple[str, bool]:
    """One Markdown row, and whether the run held cleanly: not ended, the folding roller
    at ``v_R/v = 0.5 +- 0.02`` and the speed drift within 1 %/s (the issue's steadiness)."""
    cfg = fold_config(name, dt, clearance, lower_cart, speed)
    a, carts = cfg.apparatus, cfg.carts
    sim = Simulation(cfg)
    rec = Recorder(sim, profiles=False)
    t0 = time.perf_counter()
    end, ended, clamp = seconds, "held", float("nan")
    try:
        clamp = _clamp_force(sim, CLAMP_WINDOW)
        sim.advance(seconds - sim.time)
    except RunEnded:
        end, ended = sim.time, f"ended {sim.time:.2f} s"
    wall = time.perf_counter() - t0
    head = (f"| {name} | {1e3 * a.fold_clearance:g} | {1e3 * carts[1].mass:g} | "
            f"{a.speed:g} | {dt * 1e3:g} | {cfg.solver.iterations} |")
    tail = f"{clamp:.2f} | {ended} | {wall:.0f} |"
    if end < WINDOW_START + 0.2:
        return f"{head} | | | | | | | {tail}", False
    r = report(sim, rec, WINDOW_START, end)
    m, c = r["measured"], r["catenary"]
    held = ended == "held" and abs(m["roller_ratio_lo"] - 0.5) <= 0.02 and \
        abs(m["speed_drift_per_s"]) <= 0.01
    return (f"{head} {m['v']:.3f} | {100 * m['speed_drift_per_s']:+.2f} | "
            f"{m['roller_ratio_lo']:.3f} | {m['T0_bar']:.3f} | {m['TE_bar']:.3f} | "
            f"{m['T0_bar'] - m['TE_bar'] - m['kH']:+.3f} | "
            f"{100 * c['vertex_y_rel_error']:+.1f} % | {tail}"), held


def rig_row(dt: float, push: float = 0.4, feed: str = "free", clearance: float = 0.0,
            iterations: int = 10) -> str:
    lam, v = 0.05, 3.0
    ch = ChainConfig(link_length=0.02, linear_density=lam, friction=0.6, link_radius=0.002)
    sol = SolverConfig(dt=dt, iterations=iterations, joint_error_bias=1e-10,
                       collision_slop=1e-4)
    cfg = RigConfig(mode="putdown", speed=v, cart_force=push * lam * v * v, chain=ch,
                    solver=sol, feed=feed, clearance=clearance)
    r = run_rig(cfg, duration=1.5, settle=0.5)
    return (f"| {feed} | {1e3 * clearance:g} | {push:g} | {dt * 1e3:g} | {iterations} | "
            f"{r.speed:.3f} | {r.roller_ratio:.3f} | {r.force_bar:.3f} | {r.pivot_bar:.3f} |")



def positive(kind: type) -> Callable[[str], float]:
    """argparse type: a number of ``kind`` (int or float) > 0, one line naming the value
    otherwise (also used by the sibling ``swing_study.py``)."""
    what = "a whole number" if kind is int else "a number"

    def conv(text: str) -> float:
        try:
            x = kind(text)
        except ValueError:
            x = 0
        if not x > 0:
            raise argparse.ArgumentTypeError(f"{text!r}: allowed: {what} > 0")
        return x

    return conv


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dt", type=float, nargs="+", default=[0.5, 0.35, 0.25, 0.1],
                    help="solver steps in ms")
    ap.add_argument("--seconds", type=float, default=3.0)
    ap.add_argument("--only", default="", help="run presets whose name contains this")
    ap.add_argument("--rig", action="store_true", help="the put-down rig alone")
    ap.add_argument("--clearance", type=float, default=None,
                    help="apparatus.fold_clearance in m (rig: groove line above the top)")
    ap.add_argument("--lower-cart", type=float, default=None, help="lower cart mass in kg")
    ap.add_argument("--speeds", type=float, nargs="+", default=[None],
                    help="start speeds apparatus.speed in m/s (perturbed starts of the "
                    "same level; default: the preset's)")
    ap.add_argument("--feed", choices=("free", "groove"), default="free", help="rig feed")
    ap.add_argument("--iterations", type=positive(int), nargs="+", default=[10],
                    help="rig solver iterations")
    ap.add_argument("--push", type=float, default=0.4, help="rig cart push / (lambda v^2)")
    args = ap.parse_args(argv)
    if args.rig:
        print("| feed | clearance mm | push | dt ms | iterations | chain m/s | v_R/v "
              "| entry Tbar (contacts) | entry Tbar (pivots) |")
        print("|---|---|---|---|---|---|---|---|---|")
        for it in args.iterations:
            for dt in args.dt:
                print(rig_row(dt * 1e-3, args.push, args.feed, args.clearance or 0.0, it),
                      flush=True)
        return 0
    print(f"Window {WINDOW_START:g} s to the end of a {args.seconds:g}-s run.\n")
    print("| preset | clearance mm | lower cart g | v0 m/s | dt ms | iterations | v m/s | "
          "drift %/s | lower v_R/v | Tbar_0 | Tbar_E | Tbar_0 - Tbar_E - kH | vertex | "
          "clamp N | run | wall s |")
    print("|---" * 16 + "|")
    n_runs = n_clean = 0
    for name in FOLD_PRESETS:
        if args.only not in name:
            continue
        for dt in args.dt:
            for v0 in args.speeds:
                row, held = run_preset(name, dt * 1e-3, args.seconds, args.clearance,
                                       args.lower_cart, v0)
                print(row, flush=True)
                n_runs, n_clean = n_runs + 1, n_clean + held
    print(f"\nHeld cleanly (not ended, lower v_R/v within 0.02 of 0.5, |drift| <= 1 %/s): "
          f"{n_clean} of {n_runs} runs.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
