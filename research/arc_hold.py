"""How a joint guide holds its links on its arcs, and what that does to the machine's
speed and start tension at the preset's pymunk step and at half of it.

The joint guides (upper channel, 'fold' lower channel) hold each link on an arc with a
slide joint to the arc's centre, limits ``R -+ PLAY``. As built, the slide joint has
pymunk's default error bias (``guide.GUIDE_BIAS``) and the bookkeeping puts links that
have left the limits back onto them (``joints.keep_on_arcs``, every ``solver.dt``).
``--hold`` chooses how:

* ``project``: as built.
* ``bias``: no projection; the slide joints correct their own error with the error bias
  ``--bias`` (pymunk solves it in every pymunk step; the bookkeeping only closes the
  limits of links captured off the radius).

Per run: mean chain speed and the scaled start tension ``Tbar_0`` over ``--window``,
laid on its path, from the level's start.

Usage::

    python -m research.arc_hold --level apparatus_fold_gripped --hold project bias \\
        --bias 1e-10 --dt-factor 1 0.5 --window 1 4
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import time

import numpy as np

from chainfountain.errors import RunEnded
from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Recorder, Simulation, guide
from chainfountain.sim.apparatus import fold, joints, upper_guide
from chainfountain.study.changes import laid_on_path, with_changes
from research.gripped_fold import _value

LEVELS = shipped_dir()
ORIG_KEEP = joints.keep_on_arcs


def close_only(els, qs, close: float) -> None:
    """``keep_on_arcs`` without the projection: only close captured links' limits."""
    for el, q in zip(els, qs, strict=True):
        if el.form != "arc":
            continue
        lo, hi = el.R - guide.PLAY, el.R + guide.PLAY
        for _, j in q:
            j_min, j_max = j.lim
            if j_max > hi or j_min < lo:
                h = j.handle
                p = joints.fastbody.get_position(h)
                d = math.hypot(p.x - el.a[0], p.y - el.a[1])
                j.set_limits(min(lo, max(j_min + close, d)), max(hi, min(j_max - close, d)))


def run(level: str, hold: str, bias: float, factor: float, window: tuple[float, float],
        sets: list[str]) -> str:
    keep = ORIG_KEEP if hold == "project" else close_only
    fold.keep_on_arcs = upper_guide.keep_on_arcs = keep
    guide.GUIDE_BIAS = bias if hold == "bias" else 0.0018
    lvl = io.load(LEVELS / f"{level}.toml")
    ch = {k: _value(v) for k, v in (x.split("=", 1) for x in sets)}
    if factor != 1.0:
        ch["solver.dt"] = lvl.sim.solver.dt * factor
    cfg = with_changes(laid_on_path(lvl), ch).sim
    sim = Simulation(cfg)
    rc = dataclasses.replace(cfg.recording, sample_interval=0.002)
    rec = Recorder(sim, rc)
    sim.recorder = rec
    t0 = time.perf_counter()
    note = "held"
    try:
        sim.advance(window[1])
    except RunEnded as e:
        note = f"ended {sim.time:.2f} s: {e}"[:80]
    wall = time.perf_counter() - t0
    ss = [a for a in rec.apparatus_samples if window[0] <= a.t <= window[1]]
    v = np.array([a.v for a in ss])
    t0b = np.array([a.T0_bar for a in ss])
    ex = np.array([a.end_x for a in ss])
    return (f"{level} hold={hold} bias={bias:g} h={sim.h * 1e3:.3g} ms: "
            f"v {np.nanmean(v):.4f} m/s, Tbar_0 {np.nanmean(t0b):.4f}, end_x "
            f"{np.nanmean(ex):.4f} m over {window[0]:g}-{window[1]:g} s; {note}; "
            f"{wall:.0f} s wall")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="apparatus_fold_gripped")
    ap.add_argument("--hold", nargs="+", default=["project", "bias"],
                    choices=("project", "bias"))
    ap.add_argument("--bias", type=float, default=1e-10)
    ap.add_argument("--dt-factor", type=float, nargs="+", default=[1.0, 0.5])
    ap.add_argument("--window", type=float, nargs=2, default=[1.0, 4.0])
    ap.add_argument("--set", nargs="*", default=[], metavar="PATH=VALUE")
    a = ap.parse_args()
    for hold in a.hold:
        for f in a.dt_factor:
            print(run(a.level, hold, a.bias, f, tuple(a.window), a.set), flush=True)


if __name__ == "__main__":
    main()
