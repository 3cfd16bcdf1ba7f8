"""Studies from Python (a notebook): a whole run as a call (:func:`run`), or a level
stepped by hand (:func:`start`, a :class:`Stepper`). Arguments are checked with the
command line's messages (``duration: -1 is out of range; allowed: a duration in s > 0
and <= 3600``); nothing is left on disk unless ``out=`` names a folder."""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from chainfountain.errors import UserError
from chainfountain.headless import FOUNTAIN_SERIES, RunSummary, check_run, write_outputs
from chainfountain.headless import Stepper as _Stepper
from chainfountain.level import io, library
from chainfountain.level.model import Level
from chainfountain.sim.kinds import kind_of
from chainfountain.study.changes import with_changes

SERIES = FOUNTAIN_SERIES
"""The time series a :class:`RunResult` of a fountain carries (one value per recorded
sample); a scene's carries ``t`` and each probe's columns as ``"<probe>.<column>"``."""


@dataclass
class RunResult:
    """What a run gives back: the ``summary.json`` object, the recorded time series as
    arrays, and where the run's files are (``out_dir`` ``None`` and ``paths`` empty when
    no ``out=`` was given: the files were made in a temporary folder, read and removed)."""

    level: Level
    summary: dict[str, Any]
    series: dict[str, np.ndarray] = field(default_factory=dict)
    out_dir: Path | None = None
    paths: dict[str, Path] = field(default_factory=dict)
    """Each output file by name (``summary.json``, ``speed.csv``, ...)."""

    @property
    def ok(self) -> bool:
        """Whether the run went its whole length and every output was written."""
        return not self.summary.get("ended_early") and not self.summary.get("write_failed")

    @property
    def report(self) -> RunSummary:
        """The summary typed (:class:`~chainfountain.headless.report.RunSummary`)."""
        return RunSummary.from_json(self.summary)

    def error(self, figure: str) -> float | None:
        """Relative error of ``figure`` (``"h"``, ``"l"``, ``"vertex_x"``, ``"q"``,
        ``"v"``) against the paper's prediction (``None`` without one)."""
        th = self.report.theory
        return None if th is None else getattr(th.rel_error, figure, None)


def load(level: str | os.PathLike[str] | Level) -> Level:
    """A level from a name (``"paper_tall"``), a path, or a :class:`Level` as is."""
    if isinstance(level, Level):
        return level
    if not isinstance(level, str | os.PathLike):
        raise UserError(f"level: {level!r} is not allowed; allowed: a level name (e.g. "
                        "'paper_tall'), a path to a level file, or a Level")
    return io.load(library.resolve(level))


def _prepared(level: str | os.PathLike[str] | Level, changes: Mapping[str, Any] | None,
              duration: float | None, seed: int | None) -> tuple[Level, float]:
    """The level with its changes, and the duration the run takes, every argument checked
    before anything is built."""
    lvl = load(level)
    if changes is not None:
        lvl = with_changes(lvl, changes, where="changes")
    return lvl, check_run(lvl, duration, seed)


class Stepper(_Stepper):
    """A level simulated one call at a time (:class:`chainfountain.headless.Stepper`),
    which can also write its run's outputs (:meth:`write`)."""

    def write(self, out: str | os.PathLike[str], *, snapshot: bool = True) -> Path:
        """Write the run so far into the folder ``out`` as ``chainfountain run`` does
        (``summary.json``, CSVs, a picture); returns ``summary.json``."""
        if not isinstance(out, str | os.PathLike) or not str(out).strip():
            raise UserError(f"out: {out!r} is not allowed; allowed: a folder to write to")
        return write_outputs(self, Path(out), snapshot=snapshot)


def start(level: str | os.PathLike[str] | Level, *, seed: int | None = None,
          changes: Mapping[str, Any] | None = None, duration: float | None = None) -> Stepper:
    """Build ``level`` (a name, a path or a :class:`Level`, with ``changes`` and ``seed``
    as :func:`run` takes them) and return it ready to step::

        sim = chainfountain.start("wide_low", changes={"feed.speed": 4.5})
        sim.advance(1.0)
        sim.positions(), sim.speeds(), sim.tensions()

    ``duration``: how long a scene is sampled for (default its ``scene.duration``)."""
    lvl, _ = _prepared(level, changes, duration, seed)
    return Stepper(lvl, seed=seed, duration=duration)


def run(level: str | os.PathLike[str] | Level, duration: float | None = None, *,
        seed: int | None = None, changes: Mapping[str, Any] | None = None,
        out: str | os.PathLike[str] | None = None, progress: bool = False) -> RunResult:
    """Run ``level`` headless, as ``chainfountain run`` does, and return the result.

    ``changes`` sets level fields first (:func:`~chainfountain.study.with_changes`, the
    same validation as a file); ``duration`` and ``seed`` as the command's options
    (``None``: the level's defaults), checked with its messages. The outputs go to the
    folder ``out``; without it they are made in a temporary folder, read into the result
    and removed."""
    from chainfountain.headless import run_and_record

    if not isinstance(progress, bool):
        raise UserError(f"progress: {progress!r} is not allowed; allowed: True or False")
    if out is not None and (not isinstance(out, str | os.PathLike) or not str(out).strip()):
        raise UserError(f"out: {out!r} is not allowed; allowed: a folder to write to, or "
                        "None")
    lvl, seconds = _prepared(level, changes, duration, seed)
    if out is None:
        with tempfile.TemporaryDirectory(prefix="chainfountain-") as tmp:
            res = _run(run_and_record, lvl, Path(tmp), seconds, seed, progress)
        return RunResult(level=res.level, summary=res.summary, series=res.series)
    return _run(run_and_record, lvl, Path(out), seconds, seed, progress)


def _run(run_and_record, lvl: Level, out_dir: Path, duration: float, seed: int | None,
         progress: bool) -> RunResult:
    path, rec = run_and_record(lvl, out_dir, duration, seed=seed, progress=progress)
    summary = json.loads(path.read_text())
    if not kind_of(lvl.sim).fountain:  # a scene: "t" and each probe's "<probe>.<column>"
        log = rec.log
        series = {"t": log.t[: log.n].copy()}
        for i, probe in enumerate(lvl.sim.scene.probes):
            series.update({f"{probe.name}.{c}": v.copy() for c, v in log.columns(i).items()
                           if c != "t"})
    else:
        series = {name: rec.series(name) for name in SERIES}
    paths = {name: out_dir / name for name in summary.get("outputs", [])}
    return RunResult(level=lvl, summary=summary, series=series, out_dir=out_dir, paths=paths)
