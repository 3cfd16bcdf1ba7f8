"""A sweep stopped by a signal, or by losing its workers: it ends within seconds with all
its processes, records the points that were running as interrupted, writes the table for
the finished ones, and a rerun runs exactly the points that did not finish.

The sweeps run as real ``chainfountain sweep`` processes in a session of their own, so
every process they start (loky workers, resource trackers) is found by its session id,
wherever it was re-parented; whatever is left is killed when the test ends."""

from __future__ import annotations

import contextlib
import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

SWEEP = 'base = "wide_low"\nduration = 10.0\n[grid]\n"feed.speed" = [4.0, 4.2, 4.4, 4.6]\n'
"""Four points of about two seconds of wall time each: long enough that the point seen
running is still running when the signal arrives (with points of under a second, a
loaded machine finished it in between and the table had nothing interrupted)."""
WAIT = 120.0
"""Seconds a step may take at most (a loaded machine), before the test gives up."""


def _session(sid: int) -> list[int]:
    """The processes of session ``sid`` that are still alive (zombies aside)."""
    found = []
    for d in Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        try:
            stat = (d / "stat").read_text()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2:].split()
        if int(fields[3]) == sid and fields[0] != "Z":
            found.append(int(d.name))
    return found


def _records(out: Path) -> list[dict]:
    recs = []
    for f in (out / "points").glob("*/point.json"):
        with contextlib.suppress(OSError, ValueError):
            recs.append(json.loads(f.read_text()))
    return recs


def _until(what: str, check, timeout: float = WAIT):
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        value = check()
        if value:
            return value
        time.sleep(0.05)
    raise AssertionError(f"timed out waiting for {what}")


@contextlib.contextmanager
def _sweep(tmp_path: Path, *args: str):
    """A ``chainfountain sweep`` process in a new session; killed with its session at the
    end whatever happens."""
    (tmp_path / "s.toml").write_text(SWEEP)
    proc = subprocess.Popen([sys.executable, "-m", "chainfountain", "sweep", "s.toml",
                             "--out", "out", "--quiet", *args], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    try:
        yield proc
    finally:
        for pid in _session(proc.pid):
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
        with contextlib.suppress(subprocess.TimeoutExpired):
            proc.communicate(timeout=10)


def _stop_midway(tmp_path: Path, sig: signal.Signals, group: bool) -> tuple[int, str, list]:
    """Run the sweep on two workers, send ``sig`` (to the process, or to its whole group
    as Ctrl-C does) once one point is done and another running; the exit status, the
    last line on stderr and the table's rows."""
    with _sweep(tmp_path, "--jobs", "2") as proc:
        out = tmp_path / "out"
        # a point done, then one that started after it: the point seen running has just
        # begun (one running since the start may be finishing as the signal is sent)
        first = _until("a point done", lambda: [r for r in _records(out)
                                                 if r["status"] == "done"] or None)
        early = {r["key"] for r in _records(out) if r["status"] == "running"}
        early |= {r["key"] for r in first}
        _until("a later point running", lambda: any(
            r["status"] == "running" and r["key"] not in early for r in _records(out)))
        (os.killpg if group else os.kill)(proc.pid, sig)
        _, err = proc.communicate(timeout=WAIT)
        # every process of the sweep ends with it (workers, resource trackers)
        _until("the sweep's processes to end", lambda: not _session(proc.pid), timeout=30)
    rows = list(csv.DictReader((tmp_path / "out" / "results.csv").open()))
    return proc.returncode, err.strip().splitlines()[-1], rows


@pytest.mark.slow
def test_sigterm_ends_the_sweep_and_its_workers_and_a_rerun_finishes_it(tmp_path):
    status, last, rows = _stop_midway(tmp_path, signal.SIGTERM, group=False)
    assert status == 143, last
    assert last.startswith("chainfountain: error: interrupted by SIGTERM"), last
    done = {r["key"] for r in rows if r["status"] == "done"}
    stopped = {r["key"] for r in rows if r["status"] == "interrupted"}
    assert done and stopped and {r["status"] for r in rows} <= {"done", "interrupted"}
    assert all(r["reason"] == "interrupted by SIGTERM" for r in rows if r["key"] in stopped)
    before = {r["key"]: r["wall_s"] for r in rows if r["key"] in done}
    r = subprocess.run([sys.executable, "-m", "chainfountain", "sweep", "s.toml", "--out",
                        "out", "--quiet", "--jobs", "2"], cwd=tmp_path, capture_output=True,
                       text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert f"{len(done)} recorded before, {4 - len(done)} to run" in r.stderr, r.stderr
    rows = list(csv.DictReader((tmp_path / "out" / "results.csv").open()))
    assert [row["status"] for row in rows] == ["done"] * 4
    # the finished points were not run again; the interrupted ones were
    assert {row["key"]: row["wall_s"] for row in rows if row["key"] in done} == before


@pytest.mark.slow
def test_ctrl_c_to_the_process_group_ends_the_sweep_and_its_workers(tmp_path):
    status, last, rows = _stop_midway(tmp_path, signal.SIGINT, group=True)
    assert status == 130, last
    assert last.startswith("chainfountain: error: interrupted by SIGINT"), last
    assert "interrupted" in {r["status"] for r in rows}
    assert {r["status"] for r in rows} <= {"done", "interrupted"}


def test_a_dask_cluster_whose_workers_all_die_ends_the_sweep_with_one_line(tmp_path):
    """A real LocalCluster's scheduler with two worker processes of its own (no nanny, so
    nothing restarts them), killed while they run points: the sweep waits a bounded time
    for workers, then ends with one line, the running points recorded as interrupted."""
    distributed = pytest.importorskip("distributed")
    from chainfountain.study import cluster as cl
    from chainfountain.study import sweep as sw

    (tmp_path / "s.toml").write_text(SWEEP)
    spec = sw.load(tmp_path / "s.toml")
    out = tmp_path / "out"
    with distributed.LocalCluster(n_workers=0, dashboard_address=None) as cluster:
        workers = [subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_worker", cluster.scheduler_address,
             "--no-nanny", "--nthreads", "1", "--no-dashboard"], cwd=tmp_path,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
            for _ in range(2)]
        try:
            import threading

            def kill_when_running() -> None:
                _until("points running on the workers",
                       lambda: sum(r["status"] == "running" for r in _records(out)) >= 1)
                for w in workers:
                    w.kill()

            killer = threading.Thread(target=kill_when_running, daemon=True)
            killer.start()
            t0 = time.monotonic()
            with pytest.raises(sw.Stopped) as stopped:
                sw.execute(spec, out, dask=cluster.scheduler_address, wait_for_workers=3.0)
            assert time.monotonic() - t0 < WAIT
        finally:
            for w in workers:
                w.kill()
                w.wait(timeout=30)
    msg = str(stopped.value)
    assert "\n" not in msg and stopped.value.status == 5
    assert "has had no workers for 3 s" in msg, msg
    recs = _records(out)
    assert "interrupted" in {r["status"] for r in recs}
    assert "running" not in {r["status"] for r in recs}
    assert cl.NO_WORKERS_WAIT > 3.0
