"""Cross-field checks of a beaker level (``kind = "beaker"``): the pile fits the pot, the
chain can pile (its links collide), and nothing is set that a beaker would ignore."""

from __future__ import annotations

import dataclasses
import math

from chainfountain.errors import fail
from chainfountain.sim.beaker import ROW_GAP, WALL_RADIUS, row_geometry
from chainfountain.sim.config import InitialConfig, SimConfig

MIN_ROW_LINKS = 3
"""Fewest links a pile's row may have (a narrower pot holds no zig-zag)."""


def check_beaker(sim: SimConfig, where: str, max_links: int) -> None:
    """Refuse, in one line naming the field, a beaker that cannot be built or would not
    pile: links that do not collide, rows that do not fit the pot, a start below the
    floor, and settings a beaker ignores."""
    b, c = sim.beaker, sim.chain
    L, r = c.link_length, c.link_radius
    if not c.self_collision:
        fail(where, "chain.self_collision", "false: the links of a pile must lie on each "
              "other; allowed: true in a 'beaker' level")
    if 2.0 * r + ROW_GAP >= 0.9 * L:
        fail(where, "chain.link_radius", f"{r!r} m: rows of links this thick cannot turn "
              f"within one {L} m link; allowed: at most {(0.9 * L - ROW_GAP) / 2:.4g} m")
    m, s, _ = row_geometry(b, L, r)
    if m < MIN_ROW_LINKS:
        fail(where, "beaker.pot_width", f"{b.pot_width!r} m holds {max(m, 0)} links of "
              f"{L} m in a row; allowed: at least "
              f"{MIN_ROW_LINKS * L + math.sqrt(max(L * L - s * s, 0.0)) + 2 * r + 0.002:.4g} m")
    below = b.pile_depth + (b.pile_rows - 1) * s + r + ROW_GAP + 2.0 * WALL_RADIUS
    if below > b.pot_depth:
        fail(where, "beaker.pot_depth", f"{b.pot_depth!r} m is too shallow for "
              f"{b.pile_rows} rows of the pile {b.pile_depth} m below the rim; allowed: at "
              f"least {below:.4g} m (or fewer beaker.pile_rows)")
    if b.hang > b.drop - L:
        fail(where, "beaker.hang", f"{b.hang!r} m would start the chain's end below the "
              f"floor {b.drop} m down; allowed: at most {b.drop - L:.4g} m")
    n = (b.hang + 0.1 + b.pot_width) / L + b.pile_rows * (m + 1)
    if n > max_links:
        fail(where, "beaker.pile_rows", f"{b.pile_rows!r} rows put {n:.0f} links into the "
              f"simulation; allowed: at most {max_links} links")
    if sim.rollers or sim.carts:
        fail(where, "rollers" if sim.rollers else "carts", "have no effect in a 'beaker' "
              "level; allowed: none (rollers = [], carts = [])")
    unseeded = dataclasses.replace(sim.initial, seed=0)
    if dataclasses.asdict(unseeded) != dataclasses.asdict(InitialConfig()):
        fail(where, "initial", "a beaker lays its chain in its pot, at rest (initial.seed "
              "alone picks one of its chaotic runs); allowed: an [initial] table with seed "
              "only, or none")
