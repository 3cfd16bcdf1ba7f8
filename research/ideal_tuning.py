"""Tuning the ideal full machine: the speed it selects against the paper's laws.

Runs ``chainfountain sweep`` on ``ideal_fold`` (bearing drag 0.06 N*s/m) over a grid of
lower-cart forces and beaker offsets ``xi2`` (``--duration`` simulated seconds each from
the level's 4.7 m/s start; the figure uses each run's last ``recording.window``), and draws
the measured speed against ``v = (F_lc + lambda g H (1 - xi2 - xi3) - F_uc)/c``
(:func:`chainfountain.theory.apparatus.ideal_fold_speed`). Points the level check
refuses (no fountain at the speed they would select) are listed, not drawn.

Usage::

    python -m research.ideal_tuning --out /tmp/tuning --jobs 2 --figure docs/img/ideal_tuning.png

Cost: 15 points of 25 s at about 2-3x real time: 2-3 min on two cores.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from chainfountain.level.library import shipped_dir

ROOT = Path(__file__).resolve().parents[1]
LOWER = (0.14, 0.17, 0.2, 0.23, 0.26)
XI2 = (0.15, 0.25, 0.35)


def tuning_args(doc: str, duration: float, argv: list[str] | None) -> argparse.Namespace:
    """The tuning scripts' options: ``--out`` (required), ``--duration``, ``--jobs``,
    ``--figure``, ``--seeds``."""
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--duration", type=float, default=duration)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--figure", type=Path)
    ap.add_argument("--seeds", type=int, nargs="+", default=None,
                    help="run every point once per seed (an apparatus: a seed above 0 "
                    "nudges its start by 1e-12)")
    return ap.parse_args(argv)


def run_grid(level: str, grid: dict[str, tuple[float, ...]], a: argparse.Namespace,
             seeds: list[int] | None = None) -> list[dict]:
    """Sweep the shipped ``level`` over ``grid`` (field: values) for ``a.duration`` s per
    point into ``a.out`` on ``a.jobs`` processes (``chainfountain sweep``), once per seed
    of ``seeds`` if given; its rows."""
    a.out.mkdir(parents=True, exist_ok=True)
    sweep_file = a.out / "tuning.toml"
    lines = "".join(f'"{k}" = {list(v)}\n' for k, v in grid.items())
    seeded = f"seeds = {list(seeds)}\n" if seeds else ""
    sweep_file.write_text(f'base = "{shipped_dir() / f"{level}.toml"}"\n'
                          f"duration = {a.duration}\n{seeded}[grid]\n{lines}")
    from chainfountain.study import sweep

    sw = sweep.load(sweep_file)
    sweep.execute(sw, a.out, jobs=a.jobs)
    return sweep.collect(sw, a.out)


def save_figure(fig, ax, path: Path, legend_size: int) -> None:  # noqa: ANN001 (matplotlib)
    """The tuning figures' common end: legend, grid, layout, written to ``path``."""
    ax.legend(fontsize=legend_size)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    print(f"wrote {path}")


def main(argv: list[str] | None = None) -> int:
    a = tuning_args(__doc__, 25.0, argv)
    rows = run_grid("ideal_fold", {"feed.lower_cart_force": LOWER, "feed.xi2": XI2}, a)
    print(f"{'F_lc N':>7s} {'xi2':>5s} {'status':>8s} {'paper v':>8s} {'measured':>9s} "
          f"{'error':>8s}")
    pts = []
    for r in rows:
        v_th, v = r.get("theory_v"), r.get("v")
        status = r["status"]
        shown = (f"{v_th:8.3f} {v:9.3f} {v / v_th - 1:+8.2%}" if status == "done" and v_th
                 else f"  {r.get('reason', '')[:70]}")
        print(f"{r['feed.lower_cart_force']:7.3f} {r['feed.xi2']:5.2f} {status:>8s} {shown}")
        if status == "done" and v_th:
            pts.append((r["feed.lower_cart_force"], r["feed.xi2"], v_th, v))
    if a.figure and pts:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        p = np.array(pts)
        fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=110)
        for xi2 in XI2:
            m = p[:, 1] == xi2
            if m.any():
                ax.plot(p[m, 0], p[m, 2], "-", lw=1, color="0.6")
                ax.plot(p[m, 0], p[m, 3], "o", label=f"xi2 = {xi2:g}")
        ax.plot([], [], "-", color="0.6",
                label="paper's laws: (F_lc + lambda g H (1-xi2-xi3) - F_uc)/c")
        ax.set_xlabel("lower cart F_lc (N)")
        ax.set_ylabel("chain speed (m/s)")
        ax.set_title(f"ideal_fold: selected speed, last 2 s of {a.duration:g}-s runs", fontsize=10)
        save_figure(fig, ax, a.figure, 8)
    return 0


if __name__ == "__main__":
    sys.exit(main())
