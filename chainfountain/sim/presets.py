"""Shipped feed levels (to become ``levels/*.toml`` once the level loader exists).

Each preset is a :class:`~chainfountain.sim.config.SimConfig`; :data:`PRESETS`
maps names to constructors, :func:`as_dict` gives the TOML-shaped nested dict.

- ``paper_tall``: a tall, narrow fountain in the spirit of the paper's example
  (paper: ``H = 2 m``, ``v`` about 5 m/s, launch almost vertical). Here
  ``v = 5.5 m/s``, ``alpha0 = 80 deg``, ``H = 2 m``: predicted overshoot
  ``h = 0.895 m``, width ``l = 1.11 m``, about 4.2 m (207 links) in flight.
- ``wide_low``: a wide, low fountain launched at 60 deg: ``v = 4 m/s``,
  ``H = 0.5 m``: ``h = 0.565 m``, ``l = 1.71 m``, about 2.5 m in flight.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

from chainfountain.sim.config import FeedConfig, SimConfig


def paper_tall() -> SimConfig:
    """Tall narrow fountain, ``H = 2 m``, ``v = 5.5 m/s``, ``alpha0 = 80 deg``."""
    return SimConfig(
        name="paper_tall",
        feed=FeedConfig(speed=5.5, launch_angle=math.radians(80.0), drop=2.0, floor_width=4.0),
    )


def wide_low() -> SimConfig:
    """Wide low fountain, ``H = 0.5 m``, ``v = 4 m/s``, ``alpha0 = 60 deg``."""
    return SimConfig(
        name="wide_low",
        feed=FeedConfig(speed=4.0, launch_angle=math.radians(60.0), drop=0.5, floor_width=4.0),
    )


PRESETS: dict[str, Callable[[], SimConfig]] = {
    "paper_tall": paper_tall,
    "wide_low": wide_low,
}


def get(name: str) -> SimConfig:
    """The preset called ``name`` (``KeyError`` naming the known ones otherwise)."""
    try:
        return PRESETS[name]()
    except KeyError:
        raise KeyError(f"unknown preset {name!r}; known: {', '.join(PRESETS)}") from None


def as_dict(cfg: SimConfig) -> dict[str, Any]:
    """TOML-shaped nested dict of a config (tuples of sub-configs become lists of tables)."""
    return dataclasses.asdict(cfg)
