"""The paper's ideal machines (``kind = "feed"`` with ``feed.drive`` ``ideal_floor``,
``ideal_fold`` or ``ideal_open``): massless loss-free rollers replaced by their laws, the
upper half a :class:`~chainfountain.sim.piston.Piston` on the guide, the lower half the
floor's pull (:class:`~chainfountain.sim.put_down.PutDown`) or the turn onto a plate
(:class:`~chainfountain.sim.slide_away.SlideAway`); sections "Idealized beaker, real
floor" and "Generating Steady-State Chain Fountains"."""

from __future__ import annotations

from typing import Any

from chainfountain.sim.config import FeedConfig, SimConfig
from chainfountain.sim.kinds import fed_accuracy
from chainfountain.sim.kinds.base import DEFAULT_DURATION, MACHINE_FORMING_DURATION, Kind
from chainfountain.sim.kinds.fed import check_fed
from chainfountain.sim.kinds.feed import accuracy_refusal, feed_for, lay_chain, reach, speed_setter
from chainfountain.sim.kinds.ideal.checks import check_drive
from chainfountain.sim.machine_rules import MACHINE_FIELDS
from chainfountain.sim.piston import Piston
from chainfountain.sim.put_down import PutDown
from chainfountain.sim.slide_away import SlideAway


def build(sim: Any) -> None:
    """The fed chain, its lower half's pull on the floor end, and the piston that holds the
    feed and drives the chain by the upper half's law."""
    lay_chain(sim)
    drive = sim.config.feed.drive
    tail = SlideAway(sim) if drive == "ideal_open" else None
    pull = (PutDown(sim).pull if drive == "ideal_fold" else
            tail.pull if tail is not None else None)
    sim.feed = feed_for(sim, end_pull=pull)
    sim.slide_away = tail
    sim.piston = sim.ends = Piston(sim, sim.feed, tail=tail)


def check(cfg: SimConfig, where: str) -> None:
    """The machine's laws (:func:`~chainfountain.sim.kinds.ideal.checks.check_drive`), then
    the fountain they start with (:func:`~chainfountain.sim.kinds.fed.check_fed`)."""
    check_fed(cfg, where, check_drive(cfg, where))


def default_duration(cfg: SimConfig) -> float:
    """:data:`MACHINE_FORMING_DURATION` from a stub (it settles on its laws' speed after its
    starter), else :data:`DEFAULT_DURATION`."""
    return MACHINE_FORMING_DURATION if cfg.initial.mode == "stub" else DEFAULT_DURATION


def _machine(sim: Any, index: int | None, v: float) -> None:
    sim.machine_changed()


DEFAULT_ACCURACY = 0.02
"""An ideal machine's level file that sets no settings runs at 2 %
(:attr:`Kind.default_accuracy`): the machines' flight carries a step term of 0.94 % at
250 us and a margin of 0.74 % in the vertex's x beyond the motor-fed model
(:data:`chainfountain.sim.accuracy.IDEAL_STEP`, ``IDEAL_MARGIN``), so 1 % takes a
31-62.5-us step (0.1-0.3x real time) where 2 % is reached at 125-250 us."""


KIND = Kind(
    config=FeedConfig, name="ideal", table="feed", title="an ideal machine", check=check,
    default_duration=default_duration, reach=reach, build=build,
    live={"feed.speed": speed_setter, **{path: _machine for path in MACHINE_FIELDS}},
    accuracy_refusal=accuracy_refusal, default_accuracy=DEFAULT_ACCURACY,
    choose_settings=fed_accuracy.choose_settings,
    style=lambda cfg: cfg.feed.drive,
    sections=("machine", "open", "error_bars", "error_model"), predicted=True,
)
