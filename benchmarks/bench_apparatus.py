"""Speed of the apparatus presets: real-time factor, links, steps per second.

    .venv/bin/python benchmarks/bench_apparatus.py [--seconds 6] [--repeat 3] [--only special]
    .venv/bin/python benchmarks/bench_apparatus.py --only special --upper-guide walls joints
    .venv/bin/python benchmarks/bench_apparatus.py --figure docs/img/apparatus_floor.png
    .venv/bin/python benchmarks/bench_apparatus.py --overhead [--only fold]

``--overhead`` times each preset's ``Simulation.step`` against the ``space.step`` inside it
(wall clock, 4000 pymunk steps after 500, each preset laid along its path): the
apparatus's bookkeeping (guides, treadmills, absorbing; once per ``solver.dt``, i.e. every
``solver.substeps`` pymunk steps) and its per-step forces are the difference. The column
"arc projection" is the part of it spent putting held links back onto the joint guides'
arcs (:func:`chainfountain.sim.apparatus.joints.keep_on_arcs`, every held link every
bookkeeping step), the one piece of the bookkeeping that is not an event check.

``--figure`` instead runs the two floor presets (6 s and 5 s) and the 9 g one
started at 3.1 m/s (about 25 s of wall time) and draws the chain speed against
time with the selected-speed predictions (rig law for these links, paper
``p = 1/2``), and the last fountain of ``apparatus_floor`` against the inverted
catenary through its measured ends (paper Eq. of the catenary, launch at
``alpha0``).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import time
from pathlib import Path

import numpy as np

from chainfountain.errors import RunEnded
from chainfountain.headless import default_duration
from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Recorder, Simulation
from chainfountain.sim.apparatus_report import catenary_through, report
from chainfountain.study.changes import laid_on_path

ROOT = Path(__file__).resolve().parents[1]


def bench(seconds: float, repeat: int = 1, only: str = "",
          guides: tuple[str | None, ...] = (None,)) -> None:
    """Markdown table of the real-time factor of every apparatus preset (names
    containing ``only``), built with each of ``guides`` (``apparatus.upper_guide``;
    None: as in the level). With ``repeat > 1`` each preset runs that many times and
    the table gives the best and the median: this machine's speed wanders by
    20-40 % between identical runs, and the best is the least disturbed one. The
    builds' runs alternate, so a slow spell of the machine hits them alike."""
    print("| preset | upper guide | links (start/end) | steps/s (best) "
          "| real-time factor best / median |")
    print("|---|---|---|---|---|")
    for path in sorted((shipped_dir()).glob("apparatus_*.toml")):
        if only not in path.stem:
            continue
        lvl = io.load(path)
        T = min(seconds, default_duration(lvl))  # a table-sized preset stops with its table
        cfgs = [lvl.sim if g is None else dataclasses.replace(
            lvl.sim, apparatus=dataclasses.replace(lvl.sim.apparatus, upper_guide=g))
            for g in guides]
        walls: list[list[float]] = [[] for _ in cfgs]
        links = [(0, 0)] * len(cfgs)
        for _ in range(repeat):
            for i, cfg in enumerate(cfgs):
                sim = Simulation(cfg)
                n0 = sim.n_links
                t0 = time.perf_counter()
                steps = sim.advance(T)
                walls[i].append(time.perf_counter() - t0)
                links[i] = (n0, sim.n_links)
        for cfg, w, (n0, n1) in zip(cfgs, walls, links, strict=True):
            best, med = min(w), float(np.median(w))
            print(f"| {path.stem} ({T:g} s) | {cfg.apparatus.upper_guide} | {n0}/{n1} | "
                  f"{steps / best:.0f} | {T / best:.2f} / {T / med:.2f} |", flush=True)


def overhead(only: str = "", steps: int = 4000, warmup: int = 500) -> None:
    """Markdown table: microseconds per pymunk step of each apparatus preset (names
    containing ``only``), all of ``Simulation.step`` and the ``space.step`` inside it, and
    their ratio. ``steps`` and ``warmup`` count pymunk steps; a preset with
    ``solver.substeps = k`` does its bookkeeping once per ``k`` of them."""
    from chainfountain.sim.apparatus import fold, upper_guide

    print("| preset | links | substeps | per pymunk step (us) | space.step (us) "
          "| arc projection (us) | step / space.step |")
    print("|---|---|---|---|---|---|---|")
    projection = [0.0]
    keep = fold.keep_on_arcs

    def timed_keep(*args, _keep=keep, _acc=projection) -> None:
        t = time.perf_counter()
        _keep(*args)
        _acc[0] += time.perf_counter() - t

    fold.keep_on_arcs = upper_guide.keep_on_arcs = timed_keep
    try:
        for path in sorted((shipped_dir()).glob("apparatus_*.toml")):
            if only in path.stem:
                _overhead_row(path, steps, warmup, projection)
    finally:
        fold.keep_on_arcs = upper_guide.keep_on_arcs = keep


def _overhead_row(path: Path, steps: int, warmup: int, projection: list[float]) -> None:
    """One row of :func:`overhead`: the preset at ``path``, ``projection[0]`` accumulating
    the arc projection's wall time."""
    lvl = io.load(path)
    sim = Simulation(laid_on_path(lvl).sim)
    k = int(lvl.sim.solver.substeps)
    sim.advance(warmup * sim.h)
    inner = [0.0]
    projection[0] = 0.0
    space_step = sim.space.step

    def timed(dt: float, _step=space_step, _acc=inner) -> None:
        t = time.perf_counter()
        _step(dt)
        _acc[0] += time.perf_counter() - t

    sim.space.step = timed  # type: ignore[method-assign]
    n = min(steps // k, int(round(default_duration(lvl) / sim.dt)) - warmup // k)
    t0 = time.perf_counter()
    done, note = 0, ""
    try:
        for _ in range(n):
            sim.step()
            done += 1
    except RunEnded:  # apparatus_limit's fold: timed up to its end
        note = f" (its run ends at {sim.time:.2f} s)"
    total = time.perf_counter() - t0
    m = max(done, 1) * k
    print(f"| {path.stem}{note} | {sim.n_links} | {k} | {total / m * 1e6:.0f} | "
          f"{inner[0] / m * 1e6:.0f} | {projection[0] / m * 1e6:.0f} | "
          f"{total / inner[0]:.2f} |", flush=True)


def figure(out: Path) -> None:
    """Speed selection of the two floor presets and the fountain against the catenary."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2))
    shape = None
    runs = (("apparatus_floor", 6.0, "C0", None), ("apparatus_floor_heavy", 5.0, "C3", None),
            ("apparatus_floor", 6.0, "C0", 3.1))
    for name, T, col, v0 in runs:
        lvl = laid_on_path(io.load(shipped_dir() / f"{name}.toml"))
        if v0 is not None:  # same level started faster: it relaxes toward its speed
            lvl.sim.apparatus.speed = v0
            sim = Simulation(lvl.sim)
            t, v = [], []
            for _ in range(int(round(T / 0.01))):
                sim.advance(0.01)
                t.append(sim.time)
                v.append(sim.apparatus.strand_speed)
            ax.plot(t, v, color=col, lw=0.8, alpha=0.7, label=f"same, started at {v0:g}")
            continue
        sim = Simulation(lvl.sim)
        rec = Recorder(sim, profiles=False)
        app = sim.apparatus
        t, v = [], []
        for _ in range(int(round(T / 0.01))):
            sim.advance(0.01)
            t.append(sim.time)
            v.append(app.strand_speed)
        rep = report(sim, rec, 3.0, T)
        sel = rep["speed_selection"]
        m_cart = lvl.sim.carts[0].mass * 1e3
        ax.plot(t, v, color=col, label=f"{m_cart:.0f} g cart: measured {sel['v_measured']:.2f}")
        vr, sv = sel["v_rig_2cm"], sel["v_rig_2cm_sigma"]
        ax.axhspan(vr - 2 * sv, vr + 2 * sv, color=col, alpha=0.15)
        ax.axhline(vr, color=col, ls="--", lw=1, label=f"rig law {vr:.2f} +- 2 sigma")
        ax.axhline(sel["v_paper_p_half"], color=col, ls=":", lw=1,
                   label=f"paper p = 1/2: {sel['v_paper_p_half']:.2f}")
        if shape is None:
            st = sim.state()
            P = st.position
            fl = (P[:, 0] > 0.0) & (P[:, 1] > -app.H)
            m = rep["measured"]
            shape = (P[fl], m["end"], app.alpha0)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("chain speed on the plate (m/s)")
    ax.set_ylim(1.9, 3.25)
    ax.legend(fontsize=7, loc="lower right", ncol=2)
    ax.set_title("free end (absorbing floor): the speed selects itself")
    pts, end, a0 = shape
    q = catenary_through(a0, tuple(end))
    h = (1.0 / math.cos(a0) - 1.0) / q
    xr = math.acosh(1.0 + q * h) / q
    xs = np.linspace(0.0, end[0], 200)
    bx.plot(pts[:, 0], pts[:, 1], ".", ms=3, label="links (t = 6 s)")
    bx.plot(xs, h + (1.0 - np.cosh(q * (xs - xr))) / q, "k-", lw=1,
            label="catenary through the measured ends")
    bx.set_aspect("equal")
    bx.set_xlabel("x (m)")
    bx.set_ylabel("y (m)")
    bx.legend(fontsize=7, loc="lower left")
    bx.set_title("apparatus_floor: fountain (start at 0, 0)")
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--seconds", type=float, default=6.0, help="simulated seconds per preset")
    ap.add_argument("--repeat", type=int, default=1,
                    help="runs per preset; the table gives the best and the median")
    ap.add_argument("--only", default="", help="only presets whose name contains this")
    ap.add_argument("--figure", type=Path, default=None, help="draw the speed-selection figure")
    ap.add_argument("--overhead", action="store_true",
                    help="time each preset's step against the space.step inside it")
    ap.add_argument("--upper-guide", nargs="+", default=[None], choices=("walls", "joints"),
                    help="build each preset with these apparatus.upper_guide values "
                    "(default: as in the level)")
    args = ap.parse_args()
    if args.repeat < 1:
        ap.error(f"--repeat: {args.repeat} is not a number of runs; allowed: 1 or more")
    names = [p.stem for p in sorted((shipped_dir()).glob("apparatus_*.toml"))]
    if not any(args.only in n for n in names):
        ap.error(f"--only: {args.only!r} matches no apparatus preset; allowed: part of one of "
                 f"{', '.join(names)}")
    if args.figure is not None:
        figure(args.figure)
    elif args.overhead:
        overhead(args.only)
    else:
        bench(args.seconds, args.repeat, args.only, tuple(args.upper_guide))


if __name__ == "__main__":
    main()
