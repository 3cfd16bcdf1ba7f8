"""The gripped fold's catch: what the landing chain does at the end guide's mouth before a
run ends, and how long runs hold with a changed catch, aim, damper or carts.

Builds ``apparatus_fold`` with the gripped 100-mm folding roller as
``research/gripped_fold.py`` does (laid on its path, ``--set`` changes), optionally nudged
(``--seeds``), and varies the catch (``--capture BAND MARGIN_DEG``, ``--close RATE``: a
:class:`~chainfountain.sim.apparatus.Tuning`). Every bookkeeping step it reads, for the
first link not yet captured (the one hanging at the mouth), its offset from the first
turn's radius ``dr`` (m, > 0 outside) and its angle from the mouth ``dth`` (deg, < 0
before the mouth), and the offset of every link that enters through the mouth. Per run it
prints how the run ended, the mean speed, the spread of the mouth offsets per 5-s window
and, for a run that ended, the last ``--tail`` s of the catch (0.1-s rows).

Usage::

    python -m research.fold_catch_study --seconds 60 --dt-factor 1 0.5 --seeds 0 1 \\
        --set carts[0].mass=0.019 carts[1].mass=0.002 [--capture 0.10 3] [--close 5]
    python -m research.fold_catch_study --snap 5.0,5.2 --dt-factor 0.5 \\
        --set carts[0].mass=0.019 carts[1].mass=0.004   # draws the mouth (png)

One core: about 1.5 s of wall time per simulated second at 0.5 ms, 3 s at 0.25 ms.
Measured: research/notes/apparatus_notebook.md, "Thirty-ninth session: the gripped
fold's catch".
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from chainfountain.errors import RunEnded
from chainfountain.sim.apparatus import Tuning
from chainfountain.sim.fastbody import pos
from research.gripped_fold import _value, build


class Watch:
    """Per bookkeeping step: the hanging link's ``(t, dr, dth)``; per mouth entry
    ``(t, dr)``; every 0.1 s the chain speed."""

    def __init__(self, sim) -> None:
        self.sim, app = sim, sim.apparatus
        self.app = app
        self.hang: list[tuple[float, float, float]] = []
        self.entries: list[tuple[float, float]] = []
        fold = app.fold
        orig = fold.capture_at_mouth
        el0 = app.guide[0]
        cx, cy = el0.a
        Rc, th0 = el0.R, el0.th0

        def capture(popped: int) -> None:
            before = fold.mouth_t
            n0 = fold.cap_next - popped
            orig(popped)
            if fold.mouth_t is not None and (fold.mouth_t != before or fold.cap_next > n0 + 1):
                self.entries.append((app.time, fold.mouth_dr))
            i = fold.cap_next
            if 0 <= i < len(sim.chain.links):
                p = pos(sim.chain.links[i].body)
                d = math.hypot(p.x - cx, p.y - cy)
                th = math.atan2(p.y - cy, p.x - cx)
                dth = (th - th0 + math.pi) % (2.0 * math.pi) - math.pi
                self.hang.append((app.time, d - Rc, math.degrees(dth)))

        fold.capture_at_mouth = capture


def run(sim, seconds: float) -> tuple[Watch, list[float], str]:
    w, app, v = Watch(sim), sim.apparatus, []
    try:
        while sim.time < seconds - 1e-9:
            sim.advance(0.1)
            v.append(app.strand_speed)
    except RunEnded:
        return w, v, f"ended {sim.time:.2f} s"
    return w, v, f"held {seconds:g} s"


def report(w: Watch, v: list[float], end: str, label: str, wall: float, tail: float) -> None:
    vv = np.array(v)
    E = np.array(w.entries) if w.entries else np.zeros((0, 2))
    H = np.array(w.hang) if w.hang else np.zeros((0, 3))
    print(f"{label}: {end}; mean speed {np.nanmean(vv[10:] if len(vv) > 20 else vv):.3f} m/s "
          f"(1-s means {np.nanmin(vv[5:]) if len(vv) > 5 else np.nan:.3f}-"
          f"{np.nanmax(vv[5:]) if len(vv) > 5 else np.nan:.3f}); {wall:.0f} s wall", flush=True)
    if len(E):
        T = E[-1, 0] if len(E) else 0.0
        row = []
        for t0 in np.arange(0.0, T + 1e-9, 5.0):
            m = (E[:, 0] >= t0) & (E[:, 0] < t0 + 5.0)
            sv = vv[int(t0 * 10):int(t0 * 10) + 50]
            sp = f"@{np.nanmean(sv):.2f}" if len(sv) else ""
            if m.any():
                row.append(f"{t0:.0f}s:{100 * E[m, 1].min():+.1f}/{100 * E[m, 1].max():+.1f}{sp}")
        print("   mouth entries dr (cm, min/max per 5 s @ mean speed m/s): " + " ".join(row))
    if tail and len(H):
        t_end = H[-1, 0]
        print(f"   last {tail:g} s: t | entries | dr of entries cm (min/max) | hanging link dr cm, "
              "dth deg (min/max) | speed")
        for t0 in np.arange(max(0.0, t_end - tail), t_end, 0.1):
            m = (E[:, 0] >= t0) & (E[:, 0] < t0 + 0.1) if len(E) else np.zeros(0, bool)
            mh = (H[:, 0] >= t0) & (H[:, 0] < t0 + 0.1)
            k = min(int(t0 * 10), len(v) - 1)
            e = (f"{m.sum():3d} | {100 * E[m, 1].min():+5.1f}/{100 * E[m, 1].max():+5.1f}"
                 if m.any() else "  0 |      -     ")
            hh = (f"{100 * H[mh, 1].min():+6.1f}/{100 * H[mh, 1].max():+6.1f}, "
                  f"{H[mh, 2].min():+6.1f}/{H[mh, 2].max():+6.1f}" if mh.any() else "-")
            print(f"   {t0:5.1f} | {e} | {hh} | {v[k]:.3f}")


def snap(sim, times: list[float], out: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    app = sim.apparatus
    el0 = app.guide[0]
    fig, axs = plt.subplots(len(times), 1, figsize=(7, 4.2 * len(times)))
    for ax, t in zip(np.atleast_1d(axs), times, strict=True):
        try:
            sim.advance(t - sim.time)
        except RunEnded as e:
            print("ended", getattr(e, "plain", e))
        cx, cy = el0.a
        R, (band, marg) = el0.R, app.fold.capture
        th = np.linspace(el0.th0, el0.th1, 100)
        ax.plot(cx + R * np.cos(th), cy + R * np.sin(th), "g-", lw=3, alpha=0.4)
        for r in (R - band, R + band):
            tt = np.linspace(el0.th0 - marg, -0.5 * math.pi + 0.05, 60)
            ax.plot(cx + r * np.cos(tt), cy + r * np.sin(tt), "g:", lw=1)
        held = {id(lk) for q in app.fold_held for lk, _ in q}
        for i, lk in enumerate(sim.chain.links):
            b = lk.body
            p = pos(b)
            if not (cx - 0.45 < p.x < cx + 0.2 and cy - 0.3 < p.y < cy + 0.3):
                continue
            f, bb = b.local_to_world((0.01, 0)), b.local_to_world((-0.01, 0))
            col = "blue" if id(lk) in held else ("red" if i == app.fold.cap_next else "orange")
            ax.plot([f.x, bb.x], [f.y, bb.y], "-o", color=col, ms=2, lw=1.2)
        ax.set_xlim(cx - 0.45, cx + 0.2)
        ax.set_ylim(cy - 0.3, cy + 0.3)
        ax.set_aspect("equal")
        ax.set_title(f"t={sim.time:.2f} s  v={app.strand_speed:.3f}  last mouth entry "
                     f"{app.last_mouth_entry:.2f} s dr {100 * app.last_mouth_offset:+.1f} cm")
    fig.tight_layout()
    fig.savefig(out, dpi=80)
    print("wrote", out)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="apparatus_fold")
    ap.add_argument("--seconds", type=float, default=60.0)
    ap.add_argument("--dt-factor", type=float, nargs="+", default=[1.0, 0.5])
    ap.add_argument("--seeds", type=int, nargs="+", default=[-1],
                    help="sim.nudge(seed) after building; -1: not nudged")
    ap.add_argument("--set", nargs="*", default=[], metavar="PATH=VALUE")
    ap.add_argument("--capture", type=float, nargs=2, metavar=("BAND_M", "MARGIN_DEG"))
    ap.add_argument("--close", type=float, help="the joint guides' close rate (m/s)")
    ap.add_argument("--snap", help="comma-separated times: draw the mouth region")
    ap.add_argument("--out", default="/tmp/fold_catch_snap.png")
    ap.add_argument("--tail", type=float, default=1.5,
                    help="seconds of 0.1-s rows before the end (0: none)")
    ap.add_argument("--tail-always", action="store_true", help="rows for held runs too")
    a = ap.parse_args(argv)
    tuning = Tuning(fold_capture=(a.capture[0], math.radians(a.capture[1])) if a.capture
                    else None, fold_close_rate=a.close)
    changes = {}
    for item in a.set:
        key, _, val = item.partition("=")
        changes[key] = _value(val)
    for f in a.dt_factor:
        for seed in a.seeds:
            sim = build(a.level, changes, f, False)
            sim.apparatus.retune(tuning)
            if seed >= 0:
                sim.nudge(seed)
            if a.snap:
                snap(sim, [float(x) for x in a.snap.split(",")], a.out)
                continue
            t0 = time.perf_counter()
            w, v, end = run(sim, a.seconds)
            cap = sim.apparatus.fold.capture
            label = (f"h {sim.h * 1e3:g} ms seed {seed} capture {100 * cap[0]:g} cm/"
                     f"{math.degrees(cap[1]):g} deg close {sim.apparatus.fold.close_rate:g} "
                     + " ".join(a.set))
            report(w, v, end, label, time.perf_counter() - t0,
                   a.tail if (end.startswith("ended") or a.tail_always) else 0.0)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
