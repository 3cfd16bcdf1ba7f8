"""Parameter sweeps: one level, a grid of field values (and seeds), run in parallel.

A sweep file (TOML)::

    base = "paper_tall"          # a level name, or a path relative to the sweep file
    duration = 6.0               # simulated seconds per point (default: the level's)
    seeds = [0, 1]               # optional: every point once per seed (an apparatus or
                                 # beaker: a seed above 0 nudges the start by 1e-12)
    snapshots = false            # optional: each point's snapshot.png (0.3 s each)
    [grid]                       # every combination of these fields' values
    "feed.speed" = [5.0, 5.5, 6.0]
    "feed.launch_angle" = [1.3, 1.4]

Each point is the base level with its fields changed (validated as a level file; a
point the loader refuses is recorded as ``refused`` with its reason and nothing runs for
it). Points run in one process per job (:mod:`joblib`, ``loky`` backend: the workers
stay, so imports are paid once per worker); each writes its run's outputs (without
``snapshot.png`` unless ``snapshots = true``) into ``OUT/points/<id>/`` atomically, and
its row last (``point.json``), so a rerun skips the points already recorded (and, unless
``retry_failed``, those that failed). The table of results, one row per point (the swept
fields, seed, status, reason, and every number of its ``summary.json`` with the paper's
prediction and relative errors), is written as ``results.parquet`` (loads with
``pandas.read_parquet`` or ``polars.read_parquet``) and ``results.csv``, with
``results.png``, the vertex height's error against the first swept field.
"""

from __future__ import annotations

import csv
import io as stdio
import itertools
import json
import math
import time
import tomllib
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from chainfountain import atomic
from chainfountain.errors import UserError
from chainfountain.level import io, library
from chainfountain.level.model import Level, LevelError
from chainfountain.study.changes import with_changes

KEYS = {"base", "duration", "seeds", "grid", "snapshots"}
"""Top-level keys of a sweep file."""
MAX_POINTS = 100_000
"""Most points (grid combinations times seeds) a sweep may have."""
STATUS = ("done", "failed", "refused", "ended_early")
"""A point's status: run to its end; an exception while running; the loader refused
its level; the run ended early (a table used up, divergence; its outputs are kept)."""


@dataclass(frozen=True)
class Point:
    """One run of the sweep: its id, its field values and seed."""

    id: str
    values: dict[str, Any]
    seed: int | None


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

    def points(self) -> list[Point]:
        """Every combination of the grid's values, once per seed, in a stable order."""
        names = list(self.grid)
        out = []
        for k, (combo, seed) in enumerate(itertools.product(
                itertools.product(*(self.grid[n] for n in names)), self.seeds)):
            out.append(Point(id=f"p{k:05d}", values=dict(zip(names, combo, strict=True)),
                             seed=seed))
        return out


def _fail(where: str, key: str, msg: str) -> None:
    raise UserError(f"{where}: {key}: {msg}")


def load(path: str | Path) -> Sweep:
    """Read and check a sweep file (:class:`~chainfountain.errors.UserError`, one line
    naming the file, the key and what is allowed, for anything wrong)."""
    p = Path(path)
    where = str(p)
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except OSError as exc:
        raise UserError(f"{where}: cannot read ({exc.strerror or exc})") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise UserError(f"{where}: not valid TOML ({exc})") from None
    unknown = sorted(set(data) - KEYS)
    if unknown:
        _fail(where, unknown[0], f"unknown key; allowed keys: {', '.join(sorted(KEYS))}")
    if not isinstance(data.get("base"), str) or not data["base"].strip():
        _fail(where, "base", f"{data.get('base')!r}; allowed: a level name or a path to a "
              "level file (relative to the sweep file)")
    base_arg = data["base"]
    rel = (p.parent / base_arg)
    try:
        base_path = rel if rel.suffix == ".toml" and rel.is_file() else library.resolve(base_arg)
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
    seeded = base.sim.kind in ("feed", "apparatus", "beaker") or (
        base.sim.kind == "scene" and base.sim.scene.jitter > 0)
    if not seeded and seeds != [None]:
        _fail(where, "seeds", f"{seeds!r} has no effect on {base.meta.name!r} (kind "
              f"{base.sim.kind!r}" + (", scene.jitter 0" if base.sim.kind == "scene" else "")
              + "); allowed: leave seeds out")
    grid = data.get("grid")
    if not isinstance(grid, dict) or not grid:
        _fail(where, "grid", "missing or empty; allowed: a [grid] table of field paths, each "
              "with a list of values, e.g. \"feed.speed\" = [5.0, 6.0]")
    for key, values in grid.items():
        if not isinstance(values, list) or not values:
            _fail(where, f"grid.{key}", f"{values!r}; allowed: a non-empty list of values")
        try:  # the field must exist and take the first value's type
            with_changes(base, {key: values[0]}, where=f"{where}: grid")
        except LevelError as exc:
            if "unknown key" in str(exc) or "not a field path" in str(exc) \
                    or "is not a table" in str(exc):
                raise UserError(str(exc)) from None
    snapshots = data.get("snapshots", False)
    if not isinstance(snapshots, bool):
        _fail(where, "snapshots", f"{snapshots!r}; allowed: true or false")
    n = math.prod(len(v) for v in grid.values()) * len(seeds)
    if n > MAX_POINTS:
        _fail(where, "grid", f"{n} points; allowed: at most {MAX_POINTS}")
    return Sweep(path=p, base=base, base_name=base.meta.name,
                 duration=None if duration is None else float(duration), grid=dict(grid),
                 seeds=list(seeds), snapshots=snapshots)


def run_point(base: Level, point: Point, duration: float | None, out_dir: Path,
              snapshot: bool = False) -> dict:
    """Run one point into ``out_dir`` (a fresh folder); its row of the results table.
    Never raises: a refused level or a failed run is the row's status and reason."""
    from chainfountain.headless import run_and_record

    row: dict[str, Any] = {"point": point.id, **point.values, "seed": point.seed}
    t0 = time.perf_counter()
    try:
        level = with_changes(base, point.values, where=point.id)
    except LevelError as exc:
        _finish(out_dir, row, "refused", str(exc))
        return row
    try:
        path, _ = run_and_record(level, out_dir, duration, seed=point.seed, progress=False,
                                 snapshot=snapshot)
        summary = json.loads(path.read_text())
    except Exception as exc:  # noqa: BLE001 - recorded with its reason; the sweep goes on
        _finish(out_dir, row, "failed", f"{type(exc).__name__}: {exc}")
        return row
    row.update(flatten(summary))
    ended = summary.get("ended_early")
    _finish(out_dir, row, "ended_early" if ended else "done",
            ended["reason"] if ended else "", wall=time.perf_counter() - t0)
    return row


def run_point_shipped(level_text: str, point: Point, duration: float | None,
                      snapshot: bool = False) -> tuple[dict, dict[str, bytes]]:
    """Run one point on a cluster worker: the level comes as TOML text (the worker builds
    its own space from it), the outputs are made in a temporary folder there and come back
    with the row as ``(row, {file name: bytes})``, so the workers need no shared disk."""
    import tempfile

    base = io.loads(level_text, "<sweep base>")
    with tempfile.TemporaryDirectory(prefix="chainfountain-point-") as tmp:
        out_dir = Path(tmp) / "point"
        row = run_point(base, point, duration, out_dir, snapshot)
        files = {f.name: f.read_bytes() for f in sorted(out_dir.iterdir())
                 if f.is_file() and f.name != "point.json"}
    return row, files


def _store(out_dir: Path, row: dict, files: dict[str, bytes]) -> None:
    """Write a point that ran elsewhere: its outputs, each atomically, then its row."""
    out_dir.mkdir(parents=True, exist_ok=True)
    for name, data in files.items():
        atomic.write_bytes(out_dir / name, data)
    atomic.write_text(out_dir / "point.json", json.dumps(row, indent=1, default=str) + "\n")


def _on_cluster(sweep: Sweep, todo: list[Point], out: Path, address: str) -> Iterator[dict]:
    """Run ``todo`` on the Dask cluster whose scheduler is at ``address``; yield each row as
    its point is stored. ``UserError`` when the scheduler cannot be reached."""
    try:
        from distributed import Client, as_completed
    except ImportError as exc:
        raise UserError("--dask needs the 'distributed' package: pip install "
                        "'chainfountain[cluster]'") from exc
    try:
        client = Client(address, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise UserError(f"--dask: cannot reach a Dask scheduler at {address!r} ({exc}); "
                        "allowed: the address 'dask scheduler' prints, tcp://HOST:8786") \
            from exc
    text = io.dumps(sweep.base)
    try:
        futures = {client.submit(run_point_shipped, text, pt, sweep.duration, sweep.snapshots,
                                 pure=False): pt for pt in todo}
        for fut in as_completed(futures):
            pt = futures[fut]
            try:
                row, files = fut.result()
            except Exception as exc:  # noqa: BLE001 - a lost worker: recorded, sweep goes on
                row = {"point": pt.id, **pt.values, "seed": pt.seed, "status": "failed",
                       "reason": f"{type(exc).__name__}: {exc}", "wall_s": 0.0}
                files = {}
            _store(out / "points" / pt.id, row, files)
            yield row
    finally:
        client.close()


def _finish(out_dir: Path, row: dict, status: str, reason: str, wall: float = 0.0) -> None:
    row["status"], row["reason"] = status, reason
    row.setdefault("wall_s", wall)
    out_dir.mkdir(parents=True, exist_ok=True)
    atomic.write_text(out_dir / "point.json", json.dumps(row, indent=1, default=str) + "\n")


def flatten(summary: dict[str, Any]) -> dict[str, Any]:
    """The numbers of a ``summary.json`` as flat columns (``theory.rel_error.h`` becomes
    ``theory_rel_error_h``; a list of numbers one column per item, ``vertex_0`` and
    ``vertex_1``; other lists and texts other than the level's name are left out)."""
    out: dict[str, Any] = {}

    def walk(prefix: str, obj: Any) -> None:
        if isinstance(obj, dict):
            for k, v in obj.items():
                walk(f"{prefix}_{k}" if prefix else str(k), v)
        elif isinstance(obj, list) and all(
                x is None or (isinstance(x, int | float) and not isinstance(x, bool))
                for x in obj):
            for i, x in enumerate(obj):
                out[f"{prefix}_{i}"] = x
        elif isinstance(obj, bool):
            out[prefix] = obj
        elif isinstance(obj, int | float) or obj is None:
            out[prefix] = obj

    walk("", {k: v for k, v in summary.items()
              if k not in ("outputs", "write_failed", "analysis_failed", "ended_early")})
    return out


def pending(sweep: Sweep, out: Path, retry_failed: bool = False) -> tuple[list[Point], int]:
    """The points still to run and how many are already recorded.

    A point is recorded under its place in the grid (``p00003``), so a folder that holds
    the runs of another sweep (another base, duration, grid or seeds) would be read as this
    one's: :class:`~chainfountain.errors.UserError` says so instead."""
    _check_same_sweep(sweep, out)
    todo, done = [], 0
    for pt in sweep.points():
        rec = out / "points" / pt.id / "point.json"
        if rec.is_file():
            row = json.loads(rec.read_text())
            _check_same_point(pt, row, out)
            if not (retry_failed and row.get("status") == "failed"):
                done += 1
                continue
        todo.append(pt)
    return todo, done


def _another_sweep(out: Path, what: str) -> UserError:
    return UserError(f"{out}: holds the runs of another sweep ({what}); use another --out, "
                     "or remove that folder to run this sweep there")


def _check_same_sweep(sweep: Sweep, out: Path) -> None:
    """Refuse ``out`` when the sweep file recorded there has another base or duration."""
    rec = out / "sweep.toml"
    if not rec.is_file():
        return
    try:
        old = tomllib.loads(rec.read_text(encoding="utf-8"))
        new = tomllib.loads(sweep.path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return  # the points' own records are checked one by one
    for key in ("base", "duration"):
        if old.get(key) != new.get(key):
            raise _another_sweep(out, f"{key} = {old.get(key)!r} there, {new.get(key)!r} here")


def _check_same_point(pt: Point, row: dict[str, Any], out: Path) -> None:
    """Refuse a recorded point run with other field values or another seed than ``pt``."""
    for key, value in {**pt.values, "seed": pt.seed}.items():
        if row.get(key, value) != value:
            raise _another_sweep(out, f"point {pt.id} was run with {key} = {row.get(key)!r}, "
                                      f"this sweep's has {value!r}")


def execute(sweep: Sweep, out: Path, jobs: int = 1, *, retry_failed: bool = False,
            progress: Callable[[int, int, float], None] | None = None,
            dask: str | None = None) -> list[dict]:
    """Run every pending point, ``jobs`` processes at a time (or on the Dask cluster whose
    scheduler is at ``dask``); then write the results table.
    ``progress(done, total, seconds_left)`` after each point. Returns the rows."""
    from joblib import Parallel, delayed

    todo, done = pending(sweep, out, retry_failed)
    out.mkdir(parents=True, exist_ok=True)
    atomic.write_text(out / "sweep.toml", sweep.path.read_text(encoding="utf-8"))
    total = done + len(todo)
    t0 = time.perf_counter()
    if todo:
        if dask is not None:
            results: Iterator[dict] = _on_cluster(sweep, todo, out, dask)
        elif jobs == 1:
            results = (run_point(sweep.base, pt, sweep.duration, out / "points" / pt.id,
                                 sweep.snapshots) for pt in todo)
        else:
            # one point per dispatch: a point runs for seconds, so batching saves nothing
            # and leaves a worker idle at the end while another runs its batch
            results = Parallel(n_jobs=jobs, backend="loky", return_as="generator_unordered",
                               batch_size=1)(
                delayed(run_point)(sweep.base, pt, sweep.duration, out / "points" / pt.id,
                                   sweep.snapshots)
                for pt in todo)
        for k, _ in enumerate(results, start=1):
            if progress is not None:
                per = (time.perf_counter() - t0) / k
                progress(done + k, total, per * (len(todo) - k))
    rows = collect(sweep, out)
    write_table(rows, out)
    return rows


def collect(sweep: Sweep, out: Path) -> list[dict]:
    """The recorded rows of every point, in the sweep's order."""
    rows = []
    for pt in sweep.points():
        rec = out / "points" / pt.id / "point.json"
        if rec.is_file():
            rows.append(json.loads(rec.read_text()))
    return rows


def write_table(rows: list[dict], out: Path) -> None:
    """``results.parquet`` and ``results.csv`` (each atomically), one row per point."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    cols: list[str] = []
    for r in rows:
        cols += [c for c in r if c not in cols]
    table = pa.table({c: pa.array([_cell(r.get(c)) for r in rows]) for c in cols}) \
        if rows else pa.table({})
    with atomic.atomic_path(out / "results.parquet") as tmp:
        pq.write_table(table, tmp)
    buf = stdio.StringIO()
    w = csv.DictWriter(buf, fieldnames=cols, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({c: r.get(c) for c in cols})
    atomic.write_text(out / "results.csv", buf.getvalue())


def _cell(x: Any) -> Any:
    return None if isinstance(x, float) and not math.isfinite(x) else x


def figure(sweep: Sweep, rows: list[dict], path: Path) -> Path | None:
    """The vertex height's error against the paper (a scene: its closed form's scale
    or free-end speed error) over the first swept field, one line per combination of the
    others (``None`` when no point has the figure)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    key, y_label = "theory_rel_error_h", "vertex height error against the paper (%)"
    form = sweep.base.sim.scene.closed_form if sweep.base.sim.kind == "scene" else "none"
    if form == "scale":
        key, y_label = "closed_form_force_rel_error", "scale's error against 3 lambda g y (%)"
    elif form == "folded_fall":
        key = "closed_form_speed_rel_error_2"
        y_label = "free end's speed error at 3/4 of the fall (%)"
    names = list(sweep.grid)
    x_name, others = names[0], names[1:]
    groups: dict[tuple, list[tuple[float, float, bool]]] = {}
    for r in rows:
        y, x = r.get(key), r.get(x_name)
        if r.get("status") != "done" or y is None or not isinstance(x, int | float):
            continue
        groups.setdefault(tuple(r.get(o) for o in others) + (r.get("seed"),), []).append(
            (float(x), 100.0 * float(y), r.get("steady") is not False))
    if not groups:
        return None
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=110)
    unsteady = False
    for g, pts in sorted(groups.items(), key=lambda kv: str(kv[0])):
        pts.sort()
        label = ", ".join(f"{o} = {v}" for o, v in zip([*others, "seed"], g, strict=True)
                          if v is not None)
        (line,) = ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", label=label or None)
        for x, y, steady in pts:
            ax.plot([x], [y], "o", color=line.get_color(),
                    markerfacecolor=line.get_color() if steady else "none")
            unsteady |= not steady
    ax.axhline(0.0, color="0.5", lw=0.8)
    ax.set_xlabel(x_name)
    ax.set_ylabel(y_label)
    run = f"{sweep.duration:g} s per point" if sweep.duration else "the level's duration"
    ax.set_title(f"sweep of {sweep.base_name} ({run}"
                 + ("; hollow: never steady" if unsteady else "") + ")", fontsize=10)
    if len(groups) > 1:
        ax.legend(fontsize=7)
    fig.tight_layout()
    with atomic.atomic_path(path) as tmp:
        fig.savefig(tmp, format="png")
    plt.close(fig)
    return path
