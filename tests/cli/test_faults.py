"""Faults end a run cleanly: divergence, a failed analysis, signals, unwritable and full
output folders. Each leaves complete outputs of the part run and one clear line."""

from __future__ import annotations

import errno
import json
import math
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from chainfountain import atomic, headless
from chainfountain.headless import exit_status, run_level
from chainfountain.level import io, library
from chainfountain.sim import Simulation
from chainfountain.sim.watchdog import CHECK_INTERVAL, Diverged
from tests import shipped


def _cli(*args: str, **kw) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "chainfountain", *args], capture_output=True,
                          text=True, timeout=300, **kw)


def _no_partial_files(folder: Path) -> bool:
    return not [p for p in folder.iterdir() if ".part" in p.name or p.name.startswith(".")]


@pytest.fixture(scope="module")
def quick_level():
    return io.make_level("quick", "short headless test run")


@pytest.mark.parametrize("bad", [math.nan, 1e6])
def test_watchdog_stops_a_blown_up_link_within_one_check(quick_level, bad):
    sim = Simulation(quick_level.sim)
    sim.advance(0.05)
    sim.chain.links[3].body.velocity = (bad, 0.0)
    t0 = sim.time
    with pytest.raises(Diverged, match=r"diverged at t = \d") as exc:
        sim.advance(0.5)
    assert sim.time - t0 <= CHECK_INTERVAL + 1e-12
    assert "\n" not in str(exc.value)


def test_watchdog_never_trips_on_a_healthy_run(quick_level):
    sim = Simulation(quick_level.sim)
    sim.advance(1.0)  # raises if it trips
    assert sim.time == pytest.approx(1.0)


def _diverging_level():
    """apparatus_floor, started laid along its path, with a bending spring of
    0.25 N*m/rad between its 2-cm links: pymunk applies the spring explicitly, which is
    unstable at the 0.5 ms step for links this light (omega*h = 2.7), so the run
    diverges before the machine can do anything else (measured: at 0.040-0.058 s from
    four nudged starts). The level check refuses such a spring
    (:data:`chainfountain.sim.joints.SPRING_STABILITY`), so the level is changed after
    it was read, as a study's own code could."""
    lvl = shipped.level("apparatus_floor")
    sim = lvl.sim
    sim.initial.mode = "catenary"
    sim.apparatus.starter = 0.0
    sim.chain.bending_stiffness = 0.25
    with pytest.raises(io.LevelError, match="chain.bending_stiffness"):
        io.check_consistency(lvl, "diverging")  # what a level file gets instead
    return lvl


def test_a_diverging_run_ends_with_status_3_and_complete_outputs(tmp_path):
    out = tmp_path / "out"
    path = run_level(_diverging_level(), out, 2.0, progress=False)
    s = json.loads(path.read_text())
    assert exit_status(s) == 3 and "diverged" in headless.describe_outputs(path)
    ended = s["ended_early"]
    assert ended["cause"] == "diverged" and ended["t_s"] < 1.0
    assert all((out / f).exists() for f in s["outputs"])
    assert {"speed.csv", "tensions.csv", "snapshot.png", "apparatus.csv"} <= set(s["outputs"])
    assert _no_partial_files(out)


def test_a_failed_analysis_is_named_and_loses_nothing(tmp_path, quick_level, monkeypatch):
    """The catenary fit failing (as it did on garbage data: 'SVD did not converge') leaves
    every file written and names the failure in summary.json and on the terminal."""
    import chainfountain.sim.recorder as recorder

    def broken(*args, **kw):
        raise np.linalg.LinAlgError("SVD did not converge in Linear Least Squares")

    monkeypatch.setattr(recorder, "fit_catenary", broken)
    path = run_level(quick_level, tmp_path, 0.3, progress=False)
    s = json.loads(path.read_text())
    assert s["analysis_failed"] == {"catenary fit": "LinAlgError: SVD did not converge in "
                                                    "Linear Least Squares"}
    assert s["q"] is None and s["h"] is not None  # the rest is measured
    assert set(s["outputs"]) == set(headless.DEFAULT_OUTPUTS) and exit_status(s) == 0
    assert "analysis failed: catenary fit" in headless.describe_outputs(path)


def test_a_failed_figure_is_named_and_the_rest_written(tmp_path, quick_level, monkeypatch):
    def broken(*args, **kw):
        raise ValueError("figure broke")

    monkeypatch.setattr("chainfountain.headless.files.write_snapshot", broken)
    s = json.loads(run_level(quick_level, tmp_path, 0.2, progress=False).read_text())
    assert s["analysis_failed"] == {"snapshot.png": "ValueError: figure broke"}
    assert "snapshot.png" not in s["outputs"] and (tmp_path / "speed.csv").exists()


def test_a_full_disk_names_the_file_and_keeps_the_rest(tmp_path, quick_level, monkeypatch):
    real = atomic.write_text

    def full(path, text):
        if Path(path).name == "tensions.csv":
            raise OSError(errno.ENOSPC, "No space left on device")
        return real(path, text)

    monkeypatch.setattr(atomic, "write_text", full)
    s = json.loads(run_level(quick_level, tmp_path, 0.2, progress=False).read_text())
    assert s["write_failed"] == {"tensions.csv": "No space left on device"}
    assert exit_status(s) == 4 and "tensions.csv" not in s["outputs"]
    assert (tmp_path / "speed.csv").exists() and not (tmp_path / "tensions.csv").exists()
    assert _no_partial_files(tmp_path)


def test_summary_that_cannot_be_written_is_one_line_status_4(tmp_path, quick_level):
    lvl = io.save(quick_level, tmp_path / "quick.toml")
    code = ("import sys, errno; from chainfountain import atomic, cli; real = atomic.write_text\n"
            "def w(p, t):\n"
            "    if str(p).endswith('summary.json'): raise OSError(errno.ENOSPC, 'No space left "
            "on device')\n"
            "    return real(p, t)\n"
            "atomic.write_text = w\n"
            f"sys.exit(cli.main(['run', {str(lvl)!r}, '--duration', '0.1', '--quiet', "
            f"'--out', {str(tmp_path / 'o')!r}]))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 4 and "Traceback" not in r.stderr
    errors = [ln for ln in r.stderr.splitlines() if "error" in ln]
    assert len(errors) == 1 and "summary.json (No space left on device)" in errors[0]
    assert (tmp_path / "o" / "speed.csv").exists()


def test_an_unwritable_out_folder_is_bad_input_before_running(tmp_path, quick_level):
    lvl = io.save(quick_level, tmp_path / "quick.toml")
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    r = _cli("run", str(lvl), "--duration", "0.1", "--out", str(blocker / "out"))
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and "--out: cannot write to" in r.stderr
    assert "running" not in r.stderr  # refused before simulating


@pytest.mark.parametrize("sig, status", [(signal.SIGINT, 130),
                                         pytest.param(signal.SIGTERM, 143, marks=pytest.mark.slow)])
def test_a_signal_leaves_complete_outputs_of_the_part_run(tmp_path, sig, status):
    """A real signal to a real `chainfountain run`: the part run is written completely."""
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-m", "chainfountain", "run", "paper_tall",
                             "--duration", "600", "--out", str(out), "--quiet"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(6.0)  # imports, the build, then a few tenths of simulated seconds
    proc.send_signal(sig)
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == status, stderr
    assert "Traceback" not in stderr
    s = json.loads((out / "summary.json").read_text())
    ended = s["ended_early"]
    assert ended["cause"] == "interrupted" and ended["signal_number"] == int(sig)
    assert 0.0 < ended["t_s"] < 600 and s["duration_s"] == ended["t_s"]
    assert set(s["outputs"]) == set(headless.DEFAULT_OUTPUTS)
    assert all((out / f).stat().st_size > 0 for f in s["outputs"])
    assert _no_partial_files(out)
    assert f"interrupted by {sig.name}" in stdout


def test_library_resolves_every_shipped_level():
    for p in shipped.PATHS:
        assert library.resolve(p.stem) is not None


def test_a_reader_that_goes_away_ends_the_listing_quietly(tmp_path):
    """``chainfountain levels | head -1``: the pipe closes under the listing; the command
    stops without a traceback, as a Unix tool does."""
    import subprocess
    import sys

    proc = subprocess.Popen([sys.executable, "-c", "from chainfountain.cli import "
                             "console_main; console_main()", "levels"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=tmp_path)
    proc.stdout.close()  # gone before the first line (the import takes a while)
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=60) == 0
    assert "Traceback" not in err and "BrokenPipe" not in err
