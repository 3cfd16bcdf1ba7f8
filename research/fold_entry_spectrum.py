"""Spectrum of one lower-plate joint's force (signed x and y, chipmunk's jAcc) in an
apparatus run: which frequencies carry the fluctuation that inflates |impulse|/h.

    python -m research.fold_entry_spectrum H [key=value ...]
"""
import argparse
import sys

import numpy as np

from chainfountain.sim.fastbody import pivot_impulse
from research.fold_entry_step import laid_run

BANDS = [(0, 50), (50, 140), (140, 160), (160, 400), (400, 1000), (1000, 5000), (5000, 1e9)]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("h", type=float, help="pymunk step (s)")
    ap.add_argument("changes", nargs="*", metavar="key=value", help="level changes")
    a = ap.parse_args(argv)
    h = a.h
    sim = laid_run(h, a.changes)
    app = sim.apparatus
    lam = sim.chain.cfg.linear_density
    ss = sim.space.step
    X, Y, V = [], [], []

    def step(hs):
        ss(hs)
        q = list(app.fold_held[-1])
        jx, jy = pivot_impulse(q[8][0].up_joint)
        X.append(jx / hs)
        Y.append(jy / hs)
        V.append(q[8][0].body.velocity.x)

    sim.space.step = step
    sim.advance(1.0)
    X, Y, V = map(np.array, (X, Y, V))
    v = app.strand_speed
    s = lam * v * v
    print(f"h {h*1e3:g} ms: Tx mean {X.mean()/s:.4f} sd {X.std()/s:.4f}; Ty sd "
          f"{Y.std()/s:.4f}; link vx sd {V.std():.4f} m/s")
    for name, z in (("Tx", X), ("Ty", Y), ("vx", V)):
        f = np.fft.rfftfreq(len(z), h)
        P = np.abs(np.fft.rfft(z - z.mean())) ** 2
        top = np.argsort(P)[::-1][:6]
        tot = P.sum()
        bs = " ".join(f"{lo}-{hi:g}:{P[(f >= lo) & (f < hi)].sum()/tot:.2f}" for lo, hi in BANDS)
        print(f"  {name}: peaks " + ", ".join(f"{f[i]:.0f} Hz" for i in top)
              + f"; power by band {bs}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
