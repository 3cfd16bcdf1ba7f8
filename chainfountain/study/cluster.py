"""A sweep's points on a Dask cluster (``chainfountain sweep --dask ADDRESS``).

Each point goes to a worker with its resolved level; the worker runs it in a temporary
folder and sends the record and the outputs back, so no disk is shared. A worker lost
mid-point: Dask runs the point again on another worker (a point that has killed three
workers comes back as ``KilledWorker`` and is recorded ``interrupted``). When the
cluster has had no worker for :data:`NO_WORKERS_WAIT` seconds the sweep ends with one
line, the points that were running recorded ``interrupted``.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from pathlib import Path

from chainfountain.errors import UserError
from chainfountain.study import points
from chainfountain.study.points import Planned
from chainfountain.study.worker import run_point_shipped, store

NO_WORKERS_WAIT = 30.0
"""Seconds a sweep waits for a cluster without workers before it ends."""
POLL = 0.2
"""Seconds between looks at the cluster while the points run."""


class ClusterLost(UserError):
    """The cluster has had no worker for :data:`NO_WORKERS_WAIT` seconds."""


def _connect(address: str):
    try:
        from distributed import Client
    except ImportError as exc:
        raise UserError("--dask needs the 'distributed' package: pip install "
                        "'chainfountain[cluster]'") from exc
    try:
        return Client(address, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise UserError(f"--dask: cannot reach a Dask scheduler at {address!r} ({exc}); "
                        "allowed: the address 'dask scheduler' prints, tcp://HOST:8786") \
            from exc


def _workers(client) -> tuple[int, set[str]]:
    """How many workers the cluster has and which tasks they are running."""
    try:
        running = client.processing()
        return len(client.nthreads()), {k for keys in running.values() for k in keys}
    except Exception:  # noqa: BLE001 - a scheduler that does not answer has no workers
        return 0, set()


def run_on_cluster(todo: list[Planned], out: Path, address: str, snapshots: bool,
                   wait: float | None = None) -> Iterator[dict]:
    """Run ``todo`` on the cluster whose scheduler is at ``address``; yield each record as
    its point is stored. :class:`UserError` when the scheduler cannot be reached,
    :class:`ClusterLost` when it has had no worker for ``wait`` seconds (default
    :data:`NO_WORKERS_WAIT`)."""
    wait = NO_WORKERS_WAIT if wait is None else wait
    client = _connect(address)
    futures = {}
    seen: set[str] = set()
    try:
        for pt in todo:
            fut = client.submit(run_point_shipped, pt, snapshots, pure=False,
                                key=f"chainfountain-point-{pt.key}")
            futures[fut] = pt
        left = set(futures)
        alone_since: float | None = None
        while left:
            done = {f for f in left if f.done()}
            left -= done
            for fut in done:
                pt = futures[fut]
                try:
                    rec, files = fut.result()
                except Exception as exc:  # noqa: BLE001 - a lost point: rerun on resume
                    killed = type(exc).__name__ == "KilledWorker"
                    rec = points.record(pt, "interrupted" if killed else "failed",
                                        f"{type(exc).__name__}: {exc}")
                    files = {}
                store(points.folder(out, pt), rec, files)
                yield rec
            if not left:
                break
            if done:
                continue
            time.sleep(POLL)
            n, running = _workers(client)
            by_key = {f.key: futures[f] for f in left}
            for key in running - seen:  # recorded here as running, as a local worker does
                if key in by_key:
                    points.write(points.folder(out, by_key[key]),
                                 points.record(by_key[key], "running"))
            seen |= running
            if n:
                alone_since = None
            elif alone_since is None:
                alone_since = time.monotonic()
            elif time.monotonic() - alone_since >= wait:
                pending = [futures[f] for f in left]
                lost = points.mark_interrupted(
                    out, pending, f"the Dask cluster at {address} lost its workers")
                raise ClusterLost(
                    f"--dask: the cluster at {address!r} has had no workers for {wait:g} s; "
                    f"{lost} running points recorded as interrupted, {len(pending) - lost} "
                    "not run: start workers and run the sweep again to run them")
    finally:
        for fut in futures:
            fut.cancel()
        client.close()
