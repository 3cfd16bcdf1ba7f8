"""A sweep's points, identified by what they run.

Each point is the base level with the sweep's ``[changes]``, its grid values and its seed
applied, validated as a level file (``solver.accuracy``'s choices included). Its identity,
:attr:`Planned.key`, is a hash of that resolved level's text (every field but the
description), the simulated duration and the software (:data:`VERSION`); its record lives
in ``OUT/points/<key>/``: ``level.toml`` (the level exactly as it ran), ``point.json``
(status, reason, version, duration and the run's numbers) and the run's outputs. A rerun
reuses a record only under the same key, so an edited base level, a changed duration or
another version runs again, and an extended grid runs exactly its new points.

A point's record is written ``running`` when it starts and replaced when it ends; a point
found ``running`` or ``interrupted`` (a signal, a lost worker) is run again.
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
from dataclasses import dataclass
from functools import cache
from importlib import metadata
from pathlib import Path
from typing import Any

from chainfountain import __version__, atomic
from chainfountain.headless import check_run, default_duration, seeded
from chainfountain.level import io
from chainfountain.level.model import Level, LevelError
from chainfountain.study.changes import with_changes
from chainfountain.study.sweep_file import Sweep

STATUS = ("done", "ended_early", "interrupted", "failed", "refused")
"""A point's status: run to its end; the run ended early (a table used up, divergence;
its outputs are kept); stopped by a signal or a lost worker (run again on resume); an
exception while running; the loader refused its level (nothing ran)."""
RERUN = ("running", "interrupted")
"""Recorded statuses a rerun runs again (``failed`` too with ``--retry-failed``)."""
RECORD = "point.json"
LEVEL = "level.toml"


@cache
def version() -> str:
    """The software a point's numbers depend on: chainfountain's and pymunk's versions."""
    try:
        pymunk = metadata.version("pymunk")
    except metadata.PackageNotFoundError:  # pragma: no cover - a dependency
        pymunk = "?"
    return f"chainfountain {__version__}, pymunk {pymunk}"


@dataclass(frozen=True)
class Planned:
    """One point of a sweep: its place (``p00003``), its grid values and seed, and either
    its resolved level (text, duration, key) or why the loader refused it."""

    id: str
    values: dict[str, Any]
    seed: int | None
    level_text: str = ""
    duration: float = 0.0
    key: str = ""
    refused: str = ""

    def row(self) -> dict[str, Any]:
        """The table's first columns for this point."""
        return {"point": self.id, **self.values, "seed": self.seed}


def identity(level: Level, duration: float) -> str:
    """The key of a run of ``level`` for ``duration`` s with this software: a hash of
    the level's text (its description left out: it changes no number), the duration and
    :func:`version`."""
    plain = dataclasses.replace(level, meta=dataclasses.replace(level.meta, description=""))
    blob = json.dumps({"level": io.dumps(plain), "duration": repr(float(duration)),
                       "version": version()}, sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:20]


def plan(sweep: Sweep) -> list[Planned]:
    """Every combination of the grid's values, once per seed, in a stable order, each
    resolved (or refused, with the loader's reason)."""
    names = sweep.columns
    out = []
    for k, (combo, seed) in enumerate(itertools.product(
            itertools.product(*(sweep.grid[n] for n in names)), sweep.seeds)):
        pid = f"p{k:05d}"
        values = dict(zip(names, combo, strict=True))
        try:
            level = seeded(with_changes(sweep.base, {**sweep.changes, **values}, where=pid),
                           seed)
            duration = sweep.duration or default_duration(level)
            check_run(level, duration, where=pid)
        except LevelError as exc:
            out.append(Planned(pid, values, seed, refused=str(exc)))
            continue
        out.append(Planned(pid, values, seed, level_text=io.dumps(level), duration=duration,
                           key=identity(level, duration)))
    return out


def folder(out: Path, pt: Planned) -> Path:
    """Where ``pt``'s record and outputs live."""
    return out / "points" / pt.key


def read(out: Path, pt: Planned) -> dict[str, Any] | None:
    """``pt``'s record under ``out`` (``None``: none, or unreadable, or another key's)."""
    try:
        rec = json.loads((folder(out, pt) / RECORD).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return rec if isinstance(rec, dict) and rec.get("key") == pt.key else None


def write(out_dir: Path, record: dict[str, Any]) -> None:
    """Write a point's record atomically (``point.json``)."""
    out_dir.mkdir(parents=True, exist_ok=True)
    atomic.write_text(out_dir / RECORD, json.dumps(record, indent=1, default=str) + "\n")


def record(pt: Planned, status: str, reason: str = "", **extra: Any) -> dict[str, Any]:
    """A record of ``pt`` with ``status`` and ``reason``."""
    return {"key": pt.key, "version": version(), "duration": pt.duration, "values": pt.values,
            "seed": pt.seed, "status": status, "reason": reason, "wall_s": 0.0,
            "results": {}, **extra}


def row(pt: Planned, rec: dict[str, Any] | None) -> dict[str, Any]:
    """``pt``'s row of the table: its place, values and seed, its status and reason, its
    key and version, and every number of its run."""
    if pt.refused:
        return {**pt.row(), "status": "refused", "reason": pt.refused, "key": "",
                "version": version(), "wall_s": 0.0}
    assert rec is not None
    status = "interrupted" if rec.get("status") == "running" else rec.get("status")
    return {**pt.row(), "status": status, "reason": rec.get("reason", ""), "key": pt.key,
            "version": rec.get("version"), "wall_s": rec.get("wall_s", 0.0),
            **(rec.get("results") or {})}


def reusable(rec: dict[str, Any] | None, retry_failed: bool) -> bool:
    """Whether a recorded point counts as done for a rerun."""
    if rec is None or rec.get("status") in RERUN:
        return False
    return not (retry_failed and rec.get("status") == "failed")


def mark_interrupted(out: Path, pts: list[Planned], reason: str) -> int:
    """Record as ``interrupted`` every point of ``pts`` found ``running`` (its worker was
    stopped before it could say so); returns how many."""
    n = 0
    for pt in pts:
        rec = read(out, pt)
        if rec is not None and rec.get("status") == "running":
            write(folder(out, pt), {**rec, "status": "interrupted", "reason": reason})
            n += 1
    return n
