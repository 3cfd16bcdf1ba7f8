"""Fed stiff fountains measured: a chain with joint springs ``c`` and dampers ``d``
(``chain.bending_stiffness``, ``chain.bending_damping``), started on the catenary, run
``--duration`` simulated seconds; the window's figures, their scatter and a steadiness
verdict, at the base discretisation and a refined one (issue 62).

Each case runs at refinement ``r`` = 1 (``L = 0.02 m``, ``dt = 0.25 ms``) and, with
``--refine 1 2``, at ``r = 2``: ``L/2``, ``dt/2`` and ``c``, ``d`` doubled, so that the
bending rigidity ``c L`` and the damping ``d L`` are those of the same chain (the BVP's
``e = c L/(lambda v^2) - L^2/12`` still moves with ``L`` through the rotary inertia).
``solver.accuracy`` is 0 and ``iterations`` 10: what runs is what is written. The pymunk
step ``h = dt/substeps`` is chosen per run so that the spring rings at ``omega h <=``
:data:`SPRING_OMEGA_H` (``omega = sqrt(4 c/I)``, ``I = lambda L^3/12``) and the damper's
step exponent ``x = 2 d h/I <=`` :data:`DAMPER_X` (pymunk's damper is exponential: it
takes ``1 - exp(-x)`` of a joint's relative spin a step, so it acts as
``d (1 - exp(-x))/x``, recorded as ``d_eff``).

Per run (printed, and written to ``--out`` as JSON): the settings, the run length, the
window (the last ``--window`` seconds), the window means and standard deviations of the
vertex height above the launch, the vertex x, the landing x and the chain speed in
flight (the recorder's, :mod:`chainfountain.sim.recorder`), and the verdict:

- ``drift``: the vertex height's mean over the window's second half less its first, over
  the mean;
- ``growth``: the rate (1/s) at which the vertex height's oscillation about its linear
  trend grows, ``ln(rms2/rms1)/(window/2)`` over the window's halves;
- ``verdict``: ``steady`` when ``|drift| <= 0.3 %`` and the vertex's std is at most
  0.3 % of its height; else ``growing`` when ``growth > 0.1 /s``, else ``unsteady``.

``table IN.json`` adds the steady stiff BVP (:func:`chainfountain.theory.stiff.stiff_fountain`,
with its damper ``delta = d L/(lambda v)`` when the installed theory has it) at the
feed speed and at the measured speed, and the paper's catenary, and prints a markdown table.

Usage::

    python -m research.stiff_runs run --fountain wide_low --cases 0.04:0 0.04:3e-5 \
        --refine 1 2 --duration 8 --out /tmp/stiff.json
    python -m research.stiff_runs run --grid --out /tmp/stiff.json   # the notes' grid
    python -m research.stiff_runs table /tmp/stiff.json

Cost: a base run is 0.2-0.7 s of wall time per simulated second (1-4 substeps), a refined
one about 4x that per substep (``research/notes/stiff_validation.md``).
"""

from __future__ import annotations

import argparse
import inspect
import json
import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

from chainfountain.sim.reference import LaunchReference
from chainfountain.study.api import load, start
from chainfountain.study.changes import with_changes

FOUNTAINS: dict[str, tuple[str, dict[str, Any]]] = {
    "wide_low": ("wide_low", {}),
    "steep": ("wide_low", {"feed.launch_angle": math.radians(75.0), "feed.speed": 3.5}),
}
"""The fed fountains: ``wide_low`` (4 m/s, 60 deg, 0.5 m drop) and ``steep``
(``wide_low`` at 3.5 m/s and 75 deg)."""

BASE_L = 0.02
BASE_DT = 2.5e-4
ITERATIONS = 10
SPRING_OMEGA_H = 1.0
"""Largest ``omega h`` allowed (the level check refuses 2)."""
DAMPER_X = 0.3
"""Largest damper step exponent ``2 d h/I`` allowed (``d_eff/d >= 0.86``)."""
MAX_SUBSTEPS = 64

GRID: dict[str, list[tuple[float, float]]] = {
    "wide_low": [(0.01, 0.0), (0.04, 0.0), (0.01, 1e-5), (0.01, 3e-5), (0.04, 1e-5),
                 (0.04, 3e-5), (0.04, 1e-4)],
    "steep": [(0.003, 0.0), (0.003, 1e-5), (0.005, 1e-5), (0.005, 3e-5), (0.01, 3e-5),
              (0.01, 1e-4), (0.02, 1e-4)],
}
"""``--grid``: (c, d) at the base link (N*m/rad, N*m*s/rad) per fountain."""


def substeps_for(c: float, d: float, L: float, lam: float, dt: float,
                 damper_x: float = DAMPER_X) -> int:
    """The fewest pymunk steps per ``dt`` keeping the spring and the damper within
    :data:`SPRING_OMEGA_H` and :data:`DAMPER_X`."""
    moment = lam * L**3 / 12.0
    n = 1
    if c > 0.0:
        omega = 2.0 * math.sqrt(c / moment)
        n = max(n, math.ceil(omega * dt / SPRING_OMEGA_H - 1e-12))
    if d > 0.0:
        n = max(n, math.ceil(2.0 * d * dt / moment / damper_x - 1e-12))
    return min(n, MAX_SUBSTEPS)


def case_level(fountain: str, c: float, d: float, refine: int,
               damper_x: float = DAMPER_X):
    """The level of one run: ``fountain`` with ``c``, ``d`` given at the base link and
    refinement ``refine``; returns the level and its settings."""
    name, changes = FOUNTAINS[fountain]
    base = load(name)
    lam = base.sim.chain.linear_density
    L, dt = BASE_L / refine, BASE_DT / refine
    cr, dr = c * refine, d * refine
    sub = substeps_for(cr, dr, L, lam, dt, damper_x)
    ch = dict(changes)
    ch.update({"solver.accuracy": 0.0, "initial.mode": "catenary", "chain.link_length": L,
               "chain.link_radius": min(base.sim.chain.link_radius, 0.4 * L),
               "solver.dt": dt, "solver.substeps": sub, "solver.iterations": ITERATIONS,
               "chain.bending_stiffness": cr, "chain.bending_damping": dr})
    lvl = with_changes(base, ch, where=f"{fountain} c={c:g} d={d:g} r={refine}")
    h = dt / sub
    moment = lam * L**3 / 12.0
    x = 2.0 * dr * h / moment
    settings = {
        "L": L, "dt": dt, "substeps": sub, "h": h, "iterations": ITERATIONS,
        "c": cr, "d": dr, "c_base": c, "d_base": d, "cL": cr * L, "dL": dr * L,
        "wave_damping": lvl.sim.solver.wave_damping,
        "wave_damper": lvl.sim.solver.wave_damping * lam * lvl.sim.feed.speed * L * L,
        "omega_h": 2.0 * math.sqrt(cr / moment) * h if cr > 0 else 0.0,
        "damper_x": x, "damper_x_max": damper_x,
        "d_eff": dr * (1.0 - math.exp(-x)) / x if x > 0 else 0.0,
        "lambda": lam, "feed_speed": lvl.sim.feed.speed,
        "launch_angle": lvl.sim.feed.launch_angle, "drop": lvl.sim.feed.drop,
        "TE_bar": lvl.sim.feed.end_tension, "g": lvl.sim.gravity,
    }
    return lvl, settings


def _halves(t: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Drift (second half's mean less the first's, over the mean) and growth rate (1/s)
    of the oscillation about the linear trend over the two halves."""
    mid = 0.5 * (t[0] + t[-1])
    a, b = t < mid, t >= mid
    drift = float((y[b].mean() - y[a].mean()) / y.mean())
    rms = []
    for sel in (a, b):
        p = np.polyfit(t[sel], y[sel], 1)
        rms.append(float(np.sqrt(np.mean((y[sel] - np.polyval(p, t[sel])) ** 2))))
    growth = (math.log(rms[1] / rms[0]) / (mid - t[0])) if min(rms) > 0 else math.nan
    return drift, growth


def verdict(drift: float, rel_std: float, growth: float) -> str:
    """``steady``, ``growing`` or ``unsteady`` (see the module docstring)."""
    if abs(drift) <= 3e-3 and rel_std <= 3e-3:
        return "steady"
    if math.isfinite(growth) and growth > 0.1:
        return "growing"
    return "unsteady"


def measure(runner, window: float) -> dict[str, Any]:
    """The window's figures of a run that has gone its length."""
    rec = runner.recorder
    s = rec.summary(window)
    t = rec.series("t")
    sel = (t >= s.t0 - 1e-12) & (t <= s.t1 + 1e-12)
    out: dict[str, Any] = {"window": [s.t0, s.t1], "samples": int(sel.sum())}
    for key, name in (("vertex_h", "vertex_y"), ("vertex_x", "vertex_x"),
                      ("landing_x", "landing_x"), ("speed", "speed_mean")):
        v = rec.series(name)[sel]
        out[key] = float(v.mean())
        out[key + "_std"] = float(v.std())
    # the recorder's own means (measure.Summary) agree; keep its T0_bar and end tension
    out["T0_bar"] = s.T0_bar
    tb = s.extras.get("tension_bar")
    out["TE_bar_measured"] = float(tb[-1]) if tb is not None and len(tb) else math.nan
    vy = rec.series("vertex_y")[sel]
    drift, growth = _halves(t[sel], vy)
    rel = out["vertex_h_std"] / out["vertex_h"]
    out.update(drift=drift, growth=growth, rel_std=rel, verdict=verdict(drift, rel, growth))
    return out


def run_case(fountain: str, c: float, d: float, refine: int, duration: float,
             window: float, damper_x: float = DAMPER_X) -> dict[str, Any]:
    """One run, measured."""
    lvl, settings = case_level(fountain, c, d, refine, damper_x)
    runner = start(lvl)
    t0 = time.perf_counter()
    ended = runner.advance(duration)
    wall = time.perf_counter() - t0
    rec: dict[str, Any] = {"fountain": fountain, "refine": refine, "settings": settings,
                           "start": "catenary", "duration": runner.time, "wall_s": wall,
                           "links": runner.sim.n_links,
                           "ended": None if ended is None else ended.reason}
    if ended is None:
        rec.update(measure(runner, window))
    return rec


def _parse_case(text: str) -> tuple[float, float]:
    c, _, d = text.partition(":")
    return float(c), float(d or 0.0)


def _line(r: dict[str, Any]) -> str:
    s = r["settings"]
    head = (f"{r['fountain']:8s} c={s['c_base']:<6g} d={s['d_base']:<7g} r={r['refine']} "
            f"L={s['L']:g} dt={s['dt']:g} sub={s['substeps']} wall={r['wall_s']:.0f}s")
    if r.get("ended"):
        return head + f"  ENDED: {r['ended']}"
    return (head + f"  h={r['vertex_h']:.4f}+-{r['vertex_h_std']:.4f} "
            f"xv={r['vertex_x']:.4f} l={r['landing_x']:.4f}+-{r['landing_x_std']:.4f} "
            f"v={r['speed']:.4f} drift={100 * r['drift']:+.2f}% "
            f"growth={r['growth']:+.2f}/s {r['verdict']}")


# ------------------------------------------------------------------ theory
def _has_delta() -> bool:
    from chainfountain.theory import stiff

    return "delta" in inspect.signature(stiff.stiff_fountain).parameters


def theory(r: dict[str, Any], v_source: str = "feed") -> dict[str, Any]:
    """The BVP and the catenary for run ``r``'s fountain at the feed speed
    (``v_source="feed"``) or the measured speed in flight (``"measured"``)."""
    from chainfountain.theory.stiff import NoSteadyFountain, scaled_stiffness, stiff_fountain

    s = r["settings"]
    v = s["feed_speed"] if v_source == "feed" else r["speed"]
    lam, L = s["lambda"], s["L"]
    e = scaled_stiffness(s["c"], L, lam, v)
    out: dict[str, Any] = {"v": v, "e": e}
    kw: dict[str, Any] = {}
    if s["d"] > 0.0:
        if not _has_delta():
            out["bvp"] = "no damper in chainfountain.theory.stiff"
            return _catenary(out, s, v)
        delta = s["d"] * L / (lam * v)
        kw["delta"] = delta
        out["delta"] = delta
    try:
        f = stiff_fountain(v, s["launch_angle"], s["drop"], s["TE_bar"], e, g=s["g"], **kw)
        out.update(bvp_h=f.h, bvp_vertex_x=f.vertex_x, bvp_l=f.l)
    except (NoSteadyFountain, ValueError) as exc:
        out["bvp"] = str(exc)
    return _catenary(out, s, v)


def _catenary(out: dict[str, Any], s: dict[str, Any], v: float) -> dict[str, Any]:
    ref = LaunchReference.from_launch(v, s["launch_angle"], s["drop"], s["g"],
                                      TE_bar=s["TE_bar"])
    out.update(cat_h=ref.h, cat_vertex_x=ref.x_rise, cat_l=ref.landing_x)
    return out


def table(runs: list[dict[str, Any]], v_source: str) -> str:
    """A markdown table, a row per run: the simulated vertex height and landing, the BVP
    at that run's ``e`` (and ``delta``), the catenary, the differences, the refinement
    difference (the ``r = 2`` row against the ``r = 1`` one) and the verdict."""
    first: dict[tuple, dict[str, Any]] = {}
    rows = ["| fountain | c | d | r | L | dt | sub | h sim | h BVP | h cat | sim/BVP-1 h | "
            "l sim | l BVP | l cat | sim/BVP-1 l | r2/r1-1 h, l | verdict |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sorted(runs, key=lambda r: (r["fountain"], r["settings"]["c_base"],
                                         r["settings"]["d_base"], r["refine"])):
        s = r["settings"]
        key = (r["fountain"], s["c_base"], s["d_base"])
        head = (f"| {r['fountain']} | {s['c_base']:g} | {s['d_base']:g} | {r['refine']} | "
                f"{s['L']:g} | {s['dt']:g} | {s['substeps']} |")
        if r.get("ended"):
            rows.append(head + f" ended: {r['ended']} |" + " |" * 9)
            continue
        th = theory(r, v_source)
        bh, bl = th.get("bvp_h"), th.get("bvp_l")

        def pct(a: float, b: float | None) -> str:
            return "-" if b is None else f"{100 * (a / b - 1):+.2f} %"

        def num(x: float | None) -> str:
            return "none" if x is None else f"{x:.4f}"

        ref = ""
        if r["refine"] == 1:
            first[key] = r
        elif key in first:
            r1 = first[key]
            ref = (f"{100 * (r['vertex_h'] / r1['vertex_h'] - 1):+.2f}, "
                   f"{100 * (r['landing_x'] / r1['landing_x'] - 1):+.2f} %")
        rows.append(head + f" {r['vertex_h']:.4f} +- {r['vertex_h_std']:.4f} | {num(bh)} | "
                    f"{th['cat_h']:.4f} | {pct(r['vertex_h'], bh)} | "
                    f"{r['landing_x']:.4f} +- {r['landing_x_std']:.4f} | {num(bl)} | "
                    f"{th['cat_l']:.4f} | {pct(r['landing_x'], bl)} | {ref} | "
                    f"{r['verdict']} |")
    return "\n".join(rows)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m research.stiff_runs",
                                 description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    rp = sub.add_parser("run", help="run cases and write their figures")
    rp.add_argument("--fountain", choices=sorted(FOUNTAINS), nargs="+",
                    default=["wide_low"])
    rp.add_argument("--cases", nargs="*", default=[], metavar="C:D",
                    help="(c, d) at the base link, e.g. 0.04:3e-5")
    rp.add_argument("--grid", action="store_true", help="the notes' grid (GRID) instead")
    rp.add_argument("--refine", type=int, nargs="+", default=[1], choices=(1, 2))
    rp.add_argument("--duration", type=float, default=10.0)
    rp.add_argument("--window", type=float, default=4.0)
    rp.add_argument("--damper-x", type=float, default=DAMPER_X,
                    help="largest damper step exponent 2 d h/I (sets the substeps)")
    rp.add_argument("--out", type=Path)
    tp = sub.add_parser("table", help="the markdown table of a run file, with theory")
    tp.add_argument("file", type=Path, nargs="+")
    tp.add_argument("--v", choices=("feed", "measured"), default="feed",
                    help="the speed the BVP and the catenary are solved at")
    a = ap.parse_args(argv)
    if a.cmd == "table":
        runs = [r for f in a.file for r in json.loads(f.read_text())]
        print(table(runs, a.v))
        return 0
    todo = [(f, c, d) for f in a.fountain for c, d in
            (GRID[f] if a.grid else [_parse_case(x) for x in a.cases])]
    if not todo:
        ap.error("no cases: --cases C:D ... or --grid")
    runs: list[dict[str, Any]] = []
    for f, c, d in todo:
        for r in a.refine:
            res = run_case(f, c, d, r, a.duration, a.window, a.damper_x)
            record(runs, res, _line(res), a.out)
    return 0


def record(runs: list[dict[str, Any]], res: dict[str, Any], line: str,
           out: Path | None) -> None:
    """Append a run, print its line and rewrite ``out`` (JSON) with every run so far."""
    runs.append(res)
    print(line, flush=True)
    if out is not None:
        out.write_text(json.dumps(runs, indent=1))


if __name__ == "__main__":
    sys.exit(main())
