"""Why the lower plate strand's tension depends on the pymunk step h (thirty-ninth session).

Runs an apparatus level laid on its path, with optional monkeypatched variants of the lower
side, and prints over [t0, t1] (every pymunk step): the plate strand's tension read as
|up_joint.impulse|/h over plate-queue links 3..12 (the session's reading), the same read
as the signed x-force (chipmunk's jAcc, read from memory), the tension profile
along the lower guide's elements, the chain speed and the roller's speed, all scaled by
lambda v^2, against the loss-free law 1/4 + F_c/(2 lambda v^2) + g R/v^2 (gripped).

Usage::

    python -m research.fold_entry_step --level apparatus_fold --h 5e-4 2.5e-4 \
        --set apparatus.fold_roller=gripped apparatus.fold_roller_radius=0.1 \
        carts[0].mass=0.019 carts[1].mass=0.002 apparatus.plate_links=0 [--patch NAME=VALUE ...]

Patches: nokeep (no keep_on_arcs projection), close=X (FOLD_CLOSE_RATE), gbias=X (arc slide
joints' error bias), lbias=X (guide line/groove joints' error bias), release=X
(FOLD_RELEASE), catch=X (the gripped roller's CATCH_TIME), platenog (no gravity on
plate-strand links), cbias=X (chain joints' bias).
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Simulation
from chainfountain.sim.apparatus import Tuning
from chainfountain.sim.fastbody import PIVOT_JACC as JACC
from chainfountain.sim.fastbody import pivot_impulse
from chainfountain.study.changes import laid_on_path, with_changes

__all__ = ["JACC", "jacc_x", "laid_run", "parse_val"]


def jacc_x(j) -> float:
    """Signed x-impulse of a chain pivot joint on its upstream link (> 0: tension)."""
    return pivot_impulse(j)[0]


def laid_run(h: float, changes: list[str], level: str = "apparatus_fold") -> Simulation:
    """``level`` at pymunk step ``h`` with ``key=value`` ``changes``, laid on its path and
    run 1 s (the start of fold_entry_check.py and fold_entry_spectrum.py)."""
    ch = {k: parse_val(v) for k, v in (a.split("=", 1) for a in changes)}
    lvl = io.load(shipped_dir() / f"{level}.toml")
    ch["solver.dt"] = h * lvl.sim.solver.substeps
    sim = Simulation(with_changes(laid_on_path(lvl), ch).sim)
    sim.advance(1.0)
    return sim


def parse_val(v: str):
    for f in (int, float):
        try:
            return f(v)
        except ValueError:
            pass
    return v


def apply_patches(patches: dict) -> None:
    import chainfountain.sim.apparatus.fold as fold
    import chainfountain.sim.guide as guide
    if "nokeep" in patches:
        fold.keep_on_arcs = lambda *a, **k: None
    if "gbias" in patches:
        guide.GUIDE_BIAS = float(patches["gbias"])
    if "release" in patches:
        fold.FOLD_RELEASE = float(patches["release"])
    if "catch" in patches:
        import chainfountain.sim.apparatus.grip as grip
        grip.CATCH_TIME = float(patches["catch"])
    if "lbias" in patches:
        orig = guide.GuideElement.joint
        lb = float(patches["lbias"])

        def joint(self, space, body, error_bias):
            j = orig(self, space, body, error_bias)
            if self.form == "line":
                j.error_bias = lb
            return j
        guide.GuideElement.joint = joint


def run(level: str, h: float, sets: dict, patches: dict, t0: float, t1: float,
        dt_keep: bool = False) -> dict:
    lvl = io.load(shipped_dir() / f"{level}.toml")
    ch = dict(sets)
    sub = lvl.sim.solver.substeps if "solver.substeps" not in ch else ch["solver.substeps"]
    ch["solver.dt"] = h * sub
    lvl = with_changes(lvl, ch)
    sim = Simulation(laid_on_path(lvl).sim)
    app = sim.apparatus
    if "close" in patches:
        app.retune(Tuning(fold_close_rate=float(patches["close"])))
    if "cbias" in patches:
        sim.chain.set_error_bias(float(patches["cbias"]))
    lam = lvl.sim.chain.linear_density
    g = lvl.sim.gravity
    hh = app.h
    sim.advance(t0)
    ss = sim.space.step
    rows = []
    prof = []
    platenog = "platenog" in patches

    def step(hs):
        if platenog:  # cancel gravity on the plate strand's links
            for lk, _ in app.fold_held[-1]:
                b = lk.body
                b.apply_force_at_local_point((0.0, b.mass * g), (0.0, 0.0))
        ss(hs)
        q = list(app.fold_held[-1])
        sel = [lk for lk, _ in q[3:12] if lk.up_joint is not None]
        Tm = np.mean([abs(lk.up_joint.impulse) / hh for lk in sel])
        jx = np.array([jacc_x(lk.up_joint) / hh for lk in sel])
        Tx = jx.mean()
        j5 = jacc_x(sel[5].up_joint) / hh if len(sel) > 5 else np.nan
        vpl = np.mean([lk.body.velocity.x for lk, _ in q[3:12]])
        prof_el = []
        for qq in app.fold_held:
            ts = [abs(lk.up_joint.impulse) / hh for lk, _ in list(qq)[1:-1]
                  if lk.up_joint is not None]
            prof_el.append(np.mean(ts) if ts else np.nan)
        rows.append((Tm, Tx, app.strand_speed, vpl, app.lower.speed,
                     app.lower.roller.angular_velocity, np.mean(np.abs(jx)), np.mean(jx < 0),
                     j5))
        prof.append(prof_el)
    sim.space.step = step
    w = time.time()
    sim.advance(t1 - t0)
    a = np.array(rows)
    v = a[:, 2].mean()
    s = lam * v * v
    R = app.R_lo if app.gripped else 0.0
    law = 0.25 + 0.5 * app.lower.force / s + g * R / v**2
    pr = np.nanmean(np.array(prof), axis=0) / s
    return dict(T=a[:, 0].mean() / s, Tx=a[:, 1].mean() / s, v=v, vpl=a[:, 3].mean(),
                vR=a[:, 4].mean() / v, law=law, prof=pr, wall=time.time() - w,
                Tsd=np.std(a[:, 0]) / s, Tabsx=a[:, 6].mean() / s, comp=a[:, 7].mean(),
                j5sd=np.std(a[:, 8]) / s, ac1=np.corrcoef(a[1:, 8], a[:-1, 8])[0, 1])


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--level", default="apparatus_fold")
    ap.add_argument("--h", type=float, nargs="+", default=[5e-4, 2.5e-4])
    ap.add_argument("--set", nargs="*", default=[])
    ap.add_argument("--patch", nargs="*", default=[])
    ap.add_argument("--t0", type=float, default=1.0)
    ap.add_argument("--t1", type=float, default=2.0)
    a = ap.parse_args()
    sets = {k: parse_val(v) for k, v in (s.split("=", 1) for s in a.set)}
    patches = dict((p.split("=", 1) + [""])[:2] for p in a.patch)
    apply_patches(patches)
    for h in a.h:
        r = run(a.level, h, sets, patches, a.t0, a.t1)
        prof = " ".join(f"{x:.3f}" for x in r["prof"])
        print(f"h {h*1e3:.4g} ms  |J|/h {r['T']:.4f}  Jx/h {r['Tx']:.4f}  |Jx|/h {r['Tabsx']:.4f}  "
              f"compressed {r['comp']:.3f}  one joint: sd {r['j5sd']:.3f} "
              f"lag-1 corr {r['ac1']:+.2f}  law {r['law']:.4f}  "
              f"v {r['v']:.3f} vplate {r['vpl']:.3f}  vR/v {r['vR']:.4f}  profile [{prof}]  "
              f"({r['wall']:.0f} s)", flush=True)


if __name__ == "__main__":
    main()
