"""The files of a headless run besides ``summary.json``: CSVs and figures."""

from __future__ import annotations

import csv
import dataclasses
import io as _io
import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from chainfountain import atomic
from chainfountain.errors import OutputError
from chainfountain.headless.report import RunSummary
from chainfountain.sim import placement
from chainfountain.sim.recorder import Recorder
from chainfountain.sim.reference import LaunchReference
from chainfountain.sim.stiff_reference import StiffReference, joints
from chainfountain.sim.world import Simulation
from chainfountain.theory.apparatus import plate_reaction

MAX_TENSION_SAMPLES = 200
"""Time samples of ``tensions.csv`` (evenly chosen among the recorded profiles)."""


def write_summary(out_dir: Path, summary: RunSummary, written: list[str]) -> Path:
    """Write ``summary.json`` (:meth:`RunSummary.to_json`) last, atomically;
    :class:`OutputError` names the outputs that were written when it cannot be."""
    path = out_dir / "summary.json"
    try:
        atomic.write_text(path, json.dumps(summary.to_json(), indent=2) + "\n")
    except OSError as exc:
        raise OutputError(f"cannot write {path} ({exc.strerror or exc}); the run's other "
                          f"outputs: {', '.join(written) or 'none'}") from None
    return path


def write_tensions(path: Path, rec: Recorder, lam: float) -> None:
    profs = rec.profiles
    samples = rec.samples
    if not profs:
        atomic.write_text(path, "t,joint,s,x,y,tension_N,tension_bar\n")
        return
    idx = np.unique(np.linspace(0, len(profs) - 1, min(MAX_TENSION_SAMPLES, len(profs)))
                    .round().astype(int))
    t_samples = np.array([smp.t for smp in samples])
    blocks = []
    for i in idx:
        p = profs[i]
        smp = samples[int(np.argmin(np.abs(t_samples - p.t)))]
        v = smp.speed_mean if smp.speed_mean > 0 else 1.0
        xy = np.column_stack([p.x, p.y])
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))])
        n = len(p.tension_bar)
        tb = np.asarray(p.tension_bar, dtype=float)
        blocks.append(np.column_stack([np.full(n, smp.t), np.arange(n), s[:n], p.x[:n],
                                       p.y[:n], tb * (lam * v * v), tb]))
    buf = _io.StringIO()
    buf.write("t,joint,s,x,y,tension_N,tension_bar\n")
    # one formatted write of the whole table (row by row, 82,000 rows took 0.5 s)
    np.savetxt(buf, np.vstack(blocks), fmt=["%.6g", "%d", "%.6g", "%.6g", "%.6g", "%.6g",
                                            "%.6g"], delimiter=",")
    atomic.write_text(path, buf.getvalue())


ONLY_WHEN_MEASURED = ("plate_reaction",)
"""Sample fields that only some levels measure (the open arrangement's plate reaction):
their column is left out when no sample has a value."""


def write_samples(path: Path, samples: list) -> None:
    """One row per recorded sample (a dataclass), one column per field (but see
    :data:`ONLY_WHEN_MEASURED`)."""
    buf = _io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    cols = [f.name for f in dataclasses.fields(samples[0])] if samples else ["t"]
    cols = [c for c in cols if c not in ONLY_WHEN_MEASURED
            or any(math.isfinite(getattr(smp, c)) for smp in samples)]
    w.writerow(cols)
    for smp in samples:
        w.writerow([f"{getattr(smp, c):.6g}" for c in cols])
    atomic.write_text(path, buf.getvalue())


def write_reaction_figure(path: Path, rec: Recorder, summary: RunSummary,
                          lam: float, g: float, title: str) -> None:
    """The open arrangement (an apparatus's 'open' variant, or ``feed.drive =
    "ideal_open"``): the lower plate's reaction force against time, with the paper's rate
    ``lambda g v`` integrated over the measured speed from the first sample (the paper:
    "the reaction force change is exactly known over time")."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if summary.sections.get("open"):  # the ideal machine: counted on the plate
        o = summary.sections["open"]
        w0, w1 = o["window"]
        S = [x for x in rec.samples if x.t >= w0 - 1e-9]
        t = np.array([x.t for x in S], dtype=float)
        R = np.array([x.plate_reaction for x in S], dtype=float)
        v = np.array([x.speed_mean for x in S], dtype=float)
        fit = "least squares"
    else:
        ap = summary.sections.get("apparatus") or {}
        o = ap.get("open") or {}
        w0, w1 = ap.get("window") or (math.nan, math.nan)
        S = rec.apparatus_samples
        t = np.array([x.t for x in S], dtype=float)
        R = np.array([x.tail_reaction for x in S], dtype=float)
        v = np.array([x.v for x in S], dtype=float)
        fit = "Theil-Sen"
    ok = np.isfinite(R) & np.isfinite(v)
    t, R, v = t[ok], R[ok], v[ok]
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=100)
    ax.plot(t, R, ".", ms=3, color="#333333", label="measured (each sample)")
    if len(t) > 1:
        ax.plot(t, plate_reaction(t, v, float(R[0]), lam, g), "--", color="#d62728", lw=1.4,
                label="lambda g v (paper), from the first sample")
    rate, pred = o.get("tail_reaction_rate_N_per_s"), o.get("tail_reaction_rate_predicted")
    if rate is not None and pred is not None:
        ax.text(0.02, 0.97, f"rate over {w0:.2g}-{w1:.2g} s: {rate:.3f} N/s measured "
                f"({fit}), {pred:.3f} N/s = lambda g v ({100 * (rate / pred - 1):+.1f} %)",
                transform=ax.transAxes, va="top", fontsize=8)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("lower plate reaction (N)")
    ax.grid(alpha=0.3)
    ax.set_ylim(bottom=0.0)
    _save_png(fig, ax, path, title, legend="lower right")


def write_snapshot(path: Path, sim: Simulation, summary: RunSummary, title: str) -> None:
    """The chain at the end of the run over the predicted catenary, axes in metres."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pts = sim.chain_polyline()
    fig, ax = plt.subplots(figsize=(6.4, 6.4), dpi=100)
    ax.plot(pts[:, 0], pts[:, 1], "-", color="#333333", lw=1.6, label="simulated chain")
    ref = sim.reference
    if isinstance(ref, StiffReference):
        xy = ref.curve(300)
        ax.plot(xy[:, 0], xy[:, 1], "--", color="#d62728", lw=1.2,
                label=f"{ref.label} (c = {ref.c:.3g} N*m/rad, d = {ref.d:.3g} N*m*s/rad)")
        ax.plot(*ref.vertex, "x", color="#d62728", ms=9, mew=2, label="predicted vertex")
        _catenary_beside(ax, ref.catenary, "the catenary (no joint resistance)")
    elif ref is not None:
        x = np.linspace(0.0, ref.landing_x, 300)
        ax.plot(x, ref.y_of_x(x), "--", color="#d62728", lw=1.2,
                label=f"inverted catenary (theory), q = {ref.q:.3g} 1/m")
        ax.plot(*ref.vertex, "x", color="#d62728", ms=9, mew=2, label="predicted vertex")
    elif sim.catenary is not None and sim.reference_note:
        ch = sim.config.chain
        _catenary_beside(ax, sim.catenary, "the catenary: no steady stiff fountain at "
                         + joints(ch.bending_stiffness, ch.bending_damping))
    vx, vy = summary.fountain.vertex_x, summary.fountain.h
    if vx is not None and vy is not None:
        ax.plot(vx, vy, "o", mfc="none", color="#1f77b4", ms=9, mew=1.5,
                label="measured vertex (window mean)")
    fy, fx0, fx1, mode = placement.floor(sim)
    app = sim.apparatus
    if mode != "none":
        ax.plot([fx0, fx1], [fy, fy], color="#8c564b", lw=3, label=f"{mode} floor")
    if app is not None and app.floor_depth > 0:
        ex = app.end[0]
        ax.plot([ex - 0.3, ex + 0.3], [-app.H, -app.H], ":", color="#7f7f7f", lw=1.5,
                label=f"fountain end height (Tbar_E read here; floor {app.floor_depth:.3g} m "
                "lower)")
    vessel = placement.vessel(sim)
    if vessel is not None:
        outline, plate = vessel
        ax.plot(outline[:, 0], outline[:, 1], color="#17becf", lw=2.5, label="pot")
        ax.plot(plate[:, 0], plate[:, 1], color="#7f7f7f", lw=1.5,
                label="plate under the pile (rises as it is drawn off)")
        _beaker_curve(ax, summary.sections.get("beaker") or {}, sim.g)
    elif app is None:
        (gx, gy), (ux, uy) = placement.launch(sim)
        ax.plot([gx - 0.15 * ux, gx], [gy - 0.15 * uy, gy], color="#2ca02c", lw=4,
                label="feed guide")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.grid(alpha=0.3)
    if app is not None:
        # the fountain and the guides, not the metres of table on either side (a tall,
        # narrow fountain such as the paper's D ends well before 2.4 H)
        H = app.H
        ax.set_xlim(-0.6, max(1.2, min(2.4 * H, app.end[0] + 1.0)))
        ax.set_ylim(min(-H - 0.4, app.floor_y - 0.1), max(0.3, 0.6 * H))
    else:
        xs = np.concatenate([pts[:, 0], [fx0, fx1]]) if ref is None else pts[:, 0]
        ax.set_xlim(min(xs.min(), -0.2) - 0.1, max(xs.max(), 0.2) + 0.1)
    _save_png(fig, ax, path, title)


def _catenary_beside(ax, cat: LaunchReference, label: str) -> None:
    """The paper's catenary, dotted grey, beside a stiff chain's theory."""
    x = np.linspace(0.0, cat.landing_x, 300)
    ax.plot(x, cat.y_of_x(x), ":", color="#7f7f7f", lw=1.2, label=label)


def _beaker_curve(ax, bk: dict[str, Any], g: float) -> None:
    """The paper's inverted catenary through a beaker run's measured pick-up, top and
    landing at its measured speed (``summary.json``'s ``beaker``), when there is one."""
    from chainfountain.theory import Fountain

    if not (bk.get("paper") or {}).get("q"):
        return
    px, py = bk["pickup"]
    f = Fountain.from_geometry(l=bk["span_from_pickup"], h=bk["rise_above_pickup"],
                               H=bk["drop_from_pickup"], v=bk["speed"], g=g)
    xs, ys = f.curve(200)
    sx, sy = f.start
    ax.plot(np.asarray(xs) - sx + px, np.asarray(ys) - sy + py, "--", color="#d62728",
            lw=1.2, label="the paper's curve through the measured ends")
    ax.plot(px, py, "s", mfc="none", color="#2ca02c", ms=7, label="pick-up (window mean)")


def _save_png(fig, ax, path: Path, title: str, legend: str = "best") -> None:
    """Title and legend, then the figure as PNG, atomically; closes it."""
    import matplotlib.pyplot as plt

    ax.set_title(title, fontsize=10)
    ax.legend(loc=legend, fontsize=8, framealpha=0.9)
    fig.tight_layout()
    with atomic.atomic_path(path) as tmp:
        fig.savefig(tmp, format="png")
    plt.close(fig)
