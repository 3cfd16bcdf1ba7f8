"""Cross-field checks of an ideal machine (``feed.drive`` one of the ideal drives): the
paper's laws must select (or keep) a speed that makes a fountain."""

from __future__ import annotations

import math

from chainfountain.errors import fail
from chainfountain.sim.config import SimConfig
from chainfountain.sim.kinds.fed import check_drive_fields


def check_drive(sim: SimConfig, where: str) -> float:
    """The ideal machines' settings: used only by them, and making a fountain. Returns
    the end tension ``Tbar_E`` the level's fountain starts with."""
    feed = sim.feed
    check_drive_fields(sim, where)
    if sim.initial.mode != "catenary" and feed.starter == 0.0:
        fail(where, "initial.mode",
              f"{sim.initial.mode!r} with feed.drive = {feed.drive!r}: the machine is driven by "
              "the fall of its fountain, so from a stub it stops before the chain lands; "
              "allowed: 'catenary' (the machine starts with its fountain), or a starter "
              "(feed.starter > 0)")
    if sim.initial.mode == "catenary" and feed.starter != 0.0:
        fail(where, "feed.starter",
              f"{feed.starter!r} s has no effect with initial.mode = 'catenary' (the machine "
              "starts with its fountain); allowed: 0, or initial.mode = 'stub'")
    if feed.floor != "absorbing" or feed.end_tension != 0.0:
        field = "feed.floor" if feed.floor != "absorbing" else "feed.end_tension"
        why = {"ideal_floor": "the paper's real floor takes the chain without pull",
               "ideal_open": "the turn onto the plate sets the pull (feed.turn_drop)"}.get(
                   feed.drive, "the machine's lower half sets the pull")
        fail(where, field,
              f"{getattr(feed, field.split('.')[1])!r} with feed.drive = {feed.drive!r} ({why}); "
              "allowed: feed.floor = 'absorbing' with feed.end_tension = 0")
    _check_ideal_table(sim, where)
    if feed.drive == "ideal_floor":
        _check_ideal_floor(sim, where)
        return 0.0
    if feed.drive == "ideal_open":
        return _check_ideal_open(sim, where)
    return _check_ideal_fold(sim, where)


def _check_ideal_floor(sim: SimConfig, where: str) -> None:
    """The idealized beaker with a real floor must select a speed fast enough for a fountain."""
    from chainfountain.theory.apparatus import ideal_floor_speed

    feed = sim.feed
    lam, g, H = sim.chain.linear_density, sim.gravity, feed.drop
    share = feed.xi2 + feed.cart_force / (lam * g * H)
    if share >= 0.5:
        v = ideal_floor_speed(H, feed.xi2, feed.cart_force, lam, g)
        shown = f"{v:.4g} m/s" if math.isfinite(v) else "no speed"
        fail(where, "feed.xi2",
              f"{feed.xi2!r} with feed.cart_force = {feed.cart_force:g} N selects {shown}, "
              f"too slow for a fountain over feed.drop = {H:g} m (xi2 + F_uc/(lambda*g*H) = "
              f"{share:.4g}; k*H < 1 needs < 0.5); allowed: xi2 < "
              f"{max(0.0, 0.5 - feed.cart_force / (lam * g * H)):.4g} with this cart")


TABLE_MARGIN = 1.0
"""Chain (m) an ideal machine's finite table must hold beyond what the level starts with
(the stub or the fountain, and the guide), so that the machine runs at all."""


def _check_ideal_table(sim: SimConfig, where: str) -> None:
    """An ideal machine's finite table (``feed.chain_length``) must hold more than the chain
    the level starts with: the machine picks its chain up from it."""
    feed = sim.feed
    if feed.chain_length == 0.0:
        return
    start = sim.initial.stub_length if sim.initial.mode == "stub" else 0.0
    if sim.initial.mode == "catenary":
        from chainfountain.sim.reference import LaunchReference

        try:
            start = LaunchReference.of_level(sim).arc_length
        except ValueError:
            return  # no fountain: the drive's own check says why
    need = start + feed.guide_links * sim.chain.link_length + TABLE_MARGIN
    if feed.chain_length < need:
        fail(where, "feed.chain_length",
              f"{feed.chain_length!r} m is the upper table of feed.drive = {feed.drive!r} and "
              f"holds less than the chain the level starts with plus a metre ({need:.3g} m); "
              f"allowed: 0 (an endless table) or at least {need:.3g} m")


def _check_ideal_open(sim: SimConfig, where: str) -> float:
    """The open arrangement with ideal rollers must select a speed fast enough for a
    fountain: ``Tbar_0 = k (H + d) < 1``. Returns the ``Tbar_E = k d`` it selects."""
    from chainfountain.theory.apparatus import ideal_open_speed, ideal_open_TE_bar

    feed = sim.feed
    lam, g, H, d = sim.chain.linear_density, sim.gravity, feed.drop, feed.turn_drop
    v = ideal_open_speed(H, feed.xi2, feed.cart_force, d, lam, g)
    if not (math.isfinite(v) and v * v > g * (H + d)):
        shown = f"{v:.4g} m/s" if math.isfinite(v) else "no speed"
        why = (f"selects {shown}, too slow for a fountain over feed.drop = {H:g} m (Tbar_0 = "
               "k*(H + turn_drop) must be < 1)")
        room = 0.5 * (H + d) - feed.cart_force / (lam * g)
        if room <= 0.0:  # no offset helps: the cart alone holds the chain too hard
            limit = lam * g * (0.5 * (H + d) - feed.xi2 * H)
            fail(where, "feed.cart_force",
                  f"{feed.cart_force!r} N with feed.xi2 = {feed.xi2:g} and feed.turn_drop = "
                  f"{d:g} m {why}; allowed: feed.cart_force < {max(0.0, limit):.4g} N")
        fail(where, "feed.xi2",
              f"{feed.xi2!r} with feed.cart_force = {feed.cart_force:g} N and feed.turn_drop "
              f"= {d:g} m {why}; allowed: xi2 < {room / H:.4g} with this cart and turn")
    return ideal_open_TE_bar(v, d, g)


BALANCE_TOLERANCE = 1e-6
"""Largest imbalance of the ideal full machine's carts a level may have, in units of
``lambda g H``: it speeds the chain up by about ``1e-6 lambda g H/mass``, far below the
simulation's own drift (docs/apparatus.md, "The ideal machines")."""


IDEAL_MIN_KQ = 0.125
"""Smallest ``k/q`` an ideal full machine may run at. Measured (``research/ideal_machine_holds.py``,
H = 1 m, 60 deg): machines at ``k/q`` 0.13-0.16 held 600 s within 0.5 % of the laws' speed;
the special case at 5 m/s (``k/q`` 0.124) sank 4.5 % in 80 s and kept sinking, at 0.09 it
stopped within 35 s: near critical the simulated chain leaves a back force of order
``0.01 lambda v^2`` that grows as the machine slows."""


def _check_ideal_fold(sim: SimConfig, where: str) -> float:
    """The ideal full machine must run steady: loss-free, its carts balanced (it is neutral
    in the speed, so an unbalanced one never settles); with bearing drag, selecting a speed.
    The speed it keeps (the start speed, or the selected one) must make a fountain with a
    taut lower strand. Returns the ``Tbar_E`` the level's fountain starts with."""
    from chainfountain.theory.apparatus import (
        balanced_cart_force,
        ideal_fold_speed,
        ideal_fold_T0_bar,
        ideal_fold_TE_bar,
    )

    feed = sim.feed
    lam, g, H, c = sim.chain.linear_density, sim.gravity, feed.drop, feed.bearing_drag
    F_bal = balanced_cart_force(feed.lower_cart_force, feed.xi2, feed.xi3, lam, H, g)
    if c == 0.0:
        if F_bal < 0.0:
            fail(where, "feed.xi3",
                  f"{feed.xi3!r} with feed.xi2 = {feed.xi2:g} and feed.lower_cart_force = "
                  f"{feed.lower_cart_force:g} N needs an upper cart pushing the chain out "
                  f"({F_bal:.4g} N; carts only hold back); allowed: xi2 + xi3 <= 1 + "
                  "F_lc/(lambda*g*H)")
        if abs(feed.cart_force - F_bal) > BALANCE_TOLERANCE * lam * g * H:
            fail(where, "feed.cart_force",
                  f"{feed.cart_force!r} N does not balance the lower half of a loss-free "
                  "machine (the chain would speed up or slow down at a constant rate without "
                  f"end); allowed: {F_bal:.6g} N = F_lc + lambda*g*H*(1 - xi2 - xi3), or "
                  "feed.bearing_drag > 0")
        v, which = feed.speed, "feed.speed"
    else:
        v = ideal_fold_speed(feed.cart_force, feed.lower_cart_force, feed.xi2, feed.xi3, c,
                             lam, H, g)
        if not math.isfinite(v):
            fail(where, "feed.cart_force",
                  f"{feed.cart_force!r} N holds the chain back at least as hard as the lower "
                  f"half and the fall pull it on ({F_bal:.4g} N), so with bearing drag the "
                  f"machine selects no speed; allowed: feed.cart_force < {F_bal:.4g} N")
        which = "feed.cart_force"
    T0 = ideal_fold_T0_bar(v, feed.xi2, feed.cart_force, lam, H, g, c)
    TE = ideal_fold_TE_bar(v, feed.xi3, feed.lower_cart_force, lam, H, g, c)
    shown = f"{v:.4g} m/s" if c == 0.0 else f"the selected {v:.4g} m/s"
    if T0 >= 1.0:
        allowed = ("a lighter upper cart (a faster chain)" if c > 0.0 else
                   "a start speed > sqrt(2*(F_uc/lambda + xi2*g*H)) = "
                   f"{math.sqrt(2.0 * (feed.cart_force / lam + feed.xi2 * g * H)):.4g} m/s")
        fail(where, which,
              f"{getattr(feed, which.split('.')[1])!r} gives no fountain: at {shown} the "
              f"machine's Tbar_0 = 1/2 + Tbar_uc + xi2*k*H = {T0:.4g} (the paper needs < 1); "
              f"allowed: {allowed}")
    kq = (1.0 - T0) * math.cos(feed.launch_angle)  # k/q at the launch: q = k/(cos a0 (1-T0))
    if kq < IDEAL_MIN_KQ:
        fail(where, which,
              f"{getattr(feed, which.split('.')[1])!r} puts the machine's fountain too near "
              f"critical at {shown} (k/q = {kq:.3f}, Tbar_0 = {T0:.3f}): there the simulated "
              "chain holds the machine back by about 1 % of lambda*v^2, and it sinks; allowed: "
              f"k/q >= {IDEAL_MIN_KQ} (a faster chain: "
              + ("a lighter upper cart or a heavier lower one)" if c > 0.0 else
                 "a higher feed.speed)"))
    if c > 0.0 and TE < 0.0:
        fail(where, which,
              f"{feed.cart_force!r} N selects {v:.4g} m/s, where the lower strand goes slack "
              f"(Tbar_E = {TE:.4g}); allowed: a heavier lower cart or a lower xi3")
    return max(0.0, TE)
