"""Spectrum of one lower-plate joint's force (signed x and y, chipmunk's jAcc) in an
apparatus run: which frequencies carry the fluctuation that inflates |impulse|/h.

    python research/fold_entry_spectrum.py H [key=value ...]
"""
import sys
from pathlib import Path

import numpy as np
from pymunk._chipmunk_cffi import ffi

from chainfountain.level import io
from chainfountain.sim import Simulation
from chainfountain.study.changes import laid_on_path, with_changes

sys.path.insert(0, str(Path(__file__).parent))
from fold_entry_step import JACC, parse_val  # noqa: E402

h = float(sys.argv[1])
ch = {k: parse_val(v) for k, v in (a.split("=", 1) for a in sys.argv[2:])}
lvl = io.load(Path("levels/apparatus_fold.toml"))
ch["solver.dt"] = h * lvl.sim.solver.substeps
lvl = with_changes(lvl, ch)
sim = Simulation(laid_on_path(lvl).sim)
app = sim.apparatus
lam = lvl.sim.chain.linear_density
sim.advance(1.0)
ss = sim.space.step
X, Y, V = [], [], []


def step(hs):
    ss(hs)
    q = list(app.fold_held[-1])
    d = ffi.cast("double *", q[8][0].up_joint._constraint)
    X.append(d[JACC] / hs)
    Y.append(d[JACC + 1] / hs)
    V.append(q[8][0].body.velocity.x)


sim.space.step = step
sim.advance(1.0)
X, Y, V = map(np.array, (X, Y, V))
v = app.strand_speed
s = lam * v * v
print(f"h {h*1e3:g} ms: Tx mean {X.mean()/s:.4f} sd {X.std()/s:.4f}; Ty sd {Y.std()/s:.4f}; "
      f"link vx sd {V.std():.4f} m/s")
for name, z in (("Tx", X), ("Ty", Y), ("vx", V)):
    f = np.fft.rfftfreq(len(z), h)
    P = np.abs(np.fft.rfft(z - z.mean())) ** 2
    top = np.argsort(P)[::-1][:6]
    tot = P.sum()
    bands = [(0, 50), (50, 140), (140, 160), (160, 400), (400, 1000), (1000, 5000), (5000, 1e9)]
    bs = " ".join(f"{a}-{b:g}:{P[(f >= a) & (f < b)].sum()/tot:.2f}" for a, b in bands)
    print(f"  {name}: peaks " + ", ".join(f"{f[i]:.0f} Hz" for i in top) + f"; power by band {bs}")
