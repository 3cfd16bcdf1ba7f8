"""A headless run as a Python call: ``chainfountain.study.run("classroom", duration=5)``."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from chainfountain.level import io, library
from chainfountain.level.model import Level
from chainfountain.study.changes import with_changes

SERIES = ("t", "speed_mean", "speed_min", "speed_max", "vertex_x", "vertex_y", "landing_x",
          "stretch", "n_free", "T0_bar")
"""The time series a :class:`RunResult` of a fountain carries (one value per recorded
sample); a scene's carries ``t`` and each probe's columns as ``"<probe>.<column>"``."""


@dataclass
class RunResult:
    """What a run gives back: the ``summary.json`` object, the recorded time series as
    arrays, and where the run's files are."""

    level: Level
    summary: dict[str, Any]
    series: dict[str, np.ndarray] = field(default_factory=dict)
    out_dir: Path = Path()
    paths: dict[str, Path] = field(default_factory=dict)
    """Each output file by name (``summary.json``, ``speed.csv``, ...)."""

    @property
    def ok(self) -> bool:
        """Whether the run went its whole length and every output was written."""
        return not self.summary.get("ended_early") and not self.summary.get("write_failed")

    def error(self, figure: str) -> float | None:
        """Relative error of ``figure`` (``"h"``, ``"l"``, ``"vertex_x"``, ``"speed"``)
        against the paper's prediction (``None`` without one)."""
        th = self.summary.get("theory") or {}
        return (th.get("rel_error") or {}).get(figure)


def load(level: str | os.PathLike[str] | Level) -> Level:
    """A level from a name (``"paper_tall"``), a path, or a :class:`Level` as is."""
    if isinstance(level, Level):
        return level
    return io.load(library.resolve(level))


def run(level: str | os.PathLike[str] | Level, duration: float | None = None, *,
        seed: int | None = None, changes: Mapping[str, Any] | None = None,
        out: str | os.PathLike[str] | None = None, progress: bool = False) -> RunResult:
    """Run ``level`` headless, as ``chainfountain run`` does, and return the result.

    ``changes`` sets level fields first (:func:`~chainfountain.study.with_changes`, the
    same validation as a file); ``duration`` and ``seed`` as the command's options
    (``None``: the level's defaults). The outputs go to ``out`` (default: a new temporary
    folder, named in the result)."""
    from chainfountain.headless import run_and_record

    lvl = load(level)
    if changes:
        lvl = with_changes(lvl, changes)
    out_dir = Path(out) if out is not None else Path(tempfile.mkdtemp(prefix="chainfountain-"))
    path, rec = run_and_record(lvl, out_dir, duration, seed=seed, progress=progress)
    import json

    summary = json.loads(path.read_text())
    if lvl.sim.kind == "scene":  # each probe's columns, as "<probe>.<column>", and "t"
        log = rec.log
        series = {"t": log.t[: log.n].copy()}
        for i, probe in enumerate(lvl.sim.scene.probes):
            series.update({f"{probe.name}.{c}": v for c, v in log.columns(i).items()
                           if c != "t"})
    else:
        series = {name: rec.series(name) for name in SERIES}
    paths = {name: out_dir / name for name in summary.get("outputs", [])}
    return RunResult(level=lvl, summary=summary, series=series, out_dir=out_dir, paths=paths)
