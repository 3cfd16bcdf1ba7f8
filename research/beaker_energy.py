"""The beaker's energy: what the floor takes against the weight's work from the pick-up.

    .venv/bin/python -m research.beaker_energy [--dt 0.00025 0.0000625] [--form 8] [--seconds 6]

Each run forms the fountain from rest for ``--form`` s, then for ``--seconds`` s tallies
the kinetic energy (translation and rotation) of every link the floor takes, against the
work the weight did on them from the pick-up (its mean height over the window) down to the
floor. A ratio below 1 is energy lost on the way (the pick-up, the pile's collisions, the
swaying strand); above 1 would be energy the model makes. Also printed: the links' mean
speed at the floor against the chain's arc length the floor counts per second. About 15 s
of wall time at the level's step, a minute at a quarter of it.
"""

from __future__ import annotations

import argparse

import numpy as np

from chainfountain.level import io, library
from chainfountain.sim.world import Simulation
from chainfountain.study import with_changes


def tally(level: str, dt: float, form: float, seconds: float) -> str:
    lv = with_changes(io.load(library.resolve(level)), {"solver.dt": dt})
    sim = Simulation(lv.sim)
    beaker, chain = sim.beaker, sim.chain
    taken: list[tuple[float, float]] = []
    pop = chain.pop_front

    def pop_and_tally():  # the floor takes chain.links[0]: its energy first
        body = chain.links[0].body
        v2 = body.velocity.x ** 2 + body.velocity.y ** 2
        taken.append((0.5 * chain.mass * v2, 0.5 * chain.moment * body.angular_velocity ** 2))
        return pop()

    chain.pop_front = pop_and_tally
    sim.advance(form)
    n0, t0, heights = len(taken), sim.time, []
    while sim.time < t0 + seconds - 1e-9:
        sim.advance(0.05)
        heights.append(beaker.pickup[1])
    e = np.array(taken[n0:])
    n, T = len(e), sim.time - t0
    work = n * chain.mass * sim.g * (float(np.mean(heights)) - beaker.floor_y)
    ke = float(e.sum())
    v_links = float(np.sqrt(2.0 * e[:, 0].mean() / chain.mass))
    return (f"dt {dt * 1e6:.1f} us: {n} links taken in {T:.1f} s, {n * chain.L / T:.3f} m/s of "
            f"chain; their energy {ke:.3f} J ({float(e[:, 1].sum()):.4f} J turning) against "
            f"the weight's work {work:.3f} J: ratio {ke / work:.3f}; links at the floor "
            f"{v_links:.3f} m/s")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="beaker")
    ap.add_argument("--dt", type=float, nargs="+", default=[2.5e-4, 6.25e-5])
    ap.add_argument("--form", type=float, default=8.0)
    ap.add_argument("--seconds", type=float, default=6.0)
    a = ap.parse_args()
    for dt in a.dt:
        print(tally(a.level, dt, a.form, a.seconds), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
