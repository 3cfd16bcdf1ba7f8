"""Parameter sweeps: one level, fixed changes and a grid of field values (and seeds), run in
parallel into a table.

The sweep file is :mod:`chainfountain.study.sweep_file`; its points and their identity
:mod:`chainfountain.study.points` (a hash of each point's resolved level, duration and
software version, so a rerun reuses exactly the points that would run the same). Points
run in one process per job (:mod:`joblib`, ``loky`` backend: the workers stay, so imports
are paid once per worker) or on a Dask cluster (:mod:`chainfountain.study.cluster`); each
writes its outputs into ``OUT/points/<key>/`` atomically, its record last. The table of
results, one row per point (the swept fields, seed, status, reason, key, version and every
number of its ``summary.json`` with the paper's prediction and relative errors), is
``results.parquet`` (``pandas.read_parquet`` or ``polars.read_parquet``) and
``results.csv``, with ``results.png`` (:mod:`chainfountain.study.table`).

SIGINT or SIGTERM ends a sweep within seconds: its workers are stopped, the points they
were running recorded ``interrupted`` (a rerun runs them), the table written for the
points that finished, and :class:`Stopped` raised with the exit status 130 or 143.
"""

from __future__ import annotations

import contextlib
import signal
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path

from chainfountain import atomic
from chainfountain.errors import UserError
from chainfountain.headless.stepping import Interrupted, _signals_deferred
from chainfountain.study import points
from chainfountain.study.cluster import ClusterLost, run_on_cluster
from chainfountain.study.points import STATUS, Planned, plan
from chainfountain.study.sweep_file import KEYS, MAX_POINTS, Sweep, load
from chainfountain.study.table import figure, flatten, write_table
from chainfountain.study.worker import run_point

__all__ = ["KEYS", "MAX_POINTS", "STATUS", "Planned", "Stopped", "Sweep", "collect",
           "execute", "figure", "flatten", "interruptible", "load", "pending", "plan",
           "write_table"]


class Stopped(UserError):
    """A sweep that ended before all its points ran (a signal, a lost worker, a cluster
    without workers); its table is written. ``status`` is the command's exit status."""

    def __init__(self, message: str, status: int, rows: list[dict]) -> None:
        super().__init__(message)
        self.status, self.rows = status, rows


_received: list[int] = []
"""The signals :func:`interruptible` has taken (a worker that died of the same Ctrl-C is
the signal's doing, not a lost worker)."""


@contextlib.contextmanager
def interruptible() -> Iterator[None]:
    """While a sweep runs, SIGINT and SIGTERM raise
    :class:`~chainfountain.headless.stepping.Interrupted` in the main thread (a run
    simulating there catches it itself and ends early)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum: int, frame: object) -> None:
        _received.append(signum)
        raise Interrupted(signum)

    _received.clear()
    old = {sig: signal.signal(sig, handler) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for sig, h in old.items():
            signal.signal(sig, h)


def pending(sweep: Sweep, out: Path, retry_failed: bool = False,
            planned: list[Planned] | None = None) -> tuple[list[Planned], int]:
    """The points still to run and how many are already recorded (or refused: nothing
    runs for those). A point counts as recorded only under its own key."""
    planned = plan(sweep) if planned is None else planned
    todo = [pt for pt in planned if not pt.refused
            and not points.reusable(points.read(out, pt), retry_failed)]
    return todo, len(planned) - len(todo)


def collect(sweep: Sweep, out: Path, planned: list[Planned] | None = None) -> list[dict]:
    """The rows of every point recorded (or refused), in the sweep's order."""
    rows = []
    for pt in plan(sweep) if planned is None else planned:
        rec = None if pt.refused else points.read(out, pt)
        if pt.refused or rec is not None:
            rows.append(points.row(pt, rec))
    return rows


def _local(todo: list[Planned], out: Path, jobs: int, snapshots: bool) -> Iterator[dict]:
    if jobs == 1:
        for pt in todo:
            rec = run_point(pt, points.folder(out, pt), snapshots)
            yield rec
            if rec["status"] == "interrupted" and rec.get("signal"):
                raise Interrupted(int(rec["signal"]))  # the run took this process's signal
        return
    import sys

    from joblib import Parallel, delayed

    # workers stopped mid-point leave their queues' semaphores to the resource tracker,
    # which removes them and would warn about it on the terminal: not the user's concern
    quiet = "ignore::UserWarning:multiprocessing.resource_tracker"
    if quiet not in sys.warnoptions:
        sys.warnoptions.append(quiet)
    # one point per dispatch: a point runs for seconds, so batching saves nothing and
    # leaves a worker idle at the end while another runs its batch
    results = Parallel(n_jobs=jobs, backend="loky", return_as="generator_unordered",
                       batch_size=1)(
        delayed(run_point)(pt, points.folder(out, pt), snapshots) for pt in todo)
    try:
        yield from results
    finally:
        results.close()  # on an exception: joblib stops the workers now


def execute(sweep: Sweep, out: Path, jobs: int = 1, *, retry_failed: bool = False,
            progress: Callable[[int, int, float], None] | None = None,
            dask: str | None = None, planned: list[Planned] | None = None,
            wait_for_workers: float | None = None) -> list[dict]:
    """Run every pending point, ``jobs`` processes at a time (or on the Dask cluster whose
    scheduler is at ``dask``); then write the results table. ``progress(done, total,
    seconds_left)`` after each point. Returns the rows; raises :class:`Stopped` (the table
    written) when a signal or a lost worker ended the sweep early. Call it inside
    :func:`interruptible` for signals to end it so. ``wait_for_workers``: seconds a Dask
    cluster may have no worker before the sweep ends
    (:data:`~chainfountain.study.cluster.NO_WORKERS_WAIT`)."""
    from joblib.externals.loky.process_executor import TerminatedWorkerError

    planned = plan(sweep) if planned is None else planned
    todo, done = pending(sweep, out, retry_failed, planned)
    out.mkdir(parents=True, exist_ok=True)
    atomic.write_text(out / "sweep.toml", sweep.path.read_bytes().decode("utf-8-sig"))
    total = done + len(todo)
    t0 = time.perf_counter()
    stop: tuple[str, int] | None = None
    lost_cluster = ""
    try:
        if todo:
            results = (run_on_cluster(todo, out, dask, sweep.snapshots, wait_for_workers)
                       if dask is not None
                       else _local(todo, out, jobs, sweep.snapshots))
            for k, _ in enumerate(results, start=1):
                if progress is not None:
                    per = (time.perf_counter() - t0) / k
                    progress(done + k, total, per * (len(todo) - k))
    except Interrupted as exc:
        stop = (f"interrupted by {signal.Signals(exc.signum).name}", 128 + exc.signum)
    except TerminatedWorkerError as exc:
        if _received:  # the workers took the same Ctrl-C as this process
            stop = (f"interrupted by {signal.Signals(_received[0]).name}", 128 + _received[0])
        else:
            stop = (f"a worker process died ({str(exc).splitlines()[0][:160]})", 5)
    except ClusterLost as exc:
        stop, lost_cluster = ("its Dask cluster lost its workers", 5), str(exc)
    with _signals_deferred([]):  # a second signal: noted, the table is written whole
        if stop:
            points.mark_interrupted(out, todo, stop[0])
        rows = collect(sweep, out, planned)
        write_table(rows, out)
    if stop is not None:
        finished = sum(r["status"] not in ("interrupted", "refused") for r in rows)
        keys = {pt.key for pt in todo}
        lost = sum(r["status"] == "interrupted" and r["key"] in keys for r in rows)
        not_run = sum(pt.key not in {r["key"] for r in rows} for pt in todo)
        if lost_cluster:
            raise Stopped(f"{lost_cluster}; the table holds the {finished} finished points",
                          stop[1], rows)
        raise Stopped(f"{stop[0]}: the table holds the {finished} finished points; "
                      f"{lost} interrupted and {not_run} not run, which a rerun of the "
                      "sweep runs", stop[1], rows)
    return rows
