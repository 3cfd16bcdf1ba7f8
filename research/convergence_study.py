"""Convergence study of the fed fountain against the paper's catenary (not a test).

Usage: ``.venv/bin/python -m research.convergence_study [--quick]``

Scans link length, time step and solver iterations around the defaults for the
shipped presets, prints a markdown table of the errors against
:class:`~chainfountain.sim.reference.LaunchReference` (vertex height, vertex x,
landing x, RMS of scaled tension, stretch, speed uniformity, wall time) and
writes ``docs/img/convergence.png``. Each run starts on the predicted catenary,
settles ``SETTLE`` s and is averaged over ``WINDOW`` s. Takes a few minutes.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import math  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

from chainfountain.sim import Recorder, SimConfig, Simulation  # noqa: E402
from chainfountain.sim.config import FeedConfig  # noqa: E402

SETTLE = 1.5
WINDOW = 2.0
OUT = Path(__file__).resolve().parent.parent / "docs" / "img" / "convergence.png"

KEYS = ("vertex_y", "vertex_x", "landing_x", "tension_rms")
ERRORS = {"vertex_y": "h", "landing_x": "l"}
"""The names :meth:`~chainfountain.sim.measure.Summary.errors` gives the columns."""

PRESETS = {
    # the study's two fountains at the solver defaults, started on the catenary
    "paper_tall": dict(speed=5.5, launch_angle=math.radians(80.0), drop=2.0, floor_width=4.0),
    "wide_low": dict(speed=4.0, launch_angle=math.radians(60.0), drop=0.5, floor_width=4.0),
}


def run(preset: str, *, L: float | None = None, dt: float | None = None,
        iterations: int | None = None) -> dict[str, float]:
    cfg = SimConfig(name=preset, feed=FeedConfig(**PRESETS[preset]))
    if L is not None:
        cfg.chain.link_length = L
    if dt is not None:
        cfg.solver.dt = dt
    if iterations is not None:
        cfg.solver.iterations = iterations
    sim = Simulation(cfg)
    t0 = time.perf_counter()
    sim.advance(SETTLE)
    rec = Recorder(sim)
    sim.advance(WINDOW)
    wall = time.perf_counter() - t0
    s = rec.summary(window=WINDOW)
    e = s.errors(sim.reference)
    return {
        "preset": preset, "L": cfg.chain.link_length, "dt": cfg.solver.dt,
        "iterations": cfg.solver.iterations, "links": sim.n_free,
        **{k: e[ERRORS.get(k, k)] for k in KEYS}, "T0_bar": e["T0_bar"], "stretch": s.stretch_max,
        "uniformity": s.speed_uniformity, "rtf": (SETTLE + WINDOW) / wall,
    }


def _row(r: dict[str, float]) -> str:
    return (f"| {r['preset']} | {1e3 * r['L']:.0f} | {1e3 * r['dt']:.3g} | {r['iterations']} | "
            f"{r['links']} | {100 * r['vertex_y']:+.2f} | {100 * r['vertex_x']:+.2f} | "
            f"{100 * r['landing_x']:+.2f} | {r['tension_rms']:.4f} | {r['T0_bar']:+.4f} | "
            f"{100 * r['stretch']:.3f} | {100 * r['uniformity']:.2f} | {r['rtf']:.2f} |")


HEADER = ("| preset | L mm | dt ms | iter | links | vertex y % | vertex x % | landing % | "
          "Tbar RMS | Tbar_0 err | stretch % | speed unif. % | RTF |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer points")
    args = ap.parse_args()
    Ls = [0.04, 0.02, 0.01] if args.quick else [0.04, 0.03, 0.02, 0.015, 0.01]
    dts = [1e-3, 2.5e-4] if args.quick else [1e-3, 5e-4, 2.5e-4, 1.25e-4]
    its = [5, 25] if args.quick else [5, 10, 25, 50]
    scans: dict[str, list[dict[str, float]]] = {"L": [], "dt": [], "iterations": []}
    print(HEADER, flush=True)
    for preset in sorted(PRESETS):
        for L in Ls:
            r = run(preset, L=L)
            scans["L"].append(r)
            print(_row(r), flush=True)
    for dt in dts:
        r = run("paper_tall", dt=dt)
        scans["dt"].append(r)
        print(_row(r), flush=True)
    for it in its:
        r = run("paper_tall", iterations=it)
        scans["iterations"].append(r)
        print(_row(r), flush=True)

    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2), constrained_layout=True)
    markers = {"vertex_y": "o", "vertex_x": "s", "landing_x": "^", "tension_rms": "d"}
    colors = {"vertex_y": "C0", "vertex_x": "C1", "landing_x": "C2", "tension_rms": "C3"}
    for ax, (param, rows) in zip(axes, scans.items(), strict=True):
        for preset in sorted({r["preset"] for r in rows}):
            sel = [r for r in rows if r["preset"] == preset]
            xs = [r[param] * (1e3 if param in ("L", "dt") else 1) for r in sel]
            for k in KEYS:
                ys = [abs(r[k]) * (1 if k == "tension_rms" else 100) for r in sel]
                ls = "-" if preset == "paper_tall" else ":"
                ax.plot(xs, ys, ls=ls, marker=markers[k], color=colors[k], ms=4,
                        label=f"{preset}: |{k}|" + (
                    "" if k == "tension_rms" else " %"))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        ax.set_xticks(xs)
        ax.set_xlabel({"L": "link length L (mm)", "dt": "time step dt (ms)",
                       "iterations": "solver iterations"}[param])
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("error vs theory (% or Tbar RMS)")
    axes[0].legend(fontsize=6.5, ncol=1)
    axes[0].set_title("both presets, dt = 0.25 ms, 25 iterations", fontsize=9)
    axes[1].set_title("paper_tall, L = 20 mm, 25 iterations", fontsize=9)
    axes[2].set_title("paper_tall, L = 20 mm, dt = 0.25 ms", fontsize=9)
    OUT.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT, dpi=110)
    print(f"\nfigure: {OUT}")


if __name__ == "__main__":
    main()
