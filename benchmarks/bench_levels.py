"""Every shipped level at its default length, as a user runs it: speed, memory, outcome.

Usage::

    .venv/bin/python benchmarks/bench_levels.py [level ...]

Runs ``chainfountain run LEVEL --headless --quiet`` (default duration) for each level
in ``levels/`` (or the ones named), one at a time in a subprocess, and prints per level:
simulated seconds, wall seconds, real-time factor, links, peak resident memory, exit
status and, when there is one, why the run ended early or which analysis failed. A run
that ends with a traceback (exit status 1) is reported as such and makes the script
exit with 1.
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from chainfountain.level.library import shipped_dir

LEVELS = shipped_dir()


def run_one(name: str) -> dict:
    """Run one level in a subprocess; return its figures."""
    with tempfile.TemporaryDirectory() as out:
        t0 = time.perf_counter()
        r = subprocess.run([sys.executable, "-m", "chainfountain", "run", name, "--headless",
                            "--quiet", "--out", out], capture_output=True, text=True)
        wall = time.perf_counter() - t0
        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0
        summary_path = Path(out) / "summary.json"
        s = json.loads(summary_path.read_text()) if summary_path.exists() else {}
    return {"level": name, "status": r.returncode, "wall": wall, "peak_mb": peak, "summary": s,
            "stderr": r.stderr.strip().splitlines()[-1:] if r.returncode else []}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("levels", nargs="*", help="level names (default: every levels/*.toml)")
    args = ap.parse_args()
    names = args.levels or sorted(p.stem for p in LEVELS.glob("*.toml"))
    print(f"{'level':28s} {'sim s':>6s} {'wall s':>7s} {'RTF':>6s} {'links':>6s} "
          f"{'peak MB':>8s} {'exit':>4s}  note")
    worst = 0
    for name in names:
        f = run_one(name)
        s = f["summary"]
        note = ""
        if (s.get("ended_early") or {}).get("reason"):
            note = "ended early: " + s["ended_early"]["reason"][:90]
        if s.get("analysis_failed"):
            note += " analysis failed: " + ", ".join(s["analysis_failed"])
        if f["stderr"]:
            note += " " + f["stderr"][0][:100]
        # the peak of RUSAGE_CHILDREN is the largest child so far: an upper bound per level
        print(f"{name:28s} {s.get('duration_s') or 0:6.2f} {f['wall']:7.1f} "
              f"{s.get('realtime_factor') or 0:6.2f} {s.get('links') or 0:6d} "
              f"{f['peak_mb']:8.0f} {f['status']:4d}  {note}", flush=True)
        if f["status"] == 1:
            worst = 1
    return worst


if __name__ == "__main__":
    sys.exit(main())
