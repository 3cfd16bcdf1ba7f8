"""The chain fountain from a beaker (``kind = "beaker"``): a chain piled in a pot rises
over the rim and falls to an absorbing floor (:mod:`chainfountain.sim.beaker`); the chain
chooses its own speed."""

from __future__ import annotations

import math
from typing import Any

from chainfountain.sim import beaker_error
from chainfountain.sim.beaker import Beaker
from chainfountain.sim.bodies import nudge_bodies
from chainfountain.sim.chain import Chain
from chainfountain.sim.config import BeakerConfig, SimConfig
from chainfountain.sim.kinds.base import Kind
from chainfountain.sim.kinds.beaker.checks import check_beaker
from chainfountain.sim.kinds.sizing import MAX_LINKS


def build(sim: Any) -> None:
    """The chain piled in its pot; the :class:`Beaker` drives both ends."""
    cfg = sim.config
    b = cfg.beaker
    v_guess = math.sqrt(2.0 * cfg.gravity * b.drop)
    sim.chain = Chain(sim.space, cfg.chain, cfg.solver, shapes=True,
                      wave_damping=sim.wave_damping_at(v_guess))
    sim.beaker = sim.ends = Beaker(sim.space, sim.chain, b, friction=cfg.chain.friction)
    if cfg.initial.seed:  # the pile is chaotic: a seed picks one of its runs
        nudge_bodies(sim.space, cfg.initial.seed)


def reach(cfg: SimConfig) -> tuple[float, float]:
    """Twice the free fall over the drop, and the drop and the pot."""
    b = cfg.beaker
    return math.sqrt(4.0 * cfg.gravity * b.drop), b.drop + b.pot_width + b.pot_depth


KIND = Kind(
    config=BeakerConfig, name="beaker", table="beaker", title="a chain rising from a beaker",
    check=lambda cfg, where: check_beaker(cfg, where, MAX_LINKS),
    default_duration=lambda cfg: float(cfg.beaker.duration), reach=reach, build=build,
    style=lambda cfg: "beaker", sections=("beaker",), paper_curve=False,
    accuracy_refusal=beaker_error.accuracy_refusal, choose_settings=beaker_error.choose_settings,
)
