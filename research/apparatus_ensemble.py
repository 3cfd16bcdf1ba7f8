"""Ensembles of the apparatus's chaotic readings over nudged starts.

A run of an apparatus level is chaotic: a change of its start in the last bits (another
machine, another library build) gives another trajectory, and some readings of a short
window (the fountain's tensions while near-critical fountain D breathes, the cart step's
deceleration, the open arrangement's speed) differ from run to run by more than the
tolerance a test would set. This script runs each reading over ``--seeds`` starts, each
nudged by :meth:`chainfountain.sim.Simulation.nudge` (``1e-12`` of the velocities), and
prints every run's value, the ensemble mean, its standard error and the single-run
standard deviation. The suite asserts only what one run settles; what needs an ensemble
is measured here, and its figures are quoted in ``docs/apparatus.md`` ("Ensembles").

Usage::

    python -m research.apparatus_ensemble                  # every reading, 8 seeds
    python -m research.apparatus_ensemble fountain_d --seeds 4 --jobs 2

Fountain D's two presets take about 30 s a run, the others 2-15 s.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import statistics
import sys
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor

from chainfountain.level.library import shipped_dir

LEVELS = shipped_dir()


def _sim(name: str, seed: int, cfg=None):
    from chainfountain.level import io
    from chainfountain.sim import Simulation
    from chainfountain.study.changes import laid_on_path

    sim = Simulation(cfg if cfg is not None else laid_on_path(io.load(LEVELS / f"{name}.toml")).sim)
    if seed:
        sim.nudge(seed)
    return sim


def fountain_d(seed: int) -> dict[str, float]:
    """Both fountain D presets over 1.5 s, window 0.25-1.5 s (as its tests)."""
    from chainfountain.sim import Recorder
    from chainfountain.sim.apparatus_report import report

    out = {}
    for tag, name in (("kmax", "apparatus_fountain_d_kmax"), ("k0377", "apparatus_fountain_d")):
        sim = _sim(name, seed)
        rec = Recorder(sim, profiles=False)
        sim.advance(1.5)
        r = report(sim, rec, 0.25, 1.5)
        m = r["measured"]
        out[f"{tag} T0-TE-kH"] = m["T0_bar"] - m["TE_bar"] - m["kH"]
        out[f"{tag} TE"] = m["TE_bar"]
        out[f"{tag} v"] = m["v"]
        out[f"{tag} drift/s"] = m["speed_drift_per_s"]
        out[f"{tag} vertex_y err"] = r["catenary"]["vertex_y_rel_error"]
    return out


def cart_step(seed: int) -> dict[str, float]:
    """The heavier cart's step on the floor preset (tests/sim/apparatus/test_carts.py)."""
    from chainfountain.level import io
    from chainfountain.sim.apparatus import CART_GAIN_2CM
    from chainfountain.study.changes import laid_on_path
    from research.rigs.cart_step import cart_step as step

    cfg = laid_on_path(io.load(LEVELS / "apparatus_floor.toml")).sim
    cfg = dataclasses.replace(cfg, apparatus=dataclasses.replace(cfg.apparatus, plate_links=0))
    s = step(cfg, 0.06, 1.0, 0.6, seed=seed)
    return {"closure/M_up": s.closure_mass / s.m_up, "dT_launch/dT_exit": s.dT_launch / s.dT_exit,
            "pickup gain": s.pickup_gain, "ratio gain 0.5": s.ratio(gain=0.5),
            "ratio rig gain": s.ratio(gain=CART_GAIN_2CM), "ratio gain 1": s.ratio(gain=1.0)}


def open_run(seed: int) -> dict[str, float]:
    """The open arrangement over 2.2 s, window 0.1-2.2 s
    (tests/sim/apparatus/test_open.py)."""
    from chainfountain.sim import Recorder
    from chainfountain.sim.apparatus_report import report

    sim = _sim("apparatus_open", seed)
    rec = Recorder(sim, profiles=False)
    sim.advance(2.2)
    r = report(sim, rec, 0.1, 2.2)
    m, o = r["measured"], r["open"]
    lam = sim.config.chain.linear_density
    return {"exit - rig": m["T_pickup_exit_bar"] - o["exit_tension_rig_N"] / (lam * m["v"] ** 2),
            "T0-TE-kH": m["T0_bar"] - m["TE_bar"] - m["kH"], "v": m["v"],
            "drift/s": m["speed_drift_per_s"]}


READINGS: dict[str, Callable[[int], dict[str, float]]] = {
    "fountain_d": fountain_d, "cart_step": cart_step, "open": open_run}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("readings", nargs="*", choices=[[], *READINGS], default=[],
                    help="which readings (default: all)")
    ap.add_argument("--seeds", type=int, default=8, help="runs per reading (seeds 0 .. N-1)")
    ap.add_argument("--jobs", type=int, default=1, help="worker processes")
    args = ap.parse_args(argv)
    if args.seeds < 2:
        ap.error(f"--seeds: {args.seeds}; allowed: at least 2 (a spread needs two runs)")
    names = args.readings or list(READINGS)
    with ProcessPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        for name in names:
            print(f"{name}: {args.seeds} runs (seeds 0-{args.seeds - 1})", flush=True)
            runs = list(pool.map(READINGS[name], range(args.seeds)))
            for key in runs[0]:
                vals = [r[key] for r in runs]
                sd = statistics.stdev(vals)
                print(f"  {key:22s} mean {statistics.fmean(vals):+.4f} "
                      f"+- {sd / math.sqrt(len(vals)):.4f} (s.e.), one run sd {sd:.4f}; "
                      + " ".join(f"{v:+.4f}" for v in vals), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
