"""Time the full figure set: ``.venv/bin/python benchmarks/bench_figures.py [OUT_DIR]``.

Budget: the whole set in under a minute (issue 6). Prints per-figure and total times.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

from chainfountain import figures


def main() -> None:
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp(prefix="cf-figs-"))
    total = 0.0
    for name in figures.FIGURES:
        t0 = time.perf_counter()
        figures.main(out, progress=False, names=[name])
        dt = time.perf_counter() - t0
        total += dt
        print(f"{name:28s} {dt:6.2f} s")
    print(f"{'total':28s} {total:6.2f} s  (budget 60 s) -> {out}")
    if total > 60:
        raise SystemExit("figure set over budget")


if __name__ == "__main__":
    main()
