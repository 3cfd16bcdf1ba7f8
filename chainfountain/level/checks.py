"""Cross-field checks of a level: it must describe a fountain that can exist, in a scene
the simulation can hold, and every setting must have an effect (:func:`check_consistency`)."""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

from chainfountain.fields import iter_numeric_fields
from chainfountain.level.model import Level, _fail
from chainfountain.sim.config import KINDS, FeedConfig, InitialConfig, SimConfig

if TYPE_CHECKING:
    from chainfountain.sim.accuracy import Estimate

MAX_LINKS = 20_000
"""Most chain links a level may put into the simulation at its start (the chain in
flight, plus an apparatus's upper plate strand): a level beyond it would take minutes
to build and hours to run, or exhaust the machine's memory."""


def check_consistency(level: Level, where: str) -> None:
    """Cross-field checks: the configured fountain must exist, fit the simulator, and
    every setting given must have an effect in this kind of level."""
    sim = level.sim
    g = sim.gravity
    if not g > 0:
        _fail(where, "gravity", f"{g!r} is out of range; allowed: a number > 0 (m/s^2)")
    _check_other_kind(sim, where)
    if sim.kind == "apparatus":
        _check_apparatus(level, where)
    if sim.kind == "feed":
        _check_feed(level, where)
    if sim.kind == "scene":
        from chainfountain.level.scene_checks import check_scene

        check_scene(level, where, MAX_LINKS)
    if sim.kind == "beaker":
        from chainfountain.level.beaker_checks import check_beaker

        check_beaker(level, where, MAX_LINKS)
    _check_accuracy_scope(sim, where)
    _check_controls(level, where)


def _check_controls(level: Level, where: str) -> None:
    """``meta.controls`` names numeric fields this level has (each becomes a slider)."""
    other = tuple(f"{k}." for k in KINDS if k != level.sim.kind)
    known = [path for path, _, _ in iter_numeric_fields(level.sim)
             if not path.startswith(other)]
    for path in level.meta.control_paths():
        if path not in known:
            shown = ", ".join(known[:6])
            _fail(where, "meta.controls", f"{path!r} is not a number field of this level; "
                  f"allowed: its number fields, separated by commas (such as {shown})")


def _check_other_kind(sim: SimConfig, where: str) -> None:
    """The table of the other level kind is left out or at its defaults (it has no effect)."""
    defaults = SimConfig()
    for kind in KINDS:
        if kind == sim.kind:
            continue
        table, default = getattr(sim, kind), getattr(defaults, kind)
        for f in dataclasses.fields(table):
            value = getattr(table, f.name)
            if value != getattr(default, f.name):
                _fail(where, f"{kind}.{f.name}",
                      f"{value!r} has no effect in a {sim.kind!r} level (the [{kind}] table "
                      f"belongs to kind {kind!r}); allowed: {getattr(default, f.name)!r} or "
                      f"no [{kind}] table")


def _fountain_or_fail(where: str, field: str, v: float, alpha0: float, H: float,
                      TE_bar: float, g: float):
    """The paper's fountain for a launch (the checks before this one make it exist)."""
    from chainfountain.theory import Fountain

    try:
        return Fountain.from_launch(v=v, alpha0=alpha0, H=H, TE_bar=TE_bar, g=g)
    except (ValueError, ArithmeticError) as exc:
        _fail(where, field, f"{v!r} m/s gives no fountain ({exc})")


def _fastest_fitting(v_lo: float, v_hi: float, alpha0: float, H: float, TE_bar: float,
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


def _check_size(where: str, speed_field: str, flight: float, extra_links: float,
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
        _fail(where, "chain.link_length",
              f"{link!r} m puts {n:.0f} links into the simulation ({flight:.4g} m of chain in "
              f"flight); allowed: at most {MAX_LINKS} links, here a link_length >= "
              f"{link_need:.4g} m (at most {link_max:.4g} m for this drop)")
    v_fit = fit(link_max * room) if room > 0 else v_min
    _fail(where, speed_field,
          f"{v!r} m/s throws {flight:.4g} m of chain into flight, {n:.0f} links even at the "
          f"longest link allowed ({link_max:.4g} m); allowed: at most {MAX_LINKS} links, here a "
          f"speed <= {v_fit:.4g} m/s (or stronger gravity, a lower launch angle)")


def _check_blocks_in_scene(sim: SimConfig, where: str) -> None:
    """Rollers and carts of a feed level lie inside the scene the divergence watchdog
    allows (:func:`chainfountain.sim.watchdog.limits_for`): a body beyond it would stop the
    run at once as diverged."""
    from chainfountain.sim.watchdog import limits_for

    reach = limits_for(sim).radius
    for i, r in enumerate(sim.rollers):
        d = math.hypot(r.x, r.y) + r.radius
        if d >= reach:
            _fail(where, f"rollers[{i}].x",
                  f"{r.x!r} m (with y = {r.y:g} m) puts the roller {d:.4g} m from the launch "
                  f"point, outside this level's scene; allowed: rollers within {reach:.4g} m "
                  "of the launch point")
    for i, c in enumerate(sim.carts):
        half = 0.5 * c.track_length + 0.5 * math.hypot(c.width, c.height)
        d = math.hypot(c.x, c.y) + half
        if d >= reach:
            _fail(where, f"carts[{i}].x",
                  f"{c.x!r} m (with y = {c.y:g} m and a {c.track_length:g} m track) lets the "
                  f"cart reach {d:.4g} m from the launch point, outside this level's scene; "
                  f"allowed: carts and their tracks within {reach:.4g} m of the launch point")


def _check_feed(level: Level, where: str) -> None:
    """Feed cross-field checks (paper: ``Tbar_E + k*H < 1`` for the launch)."""
    sim = level.sim
    feed = sim.feed
    g = sim.gravity
    v, H = feed.speed, feed.drop
    te = _check_drive(level, where)
    v_need = math.sqrt(g * H)
    if v <= v_need:
        with_te = (f" (with feed.end_tension = {te:g}: > sqrt(g*H/(1 - Tbar_E)) = "
                   f"{math.sqrt(g * H / (1.0 - te)):.4g} m/s)" if te > 0 else "")
        _fail(
            where, "feed.speed",
            f"{v!r} m/s cannot make a fountain that lands {H:g} m below "
            f"the launch point (k*H >= 1); allowed: a speed > sqrt(g*H) = {v_need:.4g} m/s"
            + with_te,
        )
    if te > 0 and feed.floor == "solid":
        _fail(where, "feed.end_tension",
              f"{te!r} has no effect with feed.floor = 'solid' (the pull on the chain end is "
              "the absorbing floor's; a solid floor only carries the pile); allowed: 0 with a "
              "solid floor")
    kH = g * H / v**2
    if te + kH >= 1.0:
        _fail(where, "feed.end_tension",
              f"{te!r} leaves no fountain at feed.speed = {v:g} m/s and feed.drop = {H:g} m "
              f"(Tbar_E + k*H = {te + kH:.4g}, k = g/v^2; the paper needs < 1); allowed: "
              f"Tbar_E < 1 - k*H = {1.0 - kH:.4g} at this speed and drop (this end tension "
              f"needs a speed > sqrt(g*H/(1 - Tbar_E)) = {math.sqrt(g * H / (1.0 - te)):.4g} "
              "m/s)")
    link_max = min(0.1 * H, 0.2)
    if sim.chain.link_length > 0.1 * H:
        _fail(
            where, "chain.link_length",
            f"{sim.chain.link_length!r} m is too coarse for a drop of {H:g} m; "
            f"allowed: at most a tenth of feed.drop ({0.1 * H:.4g} m)",
        )
    a0 = feed.launch_angle
    f = _fountain_or_fail(where, "feed.speed", v, a0, H, te, g)
    _check_size(where, "feed.speed", f.length, 0.0, sim.chain.link_length, link_max, v,
                v_need, lambda length: _fastest_fitting(v_need, v, a0, H, te, g, length))
    if feed.floor == "solid" and 0.5 * feed.floor_width <= f.l:
        _fail(where, "feed.floor_width",
              f"{feed.floor_width!r} m reaches {0.5 * feed.floor_width:g} m from the launch "
              f"point, short of where the fountain lands ({f.l:.4g} m), so the chain would "
              f"fall past the solid floor's end; allowed: a width > 2*l = {2.0 * f.l:.4g} m "
              "(the floor is centred on the launch point)")
    _check_blocks_in_scene(sim, where)
    init, default_init = sim.initial, InitialConfig()
    if init.mode == "catenary" and init.stub_length != default_init.stub_length:
        _fail(where, "initial.stub_length",
              f"{init.stub_length!r} m has no effect with initial.mode = 'catenary' (the chain "
              f"starts on the predicted fountain); allowed: {default_init.stub_length!r}, or "
              "initial.mode = 'stub'")


def _check_apparatus_start(sim: SimConfig, where: str) -> None:
    """How an apparatus starts: laid along its path, moving (``initial`` at its defaults,
    no starter), or from rest with a starter (``initial.mode = "stub"``, the 'floor'
    variant or the gripped 'fold', with the upper joint guide)."""
    a = sim.apparatus
    default_initial = type(sim.initial)()
    from_rest = sim.initial.mode == "stub"
    for f in dataclasses.fields(sim.initial):
        value, default = getattr(sim.initial, f.name), getattr(default_initial, f.name)
        if value == default or f.name == "seed" or (
                from_rest and f.name in ("mode", "stub_length")):
            continue
        _fail(where, f"initial.{f.name}",
              f"{value!r} has no effect in an 'apparatus' level: the apparatus lays its "
              "chain along its own path, moving at apparatus.speed, or from rest with "
              "initial.mode = 'stub' (to start a perturbed run, set initial.seed above 0: "
              f"a 1e-12 nudge); allowed: {default!r}" + (", or 'stub'" if f.name == "mode" else ""))
    if not from_rest:
        if a.starter:
            _fail(where, "apparatus.starter",
                  f"{a.starter!r} s has no effect with initial.mode = 'catenary' (the chain "
                  "starts laid along its path at apparatus.speed); allowed: 0, or "
                  "initial.mode = 'stub'")
        return
    threads = a.variant == "fold" and a.plate == "groove" and a.fold_roller == "gripped"
    if a.variant not in ("floor", "fold") or a.upper_guide != "joints":
        field, value = (("apparatus.variant", a.variant) if a.variant not in ("floor", "fold")
                        else ("apparatus.upper_guide", a.upper_guide))
        _fail(where, field,
              f"{value!r} cannot start from rest (initial.mode = 'stub'): the starter runs the "
              "chain in the upper joint guide, and only the floor or the gripped fold takes "
              "in a forming fountain; allowed: variant = 'floor' or 'fold' with upper_guide "
              "= 'joints', or initial.mode = 'catenary'")
    if a.variant == "fold" and not threads:
        field, value = (("apparatus.fold_roller", a.fold_roller) if a.plate == "groove"
                        else ("apparatus.plate", a.plate))
        _fail(where, field,
              f"{value!r} cannot start from rest (initial.mode = 'stub'): the starter threads "
              "the chain's head through the end guide's joints and the gripped folding "
              "roller; allowed: fold_roller = 'gripped' with plate = 'groove', or "
              "initial.mode = 'catenary'")
    if a.variant == "fold" and sim.initial.stub_length != default_initial.stub_length:
        _fail(where, "initial.stub_length",
              f"{sim.initial.stub_length!r} m has no effect in 'fold': its head waits inside "
              "the upper guide until the starter launches it; allowed: "
              f"{default_initial.stub_length!r}")
    if a.starter <= 0.0:
        _fail(where, "apparatus.starter",
              f"{a.starter!r} s with initial.mode = 'stub': at rest the cart holds the chain "
              "and nothing falls, so the machine needs a starter; allowed: a time > 0 "
              "(seconds the starter runs on after the chain lands, e.g. 3)")


IDEAL_DRIVES = ("ideal_floor", "ideal_fold", "ideal_open")
"""The ideal machines' drives (the paper's laws move the chain)."""

DRIVE_FIELDS = {"xi2": IDEAL_DRIVES, "cart_force": IDEAL_DRIVES, "machine_mass": IDEAL_DRIVES,
                "xi3": ("ideal_fold",), "lower_cart_force": ("ideal_fold",),
                "bearing_drag": ("ideal_fold",), "turn_drop": ("ideal_open",),
                "starter": IDEAL_DRIVES}
"""Feed fields only the ideal machines use, with the drives that use them."""


def _check_drive(level: Level, where: str) -> float:
    """The ideal machines' settings: used only by them, and making a fountain. Returns
    the end tension ``Tbar_E`` the level's fountain starts with."""
    sim = level.sim
    feed, defaults = sim.feed, FeedConfig()
    for name, drives in DRIVE_FIELDS.items():
        if feed.drive not in drives and getattr(feed, name) != getattr(defaults, name):
            _fail(where, f"feed.{name}",
                  f"{getattr(feed, name)!r} has no effect with feed.drive = {feed.drive!r}; "
                  f"allowed: {getattr(defaults, name)!r}, or feed.drive = "
                  + " or ".join(repr(d) for d in drives))
    if feed.drive == "motor":
        return feed.end_tension
    if sim.initial.mode != "catenary" and feed.starter == 0.0:
        _fail(where, "initial.mode",
              f"{sim.initial.mode!r} with feed.drive = {feed.drive!r}: the machine is driven by "
              "the fall of its fountain, so from a stub it stops before the chain lands; "
              "allowed: 'catenary' (the machine starts with its fountain), or a starter "
              "(feed.starter > 0)")
    if sim.initial.mode == "catenary" and feed.starter != 0.0:
        _fail(where, "feed.starter",
              f"{feed.starter!r} s has no effect with initial.mode = 'catenary' (the machine "
              "starts with its fountain); allowed: 0, or initial.mode = 'stub'")
    if feed.floor != "absorbing" or feed.end_tension != 0.0:
        field = "feed.floor" if feed.floor != "absorbing" else "feed.end_tension"
        why = {"ideal_floor": "the paper's real floor takes the chain without pull",
               "ideal_open": "the turn onto the plate sets the pull (feed.turn_drop)"}.get(
                   feed.drive, "the machine's lower half sets the pull")
        _fail(where, field,
              f"{getattr(feed, field.split('.')[1])!r} with feed.drive = {feed.drive!r} ({why}); "
              "allowed: feed.floor = 'absorbing' with feed.end_tension = 0")
    _check_ideal_table(level, where)
    if feed.drive == "ideal_floor":
        _check_ideal_floor(level, where)
        return 0.0
    if feed.drive == "ideal_open":
        return _check_ideal_open(level, where)
    return _check_ideal_fold(level, where)


def _check_ideal_floor(level: Level, where: str) -> None:
    """The idealized beaker with a real floor must select a speed fast enough for a fountain."""
    from chainfountain.theory.apparatus import ideal_floor_speed

    sim = level.sim
    feed = sim.feed
    lam, g, H = sim.chain.linear_density, sim.gravity, feed.drop
    share = feed.xi2 + feed.cart_force / (lam * g * H)
    if share >= 0.5:
        v = ideal_floor_speed(H, feed.xi2, feed.cart_force, lam, g)
        shown = f"{v:.4g} m/s" if math.isfinite(v) else "no speed"
        _fail(where, "feed.xi2",
              f"{feed.xi2!r} with feed.cart_force = {feed.cart_force:g} N selects {shown}, "
              f"too slow for a fountain over feed.drop = {H:g} m (xi2 + F_uc/(lambda*g*H) = "
              f"{share:.4g}; k*H < 1 needs < 0.5); allowed: xi2 < "
              f"{max(0.0, 0.5 - feed.cart_force / (lam * g * H)):.4g} with this cart")


TABLE_MARGIN = 1.0
"""Chain (m) an ideal machine's finite table must hold beyond what the level starts with
(the stub or the fountain, and the guide), so that the machine runs at all."""


def _check_ideal_table(level: Level, where: str) -> None:
    """An ideal machine's finite table (``feed.chain_length``) must hold more than the chain
    the level starts with: the machine picks its chain up from it."""
    sim = level.sim
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
        _fail(where, "feed.chain_length",
              f"{feed.chain_length!r} m is the upper table of feed.drive = {feed.drive!r} and "
              f"holds less than the chain the level starts with plus a metre ({need:.3g} m); "
              f"allowed: 0 (an endless table) or at least {need:.3g} m")


def _check_ideal_open(level: Level, where: str) -> float:
    """The open arrangement with ideal rollers must select a speed fast enough for a
    fountain: ``Tbar_0 = k (H + d) < 1``. Returns the ``Tbar_E = k d`` it selects."""
    from chainfountain.theory.apparatus import ideal_open_speed, ideal_open_TE_bar

    sim = level.sim
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
            _fail(where, "feed.cart_force",
                  f"{feed.cart_force!r} N with feed.xi2 = {feed.xi2:g} and feed.turn_drop = "
                  f"{d:g} m {why}; allowed: feed.cart_force < {max(0.0, limit):.4g} N")
        _fail(where, "feed.xi2",
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


def _check_ideal_fold(level: Level, where: str) -> float:
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

    sim = level.sim
    feed = sim.feed
    lam, g, H, c = sim.chain.linear_density, sim.gravity, feed.drop, feed.bearing_drag
    F_bal = balanced_cart_force(feed.lower_cart_force, feed.xi2, feed.xi3, lam, H, g)
    if c == 0.0:
        if F_bal < 0.0:
            _fail(where, "feed.xi3",
                  f"{feed.xi3!r} with feed.xi2 = {feed.xi2:g} and feed.lower_cart_force = "
                  f"{feed.lower_cart_force:g} N needs an upper cart pushing the chain out "
                  f"({F_bal:.4g} N; carts only hold back); allowed: xi2 + xi3 <= 1 + "
                  "F_lc/(lambda*g*H)")
        if abs(feed.cart_force - F_bal) > BALANCE_TOLERANCE * lam * g * H:
            _fail(where, "feed.cart_force",
                  f"{feed.cart_force!r} N does not balance the lower half of a loss-free "
                  "machine (the chain would speed up or slow down at a constant rate without "
                  f"end); allowed: {F_bal:.6g} N = F_lc + lambda*g*H*(1 - xi2 - xi3), or "
                  "feed.bearing_drag > 0")
        v, which = feed.speed, "feed.speed"
    else:
        v = ideal_fold_speed(feed.cart_force, feed.lower_cart_force, feed.xi2, feed.xi3, c,
                             lam, H, g)
        if not math.isfinite(v):
            _fail(where, "feed.cart_force",
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
        _fail(where, which,
              f"{getattr(feed, which.split('.')[1])!r} gives no fountain: at {shown} the "
              f"machine's Tbar_0 = 1/2 + Tbar_uc + xi2*k*H = {T0:.4g} (the paper needs < 1); "
              f"allowed: {allowed}")
    kq = (1.0 - T0) * math.cos(feed.launch_angle)  # k/q at the launch: q = k/(cos a0 (1-T0))
    if kq < IDEAL_MIN_KQ:
        _fail(where, which,
              f"{getattr(feed, which.split('.')[1])!r} puts the machine's fountain too near "
              f"critical at {shown} (k/q = {kq:.3f}, Tbar_0 = {T0:.3f}): there the simulated "
              "chain holds the machine back by about 1 % of lambda*v^2, and it sinks; allowed: "
              f"k/q >= {IDEAL_MIN_KQ} (a faster chain: "
              + ("a lighter upper cart or a heavier lower one)" if c > 0.0 else
                 "a higher feed.speed)"))
    if c > 0.0 and TE < 0.0:
        _fail(where, which,
              f"{feed.cart_force!r} N selects {v:.4g} m/s, where the lower strand goes slack "
              f"(Tbar_E = {TE:.4g}); allowed: a heavier lower cart or a lower xi3")
    return max(0.0, TE)


def _check_apparatus(level: Level, where: str) -> None:
    """Apparatus cross-field checks (paper: ``Tbar_E + k*H < 1`` for the launch)."""
    sim = level.sim
    a = sim.apparatus
    g = sim.gravity
    if a.floor_depth > 0:
        if a.variant != "floor" or a.end != "absorbing":
            _fail(where, "apparatus.floor_depth",
                  f"{a.floor_depth!r} m needs apparatus.variant = 'floor' with end = "
                  f"'absorbing' (it is {a.variant!r} with end {a.end!r}); allowed: 0")
        if a.end_tension != 0:
            _fail(where, "apparatus.end_tension",
                  f"{a.end_tension!r} conflicts with apparatus.floor_depth = {a.floor_depth:g} m, "
                  "which sets Tbar_E = g*floor_depth/speed**2; allowed: 0 with a floor_depth")
        v_need = math.sqrt(g * (a.drop + a.floor_depth))
        if a.speed <= v_need:
            _fail(where, "apparatus.speed",
                  f"{a.speed!r} m/s cannot launch a fountain that reaches a free end "
                  f"{a.drop + a.floor_depth:g} m lower (drop + floor_depth); allowed: a speed > "
                  f"sqrt(g*(H + floor_depth)) = {v_need:.4g} m/s")
    v_need = math.sqrt(g * a.drop / (1.0 - a.end_tension))
    if a.speed <= v_need:
        kH = g * a.drop / a.speed**2
        if a.end_tension > 0 and kH < 1.0:
            _fail(where, "apparatus.end_tension",
                  f"{a.end_tension!r} leaves no fountain at apparatus.speed = {a.speed:g} m/s "
                  f"and apparatus.drop = {a.drop:g} m (Tbar_E + k*H = {a.end_tension + kH:.4g}, "
                  f"k = g/v^2; the paper needs < 1); allowed: Tbar_E < 1 - k*H = {1.0 - kH:.4g} "
                  f"at this speed and drop (this end tension needs a speed > "
                  f"sqrt(g*H/(1 - Tbar_E)) = {v_need:.4g} m/s)")
        _fail(where, "apparatus.speed",
              f"{a.speed!r} m/s cannot launch a fountain that ends {a.drop:g} m lower with "
              f"Tbar_E = {a.end_tension:g}; allowed: a speed > sqrt(g*H/(1 - Tbar_E)) = "
              f"{v_need:.4g} m/s")
    if sim.chain.link_length > 0.1 * a.drop:
        _fail(where, "chain.link_length",
              f"{sim.chain.link_length!r} m is too coarse for a drop of {a.drop:g} m; "
              f"allowed: at most a tenth of apparatus.drop ({0.1 * a.drop:.4g} m)")
    if a.plate_links and a.plate != "groove":
        _fail(where, "apparatus.plate_links",
              f"{a.plate_links!r} needs apparatus.plate = 'groove' (it is {a.plate!r}); "
              "allowed: 0 with a 'contact' plate")
    if a.end_follow and a.plate != "groove":
        _fail(where, "apparatus.end_follow",
              f"{a.end_follow!r} needs the end guide of joints, apparatus.plate = 'groove' "
              f"(it is {a.plate!r}); allowed: 0 with a 'contact' plate")
    if a.plate_links and a.plate_links < 4:
        _fail(where, "apparatus.plate_links",
              f"{a.plate_links!r} is too short a plate strand to cut or extend in the middle; "
              "allowed: 0 (off) or at least 4")
    if 0 < a.pickup_rest_links < 5:
        _fail(where, "apparatus.pickup_rest_links",
              f"{a.pickup_rest_links!r} leaves the pick-up roller too little resting chain to "
              "roll on; allowed: 0 (as apparatus.rest_links) or at least 5")
    _check_apparatus_start(sim, where)
    if a.swing_damper and a.variant != "fold":
        _fail(where, "apparatus.swing_damper",
              f"{a.swing_damper!r} N*s/m only applies to variant = 'fold' (it acts between the "
              f"pick-up and the folding roller; here variant {a.variant!r}); allowed: 0")
    if a.fold_clearance and (a.variant != "fold" or a.plate != "groove"):
        _fail(where, "apparatus.fold_clearance",
              f"{a.fold_clearance!r} m only applies to variant = 'fold' with plate = 'groove' "
              f"(here variant {a.variant!r}, plate {a.plate!r}); allowed: 0")
    if 0.0 < a.fold_roller_radius < 0.005:
        _fail(where, "apparatus.fold_roller_radius",
              f"{a.fold_roller_radius!r} m is too small a roller; allowed: 0 (as "
              "apparatus.roller_radius) or 0.005-0.5 m")
    if a.fold_roller == "gripped":
        _check_gripped_fold(sim, where)
    if a.upper_guide == "joints" and a.plate != "groove":
        _fail(where, "apparatus.upper_guide",
              f"'joints' needs apparatus.plate = 'groove' (it is {a.plate!r}): the joint guide "
              "takes the links from the plate's grooves; allowed: 'walls' with a 'contact' plate")
    _check_apparatus_unused(sim, where)
    _check_apparatus_size(sim, where)
    _check_end_channel(sim, where)


def _check_gripped_fold(sim: SimConfig, where: str) -> None:
    """The gripped folding roller takes the chain from the lower plate's grooves, lays it
    where its circle meets the table (no clearance) and needs a circle of at least one
    link length round the chain's centre line (:mod:`chainfountain.sim.apparatus.grip`)."""
    a, L = sim.apparatus, sim.chain.link_length
    if a.plate != "groove":
        _fail(where, "apparatus.fold_roller",
              f"'gripped' needs apparatus.plate = 'groove' (it is {a.plate!r}): the roller "
              "takes the chain from the lower plate's grooves; allowed: 'contact'")
    if a.fold_clearance:
        _fail(where, "apparatus.fold_clearance",
              f"{a.fold_clearance!r} m has no effect with apparatus.fold_roller = 'gripped' "
              "(the gripped roller lays the chain where its circle meets the table); "
              "allowed: 0")
    r = a.fold_roller_radius or a.roller_radius
    if r + sim.chain.link_radius < L:
        _fail(where, "apparatus.fold_roller_radius",
              f"{r!r} m is too small a gripped folding roller for {L!r}-m links (the chain's "
              f"centre line must run at least one link length from its axle); allowed: at "
              f"least {L - sim.chain.link_radius:.4g} m (converged in the step from about "
              f"{5 * L:.3g} m, five link lengths; docs/apparatus.md)")


ONLY_FOR_VARIANT: dict[str, tuple[str, ...]] = {
    "xi3": ("fold",),
    "fold_roller": ("fold",),
    "fold_roller_radius": ("fold",),
    "fold_brake": ("fold",),
    "end_follow": ("fold",),
    "end_pull": ("open",),
    "end": ("floor",),
    "floor_width": ("floor",),
}
"""Apparatus fields that only the named variants use: ``xi3`` is the lower table's height
(only 'fold' has one), ``end_pull`` pulls the chain sliding away ('open'), ``end`` and
``floor_width`` are the floor's (only 'floor' has one)."""


def _check_apparatus_unused(sim: SimConfig, where: str) -> None:
    """Settings an apparatus level would ignore are refused: another variant's fields,
    ``[[rollers]]``, and carts beyond the ones its rollers take."""
    a, default = sim.apparatus, type(sim.apparatus)()
    for name, variants in ONLY_FOR_VARIANT.items():
        value = getattr(a, name)
        if a.variant not in variants and value != getattr(default, name):
            only = " or ".join(repr(v) for v in variants)
            _fail(where, f"apparatus.{name}",
                  f"{value!r} has no effect with apparatus.variant = {a.variant!r} (only "
                  f"{only} uses it); allowed: {getattr(default, name)!r}")
    if sim.rollers:
        _fail(where, "rollers",
              f"{len(sim.rollers)} [[rollers]] have no effect in an 'apparatus' level (it "
              "builds its own rollers); allowed: none (rollers = [])")
    n_carts = 2 if a.variant == "fold" else 1
    if len(sim.carts) > n_carts:
        which = ("carts[0] pulls the pick-up roller, carts[1] pushes the folding roller"
                 if n_carts == 2 else "carts[0] pulls the pick-up roller")
        _fail(where, f"carts[{n_carts}]",
              f"has no effect with apparatus.variant = {a.variant!r} ({which}); allowed: at "
              f"most {n_carts} [[carts]]")


def _check_end_channel(sim: SimConfig, where: str) -> None:
    """'fold': the end channel's two bends fit into the rise ``xi3*H`` (or it is zero)."""
    from chainfountain.sim.guide import end_channel_bends, end_channel_min_rise

    a = sim.apparatus
    rise = a.xi3 * a.drop
    if a.variant != "fold" or rise <= 1e-9:
        return
    f = _fountain_or_fail(where, "apparatus.speed", a.speed, a.launch_angle, a.drop,
                          a.end_tension, sim.gravity)
    try:
        end_channel_bends(f.alphaE, rise, a.channel_radius)
    except ValueError:
        least = end_channel_min_rise(f.alphaE, a.channel_radius) / a.drop
        _fail(where, "apparatus.xi3",
              f"{a.xi3!r} lifts the chain only {rise:.3g} m, too little for the end channel's "
              f"two bends at this landing angle; allowed: 0 or at least {least:.4g} "
              f"(a rise of {least * a.drop:.3g} m)")


def _check_apparatus_size(sim: SimConfig, where: str) -> None:
    """At most :data:`MAX_LINKS` links at the start: the chain in flight, and the upper
    plate strand that spans the pick-up roller's travel (``v/2`` for ``duration``) unless
    the plate is a treadmill."""
    a, g, L = sim.apparatus, sim.gravity, sim.chain.link_length
    d = a.floor_depth if a.variant == "floor" else 0.0
    te = a.end_tension + g * d / a.speed**2
    f = _fountain_or_fail(where, "apparatus.speed", a.speed, a.launch_angle, a.drop, te, g)
    v_min = math.sqrt(g * (a.drop + d) / (1.0 - a.end_tension))
    _check_size(where, "apparatus.speed", f.length, 0.0, L, min(0.1 * a.drop, 0.2), a.speed,
                v_min, lambda length: _fastest_fitting(v_min, a.speed, a.launch_angle, a.drop,
                                                       a.end_tension, g, length, d))
    if a.plate_links > 0 and a.plate == "groove":
        return
    n = (f.length + 0.5 * a.speed * a.duration + 0.15) / L
    if n > MAX_LINKS:
        room = (MAX_LINKS * L - f.length - 0.15) / (0.5 * a.speed)
        _fail(where, "apparatus.duration",
              f"{a.duration!r} s sizes the upper plate for {0.5 * a.speed * a.duration:.4g} m of "
              f"roller travel (v/2 for the duration): {n:.0f} links at the start; allowed: at "
              f"most {MAX_LINKS} links, here a duration <= {max(room, 0.0):.4g} s (or "
              "apparatus.plate_links > 0, a treadmill, for runs of any length)")


def _check_accuracy_scope(sim: SimConfig, where: str) -> None:
    """``solver.accuracy`` only where its error model was measured: a motor-fed fountain
    landing on an absorbing floor, without blocks in the scene or self-collision."""
    if sim.solver.accuracy == 0.0:
        return
    why = None
    if sim.kind != "feed":
        why = f"kind = {sim.kind!r}"
    elif sim.feed.floor != "absorbing":
        why = f"feed.floor = {sim.feed.floor!r}"
    elif sim.feed.drive != "motor":
        why = f"feed.drive = {sim.feed.drive!r}"
    elif sim.rollers or sim.carts:
        why = "rollers or carts in the scene"
    elif sim.chain.self_collision:
        why = "chain.self_collision = true"
    if why is not None:
        _fail(where, "solver.accuracy",
              f"{sim.solver.accuracy!r} with {why}: the error model covers motor-fed fountains "
              "on an absorbing floor only; allowed: 0 (use the level's own link length, step "
              "and iterations)")


def apply_accuracy(level: Level, where: str) -> Estimate | None:
    """Choose link length, step and iterations for ``solver.accuracy`` (when above 0) and
    write them into ``level.sim``; returns the error model's estimate for them.

    A fountain the model cannot reach the accuracy for is refused with the best bound it
    can reach (:func:`chainfountain.sim.accuracy.choose`)."""
    from chainfountain.sim import accuracy
    from chainfountain.sim.reference import LaunchReference

    sim = level.sim
    acc = sim.solver.accuracy
    if acc == 0.0 or sim.kind != "feed":
        return None
    f = sim.feed
    ref = LaunchReference.of_feed(f, sim.gravity)
    try:
        est = accuracy.choose(ref, acc)
    except accuracy.OutOfReach as exc:
        least = (f"at least {math.ceil(exc.best * 1e4) / 1e4:g}, or 0" if math.isfinite(exc.best)
                 else "0")
        _fail(where, "solver.accuracy", f"{acc!r}: {exc}; allowed: {least} (0: the level's own "
              "settings, with `chainfountain converge LEVEL` for their error)")
    s = est.settings
    sim.chain.link_length = s.link_length
    sim.chain.link_radius = min(sim.chain.link_radius, 0.4 * s.link_length)
    sim.solver.dt = s.dt
    sim.solver.substeps = 1
    sim.solver.iterations = s.iterations
    return est
