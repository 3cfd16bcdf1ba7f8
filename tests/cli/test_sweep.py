"""Studies: a run as a Python call (``chainfountain.study.run``) and ``chainfountain sweep``
(a level over a grid of fields, in parallel, resumable, into a Parquet and CSV table)."""

from __future__ import annotations

import csv
import json
import subprocess
import sys

import pytest

import chainfountain
from chainfountain.level import io
from chainfountain.level.model import LevelError
from chainfountain.study import run, with_changes
from chainfountain.study.api import load
from tests import shipped


class _InProcess:
    """``chainfountain ARGS`` run in this process (no interpreter to start: a sweep of
    single-process points costs its runs only), with its exit status and output."""

    def __init__(self, capsys, monkeypatch, cwd) -> None:
        self.capsys, self.monkeypatch, self.cwd = capsys, monkeypatch, cwd

    def __call__(self, *args: str) -> subprocess.CompletedProcess:
        from chainfountain.cli import main

        self.monkeypatch.chdir(self.cwd)
        self.capsys.readouterr()
        try:
            status = main(list(args))
        except SystemExit as exc:  # argparse's refusals
            status = exc.code
        out = self.capsys.readouterr()
        return subprocess.CompletedProcess(args, status, out.out, out.err)


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
    assert r2.returncode == 0 and "1 refused, 2 recorded before, 0 to run" in r2.stderr
    assert list(csv.DictReader((tmp_path / "out" / "results.csv").open())) == rows


def _statuses(out) -> dict[str, str]:
    """Each point's key and status as the table has them."""
    return {row["key"]: row["status"] for row in csv.DictReader((out / "results.csv").open())}


def test_a_rerun_reuses_exactly_the_points_that_would_run_the_same(tmp_path, capsys,
                                                                    monkeypatch):
    """Points are identified by a hash of what they run: an extended grid runs only its new
    point, an edited base level (gravity) runs every point again and gives other numbers,
    a grid over a field that was fixed gets its column; nothing is reused by its place."""
    sweep = _InProcess(capsys, monkeypatch, tmp_path)
    base = shipped.path("wide_low").read_text()
    (tmp_path / "mine.toml").write_text(base)
    (tmp_path / "s.toml").write_text(
        'base = "mine.toml"\nduration = 0.2\n[grid]\n"feed.speed" = [4.0, 4.5]\n')
    assert sweep("sweep", "s.toml", "--jobs", "1", "--out", "out", "--quiet").returncode == 0
    first = list(csv.DictReader((tmp_path / "out" / "results.csv").open()))
    (tmp_path / "s.toml").write_text(
        'base = "mine.toml"\nduration = 0.2\n[grid]\n"feed.speed" = [4.0, 4.2, 4.5]\n')
    r = sweep("sweep", "s.toml", "--jobs", "1", "--out", "out", "--quiet")
    assert r.returncode == 0 and "2 recorded before, 1 to run" in r.stderr, r.stderr
    rows = list(csv.DictReader((tmp_path / "out" / "results.csv").open()))
    assert [row["point"] for row in rows] == ["p00000", "p00001", "p00002"]
    assert (rows[0], rows[2]) == (first[0], {**first[1], "point": "p00002"})
    # the base level edited: gravity 9.81 -> 9.0, every point runs again
    (tmp_path / "mine.toml").write_text(base.replace("gravity = 9.81", "gravity = 9.0"))
    r = sweep("sweep", "s.toml", "--jobs", "1", "--out", "out", "--quiet")
    assert r.returncode == 0 and "0 recorded before, 3 to run" in r.stderr, r.stderr
    edited = list(csv.DictReader((tmp_path / "out" / "results.csv").open()))
    assert {row["key"] for row in edited}.isdisjoint(row["key"] for row in rows)
    assert edited[0]["h"] != rows[0]["h"]
    level = io.load(tmp_path / "out" / "points" / edited[0]["key"] / "level.toml")
    assert level.sim.gravity == 9.0 and level.sim.feed.speed == 4.0
    record = json.loads((tmp_path / "out" / "points" / edited[0]["key"] / "point.json")
                        .read_text())
    assert record["version"].startswith(f"chainfountain {chainfountain.__version__}")
    assert edited[0]["version"] == record["version"] and record["duration"] == 0.2
    # gravity swept: its own column, and only the new value runs
    (tmp_path / "s.toml").write_text('base = "mine.toml"\nduration = 0.2\n[grid]\n'
                                     '"feed.speed" = [4.0]\n"gravity" = [9.0, 3.0]\n')
    r = sweep("sweep", "s.toml", "--jobs", "1", "--out", "out", "--quiet")
    assert r.returncode == 0 and "1 recorded before, 1 to run" in r.stderr, r.stderr
    swept = list(csv.DictReader((tmp_path / "out" / "results.csv").open()))
    assert [float(row["gravity"]) for row in swept] == [9.0, 3.0]
    assert swept[0]["h"] == edited[0]["h"] and swept[1]["h"] != edited[0]["h"]
    # another duration: another run
    (tmp_path / "s.toml").write_text(
        'base = "mine.toml"\nduration = 0.25\n[grid]\n"feed.speed" = [4.0]\n')
    r = sweep("sweep", "s.toml", "--jobs", "1", "--out", "out", "--quiet")
    assert r.returncode == 0 and "0 recorded before, 1 to run" in r.stderr, r.stderr


@pytest.mark.slow
def test_fixed_changes_list_items_and_a_sweep_over_seeds_alone(tmp_path):
    """[changes] sets a field in every point without a one-value list; a grid can sweep a
    field inside an array of tables (a pin's release time); seeds alone make a sweep."""
    (tmp_path / "s.toml").write_text(
        'base = "falling_chain"\nduration = 0.12\n[changes]\n"scene.closed_form" = "none"\n'
        '[grid]\n"scene.pins[0].release" = [0.0, 0.05]\n"scene.probes[0].point" = [-1, 50]\n')
    r = _cli("sweep", "s.toml", "--jobs", "1", "--out", "out", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows = list(csv.DictReader((tmp_path / "out" / "results.csv").open()))
    assert [(row["scene.pins[0].release"], row["scene.probes[0].point"]) for row in rows] == [
        ("0.0", "-1"), ("0.0", "50"), ("0.05", "-1"), ("0.05", "50")]
    assert {row["status"] for row in rows} == {"done"}
    # the pin let go: its force is zero from 0.05 s on, so its mean is below the held one's
    held, let_go = float(rows[0]["probes_fixed_end_columns_F_mean"]), \
        float(rows[2]["probes_fixed_end_columns_F_mean"])
    assert let_go < held
    level = io.load(tmp_path / "out" / "points" / rows[2]["key"] / "level.toml")
    assert level.sim.scene.pins[0].release == 0.05 and level.sim.scene.closed_form == "none"
    (tmp_path / "seeds.toml").write_text('base = "chain_on_scale"\nduration = 0.05\n'
                                         'seeds = [1, 2]\n')
    r = _cli("sweep", "seeds.toml", "--jobs", "1", "--out", "so", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows = list(csv.DictReader((tmp_path / "so" / "results.csv").open()))
    assert [(row["seed"], row["status"]) for row in rows] == [("1", "done"), ("2", "done")]


def test_a_sweep_whose_points_are_all_refused_exits_2_with_one_line(tmp_path):
    (tmp_path / "s.toml").write_text(
        'base = "wide_low"\nduration = 0.2\n[grid]\n"feed.speed" = [1.0, 2.0]\n')
    r = _cli("sweep", "s.toml", "--out", "out", "--quiet", cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    last = r.stderr.strip().splitlines()[-1]
    assert last.startswith("chainfountain: error: every point of the sweep was refused"), last
    assert "feed.speed" in last


def test_a_sweep_whose_points_all_fail_exits_5_with_one_line(tmp_path, monkeypatch, capsys):
    """A run that raises is recorded as failed; when no point gives a result the sweep
    says so in one line and exits 5 (run in this process, its runs made to raise)."""
    import chainfountain.headless as headless
    from chainfountain.cli import main

    def broken(*args, **kwargs):
        raise RuntimeError("no memory left")

    monkeypatch.setattr(headless, "run_and_record", broken)
    (tmp_path / "s.toml").write_text(
        'base = "wide_low"\nduration = 0.2\n[grid]\n"feed.speed" = [4.0, 4.5]\n')
    status = main(["sweep", str(tmp_path / "s.toml"), "--jobs", "1", "--out",
                   str(tmp_path / "out"), "--quiet"])
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 5
    assert err[-1] == "chainfountain: error: no point of the sweep gave a result (2 failed)"


def test_a_grid_of_mixed_types_is_refused_when_the_file_is_read(tmp_path):
    (tmp_path / "s.toml").write_text(
        'base = "wide_low"\nduration = 0.2\n[grid]\n"feed.speed" = [4.0, "x"]\n')
    r = _cli("sweep", "s.toml", "--out", "out", cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    for w in ("grid.feed.speed", "value 2 of 2", "'x' is not allowed", "a number"):
        assert w in r.stderr, (w, r.stderr)
    assert not (tmp_path / "out").exists()


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
    ('base = "wide_low"\n[grid]\n"meta.name" = [3]\n', ["grid.meta.name", "a text string"]),
    ('base = "falling_chain"\n[grid]\n"scene.pins[2].release" = [0.1]\n',
     ["scene.pins[2].release", "has 1 scene.pins", "index below 1"]),
    ('base = "wide_low"\n[changes]\n"feed.sped" = 4.0\n[grid]\n"feed.speed" = [4.0]\n',
     ["changes", "feed.sped", "unknown key"]),
    ('base = "wide_low"\n[changes]\n"feed.speed" = 4.0\n[grid]\n"feed.speed" = [4.0]\n',
     ["grid.feed.speed", "also in [changes]"]),
])
def test_bad_sweep_files_one_line_and_nothing_written(tmp_path, text, words):
    (tmp_path / "s.toml").write_text(text)
    r = _cli("sweep", "s.toml", "--out", "out", cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    for w in words:
        assert w in r.stderr, (w, r.stderr)
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
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
            assert a["v"] == b["v"] and a["h"] == b["h"]
    for r in rows[1:]:
        d = tmp_path / "dask" / "points" / r["key"]
        assert (d / "summary.json").is_file() and (d / "tensions.csv").is_file()
        assert (d / "point.json").is_file() and (d / "level.toml").is_file()
    assert (tmp_path / "dask" / "results.parquet").is_file()


@pytest.mark.slow
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


@pytest.mark.slow
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
