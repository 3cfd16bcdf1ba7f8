"""What a fountain costs the window: the fountains it cannot show at real time.

Level files and ``chainfountain run`` accept any fountain the schema allows (a 30 m/s
feed flies 28 m up with thousands of links); the window keeps a fed level within what
one core simulates at real time by the error model's cost estimate
(:mod:`chainfountain.sim.accuracy`: wall seconds per simulated second
``n (C_LINK + C_ITER iterations) / dt``), so the scene stays interactive: a change that
would cost more than :func:`limit` is refused, a feed speed is set to the fastest within
it, and the message says why.
"""

from __future__ import annotations

import copy
import math

from chainfountain.sim import accuracy
from chainfountain.sim.config import SimConfig
from chainfountain.sim.kinds import kind_of
from chainfountain.sim.reference import LaunchReference

WINDOW_COST = 0.5
"""Most wall seconds per simulated second (one core, the error model's estimate) a fed
level's physics may cost in the window: half of real time, the other half left for
drawing and the readout (at 1.0, classroom at 12.4 m/s ran at 0.46x real time, 29 fps,
under Xvfb while its fountain formed)."""


BEAKER_LINK_STEP = 1.6e-6
"""Wall seconds per link and pymunk step of a beaker (self-colliding links, 6 iterations:
the shipped ``beaker``, 158 links at 256 us per 250-us step; ``benchmarks/bench_beaker.py``
times it)."""


def beaker_links(sim: SimConfig) -> int:
    """Links a beaker level keeps in the solver: the drop and a rise of about a third of it,
    over the rim, and the pile's rows."""
    from chainfountain.sim.beaker import row_geometry

    b, L = sim.beaker, sim.chain.link_length
    m = row_geometry(b, L, sim.chain.link_radius)[0]
    return int((1.35 * b.drop + b.pile_depth + 0.5 * b.pot_width) / L) + b.pile_rows * (m + 1)


APPARATUS_LINK_STEP = 1.9e-6
"""Wall seconds per link and pymunk step of an apparatus (the machine's bookkeeping makes
it nearly independent of the iterations: ``apparatus_special`` 1.8e-6 with about 200
links at 15 iterations, ``apparatus_floor`` 1.9e-6 with about 125 at 10, both with the
bookkeeping in every pymunk step; ``benchmarks/bench_apparatus.py`` times them). With
``solver.substeps`` above 1 the bookkeeping runs less often and this overestimates."""


def apparatus_links(sim: SimConfig) -> int | None:
    """Links an apparatus level keeps in the solver, by its parts: the fountain predicted at
    its start speed, the upper guide, the resting chain ahead of the pick-up and its wrap,
    the upper plate strand (the treadmill's, or the table's length), and with a fold the
    end guide, the lower wrap, plate strand and resting chain (``None`` when no fountain
    leaves the start at that speed)."""
    from chainfountain.theory import Fountain

    a, L = sim.apparatus, sim.chain.link_length
    d = a.floor_depth if a.variant == "floor" else 0.0
    try:
        f = Fountain.from_launch(v=a.speed, alpha0=a.launch_angle, H=a.drop,
                                 TE_bar=a.end_tension + sim.gravity * d / a.speed**2,
                                 g=sim.gravity)
        flight = f.length
    except ValueError:
        return None
    wrap = math.pi * (a.roller_radius + sim.chain.link_radius) / L
    wrap_lo = math.pi * ((a.fold_roller_radius or a.roller_radius) + sim.chain.link_radius) / L
    plate = a.plate_links or (0.5 * a.speed * a.duration + 0.15) / L
    n = flight / L + (a.xi2 * a.drop + 0.4) / L + (a.pickup_rest_links or a.rest_links)
    n += wrap + plate
    if a.variant == "fold":
        n += (a.xi3 * a.drop + 0.4) / L + wrap_lo + a.plate_links + a.rest_links
    return int(n)


def _apparatus_cost(sim: SimConfig) -> tuple[int, float] | None:
    n = apparatus_links(sim)
    if n is None:
        return None
    return n, n * APPARATUS_LINK_STEP * sim.solver.substeps / sim.solver.dt


def _beaker_cost(sim: SimConfig) -> tuple[int, float] | None:
    n = beaker_links(sim)
    s = sim.solver
    return n, n * BEAKER_LINK_STEP * (s.iterations / 6.0) ** 0.5 * s.substeps / s.dt


def _fed_cost(sim: SimConfig) -> tuple[int, float] | None:
    try:
        ref = LaunchReference.of_level(sim)
    except ValueError:
        return None
    s = sim.solver
    n = accuracy.links_in_flight(ref, sim.chain.link_length)
    return n, accuracy.wall_cost(n, s.dt / s.substeps, s.iterations)


COSTS = {"feed": _fed_cost, "ideal": _fed_cost, "apparatus": _apparatus_cost,
         "beaker": _beaker_cost}
"""Each kind's cost estimate (links, wall seconds per simulated second)."""

WHAT_COSTS = {"beaker": "the beaker would keep {n} links in flight",
              "apparatus": "the machine would keep {n} links moving"}
"""What makes a level of each kind slow (default: the links of a fountain in flight)."""


def cost(sim: SimConfig) -> tuple[int, float] | None:
    """Links in flight and estimated wall seconds per simulated second of a fed level, at
    its feed speed or at the speed its machine selects, of a beaker, or of an apparatus
    (links in the solver; ``None`` for other levels or a feed without a fountain)."""
    estimate = COSTS.get(kind_of(sim).name)
    return estimate(sim) if estimate is not None else None


ORIGIN_FACTOR = 1.5
"""A level may cost this much more than as loaded (a level shipped slower, like
``paper_tall`` at 0.94 s per simulated second or fountain D at 20, still has room)."""


def limit(origin: SimConfig) -> float:
    """The most wall seconds per simulated second the window allows for changes of the
    level ``origin`` (as loaded): :data:`WINDOW_COST`, or :data:`ORIGIN_FACTOR` times the
    level's own cost when that is more."""
    c = cost(origin)
    return max(WINDOW_COST, ORIGIN_FACTOR * c[1]) if c is not None else WINDOW_COST


def over_budget(sim: SimConfig, origin: SimConfig) -> str | None:
    """Why the window will not run ``sim``, a change of the level ``origin`` (``None`` when
    it will): its cost exceeds :func:`limit`."""
    c = cost(sim)
    if c is None or c[1] <= limit(origin):
        return None
    n, wall = c
    what = WHAT_COSTS.get(kind_of(sim).name,
                          "the fountain would put {n} links in flight").format(n=n)
    return (f"{what} and run at about {1.0 / wall:.2g}x "
            "real time, too slow for the window (level files and `chainfountain run` "
            "accept it)")


def fastest_feed(sim: SimConfig, origin: SimConfig, v_hi: float) -> float | None:
    """The largest feed speed between ``sim``'s and ``v_hi`` that the window runs
    (bisection on the cost; ``None`` when not even ``sim``'s own speed is within it)."""
    trial = copy.deepcopy(sim)

    def ok(v: float) -> bool:
        trial.feed.speed = v
        return over_budget(trial, origin) is None

    lo = sim.feed.speed
    if not ok(lo):
        return None
    if ok(v_hi):
        return v_hi
    hi = v_hi
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return math.floor(lo * 100.0) / 100.0
