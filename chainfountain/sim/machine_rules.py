"""The loss-free full machine's one rule for changes: its upper cart follows the balance.

A loss-free ideal full machine (``feed.drive = "ideal_fold"``, ``feed.bearing_drag = 0``)
is neutral in the speed: it keeps any speed while its carts balance,
``F_uc = F_lc + lambda g H (1 - xi2 - xi3)``, and speeds up or slows down for good
otherwise. So when ``xi2``, ``xi3`` or the lower cart change, the upper cart is moved to the
balance with them (the window and :meth:`~chainfountain.sim.world.Simulation.set_machine`
both apply this), and the machine keeps its speed while its fountain takes a new shape.
"""

from __future__ import annotations

from chainfountain.sim.config import SimConfig
from chainfountain.theory.apparatus import balanced_cart_force

MACHINE_FIELDS = ("feed.xi2", "feed.cart_force", "feed.xi3", "feed.lower_cart_force",
                  "feed.bearing_drag", "feed.turn_drop")
"""The ideal machines' own fields: live (:meth:`~chainfountain.sim.world.Simulation.set_machine`),
their sliders spanning only what runs (:mod:`chainfountain.app.spans`)."""

FOLLOWED = ("feed.xi2", "feed.xi3", "feed.lower_cart_force", "feed.drive",
            "feed.bearing_drag")
"""Changes after which a loss-free full machine's upper cart is moved to the balance."""


def keeps_any_speed(config: SimConfig) -> bool:
    """Whether ``config`` is a loss-free full machine: neutral in the speed, it keeps any
    speed while balanced (the paper's laws select none)."""
    f = config.feed
    return f.drive == "ideal_fold" and f.bearing_drag == 0.0  # other kinds: feed.drive 'motor'


def follow(config: SimConfig, path: str) -> float | None:
    """After ``path`` changed in ``config``: move the upper cart of a loss-free full machine
    to the balance. Returns the new ``feed.cart_force`` (N), or ``None`` when nothing
    follows (another drive, a machine with bearing drag, or another field)."""
    if not keeps_any_speed(config) or path not in FOLLOWED:
        return None
    f = config.feed
    f.cart_force = max(0.0, balanced_cart_force(f.lower_cart_force, f.xi2, f.xi3,
                                                config.chain.linear_density, f.drop,
                                                config.gravity))
    return f.cart_force
