"""Random settings inside a contact machine's start region, each run from rest.

Draws ``--n`` settings of a gripped-fold or floor preset uniformly inside its admissible
region (:mod:`chainfountain.sim.apparatus.region`, which the level check reads): every
field the region ranges over (``region.Bands.other_ranges``, ``FLOOR_FROM_REST_RANGE``: the
chain's links, friction and joints, the rollers, the treadmill), the upper cart and its
track, and for a gripped fold the lower cart and, in its tables' bands
(``region.bands``), the drop, start speed and launch angle; for the floor machine
the drop, start speed, launch angle, upper table offset and bearing drag. A draw the level
check refuses (the carts' push, the floor's law) is drawn again. Each runs from rest for
``--seconds`` (``chainfountain run``, one process per core); the script prints how many
formed and held, each setting's speed against its law (a gripped fold's: the paper's laws
with the brake; the floor's: this model's pick-up law) and the wall time::

    python -m research.contact_region.draws apparatus_fold_gripped --n 20
    python -m research.contact_region.draws apparatus_floor --n 20 --seed 1

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
from chainfountain.sim.apparatus.laws import braked_fold_speed, floor_speeds
from chainfountain.study.changes import with_changes


def _uniform(rng: np.random.Generator, band: tuple[float, float]) -> float | int:
    lo, hi = band
    if isinstance(lo, int) and isinstance(hi, int):
        return int(rng.integers(lo, hi + 1))
    return float(f"{rng.uniform(lo, hi):.5g}")


def draw(name: str, n: int, seed: int) -> list[dict[str, float]]:
    """``n`` settings inside the region of preset ``name`` (rejection sampling: every field
    the region ranges over drawn uniformly in its band, kept where the level check, which
    reads the region, admits it)."""
    base = load(resolve(name))
    rng = np.random.default_rng(seed)
    g, te = base.sim.gravity, base.sim.apparatus.end_tension
    floor = base.sim.apparatus.variant == "floor"
    band = None if floor else region.bands(base.sim)  # the bands at the preset's tables
    assert floor or band is not None, f"{name}: no start region at its table offsets"
    ranges = region.FLOOR_FROM_REST_RANGE if floor else band.other_ranges()
    m_up = base.sim.carts[0].mass
    out: list[dict[str, float]] = []
    while len(out) < n:
        changes: dict[str, float] = {p: _uniform(rng, r) for p, r in ranges.items()}
        changes["carts[0].incline"] = _uniform(rng, (0.35, 0.7))
        changes["carts[0].mass"] = round(float(rng.uniform(0.3 * m_up, 1.5 * m_up)), 4)
        if floor:
            changes |= {"apparatus.drop": _uniform(rng, (0.37, 0.9)),
                        "apparatus.speed": _uniform(rng, (2.5, 3.5)),
                        "apparatus.launch_angle": _uniform(rng, region.FLOOR_ANGLE),
                        "apparatus.xi2": _uniform(rng, (0.1, 0.5)),
                        "apparatus.bearing_drag": _uniform(rng, (0.0, 0.02))}
        else:
            assert band is not None
            m_lo = base.sim.carts[1].mass
            changes["carts[1].mass"] = round(float(rng.uniform(0.97 * m_lo, 1.1 * m_lo)), 4)
            v = float(rng.uniform(*band.speed))
            q_lo, q_hi = band.q
            changes |= {
                "apparatus.speed": round(v, 4),
                "apparatus.drop": round(float(rng.uniform(max(q_lo - te, 0.0) * v * v / g,
                                                          (q_hi - te) * v * v / g)), 4),
                "apparatus.launch_angle": _uniform(rng, band.angle)}
        try:
            with_changes(base, changes)
        except Exception:  # refused: outside the region (the carts' push, the floor's law)
            continue
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
    if a.save is not None:  # first: the runs are what took the time
        a.save.parent.mkdir(parents=True, exist_ok=True)
        a.save.write_text(json.dumps({"preset": a.preset, "seconds": a.seconds,
                                      "rows": rows}, indent=1))
    base = load(resolve(a.preset))
    held = 0
    for r in rows:
        ok = r["rc"] == 0 and not r["ended"]
        held += bool(ok)
        state = ("holds, steady " if ok and r["steady"] else "holds, swings" if ok
                 else "FAILS        ")
        sim = with_changes(base, r["changes"]).sim
        law = floor_speeds(sim)[0] if sim.apparatus.variant == "floor" else \
            braked_fold_speed(sim)
        c = {**region.pinned(base.sim), **r["changes"]}
        v = r["v"]
        off = f"{100 * (v / law - 1):+.2f} %" if v else "-"
        which = "this model's pick-up law" if sim.apparatus.variant == "floor" else \
            "the laws with the brake"
        shown = " ".join(f"{k.split('.')[-1]}={val:.4g}" for k, val in sorted(c.items())
                         if k in r["changes"] and not isinstance(val, str))
        print(f"{state}  v={v if v else float('nan'):.3f} ({off} of {which})  {shown}  "
              f"{r['ended'] or r['refused']}")
    print(f"{a.preset}: {held} of {len(rows)} held {a.seconds:g} s from rest "
          f"({wall:.0f} s wall on {a.jobs} processes)")
    return 0 if held == len(rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
