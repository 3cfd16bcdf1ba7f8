"""``python -m chainfountain.figures OUT_DIR [NAME ...]``: write the paper's figures."""

from __future__ import annotations

import sys
from pathlib import Path

from chainfountain.figures import main

if __name__ == "__main__":
    args = sys.argv[1:]
    if not args or args[0] in ("-h", "--help"):
        print(__doc__)
        raise SystemExit(0 if args else 2)
    for p in main(Path(args[0]), names=args[1:] or None):
        print(p)
