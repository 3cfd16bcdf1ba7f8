"""A level with some fields changed, validated exactly as a level file is."""

from __future__ import annotations

import re
import tomllib
from collections.abc import Mapping
from typing import Any

from chainfountain.level import io
from chainfountain.level.model import Level, LevelError

_PATH = re.compile(r"^(?:[a-z_]+)(?:\.[a-z_0-9]+|\[\d+\]\.[a-z_0-9]+)?$")


def with_changes(level: Level, changes: Mapping[str, Any], where: str = "change") -> Level:
    """``level`` with each dotted field of ``changes`` set (``"feed.speed"``, ``"gravity"``,
    ``"carts[0].mass"``, ``"meta.name"``), checked as a level file is: a field that does not
    exist, a value out of its range, or a combination the loader refuses raises
    :class:`~chainfountain.level.model.LevelError` naming the field. The result is a new
    level (``solver.accuracy`` applied again); ``level`` is untouched."""
    data = tomllib.loads(io.dumps(level))
    for path, value in changes.items():
        if not isinstance(path, str) or not _PATH.match(path):
            raise LevelError(f"{where}: {path!r} is not a field path; allowed: a dotted path "
                             "as in docs/levels.md, e.g. 'feed.speed' or 'carts[0].mass'")
        _set(data, path, value, where)
    return io.parse_level(data, where)


def _set(data: dict[str, Any], path: str, value: Any, where: str) -> None:
    head, _, rest = path.partition(".")
    m = re.match(r"^([a-z_]+)\[(\d+)\]$", head)
    if m:
        items = data.get(m.group(1))
        i = int(m.group(2))
        if not isinstance(items, list) or i >= len(items):
            n = len(items) if isinstance(items, list) else 0
            raise LevelError(f"{where}: {path}: the level has {n} {m.group(1)}; allowed: an "
                             f"index below {n}")
        items[i][rest] = value
    elif rest:
        table = data.setdefault(head, {})
        if not isinstance(table, dict):
            raise LevelError(f"{where}: {path}: {head!r} is not a table; allowed: a field "
                             "path as in docs/levels.md")
        table[rest] = value
    else:
        data[head] = value


def laid_on_path(level: Level) -> Level:
    """An apparatus ``level`` started the study way: laid along its path, moving at
    ``apparatus.speed`` (``initial.mode = "catenary"``, no starter), so that a study reads
    the machine's steady state without first waiting for it to form from rest. A level
    that already starts so is returned as it is."""
    if level.sim.kind != "apparatus" or level.sim.initial.mode == "catenary":
        return level
    return with_changes(level, {"initial.mode": "catenary", "apparatus.starter": 0.0},
                        where=level.meta.name or "level")
