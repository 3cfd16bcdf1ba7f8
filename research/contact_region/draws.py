"""Random settings inside a gripped fold's start region, each run from rest.

Draws ``--n`` settings of a gripped-fold preset uniformly inside its admissible region
(:mod:`chainfountain.sim.apparatus.region`: the start speed within its band, the drop
within the band of ``Q = Tbar_E + g H/v**2``, the launch angle within its band; both
carts within their measured bands, :func:`chainfountain.sim.apparatus.laws.fold_runs_on`;
the bands of the preset's table offsets, ``region.bands``; where those fix the geometry,
the carts alone),
runs each from rest for ``--seconds`` (``chainfountain run``, one process per core) and
prints how many formed and held, each setting's speed against the paper's laws with the
brake, and the wall time::

    python -m research.contact_region.draws apparatus_fold_gripped --n 20
    python -m research.contact_region.draws apparatus_special_gripped --n 20 --seed 1

A setting "holds" when the run goes its full length with no early end; "steady" or
"swings" says whether its speed had settled by the steady test (``recording``).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from joblib import Parallel, delayed

from chainfountain.level.io import load
from chainfountain.level.library import resolve
from chainfountain.sim.apparatus import region
from chainfountain.sim.apparatus.laws import braked_fold_speed, fold_runs_on
from chainfountain.study.changes import with_changes


def draw(name: str, n: int, seed: int) -> list[dict[str, float]]:
    """``n`` settings inside the region of preset ``name`` (rejection sampling)."""
    base = load(resolve(name))
    rng = np.random.default_rng(seed)
    g, te = base.sim.gravity, base.sim.apparatus.end_tension
    band = region.bands(base.sim)  # the bands at the preset's table offsets
    assert band is not None, f"{name}: no start region at its table offsets"
    q_lo, q_hi = band.q
    a_lo, a_hi = band.angle
    m_up, m_lo = base.sim.carts[0].mass, base.sim.carts[1].mass
    out: list[dict[str, float]] = []
    while len(out) < n:
        v = float(rng.uniform(*band.speed))
        H = float(rng.uniform(max(q_lo - te, 0.0) * v * v / g, (q_hi - te) * v * v / g))
        geometry = {
            "apparatus.speed": round(v, 4), "apparatus.drop": round(H, 4),
            "apparatus.launch_angle": round(float(rng.uniform(a_lo, a_hi)), 4)}
        changes = {
            **({} if band.fixed else geometry),
            "carts[0].mass": round(float(rng.uniform(0.5 * m_up, 1.5 * m_up)), 4),
            "carts[1].mass": round(float(rng.uniform(0.97 * m_lo, 1.1 * m_lo)), 4),
        }
        try:
            level = with_changes(base, changes)
        except Exception:  # refused: outside the region after rounding
            continue
        if fold_runs_on(level.sim, base.sim):
            out.append(changes)
    return out


def run_one(name: str, changes: dict[str, float], seconds: float, out: Path) -> dict:
    """Run one setting from rest; its outcome and figures."""
    args = [sys.executable, "-m", "chainfountain", "run", name, "--duration", str(seconds),
            "--out", str(out), "--quiet", *(f"{k}={v}" for k, v in changes.items())]
    proc = subprocess.run(args, capture_output=True, text=True)
    summary = out / "summary.json"
    s = json.loads(summary.read_text()) if summary.exists() else {}
    ended = s.get("ended_early") or {}
    return {"changes": changes, "rc": proc.returncode, "steady": s.get("steady"),
            "v": s.get("v"), "ended": str(ended.get("reason", ended) if ended else "")[:80],
            "refused": proc.stderr.strip()[:120] if proc.returncode == 2 else ""}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("preset")
    p.add_argument("--n", type=int, default=20)
    p.add_argument("--seconds", type=float, default=30.0)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--save", type=Path, default=None,
                   help="write the settings and outcomes as JSON (the map reads them)")
    a = p.parse_args(argv)
    settings = draw(a.preset, a.n, a.seed)
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        rows = Parallel(n_jobs=a.jobs)(
            delayed(run_one)(a.preset, c, a.seconds, Path(tmp) / f"p{i}")
            for i, c in enumerate(settings))
    wall = time.perf_counter() - t0
    base = load(resolve(a.preset))
    held = 0
    for r in rows:
        ok = r["rc"] == 0 and not r["ended"]
        held += bool(ok)
        state = ("holds, steady " if ok and r["steady"] else "holds, swings" if ok
                 else "FAILS        ")
        law = braked_fold_speed(with_changes(base, r["changes"]).sim)
        c = {**region.fixed_geometry(base.sim), **r["changes"]}
        v = r["v"]
        off = f"{100 * (v / law - 1):+.2f} %" if v else "-"
        print(f"{state}  H={c['apparatus.drop']:.3f} v0={c['apparatus.speed']:.3f}"
              f" a0={np.degrees(c['apparatus.launch_angle']):.1f}"
              f" up={1e3 * c['carts[0].mass']:.1f} g"
              f" lo={1e3 * c['carts[1].mass']:.1f} g  v={v if v else float('nan'):.3f} ({off} of"
              f" the laws)  {r['ended'] or r['refused']}")
    if a.save is not None:
        a.save.parent.mkdir(parents=True, exist_ok=True)
        a.save.write_text(json.dumps({"preset": a.preset, "seconds": a.seconds,
                                      "rows": rows}, indent=1))
    print(f"{a.preset}: {held} of {len(rows)} held {a.seconds:g} s from rest "
          f"({wall:.0f} s wall on {a.jobs} processes)")
    return 0 if held == len(rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
