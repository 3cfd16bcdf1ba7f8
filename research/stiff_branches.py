"""The steady stiff fountains of a launch over a range of stiffness: the branches that
continuation upwards, downwards and fresh solves from the catenary find
(:func:`chainfountain.theory.stiff.branches`), printed and, with ``--figure``, drawn.

    python -m research.stiff_branches --fountain paper --figure /tmp/branches.png
    python -m research.stiff_branches --fountain wide_low --e 1e-4 2e-2 --n 40
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

FOUNTAINS = {
    "paper": "the paper's example: 5.10 m/s at 82.0 deg, H = 2 m, Tbar_E = 0.123",
    "wide_low": "wide_low: 4 m/s at 60 deg, H = 0.5 m, Tbar_E = 0",
}


def launch(name: str) -> tuple[float, float, float, float]:
    """``(v, alpha0, H, Tbar_E)`` of the named fountain."""
    if name == "paper":
        from chainfountain.figures.paper import example_fountain

        f = example_fountain()
        return f.v, f.alpha0, f.H, f.TE_bar
    return 4.0, math.pi / 3, 0.5, 0.0


def main(argv: list[str] | None = None) -> None:
    from chainfountain.theory import Fountain, stiff

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fountain", choices=list(FOUNTAINS), default="paper")
    ap.add_argument("--e", nargs=2, type=float, default=(1e-4, 1e-3), metavar=("LO", "HI"),
                    help="range of the scaled stiffness e (m^2)")
    ap.add_argument("--n", type=int, default=37, help="stiffnesses (log-spaced)")
    ap.add_argument("--delta", type=float, default=0.0, help="scaled damping (m^3)")
    ap.add_argument("--figure", type=Path)
    a = ap.parse_args(argv)
    v, alpha0, H, TE = launch(a.fountain)
    cat = Fountain.from_launch(v=v, alpha0=alpha0, H=H, TE_bar=TE)
    es = list(np.geomspace(a.e[0], a.e[1], a.n))
    t = time.perf_counter()
    found = stiff.branches(v, alpha0, H, TE, es, delta=a.delta)
    print(f"{FOUNTAINS[a.fountain]}; catenary h = {cat.h:.4f} m, l = {cat.l:.4f} m; "
          f"{len(found)} branch(es), {time.perf_counter() - t:.0f} s")
    print("e [m^2]   " + "   ".join(f"h{i} [m]  l{i} [m]" for i in range(len(found))))
    for j, e in enumerate(es):
        cells = "   ".join(("   --      --   " if not np.isfinite(b.h[j]) else
                           f"{b.h[j]:.4f}  {b.l[j]:.4f}") for b in found)
        print(f"{e:.3e} {cells}")
    if a.figure:
        from chainfountain.figures._io import plt

        fig, (ax_h, ax_l) = plt.subplots(2, 1, figsize=(6.4, 5.6), sharex=True,
                                         layout="constrained")
        for i, b in enumerate(found):
            ax_h.plot(b.e, b.h, "o-", ms=3, label=f"branch {i}")
            ax_l.plot(b.e, b.l, "o-", ms=3)
        ax_h.axhline(cat.h, color="0.4", ls="--", lw=0.8, label="catenary")
        ax_l.axhline(cat.l, color="0.4", ls="--", lw=0.8)
        ax_h.set_xscale("log")
        ax_h.set_ylabel("vertex height h [m]")
        ax_l.set_ylabel("landing l [m]")
        ax_l.set_xlabel("scaled stiffness e [m^2]")
        ax_h.legend(fontsize=8)
        ax_h.set_title(FOUNTAINS[a.fountain], fontsize=9)
        fig.savefig(a.figure, dpi=110)


if __name__ == "__main__":
    main()
