"""Running one point of a sweep, in a worker process here or on a cluster's worker."""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

from chainfountain import atomic
from chainfountain.level import io
from chainfountain.study import points
from chainfountain.study.points import Planned
from chainfountain.study.table import flatten


def _clear(out_dir: Path) -> None:
    """Remove what an earlier, interrupted run of the point left in its folder."""
    if out_dir.is_dir():
        for f in out_dir.iterdir():
            if f.is_file():
                f.unlink()


def run_point(pt: Planned, out_dir: Path, snapshot: bool = False) -> dict[str, Any]:
    """Run ``pt`` into ``out_dir``: its resolved level first (``level.toml``) with a
    ``running`` record, then the run's outputs, then its final record. Returns the record.
    Never raises for the run itself: an exception is the record's ``failed`` and its
    reason; a signal while simulating ends the run early and is ``interrupted``."""
    from chainfountain.headless import RunSummary, run_and_record

    _clear(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    atomic.write_text(out_dir / points.LEVEL, pt.level_text)
    points.write(out_dir, points.record(pt, "running"))
    t0 = time.perf_counter()
    try:
        level = io.loads(pt.level_text, f"{pt.id} ({pt.key})")
        path, _ = run_and_record(level, out_dir, pt.duration, progress=False, snapshot=snapshot)
        summary = json.loads(path.read_text())
    except Exception as exc:  # noqa: BLE001 - recorded with its reason; the sweep goes on
        rec = points.record(pt, "failed", f"{type(exc).__name__}: {exc}",
                            wall_s=time.perf_counter() - t0)
        points.write(out_dir, rec)
        return rec
    ended = RunSummary.from_json(summary).ended_early
    status, extra = "done", {}
    if ended is not None and ended.cause == "interrupted":
        status, extra = "interrupted", {"signal": ended.signal_number}
    elif ended is not None:
        status = "ended_early"
    rec = points.record(pt, status, ended.reason if ended is not None else "",
                        wall_s=time.perf_counter() - t0, results=flatten(summary), **extra)
    points.write(out_dir, rec)
    return rec


def run_point_shipped(pt: Planned, snapshot: bool = False) -> tuple[dict, dict[str, bytes]]:
    """Run ``pt`` on a cluster's worker: the outputs are made in a temporary folder there
    and come back with the record as ``(record, {file name: bytes})``, so the workers
    need no shared disk."""
    import tempfile

    with tempfile.TemporaryDirectory(prefix="chainfountain-point-") as tmp:
        out_dir = Path(tmp) / "point"
        rec = run_point(pt, out_dir, snapshot)
        files = {f.name: f.read_bytes() for f in sorted(out_dir.iterdir())
                 if f.is_file() and f.name != points.RECORD}
    return rec, files


def store(out_dir: Path, rec: dict[str, Any], files: dict[str, bytes]) -> None:
    """Write a point that ran elsewhere: its outputs, each atomically, then its record."""
    _clear(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    for name, data in files.items():
        atomic.write_bytes(out_dir / name, data)
    points.write(out_dir, rec)
