"""The paper's pulley apparatus (``kind = "apparatus"``): rollers, carts on inclined
tracks and tables in contact with the chain (:mod:`chainfountain.sim.apparatus`); the
machine chooses its speed."""

from __future__ import annotations

from typing import Any

from chainfountain.sim.apparatus import Apparatus, region
from chainfountain.sim.bodies import nudge_bodies
from chainfountain.sim.chain import Chain
from chainfountain.sim.config import ApparatusConfig, SimConfig
from chainfountain.sim.kinds.apparatus.checks import check_apparatus
from chainfountain.sim.kinds.base import DEFAULT_DURATION, FORMING_DURATION, Kind


def build(sim: Any) -> None:
    """The chain and the machine; the :class:`Apparatus` drives both ends. ``initial.seed``
    > 0 nudges every moving body by 1e-12 of its velocity: another of the machine's
    chaotic runs, for ensembles."""
    cfg = sim.config
    sim.chain = Chain(sim.space, cfg.chain, cfg.solver, shapes=True,
                      wave_damping=sim.wave_damping_at(cfg.apparatus.speed))
    make = sim.builders.get("apparatus", Apparatus)  # a study's own (research/hanging_start.py)
    sim.apparatus = sim.ends = make(sim.space, sim.chain, cfg)
    if cfg.initial.seed:  # a chaotic machine: a seed picks another of its runs
        nudge_bodies(sim.space, cfg.initial.seed)


def default_duration(cfg: SimConfig) -> float:
    """``apparatus.duration`` when the upper table is sized by it (no treadmill), so the run
    ends before the table does; :data:`FORMING_DURATION` from rest; else
    :data:`DEFAULT_DURATION`."""
    if cfg.apparatus.plate_links == 0:
        return float(cfg.apparatus.duration)
    return FORMING_DURATION if cfg.initial.mode == "stub" else DEFAULT_DURATION


def reach(cfg: SimConfig) -> tuple[float, float]:
    """The start speed, and the tables' drops, the floor and the run's travel."""
    a = cfg.apparatus
    v = float(a.speed)
    return v, a.drop * (1.0 + a.xi2 + a.xi3) + a.floor_depth + v * a.duration


def _cart_mass(sim: Any, index: int | None, v: float) -> None:
    app = sim.apparatus
    unit = (app.upper, app.lower)[int(index or 0)]
    if unit is None or unit.cart is None:
        raise KeyError(f"carts[{index}].mass: no such cart in this apparatus")
    unit.set_cart_mass(v, sim.config.apparatus.carriage_mass)


def _losses(sim: Any, index: int | None, v: float) -> None:
    sim.apparatus.set_losses()  # the carriages' springs


def study_start(cfg: SimConfig) -> dict[str, Any]:
    """A study reads the machine's steady state without first waiting for it to form from
    rest: laid along its path, moving at ``apparatus.speed``."""
    if cfg.initial.mode == "catenary":
        return {}
    return {"initial.mode": "catenary", "apparatus.starter": 0.0}


KIND = Kind(
    config=ApparatusConfig, name="apparatus", table="apparatus", title="the pulley apparatus",
    check=check_apparatus,
    default_duration=default_duration, reach=reach, build=build,
    live={"carts[].mass": _cart_mass, "apparatus.bearing_drag": _losses,
          "apparatus.fold_brake": _losses, "apparatus.swing_damper": _losses},
    style=lambda cfg: cfg.apparatus.variant, sections=("apparatus",),
    start_region=region.from_rest,
    study_start=study_start, half_step_bars=True,
)
