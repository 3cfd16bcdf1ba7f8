"""Is what the gripped folds launch the paper's fountain? The flight's launch and end
tensions against ``k`` times the height between them, and its vertex against the
catenary through its measured ends, from rest, at the preset's step and at half of it.

Per preset, step and seed it runs the level from rest for ``--seconds`` (nudged at
0.1 s by the seed, as ``tests/sim/apparatus/test_fold_from_rest.py`` does; without
``--seeds`` not nudged) and reads the window ``--window`` (default: the recorder's
steady window, as ``summary.json``) from the samples: the means
of ``Tbar_0``, ``Tbar_E`` and ``Tbar_0 - Tbar_E - k (y_0 - y_E)`` (the paper's relation
with the measured ends' heights: tension minus ``lambda v^2`` grows as ``lambda g y``
along a steady flight), each with the standard error of its mean, and the vertex against
the catenary through the ends: ``summary.json``'s ``apparatus.flight`` over that window.

Usage::

    python -m research.gripped_flight apparatus_fold_gripped apparatus_special_gripped \\
        --seconds 40 --dt-factor 1 0.5
    python -m research.gripped_flight apparatus_fold_gripped apparatus_special_gripped \\
        --seconds 15 --window 10 15 --seeds 0 1 2 3 4 5

Two processes: about 1.2 min of wall time per 40-s run at the preset's step, twice that at
half of it.
"""

from __future__ import annotations

import argparse
from concurrent.futures import ProcessPoolExecutor

from chainfountain.errors import RunEnded
from chainfountain.headless.stepper import simulate
from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus_report import report
from chainfountain.study.changes import with_changes


def _run(lvl, seconds: float, seed: int | None) -> tuple[Simulation, Recorder, str]:
    if seed is None:
        sim, rec, _, ended = simulate(lvl, seconds, progress=False)
        return sim, rec, "" if ended is None else f" (ended early: {ended.reason})"
    sim = Simulation(lvl.sim)
    rec = Recorder(sim, profiles=False)
    try:
        sim.advance(0.1)
        sim.nudge(seed)
        sim.advance(seconds - 0.1)
    except RunEnded as exc:
        return sim, rec, f" (ended early: {getattr(exc, 'plain', exc)})"
    return sim, rec, ""


def one(args: tuple[str, float, float, int | None, tuple[float, float] | None]) -> str:
    name, factor, seconds, seed, window = args
    lvl = io.load(shipped_dir() / f"{name}.toml")
    if factor != 1.0:
        lvl = with_changes(lvl, {"solver.dt": lvl.sim.solver.dt * factor})
    sim, rec, why = _run(lvl, seconds, seed)
    if window is None:
        steady = rec.summary()
        t0, t1 = steady.t0, steady.t1
    else:
        t0, t1 = window
    summ = report(sim, rec, t0, t1)
    f = summ["flight"]
    m0, e0, mE, eE = f["T0_bar"], f["T0_bar_se"], f["TE_bar"], f["TE_bar_se"]
    mr, er, kH = f["relation_miss"], f["relation_miss_se"], f["kH"]
    cat = f["vertex_y_rel_error"]
    nudge = "" if seed is None else f", seed {seed}"
    return (f"{name} dt x{factor:g}{nudge}, {t0:.1f}-{t1:.1f} s of {seconds:g} s from rest"
            f"{why}: "
            f"Tbar_0 {m0:.3f} +- {e0:.3f}, Tbar_E {mE:.3f} +- {eE:.3f}, "
            f"Tbar_0 - Tbar_E - k dy {mr:+.3f} +- {er:.3f} (k H {kH:.3f}), "
            f"vertex {100 * cat:+.1f} % of the catenary through the ends")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("levels", nargs="+")
    ap.add_argument("--seconds", type=float, default=40.0)
    ap.add_argument("--dt-factor", type=float, nargs="+", default=[1.0])
    ap.add_argument("--seeds", type=int, nargs="+", default=[None])
    ap.add_argument("--window", type=float, nargs=2, default=None)
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args()
    w = tuple(a.window) if a.window else None
    todo = [(n, f, a.seconds, s, w) for n in a.levels for f in a.dt_factor for s in a.seeds]
    with ProcessPoolExecutor(a.jobs) as ex:
        for line in ex.map(one, todo):
            print(line, flush=True)


if __name__ == "__main__":
    main()
