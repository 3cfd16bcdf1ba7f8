"""A level with some fields changed, validated exactly as a level file is."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from chainfountain.level import paths
from chainfountain.level.model import Level
from chainfountain.sim.kinds import kind_of


def with_changes(level: Level, changes: Mapping[str, Any], where: str = "change") -> Level:
    """``level`` with each field of ``changes`` set (``"feed.speed"``, ``"gravity"``,
    ``"carts[0].mass"``, ``"scene.pins[0].release"``, ``"meta.name"``: any path of
    :mod:`chainfountain.level.paths`), checked as a level file is: a field that does not
    exist, a value of another type or out of its range, an index beyond an array's end,
    or a combination the loader refuses raises
    :class:`~chainfountain.level.model.LevelError` naming the field. The result is a new
    level (``solver.accuracy`` applied again); ``level`` is untouched."""
    return paths.changed(level, changes, where)


def laid_on_path(level: Level) -> Level:
    """An apparatus ``level`` started the study way: laid along its path, moving at
    ``apparatus.speed`` (``initial.mode = "catenary"``, no starter), so that a study reads
    the machine's steady state without first waiting for it to form from rest. A level
    that already starts so is returned as it is."""
    changes = kind_of(level.sim).study_start(level.sim)
    if not changes:
        return level
    return with_changes(level, changes, where=level.meta.name or "level")
