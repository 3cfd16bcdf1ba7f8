"""A sweep file (TOML), read and checked before anything runs.

::

    base = "paper_tall"          # a level name, or a path relative to the sweep file
    duration = 6.0               # simulated seconds per point (default: the level's)
    seeds = [0, 1]               # optional: every point once per seed
    snapshots = false            # optional: each point's snapshot.png (0.3 s each)
    [changes]                    # optional: fields set in every point
    "solver.iterations" = 30
    [grid]                       # every combination of these fields' values
    "feed.speed" = [5.0, 5.5, 6.0]
    "scene.pins[0].release" = [0.1, 0.2]

The grid may be left out when ``seeds`` is given (a sweep over seeds alone). Every field
path is one of :mod:`chainfountain.level.paths` (list items included); each value's type
is checked here, so a grid that mixes a text into a number's values is refused at once.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from chainfountain.errors import UserError
from chainfountain.level import io, library, paths
from chainfountain.level.model import Level, LevelError
from chainfountain.sim.kinds import kind_of
from chainfountain.study.changes import with_changes

KEYS = {"base", "duration", "seeds", "grid", "changes", "snapshots"}
"""Top-level keys of a sweep file."""
MAX_POINTS = 100_000
"""Most points (grid combinations times seeds) a sweep may have."""
_STRUCTURAL = ("unknown key", "not a field path", "is not a table", "index below")
"""Words of a loader's message that mean the path itself is wrong (not its value)."""


@dataclass
class Sweep:
    """A parsed sweep file."""

    path: Path
    base: Level
    base_name: str
    duration: float | None
    grid: dict[str, list[Any]]
    seeds: list[int | None] = field(default_factory=lambda: [None])
    snapshots: bool = False
    changes: dict[str, Any] = field(default_factory=dict)
    """Fields set in every point (the ``[changes]`` table)."""

    @property
    def columns(self) -> list[str]:
        """The swept fields, in the file's order (the table's first columns)."""
        return list(self.grid)


def _fail(where: str, key: str, msg: str) -> None:
    raise UserError(f"{where}: {key}: {msg}")


def _read(p: Path) -> dict[str, Any]:
    where = io.shown_path(p)
    try:
        text = p.read_bytes().decode("utf-8-sig")  # a byte-order mark is no content
    except OSError as exc:
        raise UserError(f"{where}: cannot read ({exc.strerror or exc})") from None
    except UnicodeDecodeError:
        raise UserError(f"{where}: not a UTF-8 text file") from None
    try:
        return tomllib.loads(text)
    except (tomllib.TOMLDecodeError, ValueError, RecursionError) as exc:
        raise UserError(f"{where}: not valid TOML ({exc})") from None


def _check_path(base: Level, where: str, key: str, value: Any) -> None:
    """The field ``key`` exists in ``base`` and takes ``value``'s type; a value out of
    range is left to each point (it may be refused there, with its reason)."""
    try:
        paths.check_type(key, value, where)
    except LevelError as exc:
        raise UserError(str(exc)) from None
    try:
        with_changes(base, {key: value}, where=where)
    except LevelError as exc:
        if any(w in str(exc) for w in _STRUCTURAL):
            raise UserError(str(exc)) from None


def load(path: str | Path) -> Sweep:
    """Read and check a sweep file (:class:`~chainfountain.errors.UserError`, one line
    naming the file, the key, the value and what is allowed, for anything wrong)."""
    p = Path(path)
    where = io.shown_path(p)
    data = _read(p)
    unknown = sorted(set(data) - KEYS)
    if unknown:
        _fail(where, unknown[0], f"unknown key; allowed keys: {', '.join(sorted(KEYS))}")
    if not isinstance(data.get("base"), str) or not data["base"].strip():
        _fail(where, "base", f"{data.get('base')!r}; allowed: a level name or a path to a "
              "level file (relative to the sweep file)")
    rel = p.parent / data["base"]
    try:
        base_path = rel if rel.suffix == ".toml" and rel.is_file() else \
            library.resolve(data["base"])
        base = io.load(base_path)
    except LevelError as exc:
        raise UserError(f"{where}: base: {exc}") from None
    duration = data.get("duration")
    if duration is not None and (isinstance(duration, bool) or not isinstance(
            duration, int | float) or not 0 < duration <= 3600):
        _fail(where, "duration", f"{duration!r}; allowed: simulated seconds in (0, 3600]")
    seeds = data.get("seeds", [None])
    if (not isinstance(seeds, list) or not seeds
            or not all(s is None or (isinstance(s, int) and not isinstance(s, bool) and s >= 0)
                       for s in seeds)):
        _fail(where, "seeds", f"{seeds!r}; allowed: a non-empty list of integers >= 0")
    if len(set(seeds)) != len(seeds):
        _fail(where, "seeds", f"{seeds!r} repeats a seed; allowed: each seed once")
    unseeded = kind_of(base.sim).unseeded(base.sim)
    if unseeded is not None and seeds != [None]:
        _fail(where, "seeds", f"{seeds!r} has no effect on {base.meta.name!r} ({unseeded}); "
              "allowed: leave seeds out")
    changes = data.get("changes", {})
    if not isinstance(changes, dict):
        _fail(where, "changes", f"{changes!r}; allowed: a [changes] table of field paths, "
              "each with one value, e.g. \"solver.iterations\" = 30")
    for key, value in changes.items():
        _check_path(base, f"{where}: changes", key, value)
    grid = data.get("grid", {})
    if not isinstance(grid, dict) or (not grid and "seeds" not in data):
        _fail(where, "grid", "missing or empty; allowed: a [grid] table of field paths, each "
              "with a list of values, e.g. \"feed.speed\" = [5.0, 6.0] (or seeds = [...] "
              "alone, for a sweep over seeds)")
    for key, values in grid.items():
        if not isinstance(values, list) or not values:
            _fail(where, f"grid.{key}", f"{values!r}; allowed: a non-empty list of values")
        if key in changes:
            _fail(where, f"grid.{key}", "is also in [changes]; allowed: a field in one of "
                  "them")
        field_ = paths.declared(key, f"{where}: grid")
        for i, value in enumerate(values):
            problem = paths.type_problem(field_, value) if field_ is not None else None
            if problem:
                _fail(where, f"grid.{key}", f"value {i + 1} of {len(values)}: {problem}")
        _check_path(base, f"{where}: grid", key, values[0])
    snapshots = data.get("snapshots", False)
    if not isinstance(snapshots, bool):
        _fail(where, "snapshots", f"{snapshots!r}; allowed: true or false")
    n = math.prod(len(v) for v in grid.values()) * len(seeds)
    if n > MAX_POINTS:
        _fail(where, "grid", f"{n} points; allowed: at most {MAX_POINTS}")
    return Sweep(path=p, base=base, base_name=base.meta.name,
                 duration=None if duration is None else float(duration), grid=dict(grid),
                 seeds=list(seeds), snapshots=snapshots, changes=dict(changes))
