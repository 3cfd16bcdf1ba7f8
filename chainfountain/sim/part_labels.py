"""Names of the machine's parts in the paper's words, and where they are: what the window
writes beside the pulley apparatus (``kind = "apparatus"``) so that a class can follow
the paper's figure ("pulley_experiment"). World coordinates (m); no pixels here."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np


class Simulation(Protocol):
    """What the labels read of a :class:`~chainfountain.sim.world.Simulation` (which calls
    :func:`part_labels`; a protocol, so that this module does not import it)."""

    apparatus: Any
    config: Any

    def roller_geometry(self) -> list[tuple[float, float, float, float]]: ...

    def cart_geometry(self) -> list[np.ndarray]: ...

SIDES = ("above", "below", "left", "right")


@dataclass(frozen=True)
class PartLabel:
    """A part's name at a point of it (m); ``side``: where the text goes, one of
    :data:`SIDES`; ``tier``: how many rows further out."""

    text: str
    x: float
    y: float
    side: str = "above"
    tier: int = 0
    """Rows of text further out on ``side`` (two labels that would overlap)."""


def _grams(kg: float) -> str:
    return f"{kg * 1e3:.3g} g"


def part_labels(sim: Simulation) -> list[PartLabel]:
    """The apparatus's parts, named as the paper names them (a beaker's pot, pile and
    pick-up; empty for other kinds): the rollers, the carts with their masses, the tables,
    the guides and the end."""
    beaker = getattr(sim, "beaker", None)
    if beaker is not None:
        return beaker_labels(beaker)
    app = sim.apparatus
    if app is None:
        return []
    cfg = sim.config
    a = cfg.apparatus
    out: list[PartLabel] = []
    rollers = sim.roller_geometry()
    x, y, r, _ = rollers[0]
    out.append(PartLabel("pick-up roller", x, y + r, "above"))
    tab = app.table_up
    out.append(PartLabel("upper table (beaker)",
                         max(float(tab.a.x), x - 0.3), float(tab.a.y), "below"))
    out.append(PartLabel(f"guide up xi2*H = {a.xi2 * app.H:.2f} m",
                         app.x_plate_up_end, app.y_up, "below"))
    units = [u for u in (app.upper, app.lower) if u is not None]
    names = ("upper cart", "lower cart")
    carts = sim.cart_geometry()
    with_cart = [i for i, u in enumerate(units) if u.cart is not None]
    cart_y: dict[int, float] = {}
    for i, verts in zip(with_cart, carts, strict=False):
        cx, cy = np.asarray(verts).mean(axis=0)
        cart_y[i] = float(cy)
        out.append(PartLabel(f"{names[i]} {_grams(units[i].cart.mass)}",
                             float(cx), float(cy), "below", tier=1))
    starter = ""
    if app.up_guide and getattr(app, "fading", False):
        starter = "starter motor: letting go"
    elif app.up_guide and getattr(app, "starting", False):
        starter = ("starter motor: threads the chain round the folding roller, then lets go"
                   if a.variant == "fold" else
                   "starter motor: runs the chain up, lets go once it has landed")
    if starter:
        (ax, ay), (bx, by) = app.up_guide[-1].a, app.up_guide[-1].b
        out.append(PartLabel(starter, 0.5 * (ax + bx), 0.5 * (ay + by), "left"))
    ex, ey = app.end
    if a.variant == "fold":
        follows = ""
        if getattr(app, "end_follow", 0.0):  # it rides a slide under the landing
            follows = f", follows the landing ({100 * app.end_shift:+.0f} cm)"
        out.append(PartLabel(f"end guide up xi3*H = {a.xi3 * app.H:.2f} m{follows}",
                             ex, ey, "below"))
        if len(rollers) > 1:
            x, y, r, _ = rollers[1]
            out.append(PartLabel("folding roller", x, y + r, "above"))
            tab = app.table_lo
            y_tab = float(tab.a.y)
            # the lower cart's label sits a row under the cart, right of the roller, where
            # the table's name goes too; a cart riding just above the table (a large
            # folding roller) would put both on one row, so then the table's name goes left
            crowded = -0.01 < cart_y.get(1, math.inf) - y_tab < 0.1
            out.append(PartLabel("lower table (bottom)",
                                 x - 0.3 if crowded else min(float(tab.b.x), x + 0.3),
                                 y_tab, "below"))
    elif a.variant == "open":
        out.append(PartLabel("lower plate: the chain slides away", ex, ey, "below"))
    return out


def beaker_labels(beaker: Any) -> list[PartLabel]:
    """A beaker level's parts (:class:`~chainfountain.sim.beaker.Beaker`): the pot, its
    rim, the pile with how it is kept full, and where the chain is picked up."""
    (x0, x1), bottom = beaker.x_in, -float(beaker.cfg.pot_depth)
    plate_y = float(beaker.plate_segment()[0, 1])
    px, py = beaker.pickup
    return [PartLabel("pot", x0, 0.5 * bottom, "left"),
            PartLabel("rim", x1, 0.0, "right"),
            PartLabel("pile (topped up from below)", 0.5 * (x0 + x1), plate_y, "below"),
            PartLabel("pick-up", px, py, "left", tier=0)]
