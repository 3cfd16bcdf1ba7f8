"""Headless runner: files, keys, determinism, errors."""

import csv
import json
import subprocess
import sys

import pytest

from chainfountain.headless import run_level
from chainfountain.level import io
from tests import shipped

KEYS = ["level", "duration_s", "steps", "links", "wall_s", "realtime_factor", "steady_since_s",
        "v", "speed_cv", "max_stretch", "vertex_x", "h", "l", "H", "q", "T0_bar", "TE_bar",
        "theory"]


@pytest.fixture(scope="module")
def quick_level():
    return io.make_level("quick", "short headless test run")


def _numbers(summary):
    s = dict(summary)
    s.pop("wall_s")
    s.pop("realtime_factor")
    return s


def test_run_writes_all_files_and_keys(tmp_path, quick_level):
    path = run_level(quick_level, tmp_path, 0.3, progress=False)
    s = json.loads(path.read_text())
    for k in KEYS:
        assert k in s, k
    for k in ("h", "vertex_x", "q", "T0_bar", "TE_bar", "rel_error"):
        assert k in s["theory"], k
    assert s["steps"] == round(0.3 / quick_level.sim.solver.dt) and s["level"] == "quick"
    with open(tmp_path / "tensions.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert rows and set(rows[0]) == {"t", "joint", "s", "x", "y", "tension_N", "tension_bar"}
    with open(tmp_path / "speed.csv") as fh:
        assert len(list(csv.DictReader(fh))) == 30
    png = (tmp_path / "snapshot.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000
    assert not [p for p in tmp_path.iterdir() if ".part" in p.name]


def test_same_level_and_seed_give_identical_numbers(tmp_path, quick_level):
    a = json.loads(run_level(quick_level, tmp_path / "a", 0.2, seed=3, progress=False).read_text())
    b = json.loads(run_level(quick_level, tmp_path / "b", 0.2, seed=3, progress=False).read_text())
    assert _numbers(a) == _numbers(b)
    assert (tmp_path / "a" / "tensions.csv").read_text() == \
        (tmp_path / "b" / "tensions.csv").read_text()


def _cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "chainfountain", *args], capture_output=True,
                          text=True, timeout=120, cwd=cwd)


def test_cli_run_and_bad_flags(tmp_path, quick_level):
    lvl = io.save(quick_level, tmp_path / "quick.toml")
    ok = _cli("run", str(lvl), "--headless", "--duration", "0.1", "--out", str(tmp_path / "o"))
    assert ok.returncode == 0, ok.stderr
    assert "summary.json" in ok.stdout and (tmp_path / "o" / "summary.json").exists()
    for bad, flag in ((["--duration", "-1"], "--duration"), (["--duration", "x"], "--duration"),
                      (["--seed", "-2"], "--seed")):
        r = _cli("run", str(lvl), *bad)
        assert r.returncode != 0 and "Traceback" not in r.stderr
        assert flag in r.stderr and len(r.stderr.strip().splitlines()) == 1
    r = _cli("run", str(tmp_path / "missing.toml"))
    assert r.returncode == 2 and "no such file" in r.stderr and "Traceback" not in r.stderr


def test_a_seed_nudges_an_apparatus_start_and_repeats_it(level) -> None:
    """``initial.seed`` above 0 (``run --seed``, a sweep's ``seeds``) nudges an apparatus's
    start by 1e-12 as :meth:`Simulation.nudge` does: another run of the chaotic machine,
    the same one for the same seed; 0 leaves the level's own start."""
    import dataclasses

    import numpy as np

    from chainfountain.sim import Simulation

    base = level("apparatus_special").sim

    def velocities(seed: int, nudge: int | None = None) -> np.ndarray:
        cfg = dataclasses.replace(base, initial=dataclasses.replace(base.initial, seed=seed))
        sim = Simulation(cfg)
        if nudge is not None:
            sim.nudge(nudge)
        return sim.state().velocity

    plain, one, again = velocities(0), velocities(1), velocities(1)
    assert np.array_equal(one, again)
    assert np.array_equal(one, velocities(0, nudge=1))
    d = np.abs(one - plain)
    assert 0 < d.max() < 1e-10 * (np.abs(plain).max() + 1.0)


def test_default_duration_of_a_table_sized_apparatus_is_its_own(level) -> None:
    from chainfountain.headless import DEFAULT_DURATION, FORMING_DURATION, default_duration

    fold = level("apparatus_limit")
    assert fold.sim.apparatus.plate_links == 0
    assert default_duration(fold) == fold.sim.apparatus.duration  # the table is sized for it
    floor = level("apparatus_floor")  # treadmill, from rest: forms
    assert floor.sim.initial.mode == "stub" and default_duration(floor) == FORMING_DURATION
    special = level("apparatus_special")  # treadmill, on its path
    assert special.sim.apparatus.plate_links and default_duration(special) == DEFAULT_DURATION


def test_demo_fed_levels_form_from_a_stub_and_run_long_enough_to_be_averaged(level) -> None:
    """The ordinary fed levels start from rest on a stub and form (steady after 4-12 s,
    research/long_runs.py); a headless run of them lasts long enough to average the
    formed fountain over the level's window."""
    from chainfountain.headless import FORMING_DURATION, default_duration

    for name in ("classroom", "paper_tall", "paper_tall_fine", "wide_low"):
        lvl = level(name)
        assert lvl.sim.initial.mode == "stub", name
        assert default_duration(lvl) == FORMING_DURATION
        assert FORMING_DURATION >= 12.5 + 2 * lvl.sim.recording.window


def test_ideal_machines_from_a_stub_run_long_enough_to_settle(level) -> None:
    """The ideal presets start from a stub with a 5-s starter and settle on their laws'
    speed 10-15 s after it hands over: their headless run is long enough for that and a
    window."""
    from chainfountain.headless import MACHINE_FORMING_DURATION, default_duration

    for name in ("ideal_floor", "ideal_fold", "ideal_special", "ideal_limit", "ideal_open"):
        lvl = level(name)
        assert lvl.sim.initial.mode == "stub" and lvl.sim.feed.starter > 0, name
        assert default_duration(lvl) == MACHINE_FORMING_DURATION
        assert MACHINE_FORMING_DURATION >= 2 + lvl.sim.feed.starter + 15 + \
            2 * lvl.sim.recording.window
        # the open arrangement's table lasts longer than the run (it ends the run when empty)
        f = lvl.sim.feed
        assert f.chain_length == 0.0 or f.chain_length / f.speed > 1.1 * MACHINE_FORMING_DURATION


def test_run_that_ends_early_writes_its_part_and_exits_3(tmp_path):
    """A collapsing fold (the paper's limit case, apparatus_limit) ends the run early:
    the outputs cover the part simulated, summary.json says why, and `run` exits with 3."""
    r = _cli("run", "apparatus_limit", "--out", str(tmp_path), "--quiet")
    assert r.returncode == 3, r.stderr
    s = json.loads((tmp_path / "summary.json").read_text())
    ended = s["ended_early"]
    assert ended is not None and 0.5 < ended["t_s"] < s["requested_duration_s"] == 2.0
    assert "folding roller rolls backwards" in ended["reason"]
    # measured: the fountain last landed in the end guide's mouth at 0.52 s (the catch
    # lost before the collapse at 0.99 s); the reason says the same
    assert 0.0 < ended["last_mouth_entry_s"] < ended["t_s"] - 0.1
    assert f"mouth at t = {ended['last_mouth_entry_s']:.2f} s" in ended["reason"]
    assert s["duration_s"] == ended["t_s"]
    assert "ENDED EARLY" in r.stdout and "Traceback" not in r.stderr
    assert (tmp_path / "snapshot.png").exists() and (tmp_path / "speed.csv").exists()
    assert s["outputs"][-1] == "apparatus.csv" and (tmp_path / "apparatus.csv").exists()
    # the reason (about 600 characters here) is wrapped for the terminal, not one line
    out = r.stdout.splitlines()
    i = next(k for k, ln in enumerate(out) if "ENDED EARLY" in ln)
    assert len(out) - i > 3 and all(len(ln) <= 100 for ln in out[i:])
    assert " ".join(ln.strip() for ln in out[i:]).count("folding roller rolls backwards") == 1


def test_open_arrangement_writes_its_reaction(level, tmp_path):
    """The 'open' preset: apparatus.csv carries the lower plate's reaction per sample, it
    grows, reaction.png draws it, and summary.json and the terminal list both files."""
    from chainfountain.headless import describe_outputs

    path = run_level(level("apparatus_open"), tmp_path, 0.6,
                     progress=False)
    s = json.loads(path.read_text())
    # a short run is not "steady" because its last samples settle: it is averaged whole
    assert not s["steady"] and s["window"][1] - s["window"][0] > 0.5
    assert s["outputs"][-2:] == ["apparatus.csv", "reaction.png"]
    assert all((tmp_path / f).exists() for f in s["outputs"])
    lines = describe_outputs(path).splitlines()
    assert "apparatus.csv, reaction.png" in lines[0]
    assert "non-stationary by design; lower plate reaction grows at" in lines[1]
    rows = list(csv.DictReader((tmp_path / "apparatus.csv").open()))
    R = [float(r["tail_reaction"]) for r in rows]
    assert len(R) > 50 and sum(R[-5:]) > 3.0 * sum(R[:5]) > 0.0
    assert (tmp_path / "reaction.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_full_run_is_not_marked_ended_early(tmp_path, quick_level):
    s = json.loads(run_level(quick_level, tmp_path, 0.1, progress=False).read_text())
    assert s["ended_early"] is None and s["requested_duration_s"] == pytest.approx(0.1)


def test_progress_lines_when_not_a_terminal(tmp_path, quick_level, capsys, monkeypatch):
    """stderr is no terminal under pytest: progress comes as plain lines (a log file)."""
    monkeypatch.setattr("chainfountain.headless.stepping.LOG_PROGRESS_EVERY", 0.0)
    run_level(quick_level, tmp_path, 0.2, progress=True)
    lines = [ln for ln in capsys.readouterr().err.splitlines() if "sim s" in ln]
    assert lines and lines[-1].strip().startswith("quick: 0.20/0.20 sim s (100 %)")
    run_level(quick_level, tmp_path, 0.2, progress=False)
    assert "sim s" not in capsys.readouterr().err


@pytest.mark.slow
def test_a_fountain_formed_from_its_stub_is_steady_from_when_it_formed(level, tmp_path):
    """wide_low forms from its stub in about 4 s (research/long_runs.py): its default run
    reports it steady from then and averages the formed fountain, not the whole run."""

    lvl = level("wide_low")
    s = json.loads(run_level(lvl, tmp_path, progress=False).read_text())
    assert s["duration_s"] == pytest.approx(20.0)
    assert s["steady"] and 2.0 < s["steady_since_s"] < 8.0, s["steady_since_s"]
    assert s["window"][0] == pytest.approx(s["steady_since_s"], abs=0.05)
    assert abs(s["theory"]["rel_error"]["h"]) < 0.01


def test_a_scene_level_runs_and_says_how_it_compares(tmp_path):
    r = _cli("run", "falling_chain", "--out", str(tmp_path), "--quiet", "--duration", "0.3")
    assert r.returncode == 0, r.stderr
    assert "folded fall at 25 % of the length: free end" in r.stdout  # 0.3 s falls 25-50 %
    assert "Calkin-March" in r.stdout and "at 75 % of the length: not reached" in r.stdout
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["kind"] == "scene" and s["samples"] == 600
    assert s["outputs"] == ["summary.json", "probe_free_end.csv", "probe_fixed_end.csv",
                            "probe_energy.csv", "scene.png"]
    with open(tmp_path / "probe_free_end.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert list(rows[0]) == ["t", "x", "y", "vx", "vy"] and len(rows) == 600
    assert s["probes"]["free_end"]["columns"]["vy"]["min"] < -3.0


@pytest.mark.parametrize("args, words", [
    (["run", "falling_chain", "--seed", "2"], "its scene.jitter is 0"),
    (["play", "falling_chain", "--frames", "1"], "scenes run headless only, with "
     "chainfountain run falling_chain"),
])
def test_scene_levels_refuse_what_they_cannot_do(args, words, tmp_path):
    r = _cli(*args, cwd=tmp_path)
    assert r.returncode == 2 and words in r.stderr and "Traceback" not in r.stderr


def test_a_braked_fold_says_the_speed_it_selects(tmp_path):
    """``apparatus_fold_gripped``: the terminal gives the measured speed beside the one the
    carts and the brake select by the paper's laws (``laws.braked_fold_speed``)."""
    from chainfountain.headless import describe_outputs
    from chainfountain.sim.apparatus import braked_fold_speed
    from chainfountain.study.changes import laid_on_path

    level = laid_on_path(shipped.level("apparatus_fold_gripped"))
    path = run_level(level, tmp_path, 0.5, progress=False)
    s = json.loads(path.read_text())
    v_sel = braked_fold_speed(level.sim)
    assert s["apparatus"]["predicted_paper"]["v_steady"] == pytest.approx(v_sel, rel=1e-12)
    line = next(ln for ln in describe_outputs(path).splitlines() if "brake select" in ln)
    assert f"select {v_sel:.3f} m/s by the paper's laws" in line
