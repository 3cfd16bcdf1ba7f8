"""Tuning the gripped fold: the speed ``apparatus_fold_gripped`` selects over both carts.

Runs ``chainfountain sweep`` on ``apparatus_fold_gripped`` (the paper's full arrangement
with the gripped folding roller, its brake and the following end guide) over a grid of
upper- and lower-cart masses, each point from rest for ``--duration`` simulated seconds
(the starter lets go about 5 s in; the speed is the mean over the run's last
``recording.window``, 4 s), once per seed of ``--seeds`` (a seed above 0 nudges the
start by 1e-12: another of the machine's chaotic runs), and prints and draws the
selected speed against the paper's laws with the brake (``summary.json``
``apparatus.predicted_paper.v_steady``: ``v = 2 (F_lc + lambda g H (1 - xi2 - xi3) - F_uc)/c``,
:func:`chainfountain.sim.apparatus.laws.braked_fold_speed`). Points that end early (the
fountain misses the end guide, the chain runs away) are drawn as crosses; the window's
sliders allow the ringed pairs
(:func:`chainfountain.sim.apparatus.laws.fold_runs_on`).

Usage::

    python -m research.fold_tuning --out /tmp/fold_tuning --jobs 2 --seeds 0 1 \\
        --figure docs/img/fold_tuning.png

Cost: 30 pairs, two seeds, 30 s each at about 1.6x real time: about 10 min on two cores.
"""

from __future__ import annotations

import copy
import math
import sys
from pathlib import Path

import numpy as np

from chainfountain.level.library import shipped_dir
from research.ideal_tuning import (
    run_grid,
    save_figure,
    tuning_args,
)

UPPER = (0.008, 0.013, 0.019, 0.024, 0.027)
LOWER = (0.296, 0.301, 0.306, 0.311, 0.326, 0.341)
LEVEL = "apparatus_fold_gripped"
ROOT = Path(__file__).resolve().parents[1]


def _allowed(m_up: float, m_lo: float) -> bool:
    """Whether the window's sliders allow this pair (the level's measured bands)."""
    from chainfountain.level import io
    from chainfountain.sim.apparatus.laws import fold_runs_on

    base = io.load(shipped_dir() / f"{LEVEL}.toml").sim
    cfg = copy.deepcopy(base)
    cfg.carts[0].mass, cfg.carts[1].mass = m_up, m_lo
    return fold_runs_on(cfg, base)


def main(argv: list[str] | None = None) -> int:
    a = tuning_args(__doc__, 30.0, argv)
    rows = run_grid(LEVEL, {"carts[0].mass": UPPER, "carts[1].mass": LOWER}, a, a.seeds)
    pairs: dict[tuple[float, float], list[dict]] = {}
    for r in rows:
        pairs.setdefault((r["carts[0].mass"], r["carts[1].mass"]), []).append(r)
    print(f"{'upper g':>8s} {'lower g':>8s} {'sliders':>8s} {'held':>5s} {'paper':>7s} "
          f"{'measured':>16s} {'vs paper':>9s}")
    pts = []
    for (m_up, m_lo), runs in pairs.items():
        vs = [r["apparatus_measured_v"] for r in runs
              if r["status"] == "done" and r.get("apparatus_measured_v") is not None]
        paper = next((r.get("apparatus_predicted_paper_v_steady") for r in runs
                      if r.get("apparatus_predicted_paper_v_steady")), None)
        allowed = _allowed(m_up, m_lo)
        held = f"{len(vs)}/{len(runs)}"
        if vs and paper:
            v = float(np.mean(vs))
            spread = f"{v:.3f} +- {np.std(vs):.3f}" if len(vs) > 1 else f"{v:.3f}"
            tail = f"{paper:7.3f} {spread:>16s} {v / paper - 1:+9.2%}"
        else:
            v = math.nan
            tail = f"{paper or math.nan:7.3f} {'':>16s} {'':>9s}"
        print(f"{1e3 * m_up:8.1f} {1e3 * m_lo:8.1f} {'yes' if allowed else 'no':>8s} "
              f"{held:>5s} {tail}")
        for r in runs:
            if r["status"] != "done":
                print(f"{'':>18s} seed {r.get('seed')}: {str(r.get('reason', ''))[:100]}")
        pts.append((m_up, m_lo, paper or np.nan, v, len(vs), len(runs), allowed))
    if a.figure and pts:
        _figure(pts, a)
    return 0


def _figure(pts: list[tuple], a) -> None:  # noqa: ANN001 (argparse namespace)
    """Left: the selected speed against the upper cart, one colour per lower cart, with
    the paper's laws; right: the grid of pairs, held by every seed or not."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11.0, 4.4), dpi=110)
    n_seeds = max(p[5] for p in pts)
    for i, m_lo in enumerate(LOWER):
        col = f"C{i}"
        sel = [p for p in pts if p[1] == m_lo]
        ax.plot([1e3 * p[0] for p in sel], [p[2] for p in sel], ":", color=col, lw=1)
        held = [p for p in sel if p[4] == p[5]]
        ax.plot([1e3 * p[0] for p in held], [p[3] for p in held], "o", color=col,
                label=f"lower cart {1e3 * m_lo:g} g")
        lost = [p for p in sel if p[4] < p[5]]
        ax.plot([1e3 * p[0] for p in lost], [p[2] for p in lost], "x", color=col, ms=8)
    ax.plot([], [], ":", color="0.4", lw=1, label="paper's laws with the brake")
    ax.plot([], [], "x", color="0.4", label="a run ended (drawn at the laws' speed)")
    ax.set_xlabel("upper cart mass (g), on a 30 deg track")
    ax.set_ylabel("chain speed (m/s)")
    ax.set_title(f"{LEVEL} from rest: the selected speed\n(last 4 s of {a.duration:g}-s runs"
                 + (f", mean of {n_seeds} starts)" if n_seeds > 1 else ")"), fontsize=10)
    save_figure(fig, ax, a.figure, 7)
    for p in pts:
        x, y = 1e3 * p[0], 1e3 * p[1]
        every = p[4] == p[5]
        bx.plot(x, y, "o" if every else "x", color="C2" if every else "C3", ms=9)
        label = f"{p[3] / p[2] - 1:+.1%}" if every and np.isfinite(p[2]) else \
            f"{p[4]}/{p[5]} held"
        bx.annotate(label, (x, y), textcoords="offset points", xytext=(6, 4), fontsize=7)
        if p[6]:  # the sliders allow the pair: a grey ring
            bx.plot(x, y, "o", mfc="none", mec="0.3", ms=15)
    bx.plot([], [], "o", color="C2", label="every start held (speed against the laws')")
    bx.plot([], [], "x", color="C3", label="a start ended early")
    bx.plot([], [], "o", mfc="none", mec="0.3", ms=12, label="the sliders allow the pair")
    bx.set_xlabel("upper cart mass (g)")
    bx.set_ylabel("lower cart mass (g)")
    bx.set_title(f"which pairs hold from rest ({n_seeds} start{'s' if n_seeds > 1 else ''} "
                 "each)", fontsize=10)
    save_figure(fig, bx, a.figure, 7)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
