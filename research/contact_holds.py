"""How long the contact machine (``kind = "apparatus"``) holds its fountain.

Runs a contact apparatus level for ``--duration`` simulated seconds with field changes
(``--set apparatus.bearing_drag=0.05``; repeatable) at its step times ``--dt-factor``,
and prints, per ``--window``-second window, the mean chain speed (twice the pick-up
roller's), the speed's drift (slope of a line through it over the mean, %/s) and its
swing (max - min of the folding roller's chain speed), then when and why the run ended.

Usage::

    python -m research.contact_holds apparatus_special --duration 60 \
        --set apparatus.bearing_drag=0.05 --dt-factor 0.5
    python -m research.contact_holds apparatus_fold_gripped --duration 600 --seed 1 --laid
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from chainfountain.level.library import shipped_dir

LEVELS = shipped_dir()


def _value(text: str) -> int | float | str:
    """A ``--set`` value: a whole number, a number, or a word (``joints``)."""
    if text.lstrip("-").isdigit():
        return int(text)
    try:
        return float(text)
    except ValueError:
        return text


def run(name: str, duration: float, window: float, dt_factor: float,
        changes: dict[str, str], seed: int | None = None, laid: bool = False) -> dict:
    """One run; per-window figures and the end. ``seed``: nudge the start
    (:meth:`~chainfountain.sim.world.Simulation.nudge`, 1e-12 of each velocity)."""
    from chainfountain.level import io
    from chainfountain.sim import Simulation
    from chainfountain.study.changes import laid_on_path, with_changes

    level = io.load(LEVELS / f"{name}.toml")
    if laid:
        level = laid_on_path(level)
    if changes:
        level = with_changes(level, {k: _value(v) for k, v in changes.items()})
    cfg = level.sim
    cfg.solver.dt *= dt_factor
    sim = Simulation(cfg)
    if seed is not None:
        sim.nudge(seed)
    app = sim.apparatus
    every = max(1, int(round(0.02 / sim.dt)))
    wall = time.perf_counter()
    windows, ended = [], None
    t = 0.0
    while t + window <= duration + 1e-9 and ended is None:
        ts, vs, vl = [], [], []
        n = int(round(window / sim.dt))
        try:
            for i in range(n):
                sim.step()
                if i % every == 0:
                    ts.append(sim.time)
                    vs.append(app.speed)
                    vl.append(2 * abs(app.lower.speed) if app.lower is not None else np.nan)
        except Exception as exc:  # noqa: BLE001 - reported
            ended = f"{sim.time:.2f} s {type(exc).__name__}: {str(exc)[:160]}"
        t += window
        if len(ts) < 3:
            break
        ts_a, vs_a = np.asarray(ts), np.asarray(vs)
        slope = np.polyfit(ts_a, vs_a, 1)[0]
        v_mean = float(vs_a.mean())
        windows.append({"t1": round(ts[-1], 2), "speed": round(v_mean, 4),
                        "drift_pct_s": round(100 * float(slope / v_mean), 4),
                        "fold_swing": round(float(np.max(vl) - np.min(vl)), 4)
                        if app.lower is not None else None})
    return {"level": name, "changes": changes, "seed": seed, "dt": sim.dt, "ended": ended,
            "simulated_s": round(sim.time, 2), "wall_s": round(time.perf_counter() - wall, 1),
            "windows": windows}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("level")
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--window", type=float, default=10.0)
    ap.add_argument("--dt-factor", type=float, default=1.0)
    ap.add_argument("--set", action="append", default=[], metavar="FIELD=VALUE")
    ap.add_argument("--seed", type=int, help="nudge the start by 1e-12 with this seed")
    ap.add_argument("--laid", action="store_true",
                    help="start laid on its path, moving, not from the level's own start")
    ns = ap.parse_args()
    changes = dict(s.split("=", 1) for s in ns.set)
    print(json.dumps(run(ns.level, ns.duration, ns.window, ns.dt_factor, changes, ns.seed,
                         ns.laid), indent=1))


if __name__ == "__main__":
    main()
