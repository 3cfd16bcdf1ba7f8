"""Run every benchmark script in this folder and print their figures (``make bench``).

The studies of the model against the paper are in ``research/``, run by hand.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def main() -> int:
    status = 0
    for script in sorted(HERE.glob("bench_*.py")):
        print(f"== {script.name}", flush=True)
        rc = subprocess.call([sys.executable, str(script)])
        if rc:
            print(f"   {script.name} exited with {rc}")
            status = rc
    return status


if __name__ == "__main__":
    sys.exit(main())
