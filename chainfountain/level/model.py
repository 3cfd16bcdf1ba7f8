"""What a level is: its meta data and simulation setup, the schema version and the
error every level problem raises (one line naming where, the field, the value and what is
allowed)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from chainfountain.errors import LevelError
from chainfountain.errors import fail as _fail
from chainfountain.fields import REQUIRED, param, type_hints
from chainfountain.sim.config import SimConfig

SCHEMA_VERSION = 1
_SKIP_TOP = frozenset({"name"})  # SimConfig.name mirrors meta.name
"""Top-level config fields a level file does not carry."""


@dataclass
class Meta:
    """Name and description of a level."""

    name: str = param(REQUIRED, unit="", doc="Short name of the level (its file name's stem "
                      "for a shipped level; `chainfountain run NAME` runs it)")
    title: str = param("", unit="", doc="The level's title as the window and the picker show "
                       "it (default: the name)")
    description: str = param(
        "", unit="", doc="What the level shows and what to try, in at most three sentences "
        "(the window's card and the picker show it)"
    )
    demo: bool = param(True, unit="", doc="Whether the window's picker lists a level that "
                       "forms from rest with the demonstrations (false: with the studies, as "
                       "a level that runs slower than real time in the window)")
    controls: str = param("", unit="", doc="The sliders the window's student view shows, as "
                          "field paths separated by commas (e.g. \"carts[0].mass, "
                          "apparatus.xi2\"); empty: the kind's usual ones. The expert view "
                          "(E) shows every field")

    @property
    def shown_title(self) -> str:
        """The title, or the name when the level has none."""
        return self.title.strip() or self.name

    def control_paths(self) -> list[str]:
        """:attr:`controls` as a list of field paths (empty: none named)."""
        return [p.strip() for p in self.controls.split(",") if p.strip()]


@dataclass
class Level:
    """One saved configuration: its meta data and the simulation setup."""

    meta: Meta
    sim: SimConfig

    @property
    def name(self) -> str:
        return self.meta.name


def _hints(cls: type) -> dict[str, Any]:
    return type_hints(cls)


def _is_dataclass_type(tp: Any) -> bool:
    return isinstance(tp, type) and dataclasses.is_dataclass(tp)


__all__ = ["SCHEMA_VERSION", "Level", "LevelError", "Meta", "_fail"]
