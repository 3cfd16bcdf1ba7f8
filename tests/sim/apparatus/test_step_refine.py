"""A contact machine's step error by refinement: ``run LEVEL --error-bars`` runs it again
at half its step and gives how far its flight's figures moved
(:mod:`chainfountain.headless.apparatus_refine`)."""

from __future__ import annotations

import json

from chainfountain.cli import main
from chainfountain.headless import apparatus_refine, exit_status
from chainfountain.headless import run as headless_run
from chainfountain.headless.stepping import Ending


def _summary(out) -> dict:
    return json.loads((out / "summary.json").read_text())


def test_run_error_bars_runs_a_contact_machine_again_at_half_its_step(tmp_path, capsys,
                                                                      level) -> None:
    """``apparatus_floor``, 4 s from rest: the second run is at half the step (the moves
    are not zero, which the same step would give), and it moves the speed by less than
    the 3.4 % the gripped presets' vertex moved, the largest move measured
    (:mod:`chainfountain.sim.apparatus_report.step_change`)."""
    out = tmp_path / "o"
    assert main(["run", "apparatus_floor", "--error-bars", "--duration", "4", "--quiet",
                 "--out", str(out)]) == 0
    said = capsys.readouterr()
    step = _summary(out)["apparatus"]["flight"]["step"]
    dt = level("apparatus_floor").sim.solver.dt
    assert step["dt"] == dt and step["half_dt"] == dt / 2
    assert step["how"] == apparatus_refine.METHOD
    moves = step["moves"]
    assert set(moves) == {*apparatus_refine.FIGURES, "v_rel"}
    assert 0.0 < moves["v_rel"] < 0.034, moves
    assert all(m is not None and m >= 0.0 for m in moves.values()), moves
    assert step["half_step"]["v"] > 0 and "v" in step["half_step_se"]  # None: too short
    assert "then again at half its step" in said.err
    assert f"again at half the step ({1e6 * dt / 2:g} us), the speed moved" in said.out
    assert "its cart selects" in said.out and "by this model's pick-up" in said.out


def test_without_error_bars_a_contact_machine_says_how_to_refine_it(tmp_path, capsys) -> None:
    out = tmp_path / "o"
    assert main(["run", "apparatus_floor", "--duration", "1", "--quiet", "--out",
                 str(out)]) == 0
    step = _summary(out)["apparatus"]["flight"]["step"]
    assert step["moves"] is None and "run LEVEL --error-bars refines it" in step["how"]
    text = capsys.readouterr().out
    assert "the step's error: not measured for this arrangement's flight" in text
    assert all(len(line) <= 100 for line in text.splitlines()[1:]), text  # [0]: the path
    assert "--error-bars refines it" in text


def test_a_signal_during_the_half_step_run_writes_the_run_and_exits_130(
        tmp_path, monkeypatch, level) -> None:
    real = headless_run.simulate

    def stopped(lvl, duration, **kw):
        sim, rec, wall, ended = real(lvl, duration, **kw)
        if kw.get("label", "").endswith("at dt/2"):
            return sim, rec, wall, Ending("interrupted", "interrupted by SIGINT", 2)
        return sim, rec, wall, ended

    monkeypatch.setattr(headless_run, "simulate", stopped)
    path = headless_run.run_level(level("apparatus_floor"), tmp_path, 1.0, progress=False,
                                  half_step=True)
    s = json.loads(path.read_text())
    assert s["apparatus"]["measured"]["v"] > 0
    assert s["apparatus"]["flight"]["step"]["moves"] is None
    assert "interrupted" in s["apparatus"]["flight"]["step"]["how"]
    assert s["ended_early"]["cause"] == "interrupted"
    assert "the run's own figures are complete" in s["ended_early"]["reason"]
    assert exit_status(s) == 130


def test_error_bars_and_no_refine_together_are_refused(capsys) -> None:
    assert main(["run", "apparatus_floor", "--error-bars", "--no-refine", "--duration",
                 "1"]) == 2
    err = capsys.readouterr().err
    assert "--no-refine" in err and "--error-bars" in err and len(err.strip().splitlines()) == 1
