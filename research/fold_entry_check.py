"""Check the signed joint reading of research/fold_entry_step.py against the plate links'
x-momentum (grooves and gravity act in y only, so m dv_x = J_x(down joint) - J_x(own up
joint) per pymunk step), and compare the 50-ms window tension three ways: mean |J|/h, mean
signed J_x/h and |mean J vector|/h.

    python -m research.fold_entry_check H [key=value ...]
"""
import argparse
import sys

import numpy as np

from chainfountain.sim.fastbody import pivot_impulse
from research.fold_entry_step import laid_run


def J(j):
    return pivot_impulse(j)


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
    res, mag, sx, vec = [], [], [], []

    def step(hs):
        q = [lk for lk, _ in app.fold_held[-1]][2:14]
        v0 = [lk.body.velocity.x for lk in q]
        ss(hs)
        if [lk for lk, _ in app.fold_held[-1]][2:14] != q:
            return
        for k in range(1, len(q)):  # link q[k]: down joint is q[k-1].up_joint, own up joint
            lk = q[k]
            dp = lk.body.mass * (lk.body.velocity.x - v0[k])
            res.append((dp, J(q[k - 1].up_joint)[0] - J(lk.up_joint)[0]))
        j = q[6].up_joint
        mag.append(j.impulse / hs)
        jx, jy = J(j)
        sx.append(jx / hs)
        vec.append((jx / hs, jy / hs))

    sim.space.step = step
    sim.advance(1.0)
    r = np.array(res)
    print(f"h {h*1e3:g} ms: momentum check over {len(r)} link-steps: |m dv_x - (J_down,x - "
          f"J_up,x)| max {np.abs(r[:, 0] - r[:, 1]).max():.2e} N s (impulses "
          f"~{np.abs(r[:, 1]).mean():.1e})")
    s = lam * app.strand_speed ** 2
    n = int(round(0.05 / h))
    m, x, V = np.array(mag), np.array(sx), np.array(vec)
    w = len(m) // n
    mw = m[:w * n].reshape(w, n).mean(1) / s
    xw = x[:w * n].reshape(w, n).mean(1) / s
    vw = np.hypot(*V[:w * n].reshape(w, n, 2).mean(1).T) / s
    print(f"  50-ms windows (mean, sd): |J|/h {mw.mean():.4f} {mw.std():.4f}; signed J_x/h "
          f"{xw.mean():.4f} {xw.std():.4f}; |mean J|/h {vw.mean():.4f} {vw.std():.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
