"""The gripped folding roller in the full machine: how long a fold runs, and the pull of
the strand it takes in, at the preset's pymunk step and at half of it.

``apparatus_fold`` with ``apparatus.fold_roller = "gripped"`` (a 100-mm roller,
``fold_roller_radius = 0.1``), laid along its path at 3 m/s; any field can be changed
with ``--set path=value``. Per run it prints the chain speed's 1-s means and how the run
ended; with ``--entry`` instead the 0.5-s means of the lower plate strand's tension
(the joint forces along the strand, :func:`chainfountain.sim.fastbody.pivot_impulse`, of
plate links 3-8 before the roller, every pymunk step, scaled by ``lambda v^2``) against the
loss-free law ``1/4 + Tbar_lc/2 + k R``. (The joint forces' sizes, pymunk's ``impulse``,
read high there: they ring at the laying rate; ``research/fold_entry_step.py``.)

Usage::

    python -m research.gripped_fold --seconds 60 --dt-factor 1 0.5 \\
        --set carts[0].mass=0.019 carts[1].mass=0.002 apparatus.end_tension=0.2
    python -m research.gripped_fold --entry --seconds 2 --dt-factor 1 0.5 \\
        --set carts[0].mass=0.019 carts[1].mass=0.002 apparatus.plate_links=0
    python -m research.gripped_fold --entry --contact --level apparatus_special \\
        --set apparatus.fold_clearance=0.002 carts[1].mass=0.044 --seconds 2

One core: about 1.5 s of wall time per simulated second at 0.5 ms, twice that at
0.25 ms. Measured (docs/apparatus.md, "The gripped folding roller").
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from chainfountain.errors import RunEnded
from chainfountain.level import io
from chainfountain.level.library import shipped_dir
from chainfountain.sim import Simulation
from chainfountain.sim.fastbody import pivot_impulse
from chainfountain.study.changes import laid_on_path, with_changes

LEVELS = shipped_dir()
GRIPPED = {"apparatus.fold_roller": "gripped", "apparatus.fold_roller_radius": 0.1}


def _value(text: str) -> object:
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def build(level: str, changes: dict, dt_factor: float, contact: bool) -> Simulation:
    lvl = io.load(LEVELS / f"{level}.toml")
    ch = dict(changes) if contact else {**GRIPPED, **changes}
    if dt_factor != 1.0:
        ch["solver.dt"] = lvl.sim.solver.dt * dt_factor
    return Simulation(with_changes(laid_on_path(lvl), ch).sim)


def hold(sim: Simulation, seconds: float) -> tuple[list[float], str]:
    """1-s means of the chain speed, and how the run ended."""
    app, out = sim.apparatus, []
    try:
        while sim.time < seconds - 1e-9:
            v = []
            for _ in range(10):
                sim.advance(0.1)
                v.append(app.strand_speed)
            out.append(float(np.mean(v)))
    except RunEnded as exc:
        return out, f"ended at {sim.time:.2f} s: {getattr(exc, 'plain', str(exc))}"
    return out, f"held {seconds:g} s"


def entry(sim: Simulation, seconds: float) -> list[tuple[float, float, float, float]]:
    """0.5-s means: time, chain speed, the plate strand's tension and the loss-free law
    (both scaled by ``lambda v^2``)."""
    app = sim.apparatus
    lam = sim.chain.cfg.linear_density
    R = app.R_lo if app.gripped else 0.0
    step, buf, out = sim.space.step, [], []

    def timed(h: float) -> None:
        step(h)
        held = list(app.fold_held[-1])[3:8]
        buf.append((np.mean([pivot_impulse(lk.up_joint)[0] / h for lk, _ in held
                             if lk.up_joint is not None]), app.strand_speed))

    sim.space.step = timed  # type: ignore[method-assign]
    while sim.time < seconds - 1e-9:
        buf.clear()
        sim.advance(0.5)
        a = np.array(buf)
        v = float(a[:, 1].mean())
        law = 0.25 + 0.5 * app.lower.force / (lam * v * v) + sim.g * R / v**2
        out.append((sim.time, v, float(a[:, 0].mean()) / (lam * v * v), law))
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="apparatus_fold")
    ap.add_argument("--seconds", type=float, default=20.0)
    ap.add_argument("--dt-factor", type=float, nargs="+", default=[1.0, 0.5],
                    help="solver.dt times these (the pymunk step with it)")
    ap.add_argument("--set", nargs="*", default=[], metavar="PATH=VALUE")
    ap.add_argument("--entry", action="store_true", help="the plate strand's tension")
    ap.add_argument("--contact", action="store_true", help="keep the contact roller")
    a = ap.parse_args(argv)
    changes = {}
    for item in a.set:
        key, _, val = item.partition("=")
        changes[key] = _value(val)
    for f in a.dt_factor:
        sim = build(a.level, changes, f, a.contact)
        h = sim.h * 1e3
        t0 = time.perf_counter()
        if a.entry:
            for t, v, T, law in entry(sim, a.seconds):
                print(f"h {h:g} ms  t {t:4.1f} s  v {v:.3f} m/s  strand {T:.3f}  law {law:.3f}")
        else:
            speeds, end = hold(sim, a.seconds)
            print(f"h {h:g} ms: {end}; 1-s mean speeds " + " ".join(f"{v:.3f}" for v in speeds)
                  + f" ({time.perf_counter() - t0:.0f} s wall)", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
