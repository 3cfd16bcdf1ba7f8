"""The window runs a level whose accuracy it cannot hold at real time at a coarser
accuracy's settings, says so, and gives the bar those settings have; the level keeps the
accuracy asked for (:mod:`chainfountain.app.interactive`)."""

from __future__ import annotations

import pytest

from chainfountain.app import cost, interactive
from chainfountain.app.session import Session
from chainfountain.sim import accuracy
from chainfountain.sim.reference import LaunchReference
from chainfountain.study.changes import with_changes


def _settings(sim) -> tuple:
    return (sim.chain.link_length, sim.solver.dt, sim.solver.iterations, sim.solver.substeps)


@pytest.fixture(autouse=True)
def _home(tmp_path, monkeypatch):
    monkeypatch.setenv("CHAINFOUNTAIN_HOME", str(tmp_path / "home"))


@pytest.fixture
def slow_machine(level):
    """``ideal_fold`` asking 1 %: the error model chooses 12-mm links at 31 us, about
    2.7 s of one core per simulated second."""
    lvl = with_changes(level("ideal_fold"), {"solver.accuracy": 0.01})
    assert cost.cost(lvl.sim)[1] > interactive.REAL_TIME_COST
    return lvl


def test_a_level_too_slow_for_real_time_runs_coarser_in_the_window(slow_machine) -> None:
    asked = _settings(slow_machine.sim)
    s = Session(slow_machine)
    run = s.sim.config
    assert s.runs_at.coarsened and s.runs_at.asked == 0.01
    assert run.solver.accuracy in interactive.LADDER and run.solver.accuracy > 0.01
    assert cost.cost(run)[1] <= cost.WINDOW_COST
    # the finest rung of the ladder that fits: the one below it does not
    finer = [a for a in interactive.LADDER if 0.01 < a < run.solver.accuracy]
    for a in finer:
        assert cost.cost(_choose(slow_machine.sim, a))[1] > cost.WINDOW_COST
    # the level keeps what it asked for: saved and run headless, 1 % and its settings
    assert s.level.sim.solver.accuracy == 0.01 and _settings(s.level.sim) == asked
    assert s.setup_copy().sim.solver.accuracy == 0.01
    said = s.messages[-1][1]
    assert "solver.accuracy 1 % would run at about 0.37x real time" in said
    assert f"the settings of {100 * run.solver.accuracy:g} %" in said
    assert "`chainfountain run` meets 1 %" in said


def _choose(sim, acc: float):
    from chainfountain.sim.kinds import kind_of

    return kind_of(sim).choose_settings(sim, acc)


def test_the_bar_shown_is_the_one_the_running_settings_have(slow_machine) -> None:
    s = Session(slow_machine)
    s.advance(0.05)
    run = s.sim.config
    ref = LaunchReference.of_level(run)
    est = accuracy.estimate(ref, accuracy.Settings(run.chain.link_length, run.solver.dt,
                                                   run.solver.iterations),
                            run.chain, machine=True)
    bars = s.readout().bars
    assert f"top +-{100 * est.bounds['vertex_y']:.1f} %" in bars
    assert f"{100 * run.solver.accuracy:g} % to keep real time" in bars
    assert "solver.accuracy 1 % asked" in bars
    # and they are wider than the level's own: the window does not claim its accuracy
    own = accuracy.estimate(ref, accuracy.Settings(slow_machine.sim.chain.link_length,
                                                   slow_machine.sim.solver.dt,
                                                   slow_machine.sim.solver.iterations),
                            slow_machine.sim.chain, machine=True)
    assert est.bounds["vertex_y"] > own.bounds["vertex_y"]


@pytest.mark.parametrize("name", ["classroom", "paper_tall", "ideal_fold", "beaker"])
def test_a_level_the_window_runs_at_real_time_keeps_its_settings(level, name) -> None:
    """``paper_tall`` (0.94 s of one core per simulated second by the estimate) runs at
    0.96x in the window, so it keeps its 0.5 %; the others cost less or ask for none."""
    lvl = level(name)
    s = Session(lvl)
    assert not s.runs_at.coarsened
    assert _settings(s.sim.config) == _settings(lvl.sim)
    assert not any("would run at about" in m for _, m in s.messages)


def test_a_rebuilt_change_is_judged_at_the_settings_the_window_would_run(slow_machine) -> None:
    """The budget guard reads the coarsened settings: a change that rebuilds the slow
    machine is accepted (at its own 1 % it would be refused as too slow)."""
    s = Session(slow_machine)
    origin = s.origin
    cand = with_changes(slow_machine, {"feed.drop": slow_machine.sim.feed.drop * 1.02}).sim
    assert interactive.over_budget(cand, origin) is None
    assert cost.over_budget(cand, interactive.window_settings(origin).config) is not None
    r = s.set_field("feed.drop", slow_machine.sim.feed.drop * 1.02)
    assert r.ok, r.message
    assert s.runs_at.coarsened and s.level.sim.solver.accuracy == 0.01
