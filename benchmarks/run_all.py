"""Run every benchmark script in this folder and print their figures (``make bench``).

The studies (``convergence_study.py``, ``*_study.py``) take longer and are run
by hand; see ``docs/``.
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
