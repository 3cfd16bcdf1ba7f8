"""Studies: a run as a Python call (``chainfountain.study.run``) and ``chainfountain sweep``
(a level over a grid of fields, in parallel, resumable, into a Parquet and CSV table)."""

from __future__ import annotations

import csv
import subprocess
import sys

import pytest

from chainfountain.level.model import LevelError
from chainfountain.study import run, with_changes
from chainfountain.study.api import load


def _cli(*args: str, cwd=None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "chainfountain", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=600)


def test_run_returns_summary_series_and_paths(tmp_path):
    r = run("wide_low", duration=0.3, changes={"feed.speed": 4.5}, out=tmp_path / "o")
    assert r.ok and r.level.sim.feed.speed == 4.5
    assert r.summary["theory"]["v"] == 4.5 and r.error("h") is not None
    assert len(r.series["t"]) == len(r.series["speed_mean"]) > 10
    assert r.paths["summary.json"].is_file() and r.paths["speed.csv"].is_file()


@pytest.mark.parametrize("changes, words", [
    ({"feed.sped": 4.5}, ["feed.sped", "unknown key", "speed"]),
    ({"feed.speed": 1.0}, ["feed.speed", "1.0", "allowed"]),
    ({"carts[3].mass": 1.0}, ["carts[3].mass", "index below 0"]),
    ({"feed speed": 1.0}, ["not a field path"]),
])
def test_changes_are_validated_as_a_level_file(changes, words):
    with pytest.raises(LevelError) as exc:
        with_changes(load("wide_low"), changes)
    for w in words:
        assert w in str(exc.value), (w, str(exc.value))


def test_sweep_runs_records_refusals_and_resumes(tmp_path):
    (tmp_path / "s.toml").write_text(
        'base = "wide_low"\nduration = 0.2\n[grid]\n"feed.speed" = [2.0, 4.0, 4.5]\n')
    r = _cli("sweep", "s.toml", "--jobs", "2", "--out", "out", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "2 done, 1 refused" in r.stdout and "p00000 refused: " in r.stdout
    assert "feed.speed: 2.0 m/s cannot make a fountain" in r.stdout
    rows = list(csv.DictReader((tmp_path / "out" / "results.csv").open()))
    assert [row["status"] for row in rows] == ["refused", "done", "done"]
    assert [float(row["feed.speed"]) for row in rows] == [2.0, 4.0, 4.5]
    assert float(rows[1]["theory_v"]) == 4.0 and rows[1]["theory_rel_error_h"]
    import pyarrow.parquet as pq

    table = pq.read_table(tmp_path / "out" / "results.parquet")
    assert table.num_rows == 3 and "theory_rel_error_h" in table.column_names
    assert (tmp_path / "out" / "results.png").is_file()
    # a rerun runs nothing and rewrites the same table
    r2 = _cli("sweep", "s.toml", "--out", "out", "--quiet", cwd=tmp_path)
    assert r2.returncode == 0 and "3 recorded before, 0 to run" in r2.stderr
    assert list(csv.DictReader((tmp_path / "out" / "results.csv").open())) == rows


def test_a_sweep_never_resumes_into_another_sweeps_runs(tmp_path):
    """Points are recorded by their place in the grid: a changed grid (or duration) run
    into the same folder would read the old runs as its own. It is refused with one line,
    and the folder is left as it was."""
    (tmp_path / "s.toml").write_text(
        'base = "wide_low"\nduration = 0.2\n[grid]\n"feed.speed" = [4.0, 4.5]\n')
    assert _cli("sweep", "s.toml", "--out", "out", "--quiet", cwd=tmp_path).returncode == 0
    table = (tmp_path / "out" / "results.csv").read_text()
    (tmp_path / "s.toml").write_text(
        'base = "wide_low"\nduration = 0.2\n[grid]\n"feed.speed" = [4.2, 4.5]\n')
    r = _cli("sweep", "s.toml", "--out", "out", "--quiet", cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    msg = r.stderr.strip().splitlines()[-1]
    for w in ("another sweep", "p00000", "feed.speed", "4.0", "4.2", "--out"):
        assert w in msg, (w, msg)
    assert (tmp_path / "out" / "results.csv").read_text() == table
    (tmp_path / "s.toml").write_text(
        'base = "wide_low"\nduration = 0.3\n[grid]\n"feed.speed" = [4.0, 4.5]\n')
    r = _cli("sweep", "s.toml", "--out", "out", "--quiet", cwd=tmp_path)
    assert r.returncode == 2 and "duration = 0.2 there, 0.3 here" in r.stderr


@pytest.mark.parametrize("text, words", [
    ('base = "wide_low"\n', ["grid", "missing or empty"]),
    ('base = "wide_low"\nspeed = 3\n[grid]\n"feed.speed" = [4.0]\n', ["speed", "unknown key"]),
    ('base = "nope"\n[grid]\n"feed.speed" = [4.0]\n', ["base", "no such level"]),
    ('base = "wide_low"\n[grid]\n"feed.sped" = [4.0]\n', ["feed.sped", "unknown key"]),
    ('base = "wide_low"\n[grid]\n"feed.speed" = 4.0\n', ["grid.feed.speed", "non-empty list"]),
    ('base = "wide_low"\nduration = -1\n[grid]\n"feed.speed" = [4.0]\n', ["duration", "-1"]),
    ('base = "falling_chain"\nseeds = [1]\n[grid]\n"scene.length" = [1.0]\n',
     ["seeds", "no effect"]),
    ('base = "wide_low"\n[grid\n', ["not valid TOML"]),
])
def test_bad_sweep_files_one_line_and_nothing_written(tmp_path, text, words):
    (tmp_path / "s.toml").write_text(text)
    r = _cli("sweep", "s.toml", "--out", "out", cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    for w in words:
        assert w in r.stderr, (w, r.stderr)
    assert not (tmp_path / "out").exists()


def test_a_sweep_runs_on_a_dask_cluster_as_it_does_locally(tmp_path):
    """A real local cluster (two worker processes, no shared folder used): the points run on
    the workers, come back with their outputs, and the table matches a local run of the same
    sweep to the last digit (the same level, the same steps)."""
    distributed = pytest.importorskip("distributed")
    from chainfountain.study import sweep as sw

    (tmp_path / "s.toml").write_text(
        'base = "wide_low"\nduration = 0.2\n[grid]\n"feed.speed" = [2.0, 4.0, 4.5]\n')
    spec = sw.load(tmp_path / "s.toml")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        rows = sw.execute(spec, tmp_path / "dask", dask=cluster.scheduler_address)
    local = sw.execute(spec, tmp_path / "local", jobs=1)
    assert [r["status"] for r in rows] == ["refused", "done", "done"]
    for a, b in zip(rows, local, strict=True):
        assert a["status"] == b["status"]
        if a["status"] == "done":
            assert a["speed_mean"] == b["speed_mean"] and a["h"] == b["h"]
    for pid in ("p00001", "p00002"):
        d = tmp_path / "dask" / "points" / pid
        assert (d / "summary.json").is_file() and (d / "tensions.csv").is_file()
        assert (d / "point.json").is_file()
    assert (tmp_path / "dask" / "results.parquet").is_file()


def test_an_unreachable_scheduler_is_one_clear_message(tmp_path):
    pytest.importorskip("distributed")
    (tmp_path / "s.toml").write_text(
        'base = "wide_low"\nduration = 0.2\n[grid]\n"feed.speed" = [4.0]\n')
    r = _cli("sweep", "s.toml", "--out", "out", "--quiet", "--dask", "tcp://127.0.0.1:9",
             cwd=tmp_path)
    assert r.returncode == 2, (r.returncode, r.stderr)
    err = r.stderr.strip().splitlines()
    assert "cannot reach a Dask scheduler at 'tcp://127.0.0.1:9'" in err[-1]
    assert "Traceback" not in r.stderr


def test_a_scene_runs_as_a_call_and_sweeps_over_seeds(tmp_path):
    """A scene level through the same doors: the Python call gives each probe's columns,
    and a sweep over seeds gives one row per seed with the closed form's figure."""
    r = run("falling_chain", duration=0.05, out=tmp_path / "o")
    assert r.ok and r.summary["kind"] == "scene"
    assert len(r.series["t"]) == len(r.series["free_end.vy"]) == 100
    assert r.paths["probe_free_end.csv"].is_file()
    (tmp_path / "s.toml").write_text('base = "chain_on_scale"\nduration = 0.35\nseeds = [1, 2]\n'
                                     '[grid]\n"scene.jitter" = [0.05]\n')
    out = _cli("sweep", "s.toml", "--jobs", "2", "--out", "out", "--quiet", cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    rows = list(csv.DictReader((tmp_path / "out" / "results.csv").open()))
    assert [row["status"] for row in rows] == ["done", "done"]
    assert [int(row["seed"]) for row in rows] == [1, 2]
    errors = [float(row["closed_form_force_rel_error"]) for row in rows]
    assert errors[0] != errors[1] and all(abs(e) < 0.2 for e in errors)
    assert (tmp_path / "out" / "results.png").is_file()
