"""Every shipped level's ``summary.json`` figures, for comparing two versions of the code.

A change that only moves code (a refactoring) must leave every figure of every shipped
level unchanged, bit for bit where the arithmetic is untouched. This script runs each
level headless for ``--duration`` simulated seconds (``chainfountain run``), keeps the
figures of its ``summary.json`` (not the wall time, the real-time factor or the output
paths) and writes them to one JSON file; ``--compare`` prints the differences between two
such files, a key renamed since the older was taken compared under its new name.

Usage::

    python research/summary_snapshot.py --out before.json          # on the old code
    python research/summary_snapshot.py --out after.json           # on the new code
    python research/summary_snapshot.py --compare before.json after.json
    python research/summary_snapshot.py --hashes --out before_h.json   # link states
    python research/summary_snapshot.py --hashes --only 'apparatus_*' --out a.json  # some

About 8 minutes at the default 3 s, long enough for the steady-state path (the
near-critical fountain D presets dominate).
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

from chainfountain.level.library import shipped_dir

LEVELS = shipped_dir()
VOLATILE = {"wall_s", "realtime_factor", "outputs"}
"""Keys that differ between identical runs (timing) or name files."""


def snapshot(duration: float, only: str = "*") -> dict[str, dict]:
    """Figures of every shipped level (whose name matches ``only``) after ``duration``
    simulated seconds."""
    out: dict[str, dict] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for path in sorted(LEVELS.glob(f"{only}.toml")):
            d = Path(tmp) / path.stem
            r = subprocess.run([sys.executable, "-m", "chainfountain", "run", str(path),
                                "--duration", str(duration), "--quiet", "--out", str(d)],
                               capture_output=True, text=True)
            summary = d / "summary.json"
            if not summary.exists():
                out[path.stem] = {"exit_status": r.returncode, "stderr": r.stderr.strip()}
                continue
            s = json.loads(summary.read_text())
            out[path.stem] = {k: v for k, v in s.items() if k not in VOLATILE}
            out[path.stem]["exit_status"] = r.returncode
            print(f"{path.stem}: exit {r.returncode}", file=sys.stderr, flush=True)
    return out


def state_hashes(duration: float, only: str = "*") -> dict[str, str]:
    """A SHA-256 of every body's position, velocity, angle and spin in each shipped level
    after ``duration`` simulated seconds from its start (``chainfountain.start``): equal
    hashes mean the refactored code steps the same bodies to the last bit."""
    import hashlib

    import chainfountain

    out: dict[str, str] = {}
    for path in sorted(LEVELS.glob(f"{only}.toml")):
        sim = chainfountain.start(str(path))
        ended = sim.advance(duration)
        space = getattr(sim.sim, "space", None) or sim.sim.scene.space
        h = hashlib.sha256()
        for b in space.bodies:
            h.update(repr((tuple(b.position), tuple(b.velocity), b.angle,
                           b.angular_velocity)).encode())
        out[path.stem] = f"{h.hexdigest()[:16]} t={sim.time:.4f} ended={ended is not None}"
        print(f"{path.stem}: {out[path.stem]}", file=sys.stderr, flush=True)
    return out


def _flatten(obj, prefix: str = "") -> dict[str, object]:
    if isinstance(obj, dict):
        items: dict[str, object] = {}
        for k, v in obj.items():
            items.update(_flatten(v, f"{prefix}.{k}" if prefix else str(k)))
        return items
    if isinstance(obj, list):
        items = {}
        for i, v in enumerate(obj):
            items.update(_flatten(v, f"{prefix}[{i}]"))
        return items
    return {prefix: obj}


def renamed(flat: dict[str, object]) -> dict[str, object]:
    """A flattened snapshot (``level.key``) with the keys of earlier versions'
    ``summary.json`` under their names now (:data:`chainfountain.headless.OLD_NAMES`), so
    that an old snapshot compares with a new one figure by figure; a key dropped because it
    repeated another is left out. A key already under its new name wins."""
    from chainfountain.headless.report import OLD_NAMES

    out: dict[str, object] = {}
    moved: dict[str, object] = {}
    for key, value in flat.items():
        level, _, rest = key.partition(".")
        new = OLD_NAMES.get(rest, rest)
        if new is None:
            continue
        (out if new == rest else moved)[f"{level}.{new}"] = value
    return {**moved, **out}


def compare(a: dict, b: dict) -> int:
    """Print every figure that differs (keys renamed since ``a`` was taken compared under
    their new names: :func:`renamed`); returns the number of differences."""
    fa, fb = renamed(_flatten(a)), renamed(_flatten(b))
    n = 0
    for key in sorted(set(fa) | set(fb)):
        x, y = fa.get(key, "<missing>"), fb.get(key, "<missing>")
        same = x == y or (isinstance(x, float) and isinstance(y, float)
                          and math.isnan(x) and math.isnan(y))
        if not same:
            n += 1
            rel = ""
            if isinstance(x, int | float) and isinstance(y, int | float) and x:
                rel = f"  ({(y - x) / abs(x):+.2e} relative)"
            print(f"{key}: {x!r} -> {y!r}{rel}")
    print(f"{len(set(fa) | set(fb))} figures compared, {n} differ")
    return n


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--duration", type=float, default=None,
                    help="simulated seconds (default 3 for figures, 2 for --hashes)")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--hashes", action="store_true",
                    help="link-state hashes after --duration (default 2 s) instead of figures")
    ap.add_argument("--only", default="*", metavar="GLOB",
                    help="only the levels whose name matches GLOB (e.g. 'apparatus_*')")
    ap.add_argument("--compare", nargs=2, type=Path, metavar=("BEFORE", "AFTER"))
    a = ap.parse_args(argv)
    if a.compare:
        before, after = (json.loads(p.read_text()) for p in a.compare)
        return 1 if compare(before, after) else 0
    if a.out is None:
        ap.error("--out FILE or --compare BEFORE AFTER")
    data = (state_hashes(a.duration or 2.0, a.only) if a.hashes
            else snapshot(a.duration or 3.0, a.only))
    a.out.write_text(json.dumps(data, indent=1, sort_keys=True))
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
