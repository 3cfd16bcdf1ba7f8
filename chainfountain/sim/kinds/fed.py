"""What a fed fountain (a motor's feed or an ideal machine) must satisfy, whatever drives it."""

from __future__ import annotations

import math

from chainfountain.errors import fail
from chainfountain.sim.config import FeedConfig, InitialConfig, SimConfig
from chainfountain.sim.kinds.sizing import (
    check_blocks_in_scene,
    check_size,
    fastest_fitting,
    fountain_or_fail,
)

IDEAL_DRIVES = ("ideal_floor", "ideal_fold", "ideal_open")
"""The ideal machines' drives (the paper's laws move the chain)."""

DRIVE_FIELDS = {"xi2": IDEAL_DRIVES, "cart_force": IDEAL_DRIVES, "machine_mass": IDEAL_DRIVES,
                "xi3": ("ideal_fold",), "lower_cart_force": ("ideal_fold",),
                "bearing_drag": ("ideal_fold",), "turn_drop": ("ideal_open",),
                "starter": IDEAL_DRIVES}
"""Feed fields only the ideal machines use, with the drives that use them."""


def check_drive_fields(sim: SimConfig, where: str) -> None:
    """Feed fields only the ideal machines use (:data:`DRIVE_FIELDS`) are at their defaults
    unless ``feed.drive`` uses them."""
    feed, defaults = sim.feed, FeedConfig()
    for name, drives in DRIVE_FIELDS.items():
        if feed.drive not in drives and getattr(feed, name) != getattr(defaults, name):
            fail(where, f"feed.{name}",
                 f"{getattr(feed, name)!r} has no effect with feed.drive = {feed.drive!r}; "
                 f"allowed: {getattr(defaults, name)!r}, or feed.drive = "
                 + " or ".join(repr(d) for d in drives))


def check_fed(sim: SimConfig, where: str, te: float) -> None:
    """A fed fountain's cross-field checks (paper: ``Tbar_E + k*H < 1`` for the launch), its
    drive having been checked and found to start it with end tension ``te``."""
    feed = sim.feed
    g = sim.gravity
    v, H = feed.speed, feed.drop
    v_need = math.sqrt(g * H)
    if v <= v_need:
        with_te = (f" (with feed.end_tension = {te:g}: > sqrt(g*H/(1 - Tbar_E)) = "
                   f"{math.sqrt(g * H / (1.0 - te)):.4g} m/s)" if te > 0 else "")
        fail(
            where, "feed.speed",
            f"{v!r} m/s cannot make a fountain that lands {H:g} m below "
            f"the launch point (k*H >= 1); allowed: a speed > sqrt(g*H) = {v_need:.4g} m/s"
            + with_te,
        )
    if te > 0 and feed.floor == "solid":
        fail(where, "feed.end_tension",
              f"{te!r} has no effect with feed.floor = 'solid' (the pull on the chain end is "
              "the absorbing floor's; a solid floor only carries the pile); allowed: 0 with a "
              "solid floor")
    kH = g * H / v**2
    if te + kH >= 1.0:
        fail(where, "feed.end_tension",
              f"{te!r} leaves no fountain at feed.speed = {v:g} m/s and feed.drop = {H:g} m "
              f"(Tbar_E + k*H = {te + kH:.4g}, k = g/v^2; the paper needs < 1); allowed: "
              f"Tbar_E < 1 - k*H = {1.0 - kH:.4g} at this speed and drop (this end tension "
              f"needs a speed > sqrt(g*H/(1 - Tbar_E)) = {math.sqrt(g * H / (1.0 - te)):.4g} "
              "m/s)")
    link_max = min(0.1 * H, 0.2)
    if sim.chain.link_length > 0.1 * H:
        fail(
            where, "chain.link_length",
            f"{sim.chain.link_length!r} m is too coarse for a drop of {H:g} m; "
            f"allowed: at most a tenth of feed.drop ({0.1 * H:.4g} m)",
        )
    a0 = feed.launch_angle
    f = fountain_or_fail(where, "feed.speed", v, a0, H, te, g)
    check_size(where, "feed.speed", f.length, 0.0, sim.chain.link_length, link_max, v,
                v_need, lambda length: fastest_fitting(v_need, v, a0, H, te, g, length))
    if feed.floor == "solid" and 0.5 * feed.floor_width <= f.l:
        fail(where, "feed.floor_width",
              f"{feed.floor_width!r} m reaches {0.5 * feed.floor_width:g} m from the launch "
              f"point, short of where the fountain lands ({f.l:.4g} m), so the chain would "
              f"fall past the solid floor's end; allowed: a width > 2*l = {2.0 * f.l:.4g} m "
              "(the floor is centred on the launch point)")
    check_blocks_in_scene(sim, where)
    init, default_init = sim.initial, InitialConfig()
    if init.mode == "catenary" and init.stub_length != default_init.stub_length:
        fail(where, "initial.stub_length",
              f"{init.stub_length!r} m has no effect with initial.mode = 'catenary' (the chain "
              f"starts on the predicted fountain); allowed: {default_init.stub_length!r}, or "
              "initial.mode = 'stub'")
