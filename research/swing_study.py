"""The landing swing of the fold presets run long: how fast it grows, when the fold fails.

    .venv/bin/python -m research.swing_study                      # ~30 s
    .venv/bin/python -m research.swing_study --speeds 2.94 3.0 3.06
    .venv/bin/python -m research.swing_study --lower-cart 0.054 0.058 0.062
    .venv/bin/python -m research.swing_study --dt 0.5 0.1 --clearance 0.002 \
        --lower-cart 0.044 --speeds 2.97 --seconds 8
    .venv/bin/python -m research.swing_study --close-rate 2 20 100
    .venv/bin/python -m research.swing_study --upper-drag 0.2 --band 0.06 0.1
    .venv/bin/python -m research.swing_study --figure docs/img/fold_catch.png   # ~25 s

Runs a 'fold' level (default ``apparatus_special``, both plates treadmills, so nothing
runs out) for up to ``--seconds`` and samples the chain speed (the upper plate strand)
every 0.01 s. One Markdown row per run: when it ended (``FoldCollapsed``) or ``-``; the
mean speed over 0.5-8 s; the speed swing (half the peak-to-peak about a linear trend)
over 0.5-3.5 s and over the last 3 s before the end (or before ``--seconds`` minus 1 s);
and a fit ``v = c0 + c1 t + A exp(sigma t) sin(omega t + phi)`` over 0.5 s to 1 s before
the end: ``sigma`` (1/s, growth rate of the swing; > 0 grows) and the period.
``--close-rate`` sets the catch's closing speed (m/s, the class attribute
``Tuning.fold_close_rate``, 5 as shipped), ``--band`` its capture band (m, the first
element of ``Tuning.fold_capture``, 0.06 as shipped). "catch lost s" is the time the
last link entered the end guide through its mouth when that was
:data:`~chainfountain.sim.apparatus.tuning.CATCH_LOST` s or more before the end (``-``
otherwise). ``--upper-drag c`` (N s/m) adds a damper to the pick-up carriage about the
steady roller speed, ``-c (v_R - v0/2)``: not part of the paper's apparatus, a probe of
whether damping the chain before the fountain stops the swing. ``--figure PATH`` instead
draws the preset's run to its end (first ``--speeds`` value): the chain speed at the
pick-up and at the folding roller, and where each link landed in the end guide's mouth
against the catch's band. docs/apparatus.md, "The landing swing".
"""

from __future__ import annotations

import argparse
import dataclasses
import itertools
import math
import sys
import time

import numpy as np
from scipy.optimize import curve_fit

from chainfountain.errors import RunEnded
from chainfountain.sim import Simulation, fastbody
from chainfountain.sim.apparatus import Apparatus, Tuning
from chainfountain.sim.apparatus.tuning import CATCH_LOST, FOLD_CAPTURE
from chainfountain.sim.config import SimConfig
from research.fold_step_study import fold_config, positive

SAMPLE = 0.01


def _upper_drag(app: Apparatus, c: float, v0: float) -> None:
    """Damp the pick-up carriage about ``v0/2`` with ``c`` (N s/m), every step."""
    before = app.before_step
    h = fastbody.handle(app.upper.carriage)

    def step() -> None:
        before()
        vx = fastbody.get_velocity(h).x
        fastbody.apply_force_at_local_point(h, (-c * (vx - 0.5 * v0), 0.0), (0.0, 0.0))

    app.before_step = step


def trace(cfg: SimConfig, seconds: float, upper_drag: float = 0.0,
          tuning: Tuning | None = None) -> tuple[np.ndarray, np.ndarray, float | None, float]:
    """Strand speed every :data:`SAMPLE` s, the time the run ended (None: it did not) and
    the time the last link entered the end guide through its mouth."""
    sim = Simulation(cfg)
    app = sim.apparatus
    if tuning is not None:
        app.retune(tuning)
    if upper_drag:
        _upper_drag(app, upper_drag, cfg.apparatus.speed)
    t, v = [], []
    try:
        while sim.time < seconds - 1e-9:
            sim.advance(SAMPLE)
            t.append(sim.time)
            v.append(app.strand_speed)
    except RunEnded:
        return np.array(t), np.array(v), sim.time, app.last_mouth_entry
    return np.array(t), np.array(v), None, app.last_mouth_entry


def figure(cfg: SimConfig, seconds: float, out: str) -> None:
    """The run to its end: speeds, and the landing offset in the mouth against the band."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sim = Simulation(cfg)
    app = sim.apparatus
    rows = []
    ended = None
    try:
        while sim.time < seconds - 1e-9:
            sim.advance(SAMPLE)
            rows.append((sim.time, app.speed, 2.0 * app.lower.speed, app.last_mouth_entry,
                         app.last_mouth_offset))
    except RunEnded:
        ended = sim.time
    r = np.array(rows)
    t = r[:, 0]
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(9, 5.6), sharex=True)
    ax.plot(t, r[:, 1], lw=0.8, label="pick-up: 2 v_R")
    ax.plot(t, r[:, 2], lw=0.8, label="folding roller: 2 v_R")
    ax.set_ylim(0.0, 4.5)
    ax.set_ylabel("chain speed (m/s)")
    fresh = t - r[:, 3] < 2.0 * SAMPLE  # a link entered through the mouth in this sample
    band = 100.0 * app.fold.capture[0]
    bx.axhspan(-band, band, color="0.9", label="catch band")
    bx.plot(t[fresh], 100.0 * r[fresh, 4], ".", ms=2, color="C2",
            label="landing offset in the mouth (> 0: short)")
    bx.set_ylim(-1.3 * band, 1.3 * band)
    bx.set_ylabel("offset from the turn's radius (cm)")
    bx.set_xlabel("t (s)")
    lost = r[-1, 3]
    if ended is not None and ended - lost >= CATCH_LOST:
        for x in (ax, bx):
            x.axvline(lost, color="C3", lw=0.8, ls="--")
        bx.annotate(f"catch lost {lost:.2f} s", (lost, -1.2 * band), color="C3", fontsize=8,
                    ha="right")
    if ended is not None:
        for x in (ax, bx):
            x.axvline(ended, color="k", lw=0.8)
        ax.annotate(f"fold collapsed {ended:.2f} s", (ended, 4.2), fontsize=8, ha="right")
    ax.legend(fontsize=8, loc="lower left")
    bx.legend(fontsize=8, loc="lower left")
    ax.set_title(f"{cfg.name}, start {cfg.apparatus.speed:g} m/s, "
                 f"dt {cfg.solver.dt * 1e3:g} ms: the landing swing until the fold fails")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")


def swing(t: np.ndarray, v: np.ndarray, a: float, b: float) -> float:
    """Half the peak-to-peak speed about its linear trend over ``[a, b)`` (m/s)."""
    m = (t >= a) & (t < b)
    if m.sum() < 50:
        return math.nan
    d = v[m] - np.polyval(np.polyfit(t[m], v[m], 1), t[m])
    return 0.5 * float(d.max() - d.min())


def growth(t: np.ndarray, v: np.ndarray, a: float, b: float) -> tuple[float, float]:
    """Fitted growth rate ``sigma`` (1/s) and period (s) of the swing over ``[a, b)``."""
    m = (t >= a) & (t < b)
    tt, vv = t[m], v[m]
    if len(tt) < 200:
        return math.nan, math.nan
    p = np.polyfit(tt, vv, 1)
    d = vv - np.polyval(p, tt)
    f = np.fft.rfftfreq(len(d), SAMPLE)
    w0 = 2.0 * math.pi * f[1 + int(np.argmax(np.abs(np.fft.rfft(d * np.hanning(len(d))))[1:]))]

    def model(x, amp, s, w, ph, c0, c1):
        return c0 + c1 * x + amp * np.exp(s * (x - a)) * np.sin(w * x + ph)

    best = None
    for ph in np.linspace(0.0, 2.0 * math.pi, 8, endpoint=False):
        try:
            pp, _ = curve_fit(model, tt, vv, p0=[1.4 * np.std(d), 0.0, w0, ph, p[1], p[0]],
                              maxfev=20000)
        except RuntimeError:
            continue
        r = float(np.sum((model(tt, *pp) - vv) ** 2))
        if best is None or r < best[0]:
            best = (r, pp)
    if best is None:
        return math.nan, math.nan
    return float(best[1][1]), 2.0 * math.pi / abs(float(best[1][2]))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="apparatus_special", help="a 'fold' level name or path")
    ap.add_argument("--seconds", type=float, default=30.0)
    ap.add_argument("--dt", type=float, nargs="+", default=[0.5], help="solver steps (ms)")
    ap.add_argument("--lower-cart", type=float, nargs="+", default=[None], help="kg")
    ap.add_argument("--speeds", type=float, nargs="+", default=[None], help="start speeds")
    ap.add_argument("--clearance", type=float, default=None, help="apparatus.fold_clearance")
    ap.add_argument("--close-rate", type=float, nargs="+", default=[None],
                    help="the catch's closing speed (m/s)")
    ap.add_argument("--band", type=positive(float), nargs="+", default=[None],
                    help="the catch's capture band (m)")
    ap.add_argument("--figure", default=None, help="draw the run to its end into this PNG")
    ap.add_argument("--upper-drag", type=float, nargs="+", default=[0.0],
                    help="damper on the pick-up carriage about v0/2 (N s/m; not the paper's)")
    ap.add_argument("--iterations", type=positive(int), nargs="+", default=[None],
                    help="solver.iterations (default: as in the level)")
    ap.add_argument("--upper-guide", nargs="+", default=[None], choices=("walls", "joints"),
                    help="apparatus.upper_guide (default: as in the level)")
    args = ap.parse_args(argv)
    if args.figure:
        figure(fold_config(args.level, args.dt[0] * 1e-3, args.clearance, args.lower_cart[0],
                           args.speeds[0]), args.seconds, args.figure)
        return 0
    print("| dt ms | iterations | lower cart g | start m/s | close m/s | band m | upper drag N s/m "
          "| upper guide | ended s | catch lost s | v m/s (0.5-8 s) | swing early m/s "
          "| swing late m/s | sigma 1/s | period s | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for dt, its, mass, v0, rate, band, drag, guide in itertools.product(
            args.dt, args.iterations, args.lower_cart, args.speeds, args.close_rate, args.band,
            args.upper_drag, args.upper_guide):
        tuning = Tuning(fold_close_rate=rate, fold_capture=None if band is None
                        else (band, FOLD_CAPTURE[1]))
        cfg = fold_config(args.level, dt * 1e-3, args.clearance, mass, v0)
        if its is not None:
            cfg = dataclasses.replace(cfg, solver=dataclasses.replace(cfg.solver, iterations=its))
        if guide is not None:
            cfg = dataclasses.replace(cfg, apparatus=dataclasses.replace(
                cfg.apparatus, upper_guide=guide))
        w0 = time.perf_counter()
        t, v, ended, mouth = trace(cfg, args.seconds, drag, tuning)
        lost = ended is not None and ended - mouth >= CATCH_LOST
        end = ended if ended is not None else args.seconds
        late = (max(0.5, end - 4.0), end - 1.0)
        mean = v[(t >= 0.5) & (t < min(8.0, end))]
        s, period = growth(t, v, 0.5, end - 1.0)
        print(f"| {dt:g} | {cfg.solver.iterations} | {1e3 * cfg.carts[1].mass:g} | "
              f"{cfg.apparatus.speed:g} | "
              f"{tuning.close_rate(False):g} | {tuning.capture(False)[0]:g} | {drag:g} | "
              f"{cfg.apparatus.upper_guide} | {'-' if ended is None else f'{ended:.2f}'} | "
              f"{f'{mouth:.2f}' if lost else '-'} | "
              f"{float(np.mean(mean)) if len(mean) else math.nan:.3f} | "
              f"{swing(t, v, 0.5, 3.5):.3f} | {swing(t, v, *late):.3f} | {s:+.3f} | "
              f"{period:.2f} | {time.perf_counter() - w0:.0f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
