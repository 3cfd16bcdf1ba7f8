"""Checks every fountain kind shares: the fountain a launch makes, and how many links it
puts into the simulation."""

from __future__ import annotations

import math

from chainfountain.errors import fail
from chainfountain.sim.config import SimConfig

MAX_LINKS = 20_000
"""Most chain links a level may put into the simulation at its start (the chain in
flight, plus an apparatus's upper plate strand): a level beyond it would take minutes
to build and hours to run, or exhaust the machine's memory."""


def fountain_or_fail(where: str, field: str, v: float, alpha0: float, H: float,
                      TE_bar: float, g: float):
    """The paper's fountain for a launch (the checks before this one make it exist)."""
    from chainfountain.theory import Fountain

    try:
        return Fountain.from_launch(v=v, alpha0=alpha0, H=H, TE_bar=TE_bar, g=g)
    except (ValueError, ArithmeticError) as exc:
        fail(where, field, f"{v!r} m/s gives no fountain ({exc})")


def fastest_fitting(v_lo: float, v_hi: float, alpha0: float, H: float, TE_bar: float,
                     g: float, length: float, depth: float = 0.0) -> float:
    """The highest speed in ``(v_lo, v_hi)`` whose fountain has at most ``length`` m of chain
    in flight (bisection; the length in flight grows with the speed). ``depth``: an
    apparatus floor that far below the fountain end adds ``g*depth/v**2`` to ``TE_bar``."""
    from chainfountain.theory import Fountain

    lo, hi = v_lo, v_hi
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        try:
            ok = Fountain.from_launch(v=mid, alpha0=alpha0, H=H, TE_bar=TE_bar + g * depth / mid**2,
                                      g=g).length <= length
        except (ValueError, ArithmeticError):
            ok = True  # below the fountain's least speed: nothing in flight yet
        lo, hi = (mid, hi) if ok else (lo, mid)
    return lo


def check_size(where: str, speed_field: str, flight: float, extra_links: float,
                link: float, link_max: float, v: float, v_min: float, fit) -> None:
    """At most :data:`MAX_LINKS` links at the start: ``flight`` m of chain in flight plus
    ``extra_links``; names ``chain.link_length`` when longer links would do, else the speed
    (``fit(length)``: the fastest speed with at most ``length`` m in flight)."""
    n = flight / link + extra_links
    if n <= MAX_LINKS:
        return
    room = MAX_LINKS - extra_links
    link_need = flight / room if room > 0 else math.inf
    if link_need <= link_max:
        fail(where, "chain.link_length",
              f"{link!r} m puts {n:.0f} links into the simulation ({flight:.4g} m of chain in "
              f"flight); allowed: at most {MAX_LINKS} links, here a link_length >= "
              f"{link_need:.4g} m (at most {link_max:.4g} m for this drop)")
    v_fit = fit(link_max * room) if room > 0 else v_min
    fail(where, speed_field,
          f"{v!r} m/s throws {flight:.4g} m of chain into flight, {n:.0f} links even at the "
          f"longest link allowed ({link_max:.4g} m); allowed: at most {MAX_LINKS} links, here a "
          f"speed <= {v_fit:.4g} m/s (or stronger gravity, a lower launch angle)")


def check_blocks_in_scene(sim: SimConfig, where: str) -> None:
    """Rollers and carts of a feed level lie inside the scene the divergence watchdog
    allows (:func:`chainfountain.sim.kinds.limits_for`): a body beyond it would stop the
    run at once as diverged."""
    from chainfountain.sim.kinds import limits_for

    reach = limits_for(sim).radius
    for i, r in enumerate(sim.rollers):
        d = math.hypot(r.x, r.y) + r.radius
        if d >= reach:
            fail(where, f"rollers[{i}].x",
                  f"{r.x!r} m (with y = {r.y:g} m) puts the roller {d:.4g} m from the launch "
                  f"point, outside this level's scene; allowed: rollers within {reach:.4g} m "
                  "of the launch point")
    for i, c in enumerate(sim.carts):
        half = 0.5 * c.track_length + 0.5 * math.hypot(c.width, c.height)
        d = math.hypot(c.x, c.y) + half
        if d >= reach:
            fail(where, f"carts[{i}].x",
                  f"{c.x!r} m (with y = {c.y:g} m and a {c.track_length:g} m track) lets the "
                  f"cart reach {d:.4g} m from the launch point, outside this level's scene; "
                  f"allowed: carts and their tracks within {reach:.4g} m of the launch point")
