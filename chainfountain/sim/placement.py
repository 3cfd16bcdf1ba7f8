"""Where a running fountain's parts are, for the pictures (the window's scene, a headless
run's ``snapshot.png``): the launch, the floor, the walls, the pot, the rollers and the
open arrangement's plate, read from the model's bodies. Nothing here steps or changes the
simulation's physics."""

from __future__ import annotations

from typing import Any

import numpy as np


def launch(sim: Any) -> tuple[tuple[float, float], tuple[float, float]]:
    """Launch point and unit launch direction."""
    return (0.0, 0.0), sim.ends.u


def floor(sim: Any) -> tuple[float, float, float, str]:
    """``(y, x0, x1, mode)`` of the floor; for an absorbing floor x0/x1 span the scene.

    Apparatus: the floor of the ``floor`` variant, else the fountain end height
    with mode ``"none"``."""
    app = sim.apparatus
    if app is not None:
        if app.end_mode == "absorbing":
            return app.floor_y, app.floor_span[0], app.floor_span[1], "absorbing"
        if app.floor is not None:
            a, b = app.floor.a, app.floor.b
            return -app.H, float(a.x), float(b.x), "solid"
        return -app.H, app.end[0] - 0.1, app.end[0] + 0.1, "none"
    if sim.beaker is not None:
        x0 = sim.beaker.x_in[0] - 0.1
        return sim.beaker.floor_y, x0, 0.5 + 0.5 * sim.drop, "absorbing"
    f = sim.config.feed
    if sim.floor is not None:
        return sim.floor.y, sim.floor.x0, sim.floor.x1, "solid"
    span = 0.5 * f.floor_width
    return -f.drop, -span, span, "absorbing"


def slide(sim: Any) -> tuple[np.ndarray, float] | None:
    """The open arrangement with ideal rollers (``feed.drive = "ideal_open"``): the
    landed chain's path through the turn and along the plate (``(n, 2)``, m) and the
    length that has slid onto it (m); ``None`` for any other level. The path starts
    at the chain's end once it has landed, else where the paper's fountain lands."""
    tail = sim.slide_away
    if tail is None:
        return None
    y = sim.ends.floor_y
    if sim.ends.absorbed > 0 and sim.chain.links:
        x = float(sim.chain.links[0].body.position.x)
    elif sim.reference is not None:
        x = float(sim.reference.landing_x)
    else:
        return None
    return tail.path(x, y), tail.slid


def walls(sim: Any) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    """Static walls, plates, tables and floor of an apparatus as segments ``((x0, y0),
    (x1, y1))`` (empty for a feed level)."""
    app = sim.apparatus
    if app is None:
        return []
    app.sync_plates()
    app.sync_end_walls()
    shapes = list(app.walls) + [app.plate_up, app.table_up]
    for extra in (app.plate_lo, getattr(app, "table_lo", None), app.floor):
        if extra is not None:
            shapes.append(extra)
    return [((float(sh.a.x), float(sh.a.y)), (float(sh.b.x), float(sh.b.y)))
            for sh in shapes]


def vessel(sim: Any) -> tuple[np.ndarray, np.ndarray] | None:
    """A beaker level's pot, as the polyline of its walls' inner faces (left rim, bottom,
    right rim), and the plate under the pile as a segment ``(2, 2)``; ``None`` for
    other kinds."""
    b = sim.beaker
    if b is None:
        return None
    return b.pot_outline(), b.plate_segment()


def rollers(sim: Any) -> list[tuple[float, float, float, float]]:
    """``(x, y, radius, angle)`` of every roller (apparatus: pick-up, then folding)."""
    app = sim.apparatus
    if app is not None:
        return [(u.roller.position.x, u.roller.position.y, u.radius, u.roller.angle)
                for u in (app.upper, app.lower) if u is not None]
    return [(r.body.position.x, r.body.position.y, r.cfg.radius, r.body.angle)
            for r in sim.rollers]
