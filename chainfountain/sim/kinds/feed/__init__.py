"""A motor-fed fountain (``kind = "feed"``, ``feed.drive = "motor"``): the paper's string
model, a chain launched from a guide at a set speed onto a floor that pulls its end with
``Tbar_E lambda v^2`` (section "Inverted Catenary")."""

from __future__ import annotations

from typing import Any

from chainfountain.sim.bodies import Cart, Floor, Roller
from chainfountain.sim.chain import Chain
from chainfountain.sim.config import FeedConfig, SimConfig
from chainfountain.sim.feed import Feed
from chainfountain.sim.kinds import fed_accuracy
from chainfountain.sim.kinds.base import (
    DEFAULT_DURATION,
    FORMING_DURATION,
    Kind,
)
from chainfountain.sim.kinds.fed import check_drive_fields, check_fed


def lay_chain(sim: Any) -> None:
    """The fed fountain's chain, floor, rollers and carts in ``sim``'s space, and its
    reference at the feed speed (a motor's feed and an ideal machine's alike)."""
    cfg = sim.config
    needs_shapes = (cfg.feed.floor == "solid" or bool(cfg.rollers) or bool(cfg.carts)
                    or cfg.chain.self_collision)
    sim.chain = Chain(sim.space, cfg.chain, cfg.solver, shapes=needs_shapes,
                      wave_damping=sim.wave_damping_at(cfg.feed.speed))
    if cfg.feed.floor == "solid":
        w = cfg.feed.floor_width
        sim.floor = Floor.add(sim.space, -cfg.feed.drop, -0.5 * w, 0.5 * w,
                              friction=cfg.chain.friction)
    sim.rollers = [Roller.add(sim.space, r) for r in cfg.rollers]
    sim.carts = [Cart.add(sim.space, c, error_bias=cfg.solver.joint_error_bias)
                 for c in cfg.carts]
    sim.theory_at(cfg.feed.speed)


def feed_for(sim: Any, end_pull: Any = None) -> Feed:
    """The fed level's :class:`Feed` laid out on its start (``end_pull``: the floor's pull
    as a function of the speed, when a machine sets it)."""
    cfg = sim.config
    feed = Feed(sim.chain, cfg.feed, end_pull=end_pull)
    feed.initialise(cfg.initial, sim.catenary)
    feed.set_reference(sim.catenary)
    return feed


def build(sim: Any) -> None:
    """The motor's feed drives both ends."""
    lay_chain(sim)
    sim.feed = sim.ends = feed_for(sim)


def check(cfg: SimConfig, where: str) -> None:
    """A motor-fed fountain's checks (:func:`~chainfountain.sim.kinds.fed.check_fed`)."""
    check_drive_fields(cfg, where)
    check_fed(cfg, where, cfg.feed.end_tension)


def default_duration(cfg: SimConfig) -> float:
    """:data:`FORMING_DURATION` from a stub (it forms, then is averaged), else
    :data:`DEFAULT_DURATION`."""
    return FORMING_DURATION if cfg.initial.mode == "stub" else DEFAULT_DURATION


def reach(cfg: SimConfig) -> tuple[float, float]:
    """The feed speed, and the drop plus the chain's length."""
    return float(cfg.feed.speed), cfg.feed.drop + cfg.feed.chain_length


def speed_setter(sim: Any, index: int | None, v: float) -> None:
    """``feed.speed`` live: the feed (or the ideal machine's piston) to ``v``."""
    sim.set_feed_speed(v)


def _end_tension(sim: Any, index: int | None, v: float) -> None:
    sim.set_feed_speed(sim.config.feed.speed)  # recomputes the reference


def accuracy_refusal(cfg: SimConfig) -> str | None:
    """``solver.accuracy``'s error model covers a fed fountain on an absorbing floor (a
    motor's, or an ideal machine's flight at its speed), without blocks in the scene or
    self-collision."""
    if cfg.feed.floor != "absorbing":
        return f"feed.floor = {cfg.feed.floor!r}"
    if cfg.rollers or cfg.carts:
        return "rollers or carts in the scene"
    if cfg.chain.self_collision:
        return "chain.self_collision = true"
    return None


DEFAULT_ACCURACY = 0.01
"""A motor-fed level file that sets no settings runs at 1 % (:attr:`Kind.default_accuracy`),
whose settings depend on the fountain: a floor-pull fountain of 4.6 m/s launched at
1.2 rad gets 1.5-cm links, 250 us and 10 iterations (bound 0.94 % in the vertex height;
at the schema's 2-cm links and 25 iterations 1.02 %), the same at 12 m/s 5-cm links,
125 us and 30 iterations."""


KIND = Kind(
    config=FeedConfig, name="feed", table="feed", title="a motor-fed fountain", check=check,
    default_duration=default_duration, reach=reach, build=build,
    live={"feed.speed": speed_setter, "feed.end_tension": _end_tension},
    accuracy_refusal=accuracy_refusal, default_accuracy=DEFAULT_ACCURACY,
    choose_settings=fed_accuracy.choose_settings, style=lambda cfg: "motor",
    sections=("error_bars", "error_model"), predicted=True, stiff_theory=True,
)
